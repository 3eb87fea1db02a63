"""Knife edges found for a sketch (lagsolve.mechanics.geometry.links.blades): the velocity constraint n·v = 0 of a
member, decided at random states, with n left unsimplified (the sketch evaluates it)."""

from __future__ import annotations

import math

import sympy

from lagsolve.mechanics.geometry.links import blades
from lagsolve.problem.load import load_text
from mechanics_support import problem_file

SKATE = """\
name: A skate
parameters: {m: mass, I: moment of inertia, d: offset}
coordinates: [x, y, theta]
particles:
  p: {mass: m, position: [POSITION]}
constraints:
  skate: {nonholonomic: CONSTRAINT, on: [p]}
"""


def _blades(position: str, constraint: str) -> list:
    problem = load_text(SKATE.replace("POSITION", position).replace("CONSTRAINT", constraint), "s.yaml")
    return blades(problem, [c.symbol for c in problem.coordinates])


def _direction_at(blade, values: dict) -> tuple[float, float]:
    return tuple(float(sympy.sympify(e, strict=True).subs(values)) for e in blade.direction)


def test_a_skate_moves_along_its_heading() -> None:
    """-sin(θ) ẋ + cos(θ) ẏ = 0 on the particle at (x, y): the blade points along (cos θ, sin θ)."""
    (blade,) = _blades("x, y", "-sin(theta)*x_dot + cos(theta)*y_dot")
    x, y, theta = sympy.symbols("x y theta", real=True)
    for angle in (0.3, 1.2, -2.0):
        u, v = _direction_at(blade, {x: 0.4, y: -1.0, theta: angle})
        assert math.isclose(u * math.sin(angle), v * math.cos(angle), abs_tol=1e-12) and (u, v) != (0.0, 0.0)


def test_a_constraint_that_is_no_velocity_of_the_member_gives_no_blade() -> None:
    """θ̇ = 0 constrains no velocity of a particle at (x, y): no blade (Jᵀ n = a has no solution)."""
    assert _blades("x, y", "theta_dot") == []


def test_an_offset_point_on_the_heading_line() -> None:
    """The point d ahead of (x, y) along θ, with the skate's constraint written for (x, y) plus its turning: the
    constraint is n·v = 0 of that point (its sideways velocity), found as a blade."""
    found = _blades("x + d*cos(theta), y + d*sin(theta)",
                    "-sin(theta)*x_dot + cos(theta)*y_dot + d*theta_dot")
    assert [b.constraint for b in found] == ["skate"]


def test_the_differential_drive_has_a_blade_on_each_wheel() -> None:
    problem = problem_file("differential_drive")
    found = blades(problem, [c.symbol for c in problem.coordinates])
    assert sorted((b.constraint, b.particle) for b in found) == [("lateral", "left"), ("lateral", "right")]


def test_a_skate_whose_position_has_no_real_value_at_some_states_is_still_found() -> None:
    """√θ in the position has no real value where θ < 0: those random states are skipped, not taken as no blade
    (the constraint is the sideways velocity n·v of the point (x + √θ, y), n = (−sin θ, cos θ))."""
    constraint = "-sin(theta)*x_dot + cos(theta)*y_dot - sin(theta)*theta_dot/(2*sqrt(theta))"
    assert [b.constraint for b in _blades("x + sqrt(theta), y", constraint)] == ["skate"]
    assert _blades("x + sqrt(theta), y", "theta_dot") == []
