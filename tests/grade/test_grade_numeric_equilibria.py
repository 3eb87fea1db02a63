"""Grading ``equilibria`` and ``frequencies`` when the key knows its equilibria only numerically (issue 31).

Pendulums held by torsion springs (rest angle a): m g l sin θ + k (θ − a) = 0 has no closed form. With two of
them lagsolve finds the equilibrium and its ω² numerically at the simulation values; with one, the effective
potential gives only the condition. The student's numbers are computed here with SciPy (brentq, eigvalsh)."""

from __future__ import annotations

import json
import math
from functools import cache
from typing import Any

import numpy as np
import pytest
from scipy.optimize import brentq

from lagsolve.grade.grader import grade, key_answers
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_text

VALUES = {"m": 1.0, "g": 9.81, "l": 1.0, "k": 3.0, "a": 1.0}
HEAD = """
parameters: {m: mass, g: gravity, l: length, k: torsion stiffness, a: rest angle of the springs}
gravity: [0, -g]
"""
TWO = HEAD + """
name: two torsion pendulums
coordinates: {theta1: angle one, theta2: angle two}
particles:
  bob1: {mass: m, position: [l*sin(theta1), -l*cos(theta1)]}
  bob2: {mass: m, position: [l*sin(theta2), -l*cos(theta2)]}
potential: k*(theta1 - a)**2/2 + k*(theta2 - a)**2/2 + k*(theta1 - theta2)**2/4
simulation: {values: {m: 1.0, g: 9.81, l: 1.0, k: 3.0, a: 1.0}, initial: {theta1: 0.1, theta2: 0.2}, t_end: 1.0}
"""
ONE = HEAD + """
name: torsion pendulum
coordinates: {theta: angle}
particles:
  bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}
potential: k*(theta - a)**2/2
simulation: {values: {m: 1.0, g: 9.81, l: 1.0, k: 3.0, a: 1.0}, initial: {theta: 0.1}, t_end: 1.0}
"""


@cache
def key(which: str) -> tuple:
    problem = load_text(TWO if which == "two" else ONE)
    return problem, derive(problem)


def graded(which: str, steps: dict[str, Any]) -> dict[str, Any]:
    problem, derivation = key(which)
    result = grade(derivation, Grading(dict.fromkeys(steps, 1.0)),
                   read_text(json.dumps({"student": "s", "steps": steps}), problem, "s.yaml"))
    return {s.step: s for s in result.steps}


def _root() -> float:
    """m g l sin θ + k (θ − a) = 0 (the symmetric equilibrium: the coupling spring is then slack)."""
    v = VALUES
    return brentq(lambda th: v["m"] * v["g"] * v["l"] * math.sin(th) + v["k"] * (th - v["a"]), -1.0, 2.0, xtol=1e-14)


def _squares(theta0: float) -> list[float]:
    """Eigenvalues of M⁻¹K at the equilibrium: K = V'' (the coupling k/2 (θ1 − θ2)²/2), M = m l² I."""
    v = VALUES
    diagonal = v["m"] * v["g"] * v["l"] * math.cos(theta0) + v["k"] + v["k"] / 2
    K = np.array([[diagonal, -v["k"] / 2], [-v["k"] / 2, diagonal]])
    return sorted(float(w) for w in np.linalg.eigvalsh(K / (v["m"] * v["l"] ** 2)))


def test_the_key_has_numeric_equilibria() -> None:
    _, derivation = key("two")
    answers = key_answers(derivation)
    [point] = answers["equilibria"].values()
    assert abs(float(point["theta1"]) - _root()) < 1e-6
    assert sorted(float(w) for w in answers["frequencies"].values()) == pytest.approx(_squares(_root()), rel=1e-6)


def test_numeric_equilibria_and_frequencies_graded() -> None:
    root = _root()
    squares = _squares(root)
    steps = {"equilibria": [{"theta1": repr(root), "theta2": repr(root)}],
             "frequencies": [repr(math.sqrt(squares[1])), repr(squares[0])]}  # one ω, one ω², in any order
    result = graded("two", steps)
    assert result["equilibria"].status == "correct", result["equilibria"].message
    assert result["frequencies"].status == "correct", result["frequencies"].message
    wrong = graded("two", {"equilibria": [{"theta1": "0.3", "theta2": "0.3"}], "frequencies": ["12.5", "15.6"]})
    assert wrong["equilibria"].status == wrong["frequencies"].status == "incorrect"


def test_an_equilibrium_known_by_its_condition_is_graded_numerically() -> None:
    root = _root()
    right = graded("one", {"equilibria": [repr(root)]})
    assert right["equilibria"].status == "correct", right["equilibria"].message
    off = graded("one", {"equilibria": [repr(root + 1e-3)]})
    assert off["equilibria"].status == "incorrect"
    assert "is not an equilibrium of the key's" in off["equilibria"].message


def test_follow_through_to_numeric_equilibria() -> None:
    """The torsion springs' potential doubled (k (θ − a)² for k (θ − a)²/2): the student's own equilibrium and ω²,
    found here with SciPy for that potential, follow (lagsolve finds them numerically, as for the key)."""
    v = VALUES
    wrong = "k*(theta1 - a)**2 + k*(theta2 - a)**2 + k*(theta1 - theta2)**2/4 - m*g*l*(cos(theta1) + cos(theta2))"
    root = brentq(lambda th: v["m"] * v["g"] * v["l"] * math.sin(th) + 2 * v["k"] * (th - v["a"]), -1.0, 2.0,
                  xtol=1e-14)
    diagonal = v["m"] * v["g"] * v["l"] * math.cos(root) + 2 * v["k"] + v["k"] / 2
    K = np.array([[diagonal, -v["k"] / 2], [-v["k"] / 2, diagonal]])
    squares = sorted(float(w) for w in np.linalg.eigvalsh(K / (v["m"] * v["l"] ** 2)))
    steps = {"potential": wrong, "equilibria": [{"theta1": repr(root), "theta2": repr(root)}],
             "frequencies": [repr(w) for w in squares]}
    result = graded("two", steps)
    assert result["potential"].status == "incorrect"
    for step in ("equilibria", "frequencies"):
        assert result[step].status == "follows", (step, result[step].message)
