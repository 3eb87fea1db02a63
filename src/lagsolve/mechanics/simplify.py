"""Display simplification toward textbook form — the one place results are simplified.

Derivation keeps expressions in matrix form without ``simplify``; only the
results shown to people (accelerations, multipliers, forces, equations) pass
through :func:`tidy`, which tries a few rewritings and keeps the smallest.
The overall time budget is enforced by :mod:`lagsolve.budget` (a child process),
because SymPy's long loops cannot be interrupted from inside.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy

#: above this many operations the expensive general ``simplify`` is skipped
SIMPLIFY_LIMIT = 400


_TRIG = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)


def measure(expr: Any) -> tuple[int, int, str]:
    """Ordering used to pick the nicest form: fewer operations (a multiple-angle
    ``sin(2*theta)`` counts extra, as textbooks write ``sin(theta)*cos(theta)``),
    then shorter text, then the text itself (so ties break deterministically)."""
    text = sympy.sstr(expr)
    compound = sum(1 for f in expr.atoms(*_TRIG) if not f.args[0].is_Symbol)
    return (sympy.count_ops(expr) + 3 * compound, len(text), text)


def tidy(expr: Any) -> Any:
    """A short, factored form of ``expr`` (deterministic: ties break on the printed text).

    >>> import sympy
    >>> x, g = sympy.symbols("x g")
    >>> tidy((g*x + g)/(x + 1) + x**2 - x*(x - 1))
    g + x
    """
    expr = sympy.sympify(expr)
    if expr.is_Number or expr.is_Symbol:
        return expr
    candidates: list[Any] = [expr]
    steps: list[Callable[[Any], Any]] = [sympy.cancel, sympy.factor_terms, lambda e: sympy.factor(sympy.cancel(e))]
    if expr.has(*_TRIG):
        steps.append(lambda e: sympy.factor(sympy.trigsimp(sympy.cancel(e))))
        steps.append(lambda e: sympy.factor(sympy.expand_trig(sympy.trigsimp(sympy.cancel(e)))))
    for step in steps:
        try:
            candidates.append(step(expr))
        except (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
            continue
    best = min(candidates, key=measure)
    if sympy.count_ops(best) <= SIMPLIFY_LIMIT:
        try:
            candidates.append(sympy.simplify(best))
        except (ValueError, TypeError):
            pass
    return min(candidates, key=measure)


def tidy_sum(expr: Any) -> Any:
    """A sum of simple terms (for equations and energies): expanded, trig-reduced,
    single angles, with a common factor pulled out when there is one."""
    expr = sympy.sympify(expr)
    expanded = sympy.expand(expr)
    candidates = [expanded]
    if expanded.has(*_TRIG):
        reduced = sympy.trigsimp(expanded)
        candidates += [reduced, sympy.expand(sympy.expand_trig(reduced))]
    candidates += [sympy.factor_terms(c) for c in candidates]
    return min(candidates, key=measure)


def tidy_abs(expr: Any) -> Any:
    """Pull factors of known sign out of every ``Abs``: ``Abs(m*X/(1 + f'(x)**2))`` → ``m*Abs(X)/(1 + f'(x)**2)``.

    Derivatives and declared functions are treated as real (they are, in every
    problem: coordinates, parameters and declared functions are real).

    >>> import sympy
    >>> m = sympy.Symbol("m", positive=True); x = sympy.Symbol("x", real=True)
    >>> tidy_abs(sympy.Abs(-m*x/(x**2 + 1)))
    m*Abs(x)/(x**2 + 1)
    """

    def fix(node: Any) -> Any:
        arg = sympy.factor(node.args[0])
        atoms = sorted(arg.atoms(sympy.Derivative, sympy.core.function.AppliedUndef), key=sympy.default_sort_key)
        reals = {atom: sympy.Dummy(f"r{i}", real=True) for i, atom in enumerate(atoms)}
        back = {v: k for k, v in reals.items()}
        outside, inside = sympy.Integer(1), sympy.Integer(1)
        for factor in sympy.Mul.make_args(arg.xreplace(reals)):
            if factor.is_nonnegative:
                outside *= factor
            elif factor.is_nonpositive:
                outside *= -factor
            else:
                inside *= factor
        return (outside * sympy.Abs(inside)).xreplace(back)

    return expr.replace(lambda e: isinstance(e, sympy.Abs), fix)


def norm(components: tuple[Any, ...] | list[Any]) -> Any:
    """Euclidean length of a vector, simplified: ``sqrt`` of a square becomes ``Abs``.

    >>> import sympy
    >>> m = sympy.Symbol("m", positive=True); v, th = sympy.symbols("v theta", real=True)
    >>> norm([-2*m*v*sympy.sin(th), 2*m*v*sympy.cos(th)])
    2*m*Abs(v)
    """
    square = tidy(sum((c**2 for c in components), sympy.Integer(0)))
    atoms = sorted(square.atoms(sympy.Derivative, sympy.core.function.AppliedUndef), key=sympy.default_sort_key)
    reals = {atom: sympy.Dummy(f"r{i}", real=True) for i, atom in enumerate(atoms)}
    root = sympy.sqrt(sympy.factor(square.xreplace(reals)))
    root = root.xreplace({v: k for k, v in reals.items()})
    return min([root, tidy_abs(root), tidy(tidy_abs(root))], key=measure)
