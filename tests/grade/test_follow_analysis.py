"""Follow-through into ``normal_force``, ``conserved``, ``effective_potential``, ``equilibria`` and ``frequencies``
(issue 31): after a wrong potential (or λ), a later step that follows from the student's own earlier step is
`follows`. What follows is derived here with SymPy alone (solve, diff, eigenvals), never with lagsolve."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

import sympy

from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
m, g, R, Omega = sympy.symbols("m g R Omega", positive=True)
theta, theta_dot = sympy.symbols("theta theta_dot", real=True)
T_HOOP = "m*R**2*(theta_dot**2 + sin(theta)**2*phi_dot**2)/2"
WRONG_V = "m*g*R*cos(theta)"  # the key's is −m g R cos θ (θ from the lowest point)


@cache
def key(name: str) -> tuple:
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    return problem, derive(problem)


def graded(name: str, steps: dict[str, Any], mapping: dict[str, str] | None = None) -> dict[str, Any]:
    problem, derivation = key(name)
    data: dict[str, Any] = {"student": "s", "steps": steps}
    if mapping:
        data["coordinates_map"] = mapping
    result = grade(derivation, Grading(dict.fromkeys(steps, 1.0)), read_text(json.dumps(data), problem, "s.yaml"))
    return {s.step: s for s in result.steps}


def _hoop_with_wrong_potential() -> dict[str, Any]:
    """The student's L = T − m g R cos θ with φ̇ = Ω put in: V_eff = −L(θ̇ = 0), its equilibria (dV_eff/dθ = 0),
    ω² = V_eff''/(m R²) about each one with V_eff'' > 0 for some parameters, and the Jacobi integral."""
    L = m * R**2 * (theta_dot**2 + sympy.sin(theta) ** 2 * Omega**2) / 2 - m * g * R * sympy.cos(theta)
    v_eff = -L.subs(theta_dot, 0)
    slope = sympy.diff(v_eff, theta)
    # slope = −m R sin θ (g + R Ω² cos θ): sin θ = 0, or cos θ = −g/(R Ω²) (checked below)
    points = [sympy.Integer(0), sympy.pi, sympy.acos(-g / (R * Omega**2)), -sympy.acos(-g / (R * Omega**2))]
    assert all(sympy.simplify(slope.subs(theta, p)) == 0 for p in points)
    assert sympy.simplify(slope + m * R * sympy.sin(theta) * (g + R * Omega**2 * sympy.cos(theta))) == 0
    curvature = sympy.diff(v_eff, theta, 2) / (m * R**2)
    squares = []
    for p in points:
        w2 = sympy.simplify(curvature.subs(theta, p))
        if w2.is_negative is not True and w2 not in squares:
            squares.append(w2)
    jacobi = sympy.expand(theta_dot * sympy.diff(L, theta_dot) - L)
    return {"effective_potential": sympy.sstr(v_eff), "equilibria": [sympy.sstr(p) for p in points],
            "frequencies": [sympy.sstr(w) for w in squares], "energy": sympy.sstr(jacobi)}


def test_hoop_analysis_steps_follow_a_wrong_potential() -> None:
    own = _hoop_with_wrong_potential()
    assert len(own["equilibria"]) == 4  # 0, π and ±acos(−g/(R Ω²)): not the key's ±acos(g/(R Ω²))
    steps = {"kinetic": T_HOOP, "potential": WRONG_V,
             "effective_potential": {"coordinate": "theta", "expression": own["effective_potential"]},
             "equilibria": own["equilibria"], "frequencies": own["frequencies"],
             "conserved": {"energy": own["energy"]}}
    result = graded("bead_on_rotating_hoop", steps)
    assert result["potential"].mistake == "wrong_potential_sign"
    for step in ("effective_potential", "equilibria", "conserved"):
        assert result[step].status == "follows", (step, result[step].message)
        assert result[step].points == result[step].max_points
    # −V flips which of θ = 0 and θ = π is stable, and its ω² are the key's again
    assert result["frequencies"].status in ("correct", "follows"), result["frequencies"].message


def test_a_step_wrong_against_the_students_own_potential_too_is_incorrect() -> None:
    steps = {"kinetic": T_HOOP, "potential": WRONG_V, "equilibria": ["0", "pi", "pi/2"],
             "conserved": {"energy": "m*R**2*theta_dot**2/2 + m*g*R*cos(theta)"}}
    result = graded("bead_on_rotating_hoop", steps)
    assert result["equilibria"].status == "incorrect"
    assert result["conserved"].status == "incorrect"


def test_follow_through_in_the_students_coordinates() -> None:
    """The same wrong potential written in α = θ − π: their equilibria, shifted by π, follow."""
    own = _hoop_with_wrong_potential()
    shifted = [sympy.sstr(sympy.sympify(p) - sympy.pi) for p in own["equilibria"]]
    steps = {"kinetic": "m*R**2*(alpha_dot**2 + sin(alpha)**2*phi_dot**2)/2", "potential": "-m*g*R*cos(alpha)",
             "equilibria": shifted}
    result = graded("bead_on_rotating_hoop", steps, {"alpha": "theta - pi"})
    assert result["equilibria"].status == "follows", result["equilibria"].message


def test_coupled_pendulums_frequencies_follow_a_doubled_spring() -> None:
    """V with k l² (sin θ2 − sin θ1)² (twice the key's): ω² are the eigenvalues of M⁻¹K of that V at rest."""
    t1, t2, k, l_ = sympy.symbols("theta1 theta2 k l")
    V = -m * g * l_ * (sympy.cos(t1) + sympy.cos(t2)) + k * l_**2 * (sympy.sin(t2) - sympy.sin(t1)) ** 2
    K = sympy.hessian(V, (t1, t2)).subs({t1: 0, t2: 0})
    squares = sorted((sympy.simplify(e) for e in (K / (m * l_**2)).eigenvals()), key=sympy.default_sort_key)
    assert len(squares) == 2
    result = graded("coupled_pendulums", {"potential": sympy.sstr(V),
                                          "frequencies": [sympy.sstr(w) for w in squares]})
    assert result["potential"].status == "incorrect"
    assert result["frequencies"].status == "follows", result["frequencies"].message


def test_normal_force_follows_the_students_multiplier() -> None:
    """The block on a rough incline: N = |λ| |∇h| = |λ| for the constraint h = 0 on a unit normal."""
    result = graded("rough_incline", {"multipliers": {"surface": "m*g*sin(alpha)"},
                                      "normal_force": {"contact": "m*g*Abs(sin(alpha))"}})
    assert result["multipliers"].status == "incorrect"
    assert result["normal_force"].status == "follows", result["normal_force"].message
    wrong = graded("rough_incline", {"multipliers": {"surface": "m*g*sin(alpha)"},
                                     "normal_force": {"contact": "m*g*Abs(tan(alpha))"}})
    assert wrong["normal_force"].status == "incorrect"
