"""Normal forces of friction in closed form (lagsolve.mechanics.solution.normal), each checked by an independent route:
Newton's laws written out by hand and solved numerically, or the textbook result."""

from __future__ import annotations

import functools
import math
import random

import numpy as np
import pytest
import sympy

from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem
from lagsolve.render.report import result_dict
from mechanics_support import PROBLEMS, derived_file, derived_text, names

#: a bead on a rough vertical circle written in Cartesian x, y: no coordinate is eliminated, so the
#: decoupling is seen only with the velocity constraint x x_dot + y y_dot = 0 used
CIRCLE = """
name: Bead on a rough circle in Cartesian coordinates
parameters: {m: mass, g: gravity, R: radius, mu: friction coefficient}
coordinates: [x, y]
particles:
  bead: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  wire: {holonomic: x**2 + y**2 - R**2}
friction:
  rub: {coefficient: mu, on: bead, normal: [wire], sliding: [x, y]}
"""

#: the two-mass ladder with a rough floor AND a rough wall: two coupled contacts
LADDER_TWO_ROUGH = """
name: Ladder rough at both ends
parameters: {m1: foot mass, m2: top mass, g: gravity, L: length, mu: floor friction, nu: wall friction}
coordinates: [x1, y1, x2, y2]
particles:
  foot: {mass: m1, position: [x1, y1]}
  top: {mass: m2, position: [x2, y2]}
gravity: [0, -g]
constraints:
  floor: {holonomic: y1, on: foot}
  wall: {holonomic: x2, on: top}
  rod: {holonomic: (x1 - x2)**2 + (y1 - y2)**2 - L**2, on: [foot, top]}
friction:
  rough_floor: {coefficient: mu, on: foot, normal: [floor], sliding: [x1]}
  rough_wall: {coefficient: nu, on: top, normal: [wall], sliding: [y2]}
"""


def _normal_symbols(text: str) -> set[str]:
    return {s for s in sympy.sympify(text).free_symbols if str(s).startswith("N_")} if text else set()


def test_incline_in_cartesian_coordinates_is_decoupled_on_the_surface():
    """Off the plane the multiplier seems to depend on the friction; on it (y = -x tan(alpha)) it does not:
    N = m g |cos(alpha)| and the accelerations are Newton's s_ddot = g (sin(alpha) - mu cos(alpha) sign)
    projected on x and y, with no N left in them."""
    derivation = derived_file("incline_cartesian")
    s = names(derivation.problem)
    m, g, alpha, mu, xd = (s[k] for k in ("m", "g", "alpha", "mu", "x_dot"))
    (contact,) = derivation.friction
    assert contact.case.startswith("decoupled")
    assert sympy.simplify(contact.normal_force - m * g * sympy.Abs(sympy.cos(alpha))) == 0
    s_ddot = g * (sympy.sin(alpha) - mu * sympy.cos(alpha) * sympy.sign(xd))
    for value in (1.3, -0.7):  # sliding down the slope, and up it
        point = {m: 1.7, g: 9.81, alpha: 0.4, mu: 0.3, xd: value}
        for name, expected in (("x", s_ddot * sympy.cos(alpha)), ("y", -s_ddot * sympy.sin(alpha))):
            got = derivation.accelerations[name]
            assert not any(str(v).startswith("N_") for v in got.free_symbols)
            assert float(got.xreplace(point)) == pytest.approx(float(expected.xreplace(point)), rel=1e-12)


def test_bead_on_a_rough_circle_in_cartesian_coordinates():
    """Newton along and across the wire: N = m |v^2/R + g cos(theta)| (theta from the downward vertical),
    tangential acceleration -g sin(theta) - mu N sign/m, centripetal v^2/R; the derived x_ddot, y_ddot agree and
    contain no N."""
    derivation = derived_text(CIRCLE)
    s = names(derivation.problem)
    (contact,) = derivation.friction
    assert contact.case.startswith("decoupled")
    for name in ("x", "y"):
        assert not any(str(v).startswith("N_") for v in derivation.accelerations[name].free_symbols)
    rng = random.Random(3)
    for _ in range(8):
        m, g, R, mu = rng.uniform(0.5, 2), rng.uniform(5, 10), rng.uniform(0.5, 2), rng.uniform(0.1, 0.6)
        theta, omega = rng.uniform(-math.pi, math.pi), rng.choice([-1, 1]) * rng.uniform(0.3, 3)
        x, y = R * math.sin(theta), -R * math.cos(theta)
        xd, yd = R * math.cos(theta) * omega, R * math.sin(theta) * omega
        v2 = (R * omega) ** 2
        normal = m * abs(v2 / R + g * math.cos(theta))
        a_t = -g * math.sin(theta) - mu * normal * math.copysign(1, omega) / m
        t_hat, r_hat = np.array([math.cos(theta), math.sin(theta)]), np.array([x, y]) / R
        expected = a_t * t_hat - v2 / R * r_hat
        point = {s["m"]: m, s["g"]: g, s["R"]: R, s["mu"]: mu, s["x"]: x, s["y"]: y, s["x_dot"]: xd, s["y_dot"]: yd}
        assert float(contact.normal_force.xreplace(point)) == pytest.approx(normal, rel=1e-9)
        got = [float(derivation.accelerations[n].xreplace(point)) for n in ("x", "y")]
        assert got == pytest.approx(list(expected), rel=1e-9, abs=1e-9)


def _ladder_by_newton(m1: float, m2: float, g: float, mu: float, x1: float, y2: float, x1d: float,
                      y2d: float) -> tuple[np.ndarray, float]:
    """Newton's laws for the two-mass ladder with a rough floor, solved as a linear system in
    (x1_ddot, y2_ddot, N, T, W) for the sign of the floor force that makes N >= 0: the floor pushes up
    (N > 0), friction is -mu N sign(x1_dot), the rod pushes the foot with T (x1, -y2)/L and the top with
    the opposite force, the wall pushes the top with W; the rod keeps x1^2 + y2^2 constant."""
    L = math.hypot(x1, y2)
    s = math.copysign(1, x1d)
    # unknowns: x1dd, y2dd, N, T, W
    A = np.array([
        [m1, 0, mu * s, -x1 / L, 0],          # foot, x: m1 x1dd = -mu N s + T x1/L
        [0, 0, 1, -y2 / L, 0],                # foot, y: 0 = N - m1 g - T y2/L
        [0, 0, 0, -x1 / L, 1],                # top, x: 0 = W - T x1/L
        [0, m2, 0, -y2 / L, 0],               # top, y: m2 y2dd = -m2 g + T y2/L
        [x1, y2, 0, 0, 0],                    # rod: x1 x1dd + y2 y2dd = -(x1d^2 + y2d^2)
    ], dtype=float)
    rhs = np.array([0, m1 * g, 0, -m2 * g, -(x1d**2 + y2d**2)])
    sol = np.linalg.solve(A, rhs)
    return sol[:2], sol[2]


def test_ladder_with_a_rough_floor_matches_newton():
    """The coupled contact: N = |a|/(1 - b sign(a)) substituted in x1_ddot and y2_ddot, which equal
    Newton's laws solved by hand at random states (with N > 0 there), and N equals Newton's floor force."""
    derivation = derived_file("ladder_rough_floor")
    s = names(derivation.problem)
    (contact,) = derivation.friction
    assert contact.case.startswith("coupled, one contact") and contact.valid_while is not None
    assert contact.system is not None and contact.system.has(contact.term.normal)
    for name in ("x1", "y2"):
        assert not derivation.accelerations[name].has(contact.term.normal)
    rng = random.Random(5)
    checked = 0
    while checked < 8:
        m1, m2, g, mu = rng.uniform(0.5, 2), rng.uniform(0.5, 2), 9.81, rng.uniform(0.1, 0.5)
        angle, rate = rng.uniform(0.4, 1.2), rng.choice([-1, 1]) * rng.uniform(0.1, 1.5)
        x1, y2 = math.cos(angle), math.sin(angle)
        x1d, y2d = -math.sin(angle) * rate, math.cos(angle) * rate
        acc, normal = _ladder_by_newton(m1, m2, g, mu, x1, y2, x1d, y2d)
        if normal <= 0:
            continue  # the floor would pull: not a state of this contact
        point = {s["m1"]: m1, s["m2"]: m2, s["g"]: g, s["L"]: 1.0, s["mu"]: mu, s["x1"]: x1, s["y2"]: y2,
                 s["x1_dot"]: x1d, s["y2_dot"]: y2d, s["y1"]: 0, s["x2"]: 0, s["y1_dot"]: 0, s["x2_dot"]: 0}
        assert float(contact.normal_force.xreplace(point)) == pytest.approx(normal, rel=1e-9)
        got = [float(derivation.accelerations[n].xreplace(point)) for n in ("x1", "y2")]
        assert got == pytest.approx(list(acc), rel=1e-9, abs=1e-12)
        checked += 1


@pytest.mark.slow
def test_several_coupled_contacts_state_the_system_they_solve():
    """Two coupled contacts (floor and wall both rough): each contact gives the equation N = |a + B N| it solves;
    when the signs are not determined N stays a symbol, and either way the equation holds for the value given."""
    derivation = derived_quickly(LADDER_TWO_ROUGH)
    assert len(derivation.friction) == 2
    for contact in derivation.friction:
        assert contact.case.startswith("coupled, ")
        assert isinstance(contact.system, sympy.Eq) and contact.system.lhs == contact.term.normal
        if contact.normal_force == contact.term.normal:
            assert "implicit" in contact.case


#: two coupled contacts whose signs are known: a block on a rough floor and one on a rough wall, linked by a
#: linear constraint (no velocity terms, so each a has the sign of its gravity terms)
CORNER = """
name: Two blocks linked across a corner
parameters: {m1: mass on the floor, m2: mass on the wall, g: gravity, mu: floor friction, nu: wall friction}
coordinates: [x1, y1, x2, y2]
particles:
  a: {mass: m1, position: [x1, y1]}
  b: {mass: m2, position: [x2, y2]}
gravity: [0, -g]
constraints:
  floor: {holonomic: y1, on: a}
  wall: {holonomic: x2, on: b}
  link: {holonomic: x1 + y1 - x2 - y2, on: [a, b]}
friction:
  rough_floor: {coefficient: mu, on: a, normal: [floor], sliding: [x1]}
  rough_wall: {coefficient: nu, on: b, normal: [wall], sliding: [y2]}
"""


def _corner_by_newton(m1: float, m2: float, g: float, mu: float, nu: float, s: float) -> tuple[float, float, float]:
    """Newton for both blocks, unknowns (acceleration, link force l, floor force F, wall force W), friction
    -mu |F| s and -nu |W| s: solved for each sign pattern of F and W, keeping the one that is consistent."""
    found = []
    for sf in (1, -1):
        for sw in (1, -1):
            A = np.array([[m1, -1, mu * s * sf, 0],     # a, x: m1 acc = -mu |F| s + l
                          [0, 1, 1, 0],                 # a, y: 0 = F - m1 g + l
                          [0, -1, 0, 1],                # b, x: 0 = W - l
                          [m2, 1, 0, nu * s * sw]],     # b, y: m2 acc = -m2 g - l - nu |W| s
                         dtype=float)
            acc, _, F, W = np.linalg.solve(A, [0, m1 * g, 0, -m2 * g])
            if sf * F >= 0 and sw * W >= 0:
                found.append((acc, abs(F), abs(W)))
    assert len(found) == 1
    return found[0]


@pytest.mark.slow
def test_several_coupled_contacts_with_known_signs_match_newton():
    """Floor and wall both rough and coupled through the link: the signs of a are known, so both N come in closed
    form, substituted in the accelerations, and they agree with Newton's laws solved by hand."""
    derivation = derive(load_problem_text(CORNER), analysis=False)
    s = names(derivation.problem)
    floor, wall = derivation.friction
    assert floor.case.startswith("coupled, several contacts with the sign")
    assert not derivation.accelerations["x1"].has(floor.term.normal, wall.term.normal)
    rng = random.Random(9)
    for _ in range(8):
        m1, m2, g = rng.uniform(0.5, 2), rng.uniform(0.5, 2), 9.81
        mu, nu, rate = rng.uniform(0.05, 0.5), rng.uniform(0.05, 0.5), rng.choice([-1, 1]) * rng.uniform(0.1, 2)
        acc, n_floor, n_wall = _corner_by_newton(m1, m2, g, mu, nu, math.copysign(1, rate))
        point = {s["m1"]: m1, s["m2"]: m2, s["g"]: g, s["mu"]: mu, s["nu"]: nu, s["x1_dot"]: rate, s["y2_dot"]: rate}
        assert float(floor.normal_force.xreplace(point)) == pytest.approx(n_floor, rel=1e-9)
        assert float(wall.normal_force.xreplace(point)) == pytest.approx(n_wall, rel=1e-9)
        assert float(derivation.accelerations["x1"].xreplace(point)) == pytest.approx(acc, rel=1e-9)


def load_problem_text(text: str):  # noqa: ANN201 - a Problem
    from lagsolve.problem.load import load_text

    return load_text(text)


@functools.cache
def derived_quickly(text: str):  # noqa: ANN201 - a Derivation
    """``derive`` without the analysis, once per session."""
    return derive(load_problem_text(text), analysis=False)


def _with_friction() -> list[str]:
    return sorted(p.stem for p in PROBLEMS.glob("*.yaml") if load_problem(p).friction)


@pytest.mark.parametrize("stem", _with_friction())
def test_no_json_result_keeps_a_normal_force_that_has_a_closed_form(stem):
    """Over every shipped problem with friction (a problem without friction has no N_*): the results in the JSON
    (accelerations, multipliers, forces of constraint, the friction forces) contain no N_<contact> whose
    closed form is known."""
    derivation = derive(load_problem(PROBLEMS / f"{stem}.yaml"), analysis=False)
    result = result_dict(derivation)
    closed = {f.term.name for f in derivation.friction if f.normal_force != f.term.normal}
    unsolved = {f"N_{name}" for name in closed}
    texts = [*(result["accelerations"] or {}).values(), *(result["multipliers"] or {}).values()]
    for force in (result["constraint_forces"] or {}).values():
        texts += [*(force.get("vector") or []), force.get("magnitude") or ""]
    for contact in result["friction"].values():
        texts += [*contact["force"], *contact["generalized"].values(), contact["normal_force"]]
    for text in texts:
        assert not _normal_symbols(text) & {str(n) for n in unsolved}, text


@pytest.mark.slow
def test_an_implicit_normal_force_is_shown_by_the_equation_it_solves():
    """Where N stays implicit, the summary and the reports write N = |a + B N| (the system), not N = N."""
    from lagsolve.render.report import summary

    derivation = derived_quickly(LADDER_TWO_ROUGH)
    text = summary(derivation)
    for contact in derivation.friction:
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(f"friction {contact.term.name}:"))
        assert "sqrt(" in line or "Abs(" in line or "|" in line, line
