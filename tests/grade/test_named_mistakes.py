"""The named mistakes ``missing_moving_constraint_term`` and ``wrong_dimension`` (issue 31), each with its evidence.

The answers "as if the constraint did not move" are derived here with SymPy's LagrangesMethod on the pendulum whose
support is held still (X − A = 0 instead of X − A cos(wt)), never with lagsolve."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
MOVING = "missing_moving_constraint_term"


@cache
def key(name: str) -> tuple:
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    return problem, derive(problem)


def graded(name: str, steps: dict[str, Any]) -> dict[str, Any]:
    problem, derivation = key(name)
    text = json.dumps({"student": "s", "steps": steps})
    result = grade(derivation, Grading(dict.fromkeys(steps, 1.0)), read_text(text, problem, "s.yaml"))
    return {s.step: s for s in result.steps}


def _still_support() -> dict[str, str]:
    """q̈ and λ of the pendulum on a support held at X = A: LagrangesMethod's equations E + λ_s a = 0 (lagsolve's
    E = λ a: λ = −λ_s) solved with the constraint's Ẍ = 0."""
    t = dynamicsymbols._t
    X, theta = dynamicsymbols("X theta")
    m, M, length, g, A = sympy.symbols("m M l g A")
    x, y = X + length * sympy.sin(theta), -length * sympy.cos(theta)
    T = M * X.diff(t) ** 2 / 2 + m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2
    method = LagrangesMethod(T - m * g * y, [X, theta], hol_coneqs=[X - A])
    equations = method.form_lagranges_equations()
    Xdd, thdd, lam = sympy.symbols("Xdd thdd lam")
    plain = {X.diff(t, 2): Xdd, theta.diff(t, 2): thdd, method.lam_vec[0]: lam}
    rows = [e.subs(plain) for e in equations]
    [solution] = sympy.solve([*rows, Xdd], [Xdd, thdd, lam], dict=True)
    names = {theta.diff(t): sympy.Symbol("theta_dot"), X.diff(t): sympy.Symbol("X_dot"),
             theta: sympy.Symbol("theta"), X: sympy.Symbol("X")}
    out = [sympy.sstr(sympy.simplify(e.subs(names))) for e in (solution[Xdd], solution[thdd], -solution[lam])]
    return {"X": out[0], "theta": out[1], "drive": out[2]}


@pytest.mark.parametrize(("name", "step", "answer", "offset"), [
    ("moving_support", "constraints", {"drive": "X_dot = 0"}, "A*w*sin(t*w)"),
    ("moving_support", "constraints", {"drive": "X = 0"}, "A*w*sin(t*w)"),
    ("bead_on_rotating_hoop", "constraints", {"drive": "phi_dot = 0"}, "-Omega"),
    ("rotating_tube", "constraints", {"tilt": "theta_dot", "spin": "phi_dot = 0"}, "-Omega"),
])
def test_a_moving_constraint_written_still(name: str, step: str, answer: dict, offset: str) -> None:
    result = graded(name, {step: answer})[step]
    assert (result.status, result.mistake) == ("incorrect", MOVING), result.message
    assert f"∂ψ/∂t = {offset} is missing" in result.message


@pytest.mark.parametrize(("name", "answer"), [("moving_support", {"drive": "X_dot + A*w*sin(w*t)"}),
                                              ("moving_support", {"drive": "X = A*cos(w*t)"}),
                                              ("rotating_tube", {"tilt": "theta_dot", "spin": "phi_dot = Omega"})])
def test_the_moving_constraint_written_right_is_correct(name: str, answer: dict) -> None:
    assert graded(name, {"constraints": answer})["constraints"].status == "correct"


def test_accelerations_and_multiplier_of_a_still_support_are_named() -> None:
    still = _still_support()
    assert sympy.simplify(sympy.sympify(still["theta"]) + sympy.sympify("g*sin(theta)/l")) == 0
    result = graded("moving_support", {"accelerations": {"X": still["X"], "theta": still["theta"]},
                                       "multipliers": {"drive": still["drive"]}})
    for step in ("accelerations", "multipliers"):
        assert (result[step].status, result[step].mistake) == ("incorrect", MOVING), result[step].message
        assert "drive (∂ψ/∂t = A*w*sin(t*w))" in result[step].message


@pytest.mark.parametrize(("name", "step", "answer", "evidence"), [
    ("hole_table", "kinetic", "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot/2",
     "the terms m2*z_dot/2 [kg*m/s (momentum)] and"),
    ("hole_table", "momenta", {"r": "m1*r_dot", "theta": "m1*r*theta_dot", "z": "m2*z_dot"},
     "theta: its dimension is kg*m/s (momentum) where the key's answer is kg*m^2/s"),
    ("hole_table", "accelerations", {"r": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r",
                                     "z": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2) + r_dot"}, "m/s (velocity)"),
    ("pendulum_cartesian", "potential", "m*g*y + m*y", "have different dimensions"),
    ("bead", "potential", "m*g*f(x)/x", "its dimension is kg*m/s^2 (force) where the key's answer is kg*m^2/s^2"),
])
def test_wrong_dimension(name: str, step: str, answer: Any, evidence: str) -> None:
    result = graded(name, {step: answer})[step]
    assert (result.status, result.mistake) == ("incorrect", "wrong_dimension"), result.message
    assert evidence in result.message


def test_a_dimensional_factor_is_missing_factor_with_the_dimensions_said() -> None:
    result = graded("hole_table", {"potential": "m2*z"})["potential"]
    assert result.mistake == "missing_factor"
    assert "it is 1/g times the key's" in result.message and "its dimension is kg*m where" in result.message


def test_no_wrong_dimension_without_units() -> None:
    """The rotating tube declares no units: a momentum for an energy is not named a dimension error."""
    result = graded("rotating_tube", {"potential": "m*g*r*cos(theta) + m*r_dot"})["potential"]
    assert result.status == "incorrect" and result.mistake != "wrong_dimension"
