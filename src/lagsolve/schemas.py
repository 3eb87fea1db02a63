"""JSON Schemas (draft 2020-12) of the problem file, of the JSON result and of the JSON grades (``lagsolve schema``).

The input schema describes the shape the loader accepts (keys, nesting, which values are
expressions); the loader checks more than a schema can say (declared names, expression grammar,
sizes), so a file valid against the schema can still be refused, never the reverse. The output
schema describes :func:`lagsolve.render.report.result_dict` (format section 2 and the additions
in ``docs/format.md``); the grades schema describes ``lagsolve grade --format json``
(:func:`lagsolve.render.grades.grades_json`, ``docs/grading.md``). Plain data: nothing here imports SymPy.
"""

from __future__ import annotations

import json
from typing import Any

from lagsolve.problem.methods import METHODS

DRAFT = "https://json-schema.org/draft/2020-12/schema"
KINDS = ("input", "output", "grades")
#: the steps and mistake names of ``lagsolve grade`` (the contract's; tests check them against lagsolve.grade)
GRADE_STEPS = ("kinetic", "potential", "lagrangian", "constraints", "momenta", "generalized_forces", "equations",
               "accelerations", "multipliers", "constraint_forces", "normal_force", "conserved", "effective_potential",
               "equilibria", "frequencies", "hamiltonian")
GRADE_STATUSES = ("correct", "incorrect", "follows", "missing", "unreadable", "ungraded")
GRADE_MISTAKES = ("sign_error", "missing_factor", "lambda_sign_convention", "missing_velocity_squared_terms",
                  "missing_moving_constraint_term", "dropped_constraint", "wrong_potential_sign",
                  "missing_kinetic_term", "wrong_dimension", "missing_abs")

_NAME = {"type": "string", "pattern": "^[A-Za-z][A-Za-z0-9_]*$"}
_EXPR = {"type": ["string", "number"], "description": "an expression in the declared names (or a number)"}
_VECTOR = {"type": "array", "items": {"$ref": "#/$defs/expression"}, "minItems": 2, "maxItems": 3}
_TEXT = {"type": "string"}
_POSITIVE = {"type": "number", "exclusiveMinimum": 0}
_UNIT = {"type": ["string", "integer"], "description": "a unit such as kg, m/s^2, N*m or rad (1: a pure number)"}


def _closed(properties: dict[str, Any], required: tuple[str, ...] = ()) -> dict[str, Any]:
    out: dict[str, Any] = {"type": "object", "properties": properties, "additionalProperties": False}
    if required:
        out["required"] = list(required)
    return out


def _names(detail: dict[str, Any]) -> dict[str, Any]:
    """A list of names, or a mapping name → description (or → details)."""
    return {"oneOf": [
        {"type": "array", "items": {"$ref": "#/$defs/name"}},
        {"type": "object", "propertyNames": {"$ref": "#/$defs/name"},
         "additionalProperties": {"anyOf": [_TEXT, {"type": "null"}, detail]}},
    ]}


def _by_name(value: dict[str, Any]) -> dict[str, Any]:
    return {"type": "object", "propertyNames": {"$ref": "#/$defs/name"}, "additionalProperties": value}


def _one_or_many(item: dict[str, Any]) -> dict[str, Any]:
    return {"anyOf": [item, {"type": "array", "items": item, "minItems": 1}]}


def input_schema() -> dict[str, Any]:
    """The schema of a problem file (format v1 and lagsolve's additions)."""
    properties = {**_declarations(), **_mechanics(), "expected": _expected(), **_running()}
    return {
        "$schema": DRAFT,
        "$id": "https://lagsolve.invalid/schema/problem-v1.json",
        "title": "lagsolve problem file (format v1)",
        "type": "object",
        "required": ["name", "coordinates"],
        "properties": properties,
        "additionalProperties": False,
        "$defs": {"name": _NAME, "expression": _EXPR, "vector": _VECTOR},
    }


def _declarations() -> dict[str, Any]:
    """The problem file's title and declarations: name, description, time, parameters, functions, coordinates."""
    return {
    "name": {"type": "string", "minLength": 1},
    "description": _TEXT,
    "time": {"anyOf": [{"$ref": "#/$defs/name"}, _closed({"name": {"$ref": "#/$defs/name"}, "unit": _UNIT})]},
    "parameters": _names(_closed({"description": _TEXT, "positive": {"type": "boolean"},
                                  "real": {"type": "boolean"}, "value": {"type": "number"}, "unit": _UNIT})),
    "functions": _names(_closed({"description": _TEXT, "unit": _UNIT})),
    "coordinates": _names(_closed({"description": _TEXT, "positive": {"type": "boolean"}, "unit": _UNIT})),
    }


def _mechanics() -> dict[str, Any]:
    """The problem file's mechanics: particles, bodies, gravity, energies, forces, constraints, friction."""
    expr = {"$ref": "#/$defs/expression"}
    vector = {"$ref": "#/$defs/vector"}
    return {
    "particles": _by_name(_closed({"mass": expr, "position": vector}, ("mass", "position"))),
    "bodies": _by_name(_closed({
        "mass": expr, "position": vector,
        "inertia": {"anyOf": [expr, {"type": "array", "items": expr}]},
        "angular_velocity": {"anyOf": [expr, {"type": "array", "items": expr}]},
    }, ("mass", "position", "inertia", "angular_velocity"))),
    "gravity": vector,
    "kinetic": expr,
    "potential": expr,
    "dissipation": expr,
    "forces": {"type": "array", "items": {"oneOf": [
        _closed({"coordinate": {"$ref": "#/$defs/name"}, "value": expr}, ("coordinate", "value")),
        _closed({"on": {"$ref": "#/$defs/name"}, "force": vector}, ("on", "force")),
    ]}},
    "constraints": _by_name({
        **_closed({"holonomic": expr, "nonholonomic": expr, "on": _one_or_many({"$ref": "#/$defs/name"}),
                   "unilateral": {"type": "boolean"},
                   "at": {**vector, "description": "the point of the body or particle named first in 'on' "
                                          "where it acts: a contact, the second name gets the opposite force"}}),
        "oneOf": [{"required": ["holonomic"]}, {"required": ["nonholonomic"]}],
    }),
    "friction": _by_name(_closed({
        "coefficient": expr, "static": expr,
        "on": {**_one_or_many({"$ref": "#/$defs/name"}),
               "description": "what slides, or [what slides, what carries the surface]"},
        "at": {**vector, "description": "the contact point of a body (default: its normal constraint's)"},
        "normal": _one_or_many({"$ref": "#/$defs/name"}), "sliding": _one_or_many({"$ref": "#/$defs/name"}),
    }, ("coefficient", "normal"))),
    }


def _expected() -> dict[str, Any]:
    """The problem file's ``expected`` section: the answers a derivation is checked against."""
    expr = {"$ref": "#/$defs/expression"}
    vector = {"$ref": "#/$defs/vector"}
    equilibrium = _closed({"value": expr, "stable": {"type": "boolean"}, "frequency": expr}, ("value",))
    return _closed({
        "accelerations": _by_name(expr),
        "multipliers": _by_name(expr),
        "constraint_forces": _by_name({"anyOf": [expr, _closed({"vector": vector, "magnitude": expr})]}),
        "reduced": _closed({"independent": {"type": "array", "items": {"$ref": "#/$defs/name"}},
                            "accelerations": _by_name(expr)}),
        "conserved": _by_name(expr),
        "effective_potential": _closed({"coordinate": {"$ref": "#/$defs/name"}, "expression": expr,
                                        "equilibria": {"type": "array", "items": equilibrium}},
                                       ("coordinate",)),
        "normal_modes": {"type": "array", "items": _closed({
            "at": _by_name(expr), "stable": {"type": "boolean"},
            "squared_frequencies": {"type": "array", "items": expr, "minItems": 1},
            "shapes": {"type": "array", "items": {"type": "array", "items": expr, "minItems": 1}, "minItems": 1,
                       "description": "one mode shape per squared frequency, a component per coordinate"},
        }, ("at",))},
        "steady_motions": _closed({"coordinate": {"$ref": "#/$defs/name"}, "rate": {"$ref": "#/$defs/name"},
                                   "values": {"type": "array", "items": expr, "minItems": 1},
                                   "stable": {"type": "boolean"}, "frequency": expr},
                                  ("coordinate", "rate", "values")),
    })


def _running() -> dict[str, Any]:
    """The problem file's ``simulation``, ``independent`` and ``grading`` sections."""
    expr = {"$ref": "#/$defs/expression"}
    return {
    "simulation": _closed({
        "values": _by_name({"type": "number"}),
        "functions": {"type": "object", "additionalProperties": expr,
                      "description": "concrete forms of declared functions: \"f(u)\": expression in u"},
        "initial": _by_name({"type": "number"}),
        "t_end": _POSITIVE,
        "samples": {"type": "integer", "minimum": 2, "maximum": 1_000_000},
        "method": {"enum": list(METHODS)},
        "rtol": _POSITIVE,
        "atol": _POSITIVE,
    }),
    "independent": {"type": "array", "items": {"$ref": "#/$defs/name"}, "minItems": 1},
    "grading": _closed({  # lagsolve grade (docs/grading.md)
        "weights": {"type": "object", "additionalProperties": {"type": "number", "minimum": 0, "maximum": 1000}},
        "follow_through": {"type": "number", "minimum": 0, "maximum": 1},
        "lambda_sign": {"enum": ["strict", "either"]},
        "frequency_form": {"enum": ["either", "squared"],
                           "description": "the frequencies step: ω or ω² (either) or ω² only (squared)"},
        "step_budget": {"type": "number", "minimum": 0.1, "maximum": 3600,
                        "description": "CPU seconds to grade one step of one submission (then it is ungraded)"},
    }),
    }


def output_schema() -> dict[str, Any]:
    """The schema of a JSON result (``lagsolve derive --format json``), generated from the records the JSON is
    written from (:class:`lagsolve.render.sections.Sections`: the core's keys, ``analysis``, ``hamiltonian``,
    ``notes`` and ``units``), so that it cannot drift from the output."""
    from lagsolve.render.model import json_schema
    from lagsolve.render.sections import Sections

    generated = json_schema(Sections)
    return {
        "$schema": DRAFT,
        "$id": "https://lagsolve.invalid/schema/result-v1.json",
        "title": "lagsolve result (format v1)",
        **generated,
        "$defs": {"name": _NAME},
    }


def grades_schema() -> dict[str, Any]:
    """The schema of the grades of a class (``lagsolve grade --format json``)."""
    points = {"type": "number", "minimum": 0}
    step = _closed({
        "step": {"enum": list(GRADE_STEPS)},
        "status": {"enum": list(GRADE_STATUSES)},
        "mistake": {"anyOf": [{"type": "null"}, {"enum": list(GRADE_MISTAKES)}]},
        "points": points,
        "max_points": points,
        "message": {"type": "string"},
    }, ("step", "status", "mistake", "points", "max_points", "message"))
    submission = _closed({
        "student": {"type": "string", "minLength": 1},
        "source": {"type": "string"},
        "points": points,
        "max_points": points,
        "error": {"type": ["string", "null"], "description": "why the file could not be read at all (every step "
                                                             "is then unreadable)"},
        "steps": {"type": "array", "items": step},
    }, ("student", "source", "points", "max_points", "error", "steps"))
    return {
        "$schema": DRAFT,
        "$id": "https://lagsolve.invalid/schema/grades-v1.json",
        "title": "lagsolve grades (lagsolve grade --format json)",
        **_closed({"key": {"type": "string", "description": "the key problem's name"},
                   "source": {"type": "string", "description": "the key problem's file"},
                   "submissions": {"type": "array", "items": submission}}, ("key", "source", "submissions")),
    }


def schema(kind: str) -> dict[str, Any]:
    """The schema named ``kind`` ("input", "output" or "grades").

    Raises
    ------
    ValueError
        ``kind`` is none of them.
    """
    if kind == "input":
        return input_schema()
    if kind == "output":
        return output_schema()
    if kind == "grades":
        return grades_schema()
    raise ValueError(f"unknown schema {kind!r}; use one of: {', '.join(KINDS)}")


def schema_json(kind: str) -> str:
    """:func:`schema` as indented JSON text."""
    return json.dumps(schema(kind), indent=2) + "\n"
