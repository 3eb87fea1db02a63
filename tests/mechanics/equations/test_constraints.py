"""Constraint coefficients a, b and the acceleration-level beta
(``lagsolve.mechanics.equations.constraints``), checked against hand results and against
differentiating the constraint along concrete trajectories."""

from __future__ import annotations

import pytest
import sympy

from lagsolve.mechanics.equations.constraints import constraint_terms, velocity_form
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import (
    TUBE,
    assert_same,
    exactly_equal,
    names,
    problem_file,
    problem_text,
)

DRIVEN = """
name: Driven and shaken particle
parameters: {m: mass, Omega: rate, A: amplitude, w: frequency, v0: speed}
coordinates: [x, y, phi]
particles:
  p: {mass: m, position: [x, y]}
kinetic: phi_dot**2/2
constraints:
  drive: {holonomic: phi - Omega*t}
  shake: {holonomic: x - A*cos(w*t)}
  circle: {holonomic: x**2 + y**2 - A**2*(1 + t**2)}
  push: {nonholonomic: y_dot*cos(phi) - v0*cos(w*t)}
  roll: {nonholonomic: x*y_dot - t*phi_dot + sin(w*t)*x_dot}
"""


def terms_of(problem):
    model = build_model(problem)
    return model, {c.name: constraint_terms(c, model) for c in problem.constraints}


def test_holonomic_wire_coefficients():
    """The wire y - f(x) has a = (-f'(x), 1), b = 0 and beta = f''(x) x_dot^2."""
    problem = problem_file("bead")
    model, terms = terms_of(problem)
    s = names(problem)
    x, xd, f = s["x"], s["x_dot"], s["f"]
    wire = terms["wire"]
    assert wire.kind == "holonomic"
    assert exactly_equal(wire.coefficients[0], -sympy.Derivative(f(x), x))
    assert wire.coefficients[1] == 1
    assert wire.offset == 0
    assert exactly_equal(wire.acceleration_rhs, sympy.Derivative(f(x), (x, 2)) * xd**2)


def test_multiplier_symbol_is_named_after_the_constraint():
    """Each constraint gets a real multiplier symbol lambda_<name>."""
    _, terms = terms_of(problem_file("bead"))
    lam = terms["wire"].multiplier
    assert lam.name == "lambda_wire"
    assert lam.is_real


def test_string_constraint_with_two_particles():
    """The string r - z - l has a = (1, 0, -1), b = 0, beta = 0 and acts on both masses."""
    _, terms = terms_of(problem_file("hole_table"))
    string = terms["string"]
    assert tuple(string.coefficients) == (1, 0, -1)
    assert string.offset == 0
    assert string.acceleration_rhs == 0
    assert string.on == ("m1", "m2")


def test_knife_edge_coefficients():
    """The skate -sin(th) x_dot + cos(th) y_dot has a = (-sin, cos, 0), b = 0 and
    beta = th_dot (x_dot cos(th) + y_dot sin(th))."""
    problem = problem_file("knife_edge")
    _, terms = terms_of(problem)
    s = names(problem)
    th, xd, yd, thd = s["theta"], s["x_dot"], s["y_dot"], s["theta_dot"]
    skate = terms["skate"]
    assert skate.kind == "nonholonomic"
    expected = (-sympy.sin(th), sympy.cos(th), 0)
    assert all(exactly_equal(a, b) for a, b in zip(skate.coefficients, expected, strict=True))
    assert skate.offset == 0
    assert exactly_equal(skate.acceleration_rhs,
                         thd * (xd * sympy.cos(th) + yd * sympy.sin(th)))


def test_tube_velocity_constraints():
    """theta_dot = 0 and phi_dot - Omega = 0 give a = (0,1,0), (0,0,1), b = 0, -Omega, beta = 0."""
    problem = problem_text(TUBE)
    _, terms = terms_of(problem)
    omega = names(problem)["Omega"]
    assert tuple(terms["tilt"].coefficients) == (0, 1, 0)
    assert terms["tilt"].offset == 0
    assert tuple(terms["spin"].coefficients) == (0, 0, 1)
    assert exactly_equal(terms["spin"].offset, -omega)
    assert terms["tilt"].acceleration_rhs == 0
    assert terms["spin"].acceleration_rhs == 0


def test_on_defaults_to_the_only_particle():
    """A constraint without 'on' in a one-particle problem acts on that particle."""
    _, terms = terms_of(problem_text(TUBE))
    assert terms["tilt"].on == ("bead",)


def test_time_dependent_holonomic_constraints():
    """phi - Omega t has b = -Omega, beta = 0; x - A cos(w t) has b = A w sin(w t),
    beta = -A w^2 cos(w t)."""
    problem = problem_text(DRIVEN)
    _, terms = terms_of(problem)
    s = names(problem)
    omega, amp, w, t = s["Omega"], s["A"], s["w"], s["t"]
    drive, shake = terms["drive"], terms["shake"]
    assert tuple(drive.coefficients) == (0, 0, 1)
    assert exactly_equal(drive.offset, -omega)
    assert drive.acceleration_rhs == 0
    assert tuple(shake.coefficients) == (1, 0, 0)
    assert exactly_equal(shake.offset, amp * w * sympy.sin(w * t))
    assert exactly_equal(shake.acceleration_rhs, -amp * w**2 * sympy.cos(w * t))


def test_nonholonomic_time_dependent_offset():
    """y_dot cos(phi) - v0 cos(w t) has a = (0, cos(phi), 0), b = -v0 cos(w t)."""
    problem = problem_text(DRIVEN)
    _, terms = terms_of(problem)
    s = names(problem)
    phi, v0, w, t = s["phi"], s["v0"], s["w"], s["t"]
    push = terms["push"]
    assert exactly_equal(push.coefficients[1], sympy.cos(phi))
    assert push.coefficients[0] == 0 and push.coefficients[2] == 0
    assert exactly_equal(push.offset, -v0 * sympy.cos(w * t))


def _trajectory(problem, model):
    """Concrete, arbitrary (not admissible) paths q(t) and their derivatives."""
    t = problem.time
    paths = [sympy.sin(t) + t / 3, sympy.cos(2 * t) - t**2 / 4, sympy.exp(t / 3)]
    along = {q: p for q, p in zip(model.coordinates, paths, strict=True)}
    along |= {v: sympy.diff(p, t) for v, p in zip(model.velocities, paths, strict=True)}
    along |= {a: sympy.diff(p, t, 2) for a, p in zip(model.accelerations, paths, strict=True)}
    return along


@pytest.mark.parametrize("name", ["drive", "shake", "circle"])
def test_holonomic_beta_from_second_derivative(name):
    """Along any path, d^2 psi/dt^2 = sum_i a_i q_ddot_i - beta and
    d psi/dt = sum_i a_i q_dot_i + b."""
    problem = problem_text(DRIVEN)
    model, terms = terms_of(problem)
    c = terms[name]
    t = problem.time
    along = _trajectory(problem, model)
    psi = c.expression.xreplace(along)
    a_qdd = sum(a * qdd for a, qdd in zip(c.coefficients, model.accelerations, strict=True))
    assert_same(sympy.diff(psi, t, 2), (a_qdd - c.acceleration_rhs).xreplace(along), seed=5)
    assert_same(sympy.diff(psi, t), velocity_form(c, model).xreplace(along), seed=6)


@pytest.mark.parametrize("name", ["push", "roll"])
def test_nonholonomic_beta_from_first_derivative(name):
    """Along any path, d/dt (sum a_i q_dot_i + b) = sum a_i q_ddot_i - beta."""
    problem = problem_text(DRIVEN)
    model, terms = terms_of(problem)
    c = terms[name]
    t = problem.time
    along = _trajectory(problem, model)
    g = c.expression.xreplace(along)
    a_qdd = sum(a * qdd for a, qdd in zip(c.coefficients, model.accelerations, strict=True))
    assert_same(sympy.diff(g, t), (a_qdd - c.acceleration_rhs).xreplace(along), seed=7)


def test_knife_edge_beta_along_a_path():
    """For the skate, d/dt of the constraint along a path equals a . q_ddot - beta."""
    problem = problem_file("knife_edge")
    model, terms = terms_of(problem)
    c = terms["skate"]
    along = _trajectory(problem, model)
    a_qdd = sum(a * qdd for a, qdd in zip(c.coefficients, model.accelerations, strict=True))
    assert_same(sympy.diff(c.expression.xreplace(along), problem.time),
                (a_qdd - c.acceleration_rhs).xreplace(along), seed=8)


def test_velocity_form_of_a_nonholonomic_constraint_is_as_written():
    """sum a_i q_dot_i + b rebuilds the velocity constraint exactly as the user wrote it."""
    problem = problem_text(DRIVEN)
    model, terms = terms_of(problem)
    for name in ("push", "roll"):
        assert exactly_equal(velocity_form(terms[name], model), terms[name].expression)


def test_velocity_form_of_the_wire():
    """For y - f(x), sum a_i q_dot_i + b = y_dot - f'(x) x_dot."""
    problem = problem_file("bead")
    model, terms = terms_of(problem)
    s = names(problem)
    x, xd, yd, f = s["x"], s["x_dot"], s["y_dot"], s["f"]
    assert exactly_equal(velocity_form(terms["wire"], model),
                         yd - sympy.Derivative(f(x), x) * xd)
