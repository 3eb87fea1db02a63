r"""Generalized forces :math:`Q_i` from the problem's non-conservative loads.

* a generalized force ``{coordinate: q, value: Q}`` adds to :math:`Q_q` directly;
* a physical force :math:`\mathbf F` on particle :math:`p` adds
  :math:`\mathbf F\cdot\partial\mathbf r_p/\partial q_i` to every :math:`Q_i`;
* a Rayleigh function :math:`R(\dot q)` adds :math:`-\partial R/\partial\dot q_i`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.model import Model
from lagsolve.problem.schema import Friction, Problem


@dataclass(frozen=True)
class ForceTerm:
    """One contribution to the generalized forces, kept apart for the report."""

    label: str  # e.g. "force on bead", "dissipation"
    generalized: tuple[Any, ...]  # one entry per coordinate


def position_jacobian(position: tuple[Any, ...], model: Model) -> sympy.Matrix:
    r""":math:`J_p = \partial\mathbf r_p/\partial q`, shape (components, coordinates)."""
    return sympy.Matrix([[sympy.diff(r, q) for q in model.coordinates] for r in position])


def force_terms(problem: Problem, model: Model) -> tuple[ForceTerm, ...]:
    """Every generalized-force contribution of ``problem`` except friction."""
    n = len(model.coordinates)
    index = {c.name: i for i, c in enumerate(problem.coordinates)}
    terms: list[ForceTerm] = []
    for force in problem.forces:
        if force.coordinate is not None:
            row = [sympy.Integer(0)] * n
            row[index[force.coordinate]] = force.value[0]
            terms.append(ForceTerm(f"generalized force on {force.coordinate}", tuple(row)))
        else:
            particle = problem.particle(force.on or "")
            jac = position_jacobian(particle.position, model)
            if len(force.value) != jac.rows:
                continue  # dimensions are checked by the loader
            generalized = jac.T * sympy.Matrix(force.value)
            terms.append(ForceTerm(f"force on {particle.name}", tuple(generalized)))
    if problem.dissipation is not None:
        dissipative = tuple(-sympy.diff(problem.dissipation, qd) for qd in model.velocities)
        terms.append(ForceTerm("dissipation", dissipative))
    return tuple(terms)


@dataclass(frozen=True)
class FrictionTerm:
    r"""Kinetic Coulomb friction of one contact, :math:`\mathbf F = -\mu N\,\mathbf v/|\mathbf v|`.

    ``normal`` is the symbol :math:`N` (named ``N_<contact>``) that stands in the
    equations for the magnitude of the combined force of the ``constraints`` on
    ``particle``; ``sliding_velocity`` is :math:`\mathbf v = \sum_{i\in\text{sliding}}
    (\partial\mathbf r_p/\partial q_i)\dot q_i`; ``force`` the friction force vector and
    ``generalized`` its generalized forces :math:`Q_i = \mathbf F\cdot\partial\mathbf r_p/\partial q_i`.

    Notes
    -----
    * valid while the contact slides, :math:`\mathbf v \neq 0` (the sign of the sliding
      rate is assumed constant along a solution);
    * :math:`N \ge 0` is a magnitude; whether the constraint pushes or pulls does not
      change the friction force.
    """

    name: str
    particle: str
    coefficient: Any
    constraints: tuple[str, ...]
    normal: Any
    sliding_velocity: tuple[Any, ...]
    force: tuple[Any, ...]
    generalized: tuple[Any, ...]
    valid_while: Any


def friction_term(friction: Friction, problem: Problem, model: Model) -> FrictionTerm:
    """The friction force of one contact, with its normal force left as the symbol ``N_<name>``."""
    from lagsolve.mechanics.simplify import norm

    particle = problem.particle(friction.on)
    jac = position_jacobian(particle.position, model)
    index = {c.name: i for i, c in enumerate(problem.coordinates)}
    sliding = [index[name] for name in friction.sliding]
    velocity = sympy.zeros(jac.rows, 1)
    for i in sliding:
        velocity += jac[:, i] * model.velocities[i]
    moving = [i for i in sliding if any(v != 0 for v in jac[:, i])]
    if len(moving) == 1:
        # one sliding rate: the direction is sign(q_dot) times a unit vector, as textbooks write it
        i = moving[0]
        column = jac[:, i]
        length = norm(list(column))
        direction = column * sympy.sign(model.velocities[i]) / length
        valid_while = sympy.Ne(model.velocities[i], 0)
    else:
        speed = norm(list(velocity))
        direction = velocity / speed
        valid_while = sympy.Ne(speed, 0)
    normal = sympy.Symbol(f"N_{friction.name}", nonnegative=True)
    force = (-friction.coefficient * normal * direction).applyfunc(_clean)
    generalized = tuple(_clean((force.T * jac[:, i])[0]) for i in range(len(model.coordinates)))
    return FrictionTerm(friction.name, friction.on, friction.coefficient, friction.normal, normal,
                        tuple(velocity), tuple(force), generalized, valid_while)


def _clean(expr: Any) -> Any:
    """Cancel and reduce trigonometric identities, leaving ``sign`` alone (``simplify``
    would turn it into a Piecewise)."""
    return sympy.factor_terms(sympy.trigsimp(sympy.cancel(expr)))
