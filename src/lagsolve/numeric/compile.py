"""Compile SymPy expressions of the state into fast NumPy callables.

Plain inputs only (style rule 6): expressions and ordered symbol lists, so this
module can be tested alone. Every function compiled here has the signature
``f(t, q, qd, p) -> ndarray`` with ``q``, ``qd`` and ``p`` 1-D arrays in the
documented orders (coordinates, velocities, parameters).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
import sympy

StateFunction = Callable[[float, np.ndarray, np.ndarray, np.ndarray], np.ndarray]


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


_MODULES: list[Any] = [{"sign": _sign, "Abs": abs, "Heaviside": lambda x: float(x > 0)}, "math"]


def substitute_functions(expr: Any, concrete: Mapping[Any, tuple[tuple[Any, ...], Any]]) -> Any:
    """Replace declared functions by concrete ones and evaluate their derivatives.

    ``concrete`` maps a SymPy function class ``f`` to ``(arguments, body)``, e.g.
    ``(u,), u**2/2`` for ``"f(u)": "u**2/2"``; ``Derivative(f(x), x)`` becomes ``x``.

    >>> import sympy
    >>> x, u = sympy.symbols("x u"); f = sympy.Function("f")
    >>> substitute_functions(sympy.diff(f(x), x) + f(x), {f: ((u,), u**2/2)})
    x**2/2 + x
    """
    for fn, (arguments, body) in concrete.items():
        expr = expr.replace(fn, sympy.Lambda(arguments, body))
    return expr.doit() if expr.has(sympy.Derivative, sympy.Subs) else expr


def compile_state_function(expressions: Sequence[Any], *, time: Any, coordinates: Sequence[Any],
                           velocities: Sequence[Any], parameters: Sequence[Any]) -> StateFunction:
    """One callable evaluating all ``expressions`` at a state, as a flat float array.

    Common subexpressions are shared (``lambdify(..., cse=True)``); scalar maths
    uses the ``math`` module, which is faster than NumPy on scalars.
    """
    n, k = len(coordinates), len(parameters)
    arguments = [time, *coordinates, *velocities, *parameters]
    stray = set().union(*(getattr(e, "free_symbols", set()) for e in expressions)) - set(arguments)
    if stray:
        raise ValueError(f"expressions contain symbols with no value: {sorted(map(str, stray))}")
    if not expressions:
        return lambda t, q, qd, p: np.zeros(0)
    raw = sympy.lambdify(arguments, list(expressions), modules=_MODULES, cse=True)

    def evaluate(t: float, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        return np.asarray(raw(t, *q, *qd, *p), dtype=float)

    evaluate.__doc__ = f"{len(expressions)} expressions of {n} coordinates, {n} velocities and {k} parameters"
    return evaluate
