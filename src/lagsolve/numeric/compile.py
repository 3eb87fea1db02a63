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


BACKENDS = ("auto", "llvm", "python")


def private_arguments(arguments: Sequence[Any], expressions: Sequence[Any]) -> tuple[list[Any], list[Any]]:
    """The arguments renamed ``_lagsolve_arg0``, ``_lagsolve_arg1``, ... in order, and the expressions in them.

    Compilers with common-subexpression elimination name their temporaries ``x0, x1, ...``;
    SymEngine's ``Lambdify(cse=True)`` does not avoid the names already in use, so a
    coordinate called ``x1`` would silently take a temporary's value. A user's name starts
    with a letter (``problem/expr.py``), so these names cannot be one. Each new symbol keeps
    the assumptions of the one it replaces, so nothing evaluates differently.

    >>> import sympy
    >>> x1, x0 = sympy.symbols("x1 x0")
    >>> private_arguments([x1, x0], [x1 + 2 * x0])
    ([_lagsolve_arg0, _lagsolve_arg1], [_lagsolve_arg0 + 2*_lagsolve_arg1])
    """
    renamed = [sympy.Symbol(f"_lagsolve_arg{i}", **a.assumptions0) for i, a in enumerate(arguments)]
    mapping = dict(zip(arguments, renamed, strict=True))
    return renamed, [e.xreplace(mapping) if isinstance(e, sympy.Basic) else e for e in expressions]


def compile_state_function(expressions: Sequence[Any], *, time: Any, coordinates: Sequence[Any],
                           velocities: Sequence[Any], parameters: Sequence[Any],
                           backend: str = "auto") -> StateFunction:
    """One callable evaluating all ``expressions`` at a state, as a flat float array.

    ``backend="llvm"`` compiles to machine code with SymEngine's LLVM JIT (common
    subexpressions shared; about a microsecond per call); ``"python"`` uses
    ``sympy.lambdify(..., cse=True)`` with the ``math`` module; ``"auto"`` (default)
    tries LLVM and falls back to Python when SymEngine or LLVM is missing or an
    expression is not supported.
    """
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend {backend!r}")
    n, k = len(coordinates), len(parameters)
    arguments = [time, *coordinates, *velocities, *parameters]
    stray = set().union(*(getattr(e, "free_symbols", set()) for e in expressions)) - set(arguments)
    if stray:
        raise ValueError(f"expressions contain symbols with no value: {sorted(map(str, stray))}")
    if not expressions:
        return lambda t, q, qd, p: np.zeros(0)
    arguments, expressions = private_arguments(arguments, expressions)
    if backend != "python":
        compiled = _llvm(arguments, expressions, n, k)
        if compiled is not None:
            return compiled
        if backend == "llvm":
            raise ValueError("the LLVM backend is not available (SymEngine with LLVM is needed)")
    raw = sympy.lambdify(arguments, list(expressions), modules=_MODULES, cse=True)

    def evaluate(t: float, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        try:
            return np.asarray(raw(t, *q, *qd, *p), dtype=float)
        except (ValueError, ZeroDivisionError, OverflowError):  # outside a domain: NaN, as the LLVM backend gives
            return np.full(len(expressions), np.nan)

    evaluate.__doc__ = f"{len(expressions)} expressions of {n} coordinates, {n} velocities and {k} parameters"
    return evaluate


def _llvm(arguments: list[Any], expressions: Sequence[Any], n: int, k: int) -> StateFunction | None:
    """The expressions as one LLVM-compiled function, or None when that cannot be done here."""
    try:
        from symengine.lib.symengine_wrapper import Lambdify, sympy2symengine
    except ImportError:
        return None
    try:
        compiled = Lambdify([sympy2symengine(a) for a in arguments],
                            [sympy2symengine(sympy.Float(e) if isinstance(e, float) else e) for e in expressions],
                            backend="llvm", cse=True, real=True)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return None
    size = len(expressions)
    buffer = np.zeros(1 + 2 * n + k)

    def evaluate(t: float, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        buffer[0] = t
        buffer[1: 1 + n] = q
        buffer[1 + n: 1 + 2 * n] = qd
        buffer[1 + 2 * n:] = p
        out = np.empty(size)
        compiled.unsafe_real(buffer, out)
        return out

    return evaluate
