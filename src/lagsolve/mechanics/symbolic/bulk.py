"""The display form of a bulk system's expressions, written in SymEngine and converted once.

A chain of twenty links has thousands of terms in its expanded rates; SymPy builds each of them as an object, and
its ``TR10i`` tries the pairs of terms, so the display simplification of :func:`~lagsolve.mechanics.symbolic.
simplify.tidy_sum_light` takes seconds where the result has a few hundred terms. :func:`light` gives the same kind
of form (expanded, ``c sin²x + c cos²x`` → ``c``, products of sines and cosines contracted to functions of sums, the
common factor out) with the expansion and both rewritings done on SymEngine's sums, the terms paired by a
dictionary instead of by trying pairs, so that only the short result is built in SymPy. It is the lighter form
(:data:`~lagsolve.mechanics.symbolic.partials.BULK_SYSTEM`): a pair contracts only when its coefficients agree
(``k cos a cos b + k sin a sin b``), which is what the equations of particles on rods and bodies on hinges give.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import sympy
from sympy.core.mul import _keep_coeff

from lagsolve.mechanics.symbolic.partials import _engine, engine_converter


def light(expr: Any) -> Any | None:
    """``expr`` expanded, squares of sines and cosines of one angle summed to 1, pairs of products contracted to
    the sine or cosine of a sum or difference and the common factor out (exact: the same value), or None where
    SymEngine cannot take ``expr`` (a declared function, a float, an ``Abs``: the caller's SymPy route then)."""
    if not isinstance(expr, sympy.Basic):
        return sympy.Integer(expr)
    engine = _engine(expr)
    if engine is None:
        return None
    form, own = engine
    import symengine

    try:
        written = _contract(_unit_squares(form.expand()))
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return None
    convert = engine_converter(own)
    if not isinstance(written, symengine.Add):
        return convert(written)
    content, monomial, inner = _common_factor(written)
    parts = [convert(monomial), convert(inner)]
    if parts[0] is None or parts[1] is None:
        return None
    coefficient = sympy.Rational(content.numerator, content.denominator)
    if parts[1].is_Add and all(t.could_extract_minus_sign() for t in parts[1].args):
        # every term negative as SymPy writes it (its sin(b - a) is −sin(a − b), not SymEngine's): −1 comes out
        coefficient, parts[1] = -coefficient, sympy.Add(*[-t for t in parts[1].args])
    return _keep_coeff(coefficient, parts[0] * parts[1])


def _common_factor(written: Any) -> tuple[Fraction, Any, Any]:
    """A SymEngine sum as (its numeric content, the product of the powers every term has, the sum they leave), as
    SymPy's ``factor_terms`` writes it: the content positive (:func:`light` takes −1 out when every term is
    negative), and a fraction left inside when a term would keep an integer coefficient."""
    import symengine

    numbers: list[Fraction] = []
    common: dict[Any, Any] | None = None
    for term in written.args:
        powers = term.as_powers_dict()
        number = Fraction(1)
        for base, exponent in powers.items():
            if isinstance(base, symengine.Number):
                numerator, denominator = base.as_numer_denom()
                number *= Fraction(int(numerator), int(denominator)) ** int(exponent)
        numbers.append(number)
        bases = {b: e for b, e in powers.items()
                 if not isinstance(b, symengine.Number) and isinstance(e, int | symengine.Integer) and int(e) > 0}
        common = bases if common is None else {b: min(int(e), int(common[b])) for b, e in bases.items() if b in common}
    content = Fraction(math.gcd(*[n.numerator for n in numbers]), math.lcm(*[n.denominator for n in numbers]))
    if content.denominator != 1 and any((n / content / content.denominator).denominator == 1 for n in numbers):
        content = Fraction(content.numerator)  # a fraction stays inside while some term keeps an integer (clear=False)
    monomial = symengine.Mul(*[b ** int(e) for b, e in (common or {}).items()])
    divisor = monomial * symengine.Rational(content.numerator, content.denominator)
    return content, monomial, symengine.Add(*[t / divisor for t in written.args])


def _split(term: Any) -> tuple[Any, Any, list[Any]]:
    """A term as (its number, the product of its other factors, its sines and cosines to the first power)."""
    import symengine

    factors = term.args if isinstance(term, symengine.Mul) else (term,)
    trig = [f for f in factors if isinstance(f, symengine.sin | symengine.cos)]
    number = symengine.Mul(*[f for f in factors if isinstance(f, symengine.Number)])
    rest = symengine.Mul(*[f for f in factors if not isinstance(f, symengine.sin | symengine.cos | symengine.Number)])
    return number, rest, trig


def _unit_squares(expanded: Any) -> Any:
    """``r sin²x + r cos²x`` → ``r``, pair by pair of the terms of a SymEngine sum (every other term as it is)."""
    import symengine

    if not isinstance(expanded, symengine.Add):
        return expanded
    squares: dict[tuple[bool, Any, Any], list[int]] = {}
    terms = list(expanded.args)
    for i, term in enumerate(terms):
        for part in term.args if isinstance(term, symengine.Mul) else (term,):
            if isinstance(part, symengine.Pow) and part.args[1] == 2 and isinstance(part.args[0],
                                                                                     symengine.sin | symengine.cos):
                rest = term / part
                squares.setdefault((isinstance(part.args[0], symengine.sin), part.args[0].args[0], rest),
                                   []).append(i)
                break
    used: set[int] = set()
    extra: list[Any] = []
    for (is_sin, angle, rest), where in squares.items():
        if not is_sin:
            continue
        partners = [j for j in squares.get((False, angle, rest), []) if j not in used]
        for i, j in zip([i for i in where if i not in used], partners, strict=False):
            used.update((i, j))
            extra.append(rest)
    if not used:
        return expanded
    return symengine.Add(*[t for k, t in enumerate(terms) if k not in used], *extra)


def _contract(expanded: Any) -> Any:
    """``k r cos a cos b ± k r sin a sin b`` → ``k r cos(a ∓ b)`` and ``k r sin a cos b ± k r cos a sin b`` →
    ``k r sin(a ± b)``, ``k`` a number, ``r`` the other factors, the two terms found by a dictionary keyed by ``r`` and
    the angles. A term with other than two sines or cosines to the first power stays as it is."""
    import symengine

    if not isinstance(expanded, symengine.Add):
        return expanded
    groups: dict[tuple[Any, Any, Any], dict[str, tuple[int, Any]]] = {}
    terms = list(expanded.args)
    for i, term in enumerate(terms):
        coefficient, rest, trig = _split(term)
        if len(trig) != 2 or trig[0].args[0] == trig[1].args[0]:
            continue
        first, second = sorted(trig, key=lambda f: str(f.args[0]))
        pattern = ("s" if isinstance(first, symengine.sin) else "c") + ("s" if isinstance(second, symengine.sin)
                                                                       else "c")
        groups.setdefault((rest, first.args[0], second.args[0]), {})[pattern] = (i, coefficient)
    used: set[int] = set()
    extra: list[Any] = []
    for (rest, a, b), found in groups.items():
        for one, other, same, opposite in (("cc", "ss", symengine.cos(a - b), symengine.cos(a + b)),
                                           ("sc", "cs", symengine.sin(a + b), symengine.sin(a - b))):
            if one not in found or other not in found:
                continue
            (i, k), (j, m) = found[one], found[other]
            if k == m:
                extra.append(k * rest * same)
            elif k == -m:
                extra.append(k * rest * opposite)
            else:
                continue
            used.update((i, j))
    if not used:
        return expanded
    return symengine.Add(*[t for k, t in enumerate(terms) if k not in used], *extra)
