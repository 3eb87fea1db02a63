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
