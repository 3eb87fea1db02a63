r"""Where two members touch: the velocity of a contact point, and of that point relative to what carries the
surface.

A contact acts at a point :math:`P` of its first member (a particle: its position; a planar body: a point given
with ``at:``), against a second member that carries the surface (a particle, which translates, or a planar body,
which also turns), or against the fixed surroundings. The forces of the contact are :math:`\mathbf f` on the
first member at :math:`P` and :math:`-\mathbf f` on the second at the same point, so their generalized forces
together are :math:`J_{rel}^T\mathbf f` with

.. math:: J_{rel} = \frac{\partial\mathbf v_P}{\partial\dot q} - \frac{\partial\mathbf v_{P,2}}{\partial\dot q},

:math:`\mathbf v_{P,2}` the velocity of the point of the second member that is at :math:`P` (the velocity of
the second member's centre plus :math:`\boldsymbol\omega_2\times(\mathbf r_P - \mathbf r_2)`). The sliding
velocity of the contact is :math:`J_{rel}\dot q`, the velocity of :math:`P` relative to the surface. (Positions
that depend on the time explicitly describe a surface moving with the time: only the coordinates' rates make
the relative velocity.)
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.equations.forces import position_jacobian
from lagsolve.mechanics.equations.model import Model
from lagsolve.problem.schema import Problem


def point_jacobian(problem: Problem, model: Model, member: str, point: tuple[Any, ...]) -> sympy.Matrix:
    r""":math:`\partial\mathbf v/\partial\dot q` of the point ``point`` moving with ``member``: a particle's own
    velocity (it translates), or for a planar body the centre's plus :math:`\omega\,\hat z\times(\mathbf r_P -
    \mathbf r_C)`, column :math:`i` being :math:`\partial\mathbf r_C/\partial q_i + (\partial\omega/\partial\dot q_i)
    \,\hat z\times(\mathbf r_P - \mathbf r_C)`."""
    body = next((b for b in problem.bodies if b.name == member), None)
    if body is None:
        return position_jacobian(problem.particle(member).position, model)
    centre = sympy.Matrix(body.position)
    r = sympy.Matrix(point) - centre
    turn = sympy.Matrix([-r[1], r[0]])  # z × r
    omega = body.angular_velocity[0]
    columns = [sympy.diff(centre, q) + sympy.diff(omega, v) * turn
               for q, v in zip(model.coordinates, model.velocities, strict=True)]
    return sympy.Matrix.hstack(*columns)


def relative_jacobian(problem: Problem, model: Model, first: str, second: str | None,
                      point: tuple[Any, ...]) -> sympy.Matrix:
    r""":math:`J_{rel}`: the velocity Jacobian of the point ``point`` of ``first`` relative to the point of
    ``second`` (None: the surroundings) at the same place."""
    J = point_jacobian(problem, model, first, point)
    if second is not None:
        J = J - point_jacobian(problem, model, second, point)
    return J
