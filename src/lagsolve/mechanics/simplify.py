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
    if all(c.is_negative for c, _ in terms):
        content = -content
        terms = [(-c, powers) for c, powers in terms]
    common = dict(terms[0][1])
    for _, powers in terms[1:]:
        common = {b: min(e, powers[b]) for b, e in common.items() if b in powers}
    gcd = terms[0][0]
    for c, _ in terms[1:]:
        gcd = gcd.gcd(c)
    numers = []
    for c, powers in terms:
        left = [b if powers[b] - common.get(b, 0) == 1 else b ** (powers[b] - common.get(b, 0))
                for b in powers if powers[b] > common.get(b, 0)]
        numers.append((c / gcd) * (sympy.Mul(*left) / sympy.S.One))
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
    grouped = _keep_coeff(coeff, rest * numer / sympy.S.One, clear=False)
    return _keep_coeff(content, grouped, clear=False, sign=True)


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
    ``cancel`` writes them: :func:`lagsolve.mechanics.linsolve.cancelled` makes such forms), so that
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
    expression the shipped problems expand). Anything else is expanded by SymPy."""
    if not isinstance(expr, sympy.Basic) or not _engine_polynomial(expr):
        return sympy.expand(expr)
    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        back = sympy2symengine(expr).expand()._sympy_()  # a SymEngine object, never text
    except (ImportError, RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return sympy.expand(expr)
    own = {s.name: s for s in expr.free_symbols}
    if {s.name for s in back.free_symbols} - own.keys():
        return sympy.expand(expr)
    return back.xreplace({s: own[s.name] for s in back.free_symbols})


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
    from sympy.core.function import _coeff_isneg
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
                a = a.as_two_terms()[1] if a.args[0] is sympy.S.NegativeOne else -a
            if any(_divides(f) for f in a.args):  # else fraction(a) is (a, 1): nothing to count here
                n, d = sympy.fraction(a)
                if n.is_Integer:
                    count += 1 + bool(n < 0)  # DIV, NEG
                    args.append(d)
                    continue
                if d is not sympy.S.One:
                    if not d.is_Integer:
                        args.append(d)
                    count += 1  # DIV
                    args.append(n)
                    continue
        elif a.is_Add:
            terms = a.args
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


#: above this many operations SymPy's general ``simplify`` and ``trigsimp`` are skipped
#: (they dominate run time on large expressions; the Pythagorean reduction below is cheap)
SIMPLIFY_LIMIT = 60
#: above this many operations :func:`tidy` only pulls out common factors (no factor, cancel or trig rewriting)
TIDY_LIMIT = 200
#: above this many operations sums are not searched for compound angles (the pairing grows with the square)
CONTRACT_LIMIT = 600
TRIGSIMP_LIMIT = 0
_ERRORS = (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError)


def _reduce_squares(expr: Any, of: Any, to: Any) -> Any:
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
        n, d = _reduce_squares(numerator, of, to), _reduce_squares(denominator, of, to)
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
    forms = [base, _reduce_squares(base, sympy.cos, sympy.sin), _reduce_squares(base, sympy.sin, sympy.cos)]
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
    for step in (cancel, factor_terms, lambda e: factor(cancel(e))):
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
    if ops(best) <= SIMPLIFY_LIMIT and not best.has(*_TRIG) and not _scaled_number(best):
        with contextlib.suppress(*_ERRORS):
            candidates.append(sympy.simplify(best))
    return smallest(candidates)


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
        candidates += [_reduce_squares(expanded, sympy.cos, sympy.sin),
                       _reduce_squares(expanded, sympy.sin, sympy.cos)]
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


@functools.lru_cache(maxsize=4096)
def tidy_sum_light(expr: Any) -> Any:
    """A cheap :func:`tidy_sum` for large systems: expanded, compound angles contracted, common factors out
    (one rewriting each instead of a search over candidates)."""
    if not isinstance(expr, sympy.Basic):
        return _number(expr)
    return factor_terms(compound_angles(expand(expr)))


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
    for factor in sympy.Mul.make_args(term):
        if factor.is_number or factor.has(sympy.sin, sympy.cos):
            continue
        if factor.is_Pow and factor.exp.is_Rational and not factor.exp.is_Integer:
            continue
        rigid.append(factor)
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
    for form in (square, sympy.factor(square)):
        root = sympy.sqrt(form.xreplace(reals)).xreplace({v: k for k, v in reals.items()})
        candidates += [root, tidy_abs(root)]
    return smallest(candidates)
