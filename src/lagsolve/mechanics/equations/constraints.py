r"""Constraint coefficients in the form :math:`\sum_i a_{ji}\dot q_i + b_j = 0`.

Holonomic :math:`\psi_j(q, t) = 0` gives :math:`a_{ji} = \partial\psi_j/\partial q_i`,
:math:`b_j = \partial\psi_j/\partial t`. A velocity (nonholonomic) constraint is read as
the user wrote it: :math:`a_{ji} = \partial g_j/\partial\dot q_i`, :math:`b_j = g_j|_{\dot q=0}`.
Differentiating once more gives the acceleration-level form used in the augmented
system, :math:`\sum_i a_{ji}\ddot q_i = \beta_j` with
:math:`\beta_j = -\big(\sum_i \dot a_{ji}\dot q_i + \dot b_j\big)`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.equations.model import Model
from lagsolve.problem.schema import Constraint, ConstraintKind


@dataclass(frozen=True)
class ConstraintTerms:
    """One constraint with its coefficients.

    ``coefficients`` is the row :math:`a_j` (one entry per coordinate), ``offset``
    is :math:`b_j`, ``acceleration_rhs`` is :math:`\\beta_j`, and ``multiplier`` the
    symbol :math:`\\lambda_j` (named ``lambda_<constraint>``).
    """

    name: str
    kind: ConstraintKind
    expression: Any
    on: tuple[str, ...]
    coefficients: tuple[Any, ...]
    offset: Any
    acceleration_rhs: Any
    multiplier: Any


def constraint_terms(constraint: Constraint, model: Model) -> ConstraintTerms:
    """Coefficients of one constraint (see the module docstring for the conventions)."""
    psi = constraint.expression
    if constraint.kind == ConstraintKind.HOLONOMIC:
        a = tuple(sympy.diff(psi, q) for q in model.coordinates)
        b = sympy.diff(psi, model.time)
    else:
        a = tuple(sympy.diff(psi, qd) for qd in model.velocities)
        b = psi.xreplace({qd: 0 for qd in model.velocities})
    rate = sum(model.time_derivative(aj) * qd for aj, qd in zip(a, model.velocities, strict=True))
    beta = -(rate + model.time_derivative(b))
    multiplier = sympy.Symbol(f"lambda_{constraint.name}", real=True)
    return ConstraintTerms(constraint.name, constraint.kind, psi, constraint.on, a, b, beta, multiplier)


def velocity_form(terms: ConstraintTerms, model: Model) -> Any:
    r""":math:`\sum_i a_{ji}\dot q_i + b_j` (zero along every admissible motion)."""
    return sum((a * qd for a, qd in zip(terms.coefficients, model.velocities, strict=True)), terms.offset)
