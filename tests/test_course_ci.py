"""Course CI: the composite GitHub Action and the pre-commit hooks are well formed and their commands work."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
import xml.etree.ElementTree as ET
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
    assert 'lagsolve check --timeout "$TIMEOUT" --format junit -- "${files[@]}"' in scripts
    assert '--golden "$GOLDEN" -- "${files[@]}"' in scripts
    assert "${{" not in scripts  # expressions go into env, never into a script's text
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


FALLING = """\
name: Falling mass
parameters: {m: mass, g: gravity}
coordinates: [y]
particles: {p: {mass: m, position: [0, y]}}
gravity: [0, -g]
expected: {accelerations: {y: "-g"}}
"""

#: a pull request's template that runs a command if lagsolve ever renders it outside the sandbox
PAYLOAD = "{{ cycler.__init__.__globals__.os.system('touch PWNED') }}"


def _git(cwd: Path, *args: str) -> str:
    return subprocess.run(["git", "-c", "user.email=ci@example.org", "-c", "user.name=ci", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=60, check=True).stdout


def _run_action(repo: Path, inputs: dict[str, str], tmp: Path) -> tuple[dict[str, str], int, str]:
    """The action's "find" and "check" steps as the runner runs them: each run script in bash with the step's env
    (its ${{ }} expressions filled in from ``inputs``, the find step's outputs and GitHub's context), in ``repo``,
    with this Python's lagsolve on PATH. Returns the outputs, the check step's exit code and its log."""
    steps = {step.get("id") or step.get("name"): step for step in _yaml(ROOT / "action.yml")["runs"]["steps"]}  # type: ignore[index]
    defaults = {name: spec.get("default", "") for name, spec in _yaml(ROOT / "action.yml")["inputs"].items()}  # type: ignore[index]
    given = {**defaults, **inputs}
    outputs: dict[str, str] = {}
    context = {"github.action_path": str(ROOT), "inputs.base || github.base_ref": given["base"],
               **{f"inputs.{k}": v for k, v in given.items()}}

    def run(step: dict, output: Path) -> subprocess.CompletedProcess[str]:
        values = {**context, **{f"steps.files.outputs.{k}": v for k, v in outputs.items()}}
        env = {**os.environ, "GITHUB_OUTPUT": str(output), "RUNNER_TEMP": str(tmp),
               "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
        for key, value in step.get("env", {}).items():
            env[key] = re.sub(r"\$\{\{\s*(.*?)\s*\}\}", lambda m: values[m.group(1)], str(value))
        return subprocess.run(["bash", "-e", "-c", step["run"]], cwd=repo, env=env, capture_output=True, text=True,
                              timeout=600, check=False)

    found = run(steps["files"], tmp / "find-output")
    assert found.returncode == 0, found.stderr
    outputs.update(line.split("=", 1) for line in (tmp / "find-output").read_text().splitlines())
    assert "problem files" in found.stdout
    if outputs["count"] == "0":
        return outputs, 0, found.stdout
    check = run(steps["Check expected answers and golden files"], tmp / "check-output")
    return outputs, check.returncode, check.stdout + check.stderr


@pytest.mark.skipif(sys.platform == "win32", reason="the action's scripts are bash")
@pytest.mark.parametrize("source", ["changed", "listed"])
def test_the_action_takes_every_file_name_as_one_path(tmp_path: Path, source: str) -> None:
    """A pull request that adds "problems/a --templates tpl .yaml" (and a template that would run a command) and
    "problems/pendulum one.yaml": the action finds exactly those two files (against the base branch, or given
    one per line, with a name that starts with a dash), checks and derives each as one path, runs nothing of the
    template, and writes the reports of both."""
    origin, repo = tmp_path / "origin.git", tmp_path / "repo"
    _git(tmp_path, "init", "-q", "--bare", str(origin))
    _git(tmp_path, "clone", "-q", str(origin), str(repo))
    (repo / "problems").mkdir()
    (repo / "problems" / "base.yaml").write_text(FALLING.replace("Falling mass", "Base"))
    _git(repo, "add", "-A")
    _git(repo, "commit", "-q", "-m", "base")
    _git(repo, "push", "-q", "origin", "HEAD:main")
    names = ["problems/a --templates tpl .yaml", "problems/pendulum one.yaml"]
    for name in names:
        (repo / name).write_text(FALLING)
    (repo / "tpl" / "markdown").mkdir(parents=True)
    (repo / "tpl" / "markdown" / "report.md.j2").write_text(PAYLOAD)
    (repo / "-lead.yaml").write_text(FALLING)
    _git(repo, "add", "-A")
    _git(repo, "commit", "-q", "-m", "a pull request")
    inputs = {"base": "main", "golden": "", "timeout": "60"}
    if source == "listed":
        names = [*names, "-lead.yaml"]
        inputs = {**inputs, "files": "\n".join(names) + "\n"}
    outputs, status, log = _run_action(repo, inputs, tmp_path)
    assert json.loads(outputs["files"]) == names and outputs["count"] == str(len(names))
    assert status == 0, log
    assert not list(repo.rglob("PWNED")) and not list(tmp_path.rglob("PWNED"))
    suites = ET.fromstring((repo / "lagsolve-reports" / "check.xml").read_text()).findall("testsuite")
    assert [suite.get("file") for suite in suites] == names
    assert len(list((repo / "lagsolve-reports").glob("*/*.md"))) == len(names)
    assert "::stop-commands::" in log


@pytest.mark.skipif(sys.platform == "win32", reason="the action's scripts are bash")
def test_the_action_skips_the_check_when_no_problem_changed(tmp_path: Path) -> None:
    """No changed problem file: the count is 0, the files an empty JSON array, and nothing runs."""
    _git(tmp_path, "init", "-q")
    (tmp_path / "README").write_text("x")
    _git(tmp_path, "add", "-A")
    _git(tmp_path, "commit", "-q", "-m", "x")
    outputs, status, _ = _run_action(tmp_path, {"golden": ""}, tmp_path)
    assert (outputs["count"], json.loads(outputs["files"]), status) == ("0", [], 0)


FALLING_RUN = FALLING + "simulation: {values: {m: 1.0, g: 9.81}, initial: {y: 0, y_dot: 0}, t_end: 0.5}\n"


@pytest.mark.parametrize(("command", "options"), [
    ("derive", ["--format", "json"]),
    ("check", []),
    ("simulate", ["--format", "csv"]),
    ("sweep", ["--grid", "m=1:2:2", "-o", "s.csv"]),
])
def test_every_command_takes_file_names_after_a_double_dash(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           command: str, options: list[str]) -> None:
    """After ``--`` a file named like an option ("-x --templates y.yaml") is a file: every command reads it."""
    from click.testing import CliRunner

    from lagsolve.cli import main

    if command == "sweep":
        pytest.importorskip("pandas")
    monkeypatch.chdir(tmp_path)
    name = "-x --templates y.yaml"
    (tmp_path / name).write_text(FALLING_RUN)
    result = CliRunner().invoke(main, [command, *options, "--", name])
    assert result.exit_code == 0, result.output
    assert "No such option" not in result.output
