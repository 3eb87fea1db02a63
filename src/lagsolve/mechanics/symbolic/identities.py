"""Deciding whether an expression vanishes identically — proofs, not display.

The analysis makes claims (a constraint is integrable, a quantity is conserved, two
routes agree) that rest on some expression being identically zero. :func:`zero_status`
answers in three ways: proved zero by exact rewriting (``cancel``, then the display
simplifier :func:`~lagsolve.mechanics.symbolic.simplify.tidy`, which knows sin² + cos² = 1),
proved non-zero by a numeric value at a random point, or undecided (numerically zero
everywhere we looked, but not proved). Callers claim a result only on a proof.
"""

from __future__ import annotations

import random
from enum import Enum
from typing import Any

import sympy

from lagsolve.mechanics.symbolic.simplify import pythagoras, reduce_squares, tidy

#: concrete smooth functions standing in for declared functions in numeric probes
_PROBES = (lambda u: sympy.sin(u) + u**2 / 3, lambda u: sympy.exp(u / 2) - u, lambda u: u**3 / 5 + sympy.cos(u))


class Zero(Enum):
    """Outcome of :func:`zero_status`."""

    PROVED = "proved zero"
    NONZERO = "non-zero"
    UNDECIDED = "numerically zero, not proved"


def zero_status(expr: Any, *, samples: int = 6, seed: int = 3) -> Zero:
    """Whether ``expr`` is identically zero.

    Tries ``expr == 0``, ``cancel(expr) == 0`` and ``tidy(expr) == 0`` (exact identities), the
    last two again with compound angles expanded (``cos(θ1 − θ2)``);
    when none holds, evaluates ``expr`` at ``samples`` random points (positive symbols get
    positive values, declared functions concrete bodies): a value clearly away from zero
    proves it non-zero, otherwise the answer is :attr:`Zero.UNDECIDED`.

    >>> import sympy
    >>> th = sympy.Symbol("theta", real=True)
    >>> zero_status(sympy.sin(th)**2 + sympy.cos(th)**2 - 1)
    <Zero.PROVED: 'proved zero'>
    >>> zero_status(sympy.sin(th)**2 - 1)
    <Zero.NONZERO: 'non-zero'>
    """
    if not isinstance(expr, sympy.Basic):
        return Zero.PROVED if expr == 0 else Zero.NONZERO
    if expr == 0:
        return Zero.PROVED
    if not numerically_zero(expr, samples=1, seed=seed):
        # the first of the probes below, taken first: it settles a non-zero expression without ``cancel``
        return Zero.NONZERO
    if _polynomial(expr) and sympy.expand(expr) == 0:
        return Zero.PROVED  # a polynomial in its atoms that expands to 0: what cancel finds, for less
    try:
        if sympy.cancel(expr) == 0:
            return Zero.PROVED
    except (sympy.PolynomialError, ValueError, TypeError):
        pass
    if not numerically_zero(expr, samples=samples, seed=seed):
        return Zero.NONZERO  # a value away from zero is proof enough, and cheaper than the rewritings below
    if expr.has(sympy.sign):
        expr = split_signs(expr)
        if expr == 0:
            return Zero.PROVED
    forms = [expr]
    if any(not f.args[0].is_Symbol for f in expr.atoms(sympy.sin, sympy.cos)):
        # cos(θ1 − θ2) and the like (the solve keeps them): expand into single angles, then try again
        forms.append(sympy.expand_trig(expr))
    try:
        # the numerator with every cos² written 1 − sin², expanded: each step an identity, so 0 is a proof,
        # and much cheaper than the simplifier's search (a friction problem's reduced equations: 3 s → 0.1 s)
        if any(reduce_squares(sympy.fraction(sympy.cancel(f))[0], sympy.cos, sympy.sin) == 0 for f in forms):
            return Zero.PROVED
    except (sympy.PolynomialError, ValueError, TypeError):
        pass
    if tidy(expr) == 0:
        return Zero.PROVED
    try:
        # sin² + cos² = 1 both ways, also on expressions too large for the display simplifier
        if any(sympy.cancel(f) == 0 or any(p == 0 for p in pythagoras(f)) for f in forms[1:] + forms[:1]):
            return Zero.PROVED
    except (sympy.PolynomialError, ValueError, TypeError):
        pass
    return Zero.UNDECIDED


def split_signs(expr: Any) -> Any:
    """``expr`` with each sign(a b) written sign(a) sign(b) (the factors of ``factor_terms(a)``, a number's sign
    evaluated) and then sign(a)² as 1: identities wherever no factor is zero, so an expression they take to 0
    vanishes identically as a function. The friction of a wedge's face, sign((Ẋ − ẋ) cos α) sign(cos α) in one
    route and sign(Ẋ − ẋ) in the other, then agree."""

    def split(arg: Any) -> Any:
        out = sympy.Integer(1)
        for f in sympy.Mul.make_args(sympy.factor_terms(arg)):
            if f.is_number:
                out *= sympy.sign(f)
            else:
                base, exp = f.as_base_exp()
                out *= sympy.sign(base) ** exp if exp.is_Integer else sympy.sign(f)
        return out

    split_form = expr.replace(lambda e: isinstance(e, sympy.sign), lambda e: split(e.args[0]))
    return split_form.replace(lambda e: e.is_Pow and isinstance(e.base, sympy.sign) and e.exp.is_Integer
                              and e.base.args[0].is_extended_real, lambda e: e.base ** (int(e.exp) % 2))


def _polynomial(expr: Any) -> bool:
    """No power in ``expr`` divides by, or takes a root of, something that varies."""
    return not any(p.exp.is_negative or not p.exp.is_Integer for p in expr.atoms(sympy.Pow)
                   if not p.base.is_number)


def proved_zero(expr: Any) -> bool:
    """``expr`` is identically zero, by exact rewriting (see :func:`zero_status`)."""
    return zero_status(expr) is Zero.PROVED


def numerically_zero(expr: Any, *, samples: int = 6, seed: int = 3, tol: float = 1e-10) -> bool:
    """``expr`` is below ``tol`` (relative to its terms' size) at ``samples`` random points."""
    functions = sorted(expr.atoms(sympy.core.function.AppliedUndef), key=sympy.default_sort_key)
    kinds = sorted({f.func for f in functions}, key=str)
    rng = random.Random(seed)
    symbols = sorted(expr.free_symbols, key=sympy.default_sort_key)
    terms = sympy.Add.make_args(expr)
    # doit evaluates derivatives (of the probes put in for declared functions) and other unevaluated objects; a
    # plain expression has none, and doit would only rebuild it (half the cost of a probe)
    unevaluated = bool(kinds) or expr.has(sympy.Derivative, sympy.Integral, sympy.Sum, sympy.Product, sympy.Subs)

    def settle(e: Any) -> Any:
        return e.doit() if unevaluated else e

    for k in range(samples):
        concrete = expr
        scale_terms = list(terms)
        for i, fn in enumerate(kinds):
            body = _PROBES[(i + k) % len(_PROBES)]
            u = sympy.Dummy("u")
            concrete = concrete.replace(fn, sympy.Lambda(u, body(u)))
            scale_terms = [t.replace(fn, sympy.Lambda(u, body(u))) for t in scale_terms]
        point = {s: sympy.Rational(rng.randint(5, 20) if s.is_positive else rng.randint(-20, 20), 10) or
                 sympy.Rational(7, 10) for s in symbols}
        try:
            value = complex(sympy.N(settle(concrete).xreplace(point), 30))
            scale = sum(abs(complex(sympy.N(settle(t).xreplace(point), 30))) for t in scale_terms)
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if value != value:  # NaN: a singular point, try another
            continue
        if abs(value) > tol * max(1.0, scale):
            return False
    return True
