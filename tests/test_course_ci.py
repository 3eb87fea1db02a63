"""Course CI: the composite GitHub Action and the pre-commit hooks are well formed and their commands work."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
from ruamel.yaml import YAML

ROOT = Path(__file__).resolve().parents[1]
ATWOOD = ROOT / "problems" / "atwood.yaml"


def _yaml(path: Path) -> object:
    return YAML(typ="safe", pure=True).load(path.read_text(encoding="utf-8"))


def _hooks() -> dict[str, dict]:
    return {hook["id"]: hook for hook in _yaml(ROOT / ".pre-commit-hooks.yaml")}  # type: ignore[attr-defined]


def _run_entry(entry: str, *files: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """Run a hook's entry as pre-commit does (the entry, then the file names), with this Python's lagsolve."""
    words = shlex.split(entry)
    assert words[0] == "lagsolve"
    return subprocess.run([sys.executable, "-m", "lagsolve", *words[1:], *files], cwd=cwd, capture_output=True,
                          text=True, timeout=600, check=False)


def test_hooks_are_python_hooks_on_problem_files() -> None:
    """Both hooks install lagsolve as a Python hook and run on YAML files under problems/."""
    hooks = _hooks()
    assert set(hooks) == {"lagsolve-check", "lagsolve-golden"}
    for hook in hooks.values():
        assert hook["language"] == "python"
        assert re.search(hook["files"], "problems/bead.yaml")
        assert not re.search(hook["files"], "docs/mkdocs.yml")


def test_check_hook_passes_on_a_shipped_problem() -> None:
    """The check hook's entry on problems/atwood.yaml exits 0 with the verdict table."""
    result = _run_entry(_hooks()["lagsolve-check"]["entry"], "problems/atwood.yaml", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert "Atwood machine" in result.stdout and "4 ok" in result.stdout


def test_check_hook_fails_on_a_wrong_answer(tmp_path: Path) -> None:
    """The check hook exits 1 on a file with a wrong answer, so the commit is stopped."""
    (tmp_path / "problems").mkdir()
    wrong = tmp_path / "problems" / "atwood.yaml"
    wrong.write_text(ATWOOD.read_text().replace('y1: "(m2 - m1)*g/(m1 + m2)"', 'y1: "(m1 - m2)*g/(m1 + m2)"', 1))
    result = _run_entry(_hooks()["lagsolve-check"]["entry"], "problems/atwood.yaml", cwd=tmp_path)
    assert result.returncode == 1
    assert "opposite sign" in result.stdout


@pytest.mark.slow
def test_golden_hook_compares_with_tests_golden(tmp_path: Path) -> None:
    """The golden hook exits 0 when tests/golden holds the problem's reports, and 1 with a diff when one changed."""
    (tmp_path / "problems").mkdir()
    (tmp_path / "problems" / "atwood.yaml").write_text(ATWOOD.read_text())
    made = subprocess.run([sys.executable, "-m", "lagsolve", "-q", "derive", "problems/atwood.yaml", "--golden",
                           "tests/golden", "--update-golden"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=600, check=False)
    assert made.returncode == 0, made.stderr
    entry = _hooks()["lagsolve-golden"]["entry"]
    assert _run_entry(entry, "problems/atwood.yaml", cwd=tmp_path).returncode == 0
    golden = tmp_path / "tests" / "golden" / "atwood.md"
    golden.write_text(golden.read_text() + "changed\n")
    changed = _run_entry(entry, "problems/atwood.yaml", cwd=tmp_path)
    assert changed.returncode == 1
    assert "-changed" in changed.stdout


def test_action_is_composite_and_uploads_reports() -> None:
    """action.yml is a composite action that checks, compares with golden files and uploads the reports."""
    action = _yaml(ROOT / "action.yml")
    assert action["runs"]["using"] == "composite"  # type: ignore[index]
    steps = action["runs"]["steps"]  # type: ignore[index]
    scripts = "\n".join(step.get("run", "") for step in steps)
    assert "lagsolve check $FILES" in scripts and "--format junit" in scripts
    assert '--golden "$GOLDEN"' in scripts
    upload = next(step for step in steps if step.get("uses", "").startswith("actions/upload-artifact@"))
    assert upload["if"].startswith("always()")
    assert set(action["inputs"]) >= {"files", "pattern", "base", "golden"}  # type: ignore[index]


@pytest.mark.skipif(sys.platform == "win32", reason="the action's scripts are bash")
def test_action_scripts_are_valid_bash() -> None:
    """Every run script of the action parses with bash -n (after GitHub's ${{ }} expressions are filled in)."""
    steps = _yaml(ROOT / "action.yml")["runs"]["steps"]  # type: ignore[index]
    for step in steps:
        if "run" in step:
            script = re.sub(r"\$\{\{[^}]*\}\}", "x", step["run"])
            result = subprocess.run(["bash", "-n"], input=script, capture_output=True, text=True, check=False)
            assert result.returncode == 0, result.stderr
