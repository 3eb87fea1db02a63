"""The geometry a sketch draws: rods, pivots, surfaces and wires classified from shipped problems."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.geometry.shapes import Anchor, geometry
from mechanics_support import problem_file


def _symbols(problem: object, *names: str) -> list[sympy.Symbol]:
    return [problem.symbols[n] for n in names]  # type: ignore[attr-defined]


def test_double_pendulum_has_two_rods_pivot_to_upper_to_lower() -> None:
    """Angles fix both distances: a rod from the pivot at the origin to 'upper', one from 'upper' to 'lower'."""
    problem = problem_file("double_pendulum")
    g = geometry(problem)
    (length,) = _symbols(problem, "l")
    assert [(r.start, r.end.particle, r.constraint) for r in g.rods] == [
        (Anchor(None, (0, 0)), "upper", None), (Anchor("upper"), "lower", None)]
    assert all(sympy.simplify(r.length - length) == 0 for r in g.rods)
    assert g.pivots == (Anchor(None, (0, 0)),)
    assert not g.surfaces and not g.curves


def test_bead_is_a_curve_y_equals_f_of_x() -> None:
    """The wire y - f(x) = 0 is a curve of the bead, parametrised by x: (x, f(x))."""
    problem = problem_file("bead")
    g = geometry(problem)
    (x,) = _symbols(problem, "x")
    f = next(fn.function for fn in problem.functions if fn.name == "f")
    assert not g.rods and not g.surfaces
    (curve,) = g.curves
    assert (curve.constraint, curve.particle, curve.coordinate) == ("wire", "bead", x)
    assert curve.shape == (x, f(x))


def test_cartesian_pendulum_is_a_rod_from_the_origin() -> None:
    """(x^2 + y^2 - l^2)/2 on the bob is the rod 'rod' from a pivot at the origin, of length l."""
    problem = problem_file("pendulum_cartesian")
    g = geometry(problem)
    (length,) = _symbols(problem, "l")
    (rod,) = g.rods
    assert rod.constraint == "rod" and rod.start == Anchor(None, (0, 0)) and rod.end == Anchor("bob")
    assert sympy.simplify(rod.length - length) == 0


def test_ladder_rod_between_particles_and_two_surfaces() -> None:
    """The ladder's rod joins foot and top; the floor (normal y) and the unilateral wall (normal x) are lines."""
    g = geometry(problem_file("ladder_rough_floor"))
    (rod,) = g.rods
    assert {rod.start.particle, rod.end.particle} == {"foot", "top"} and rod.constraint == "rod"
    floor, wall = g.surfaces
    assert (floor.particle, floor.normal, floor.unilateral) == ("foot", (0, 1), False)
    assert (wall.particle, wall.normal, wall.unilateral) == ("top", (1, 0), True)


def test_wedge_incline_is_carried_by_the_wedge() -> None:
    """The block's incline passes through the wedge's edge (X, Y) and moves with it, carried by the wedge."""
    problem = problem_file("wedge")
    X, Y, alpha = _symbols(problem, "X", "Y", "alpha")
    incline = next(s for s in geometry(problem).surfaces if s.constraint == "incline")
    assert incline.particle == "block" and incline.point == (X, Y) and incline.carrier == "wedge"
    assert incline.normal == (-sympy.sin(alpha), sympy.cos(alpha))


def test_atwood_string_runs_over_a_pulley_of_radius_r() -> None:
    """y1 + y2 + l is no surface and no rod but a string: its force on each mass has the same size and lies along
    the vertical strand, from each mass up to its point of the pulley, (-R, 0) and (R, 0)."""
    problem = problem_file("atwood")
    (R,) = _symbols(problem, "R")
    g = geometry(problem)
    assert not g.rods and not g.surfaces and not g.curves
    (string,) = g.strings
    assert string.ends == ("m1", "m2") and string.anchors == ((-R, 0), (R, 0))
    assert string.slides == ((0, 1), (0, 1))


def test_unilateral_sphere_is_a_circle_not_a_rod() -> None:
    """A particle outside a sphere is drawn as the circle it stays on, centre 0, radius R."""
    problem = problem_file("sliding_off_sphere")
    g = geometry(problem)
    (R,) = _symbols(problem, "R")
    (curve,) = g.curves
    assert not g.rods and curve.coordinate is None and curve.centre == (0, 0) and curve.radius == R


def test_pendulums_hanging_from_a_moving_block_or_support() -> None:
    """A bob at X + l sin(phi) hangs from the block at X by a rod (from the particle, not a fixed pivot)."""
    for name, top in (("block_two_pendulums", "block"), ("moving_support", "support")):
        (rod,) = geometry(problem_file(name)).rods
        assert rod.start == Anchor(top) and rod.end.particle == "bob"


def test_a_bob_hangs_from_a_joint_at_the_end_of_a_bar() -> None:
    """PyDy's system: the bob (q1 + l sin q2 + l sin(q2 + q3), -l cos q2 - l cos(q2 + q3)) hangs by a rod of
    length l from the bar's lower end (q1 + l sin q2, -l cos q2), a point that moves with the bar (the scene draws
    it as a joint, an open circle, not as a fixed pivot)."""
    problem = problem_file("multidof_holonomic")
    q1, q2, length = _symbols(problem, "q1", "q2", "l")
    (rod,) = geometry(problem).rods
    assert rod.end == Anchor("bob") and rod.length == length
    assert [sympy.simplify(a - b) for a, b in zip(rod.start.point, (q1 + length * sympy.sin(q2),
                                                                     -length * sympy.cos(q2)), strict=True)] == [0, 0]


def test_bodies_the_coordinates_move_as_one_are_joined_by_a_frame() -> None:
    """A tricycle seen from above, written here (not shipped): two rear wheels on an axle of half-length b and a
    front wheel a distance c ahead of its midpoint, all bodies in (x, y, θ). The frame is the axle (the pair the
    front wheel's foot falls between, at the midpoint) and a rod from there to the front wheel; a dumbbell of two
    discs is one rod; of three discs at the corners of a scalene triangle, the longest side is the spine (the
    third's foot falls inside it, at 8/17 of the way here)."""
    from mechanics_support import problem_text

    tricycle = problem_text("""
name: tricycle frame
parameters: {m: mass, I: inertia, b: half axle, c: wheelbase}
coordinates: {x: x, y: y, theta: heading}
bodies:
  rearR: {mass: m, position: [x + b*sin(theta), y - b*cos(theta)], inertia: I, angular_velocity: theta_dot}
  rearL: {mass: m, position: [x - b*sin(theta), y + b*cos(theta)], inertia: I, angular_velocity: theta_dot}
  front: {mass: m, position: [x + c*cos(theta), y + c*sin(theta)], inertia: I, angular_velocity: theta_dot}
""")
    rods = geometry(tricycle).rods
    assert [(r.start.particle, r.end.particle) for r in rods] == [("rearR", "rearL"), (None, "front")]
    assert [str(c) for c in rods[1].start.point] == ["x", "y"]  # the front wheel's foot on the axle: its midpoint
    dumbbell = problem_text("""
name: dumbbell
parameters: {m: mass, I: inertia, l: half length}
coordinates: {x: x, y: y, theta: angle}
bodies:
  one: {mass: m, position: [x + l*cos(theta), y + l*sin(theta)], inertia: I, angular_velocity: theta_dot}
  two: {mass: m, position: [x - l*cos(theta), y - l*sin(theta)], inertia: I, angular_velocity: theta_dot}
""")
    rods = geometry(dumbbell).rods
    assert [(r.start.particle, r.end.particle) for r in rods] == [("one", "two")]
    assert str(rods[0].length) in ("2*Abs(l)", "2*l")
    skew = problem_text("""
name: three discs, one far out
parameters: {m: mass, I: inertia}
coordinates: {x: x, theta: angle}
bodies:
  a: {mass: m, position: [x + cos(theta), sin(theta)], inertia: I, angular_velocity: theta_dot}
  b: {mass: m, position: [x - cos(theta), -sin(theta)], inertia: I, angular_velocity: theta_dot}
  c: {mass: m, position: [x + 3*cos(theta) - sin(theta), 3*sin(theta) + cos(theta)], inertia: I,
      angular_velocity: theta_dot}
""")
    spine, arm = geometry(skew).rods
    assert (spine.start.particle, spine.end.particle, arm.start.particle, arm.end.particle) == ("b", "c", None, "a")
    b, c = sympy.Matrix([-1, 0]), sympy.Matrix([3, 1])  # at x = 0, theta = 0
    foot = sympy.Matrix([p.xreplace({s: 0 for s in p.free_symbols}) for p in arm.start.point])
    assert foot == b + sympy.Rational(8, 17) * (c - b)
