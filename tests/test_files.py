"""Writing outputs and reading golden files: inside the folder, no links followed, atomic, clean errors."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from lagsolve.errors import SpecError
from lagsolve.files import read_input, read_text, write_file


def test_write_creates_folders_and_returns_the_path(tmp_path: Path) -> None:
    """Text is written as UTF-8 and bytes as they are, with the folders in the name created."""
    assert write_file(tmp_path / "out", "bead/bead.md", "ẍ = 1\n") == tmp_path / "out" / "bead" / "bead.md"
    assert (tmp_path / "out" / "bead" / "bead.md").read_text(encoding="utf-8") == "ẍ = 1\n"
    write_file(tmp_path / "out", "bead/a.png", b"\x89PNG")
    assert (tmp_path / "out" / "bead" / "a.png").read_bytes() == b"\x89PNG"


def test_write_replaces_a_file_atomically(tmp_path: Path) -> None:
    """An existing file is replaced by a new one (a reader keeps the old content), and no temporary is left."""
    target = tmp_path / "r.md"
    target.write_text("old\n")
    with target.open() as reader:
        write_file(tmp_path, "r.md", "new\n")
        assert reader.read() == "old\n"  # rewritten in place, the reader would see the new text or a part
    assert target.read_text() == "new\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.md"]


def test_a_failed_write_leaves_the_old_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """When the final rename fails, the old file is intact, the temporary is removed and the error says why."""
    target = tmp_path / "r.md"
    target.write_text("old\n")

    def no_space(*args: object, **kwargs: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", no_space)
    with pytest.raises(SpecError, match="r.md: -o/--output: cannot write: No space left on device"):
        write_file(tmp_path, "r.md", "new\n")
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.md"]


def test_a_link_in_place_of_the_file_is_refused(tmp_path: Path) -> None:
    """A symbolic link where the file goes is refused, and the file it points to is untouched."""
    outside = tmp_path / "outside.txt"
    outside.write_text("keep\n")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "r.md").symlink_to(outside)
    with pytest.raises(SpecError, match="is a symbolic link; lagsolve does not follow links when writing"):
        write_file(tmp_path / "out", "r.md", "new\n")
    assert outside.read_text() == "keep\n"
    assert (tmp_path / "out" / "r.md").is_symlink()


def test_a_linked_folder_inside_the_output_folder_is_refused(tmp_path: Path) -> None:
    """A sub-folder that is a link to a folder elsewhere is not followed."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "bead").symlink_to(elsewhere, target_is_directory=True)
    with pytest.raises(SpecError, match=r"out/bead: -o/--output: is a symbolic link"):
        write_file(tmp_path / "out", "bead/bead.md", "new\n")
    assert list(elsewhere.iterdir()) == []


def test_names_that_leave_the_folder_are_refused(tmp_path: Path) -> None:
    """A name with '..' or an absolute name cannot reach outside the folder."""
    for name in ("../x.md", "/tmp/x.md", "a/../../x.md"):
        with pytest.raises(SpecError, match="is not a file name under"):
            write_file(tmp_path / "out", name, "x")


def test_a_folder_in_place_of_the_file_is_refused(tmp_path: Path) -> None:
    """A folder where the file goes is an error naming it, not an IsADirectoryError."""
    (tmp_path / "r.md").mkdir()
    with pytest.raises(SpecError, match="r.md: --update-golden: is a folder, not a file"):
        write_file(tmp_path, "r.md", "x", option="--update-golden")


def test_read_text_of_a_missing_file_is_none(tmp_path: Path) -> None:
    """A missing golden file is None (a difference), a present one its text."""
    assert read_text(tmp_path / "none.md") is None
    (tmp_path / "a.md").write_text("ẍ\n", encoding="utf-8")
    assert read_text(tmp_path / "a.md") == "ẍ\n"


@pytest.mark.parametrize(("make", "message"), [
    (lambda p: p.write_bytes(b"ok \xff\xfe"), "is not UTF-8 text"),
    (lambda p: p.mkdir(), "is a folder, not a golden file"),
    (lambda p: p.symlink_to("/etc/passwd"), "is a symbolic link; lagsolve does not follow links to golden files"),
    (lambda p: os.mkfifo(p), "is not a regular file"),
])
def test_read_text_refuses_what_is_not_a_golden_file(tmp_path: Path, make: object, message: str) -> None:
    """Non-UTF-8 bytes, a folder, a link (never followed) and a FIFO are refused with the file and option named."""
    path = tmp_path / "g.md"
    make(path)  # type: ignore[operator]
    with pytest.raises(SpecError, match=f"g.md: --golden: {message}"):
        read_text(path)


@pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(), reason="POSIX devices and pipes")
def test_an_input_file_never_hangs_nor_fills_memory(tmp_path: Path) -> None:
    """A submission (or sweep problem) was read whole, so `lagsolve grade KEY /dev/zero` ran out of memory (a
    MemoryError traceback at best); a named pipe without a writer blocked every command reading it forever."""
    from click.testing import CliRunner

    from lagsolve.cli import main

    assert len(read_input("/dev/zero", 1000)) == 1001
    fifo = tmp_path / "fifo.yaml"
    os.mkfifo(fifo)
    assert read_input(fifo, 1000) == b""
    (tmp_path / "plain.yaml").write_bytes(b"name: x\n")
    assert read_input(tmp_path / "plain.yaml", 1000) == b"name: x\n"
    key = str(Path(__file__).resolve().parents[1] / "problems" / "bead.yaml")
    result = CliRunner().invoke(main, ["grade", key, "/dev/zero", str(fifo), "--format", "json"])
    assert result.exit_code == 2 and "the limit is" in result.output and "file is empty" in result.output
    result = CliRunner().invoke(main, ["derive", str(fifo)])
    assert result.exit_code == 2 and "file is empty" in result.output
