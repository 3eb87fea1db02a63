"""``lagsolve grade``: the gradebook of the examples, the other formats, exit codes (issue 31)."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from lagsolve.cli import main

ROOT = Path(__file__).resolve().parents[2]
KEY = str(ROOT / "problems" / "bead.yaml")
EXAMPLES = sorted(str(p) for p in (ROOT / "examples" / "grading").glob("*.yaml"))


@pytest.fixture(scope="module")
def outputs() -> dict[str, object]:
    runner = CliRunner()
    out: dict[str, object] = {}
    for fmt in ("csv", "json", "junit", "text"):
        result = runner.invoke(main, ["grade", KEY, *EXAMPLES, "--format", fmt])
        out[fmt] = result
    return out


def test_csv_gradebook(outputs: dict) -> None:
    result = outputs["csv"]
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    by = {r["student"]: r for r in rows}
    assert set(by) == {"ada", "bob", "carol", "dan"}
    assert by["ada"]["points"] == by["ada"]["max_points"] == "12"
    assert by["dan"]["points"] == "12"
    assert by["bob"]["potential_status"] == "incorrect" and by["bob"]["equations_status"] == "follows"


def test_json_and_junit(outputs: dict) -> None:
    data = json.loads(outputs["json"].stdout)
    carol = next(s for s in data["submissions"] if s["student"] == "carol")
    mistakes = {s["step"]: s["mistake"] for s in carol["steps"]}
    assert mistakes["constraint_forces"] == "missing_abs"
    assert mistakes["equations"] == "lambda_sign_convention"
    assert all(set(s) == {"step", "status", "mistake", "points", "max_points", "message"} for s in carol["steps"])
    junit = outputs["junit"].stdout
    assert junit.count("<testcase") == 4 * 10 and "<failure" in junit


def test_gradescope_files_and_unreadable_submission(tmp_path: Path) -> None:
    bad = tmp_path / "eve.yaml"
    bad.write_text("steps: [not, a, mapping]\n")
    result = CliRunner().invoke(main, ["grade", KEY, EXAMPLES[0], str(bad), "--format", "gradescope",
                                       "-o", str(tmp_path / "out")])
    assert result.exit_code == 2  # a submission could not be read; the other is graded all the same
    assert "eve.yaml:1" in result.stderr
    ada = json.loads((tmp_path / "out" / "ada" / "results.json").read_text())
    assert ada["score"] == 12 and len(ada["tests"]) == 10
    eve = json.loads((tmp_path / "out" / "eve" / "results.json").read_text())
    assert eve["score"] == 0 and all(t["status"] == "failed" for t in eve["tests"])


def test_bad_key_exits_2(tmp_path: Path) -> None:
    key = tmp_path / "key.yaml"
    key.write_text((ROOT / "problems" / "bead.yaml").read_text() + "grading: {weights: {equations: -1}}\n")
    result = CliRunner().invoke(main, ["grade", str(key), EXAMPLES[0]])
    assert result.exit_code == 2
    assert "grading.weights.equations" in result.stderr


def test_two_submissions_for_one_gradescope_folder_are_refused(tmp_path: Path) -> None:
    """A second file that declares `student: ada` would replace ada's
    results.json with its own: exit 2, naming both, and no folder written."""
    copy = tmp_path / "mallory.yaml"
    copy.write_text("student: ada\nsteps: {kinetic: '0'}\n")
    result = CliRunner().invoke(main, ["grade", KEY, EXAMPLES[0], str(copy), "--format", "gradescope",
                                       "-o", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "mallory.yaml: student: the student id 'ada' gives the results folder 'ada'" in result.stderr
    assert "ada.yaml" in result.stderr and not (tmp_path / "out").exists()


def test_student_ids_a_path_cannot_hold_get_folders_of_their_own(tmp_path: Path) -> None:
    """Ids in another script (王小明, 李雷) all gave the folder 'problem', and a/b and c/b the folder 'b', so a class
    was refused as a clash: each now gets its safe letters and a short hash of the id; a plain id keeps its name."""
    from lagsolve.app.grading import student_folder

    files = []
    for k, student in enumerate(("王小明", "李雷", "a/b", "c/b")):
        path = tmp_path / f"s{k}.yaml"
        path.write_text(f"student: '{student}'\nsteps: {{kinetic: '0'}}\n", encoding="utf-8")
        files.append(str(path))
    result = CliRunner().invoke(main, ["grade", KEY, EXAMPLES[0], *files, "--format", "gradescope",
                                       "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.stderr
    folders = sorted(p.parent.name for p in (tmp_path / "out").glob("*/results.json"))
    assert len(folders) == 5 and "ada" in folders
    assert {student_folder(s) for s in ("王小明", "李雷", "a/b", "c/b")} == set(folders) - {"ada"}
    assert all(f.startswith(("student_", "a_b_", "c_b_")) for f in folders if f != "ada")


def test_student_ids_that_differ_only_in_case_are_refused(tmp_path: Path) -> None:
    """alice and Alice give two folders here, one on macOS or Windows (which ignore case): refused, nothing
    written."""
    files = []
    for student in ("alice", "Alice"):
        path = tmp_path / f"{student}_.yaml"
        path.write_text(f"student: {student}\nsteps: {{kinetic: '0'}}\n", encoding="utf-8")
        files.append(str(path))
    result = CliRunner().invoke(main, ["grade", KEY, *files, "--format", "gradescope", "-o", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "on a file system that ignores case ('alice')" in result.stderr and not (tmp_path / "out").exists()


def test_a_step_that_restates_the_multiplier_is_unreadable(tmp_path: Path) -> None:
    """`multipliers: {wire: lambda_wire}` restates what is asked (it was graded correct): the step is unreadable,
    with the line and the reason; the equations and a force of constraint (λ∇ψ, as in `expected:`) may still use
    λ."""
    student = tmp_path / "taut.yaml"
    student.write_text("student: taut\nsteps:\n  multipliers: {wire: lambda_wire}\n"
                       "  constraint_forces: {wire: Abs(lambda_wire)}\n"
                       "  equations: {x: 'm*x_ddot = -lambda_wire*Derivative(f(x), x)'}\n")
    result = CliRunner().invoke(main, ["grade", KEY, str(student), "--format", "json"])
    grades = json.loads(result.stdout)
    steps = {s["step"]: s for s in grades["submissions"][0]["steps"]}
    assert steps["multipliers"]["status"] == "unreadable" and steps["constraint_forces"]["status"] != "unreadable"
    message = steps["multipliers"]["message"]
    assert "taut.yaml:3" in message and "a multiplier is allowed only in equations and constraint_forces" in message
    assert steps["equations"]["status"] != "unreadable"


def test_no_gradebook_cell_is_a_formula(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The student id was guarded against spreadsheet formulas, the source column (a file name, also the
    student's: an uploaded `=HYPERLINK(...).yaml` graded from its folder) was not."""
    monkeypatch.chdir(tmp_path)
    name = '=HYPERLINK("http:evil","x").yaml'
    Path(name).write_text("student: ok\nsteps:\n  potential: m*g*y\n")
    result = CliRunner().invoke(main, ["grade", KEY, name, "--format", "csv"])
    assert result.exit_code == 0, result.output
    (row,) = list(csv.DictReader(io.StringIO(result.stdout)))
    assert all(cell[:1] not in "=+-@\t\r" for cell in row.values() if cell), row
    assert row["source"] == "'" + name
