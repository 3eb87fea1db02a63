# ruff: noqa: E501 - the answers are long formulas, one a line
"""``coordinates_map:`` (issue 31): a submission in other coordinates is graded after the change of coordinates.

Keys: the bead on a rotating hoop (θ, φ) answered in α = θ − π; the Cartesian pendulum (x, y) answered in polar
coordinates (r, φ); the pendulum on a driven support (X, θ) answered in u = X − A cos(wt) (a map with t). Correct
answers earn every point, a wrong step in the student's coordinates is still found and named, and a wrong L in the
student's coordinates gives `follows` to the equations SymPy's LagrangesMethod derives from it (never lagsolve)."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.app.grading import grade_files
from lagsolve.errors import SpecError
from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
ALL = ("kinetic", "potential", "lagrangian", "constraints", "momenta", "generalized_forces", "equations",
       "accelerations", "multipliers", "constraint_forces", "conserved", "effective_potential", "equilibria",
       "frequencies", "hamiltonian")

HOOP_MAP = {"alpha": "theta - pi"}
HOOP = {
    "kinetic": "m*R**2*(alpha_dot**2 + sin(alpha)**2*phi_dot**2)/2",
    "potential": "m*g*R*cos(alpha)",
    "lagrangian": "m*R**2*(alpha_dot**2 + sin(alpha)**2*phi_dot**2)/2 - m*g*R*cos(alpha)",
    "constraints": {"drive": "phi = Omega*t"},
    "momenta": {"alpha": "m*R**2*alpha_dot", "phi": "m*R**2*sin(alpha)**2*phi_dot"},
    "generalized_forces": {"alpha": "m*R**2*sin(alpha)*cos(alpha)*phi_dot**2 + m*g*R*sin(alpha)", "phi": "0"},
    "equations": {"alpha": "m*R**2*alpha_ddot - m*R**2*sin(alpha)*cos(alpha)*phi_dot**2 - m*g*R*sin(alpha)",
                  "phi": "m*R**2*sin(alpha)**2*phi_ddot + 2*m*R**2*sin(alpha)*cos(alpha)*alpha_dot*phi_dot = lambda_drive"},
    "accelerations": {"alpha": "sin(alpha)*(Omega**2*cos(alpha) + g/R)", "phi": "0"},
    "multipliers": {"drive": "2*Omega*m*R**2*alpha_dot*sin(alpha)*cos(alpha)"},
    "conserved": {"energy": "m*R**2*alpha_dot**2/2 - m*R**2*Omega**2*sin(alpha)**2/2 + m*g*R*cos(alpha)"},
    "effective_potential": {"coordinate": "alpha", "expression": "m*g*R*cos(alpha) - m*R**2*Omega**2*sin(alpha)**2/2"},
    "equilibria": ["0", "pi", "pi + acos(g/(R*Omega**2))", "pi - acos(g/(R*Omega**2))"],
    "frequencies": ["g/R - Omega**2", "Omega**2 - g**2/(R**2*Omega**2)"],
    "hamiltonian": "p_alpha**2/(2*m*R**2) + m*g*R*cos(alpha) - m*R**2*Omega**2*sin(alpha)**2/2",
}

POLAR_MAP = {"r": "sqrt(x**2 + y**2)", "phi": "atan2(x, -y)"}
POLAR = {
    "kinetic": "m*(r_dot**2 + r**2*phi_dot**2)/2",
    "potential": "-m*g*r*cos(phi)",
    "lagrangian": "m*(r_dot**2 + r**2*phi_dot**2)/2 + m*g*r*cos(phi)",
    "constraints": {"rod": "r = l"},
    "momenta": {"r": "m*r_dot", "phi": "m*r**2*phi_dot"},
    "generalized_forces": {"r": "m*r*phi_dot**2 + m*g*cos(phi)", "phi": "-m*g*r*sin(phi)"},
    "equations": {"r": "m*r_ddot - m*r*phi_dot**2 - m*g*cos(phi) = lambda_rod*r",
                  "phi": "m*r**2*phi_ddot + 2*m*r*r_dot*phi_dot + m*g*r*sin(phi)"},
    "accelerations": {"r": "0", "phi": "-g*sin(phi)/l"},
    "multipliers": {"rod": "-m*(phi_dot**2 + g*cos(phi)/l)"},
    "constraint_forces": {"rod": "m*l*Abs(phi_dot**2 + g*cos(phi)/l)"},
}

#: the support's displacement from its driven position, u = X − A cos(wt): the constraint is u = 0
DRIVEN_MAP = {"u": "X - A*cos(w*t)"}
DRIVEN = {
    "constraints": {"drive": "u = 0"},
    "momenta": {"u": "(M + m)*(u_dot - A*w*sin(w*t)) + m*l*theta_dot*cos(theta)",
                "theta": "m*l**2*theta_dot + m*l*cos(theta)*(u_dot - A*w*sin(w*t))"},
    "accelerations": {"u": "0", "theta": "(A*w**2*cos(w*t)*cos(theta) - g*sin(theta))/l"},
    "multipliers": {"drive": "-A*w**2*cos(w*t)*(M + m*sin(theta)**2) - m*g*sin(theta)*cos(theta) - m*l*theta_dot**2*sin(theta)"},
}

#: the Kepler problem seen from axes turning at the rate k (a parameter of the key, used as a rate): β = θ − k t;
#: K = H − k p_β, the generating function's rate (by hand: L' = m(ṙ² + r²(β̇ + k)²)/2 + k/r)
ROTATING_MAP = {"beta": "theta - k*t"}
ROTATING = {
    "kinetic": "m*(r_dot**2 + r**2*(beta_dot + k)**2)/2",
    "momenta": {"r": "m*r_dot", "beta": "m*r**2*(beta_dot + k)"},
    "generalized_forces": {"r": "m*r*(beta_dot + k)**2 - k/r**2", "beta": "0"},
    "equations": {"r": "m*r_ddot - m*r*(beta_dot + k)**2 + k/r**2", "beta": "m*r**2*beta_ddot + 2*m*r*r_dot*(beta_dot + k)"},
    "accelerations": {"r": "r*(beta_dot + k)**2 - k/(m*r**2)", "beta": "-2*r_dot*(beta_dot + k)/r"},
    "hamiltonian": "p_r**2/(2*m) + p_beta**2/(2*m*r**2) - k*p_beta - k/r",
    "conserved": {"p_theta": "m*r**2*(beta_dot + k)"},
}


@cache
def key(name: str) -> tuple:
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    return problem, derive(problem)


def graded(name: str, mapping: dict[str, str], steps: dict[str, Any]) -> dict[str, Any]:
    problem, derivation = key(name)
    text = json.dumps({"student": "s", "coordinates_map": mapping, "steps": steps})
    result = grade(derivation, Grading({s: 1.0 for s in ALL}), read_text(text, problem, "s.yaml"))
    return {s.step: s for s in result.steps if s.step in steps}


@pytest.mark.parametrize(("name", "mapping", "steps"), [("bead_on_rotating_hoop", HOOP_MAP, HOOP),
                                                        ("pendulum_cartesian", POLAR_MAP, POLAR),
                                                        ("moving_support", DRIVEN_MAP, DRIVEN),
                                                        ("central_force", ROTATING_MAP, ROTATING)],
                         ids=["shifted-angle", "polar", "with-time", "rotating-axes"])
def test_correct_answers_in_other_coordinates_earn_every_point(name: str, mapping: dict, steps: dict) -> None:
    result = graded(name, mapping, steps)
    assert set(result) == set(steps)
    lost = {s: (g.status, g.message) for s, g in result.items() if g.points != g.max_points}
    assert not lost


@pytest.mark.parametrize("rod", ["r = l", "r**2 - l**2", "(r - l)*(r + l + 5)", "sin(r - l)", "r*r_dot", "r_dot"])
def test_a_constraint_with_the_same_surface_in_other_coordinates_is_correct(rod: str) -> None:
    result = graded("pendulum_cartesian", POLAR_MAP, {"constraints": {"rod": rod}})
    assert result["constraints"].status == "correct", result["constraints"].message


@pytest.mark.parametrize(("name", "mapping", "steps", "step", "change", "mistake"), [
    ("bead_on_rotating_hoop", HOOP_MAP, HOOP, "accelerations",
     {"alpha": "-sin(alpha)*(Omega**2*cos(alpha) + g/R)", "phi": "0"}, "sign_error"),
    ("bead_on_rotating_hoop", HOOP_MAP, HOOP, "potential", "-m*g*R*cos(alpha)", "wrong_potential_sign"),
    ("bead_on_rotating_hoop", HOOP_MAP, HOOP, "kinetic", "m*R**2*alpha_dot**2/2", "missing_kinetic_term"),
    ("pendulum_cartesian", POLAR_MAP, POLAR, "momenta", {"r": "m*r_dot", "phi": "2*m*r**2*phi_dot"}, "missing_factor"),
    ("pendulum_cartesian", POLAR_MAP, POLAR, "equations",
     {"r": "m*r_ddot - m*g*cos(phi) = lambda_rod*r", "phi": "m*r**2*phi_ddot + m*g*r*sin(phi)"},
     "missing_velocity_squared_terms"),
    ("bead_on_rotating_hoop", HOOP_MAP, HOOP, "equilibria", ["0", "pi", "acos(g/(R*Omega**2))"], None),
    ("central_force", ROTATING_MAP, ROTATING, "hamiltonian", "p_r**2/(2*m) + p_beta**2/(2*m*r**2) - k/r", None),
    ("central_force", {"rho": "r/2", "beta": "theta + 1"}, {}, "kinetic", "2*m*rho_dot**2", "missing_kinetic_term"),
    ("central_force", ROTATING_MAP, ROTATING, "accelerations",
     {"r": "r*beta_dot**2 - k/(m*r**2)", "beta": "-2*r_dot*beta_dot/r"}, None),
    # each vanishes on the rod's surface, which was enough: a double zero (its gradient vanishes there), the
    # square of the velocity form, and, below, the other constraint of the incline written under this one's name
    ("pendulum_cartesian", POLAR_MAP, POLAR, "constraints", {"rod": "(r - l)**2"}, None),
    ("pendulum_cartesian", POLAR_MAP, POLAR, "constraints", {"rod": "r_dot**2"}, None),
    ("incline_pulley", {"u": "x"}, {}, "constraints",
     {"plane": "u*cos(alpha) - y*sin(alpha) - z", "string": "u*cos(alpha) - y*sin(alpha) - z"}, None),
])
def test_a_wrong_step_in_other_coordinates_is_found(name: str, mapping: dict, steps: dict, step: str, change: Any,
                                                    mistake: str | None) -> None:
    result = graded(name, mapping, {**steps, step: change})
    assert result[step].status == "incorrect", result[step].message
    assert result[step].mistake == mistake, result[step].message
    assert result[step].points < result[step].max_points
    if mistake == "missing_kinetic_term" and name == "central_force":  # named with the student's variables
        assert "2*beta_dot**2*m*rho**2 (in the submission's coordinates) is missing" in result[step].message


def _lagranges_method_equations(potential_sign: int) -> dict[str, str]:
    """The hoop's equations in (α, φ) by SymPy's LagrangesMethod from L = T − s·m g R cos α (SymPy writes
    E + λ a = 0, lagsolve E = λ a: λ_sympy = −λ)."""
    t = dynamicsymbols._t
    alpha, phi = dynamicsymbols("alpha phi")
    m, R, g, Omega = sympy.symbols("m R g Omega")
    L = m * R**2 * (alpha.diff(t) ** 2 + sympy.sin(alpha) ** 2 * phi.diff(t) ** 2) / 2 \
        - potential_sign * m * g * R * sympy.cos(alpha)
    method = LagrangesMethod(L, [alpha, phi], hol_coneqs=[phi - Omega * t])
    equations = method.form_lagranges_equations()
    lam = sympy.Symbol("lambda_drive")
    names = {}
    for q, name in ((alpha, "alpha"), (phi, "phi")):
        names.update({q.diff(t, 2): sympy.Symbol(f"{name}_ddot"), q.diff(t): sympy.Symbol(f"{name}_dot"),
                      q: sympy.Symbol(name)})
    out = {}
    for name, e in zip(("alpha", "phi"), equations, strict=True):
        e = e.subs(method.lam_vec[0], -lam)
        for old, new in names.items():  # second derivatives first
            e = e.subs(old, new)
        out[name] = sympy.sstr(e)
    return out


def test_follow_through_in_other_coordinates_against_lagranges_method() -> None:
    """V with the wrong sign (in α): the equations LagrangesMethod derives from the student's L follow."""
    assert _lagranges_method_equations(1)  # the right L gives the key's equations: checked below
    right = graded("bead_on_rotating_hoop", HOOP_MAP, {"equations": _lagranges_method_equations(1)})
    assert right["equations"].status == "correct", right["equations"].message
    wrong_v = "-m*g*R*cos(alpha)"
    steps = {"potential": wrong_v, "kinetic": HOOP["kinetic"], "equations": _lagranges_method_equations(-1),
             "accelerations": {"alpha": "sin(alpha)*(Omega**2*cos(alpha) - g/R)", "phi": "0"}}
    result = graded("bead_on_rotating_hoop", HOOP_MAP, steps)
    assert result["potential"].mistake == "wrong_potential_sign"
    assert result["equations"].status == "follows", result["equations"].message
    assert result["accelerations"].status == "follows", result["accelerations"].message


@pytest.mark.parametrize(("mapping", "words"), [
    ({"alpha": "theta_dot"}, "velocities"),
    ({"alpha": "theta + phi", "beta": "2*theta + 2*phi"}, "singular"),
    ({"alpha": "theta", "beta": "theta"}, "3 coordinates"),
    ({"m": "theta"}, "already a name"),
    ({"alpha": "__import__('os')"}, ""),
    ({"alpha": "Omega*t"}, "none of the key's coordinates"),
    ({"alpha": "theta - q"}, ""),
    ("theta - pi", "expected a mapping"),
])
def test_a_bad_map_is_a_per_submission_error(mapping: Any, words: str) -> None:
    problem, _ = key("bead_on_rotating_hoop")
    text = json.dumps({"student": "s", "coordinates_map": mapping, "steps": {"potential": "0"}})
    with pytest.raises(SpecError) as raised:
        read_text(text, problem, "s.yaml")
    assert words in str(raised.value)


def test_a_bad_map_leaves_the_class_graded(tmp_path: Path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("student: bad\ncoordinates_map: {alpha: theta_dot}\nsteps: {potential: '0'}\n")
    good = tmp_path / "good.yaml"
    good.write_text(f"student: good\ncoordinates_map: {{alpha: theta - pi}}\nsteps: {{potential: '{HOOP['potential']}'}}\n")
    grades = grade_files(ROOT / "problems" / "bead_on_rotating_hoop.yaml", [bad, good])
    assert grades.grades[0].error and "coordinates_map" in grades.grades[0].error
    [potential] = [s for s in grades.grades[1].steps if s.step == "potential"]
    assert potential.status == "correct"


def test_a_map_with_time_against_the_lagrangian_written_in_it() -> None:
    """u = X − A cos(wt): L' = L(X = u + A cos wt, Ẋ = u̇ − A w sin wt) differentiated here with SymPy; its ∂L'/∂q',
    Lagrange's equations (the drive u = 0 with the key's ψ = u: E_u = λ) and H in the minimal coordinate θ are
    the key's after the change of coordinates, a map with t included."""
    t, m, M, rod, g, A, w = sympy.symbols("t m M l g A w")
    u, th, ud, thd, udd, thdd, lam = sympy.symbols("u theta u_dot theta_dot u_ddot theta_ddot lambda_drive")
    Xd = ud - A * w * sympy.sin(w * t)
    T = M * Xd**2 / 2 + m * ((Xd + rod * sympy.cos(th) * thd) ** 2 + (rod * sympy.sin(th) * thd) ** 2) / 2
    L = T + m * g * rod * sympy.cos(th)
    coordinates = ((u, ud, udd), (th, thd, thdd))

    def rate(e: sympy.Expr) -> sympy.Expr:
        return sympy.diff(e, t) + sum(sympy.diff(e, q) * qd + sympy.diff(e, qd) * qdd for q, qd, qdd in coordinates)

    forces = {str(q): sympy.diff(L, q) for q, _, _ in coordinates}
    equations = {str(q): rate(sympy.diff(L, qd)) - sympy.diff(L, q) for q, qd, _ in coordinates}
    equations["u"] -= lam
    # H in the minimal coordinate θ (the drive fixes u = 0): H = p_θ θ̇ − L(u = 0, u̇ = 0), θ̇ from p_θ
    pth = sympy.Symbol("p_theta")
    reduced = L.subs({u: 0, ud: 0})
    [velocity] = sympy.solve(sympy.diff(reduced, thd) - pth, thd)
    H = sympy.simplify((pth * thd - reduced).subs(thd, velocity))
    steps = {"generalized_forces": {k: sympy.sstr(v) for k, v in forces.items()},
             "equations": {k: sympy.sstr(v) for k, v in equations.items()}, "hamiltonian": sympy.sstr(H)}
    result = graded("moving_support", DRIVEN_MAP, steps)
    for step in steps:
        assert result[step].status == "correct", (step, result[step].message)



def test_a_students_own_equilibria_known_by_a_condition_in_their_coordinates() -> None:
    """A potential whose equilibria have no closed form (their V_eff' = 0 is only a condition), in α = θ − π: the
    list step is graded (incorrect), not a crash; a bead key (its equilibria f'(x) = 0, a condition) in u = x + 1."""
    result = graded("bead_on_rotating_hoop", HOOP_MAP, {"kinetic": HOOP["kinetic"], "potential": "alpha",
                                                        "equilibria": ["0"]})
    assert result["equilibria"].status == "incorrect"
    bead = graded("bead", {"u": "x + 1"}, {"equilibria": ["1"], "potential": "m*g*f(u - 1)"})
    assert bead["potential"].status == "correct"
    assert bead["equilibria"].status == "incorrect", bead["equilibria"].message


def test_a_derivative_with_respect_to_a_mapped_coordinate_is_unreadable_not_a_crash() -> None:
    problem, derivation = key("bead")
    text = json.dumps({"coordinates_map": {"u": "x + 1"},
                       "steps": {"kinetic": "m*u_dot**2*(1 + Derivative(f(u), u)**2)/2",
                                 "hamiltonian": "p_u**2/(2*m*(1 + Derivative(f(u), u)**2))"}})
    submission = read_text(text, problem, "s.yaml")
    for step in ("kinetic", "hamiltonian"):
        issue = submission.steps[step].issue
        assert issue is not None and "cannot be written in the key's coordinates" in issue.message
    result = grade(derivation, Grading({"kinetic": 1.0, "hamiltonian": 1.0}), submission)
    assert {str(s.status) for s in result.steps} == {"unreadable"}
