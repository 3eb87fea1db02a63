"""mechanics/equations/pair.py: the velocity of a contact point, and of that point relative to what carries the
surface."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.equations.model import build_model
from lagsolve.mechanics.equations.pair import point_jacobian, relative_jacobian
from mechanics_support import derived_text, names, problem_file, problem_text

ROLLING_DISK = """
name: Disk rolling down an incline, no particles
parameters: {M: mass, R: radius, Ic: moment of inertia, g: gravity, alpha: angle}
coordinates: [x, phi]
bodies:
  disk: {mass: M, position: [x, 0], inertia: Ic, angular_velocity: -phi_dot}
potential: -M*g*sin(alpha)*x
constraints:
  roll: {holonomic: x - R*phi, on: disk, at: [x, -R]}
"""


def test_point_velocity_jacobian_includes_the_rotation() -> None:
    """v_P = v_C + omega z x (P - C): for the contact point (x, -R) of a disk turning at -phi_dot it is
    (x_dot - R phi_dot, 0), which vanishes when it rolls."""
    problem = problem_text(ROLLING_DISK)
    model = build_model(problem)
    s = names(problem)
    at = problem.constraints[0].at
    assert at is not None
    J = point_jacobian(problem, model, "disk", at)
    assert (J - sympy.Matrix([[1, -s["R"]], [0, 0]])).is_zero_matrix
    force = derived_text(ROLLING_DISK).constraint_forces["roll"]
    assert force.vector is not None and force.vector[1] == 0


def test_a_particle_carries_a_point_by_translating() -> None:
    """The point of the block carried by the wedge moves with the wedge: J_rel is the block's Jacobian minus the
    wedge's, whatever the point (a particle does not turn)."""
    problem = problem_file("rough_wedge")
    model = build_model(problem)
    block = problem.particle("block").position
    J = relative_jacobian(problem, model, "block", "wedge", block)
    # coordinates X, x, y: the block moves with x and y, the wedge with X
    assert (J - sympy.Matrix([[-1, 1, 0], [0, 0, 1]])).is_zero_matrix
    far = (sympy.Integer(7), sympy.Integer(-3))
    moved = point_jacobian(problem, model, "wedge", far) - point_jacobian(problem, model, "wedge", block)
    assert moved.is_zero_matrix


def test_a_turning_body_carries_a_point_with_its_rotation() -> None:
    """A point carried by a planar body moves with v_C + omega z x (P - C): on the wedge of
    problems/wedge_cylinder.yaml (which translates) the relative velocity of the cylinder's contact point is
    s_dot - R phi_dot along the face, zero when it rolls."""
    problem = problem_file("wedge_cylinder")
    model = build_model(problem)
    s = names(problem)
    at = problem.constraints[0].at
    assert at is not None
    J = relative_jacobian(problem, model, "cyl", "wedge", at)
    alpha, R = s["alpha"], s["R"]
    velocity = J * sympy.Matrix(model.velocities)
    along = sympy.Matrix([sympy.cos(alpha), -sympy.sin(alpha)])
    assert sympy.simplify((along.T * velocity)[0] - (s["s_dot"] - R * s["phi_dot"])) == 0
    assert sympy.simplify((sympy.Matrix([sympy.sin(alpha), sympy.cos(alpha)]).T * velocity)[0]) == 0
