r"""Physical forces of constraint.

The generalized force of constraint :math:`j` is :math:`\lambda_j a_j`. On the particles
:math:`p` it acts on (``on``), it is the force :math:`\mathbf f` with
:math:`J^T\mathbf f = \lambda_j a_j`, :math:`J = \partial\mathbf r/\partial q` stacked over those
particles. We take the least-norm solution :math:`\mathbf f = \lambda_j\,(J^T)^+ a_j`, which is
:math:`(JJ^T)^{-1}J\lambda_j a_j` (the format's formula) when :math:`JJ^T` is invertible, and check
:math:`J^T\mathbf f = \lambda_j a_j`: when that fails the constraint also acts on something
not named in ``on`` and no force is claimed.

A constraint on a rigid body names the point :math:`P` where it acts (``on: disk``,
``at: [X, Y - R]``). Then :math:`J` is that point's velocity Jacobian,
:math:`\partial\mathbf v_P/\partial\dot q` with
:math:`\mathbf v_P = \dot{\mathbf r}_C + \boldsymbol\omega\times(\mathbf r_P - \mathbf r_C)` (for a planar body
:math:`\omega` is the component along :math:`z`, counter-clockwise positive): rolling without slipping
gives the friction force at the contact. Without a point (a body, or no particles at all) no
physical force is claimed: the generalized forces of constraint :math:`\lambda_j a_j` are the
result (a force for a length, a torque for an angle), and no magnitude mixes the two.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.constraints import ConstraintTerms
from lagsolve.mechanics.forces import position_jacobian
from lagsolve.mechanics.lagrange import solve_linear
from lagsolve.mechanics.model import Model
from lagsolve.mechanics.simplify import norm, tidy
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class ParticleForce:
    """The force of one constraint on one particle is ``multiplier * direction``."""

    particle: str
    direction: tuple[Any, ...]


@dataclass(frozen=True)
class Reaction:
    """How constraint ``name`` pushes: per-particle forces, or a note saying why not.

    With no particles at all, ``particles`` is empty and ``generalized`` is true:
    the force is taken as λ a in the coordinates themselves."""

    name: str
    particles: tuple[ParticleForce, ...]
    generalized: bool
    note: str


def reaction(problem: Problem, model: Model, terms: ConstraintTerms) -> Reaction:
    """Direction and size of the force of one constraint, per unit multiplier."""
    a = sympy.Matrix(terms.coefficients)
    spec = next((c for c in problem.constraints if c.name == terms.name), None)
    if spec is not None and spec.at is not None:
        return _at_point(problem, model, terms, spec.on, spec.at)
    if not problem.particles:
        return Reaction(terms.name, (), True, GENERALIZED)
    if not terms.on:
        return Reaction(terms.name, (), False,
                        "the problem has several particles and the constraint does not say which one it "
                        "acts on; name it with 'on:' to get the physical force")
    blocks = [position_jacobian(problem.particle(p).position, model) for p in terms.on]
    J = sympy.Matrix.vstack(*blocks)
    direction = _least_norm(J, a)
    if direction is None or any(tidy(e) != 0 for e in (J.T * direction - a)):
        named = ", ".join(terms.on)
        return Reaction(terms.name, (), False,
                        f"this constraint also acts elsewhere: λ·a is not the generalized force of any force on "
                        f"{named} alone, so no physical force is claimed; list every particle it acts on in 'on:'")
    forces = []
    row = 0
    for p, block in zip(terms.on, blocks, strict=True):
        part = direction[row:row + block.rows, 0]
        row += block.rows
        forces.append(ParticleForce(p, tuple(tidy(c) for c in part)))
    return Reaction(terms.name, tuple(forces), False, "")


#: the note of a constraint whose physical force is not known: its generalized forces are given instead
GENERALIZED = ("generalized forces of constraint λ·a, one per coordinate (a force for a length, a torque for an "
               "angle), so no magnitude is given; for the physical force name the body and the point where the "
               "constraint acts with 'on:' and 'at:'")


def point_velocity_jacobian(problem: Problem, model: Model, body: str, point: tuple[Any, ...]) -> sympy.Matrix:
    r""":math:`\partial\mathbf v_P/\partial\dot q` of the point ``point`` of the planar ``body``:
    column :math:`i` is :math:`\partial\mathbf r_C/\partial q_i + (\partial\omega/\partial\dot q_i)\,
    \hat z\times(\mathbf r_P - \mathbf r_C)`."""
    b = problem.body(body)
    centre = sympy.Matrix(b.position)
    r = sympy.Matrix(point) - centre
    turn = sympy.Matrix([-r[1], r[0]])  # z × r
    omega = b.angular_velocity[0]
    columns = [sympy.diff(centre, q) + sympy.diff(omega, v) * turn
               for q, v in zip(model.coordinates, model.velocities, strict=True)]
    return sympy.Matrix.hstack(*columns)


def _at_point(problem: Problem, model: Model, terms: ConstraintTerms, on: tuple[str, ...],
              point: tuple[Any, ...]) -> Reaction:
    """The force of a constraint acting at ``point`` of the body ``on[0]``: J_Pᵀ f = a with J_P the point's
    velocity Jacobian (least norm: the components the constraint does not fix are zero). With a second name
    (a particle or planar body the first presses on, a surface that moves) the force on it is -f at the same
    point, so J_P is the relative velocity's Jacobian: the first body's point minus the point moving with the
    second."""
    body = on[0]
    J = point_velocity_jacobian(problem, model, body, point)
    if len(on) > 1:
        J = J - _carried(problem, model, on[1], point)
    a = sympy.Matrix(terms.coefficients)
    direction = _least_norm(J, a)
    where = " and ".join(repr(n) for n in on)
    if direction is None or any(tidy(e) != 0 for e in (J.T * direction - a)):
        return Reaction(terms.name, (), False,
                        f"λ·a is not the generalized force of a force at the point {[str(c) for c in point]} of "
                        f"{where}, so no physical force is claimed; check 'at:' (and that the body's "
                        "angular velocity is counter-clockwise positive)")
    force = tuple(tidy(c) for c in direction)
    if len(on) == 1:
        return Reaction(terms.name, (ParticleForce(body, force),), False,
                        f"the force on {body} at the point given under 'at:'")
    return Reaction(terms.name, (ParticleForce(body, force), ParticleForce(on[1], tuple(-c for c in force))), False,
                    f"the force on {body} at the point given under 'at:', and its reaction on {on[1]}")


def _carried(problem: Problem, model: Model, name: str, point: tuple[Any, ...]) -> sympy.Matrix:
    r""":math:`\partial\mathbf v/\partial\dot q` of the point ``point`` carried along by the particle (it
    translates) or planar body ``name``."""
    if any(b.name == name for b in problem.bodies):
        return point_velocity_jacobian(problem, model, name, point)
    return position_jacobian(problem.particle(name).position, model)


def _least_norm(J: sympy.Matrix, a: sympy.Matrix) -> sympy.Matrix | None:
    """The least-norm solution of J^T f = a, or None when it cannot be formed.

    Uses whichever Gram matrix is the smaller square (J^T J, the metric of the
    coordinates, when J has at least as many rows as columns), simplified first,
    and a linear solve rather than an inverse.
    """
    rows, cols = J.shape
    grams = [("metric", J.T * J), ("rows", J * J.T)] if rows >= cols else [("rows", J * J.T), ("metric", J.T * J)]
    for kind, gram in grams:
        gram = gram.applyfunc(tidy)
        rhs = a if kind == "metric" else J * a
        try:
            y = sympy.Matrix(solve_linear(gram, sympy.Matrix(rhs)))
        except ValueError:
            continue
        return (J * y if kind == "metric" else y).applyfunc(sympy.cancel)
    try:
        return (J.T.pinv() * a).applyfunc(sympy.cancel)
    except (ValueError, ZeroDivisionError, NotImplementedError):
        return None


def force_scale(react: Reaction) -> Any:
    """|force of the constraint| / |λ|: the length of its direction on its first particle (or named point),
    NaN where no physical force is known (no particle, no point of a body named): no magnitude is claimed."""
    if react.particles:
        return norm(list(react.particles[0].direction))
    return sympy.nan
