"""`lagsolve.schemas`: every shipped problem and JSON result is valid against the published JSON Schemas."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from ruamel.yaml import YAML

from lagsolve.schemas import (
    GRADE_MISTAKES,
    GRADE_STATUSES,
    GRADE_STEPS,
    grades_schema,
    input_schema,
    output_schema,
    schema,
)

jsonschema = pytest.importorskip("jsonschema")

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = sorted((ROOT / "problems").glob("*.yaml"))
GOLDEN = sorted((ROOT / "tests" / "golden").glob("*.json"))


def _validator(data: dict) -> object:
    jsonschema.Draft202012Validator.check_schema(data)
    return jsonschema.Draft202012Validator(data)


def _errors(validator: object, instance: object) -> list[str]:
    return [f"{list(e.absolute_path)}: {e.message}" for e in validator.iter_errors(instance)]  # type: ignore[attr-defined]


def test_schemas_are_valid_draft_2020_12() -> None:
    """The three schemas are themselves valid JSON Schemas of draft 2020-12."""
    for kind in ("input", "output", "grades"):
        assert schema(kind)["$schema"] == "https://json-schema.org/draft/2020-12/schema"
        _validator(schema(kind))


def test_unknown_kind_is_a_value_error() -> None:
    """Asking for another schema names the ones there are."""
    with pytest.raises(ValueError, match="unknown schema 'both'; use one of: input, output, grades"):
        schema("both")


@pytest.mark.parametrize("path", PROBLEMS, ids=lambda p: p.stem)
def test_shipped_problem_is_valid(path: Path) -> None:
    """Each problems/*.yaml, read as plain YAML data, is valid against the input schema."""
    data = YAML(typ="safe", pure=True).load(path.read_text(encoding="utf-8"))
    assert _errors(_validator(input_schema()), data) == []


def test_input_schema_refuses_what_the_loader_refuses() -> None:
    """An unknown key, a missing coordinates list and a constraint of both kinds are schema errors."""
    validator = _validator(input_schema())
    assert _errors(validator, {"name": "x", "coordinates": ["q"], "particle": {}})
    assert _errors(validator, {"name": "x"})
    assert _errors(validator, {"name": "x", "coordinates": ["q"],
                               "constraints": {"c": {"holonomic": "q", "nonholonomic": "q_dot"}}})


@pytest.mark.parametrize("path", GOLDEN, ids=lambda p: p.stem)
def test_golden_result_is_valid(path: Path) -> None:
    """Each tests/golden/*.json is valid against the output schema."""
    assert _errors(_validator(output_schema()), json.loads(path.read_text(encoding="utf-8"))) == []


@pytest.mark.parametrize("name", ["bead", "atwood", "rolling_coin", "central_force"])
def test_rendered_result_is_valid(name: str, shipped_derivation: Callable[[str], Any]) -> None:
    """A result rendered now (with mass_matrix, forcing and notes) is valid against the output schema."""
    from lagsolve.render.report import result_json

    data = json.loads(result_json(shipped_derivation(name)))
    assert {"mass_matrix", "forcing", "notes"} <= set(data)
    assert _errors(_validator(output_schema()), data) == []


def test_output_schema_refuses_a_wrong_version() -> None:
    """A result of another format version is refused."""
    data = json.loads(GOLDEN[0].read_text(encoding="utf-8"))
    data["format_version"] = 2
    assert _errors(_validator(output_schema()), data)


def test_grades_schema_names_are_the_graders() -> None:
    """The steps, statuses and mistake names in the grades schema are those lagsolve.grade uses."""
    from lagsolve.grade.grader import MISTAKES, GradeStatus
    from lagsolve.grade.submission import STEPS

    assert GRADE_STEPS == STEPS and GRADE_MISTAKES == MISTAKES
    assert set(GRADE_STATUSES) == {str(s) for s in GradeStatus}


def test_json_grades_of_the_examples_are_valid(tmp_path: Path) -> None:
    """``lagsolve grade --format json`` on examples/grading/*.yaml (and a file that cannot be read) is valid
    against the grades schema; a grade with an unknown status or mistake is not."""
    from click.testing import CliRunner

    from lagsolve.cli import main

    examples = sorted(str(p) for p in (ROOT / "examples" / "grading").glob("*.yaml"))
    (tmp_path / "eve.yaml").write_text("steps: [not, a, mapping]\n")
    result = CliRunner().invoke(main, ["grade", str(ROOT / "problems" / "bead.yaml"), *examples,
                                       str(tmp_path / "eve.yaml"), "--format", "json"])
    assert result.exit_code == 2, result.output
    data = json.loads(result.stdout)
    validator = _validator(grades_schema())
    assert len(data["submissions"]) == 5 and _errors(validator, data) == []
    # every status but ungraded (a comparison over its CPU budget: tests/grade/test_grade_budget.py)
    assert {s["status"] for g in data["submissions"] for s in g["steps"]} == set(GRADE_STATUSES) - {"ungraded"}
    step = data["submissions"][0]["steps"][0]
    for bad in ({**step, "status": "partial"}, {**step, "mistake": "typo"}, {**step, "extra": 1}):
        data["submissions"][0]["steps"][0] = bad
        assert _errors(validator, data)
