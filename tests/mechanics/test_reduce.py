"""Dependent coordinates and velocities given explicitly by the constraints
(``lagsolve.mechanics.equations.elimination``)."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.equations.constraints import constraint_terms, velocity_form
from lagsolve.mechanics.equations.elimination import eliminate
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import TUBE, exactly_equal, names, problem_file, problem_text

DRIVEN = """
name: Particle on a turntable guide
parameters: {m: mass, Omega: rate, l: length, v0: speed}
coordinates: [x, y, phi]
particles:
  p: {mass: m, position: [x, y]}
kinetic: phi_dot**2/2
constraints:
  drive: {holonomic: phi - Omega*t}
  rail: {holonomic: 2*x + 3*y - l}
"""

NOT_EXPLICIT = """
name: Constraints that give no variable explicitly
parameters: {m: mass, l: length}
coordinates: [x, y, theta]
particles:
  p: {mass: m, position: [x, y]}
kinetic: theta_dot**2/2
constraints:
  rod: {holonomic: x**2 + y**2 - l**2}
  skate: {nonholonomic: -sin(theta)*x_dot + cos(theta)*y_dot}
"""

SCALED_VELOCITY = """
name: Wheel rolling at a prescribed rate
parameters: {m: mass, R: radius, v0: speed}
coordinates: [x, phi]
particles:
  p: {mass: m, position: [x, 0]}
kinetic: phi_dot**2/2
constraints:
  rate: {nonholonomic: x*phi_dot - v0}
"""


def elimination_of(problem):
    model = build_model(problem)
    terms = tuple(constraint_terms(c, model) for c in problem.constraints)
    return model, terms, eliminate(terms, model)


def test_wire_eliminates_y():
    """y - f(x) gives y = f(x) and y_dot = f'(x) x_dot, from the constraint 'wire'."""
    problem = problem_file("bead")
    _, _, elim = elimination_of(problem)
    s = names(problem)
    x, y, xd, yd, f = s["x"], s["y"], s["x_dot"], s["y_dot"], s["f"]
    assert set(elim.positions) == {y}
    assert exactly_equal(elim.positions[y], f(x))
    assert exactly_equal(elim.velocities[yd], sympy.Derivative(f(x), x) * xd)
    assert elim.sources == {y: "wire"}


def test_string_eliminates_the_last_coordinate():
    """r - z - l eliminates z (the last coordinate it gives explicitly): z = r - l,
    z_dot = r_dot."""
    problem = problem_file("hole_table")
    _, _, elim = elimination_of(problem)
    s = names(problem)
    assert elim.positions == {s["z"]: s["r"] - s["l"]}
    assert exactly_equal(elim.velocities[s["z_dot"]], s["r_dot"])


def test_velocity_constraints_eliminate_velocities():
    """theta_dot = 0 and phi_dot - Omega = 0 give theta_dot -> 0 and phi_dot -> Omega."""
    problem = problem_text(TUBE)
    _, _, elim = elimination_of(problem)
    s = names(problem)
    assert elim.positions == {}
    assert elim.velocities == {s["theta_dot"]: 0, s["phi_dot"]: s["Omega"]}
    assert elim.sources == {s["theta_dot"]: "tilt", s["phi_dot"]: "spin"}


def test_time_dependent_holonomic_constraint():
    """phi - Omega t gives phi = Omega t and phi_dot = Omega; 2x + 3y - l gives y = (l - 2x)/3."""
    problem = problem_text(DRIVEN)
    _, _, elim = elimination_of(problem)
    s = names(problem)
    assert exactly_equal(elim.positions[s["phi"]], s["Omega"] * s["t"])
    assert exactly_equal(elim.velocities[s["phi_dot"]], s["Omega"])
    assert exactly_equal(elim.positions[s["y"]], (s["l"] - 2 * s["x"]) / 3)
    assert exactly_equal(elim.velocities[s["y_dot"]], -2 * s["x_dot"] / 3)


def test_eliminations_satisfy_their_constraints():
    """Substituting an elimination into its constraint (and its velocity form) gives zero."""
    for problem in (problem_file("bead"), problem_file("hole_table"), problem_text(DRIVEN),
                    problem_text(TUBE)):
        model, terms, elim = elimination_of(problem)
        for c in terms:
            if c.kind == "holonomic":
                assert sympy.simplify(elim.apply(c.expression)) == 0
            assert sympy.simplify(elim.apply(velocity_form(c, model))) == 0


def test_implicit_constraints_eliminate_nothing():
    """A non-linear holonomic constraint and a two-velocity constraint give no explicit variable."""
    _, _, elim = elimination_of(problem_text(NOT_EXPLICIT))
    assert elim.positions == {} and elim.velocities == {} and elim.sources == {}
    _, _, elim = elimination_of(problem_file("knife_edge"))
    assert elim.positions == {} and elim.velocities == {}


def test_single_velocity_with_coordinate_coefficient():
    """x phi_dot - v0 = 0 gives phi_dot = v0 / x."""
    problem = problem_text(SCALED_VELOCITY)
    _, _, elim = elimination_of(problem)
    s = names(problem)
    assert exactly_equal(elim.velocities[s["phi_dot"]], s["v0"] / s["x"])


def test_apply_chains_velocity_and_position_substitutions():
    """apply() rewrites y_dot through f'(x) and y through f(x) in one expression."""
    problem = problem_file("bead")
    _, _, elim = elimination_of(problem)
    s = names(problem)
    x, y, xd, yd, f, g = s["x"], s["y"], s["x_dot"], s["y_dot"], s["f"], s["g"]
    expr = yd**2 + g * y + sympy.sin(y) * xd
    expected = (sympy.Derivative(f(x), x) * xd) ** 2 + g * f(x) + sympy.sin(f(x)) * xd
    assert exactly_equal(elim.apply(expr), expected)
    assert elim.apply(x + xd) == x + xd


INCLINE = """
name: Particle on a fixed incline
parameters: {m: mass, g: gravity, alpha: angle of the incline}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  slope: {holonomic: x*sin(alpha) - y*cos(alpha)}
"""


def test_constant_coefficient_with_a_function_of_parameters():
    """x sin(alpha) - y cos(alpha) = 0 (alpha a parameter) gives y = x tan(alpha)."""
    problem = problem_text(INCLINE)
    _, _, elim = elimination_of(problem)
    s = names(problem)
    assert exactly_equal(elim.positions[s["y"]], s["x"] * sympy.tan(s["alpha"]))
