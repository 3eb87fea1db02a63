"""Minimal coordinates (``lagsolve.mechanics.analysis.minimal``): the reduced Lagrangian and equations,
and their agreement with the multiplier route."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.analysis.integrability import classify_all
from lagsolve.mechanics.analysis.minimal import choose_dependent, reduce_system
from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import derived_file, exactly_equal, names, problem_file, problem_text

RAIL = """
name: Particle on a straight rail
parameters: {m: mass, l: offset, g: gravity}
coordinates: [x, y]
particles: {p: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints:
  rail: {holonomic: 2*x + 3*y - l}
"""


def parts(problem):
    model = build_model(problem)
    terms = tuple(constraint_terms(c, model) for c in problem.constraints)
    return model, terms


def test_bead_reduced_lagrangian_is_the_alternate_method():
    """The bead's reduced L is m(1 + f'^2) x_dot^2/2 - m g f(x), and its x_ddot is the hint's."""
    bead = derived_file("bead")
    s = names(bead.problem)
    m, g, x, xd, f = s["m"], s["g"], s["x"], s["x_dot"], s["f"]
    fp = sympy.Derivative(f(x), x)
    reduced = bead.analysis.reduced
    assert reduced.independent == (x,)
    assert exactly_equal(reduced.lagrangian, m * (1 + fp**2) * xd**2 / 2 - m * g * f(x))
    assert exactly_equal(reduced.accelerations["x"], bead.accelerations["x"])
    assert reduced.agreement == "symbolic"


def test_independent_list_picks_which_coordinate_is_solved():
    """On the rail 2x + 3y = l, keeping x gives y = (l - 2x)/3 and keeping y gives x = (l - 3y)/2."""
    problem = problem_text(RAIL)
    model, terms = parts(problem)
    x, y, length = names(problem)["x"], names(problem)["y"], names(problem)["l"]
    keep_x, _ = choose_dependent(terms, model, ("x",))
    keep_y, _ = choose_dependent(terms, model, ("y",))
    assert exactly_equal(keep_x.positions[y], (length - 2 * x) / 3)
    assert exactly_equal(keep_y.positions[x], (length - 3 * y) / 2)


def test_a_constraint_not_linear_in_a_free_coordinate_is_explained():
    """Keeping y on the wire y = f(x) would need x = f^-1(y): no reduction, and the reason names the constraint."""
    problem = problem_file("bead")
    model, terms = parts(problem)
    elimination, reason = choose_dependent(terms, model, ("y",))
    assert elimination is None
    assert "'wire'" in reason and "independent list" in reason


def test_nonholonomic_constraint_prevents_reduction():
    """A truly nonholonomic constraint leaves no reduced system, with the reason given."""
    problem = problem_file("knife_edge")
    model, terms = parts(problem)
    classes = classify_all(terms, model, problem.constraints, set(problem.symbols))
    knife = derived_file("knife_edge")
    reduced, reason = reduce_system(model, terms, classes, knife.lagrange.generalized_forces, {},
                                    knife.raw_accelerations)
    assert reduced is None and "nonholonomic" in reason


def test_friction_enters_the_reduced_equation():
    """In the rough tube the reduced r_ddot is the multiplier route's, friction included, with theta = theta0."""
    tube = derived_file("rotating_tube")
    reduced = tube.analysis.reduced
    theta0 = tube.analysis.classification[0].constant
    theta = names(tube.problem)["theta"]
    assert reduced.independent == (names(tube.problem)["r"],)
    assert reduced.agreement == "symbolic"
    assert exactly_equal(reduced.accelerations["r"], tube.accelerations["r"].xreplace({theta: theta0}))
    assert reduced.generalized_forces[0].has(names(tube.problem)["mu"])


def test_hole_table_reduced_equations():
    """The reduced equations are (m1 + m2) r_ddot = m1 r theta_dot^2 - m2 g and d(m1 r^2 theta_dot)/dt = 0."""
    hole = derived_file("hole_table")
    s = names(hole.problem)
    m1, m2, g, r, rd, thd = s["m1"], s["m2"], s["g"], s["r"], s["r_dot"], s["theta_dot"]
    rdd, thdd = s["r_ddot"], s["theta_ddot"]
    (lhs_r, rhs_r), (lhs_t, rhs_t) = hole.analysis.reduced.equation_sides
    assert exactly_equal(lhs_r - rhs_r, (m1 + m2) * rdd - m1 * r * thd**2 + m2 * g)
    assert exactly_equal(lhs_t - rhs_t, m1 * r**2 * thdd + 2 * m1 * r * rd * thd)
