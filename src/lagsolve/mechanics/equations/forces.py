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

from lagsolve.mechanics.equations.model import Model
from lagsolve.problem.schema import Problem


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
