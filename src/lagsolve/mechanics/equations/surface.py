r"""States on the constraint surface, written symbolically: one owner for both views the mechanics uses.

* :func:`constraint_surface` — velocity level only: each constraint :math:`\mathbf a\cdot\dot q + b = 0`
  solved for one velocity (the simplest non-zero coefficient). The conserved quantities are verified
  with it (:mod:`lagsolve.mechanics.analysis.conserved`), where coordinates stay free.
* :class:`Surface` — positions and velocities: the dependent coordinates and velocities from the
  elimination (:mod:`lagsolve.mechanics.equations.elimination`), then the velocities the remaining velocity
  forms fix; with a test for "zero on the surface", symbolic then at random points. The normal
  forces of friction are decided with it (:mod:`lagsolve.mechanics.solution.normal`).

* :func:`newton` — numerically: the one Newton iteration that puts a state on
  :math:`\psi(q, t) = 0`, :math:`q \leftarrow q - J^{+}\psi`. Its callers supply the arithmetic: floats
  and a least-squares step (:mod:`lagsolve.mechanics.equations.regularity`'s random states,
  :mod:`lagsolve.numeric.initial`'s initial state), or 30-digit mpmath numbers and an LU step
  (:mod:`lagsolve.check.states`' random states for comparing answers).
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Iterable, Sequence
from typing import Any

import sympy

from lagsolve.mechanics.equations.constraints import ConstraintTerms, velocity_form
from lagsolve.mechanics.equations.elimination import Elimination
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.symbolic.points import random_point
from lagsolve.mechanics.symbolic.simplify import tidy


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
        values = random_point(symbols, rng)
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


#: what a linear solve may raise at a singular or non-finite Jacobian (NumPy's LinAlgError is a ValueError)
SOLVE_ERRORS = (ArithmeticError, ValueError, TypeError)


def newton(residual: Callable[[list[Any]], Iterable[Any]], jacobian: Callable[[list[Any]], Any],
           start: Iterable[Any], *, step: Callable[[Any, Sequence[Any]], Iterable[Any]], tolerance: Any,
           iterations: int = 60, bound: float = math.inf) -> tuple[list[Any], bool]:
    r"""Newton's iteration :math:`x \leftarrow x - \mathrm{step}(J(x), \psi(x))` from ``start`` until
    :math:`\max_j|\psi_j| <` ``tolerance``: the state reached and whether it converged. It stops, not
    converged, at a residual that is not a finite real number, a ``step`` that fails, or a component
    beyond ``bound``. ``step`` is the linear solve (least squares for a least-norm step, LU for a square
    one), so the same iteration serves floats and mpmath numbers.

    >>> import numpy as np
    >>> x, ok = newton(lambda x: [x[0] ** 2 - 2], lambda x: np.array([[2 * x[0]]]), [1.0],
    ...                step=lambda J, r: np.linalg.lstsq(J, np.array(r), rcond=None)[0], tolerance=1e-12)
    >>> print(ok, f"{x[0]:.12f}")
    True 1.414213562373
    """
    x = list(start)
    for _ in range(iterations):
        try:
            psi = list(residual(x))
            if not all(_finite(v) for v in psi):
                return x, False
            if max((abs(v) for v in psi), default=0.0) < tolerance:
                return x, True
            delta = step(jacobian(x), psi)
        except SOLVE_ERRORS:
            return x, False
        x = [a - d for a, d in zip(x, delta, strict=True)]
        if not all(_finite(v) and abs(v) <= bound for v in x):
            return x, False
    return x, False


def least_squares(jacobian: Any, residual: Sequence[Any]) -> Any:
    """The least-norm step of :func:`newton` in floating point (NumPy's ``lstsq``)."""
    import numpy as np

    return np.linalg.lstsq(np.asarray(jacobian, dtype=float), np.asarray(residual, dtype=float), rcond=None)[0]


def _finite(value: Any) -> bool:
    """``value`` is a finite real number (a float, a NumPy float or an mpmath mpf)."""
    try:
        return math.isfinite(value) if not hasattr(value, "imag") or value.imag == 0 else False
    except TypeError:
        return False
