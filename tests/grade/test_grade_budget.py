"""A CPU budget on the comparisons of ``lagsolve grade`` (issue 31): a step whose comparison takes too long (here a
deliberately huge answer) is `ungraded` with a message saying so, within about its budget, and the other steps
and the other students are graded; every output format says it (JUnit: skipped)."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from lagsolve.app.grading import grade_files
from lagsolve.errors import SpecError
from lagsolve.grade import submission as reader
from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading, read_grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem
from lagsolve.render.grades import RENDER, summary_markdown
from lagsolve.schemas import grades_schema, input_schema

ROOT = Path(__file__).resolve().parents[2]
KEY = ROOT / "problems" / "hole_table.yaml"
#: ψ expanded to a polynomial of degree 60 in seven symbols when it is compared with the key's up to a factor
HUGE = "(r + z + l + m1 + m2 + g + theta)**60 - (r - z - l)**60"
BUDGET = 1.0


def test_a_huge_answer_is_ungraded_within_its_budget() -> None:
    problem = load_problem(KEY)
    derivation = derive(problem)
    steps = {"constraints": {"string": HUGE}, "potential": "m2*g*z", "kinetic": "m1*(r_dot**2 + r**2*theta_dot**2)/2"}
    grading = Grading(dict.fromkeys(steps, 1.0), step_budget=BUDGET)
    started = time.process_time()
    result = grade(derivation, grading, read_text(json.dumps({"steps": steps}), problem, "s.yaml"))
    assert time.process_time() - started < BUDGET + 3
    by = {s.step: s for s in result.steps}
    assert (by["constraints"].status, by["constraints"].points) == ("ungraded", 0.0)
    assert "CPU budget" in by["constraints"].message and "by hand" in by["constraints"].message
    assert by["potential"].status == "correct"
    assert (by["kinetic"].status, by["kinetic"].mistake) == ("incorrect", "missing_kinetic_term")


def test_the_class_is_graded_and_every_format_says_ungraded(tmp_path: Path) -> None:
    key = tmp_path / "key.yaml"
    grading = f"grading: {{weights: {{constraints: 1, potential: 1}}, step_budget: {BUDGET}}}"
    key.write_text(KEY.read_text() + f"\n{grading}\n")
    slow, fine = tmp_path / "slow.yaml", tmp_path / "fine.yaml"
    slow.write_text(json.dumps({"student": "slow", "steps": {"constraints": {"string": HUGE}, "potential": "m2*g*z"}}))
    fine.write_text(json.dumps({"student": "fine", "steps": {"constraints": {"string": "r - z - l"},
                                                             "potential": "m2*g*z"}}))
    grades = grade_files(key, [slow, fine])
    assert [str(s.status) for s in grades.grades[0].steps] == ["correct", "ungraded"]  # potential, constraints
    assert [str(s.status) for s in grades.grades[1].steps] == ["correct", "correct"]
    junit = RENDER["junit"](grades)
    assert "<skipped message=" in junit and 'failures="0"' in junit
    data = json.loads(RENDER["json"](grades))
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.Draft202012Validator(grades_schema()).validate(data)
    assert "ungraded" in RENDER["csv"](grades) and "ungraded" in RENDER["text"](grades)
    assert "| ungraded |" in summary_markdown(grades)


def test_the_summary_has_no_ungraded_column_when_nothing_is(tmp_path: Path) -> None:
    fine = tmp_path / "fine.yaml"
    fine.write_text(json.dumps({"student": "fine", "steps": {"potential": "m2*g*z"}}))
    assert "ungraded" not in summary_markdown(grade_files(KEY, [fine]))


def test_step_budget_is_in_the_input_schema() -> None:
    jsonschema = pytest.importorskip("jsonschema")
    from ruamel.yaml import YAML

    text = KEY.read_text() + "\ngrading: {step_budget: 2.5, frequency_form: squared}\n"
    data = YAML(typ="safe", pure=True).load(text)
    jsonschema.Draft202012Validator(input_schema()).validate(data)
    data["grading"]["step_budget"] = 0
    assert list(jsonschema.Draft202012Validator(input_schema()).iter_errors(data))


@pytest.mark.parametrize("value", ["0", "-1", "true", "'fast'", "1e9"])
def test_a_bad_step_budget_is_refused(tmp_path: Path, value: str) -> None:
    key = tmp_path / "key.yaml"
    key.write_text(KEY.read_text() + f"\ngrading: {{step_budget: {value}}}\n")
    with pytest.raises(SpecError) as raised:
        read_grading(key, load_problem(key))
    assert "step_budget" in str(raised.value)


def test_a_map_too_large_to_invert_is_a_per_submission_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(reader, "MAP_BUDGET", BUDGET)
    mapping = {"a": "(r + theta + z)**30 + theta*r", "b": "(r*theta - z)**30 + z**2*r",
               "c": "(r + z*theta)**30 - theta"}
    started = time.process_time()
    with pytest.raises(SpecError) as raised:
        read_text(json.dumps({"coordinates_map": mapping, "steps": {}}), load_problem(KEY), "s.yaml")
    assert time.process_time() - started < BUDGET + 3
    assert "too large" in str(raised.value)
