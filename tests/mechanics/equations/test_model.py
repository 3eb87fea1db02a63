"""Energies and the total time derivative (``lagsolve.mechanics.equations.model``), checked against
textbook formulas written out by hand."""

from __future__ import annotations

import pytest
import sympy

from lagsolve.mechanics.equations.model import build_model, time_derivative
from mechanics_support import assert_same, exactly_equal, names, problem_file, problem_text

POLAR = """
name: Particle in polar coordinates
parameters: {m: mass}
coordinates: [r, theta]
particles:
  p: {mass: m, position: [r*cos(theta), r*sin(theta)]}
"""

SPHERICAL = """
name: Particle in spherical coordinates
parameters: {m: mass, g: gravity}
coordinates: [r, theta, phi]
particles:
  p: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), r*cos(theta)]}
gravity: [0, 0, -g]
"""

PLANAR_BODY = """
name: Physical pendulum
parameters: {M: mass, Ic: moment of inertia about the centre of mass, d: pivot distance,
             g: gravity}
coordinates: [theta]
bodies:
  rod: {mass: M, position: [d*sin(theta), -d*cos(theta)], inertia: Ic, angular_velocity: theta_dot}
gravity: [0, -g]
"""

FREE_DISK = """
name: Free disk in a plane
parameters: {M: mass, Ic: moment of inertia}
coordinates: [X, Y, phi]
bodies:
  disk: {mass: M, position: [X, Y], inertia: Ic, angular_velocity: phi_dot}
"""

TOP = """
name: Heavy symmetric top
parameters: {M: mass, g: gravity, d: distance from the tip to the centre of mass,
             I1: transverse moment about the centre of mass, I3: axial moment}
coordinates: [theta, phi, psi]
bodies:
  top:
    mass: M
    position: [d*sin(theta)*sin(phi), -d*sin(theta)*cos(phi), d*cos(theta)]
    inertia: [I1, I1, I3]
    angular_velocity:
      - phi_dot*sin(theta)*sin(psi) + theta_dot*cos(psi)
      - phi_dot*sin(theta)*cos(psi) - theta_dot*sin(psi)
      - phi_dot*cos(theta) + psi_dot
gravity: [0, 0, -g]
"""

ASYMMETRIC = """
name: Body turning about a fixed centre of mass
parameters: {A: moment, B: moment, C: moment, w: rate}
coordinates: [a, b]
bodies:
  box: {mass: 1, position: [0, 0, 0], inertia: [A, B, C],
        angular_velocity: [a_dot, b_dot*cos(a), w + b_dot*sin(a)]}
"""

SPRING = """
name: Cart on a tilted spring track
parameters: {m: mass, k: stiffness, g: gravity, alpha: tilt, J: extra inertia}
coordinates: [x, y]
particles:
  cart: {mass: m, position: [x, y]}
gravity: [g*sin(alpha), -g*cos(alpha)]
potential: k*x**2/2
kinetic: J*x_dot**2/2
"""


def symbols_of(problem, *which):
    table = names(problem)
    return [table[w] for w in which]


def test_polar_kinetic_energy():
    """A particle in polar coordinates has T = m (r_dot^2 + r^2 theta_dot^2) / 2 and V = 0."""
    problem = problem_text(POLAR)
    model = build_model(problem)
    m, r, rd, thd = symbols_of(problem, "m", "r", "r_dot", "theta_dot")
    assert exactly_equal(model.kinetic, m * (rd**2 + r**2 * thd**2) / 2)
    assert model.potential == 0


def test_spherical_kinetic_energy():
    """A particle in spherical coordinates has
    T = m (r_dot^2 + r^2 th_dot^2 + r^2 sin^2(th) ph_dot^2) / 2."""
    problem = problem_text(SPHERICAL)
    model = build_model(problem)
    m, r, th, rd, thd, phd = symbols_of(problem, "m", "r", "theta", "r_dot", "theta_dot", "phi_dot")
    expected = m * (rd**2 + r**2 * thd**2 + r**2 * sympy.sin(th) ** 2 * phd**2) / 2
    assert exactly_equal(model.kinetic, expected)


def test_gravity_potential_vertical():
    """Gravity [0, 0, -g] gives V = m g z, here m g r cos(theta)."""
    problem = problem_text(SPHERICAL)
    model = build_model(problem)
    m, g, r, th = symbols_of(problem, "m", "g", "r", "theta")
    assert exactly_equal(model.potential, m * g * r * sympy.cos(th))


def test_gravity_potential_tilted_with_extra_terms():
    """A tilted field adds V = -m g.r to the explicit potential, and T adds the explicit kinetic."""
    problem = problem_text(SPRING)
    model = build_model(problem)
    m, k, g, al, big_j, x, y, xd, yd = symbols_of(
        problem, "m", "k", "g", "alpha", "J", "x", "y", "x_dot", "y_dot")
    v_expected = -m * g * (sympy.sin(al) * x - sympy.cos(al) * y) + k * x**2 / 2
    assert exactly_equal(model.potential, v_expected)
    assert exactly_equal(model.kinetic, m * (xd**2 + yd**2) / 2 + big_j * xd**2 / 2)


def test_lagrangian_is_t_minus_v():
    """The Lagrangian is T - V (here for the bead of the seed homework: m v^2/2 - m g y)."""
    problem = problem_file("bead")
    model = build_model(problem)
    m, g, y, xd, yd = symbols_of(problem, "m", "g", "y", "x_dot", "y_dot")
    assert exactly_equal(model.lagrangian, m * (xd**2 + yd**2) / 2 - m * g * y)
    assert exactly_equal(model.lagrangian, model.kinetic - model.potential)


def test_planar_body_free_disk():
    """A planar body has T = M |v_c|^2 / 2 + I omega^2 / 2."""
    problem = problem_text(FREE_DISK)
    model = build_model(problem)
    big_m, big_i, xd, yd, phd = symbols_of(problem, "M", "Ic", "X_dot", "Y_dot", "phi_dot")
    assert exactly_equal(model.kinetic, big_m * (xd**2 + yd**2) / 2 + big_i * phd**2 / 2)


def test_planar_body_physical_pendulum():
    """A physical pendulum has T = (M d^2 + I) th_dot^2 / 2 and V = -M g d cos(theta)."""
    problem = problem_text(PLANAR_BODY)
    model = build_model(problem)
    big_m, big_i, d, g, th, thd = symbols_of(problem, "M", "Ic", "d", "g", "theta", "theta_dot")
    assert exactly_equal(model.kinetic, (big_m * d**2 + big_i) * thd**2 / 2)
    assert exactly_equal(model.potential, -big_m * g * d * sympy.cos(th))


def test_symmetric_top_energies():
    """A heavy symmetric top (principal moments I1, I1, I3 about the centre of mass) has the
    textbook T = (I1 + M d^2)(th_dot^2 + ph_dot^2 sin^2)/2 + I3 (ps_dot + ph_dot cos)^2/2."""
    problem = problem_text(TOP)
    model = build_model(problem)
    big_m, g, d, i1, i3, th, thd, phd, psd = symbols_of(
        problem, "M", "g", "d", "I1", "I3", "theta", "theta_dot", "phi_dot", "psi_dot")
    s, c = sympy.sin(th), sympy.cos(th)
    expected = (i1 + big_m * d**2) * (thd**2 + phd**2 * s**2) / 2 + i3 * (psd + phd * c) ** 2 / 2
    assert exactly_equal(model.kinetic, expected)
    assert exactly_equal(model.potential, big_m * g * d * c)


def test_asymmetric_body_principal_axes():
    """A 3-D body with principal moments A, B, C has T = (A w1^2 + B w2^2 + C w3^2) / 2."""
    problem = problem_text(ASYMMETRIC)
    model = build_model(problem)
    big_a, big_b, big_c, w, a, ad, bd = symbols_of(
        problem, "A", "B", "C", "w", "a", "a_dot", "b_dot")
    w1, w2, w3 = ad, bd * sympy.cos(a), w + bd * sympy.sin(a)
    assert exactly_equal(model.kinetic, (big_a * w1**2 + big_b * w2**2 + big_c * w3**2) / 2)


def test_model_symbols_in_input_order():
    """Coordinates, velocities and accelerations come in input order with the _dot/_ddot names."""
    model = build_model(problem_file("hole_table"))
    assert [str(q) for q in model.coordinates] == ["r", "theta", "z"]
    assert [str(v) for v in model.velocities] == ["r_dot", "theta_dot", "z_dot"]
    assert [str(a) for a in model.accelerations] == ["r_ddot", "theta_ddot", "z_ddot"]


def test_time_derivative_of_declared_function():
    """d/dt f(x) = f'(x) x_dot, written with Derivative(f(x), x)."""
    problem = problem_file("bead")
    model = build_model(problem)
    x, xd, f = symbols_of(problem, "x", "x_dot", "f")
    assert exactly_equal(time_derivative(f(x), model), sympy.Derivative(f(x), x) * xd)
    assert exactly_equal(model.time_derivative(f(x)), sympy.Derivative(f(x), x) * xd)


@pytest.mark.parametrize("second_order", [False, True])
def test_time_derivative_along_trajectory(second_order):
    """time_derivative agrees with d/dt taken along concrete trajectories q(t), with explicit t."""
    problem = problem_text(SPHERICAL)
    model = build_model(problem)
    t = problem.time
    m, g = symbols_of(problem, "m", "g")
    qs, vs, accs = model.coordinates, model.velocities, model.accelerations
    r, th, ph = qs
    expr = m * r**2 * sympy.sin(th) * sympy.cos(ph - 3 * t) + g * t**2 * r
    if second_order:
        expr += m * vs[0] * vs[2] * sympy.sin(th) + vs[1] ** 3 * t
    paths = [2 + sympy.sin(t) / 2, sympy.cos(2 * t) / 3 + 1, t**2 / 5 - t]
    along = {q: p for q, p in zip(qs, paths, strict=True)}
    along |= {v: sympy.diff(p, t) for v, p in zip(vs, paths, strict=True)}
    along |= {a: sympy.diff(p, t, 2) for a, p in zip(accs, paths, strict=True)}
    direct = sympy.diff(expr.xreplace(along), t)
    ours = time_derivative(expr, model, second_order=second_order).xreplace(along)
    assert_same(ours, direct, seed=3)


def test_time_derivative_random_identity():
    """For F(q, t), d/dt F equals the chain rule sum at random states (independent diff route)."""
    problem = problem_file("knife_edge")
    model = build_model(problem)
    x, y, th = model.coordinates
    t = problem.time
    expr = x * sympy.exp(y) * sympy.cos(th + t)
    fn = {q: sympy.Function(f"Q{i}")(t) for i, q in enumerate(model.coordinates)}
    direct = sympy.diff(expr.xreplace(fn), t)
    back = {sympy.Derivative(fn[q], t): v for q, v in zip(model.coordinates, model.velocities,
                                                            strict=True)}
    direct = direct.xreplace(back).xreplace({v: k for k, v in fn.items()})
    assert exactly_equal(time_derivative(expr, model), direct)


def test_energies_are_numerically_right_for_the_knife_edge():
    """The dumbbell's T equals the sum of m|v|^2/2 of both particles at random states."""
    problem = problem_file("knife_edge")
    model = build_model(problem)
    m, l_, th, xd, yd, thd = symbols_of(problem, "m", "l", "theta", "x_dot", "y_dot", "theta_dot")
    v2 = (xd - l_ * sympy.sin(th) * thd) ** 2 + (yd + l_ * sympy.cos(th) * thd) ** 2
    assert_same(model.kinetic, m * (xd**2 + yd**2) / 2 + m * v2 / 2)
