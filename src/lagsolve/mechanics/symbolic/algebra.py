"""SymPy's ``factor_terms``, ``cancel``, ``factor``, ``expand`` and ``count_ops``: the same results, remembered,
by cheaper routes where they are exact.

The display simplification (:mod:`lagsolve.mechanics.symbolic.simplify`) tries several rewritings of every result and
keeps the smallest, so it calls these few SymPy functions thousands of times, mostly on the same polynomials
and the same quotients. Each function here gives exactly what SymPy gives, tree for tree (tests hold them equal
on every expression the shipped problems pass through them, and on random ones), and is remembered; where a
result can be had without SymPy's general machinery it is: a polynomial in symbols, sines and cosines is
multiplied out by SymEngine, a quotient of integer polynomials is cancelled in the ring of its generators, a
polynomial linear in one generator with coprime coefficients is known irreducible with one gcd or none, the
operations of an expression are counted as integers. Each route says why it is exact. These follow SymPy 1.14
(``pyproject.toml`` pins the minor release).
"""

from __future__ import annotations

import functools
import itertools
from typing import Any

import sympy
from sympy.core.function import _coeff_isneg

#: expressions of fewer nodes than this are expanded by SymPy: a few tenths of a millisecond each, where loading
#: SymEngine (and NumPy, which it imports) costs about 0.09 s, more than a small problem's every expansion
ENGINE_FROM = 24


@functools.lru_cache(maxsize=8192, typed=True)
def factor_terms(expr: Any) -> Any:
    """``sympy.factor_terms(expr)``, remembered (the same forms come back from several rewritings), and
    built directly for a sum of monomials (:func:`_monomial_factor_terms`)."""
    found = _plain_factor_terms(expr)
    return sympy.factor_terms(expr) if found is None else found


def _plain_factor_terms(expr: Any) -> Any:
    """``sympy.factor_terms(expr)`` as its recursion goes (into powers and the factors of a product), with
    each sum of monomials done by :func:`_monomial_factor_terms`; None where anything else is met."""
    from sympy.core.mul import _keep_coeff

    if not isinstance(expr, sympy.Basic):
        return None
    if expr.is_Atom:
        return expr
    if expr.is_Add:
        return _monomial_factor_terms(expr)
    if expr.is_Pow:
        base = _plain_factor_terms(expr.base)
        if base is None or not expr.exp.is_Integer:
            return None
        return expr if base == expr.base else expr.func(base, expr.exp)
    if isinstance(expr, sympy.Function):
        return expr if _plain_base(expr) else None
    if not expr.is_Mul:
        return None
    content, primitive = expr.as_content_primitive(radical=False, clear=False)
    if not primitive.is_Mul:
        return None
    factors = [_plain_factor_terms(a) for a in primitive.args]
    if any(f is None for f in factors):
        return None
    return _keep_coeff(content, primitive.func(*factors), clear=False, sign=True)


def _monomial_factor_terms(expr: Any) -> Any:
    """``sympy.factor_terms(expr)`` for a sum whose terms are monomials in symbols and in functions of
    arguments ``factor_terms`` leaves alone (an expanded energy, say), or None for any other ``expr``.

    For such a sum ``factor_terms`` takes out the rational content, then a common -1 when every term is
    negative, then the greatest common monomial (the least power of each base every term has), and writes
    ``content * monomial * (sum of the quotients)``; the same steps are taken here, in the same order and
    with the same SymPy constructors, without its general machinery (``Factors`` and ``Term`` objects, which
    cost far more on these sums than the arithmetic)."""
    from sympy.core.mul import _keep_coeff

    if not isinstance(expr, sympy.Add):
        return None
    content, primitive = expr.as_content_primitive(radical=False, clear=False)
    if not primitive.is_Add:
        return None
    terms = _monomials(primitive)
    if terms is None:
        return None
    if all(c.is_negative for c, _ in terms):
        content = -content
        terms = [(-c, powers) for c, powers in terms]
    common, gcd = _common_monomial(terms)
    numers = _quotients(terms, common, gcd)
    coeff, rest, numer = _content_and_sum(common, gcd, numers)
    grouped = _keep_coeff(coeff, rest * numer / sympy.S.One, clear=False)
    return _keep_coeff(content, grouped, clear=False, sign=True)


def _monomials(primitive: Any) -> list[tuple[Any, dict[Any, int]]] | None:
    """Each term of the sum ``primitive`` as (rational coefficient, {base: positive integer power}), the bases
    symbols or functions ``factor_terms`` leaves alone; None when a term is no such monomial."""
    terms = []
    for term in primitive.args:
        coefficient, factors = term.as_coeff_mul()
        if not coefficient.is_Rational:
            return None
        powers: dict[Any, int] = {}
        for f in factors:
            base, exp = f.as_base_exp()
            if not (exp.is_Integer and exp > 0) or not _plain_base(base) or base in powers:
                return None
            powers[base] = int(exp)
        terms.append((coefficient, powers))
    return terms


def _common_monomial(terms: list[tuple[Any, dict[Any, int]]]) -> tuple[dict[Any, int], Any]:
    """The greatest common monomial of the terms (the least power of each base every term has) and the gcd of
    their coefficients."""
    common = dict(terms[0][1])
    for _, powers in terms[1:]:
        common = {b: min(e, powers[b]) for b, e in common.items() if b in powers}
    gcd = terms[0][0]
    for c, _ in terms[1:]:
        gcd = gcd.gcd(c)
    return common, gcd


def _quotients(terms: list[tuple[Any, dict[Any, int]]], common: dict[Any, int], gcd: Any) -> list[Any]:
    """Each term divided by the common monomial and the gcd of the coefficients."""
    numers = []
    for c, powers in terms:
        left = [b if powers[b] - common.get(b, 0) == 1 else b ** (powers[b] - common.get(b, 0))
                for b in powers if powers[b] > common.get(b, 0)]
        numers.append((c / gcd) * (sympy.Mul(*left) / sympy.S.One))
    return numers


def _content_and_sum(common: dict[Any, int], gcd: Any, numers: list[Any]) -> tuple[Any, Any, Any]:
    """The numeric coefficient and the rest of ``gcd * monomial``, and the sum of the quotients, as ``gcd_terms``
    with ``clear=False`` leaves them: a fractional coefficient goes back into the terms when one of them then has
    an integer coefficient."""
    monomial = sympy.Mul(*[b if e == 1 else b ** e for b, e in common.items()])
    cont = gcd * (monomial / sympy.S.One)
    coeff, rest = cont.as_coeff_Mul()
    numer = sympy.Add(*numers)
    c, unit = coeff.as_coeff_Mul()
    if not c.is_Integer and numer.is_Add:  # gcd_terms with clear=False: a fraction goes back into the terms
        n, d = c.as_numer_denom()
        spread = numer / d
        if any(a.as_coeff_Mul()[0].is_Integer for a in spread.args):
            numer, coeff = spread, n * unit
    return coeff, rest, numer


def _plain_base(base: Any) -> bool:
    """A symbol, or a function whose arguments ``sympy.factor_terms`` leaves as they are."""
    if base.is_Symbol:
        return True
    if isinstance(base, sympy.Function) and not isinstance(base, sympy.Piecewise):
        return all(a.is_Symbol or a.is_Number or (a.is_Add and all(t.is_Symbol or (t.is_Mul and len(t.args) == 2
                   and t.args[0] == -1 and t.args[1].is_Symbol) for t in a.args)) for a in base.args)
    return False


def cancel(expr: Any) -> Any:
    """``sympy.cancel(expr)``, remembered (:func:`tidy` and :func:`pythagoras` start from the same one), and
    known without a search for an expression :func:`known_cancelled` was told of."""
    if expr in _CANCELLED:
        return expr
    return _cancel(expr)


@functools.lru_cache(maxsize=8192, typed=True)
def _cancel(expr: Any) -> Any:
    # cancel's form is its own cancel (so on all 1 161 expressions the shipped problems cancel): not searched again
    return known_cancelled(_ring_cancel(expr))


def _ring_cancel(expr: Any) -> Any:
    """``sympy.cancel(expr)``. For a quotient of polynomials with integer coefficients in symbols and function
    applications (integer powers only, no float, no ``Piecewise``) it is found as SymPy finds it, in the ring of
    those generators (``P, Q = F.cancel(G)``, then ``P/Q``), without SymPy's preparation of the expression
    (``signsimp``, ``factor_terms``), which only writes the same quotient another way: in that ring the cancelled
    quotient is unique (coprime, the denominator's leading coefficient positive), so the result is the same tree
    (a test holds it equal to ``sympy.cancel`` on every expression the shipped problems cancel), at about half the
    cost. Any other expression goes to ``sympy.cancel``."""
    from sympy.polys.rings import sring

    if (not isinstance(expr, sympy.Expr) or expr.is_Number or not expr.is_commutative or expr.has(sympy.Piecewise)
            or any(not p.exp.is_Integer for p in expr.atoms(sympy.Pow)) or expr.atoms(sympy.Float)):
        return sympy.cancel(expr)
    numerator, denominator = expr.as_numer_denom()
    try:
        ring, (F, G) = sring((numerator, denominator))
    except (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
        return sympy.cancel(expr)
    if not ring.ngens or not ring.domain.is_ZZ or not G:
        return sympy.cancel(expr)
    P, Q = F.cancel(G)
    return P.as_expr() / Q.as_expr()


#: expressions already in ``sympy.cancel``'s form P/Q (see :func:`known_cancelled`)
_CANCELLED: set[Any] = set()


def known_cancelled(expr: Any) -> Any:
    """Record that ``expr`` is its own ``sympy.cancel`` (its numerator and denominator coprime, written as
    ``cancel`` writes them: :func:`lagsolve.mechanics.symbolic.linsolve.cancelled` makes such forms), so that
    :func:`cancel` does not search it for a common factor again; ``expr`` is returned."""
    if len(_CANCELLED) < 8192:
        _CANCELLED.add(expr)
    return expr


@functools.lru_cache(maxsize=8192, typed=True)
def factor(expr: Any) -> Any:
    """``sympy.factor(expr)``, remembered, with each polynomial in it factored once (:func:`_factor_list`).

    SymPy factors a fraction by factoring its numerator and denominator, each a polynomial in the generators it
    finds; :func:`tidy` factors a fraction and then, in :func:`pythagoras`, its numerator on its own (and a
    numerator is shared by the forms with sin² or cos² reduced), so the same polynomial used to be factored two or
    three times over, the dearest step of the display. The steps of SymPy 1.14's ``factor`` (``_symbolic_factor``
    and ``_symbolic_factor_list``) are taken here as they are there, with the factorization of each polynomial
    remembered: the result is the same expression, tree for tree (a test holds them equal on every expression the
    shipped problems factor). Anything else (no polynomial in it, a non-commutative or unusual expression) goes
    to ``sympy.factor`` itself."""
    if not isinstance(expr, sympy.Expr) or hasattr(expr, "_eval_factor") or not expr.is_commutative:
        return sympy.factor(expr)
    from sympy.polys.polytools import _factors_product, _keep_coeff

    together = expr if _over_polynomials(expr) else sympy.together(expr, fraction=True)
    coeff, factors = _symbolic_factor_list(together)
    return _keep_coeff(coeff, _factors_product(factors))


def _over_polynomials(expr: Any) -> bool:
    """``expr`` is a product of rational numbers and integer powers of symbols, function applications and sums of
    monomials in them: a quotient of polynomials, with nothing for ``together`` to bring over a common denominator.
    ``together`` would only take the common factors out of each sum, which the factorization of that sum takes out
    again, into the same coefficient and factors (a test holds ``factor`` equal to SymPy's on every expression the
    shipped problems factor); it is skipped for such an ``expr`` (it was a tenth of a small derivation)."""

    def plain(term: Any) -> bool:
        return all(a.is_Rational or a.is_Symbol or a.is_Function
                   or (a.is_Pow and a.exp.is_Integer and a.exp > 0 and (a.base.is_Symbol or a.base.is_Function))
                   for a in sympy.Mul.make_args(term))

    for f in sympy.Mul.make_args(expr):
        if f.is_Rational:
            continue
        base = f
        if f.is_Pow:
            if not f.exp.is_Integer:
                return False
            base = f.base
        if not (base.is_Symbol or base.is_Function or (base.is_Add and all(plain(t) for t in base.args))):
            return False
    return True


def _symbolic_factor_list(expr: Any) -> tuple[Any, list[tuple[Any, Any]]]:
    """SymPy 1.14's ``_symbolic_factor_list(expr, opt, "factor")`` for the options of a plain ``factor(expr)``,
    step for step, with :func:`_factor_list` for each polynomial base."""
    from collections import defaultdict

    from sympy.core.numbers import pure_complex

    coeff, factors = sympy.S.One, []
    args = [a._eval_factor() if hasattr(a, "_eval_factor") else a for a in sympy.Mul.make_args(expr)]
    for arg in args:
        if arg.is_Number or (isinstance(arg, sympy.Expr) and pure_complex(arg)):
            coeff *= arg
            continue
        if arg.is_Pow and arg.base != sympy.S.Exp1:
            base, exp = arg.args
            if base.is_Number and exp.is_Number:
                coeff *= arg
                continue
            if base.is_Number:
                factors.append((base, exp))
                continue
        else:
            base, exp = arg, sympy.S.One
        found = _factor_list(base)
        if found[0] is None:
            factors.append((found[1], exp))
            continue
        _coeff, _factors = found[0], list(found[1])
        if _coeff is not sympy.S.One:
            if exp.is_Integer:
                coeff *= _coeff**exp
            elif _coeff.is_positive:
                factors.append((_coeff, exp))
            else:
                _factors.append((_coeff, sympy.S.One))
        if exp is sympy.S.One:
            factors.extend(_factors)
        elif exp.is_integer:
            factors.extend([(f, k * exp) for f, k in _factors])
        else:
            from sympy.polys.polytools import _factors_product

            other = []
            for f, k in _factors:
                if f.as_expr().is_positive:
                    factors.append((f, k * exp))
                else:
                    other.append((f, k))
            factors.append((_factors_product(other), exp))
    collected: dict[Any, Any] = defaultdict(int)
    for k, v in factors:
        collected[k] += v
    return coeff, list(collected.items())


@functools.lru_cache(maxsize=8192, typed=True)
def _factor_list(base: Any) -> tuple[Any, Any]:
    """``Poly(base).factor_list()`` as SymPy's ``factor`` makes it (the generators ``base`` has, its own domain),
    remembered: (coefficient, tuple of (Poly, multiplicity)); (None, the expression) where ``base`` is no
    polynomial (SymPy then keeps it as a factor of its own)."""
    from sympy.polys import polyoptions
    from sympy.polys.polyerrors import PolificationFailed
    from sympy.polys.polytools import _poly_from_expr

    options = polyoptions.build_options((), {})
    options["fraction"] = True
    try:
        poly, _ = _poly_from_expr(base, options)
    except PolificationFailed as failure:
        return None, failure.expr
    coefficient, found = _linear_factor_list(poly) or poly.factor_list()
    return coefficient, tuple(found)


def _linear_factor_list(poly: Any) -> tuple[Any, list[tuple[Any, int]]] | None:
    """``poly.factor_list()`` for a polynomial over the integers in several generators that, its monomial and
    integer content taken out, is linear in one generator x with coprime coefficients, a x + b with gcd(a, b) = 1:
    such a polynomial is irreducible (a factorization would leave one factor free of x, dividing a and b), so its
    factorization is that content and itself, found with one gcd instead of SymPy's search (a square-free part and
    Wang's algorithm, the dearest step of the display: the numerator of a pendulum's acceleration, linear in g, is
    such a polynomial). The steps of SymPy 1.14's ``dmp_factor_list`` and ``dmp_zz_factor`` for that case are taken
    as they are there, so the result is the same (a test holds it equal to ``factor_list`` on every polynomial the
    shipped problems factor). None when the case does not apply (SymPy then factors)."""
    from sympy.polys.densearith import dmp_neg
    from sympy.polys.densebasic import dmp_from_dict, dmp_ground_LC, dmp_terms_gcd, dmp_to_dict
    from sympy.polys.densetools import dmp_ground_primitive
    from sympy.polys.euclidtools import dmp_gcd
    from sympy.polys.polyutils import _sort_factors

    rep = poly.rep
    ring, u = rep.dom, rep.lev
    if not ring.is_ZZ or u == 0:
        return None
    exponents, f = dmp_terms_gcd(rep.to_list(), u, ring)
    content, f = dmp_ground_primitive(f, u, ring)
    if ring.is_negative(dmp_ground_LC(f, u, ring)):
        content, f = -content, dmp_neg(f, u, ring)
    terms = dmp_to_dict(f, u, ring)
    splits = []
    for j in range(u + 1):
        if {m[j] for m in terms} == {0, 1}:
            a = {m[:j] + (0,) + m[j + 1:]: c for m, c in terms.items() if m[j] == 1}
            b = {m: c for m, c in terms.items() if m[j] == 0}
            splits.append((min(len(a), len(b)), j, a, b))
    if not splits:
        return None
    fewest, _, a, b = min(splits, key=lambda split: split[:2])
    # a monomial a or b has no common factor with the other but a monomial or an integer, which would divide every
    # term of the polynomial: none is left after its monomial and integer content, so no gcd is needed
    if fewest > 1:
        gcd = dmp_gcd(dmp_from_dict(a, u, ring), dmp_from_dict(b, u, ring), u, ring)
        if any(dmp_to_dict(gcd, u, ring).keys() - {(0,) * (u + 1)}):
            return None  # a common factor of a and b divides the polynomial
    factors = [(f, 1)]
    for i, k in enumerate(reversed(exponents)):
        if k:
            factors.insert(0, (dmp_from_dict({(0,) * (u - i) + (1,) + (0,) * i: ring.one}, u, ring), k))
    return ring.to_sympy(content), [(poly.per(rep.per(g)), k) for g, k in _sort_factors(factors)]


@functools.lru_cache(maxsize=8192, typed=True)
def expand(expr: Any) -> Any:
    """``sympy.expand(expr)``, remembered, and done by SymEngine for a polynomial (non-negative integer powers) in
    symbols and in sines and cosines of a symbol or a sum of symbols, a rational number at most in each term
    (energies, numerators of accelerations): there the expanded form is one sum of monomials, SymEngine multiplies
    it out many times faster, and SymPy builds it back into the same tree (a test holds the two equal on every
    expression the shipped problems expand). Anything else, and any expression of fewer than :data:`ENGINE_FROM`
    nodes, is expanded by SymPy."""
    if not isinstance(expr, sympy.Basic) or small(expr) or not _engine_polynomial(expr):
        return sympy.expand(expr)
    from lagsolve.mechanics.symbolic.partials import from_engine

    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        back = from_engine(sympy2symengine(expr).expand(), {s.name: s for s in expr.free_symbols})
    except (ImportError, RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return sympy.expand(expr)
    return sympy.expand(expr) if back is None else back


def small(expr: Any) -> bool:
    """``expr`` has fewer than :data:`ENGINE_FROM` nodes (counted only that far)."""
    return next(itertools.islice(sympy.preorder_traversal(expr), ENGINE_FROM - 1, None), None) is None


def _engine_polynomial(expr: Any) -> bool:
    """``expr`` is what :func:`expand` gives SymEngine: sums, products and non-negative integer powers of symbols
    (not Dummies, which come back as new ones; each name once), rational numbers, and sines and cosines of a symbol
    or of a sum of symbols with coefficients ±1."""
    names: dict[str, Any] = {}
    for node in sympy.preorder_traversal(expr):
        if node.is_Symbol:
            if isinstance(node, sympy.Dummy) or names.setdefault(node.name, node) != node:
                return False
        elif node.is_Add or node.is_Mul or node.is_Rational:
            continue
        elif node.is_Pow:
            if not (node.exp.is_Integer and node.exp >= 0):
                return False
        elif isinstance(node, sympy.sin | sympy.cos):
            if not _plain_base(node):
                return False
        else:
            return False
    return True


def _negated(product: Any) -> Any:
    """``-product`` for a product with a negative coefficient, as ``count_ops`` takes it: the rest of ``-1*x``,
    else the product negated."""
    return product.as_two_terms()[1] if product.args[0] is sympy.S.NegativeOne else -product


def _fraction_ops(product: Any, args: list[Any]) -> int | None:
    """The DIV (and NEG of an integer numerator) of a product ``sympy.fraction`` splits, its denominator (unless
    an integer) and numerator (unless an integer) put on ``args`` to be walked; None when the denominator is 1 (the
    product is walked as it is)."""
    n, d = sympy.fraction(product)
    if n.is_Integer:
        args.append(d)
        return 1 + bool(n < 0)  # DIV, NEG
    if d is not sympy.S.One:
        if not d.is_Integer:
            args.append(d)
        args.append(n)
        return 1  # DIV
    return None


def _sum_ops(terms: tuple[Any, ...], args: list[Any]) -> int:
    """The ADD or SUB between the terms of a sum (and a NEG when every term is negative), each term put on ``args``
    to be walked, a negative one negated."""
    count = 0
    negative = 0
    for i, term in enumerate(terms):
        if _coeff_isneg(term):
            negative += 1
            args.append(-term)
        else:
            args.append(term)
        count += i > 0  # ADD or SUB
    if negative == len(terms):
        count += 1  # -x - y = NEG + SUB
    # -x + y is SUB where ADD was counted: the same number
    return count


def _divides(factor: Any) -> bool:
    """``sympy.fraction`` puts (part of) this factor of a product in the denominator: a fraction, or a power (or
    ``exp``) whose exponent is negative or a product not known to be positive."""
    if factor.is_Rational:
        return not factor.is_Integer
    if factor.is_commutative and (factor.is_Pow or isinstance(factor, sympy.exp)):
        exponent = factor.as_base_exp()[1]
        return bool(exponent.is_negative) or (not exponent.is_positive and exponent.is_Mul)
    return False


@functools.lru_cache(maxsize=8192)
def ops(expr: Any) -> int:
    """``sympy.count_ops(expr)``, remembered (counted by :func:`count_ops` for an expression)."""
    if isinstance(expr, sympy.Expr) and not expr.is_Relational:
        return count_ops(expr)
    return int(sympy.count_ops(expr))


def count_ops(expr: Any) -> int:
    """``sympy.count_ops(expr)`` of an expression (not a relation), walked as SymPy 1.14 walks it, with the
    operations counted as integers instead of collected as a sum of symbols (``ADD + 2*MUL + SIN``) whose
    coefficients are added at the end: the same number, at a fraction of the cost (counting was a tenth of a
    small derivation). A test holds the two equal on every expression the shipped problems measure."""
    from sympy.core.operations import LatticeOp

    count = 0
    args = [expr]
    while args:
        a = args.pop()
        if a.is_Rational:
            if a is not sympy.S.One:
                count += (a.p < 0) + (a.q != 1)  # -1/3 = NEG + DIV
                continue
        elif a.is_Mul:
            if _coeff_isneg(a):
                count += 1  # NEG
                a = _negated(a)
            if any(_divides(f) for f in a.args):  # else fraction(a) is (a, 1): nothing to count here
                divisions = _fraction_ops(a, args)
                if divisions is not None:
                    count += divisions
                    continue
        elif a.is_Add:
            count += _sum_ops(a.args, args)
            continue
        if a.is_Pow and a.exp is sympy.S.NegativeOne:
            count += 1  # DIV
            args.append(a.base)
            continue
        if a == sympy.S.Exp1:
            count += 1  # EXP
            continue
        if a.is_Pow and a.base == sympy.S.Exp1:
            count += 1  # EXP
            args.append(a.exp)
            continue
        if a.is_Mul or isinstance(a, LatticeOp):
            count += len(a.args) - 1
        elif a.args and (a.is_Pow or a.is_Function or isinstance(a, sympy.Derivative | sympy.Integral | sympy.Sum)):
            count += 1
        if not a.is_Symbol:
            args.extend(a.args)
    return count
