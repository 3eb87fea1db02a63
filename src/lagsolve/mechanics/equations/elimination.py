"""Dependent coordinates and velocities that the constraints give in closed form.

A holonomic constraint that is linear in some coordinate with a constant
coefficient (``y - f(x)``, ``r - z - l``, ``phi - Omega*t``) fixes that coordinate;
a velocity constraint that involves a single velocity (``theta_dot``,
``phi_dot - Omega``) fixes that velocity. Results "with the constraints used"
are written in the remaining variables, as a worked solution does.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy

from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.model import Model
from lagsolve.problem.schema import ConstraintKind


@dataclass(frozen=True)
class Elimination:
    """Substitutions ``positions`` (q_k → expression) and ``velocities`` (q̇_k → expression),
    with ``sources`` naming the constraint that gave each eliminated symbol."""

    positions: dict[Any, Any] = field(default_factory=dict)
    velocities: dict[Any, Any] = field(default_factory=dict)
    sources: dict[Any, str] = field(default_factory=dict)

    def apply(self, expr: Any) -> Any:
        """``expr`` written without the eliminated coordinates and velocities."""
        if not self.positions and not self.velocities:
            return expr
        for _ in range(len(self.positions) + len(self.velocities) + 1):
            new = expr.xreplace(self.velocities).xreplace(self.positions)
            if new == expr:
                break
            expr = new
        return expr


def _constant(expr: Any, model: Model) -> bool:
    """Free of coordinates, velocities, time and declared functions (``cos(alpha)`` counts as constant)."""
    variables = set(model.coordinates) | set(model.velocities) | {model.time}
    undeclared = expr.atoms(sympy.core.function.AppliedUndef)
    return expr != 0 and not (expr.free_symbols & variables) and not undeclared


def eliminate(constraints: tuple[ConstraintTerms, ...], model: Model) -> Elimination:
    """Pick, for each constraint, a variable it gives explicitly (the last one in input order)."""
    positions: dict[Any, Any] = {}
    velocities: dict[Any, Any] = {}
    sources: dict[Any, str] = {}
    taken: set[Any] = set()
    for c in constraints:
        if c.kind == ConstraintKind.HOLONOMIC:
            for i in reversed(range(len(model.coordinates))):
                q, a = model.coordinates[i], c.coefficients[i]
                if q in taken or not _constant(a, model) or sympy.diff(c.expression, q, 2) != 0:
                    continue
                positions[q] = sympy.expand(q - c.expression / a)
                qd = model.velocities[i]
                velocities[qd] = sympy.expand(qd - sum(
                    (aj * v for aj, v in zip(c.coefficients, model.velocities, strict=True)), c.offset) / a)
                sources[q] = c.name
                taken.add(q)
                break
        else:
            nonzero = [i for i, a in enumerate(c.coefficients) if a != 0]
            if len(nonzero) == 1 and model.coordinates[nonzero[0]] not in taken:
                i = nonzero[0]
                velocities[model.velocities[i]] = sympy.cancel(-c.offset / c.coefficients[i])
                sources[model.velocities[i]] = c.name
                taken.add(model.coordinates[i])
    return Elimination(positions, velocities, sources)
