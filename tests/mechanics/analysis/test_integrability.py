"""Velocity constraints classified (``lagsolve.mechanics.analysis.integrability``): exact forms integrated,
integrating factors found, Frobenius' test proving a constraint nonholonomic."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.analysis.integrability import classify_all
from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import TUBE, exactly_equal, names, problem_file, problem_text

FACTOR = """
name: A velocity constraint that needs an integrating factor
parameters: {m: mass}
coordinates: [x, y]
particles: {p: {mass: m, position: [x, y]}}
constraints:
  ray: {nonholonomic: x*y_dot - y*x_dot}
"""

NO_SIMPLE_FACTOR = """
name: Integrable, but only with the factor exp(y)
parameters: {m: mass}
coordinates: [x, y]
particles: {p: {mass: m, position: [x, y]}}
constraints:
  odd: {nonholonomic: x_dot + (x + y)*y_dot}
"""

CLASH = """
name: A parameter already called theta0
parameters: {m: mass, g: gravity, theta0: an angle}
coordinates: [r, theta]
particles: {p: {mass: m, position: [r*cos(theta + theta0), r*sin(theta + theta0)]}}
constraints:
  lock: {nonholonomic: theta_dot}
"""


def classes(problem):
    model = build_model(problem)
    terms = tuple(constraint_terms(c, model) for c in problem.constraints)
    return classify_all(terms, model, problem.constraints, set(problem.symbols))


def test_theta_dot_integrates_to_theta0():
    """theta_dot = 0 is exact: psi = theta, so theta = theta0 with a new constant theta0."""
    problem = problem_text(TUBE)
    tilt, _ = classes(problem)
    theta = names(problem)["theta"]
    assert tilt.kind == "integrable" and tilt.exact
    assert tilt.integral == theta
    assert tilt.solved == (theta, tilt.constant) and tilt.constant.name == "theta0"
    assert exactly_equal(tilt.holonomic.expression, theta - tilt.constant)


def test_driven_rate_integrates_to_omega_t_plus_phi0():
    """phi_dot - Omega = 0 is exact in (q, t): psi = phi - Omega t, so phi = Omega t + phi0."""
    problem = problem_text(TUBE)
    _, spin = classes(problem)
    s = names(problem)
    assert spin.kind == "integrable"
    assert exactly_equal(spin.integral, s["phi"] - s["Omega"] * s["t"])
    assert exactly_equal(spin.solved[1], s["Omega"] * s["t"] + spin.constant)
    assert spin.holonomic.offset == -s["Omega"]


def test_knife_edge_fails_frobenius():
    """-sin(theta) dx + cos(theta) dy has (omega ^ d omega)_{x y theta} = -1: nonholonomic."""
    problem = problem_file("knife_edge")
    (skate,) = classes(problem)
    s = names(problem)
    assert skate.kind == "nonholonomic"
    assert skate.witness == ((s["x"], s["y"], s["theta"]), -1)
    assert skate.holonomic is None


def test_integrating_factor_is_found():
    """x dy - y dx is not exact, but 1/y^2 times it is d(-x/y): integrable, no coordinate solved."""
    problem = problem_text(FACTOR)
    (ray,) = classes(problem)
    x, y = names(problem)["x"], names(problem)["y"]
    assert ray.kind == "integrable" and not ray.exact
    scaled = [sympy.cancel(ray.factor * w) for w in ray.form]
    assert exactly_equal(sympy.diff(ray.integral, x), scaled[0])
    assert exactly_equal(sympy.diff(ray.integral, y), scaled[1])
    assert ray.solved is None and ray.constant.name == "C_ray"


def test_integrable_without_a_simple_factor_stays_a_velocity_constraint():
    """dx + (x + y) dy passes Frobenius but needs exp(y): reported unresolved, not claimed either way."""
    (odd,) = classes(problem_text(NO_SIMPLE_FACTOR))
    assert odd.kind == "unresolved"
    assert "integrating factor" in odd.note and odd.holonomic is None


def test_new_constant_never_shadows_a_declared_name():
    """With a parameter theta0 declared, the constant of integration is named theta0_1."""
    (lock,) = classes(problem_text(CLASH))
    assert lock.constant.name == "theta0_1"


def test_holonomic_constraints_are_left_as_they_are():
    """A constraint given as holonomic is classified holonomic, with nothing integrated."""
    (wire,) = classes(problem_file("bead"))
    assert wire.kind == "holonomic" and wire.integral is None
