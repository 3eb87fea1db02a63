"""Reading and writing the command line's files without following symbolic links.

The command line writes reports, tables and figures into an output folder and reads golden
files. Here, every write

* stays inside the folder it is given: no symbolic link below that folder is followed, neither a
  sub-folder nor the file itself (a link is refused, it is not replaced);
* is atomic: the data go to a new temporary file in the same folder, which then replaces the
  target with :func:`os.replace`, so a reader sees the old file or the new one, never a part;

and a golden file is read only when it is a regular file, not a link, and UTF-8 text.

Problems are :class:`~lagsolve.errors.SpecError` (exit 2) naming the file, the option and the
fix. The folder named on the command line may itself be a link: the user chose it.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import stat
from pathlib import Path

from lagsolve.errors import Issue, SpecError

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_DIRECTORY = getattr(os, "O_DIRECTORY", 0)
# os.replace takes dir_fd wherever os.rename does (supports_dir_fd lists only the latter)
_DIR_FD = all(f in os.supports_dir_fd for f in (os.open, os.mkdir, os.rename, os.stat, os.unlink))


def _refuse(path: Path | str, option: str, message: str, hint: str) -> SpecError:
    return SpecError([Issue(str(path), 0, option, message, hint)])


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc)


def write_file(folder: Path, name: str | Path, data: str | bytes, *, option: str = "-o/--output") -> Path:
    """Write ``data`` (text as UTF-8) to ``folder / name`` and return that path.

    ``name`` is relative (``bead/bead.md``); the folders in it are created, and so is
    ``folder``, which may itself be a link; nothing below it is followed.

    Raises
    ------
    SpecError
        ``name`` leaves ``folder``, a folder on the way or the target is a symbolic link, the
        target is a folder, or the file cannot be written (permissions, disk full).
    """
    payload = data.encode("utf-8") if isinstance(data, str) else data
    inside = Path(folder)
    target = inside / name
    parts = Path(name).parts
    if not parts or Path(name).is_absolute() or any(p in ("", ".", "..") for p in parts):
        raise _refuse(target, option, f"is not a file name under {inside}", "give a plain file name")
    try:
        inside.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise _refuse(inside, option, f"cannot write into this folder: {_reason(exc)}",
                      "choose a folder you can write to") from None
    if _DIR_FD:
        _write_at(inside, parts, payload, target, option)
    else:  # pragma: no cover - platforms without dir_fd (Windows): the same checks by path
        _write_by_path(inside, parts, payload, target, option)
    return target


def _write_at(inside: Path, parts: tuple[str, ...], payload: bytes, target: Path, option: str) -> None:
    """The write, each step relative to an open folder, so a link swapped in meanwhile is not followed."""
    try:
        fd = os.open(inside, os.O_RDONLY | _DIRECTORY)
    except OSError as exc:
        raise _refuse(inside, option, f"cannot write into this folder: {_reason(exc)}",
                      "choose a folder you can write to") from None
    here = inside
    try:
        for part in parts[:-1]:
            here = here / part
            try:
                os.mkdir(part, dir_fd=fd)
            except FileExistsError:
                pass
            except OSError as exc:
                raise _refuse(here, option, f"cannot write this folder: {_reason(exc)}",
                              "choose a folder you can write to") from None
            try:
                child = os.open(part, os.O_RDONLY | _DIRECTORY | _NOFOLLOW, dir_fd=fd)
            except OSError as exc:
                if exc.errno in (errno.ELOOP, errno.ENOTDIR) and _is_link(part, fd):
                    raise _refuse(here, option, "is a symbolic link; lagsolve does not follow links when writing",
                                  "remove the link or choose another output folder") from None
                raise _refuse(here, option, f"is not a folder lagsolve can write into: {_reason(exc)}",
                              "remove it or choose another output folder") from None
            os.close(fd)
            fd = child
        name = parts[-1]
        _check_target(name, fd, target, option)
        temporary = f".{name}.{secrets.token_hex(6)}.tmp"
        try:
            out = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o666, dir_fd=fd)
        except OSError as exc:
            raise _refuse(target, option, f"cannot write: {_reason(exc)}",
                          "choose a folder you can write to") from None
        try:
            with os.fdopen(out, "wb") as stream:
                stream.write(payload)
            os.replace(temporary, name, src_dir_fd=fd, dst_dir_fd=fd)
        except OSError as exc:
            with contextlib.suppress(OSError):
                os.unlink(temporary, dir_fd=fd)
            raise _refuse(target, option, f"cannot write: {_reason(exc)}",
                          "check the permissions and the free space of the output folder") from None
    finally:
        os.close(fd)


def _is_link(name: str, fd: int) -> bool:
    try:
        return stat.S_ISLNK(os.stat(name, dir_fd=fd, follow_symlinks=False).st_mode)
    except OSError:
        return False


def _check_target(name: str, fd: int, target: Path, option: str) -> None:
    try:
        mode = os.stat(name, dir_fd=fd, follow_symlinks=False).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise _refuse(target, option, f"cannot write: {_reason(exc)}", "choose another output folder") from None
    if stat.S_ISLNK(mode):
        raise _refuse(target, option, "is a symbolic link; lagsolve does not follow links when writing",
                      "remove the link or choose another output folder")
    if stat.S_ISDIR(mode):
        raise _refuse(target, option, "is a folder, not a file", "remove it or choose another output path")


def _write_by_path(inside: Path, parts: tuple[str, ...], payload: bytes, target: Path,
                   option: str) -> None:  # pragma: no cover - see write_file
    here = inside
    for part in parts[:-1]:
        here = here / part
        if here.is_symlink():
            raise _refuse(here, option, "is a symbolic link; lagsolve does not follow links when writing",
                          "remove the link or choose another output folder")
        try:
            here.mkdir(exist_ok=True)
        except OSError as exc:
            raise _refuse(here, option, f"cannot write this folder: {_reason(exc)}",
                          "choose a folder you can write to") from None
    if target.is_symlink():
        raise _refuse(target, option, "is a symbolic link; lagsolve does not follow links when writing",
                      "remove the link or choose another output folder")
    if target.is_dir():
        raise _refuse(target, option, "is a folder, not a file", "remove it or choose another output path")
    temporary = target.with_name(f".{target.name}.{secrets.token_hex(6)}.tmp")
    try:
        with open(temporary, "xb") as stream:
            stream.write(payload)
        os.replace(temporary, target)
    except OSError as exc:
        temporary.unlink(missing_ok=True)
        raise _refuse(target, option, f"cannot write: {_reason(exc)}",
                      "check the permissions and the free space of the output folder") from None


def read_text(path: Path, *, option: str = "--golden") -> str | None:
    """The UTF-8 text of the regular file ``path``, or None when it does not exist.

    Raises
    ------
    SpecError
        ``path`` is a symbolic link (not followed), a folder or another non-regular file,
        unreadable, or not UTF-8 text.
    """
    try:
        fd = os.open(path, os.O_RDONLY | _NOFOLLOW | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        return None
    except OSError as exc:
        if Path(path).is_symlink():
            raise _refuse(path, option, "is a symbolic link; lagsolve does not follow links to golden files",
                          "replace the link with the file itself") from None
        raise _refuse(path, option, f"cannot be read: {_reason(exc)}",
                      "make it a readable file or remove it") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
            raise _refuse(path, option, f"is {kind}, not a golden file",
                          "remove it, then create the golden file with --update-golden")
        chunks = []
        while chunk := os.read(fd, 1 << 20):
            chunks.append(chunk)
        data = b"".join(chunks)
    except OSError as exc:
        raise _refuse(path, option, f"cannot be read: {_reason(exc)}", "make it a readable file or remove it") from None
    finally:
        os.close(fd)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _refuse(path, option, f"is not UTF-8 text (byte {exc.start} cannot be decoded)",
                      "replace it with the report, e.g. with --update-golden") from None


def read_input(path: str | Path, limit: int) -> bytes:
    """At most ``limit`` + 1 bytes of the input file ``path`` (a problem or a submission): a device never fills
    memory (``/dev/zero``), and a named pipe without a writer reads as empty instead of blocking the open forever
    (it is opened without waiting, then read as usual, so a pipe being written still gives its data).

    Raises
    ------
    OSError
        As :func:`open` does (missing, a folder, not readable).
    """
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        if stat.S_ISDIR(os.fstat(fd).st_mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
        chunks: list[bytes] = []
        size = 0
        while size <= limit and (chunk := os.read(fd, limit + 1 - size)):
            chunks.append(chunk)
            size += len(chunk)
        return b"".join(chunks)
    finally:
        os.close(fd)


def safe_slug(path: str | Path) -> str:
    """A file-name-safe stem for output names: ``problems/My bead.yaml`` → ``My_bead``."""
    stem = Path(path).name
    stem = stem.rsplit(".", 1)[0] if "." in stem else stem
    slug = re.sub(r"[^A-Za-z0-9_-]+", "_", stem).strip("_")
    return slug or "problem"
