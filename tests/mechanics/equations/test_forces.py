"""Generalized forces (``lagsolve.mechanics.equations.forces``): physical forces on particles,
generalized forces given directly, and Rayleigh dissipation."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.equations.forces import force_terms, position_jacobian
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import (
    assert_same,
    derived_text,
    exactly_equal,
    names,
    problem_file,
    problem_text,
)

POLAR_FORCED = """
name: Forced particle in polar coordinates
parameters: {m: mass, F0: amplitude, w: frequency, P: push}
coordinates: [r, theta]
particles:
  p: {mass: m, position: [r*cos(theta), r*sin(theta)]}
forces:
  - {on: p, force: [F0*cos(w*t), P*r]}
"""

SPHERICAL_FORCED = """
name: Forced particle in spherical coordinates
parameters: {m: mass, a: a, b: b, c: c}
coordinates: [r, theta, phi]
particles:
  p: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), r*cos(theta)]}
forces:
  - {on: p, force: [a*r_dot, b*theta, c*t]}
"""

DAMPED = """
name: Two coupled dampers and a driven coordinate
parameters: {m: mass, k: stiffness, c: damping, d: coupling damping, Q0: drive}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
potential: k*(x**2 + y**2)/2
dissipation: c*x_dot**2/2 + d*(x_dot - y_dot)**2/2
forces:
  - {coordinate: y, value: Q0*sin(t)}
"""


def test_physical_force_in_polar_coordinates():
    """F = (Fx, Fy) on a particle at (r cos th, r sin th) gives Q_r = F.e_r and Q_th = r F.e_th."""
    problem = problem_text(POLAR_FORCED)
    model = build_model(problem)
    (term,) = force_terms(problem, model)
    s = names(problem)
    f0, w, p, r, th, t = s["F0"], s["w"], s["P"], s["r"], s["theta"], s["t"]
    fx, fy = f0 * sympy.cos(w * t), p * r
    assert exactly_equal(term.generalized[0], fx * sympy.cos(th) + fy * sympy.sin(th))
    assert exactly_equal(term.generalized[1], r * (-fx * sympy.sin(th) + fy * sympy.cos(th)))
    assert term.label == "force on p"


def test_physical_force_power_balance():
    """Q_i = F . dr/dq_i, so sum_i Q_i q_dot_i equals the power F . v at random states."""
    problem = problem_text(SPHERICAL_FORCED)
    model = build_model(problem)
    (term,) = force_terms(problem, model)
    s = names(problem)
    a, b, c, t = s["a"], s["b"], s["c"], s["t"]
    r, th, ph = model.coordinates
    position = [r * sympy.sin(th) * sympy.cos(ph), r * sympy.sin(th) * sympy.sin(ph),
                r * sympy.cos(th)]
    velocity = [sum(sympy.diff(x, q) * v for q, v in zip(model.coordinates, model.velocities,
                                                          strict=True)) for x in position]
    force = [a * model.velocities[0], b * th, c * t]
    power = sum(fi * vi for fi, vi in zip(force, velocity, strict=True))
    generalized_power = sum(qi * v for qi, v in zip(term.generalized, model.velocities,
                                                     strict=True))
    assert_same(generalized_power, power)


def test_physical_force_against_hand_jacobian():
    """Each Q_i of the spherical force equals F . dr/dq_i with the derivatives taken by hand."""
    problem = problem_text(SPHERICAL_FORCED)
    model = build_model(problem)
    (term,) = force_terms(problem, model)
    s = names(problem)
    a, b, c, t, rd = s["a"], s["b"], s["c"], s["t"], s["r_dot"]
    r, th, ph = model.coordinates
    st, ct, sp, cp = sympy.sin(th), sympy.cos(th), sympy.sin(ph), sympy.cos(ph)
    f = sympy.Matrix([a * rd, b * th, c * t])
    e_r = sympy.Matrix([st * cp, st * sp, ct])
    d_th = r * sympy.Matrix([ct * cp, ct * sp, -st])
    d_ph = r * st * sympy.Matrix([-sp, cp, 0])
    for q_i, column in zip(term.generalized, (e_r, d_th, d_ph), strict=True):
        assert exactly_equal(q_i, f.dot(column))


def test_position_jacobian_shape_and_entries():
    """J = dr/dq has one row per component and one column per coordinate."""
    problem = problem_text(POLAR_FORCED)
    model = build_model(problem)
    r, th = model.coordinates
    jac = position_jacobian(problem.particles[0].position, model)
    assert jac.shape == (2, 2)
    expected = sympy.Matrix([[sympy.cos(th), -r * sympy.sin(th)],
                             [sympy.sin(th), r * sympy.cos(th)]])
    assert (jac - expected).applyfunc(sympy.simplify) == sympy.zeros(2, 2)


def test_rayleigh_dissipation_and_direct_generalized_force():
    """R = c x_dot^2/2 + d (x_dot - y_dot)^2/2 gives Q_x = -c x_dot - d (x_dot - y_dot),
    Q_y = d (x_dot - y_dot); a direct force adds to its coordinate only."""
    problem = problem_text(DAMPED)
    model = build_model(problem)
    terms = {t.label: t for t in force_terms(problem, model)}
    s = names(problem)
    c, d, q0, t, xd, yd = s["c"], s["d"], s["Q0"], s["t"], s["x_dot"], s["y_dot"]
    dissipation = terms["dissipation"].generalized
    assert exactly_equal(dissipation[0], -c * xd - d * (xd - yd))
    assert exactly_equal(dissipation[1], d * (xd - yd))
    direct = terms["generalized force on y"].generalized
    assert direct[0] == 0
    assert exactly_equal(direct[1], q0 * sympy.sin(t))


def test_damped_equations_of_motion():
    """With dissipation and a drive, m x_ddot = -k x - c x_dot - d (x_dot - y_dot) and
    m y_ddot = -k y + d (x_dot - y_dot) + Q0 sin(t)."""
    derivation = derived_text(DAMPED)
    s = names(derivation.problem)
    m, k, c, d, q0, t = s["m"], s["k"], s["c"], s["d"], s["Q0"], s["t"]
    x, y, xd, yd = s["x"], s["y"], s["x_dot"], s["y_dot"]
    ax = (-k * x - c * xd - d * (xd - yd)) / m
    ay = (-k * y + d * (xd - yd) + q0 * sympy.sin(t)) / m
    assert exactly_equal(derivation.accelerations["x"], ax)
    assert exactly_equal(derivation.accelerations["y"], ay)
    total = derivation.generalized_forces
    assert exactly_equal(total[1], d * (xd - yd) + q0 * sympy.sin(t))


def test_no_loads_no_terms():
    """A problem without forces or dissipation has no force terms."""
    problem = problem_text(POLAR_FORCED.split("forces:")[0])
    assert force_terms(problem, build_model(problem)) == ()


PUCK = """
name: Puck on a rough table
parameters: {m: mass, g: gravity, mu: friction coefficient}
coordinates: [x, y, z]
particles:
  puck: {mass: m, position: [x, y, z]}
gravity: [0, 0, -g]
constraints:
  table: {holonomic: z}
friction:
  rough: {coefficient: mu, on: puck, normal: [table], sliding: [x, y]}
"""


def test_friction_opposes_the_sliding_velocity():
    """Friction on a puck sliding in x and y is -mu N (x_dot, y_dot, 0)/sqrt(x_dot^2 + y_dot^2)."""
    problem = problem_text(PUCK)
    term = matrix_form(problem).frictions[0]
    s = names(problem)
    mu, xd, yd = s["mu"], s["x_dot"], s["y_dot"]
    speed = sympy.sqrt(xd**2 + yd**2)
    expected = (-mu * term.normal * xd / speed, -mu * term.normal * yd / speed, 0)
    for ours, hand in zip(term.force, expected, strict=True):
        assert exactly_equal(ours, hand)
    for ours, hand in zip(term.generalized, expected, strict=True):
        assert exactly_equal(ours, hand)
    assert term.normal.name == "N_rough" and term.normal.is_nonnegative


def test_friction_along_a_tube_uses_the_sign_of_the_sliding_rate():
    """In the rough rotating tube friction is -mu N sign(r_dot) e_r, so
    Q = (-mu N sign(r_dot), 0, 0)."""
    problem = problem_file("rotating_tube")
    term = matrix_form(problem).frictions[0]
    s = names(problem)
    mu, th, ph, rd = s["mu"], s["theta"], s["phi"], s["r_dot"]
    e_r = (sympy.sin(th) * sympy.cos(ph), sympy.sin(th) * sympy.sin(ph), sympy.cos(th))
    push = -mu * term.normal * sympy.sign(rd)
    for ours, unit in zip(term.force, e_r, strict=True):
        assert exactly_equal(ours, push * unit)
    assert exactly_equal(term.generalized[0], push)
    assert term.generalized[1] == 0 and term.generalized[2] == 0
