r"""States on the constraint surface, written symbolically: one owner for both views the mechanics uses.

* :func:`constraint_surface` — velocity level only: each constraint :math:`\mathbf a\cdot\dot q + b = 0`
  solved for one velocity (the simplest non-zero coefficient). The conserved quantities are verified
  with it (:mod:`lagsolve.mechanics.conserved`), where coordinates stay free.
* :class:`Surface` — positions and velocities: the dependent coordinates and velocities from the
  elimination (:mod:`lagsolve.mechanics.elimination`), then the velocities the remaining velocity
  forms fix; with a test for "zero on the surface", symbolic then at random points. The normal
  forces of friction are decided with it (:mod:`lagsolve.mechanics.normal`).

Numeric states on the surface are found where they are used: :mod:`lagsolve.check.states` (random
states for comparing answers), :mod:`lagsolve.mechanics.regularity` (random states for the
regularity test) and :mod:`lagsolve.numeric.initial` (completing a simulation's initial state).
"""

from __future__ import annotations

import random
from typing import Any

import sympy

from lagsolve.mechanics.constraints import ConstraintTerms, velocity_form
from lagsolve.mechanics.elimination import Elimination
from lagsolve.mechanics.model import Model
from lagsolve.mechanics.simplify import tidy


def on_surface(expr: Any, surface: dict[Any, Any]) -> Any:
    """``expr`` with the velocities of ``surface`` (:func:`constraint_surface`) put in, until nothing changes."""
    for _ in range(len(surface) + 1):
        new = expr.xreplace(surface)
        if new == expr:
            break
        expr = new
    return expr


def constraint_surface(constraints: tuple[ConstraintTerms, ...], model: Model) -> dict[Any, Any]:
    """One velocity per constraint in terms of the others (the simplest non-zero coefficient)."""
    surface: dict[Any, Any] = {}
    for c in constraints:
        rate = on_surface(sum((a * v for a, v in zip(c.coefficients, model.velocities, strict=True)), c.offset),
                          surface)
        options = [(sympy.count_ops(sympy.diff(rate, v)), -i, v) for i, v in enumerate(model.velocities)
                   if v not in surface and sympy.diff(rate, v) != 0]
        if not options:
            continue
        _, _, v = min(options, key=lambda o: (o[0], o[1]))
        surface[v] = sympy.cancel(v - rate / sympy.diff(rate, v))
    return surface


class Surface:
    """Writes expressions on the constraint surface: dependent coordinates and velocities from the
    elimination, then the velocities that the remaining velocity forms fix (solved linearly)."""

    def __init__(self, constraints: tuple[ConstraintTerms, ...], model: Model, elimination: Elimination) -> None:
        self.elimination = elimination
        self.model = model
        free = [v for v in model.velocities if v not in elimination.velocities]
        self.velocities: dict[Any, Any] = {}
        for c in constraints:
            form = sympy.expand(elimination.apply(velocity_form(c, model)).xreplace(self.velocities))
            if form == 0:
                continue
            for v in reversed(free):
                coefficient = sympy.diff(form, v)
                if coefficient != 0 and not coefficient.has(*model.velocities):
                    solved = sympy.cancel(v - form / coefficient)
                    self.velocities = {k: e.xreplace({v: solved}) for k, e in self.velocities.items()}
                    self.velocities[v] = solved
                    free.remove(v)
                    break

    def apply(self, expr: Any) -> Any:
        return self.elimination.apply(expr).xreplace(self.velocities)

    def is_zero(self, expr: Any) -> bool:
        """True when ``expr`` vanishes on the surface: symbolically, or else at random points (the
        positions need not satisfy the holonomic constraints the elimination does not solve:
        a friction force tangent to the surface is orthogonal to it for any velocity on it)."""
        if expr == 0:
            return True
        on = self.apply(expr)
        if tidy(on) == 0:
            return True
        return _numerically_zero(on, self.model)


def _numerically_zero(expr: Any, model: Model, points: int = 6) -> bool:
    rng = random.Random(12)
    concrete = expr.replace(lambda e: isinstance(e, sympy.core.function.AppliedUndef),
                            lambda e: sympy.sin(sum(e.args, sympy.Integer(0))) + 2)
    concrete = concrete.doit()
    symbols = sorted(concrete.free_symbols, key=sympy.default_sort_key)
    if not symbols:
        return bool(abs(complex(concrete)) < 1e-12)
    compiled = sympy.lambdify(symbols, concrete, modules="mpmath")
    seen = 0
    for _ in range(4 * points):
        values = [rng.uniform(0.5, 2.0) if s.is_positive else rng.uniform(-2.0, 2.0) for s in symbols]
        try:
            value = complex(compiled(*values))
        except (ZeroDivisionError, ValueError, TypeError, OverflowError):
            continue
        if value != value:  # nan
            continue
        if abs(value) > 1e-10:
            return False
        seen += 1
        if seen >= points:
            return True
    return False
