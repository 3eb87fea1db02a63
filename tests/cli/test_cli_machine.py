"""Machine interfaces of the command line: JSON arrays and lines, check as JSON and JUnit, schemas, -q/-v."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
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


def _wrong_atwood(tmp_path: Path) -> str:
    """A copy of the Atwood machine with one acceleration of the wrong sign."""
    target = tmp_path / "atwood.yaml"
    target.write_text(ATWOOD.read_text().replace('y1: "(m2 - m1)*g/(m1 + m2)"', 'y1: "(m1 - m2)*g/(m1 + m2)"', 1))
    return str(target)


def test_derive_json_of_several_files_is_one_array(runner: CliRunner) -> None:
    """`derive --format json` with two files prints one JSON array with a result per file, in order."""
    result = runner.invoke(main, ["derive", str(BEAD), str(ATWOOD), "--format", "json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert [d["name"] for d in data] == ["Bead on a wire", "Atwood machine"]


def test_derive_json_of_one_file_is_one_object(runner: CliRunner) -> None:
    """With one file, `--format json` keeps printing the result object itself."""
    result = runner.invoke(main, ["derive", str(ATWOOD), "--format", "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["name"] == "Atwood machine"


def test_derive_jsonl_prints_one_object_per_line(runner: CliRunner) -> None:
    """`--format jsonl` prints each result as one compact line."""
    result = runner.invoke(main, ["derive", str(BEAD), str(ATWOOD), "--format", "jsonl"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert [json.loads(line)["name"] for line in lines] == ["Bead on a wire", "Atwood machine"]


def test_derive_jsonl_refuses_an_output_path(runner: CliRunner, tmp_path: Path) -> None:
    """jsonl goes to stdout only: with -o it is a usage error (exit 2) that says so."""
    result = runner.invoke(main, ["derive", str(BEAD), "--format", "jsonl", "-o", str(tmp_path)])
    assert result.exit_code == 2
    assert "--format jsonl prints to stdout" in result.stderr


def test_derive_json_array_leaves_out_an_invalid_file(runner: CliRunner, tmp_path: Path) -> None:
    """An invalid file is reported on stderr (exit 2); the array holds the other results."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\n")
    result = runner.invoke(main, ["derive", str(bad), str(ATWOOD), "--format", "json"])
    assert result.exit_code == 2
    assert "missing required key 'coordinates'" in result.stderr
    assert [d["name"] for d in json.loads(result.stdout)] == ["Atwood machine"]


def test_check_json_lists_verdicts(runner: CliRunner, tmp_path: Path) -> None:
    """`check --format json` prints one array: each file's verdicts, counts and whether it passed."""
    result = runner.invoke(main, ["check", str(BEAD), _wrong_atwood(tmp_path), "--format", "json"])
    assert result.exit_code == 1
    bead, atwood = json.loads(result.stdout)
    assert bead["passed"] is True and bead["counts"]["ok"] == 3
    assert atwood["passed"] is False
    wrong = next(v for v in atwood["verdicts"] if v["status"] == "mismatch")
    assert (wrong["quantity"], wrong["name"], wrong["reason"]) == ("accelerations", "y1", "opposite sign")
    assert wrong["expected"] == "g*(m1 - m2)/(m1 + m2)"


def test_check_junit_is_valid_xml_with_a_failure(runner: CliRunner, tmp_path: Path) -> None:
    """`check --format junit` is JUnit XML: testsuites/testsuite/testcase, a mismatch as <failure>."""
    result = runner.invoke(main, ["check", str(BEAD), _wrong_atwood(tmp_path), "--format", "junit"])
    assert result.exit_code == 1
    root = ET.fromstring(result.stdout)
    assert root.tag == "testsuites"
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("7", "1", "0")
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == ["Bead on a wire", "Atwood machine"]
    assert [c.get("name") for c in suites[0].findall("testcase")] == [
        "accelerations.x", "multipliers.wire", "constraint_forces.wire"]
    failures = root.findall("./testsuite/testcase/failure")
    assert len(failures) == 1
    assert failures[0].get("type") == "opposite sign"
    assert "expected: g*(m1 - m2)/(m1 + m2)" in failures[0].text


def test_check_junit_reports_an_invalid_file_as_an_error(runner: CliRunner, tmp_path: Path) -> None:
    """A file that cannot be loaded is one testcase with an <error> carrying the message."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\n")
    result = runner.invoke(main, ["check", str(bad), "--format", "junit"])
    assert result.exit_code == 2
    error = ET.fromstring(result.stdout).find("./testsuite/testcase/error")
    assert error is not None and error.get("type") == "spec"
    assert "missing required key 'coordinates'" in error.get("message")


def test_check_junit_parses_whatever_the_names_hold(runner: CliRunner, tmp_path: Path) -> None:
    """Characters XML forbids in a problem's name (U+FFFE, U+FFFF), in a file name (a control character, a byte
    that is not UTF-8) and in the error message quoting it are written as escapes: the JUnit XML parses."""
    import os

    named = tmp_path / "named.yaml"
    named.write_text('name: "Falling \\uFFFE mass \\uFFFF"\nparameters: {m: mass, g: gravity}\ncoordinates: [y]\n'
                     "particles: {p: {mass: m, position: [0, y]}}\ngravity: [0, -g]\n"
                     'expected: {accelerations: {y: "-g"}}\n', encoding="utf-8")
    odd = Path(os.fsdecode(os.fsencode(str(tmp_path)) + b"/odd\xff\x01\x1b.yaml"))
    odd.write_text("name: odd\n", encoding="utf-8")  # invalid: the error message names the file
    result = runner.invoke(main, ["check", str(named), str(odd), "--format", "junit"])
    assert result.exit_code == 2, result.output
    root = ET.fromstring(result.stdout)
    suites = root.findall("testsuite")
    assert suites[0].get("name") == "Falling \\ufffe mass \\uffff"
    assert suites[1].get("file").endswith("odd\\udcff\\x01\\x1b.yaml")
    assert "odd\\udcff\\x01\\x1b.yaml" in suites[1].find("./testcase/error").get("message")


def test_schema_prints_draft_2020_12(runner: CliRunner) -> None:
    """`schema input` and `schema output` print JSON Schemas of draft 2020-12."""
    for kind, title in (("input", "lagsolve problem file (format v1)"), ("output", "lagsolve result (format v1)")):
        result = runner.invoke(main, ["schema", kind])
        assert result.exit_code == 0, result.output
        data = json.loads(result.stdout)
        assert data["$schema"] == "https://json-schema.org/draft/2020-12/schema"
        assert data["title"] == title


def test_schema_needs_a_known_kind(runner: CliRunner) -> None:
    """An unknown schema name is a usage error (exit 2) listing the choices."""
    result = runner.invoke(main, ["schema", "both"])
    assert result.exit_code == 2
    assert "'input', 'output'" in result.stderr


def test_quiet_leaves_out_summaries_and_wrote_lines(runner: CliRunner, tmp_path: Path) -> None:
    """`-q derive` writes the reports but prints nothing."""
    result = runner.invoke(main, ["-q", "derive", str(ATWOOD), "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert result.stdout == "" and result.stderr == ""
    assert (tmp_path / "atwood" / "atwood.json").exists()


def test_verbose_says_what_is_done(runner: CliRunner) -> None:
    """`-v check` names each file on stderr as it is checked; the table is unchanged on stdout."""
    result = runner.invoke(main, ["-v", "check", str(ATWOOD)])
    assert result.exit_code == 0, result.output
    assert f"lagsolve: checking {ATWOOD}" in result.stderr
    assert "Atwood machine" in result.stdout


def test_quiet_and_verbose_exclude_each_other(runner: CliRunner) -> None:
    """Giving both is a usage error (exit 2)."""
    result = runner.invoke(main, ["-q", "-v", "check", str(ATWOOD)])
    assert result.exit_code == 2
    assert "--quiet and --verbose exclude each other" in result.stderr
