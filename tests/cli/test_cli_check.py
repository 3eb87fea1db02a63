"""`lagsolve check`: the verdict table, and exit codes 0 (all agree), 1 (a mismatch), 2 (invalid input)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from lagsolve.cli import main

ROOT = Path(__file__).resolve().parents[2]
BEAD = ROOT / "problems" / "bead.yaml"
ATWOOD = ROOT / "problems" / "atwood.yaml"


@pytest.fixture()
def runner() -> CliRunner:
    return CliRunner()


def _edited(tmp_path: Path, source: Path, old: str, new: str) -> str:
    """A copy of ``source`` with one answer edited."""
    text = source.read_text()
    assert old in text
    target = tmp_path / source.name
    target.write_text(text.replace(old, new, 1))
    return str(target)


def test_right_answers_exit_0(runner: CliRunner) -> None:
    """A problem whose answers all agree prints ✓ lines and a count, and exits 0."""
    result = runner.invoke(main, ["check", str(BEAD), str(ATWOOD)])
    assert result.exit_code == 0, result.output
    assert "Bead on a wire" in result.stdout and "Atwood machine" in result.stdout
    assert "✓ ẍ" in result.stdout and "ok (symbolic)" in result.stdout
    assert "  3 ok\n" in result.stdout and "✗" not in result.stdout


def test_wrong_answer_exits_1_with_both_expressions_and_a_state(runner: CliRunner, tmp_path: Path) -> None:
    """A flipped sign gives ✗, the expected and derived expressions, a state where they differ, and exit 1."""
    path = _edited(tmp_path, ATWOOD, 'y1: "(m2 - m1)*g/(m1 + m2)"', 'y1: "(m1 - m2)*g/(m1 + m2)"')
    result = runner.invoke(main, ["check", path])
    assert result.exit_code == 1, result.output
    lines = result.stdout.splitlines()
    line = next(x for x in lines if "✗" in x)
    assert "ÿ1" in line or "y1" in line
    assert "opposite sign" in line
    assert any(x.strip().startswith("expected: g*(m1 - m2)/(m1 + m2)") for x in lines)
    assert any(x.strip().startswith("derived:") for x in lines)
    differ = next(x for x in lines if "differ at" in x)
    assert "m1 = " in differ and "expected " in differ and "derived " in differ
    assert "1 mismatch" in result.stdout


def test_multiplier_convention_is_explained(runner: CliRunner, tmp_path: Path) -> None:
    """λ with the opposite sign is reported as the other sign convention."""
    path = _edited(tmp_path, ATWOOD, 'string: "2*m1*m2*g/(m1 + m2)"', 'string: "-2*m1*m2*g/(m1 + m2)"')
    result = runner.invoke(main, ["check", path])
    assert result.exit_code == 1
    assert "λ with the opposite sign convention (expected = −derived; otherwise it agrees)" in result.stdout


def test_warning_alone_exits_0(runner: CliRunner, tmp_path: Path) -> None:
    """A magnitude without Abs is a '!' warning naming where it holds; warnings do not fail the check."""
    path = _edited(tmp_path, BEAD, 'wire: "m*Abs(Derivative(f(x), (x, 2))*x_dot**2 + g)',
                   'wire: "m*(Derivative(f(x), (x, 2))*x_dot**2 + g)')
    result = runner.invoke(main, ["check", path])
    assert result.exit_code == 0, result.output
    line = next(x for x in result.stdout.splitlines() if x.lstrip().startswith("!"))
    assert "|F_wire|" in line and "holds only where g + ẋ²*f''(x) > 0" in line
    assert "f(u) = " in result.stdout
    assert "1 warning" in result.stdout


def test_invalid_file_exits_2_and_others_are_still_checked(runner: CliRunner, tmp_path: Path) -> None:
    """An expected answer with an unknown name is invalid input (exit 2); the other files are still checked."""
    path = _edited(tmp_path, ATWOOD, 'y1: "(m2 - m1)*g/(m1 + m2)"', 'y1: "(m2 - m1)*gg/(m1 + m2)"')
    result = runner.invoke(main, ["check", path, str(BEAD)])
    assert result.exit_code == 2
    assert "expected.accelerations.y1: unknown name 'gg'" in result.stderr
    assert "Bead on a wire" in result.stdout


def test_mismatch_and_invalid_input_exit_2(runner: CliRunner, tmp_path: Path) -> None:
    """With a mismatch in one file and invalid input in another the exit code is the larger, 2."""
    wrong = _edited(tmp_path, ATWOOD, 'y1: "(m2 - m1)*g/(m1 + m2)"', 'y1: "(m1 - m2)*g/(m1 + m2)"')
    missing = str(tmp_path / "missing.yaml")
    result = runner.invoke(main, ["check", wrong, missing])
    assert result.exit_code == 2
    assert "file not found" in result.stderr and "✗" in result.stdout


def test_file_without_expected_answers(runner: CliRunner, tmp_path: Path) -> None:
    """A problem without `expected:` says there is nothing to check and exits 0."""
    path = tmp_path / "free.yaml"
    path.write_text("name: free particle\nparameters: {m: mass}\ncoordinates: [x]\n"
                    "particles: {p: {mass: m, position: [x, 0]}}\n")
    result = runner.invoke(main, ["check", str(path)])
    assert result.exit_code == 0
    assert "no expected answers to check" in result.stdout


def test_no_files_is_a_usage_error(runner: CliRunner) -> None:
    """`lagsolve check` without files is a usage error (exit 2)."""
    result = runner.invoke(main, ["check"])
    assert result.exit_code == 2 and "Missing argument" in result.stderr
