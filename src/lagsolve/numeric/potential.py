"""The effective potential in numbers, for its figure.

:func:`potential_curve` samples a derivation's effective potential at numeric parameter values and
the conserved momenta (or the initial state they follow from), and finds its equilibria on the
grid; :func:`lagsolve.render.potential_plot.potential_figure` draws the result.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

if TYPE_CHECKING:

    from lagsolve.mechanics.analysis.equilibria import EffectivePotential, Equilibrium
    from lagsolve.mechanics.derivation import Derivation


@dataclass(frozen=True)
class PotentialCurve:
    """Samples of V_eff: ``q`` and ``v`` (same length), equilibria as (q0, V_eff(q0), stable), and the
    ``coordinate`` in LaTeX (for the axis label)."""

    coordinate: str
    q: tuple[float, ...]
    v: tuple[float, ...]
    equilibria: tuple[tuple[float, float, bool | None], ...]


def potential_curve(derivation: Derivation, values: Mapping[str, float], momenta: Mapping[str, float] | None = None,
                    *, initial: Mapping[str, float] | None = None, span: tuple[float, float] | None = None,
                    samples: int = 400) -> PotentialCurve:
    """Numbers for :func:`potential_figure` from ``derivation.analysis.effective_potential``.

    ``values`` give the parameters; ``momenta`` the symbols ``p_<q>`` (by name), or else
    they are evaluated from ``initial`` (coordinates and velocities). ``span`` is the
    coordinate range, by default around the equilibria.

    Raises
    ------
    ValueError
        No effective potential, or a value is missing.
    """
    analysis = derivation.analysis
    effective = analysis.effective_potential if analysis is not None else None
    if effective is None:
        raise ValueError("this derivation has no effective potential")
    numbers = _numbers(derivation, effective, values, momenta, initial)
    q = effective.coordinate
    expression = effective.expression.xreplace(numbers)
    missing = expression.free_symbols - {q}
    if missing:
        raise ValueError(f"no value for {', '.join(sorted(map(str, missing)))}")
    function = sympy.lambdify(q, expression, "math", dummify=True)
    points = _symbolic_equilibria(effective.equilibria, numbers, function)
    low, high = _range(q, expression, points, span)
    grid, curve = _samples(function, low, high, samples)
    if any(e.value is None for e in effective.equilibria):
        points += _numeric_equilibria(q, expression, grid)
    return PotentialCurve(sympy.latex(q), tuple(grid), tuple(curve), tuple(sorted(points, key=lambda p: p[0])))


def _numbers(derivation: Derivation, effective: EffectivePotential, values: Mapping[str, float],
             momenta: Mapping[str, float] | None, initial: Mapping[str, float] | None) -> dict[Any, float]:
    """The value of each parameter symbol and of each conserved momentum ``p_<q>`` of the ``effective``
    potential: given, or evaluated from ``initial``."""
    numbers: dict[Any, float] = {p.symbol: float(values[p.name]) for p in derivation.problem.parameters
                                 if p.name in values}
    momenta = dict(momenta or {})
    for _, p, _ in effective.cyclic:
        if p.name not in momenta:
            if initial is None:
                raise ValueError(f"no value for {p.name}: give it, or the initial state")
            quantity = next(c for c in derivation.analysis.conservation.quantities if c.name == p.name)
            state = {s: float(initial[s.name]) for s in quantity.expression.free_symbols if s.name in initial}
            momenta[p.name] = float(quantity.expression.xreplace({**numbers, **state}))
        numbers[p] = float(momenta[p.name])
    return numbers


def _symbolic_equilibria(equilibria: tuple[Equilibrium, ...], numbers: dict[Any, float],
                         function: Any) -> list[tuple[float, float, bool | None]]:
    """(q0, V_eff(q0), stable) of each equilibrium known in closed form that is real at ``numbers``; stable
    is None where its stability is not known."""
    points = []
    for e in equilibria:
        if e.value is None:
            continue
        try:
            q0 = float(e.value.xreplace(numbers))
            stable = e.stable
            if stable is None and e.stability_condition is not None:
                stable = bool(e.stability_condition.xreplace(numbers))
            points.append((q0, float(function(q0)), stable))
        except (TypeError, ValueError, ZeroDivisionError, OverflowError):
            continue  # not real for these values
    return points


def _range(q: Any, expression: Any, points: list[tuple[float, float, bool | None]],
           span: tuple[float, float] | None) -> tuple[float, float]:
    """The coordinate's range: ``span`` if given, a full turn for an angle (a coordinate inside sin, cos or
    tan), else around the equilibria."""
    if span is not None:
        return span
    if any(f.args[0] == q for f in expression.atoms(sympy.sin, sympy.cos, sympy.tan)):
        return -math.pi, math.pi
    return _span([p[0] for p in points], bool(q.is_positive))


def _samples(function: Any, low: float, high: float, samples: int) -> tuple[list[float], list[float]]:
    """``samples`` evenly spaced points from ``low`` to ``high`` and V_eff there, leaving out those where it
    is undefined or not finite."""
    grid, curve = [], []
    for k in range(samples):
        x = low + (high - low) * k / (samples - 1)
        try:
            y = float(function(x))
        except (ValueError, ZeroDivisionError, OverflowError):
            continue
        if math.isfinite(y):
            grid.append(x)
            curve.append(y)
    return grid, curve


def _numeric_equilibria(q: Any, expression: Any, grid: list[float]) -> list[tuple[float, float, bool | None]]:
    """Zeros of V_eff' between grid points where it changes sign (bisection), for equilibria
    known only as a condition."""
    slope = sympy.lambdify(q, sympy.diff(expression, q), "math", dummify=True)
    curvature = sympy.lambdify(q, sympy.diff(expression, q, 2), "math", dummify=True)
    function = sympy.lambdify(q, expression, "math", dummify=True)
    found = []
    for a, b in zip(grid, grid[1:], strict=False):
        try:
            fa, fb = slope(a), slope(b)
        except (ValueError, ZeroDivisionError, OverflowError):
            continue
        if fa == 0 or fa * fb > 0:
            continue
        scale = max(abs(fa), abs(fb))
        try:
            for _ in range(60):
                middle = (a + b) / 2
                fm = slope(middle)
                if fa * fm <= 0:
                    b = middle
                else:
                    a, fa = middle, fm
            x = (a + b) / 2
            if abs(slope(x)) > 1e-6 * scale:
                continue  # a pole of V_eff', not a zero
            c = curvature(x)
            found.append((x, float(function(x)), True if c > 0 else (False if c < 0 else None)))
        except (ValueError, ZeroDivisionError, OverflowError):
            continue
    return found


def _span(centres: list[float], positive: bool) -> tuple[float, float]:
    if not centres:
        return (0.05, 3.0) if positive else (-math.pi, math.pi)
    low, high = min(centres), max(centres)
    if positive:
        return 0.3 * low, 3.0 * high
    width = max(1.0, high - low)
    return low - 0.75 * width, high + 0.75 * width
