"""Display simplification toward textbook form — the one place results are simplified.

Derivation keeps expressions in matrix form without ``simplify``; only the
results shown to people (accelerations, multipliers, forces, equations) pass
through :func:`tidy`, which tries a few rewritings and keeps the smallest.
The overall time budget is enforced by :mod:`lagsolve.app.budget` (a child process),
because SymPy's long loops cannot be interrupted from inside.
"""

from __future__ import annotations

import contextlib
import functools
from typing import Any

import sympy

from lagsolve.mechanics.symbolic.algebra import _plain_base, cancel, expand, factor, factor_terms, ops
from lagsolve.mechanics.symbolic.bulk import light
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM
from lagsolve.mechanics.symbolic.signs import sign_core


def reproducible() -> None:
    """Seed SymPy's own random generator (``sympy.core.random``), which its multivariate factorisation
    (Wang's algorithm) draws evaluation points from. Unseeded, the same ``factor`` takes 0.1 s in one
    process and over 10 s in another (the charged ring's force of constraint, one run in six), so a stage
    could run out of its budget at random; seeded at the start of each derivation, the work, and so the
    time and every result, depend on the problem alone."""
    import sympy.core.random

    sympy.core.random.seed(0)


def _number(value: Any) -> Any:
    """A plain Python number (from an empty sum, say) as a SymPy number."""
    if isinstance(value, int):
        return sympy.Integer(value)
    raise TypeError(f"expected a SymPy expression, got {type(value).__name__}")


_TRIG = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)


def measure(expr: Any) -> tuple[int, int, str]:
    """Ordering used to pick the nicest form: fewer operations (a multiple-angle
    ``sin(2*theta)`` counts extra, as textbooks write ``sin(theta)*cos(theta)``),
    then shorter text, then the text itself (so ties break deterministically)."""
    text = sympy.sstr(expr)
    return (_weight(expr), len(text), text)


def smallest(candidates: list[Any]) -> Any:
    """``min(candidates, key=measure)``, printing only the candidates with the fewest operations
    (printing is the dear part of :func:`measure`, and the operation count decides most choices)."""
    weights = [_weight(c) for c in candidates]
    low = min(weights)
    # equal candidates print alike, so only the first of each is printed (min keeps the first of a tie)
    tied = list(dict.fromkeys(c for c, w in zip(candidates, weights, strict=True) if w == low))
    if len(tied) == 1:
        return tied[0]
    return min(tied, key=_text_key)


@functools.lru_cache(maxsize=8192, typed=True)
def _text_key(expr: Any) -> tuple[int, str]:
    """The last two items of :func:`measure`."""
    text = sympy.sstr(expr)
    return len(text), text


@functools.lru_cache(maxsize=8192)
def _weight(expr: Any) -> int:
    """The first item of :func:`measure`: operations, a multiple angle counting extra (remembered: the
    same candidates come back often)."""
    compound = sum(1 for f in expr.atoms(*_TRIG) if not f.args[0].is_Symbol)
    return ops(expr) + 3 * compound


#: above this many operations SymPy's general ``simplify`` and ``trigsimp`` are skipped
#: (they dominate run time on large expressions; the Pythagorean reduction below is cheap)
SIMPLIFY_LIMIT = 60
#: above this many operations :func:`tidy` only pulls out common factors (no factor, cancel or trig rewriting)
TIDY_LIMIT = 200
#: above this many operations sums are not searched for compound angles (the pairing grows with the square)
CONTRACT_LIMIT = 600
TRIGSIMP_LIMIT = 0
#: above this many operations a cancelled quotient is not factored (:func:`_factor_cancelled`)
FACTOR_LIMIT = 1000
_ERRORS = (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError)


def reduce_squares(expr: Any, of: Any, to: Any) -> Any:
    """Rewrite even powers of ``of`` (cos, say) with ``1 - to**2`` and expand: a cheap, canonical
    reduction modulo sin² + cos² = 1."""

    def rewrite(power: Any) -> Any:
        k = int(power.exp)
        angle = power.base.args[0]
        return of(angle) ** (k % 2) * (1 - to(angle) ** 2) ** (k // 2)

    return expand(expr.replace(
        lambda e: e.is_Pow and isinstance(e.base, of) and e.exp.is_Integer and e.exp >= 2, rewrite))


def pythagoras(expr: Any) -> list[Any]:
    """Forms of ``expr`` with sin² + cos² = 1 applied both ways, numerator and denominator apart."""
    numerator, denominator = sympy.fraction(cancel(expr))
    out = []
    for of, to in ((sympy.cos, sympy.sin), (sympy.sin, sympy.cos)):
        n, d = reduce_squares(numerator, of, to), reduce_squares(denominator, of, to)
        if ops(n) + ops(d) > FACTOR_LIMIT:  # only while cheap (see _factor_cancelled)
            out.append(n / d)
            continue
        try:
            out.append(factor(n) / factor(d))
        except _ERRORS:
            out.append(n / d)
    try:
        factored = factor(expr)
    except _ERRORS:
        return out
    # factor first, then reduce each factor: keeps squares such as (x*cos + y*sin)**2 intact
    out.append(sympy.Mul(*[_reduce_factor(f) for f in sympy.Mul.make_args(factored)]))
    return out


def _reduce_factor(term: Any) -> Any:
    base, exp = term.as_base_exp()
    if not base.has(sympy.sin, sympy.cos):
        return term
    forms = [base, reduce_squares(base, sympy.cos, sympy.sin), reduce_squares(base, sympy.sin, sympy.cos)]
    return smallest(forms) ** exp


@functools.lru_cache(maxsize=4096)
def tidy(expr: Any) -> Any:
    """A short, factored form of ``expr`` (deterministic: ties break on the printed text).

    >>> import sympy
    >>> x, g = sympy.symbols("x g")
    >>> tidy((g*x + g)/(x + 1) + x**2 - x*(x - 1))
    g + x
    """
    if not isinstance(expr, sympy.Basic):
        return _number(expr)
    if expr.has(sympy.sign):
        expr = plain_signs(expr)  # sign((x_dot - X_dot)*sqrt(...)) is sign(x_dot - X_dot)
    if expr.is_Number or expr.is_Symbol or _monomial(expr) or _trig_monomial(expr):
        return expr  # every rewriting below gives a monomial back as it is, or a longer form
    if ops(expr) > TIDY_LIMIT:
        # a governor: factor and cancel on a large expression cost far more than they gain
        return smallest([expr, factor_terms(expr)])
    if _scaled_number(expr):
        return _tidy_scaled(expr)
    return _search(expr)


def _search(expr: Any) -> Any:
    """The search of :func:`tidy`: each rewriting of ``expr``, then the smallest by :func:`measure`."""
    candidates: list[Any] = [expr]
    for step in (cancel, factor_terms, _factor_cancelled):
        try:
            candidates.append(step(expr))
        except _ERRORS:
            continue
    if expr.has(*_TRIG):
        candidates += pythagoras(expr)
        numerator, denominator = sympy.fraction(candidates[1])
        contracted = compound_angles(expand(numerator)) / compound_angles(expand(denominator))
        candidates += [contracted, factor_terms(contracted)]
        if ops(expr) <= TRIGSIMP_LIMIT:
            reduced = sympy.trigsimp(candidates[1])
            for step in (sympy.factor, lambda e: sympy.factor(sympy.expand_trig(e))):
                try:
                    candidates.append(step(reduced))
                except _ERRORS:
                    continue
    best = smallest(candidates)
    candidates += signs(best)  # v/|v| appears only once roots of squares became Abs: look at the best form
    best = smallest(candidates)
    if ops(best) <= SIMPLIFY_LIMIT and not best.has(*_TRIG, sympy.sign) and not _scaled_number(best):
        with contextlib.suppress(*_ERRORS):
            candidates.append(sympy.simplify(best))
    return smallest(candidates)


def _factor_cancelled(expr: Any) -> Any:
    """``factor(cancel(expr))``, only while cheap: a quotient that cancelling writes out at length (a normal force
    over a sum of squares) is not factored (Wang's algorithm on it costs seconds and the form is not kept)."""
    cancelled = cancel(expr)
    return factor(cancelled) if ops(cancelled) <= FACTOR_LIMIT else cancelled


def _scaled_number(expr: Any) -> bool:
    """``expr`` is a number times powers of symbols, ``g*(2 + sqrt(2))/l`` or ``sqrt(g)*sqrt(2 - sqrt(2))/sqrt(l)``
    (the squared frequencies of a double pendulum and their roots). SymPy's ``simplify`` leaves the number of such
    a product as it is (it neither denests nor rationalises) and has nothing else to rewrite, while the other
    rewritings of :func:`tidy` already take a common factor out of the number; it is not called for them (at two
    degrees of freedom it was a fifth of the whole derivation, for no change)."""
    return all(not f.free_symbols or f.is_Symbol or (f.is_Pow and f.base.is_Symbol and f.exp.is_Rational)
               for f in sympy.Mul.make_args(expr))


def _trig_monomial(expr: Any) -> bool:
    """``expr`` is a rational number times positive integer powers of symbols and of sines and cosines of a symbol
    or of a sum or difference of symbols (``2*l**2*m*sin(th1 - th2)*cos(th1 - th2)``, a term of Hamilton's
    equations). :func:`tidy` would give it back as it is: ``cancel``, ``factor`` and ``factor_terms`` leave a product
    of such factors alone, sin² + cos² = 1 only lengthens it (one term becomes two), and a compound angle costs
    extra in :func:`measure` (the 82 such expressions the shipped problems tidy all came back unchanged)."""
    found = False
    for f in (expr.args if expr.is_Mul else (expr,)):
        if f.is_Rational or f.is_Symbol or (f.is_Pow and f.base.is_Symbol and f.exp.is_Integer):
            continue
        base, exp = f.as_base_exp()
        if not (isinstance(base, sympy.sin | sympy.cos) and exp.is_Integer and exp > 0 and _plain_base(base)):
            return False
        found = True
    return found


def _tidy_scaled(expr: Any) -> Any:
    """:func:`tidy` of a number times powers of symbols (:func:`_scaled_number`): the number with its common factor
    taken out, or expanded and then so (``(2 + sqrt(2))**2`` → ``2*(3 + 2*sqrt(2))``), whichever is shorter. The
    symbols' part is a monomial already; ``cancel`` and ``factor`` would only write the number as a polynomial in
    its radicals (the frequencies of a chain of pendulums, ``g*(2 - sqrt(2))/l``: 2 ms each, for nothing)."""
    number, rest = expr.as_independent(*expr.free_symbols, as_Add=False)
    expanded = sympy.expand(number) * rest
    return smallest(list(dict.fromkeys([expr, factor_terms(expr), expanded, factor_terms(expanded)])))


def _monomial(expr: Any) -> bool:
    """``expr`` is a rational number times integer powers of symbols (``-2*g*l**2/m``)."""
    factors = expr.args if expr.is_Mul else (expr,)
    return all(f.is_Rational or f.is_Symbol or (f.is_Pow and f.base.is_Symbol and f.exp.is_Integer)
               for f in factors)


@functools.lru_cache(maxsize=4096)
def tidy_sum(expr: Any) -> Any:
    """A sum of simple terms (for equations and energies): expanded, trig-reduced,
    single angles, with a common factor pulled out when there is one."""
    if not isinstance(expr, sympy.Basic):
        return _number(expr)
    expanded = expand(expr)
    candidates = [expanded]
    if expanded.has(*_TRIG):
        candidates += [reduce_squares(expanded, sympy.cos, sympy.sin),
                       reduce_squares(expanded, sympy.sin, sympy.cos)]
        if ops(expanded) <= TRIGSIMP_LIMIT:
            reduced = sympy.trigsimp(expanded)
            candidates += [reduced, sympy.expand(sympy.expand_trig(reduced))]
        if ops(expanded) <= CONTRACT_LIMIT:
            candidates += [compound_angles(c) for c in candidates[:3]]
    if ops(expanded) > TIDY_LIMIT:
        # a governor: pull common factors out of the best form only
        best = smallest(candidates)
        return smallest([best, factor_terms(best)])
    candidates += [factor_terms(c) for c in candidates]
    return smallest(candidates)


#: a system of more coordinates than this is large: its many display forms are each rewritten once
#: (:func:`tidy_sum_light`, :func:`display_forms`) instead of searched over candidates
LARGE_SYSTEM = 4


def display_forms(size: int) -> tuple[Any, Any]:
    """(tidy, tidy_sum) for a system of ``size`` coordinates: the searches, or for a large system the one
    rewriting of :func:`tidy_sum_light` for both, done by SymEngine for a bulk one (:func:`tidy_sum_bulk`)."""
    if size > BULK_SYSTEM:
        return tidy_sum_bulk, tidy_sum_bulk
    return (tidy, tidy_sum) if size <= LARGE_SYSTEM else (tidy_sum_light, tidy_sum_light)


@functools.lru_cache(maxsize=4096)
def tidy_sum_bulk(expr: Any) -> Any:
    """:func:`tidy_sum_light` of a bulk system's expression, written by SymEngine
    (:func:`~lagsolve.mechanics.symbolic.bulk.light`) where it can take ``expr``."""
    found = light(expr)
    return tidy_sum_light(expr) if found is None else found


@functools.lru_cache(maxsize=4096)
def tidy_sum_light(expr: Any) -> Any:
    """A cheap :func:`tidy_sum` for large systems: expanded, compound angles contracted, common factors out
    (one rewriting each instead of a search over candidates)."""
    if not isinstance(expr, sympy.Basic):
        return _number(expr)
    return factor_terms(compound_angles(unit_squares(expand(expr))))


def unit_squares(expanded: Any) -> Any:
    """``c sin²x + c cos²x`` → ``c`` pair by pair of terms in the expanded sum, a cheap :func:`pythagoras` (the
    diagonal of a chain's mass matrix, ``(k+1) l² m (sin²θₖ + cos²θₖ)``); every other term as it is.

    >>> import sympy
    >>> x, c, d = sympy.symbols("x c d")
    >>> unit_squares(c*sympy.sin(x)**2 + c*sympy.cos(x)**2 + d*sympy.sin(x)**2)
    c + d*sin(x)**2
    """
    if not isinstance(expanded, sympy.Add) or not expanded.has(sympy.sin, sympy.cos):
        return expanded
    found: dict[tuple[Any, Any, Any], list[int]] = {}
    terms = list(expanded.args)
    for i, term in enumerate(terms):
        for part in sympy.Mul.make_args(term):
            if part.is_Pow and part.exp == 2 and isinstance(part.base, sympy.sin | sympy.cos):
                rest = term / part
                found.setdefault((type(part.base), part.base.args[0], rest), []).append(i)
                break
    used: set[int] = set()
    extra: list[Any] = []
    for (kind, angle, rest), where in found.items():
        if kind is not sympy.sin:
            continue
        partners = [j for j in found.get((sympy.cos, angle, rest), []) if j not in used]
        mine = [i for i in where if i not in used]
        for i, j in zip(mine, partners, strict=False):
            used.update((i, j))
            extra.append(rest)
    if not used:
        return expanded
    return sympy.Add(*[t for k, t in enumerate(terms) if k not in used], *extra)


@functools.lru_cache(maxsize=8192, typed=True)
def compound_angles(expr: Any) -> Any:
    """``sin a sin b + cos a cos b`` → ``cos(a − b)`` and the like (sums of products to a function of a
    sum), term by term of the expanded ``expr``: the textbook form of chains of pendulums.

    >>> import sympy
    >>> a, b = sympy.symbols("a b")
    >>> compound_angles(sympy.sin(a)*sympy.sin(b) + sympy.cos(a)*sympy.cos(b))
    cos(a - b)
    """
    if not isinstance(expr, sympy.Basic) or not expr.has(sympy.sin, sympy.cos):
        return expr
    try:
        return _contract(expand(expr))
    except _ERRORS:
        return expr


def signs(expr: Any) -> list[Any]:
    """``expr`` with ``|v| = v sign(v)`` for each symbol ``v`` whose ``Abs`` divides and that also stands
    outside one, and ``sign(v)**2 = 1``: the friction direction ``v/|v|`` written ``sign(v)`` as textbooks do
    (an empty list when no such ``v`` is there). Equal to ``expr`` wherever ``v != 0``.

    >>> import sympy
    >>> v, a, b = sympy.symbols("v a b", real=True)
    >>> signs((a*v - b*sympy.Abs(v))/sympy.Abs(v))
    [a*sign(v) - b]
    """
    if not expr.has(sympy.Abs):
        return []
    outside = expr.xreplace({a: sympy.Integer(1) for a in expr.atoms(sympy.Abs)}).free_symbols
    denominator = sympy.fraction(sympy.together(expr))[1]
    # only a |v| that divides (v/|v|, the direction of a velocity): elsewhere |v| is already the short form
    targets = sorted({a for a in denominator.atoms(sympy.Abs) if a.args[0].is_Symbol and a.args[0] in outside},
                     key=sympy.default_sort_key)
    if not targets:
        return []
    marks = {a: sympy.Dummy(f"s_{a.args[0].name}") for a in targets}
    form = expr.xreplace({a: a.args[0] * marks[a] for a in targets})
    hidden = [node for node in sympy.preorder_traversal(form)
              if (isinstance(node, sympy.Function) or (node.is_Pow and not node.exp.is_Integer))
              and node.has(*marks.values())]
    if hidden:
        return []  # sign(v)**2 = 1 is used on polynomials in sign(v) only, never inside a root or a function
    try:
        for a, mark in marks.items():
            numerator, denominator = sympy.fraction(sympy.cancel(form))
            power = sympy.degree(denominator, mark)
            numerator = sympy.rem(sympy.expand(numerator * mark**power), mark**2 - 1, mark)
            denominator = sympy.rem(sympy.expand(denominator * mark**power), mark**2 - 1, mark)
            if denominator.has(mark):
                return []
            form = (numerator / denominator).xreplace({mark: sympy.sign(a.args[0])})
        return list(dict.fromkeys([sympy.factor(form), sympy.factor_terms(form)]))
    except _ERRORS:
        return []


def _contract(expanded: Any) -> Any:
    """SymPy's ``TR10i`` (sums of products to functions of sums) on ``expanded``, applied class by class.

    ``TR10i`` tries every pair of terms; a pair combines only when, after its common factor, each term
    is a number times at most two sines, cosines or square roots. So two terms whose other factors
    differ (:func:`_pairing_key`) never combine, and ``TR10i`` on each class of terms gives exactly
    what it gives on the whole sum, for a fraction of the pairs. This holds when no sum inside a term
    holds a sine or cosine (then ``TR10i`` leaves every term itself alone); otherwise the whole sum
    goes to ``TR10i`` at once.
    """
    if not expanded.is_Add or any(a.has(sympy.sin, sympy.cos) for t in expanded.args for a in t.atoms(sympy.Add)):
        return _tr10i(expanded)
    classes: dict[Any, list[Any]] = {}
    for term in expanded.args:
        classes.setdefault(_pairing_key(term), []).append(term)
    if len(classes) == 1:
        return _tr10i(expanded)
    return sympy.Add(*[_tr10i(sympy.Add(*terms)) if len(terms) > 1 else terms[0] for terms in classes.values()])


@functools.lru_cache(maxsize=8192, typed=True)
def _tr10i(expr: Any) -> Any:
    """SymPy's ``TR10i(expr)``, remembered: the forms of a sum with sin² or cos² reduced share most classes of
    terms (the cross terms of a chain's kinetic energy), which are contracted once."""
    from sympy.simplify.fu import TR10i

    return TR10i(expr)


def _pairing_key(term: Any) -> Any:
    """The factors of ``term`` a pair of terms must share to combine in ``TR10i``: all but numbers,
    factors with a sine or cosine, and fractional powers."""
    rigid = []
    for part in sympy.Mul.make_args(term):
        if part.is_number or part.has(sympy.sin, sympy.cos):
            continue
        if part.is_Pow and part.exp.is_Rational and not part.exp.is_Integer:
            continue
        rigid.append(part)
    return tuple(rigid)  # in the Mul's canonical order


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
        for part in sympy.Mul.make_args(arg.xreplace(reals)):
            if part.is_nonnegative:
                outside *= part
            elif part.is_nonpositive:
                outside *= -part
            else:
                inside *= part
        return (outside * sympy.Abs(inside)).xreplace(back)

    return expr.replace(lambda e: isinstance(e, sympy.Abs), fix)


def norm(components: tuple[Any, ...] | list[Any]) -> Any:
    """Euclidean length of a vector, simplified: ``sqrt`` of a square becomes ``Abs``.

    >>> import sympy
    >>> m = sympy.Symbol("m", positive=True); v, th = sympy.symbols("v theta", real=True)
    >>> norm([-2*m*v*sympy.sin(th), 2*m*v*sympy.cos(th)])
    2*m*Abs(v)
    """
    direct = root_of_square(tidy(unit_signs(sum((c**2 for c in components), sympy.Integer(0)))))
    common = common_factor(components)
    if common == 1:
        return direct
    # |c u| = |c| |u|: the shared factor (a tension times a direction) comes out before the squares are summed,
    # so the Pythagorean reduction sees the direction alone
    rest = root_of_square(tidy(unit_signs(sum((sympy.cancel(c / common) ** 2 for c in components),
                                              sympy.Integer(0)))))
    return smallest([direct, root_of_square(common**2) * rest])


def unit_signs(expr: Any) -> Any:
    """Even powers of sign(v) are 1 where v ≠ 0 (where a direction v/|v| is defined, or a contact slides).

    >>> import sympy
    >>> v = sympy.Symbol("v", real=True)
    >>> unit_signs(3*sympy.sign(v)**2 + sympy.sign(v)**3)
    sign(v)**3 + 3
    """
    return expr.replace(lambda e: e.is_Pow and isinstance(e.base, sympy.sign) and e.exp.is_even,
                        lambda e: sympy.Integer(1))


def common_factor(components: tuple[Any, ...] | list[Any]) -> Any:
    """The factors that every nonzero component shares, each to its smallest power (1 when none is).

    >>> import sympy
    >>> T, a = sympy.symbols("T alpha", real=True)
    >>> common_factor([-T*sympy.cos(a)/(T + 1), T*sympy.sin(a)/(T + 1), 0])
    T/(T + 1)
    """
    nonzero = [c for c in components if c != 0]
    if len(nonzero) < 2:
        return sympy.Integer(1)
    powers = [sympy.factor(c).as_coeff_Mul()[1].as_powers_dict() for c in nonzero]
    common = sympy.Integer(1)
    for base in sorted(powers[0], key=sympy.default_sort_key):
        exponents = [p.get(base) for p in powers]
        if base.is_number or any(e is None or not e.is_Rational for e in exponents):
            continue
        if all(e > 0 for e in exponents):
            common *= base ** min(exponents)
        elif all(e < 0 for e in exponents):
            common *= base ** max(exponents)
    return common


def root_of_sum_of_squares(terms: list[Any]) -> Any:
    """``sqrt(t1**2 + t2**2 + ...)`` keeping each term's factored form (for the length of a
    sum of orthogonal vectors, whose lengths are the terms)."""
    return root_of_square(factor_terms(unit_signs(sum((tidy(t) ** 2 for t in terms), sympy.Integer(0)))))


def root_of_square(square: Any) -> Any:
    """``sqrt(square)`` with the square factored and ``sqrt(a**2)`` written ``Abs(a)``.

    Derivatives and declared functions count as real, as they are in every problem.
    """
    atoms = sorted(square.atoms(sympy.Derivative, sympy.core.function.AppliedUndef), key=sympy.default_sort_key)
    reals = {atom: sympy.Dummy(f"r{i}", real=True) for i, atom in enumerate(atoms)}
    candidates = []
    # factoring a long square (a coupled normal force written out) costs seconds and gives no root: only while cheap
    for form in (square, sympy.factor(square)) if ops(square) <= TIDY_LIMIT else (square,):
        root = sympy.sqrt(form.xreplace(reals)).xreplace({v: k for k, v in reals.items()})
        candidates += [root, tidy_abs(root)]
    return smallest(candidates)


def plain_signs(expr: Any) -> Any:
    """Each ``sign(a)`` with the factors of ``a`` of known sign taken out where that does not lengthen ``a``, and
    written with SymPy's sign convention for its argument, so that one sliding rate is written one way
    everywhere (a friction force's ``sign((x_dot - X_dot)*sqrt(tan(alpha)**2 + 1))`` is
    ``-sign(X_dot - x_dot)``).

    >>> import sympy
    >>> x, y = sympy.symbols("x_dot y_dot", real=True)
    >>> m = sympy.Symbol("m", positive=True)
    >>> plain_signs(sympy.sign(m*x - m*y) + sympy.sign(-2*m))
    sign(x_dot - y_dot) - 1
    """
    def simpler(e: Any) -> Any:
        argument = e.args[0]
        for _ in range(2):  # tidied first (sin(x)**2 + cos(x)**2 is 1), then the factors of known sign out
            known, core = sign_core(tidy(argument))
            if known is not None:
                return sympy.Integer(known)
            if core == argument or sympy.count_ops(core) > sympy.count_ops(argument):
                break
            argument = core
        return -sympy.sign(-argument) if argument.could_extract_minus_sign() else sympy.sign(argument)

    if not expr.has(sympy.sign):
        return expr
    expr = expr.replace(lambda e: isinstance(e, sympy.sign) and not e.args[0].is_Symbol, simpler)
    if expr.has(sympy.Abs):
        expr = expr.replace(lambda e: e.is_Mul and e.has(sympy.Abs), _absorbed)
    return expr


def _absorbed(product: Any) -> Any:
    """``|a| sign(a c)`` is ``a sign(c)``: a normal force ``|m g cos(alpha)|`` times the sign of a sliding rate
    ``x_dot cos(alpha)`` is ``m g cos(alpha) sign(x_dot)``."""
    factors = list(sympy.Mul.make_args(product))
    for i, f in enumerate(factors):
        if not isinstance(f, sympy.Abs):
            continue
        inner = f.args[0]
        for j, g in enumerate(factors):
            if not isinstance(g, sympy.sign):
                continue
            rest = sympy.cancel(g.args[0] / inner)
            if rest == 0 or sympy.fraction(rest)[1] != 1 or rest.has(sympy.Abs):
                continue
            factors[i], factors[j] = inner, sympy.sign(rest)
            return sympy.Mul(*factors)
    return product
