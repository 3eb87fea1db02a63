r"""The augmented system solved at once, fraction-free, in a polynomial ring, with its size known first.

The equations :math:`M\ddot q = F + A^T\lambda`, :math:`A\ddot q = \beta` are one square system

.. math::
    K \begin{pmatrix}\ddot q\\ \lambda\end{pmatrix} = \begin{pmatrix}F\\ \beta\end{pmatrix},
    \qquad K = \begin{pmatrix} M & -A^T \\ A & 0\end{pmatrix}.

Each sine, cosine or other function in its entries is a variable of its own (a generator), and each row
is multiplied by the least common multiple of its denominators (which leaves the solution as it is), so
every entry is a polynomial with integer coefficients. The unknowns fall into the blocks the pattern of
:math:`K` couples (bodies that share no coordinate and no constraint are separate blocks); each block is
solved by fraction-free (Bareiss) elimination, which divides exactly at every step and so never leaves the
ring. Each unknown is then a numerator over the block's one denominator (both determinants, by Cramer's
rule), cancelled by one gcd and written as ``sympy.cancel`` writes a rational function: the quotient is
exact and its cancelled form unique, so it is the same expression whatever route found it.

**The size first** (:func:`support_bound`). Before any algebra, the number of terms the determinant and
the numerators can have is bounded: a determinant is a signed sum over permutations of products of one
entry per row and column, and with every coefficient taken positive nothing can cancel, so the monomials of
that sum include every monomial of the determinant. They are collected by dynamic programming over the
column sets the first rows use, with monomials packed into integers (a product is one addition), in a few
milliseconds. The bound is close (the 5-link pendulum's numerators: 545 bounded, 545 found; SymPy's
two-wheeled cart: 193 bounded, 117 found) and the cost of the elimination and of the gcds grows with it, so
a block past :data:`MAX_TERMS` is not started: the solve declines at once, with the bound as its reason.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy

from lagsolve.mechanics.stages import StageTooLarge
from lagsolve.mechanics.symbolic.algebra import known_cancelled

#: a coupled block of more unknowns (coordinates and multipliers) than this is not bounded (the bound costs
#: 2^k steps) nor solved explicitly when a bound on the size is asked for
MAX_BLOCK = 10

#: a block whose determinant or numerators may have more terms than this is not solved explicitly: the
#: 4-link pendulum's have 92 (0.2 s), PyDy's three-coordinate system 154, the 5-link pendulum's 545 (3.5 s
#: of elimination and gcds, and each acceleration 9000 operations long)
MAX_TERMS = 400


def kkt(M: Any, F: Any, A: Any, beta: Any) -> tuple[sympy.Matrix, sympy.Matrix]:
    """The augmented matrix :math:`K`, shape (n + m, n + m), and its right-hand side (module docstring)."""
    M, F, A, beta = sympy.Matrix(M), sympy.Matrix(F), sympy.Matrix(A), sympy.Matrix(beta)
    m = A.rows
    if m == 0:
        return M, F
    K = sympy.Matrix(sympy.BlockMatrix([[M, -A.T], [A, sympy.zeros(m, m)]]))
    return K, F.col_join(beta)


def coupled(K: sympy.Matrix) -> list[list[int]]:
    """The index sets of the unknowns the non-zero pattern of ``K`` couples (the connected components of the
    pattern of :math:`K + K^T`), each sorted, in order of their first index."""
    n = K.rows
    parent = list(range(n))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for k in range(i + 1, n):
            if K[i, k] != 0 or K[k, i] != 0:
                parent[find(i)] = find(k)
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(find(i), []).append(i)
    return sorted(groups.values(), key=lambda g: g[0])


def check_blocks(groups: list[tuple[int, ...]] | list[list[int]]) -> None:
    """Raise :class:`StageTooLarge` when a block of coupled unknowns (:func:`coupled`) is larger than
    :data:`MAX_BLOCK`: no explicit solution is sought for it."""
    largest = max((len(g) for g in groups), default=0)
    if largest > MAX_BLOCK:
        raise StageTooLarge(f"{largest} unknowns (accelerations and multipliers) are coupled, more than the "
                            f"{MAX_BLOCK} an explicit solution is sought for; the matrix form M q̈ = F + Aᵀλ above is "
                            "the result")


def too_coupled(M: Any, A: Any) -> None:
    """:func:`check_blocks` of the augmented system of ``M`` and ``A`` from their non-zero pattern alone, before
    any work on the entries (a 20-link chain is declined at once, not after its 400 entries are rewritten)."""
    M, A = sympy.Matrix(M), sympy.Matrix(A)
    K, _ = kkt(M, sympy.zeros(M.rows, 1), A, sympy.zeros(A.rows, 1))
    check_blocks(coupled(K))


def solve_in_ring(M: Any, F: Any, A: Any, beta: Any, cap: int | None = MAX_TERMS) -> tuple[list[Any], list[Any]] | None:
    r"""(:math:`\ddot q`, :math:`\lambda`) of the augmented system, each entry cancelled as ``sympy.cancel``
    writes it; None when the entries are not polynomials over the rationals in symbols and function atoms
    once the rows are cleared of denominators (another route is then needed).

    Raises :class:`StageSkipped` ("too large") before any elimination when a block of coupled unknowns is
    larger than :data:`MAX_BLOCK` or its determinant or a numerator may have more than ``cap`` terms
    (``None``: no bound), and ``ValueError`` when a block is singular.
    """
    K, rhs = kkt(M, F, A, beta)
    n = sympy.Matrix(M).rows
    groups = [tuple(g) for g in coupled(K)]
    if cap is not None:
        check_blocks(groups)
    found = _ring_matrix(K.row_join(rhs))
    if found is None:
        return None
    matrix, back = found
    if cap is not None:
        for group in groups:
            bound = support_bound(matrix, group, cap)
            if bound is None:
                raise StageTooLarge(
                    f"the explicit solution's determinant or numerators would have more than {cap} terms "
                    f"({len(group)} coupled unknowns), far too long to read; the matrix form M q̈ = F + Aᵀλ above is "
                    "the result")
    solution = _solve_blocks(matrix, back, groups)
    return solution[:n], solution[n:]


def _ring_matrix(augmented: sympy.Matrix) -> tuple[Any, dict[Any, Any]] | None:
    """``augmented`` as a DomainMatrix over the integers or a polynomial ring over them (each function atom a
    Dummy generator, each row cleared of denominators), with the map back from the Dummies; None when its
    entries are not rational functions with rational coefficients."""
    from sympy.polys.matrices import DomainMatrix

    atoms = sorted({f for e in augmented for f in e.atoms(sympy.Function, sympy.Derivative)},
                   key=sympy.default_sort_key)
    variables = {f: sympy.Dummy() for f in atoms}
    try:
        matrix = DomainMatrix.from_Matrix(augmented.xreplace(variables))
    except (sympy.polys.polyerrors.PolynomialError, sympy.CoercionFailed, ValueError, TypeError,
            NotImplementedError):
        return None
    integral = _integral(matrix)
    if integral is None:
        return None
    return integral, {v: f for f, v in variables.items()}


def _integral(matrix: Any) -> Any:
    """``matrix`` over the integers or a polynomial ring over them, each row multiplied by the least common
    multiple of its denominators (the solution is unchanged); None for any other domain (floats, algebraic
    numbers, expressions SymPy keeps whole)."""
    from sympy import QQ, ZZ
    from sympy.polys.matrices import DomainMatrix
    from sympy.polys.rings import PolyRing

    domain = matrix.domain
    if domain.is_ZZ or (domain.is_PolynomialRing and domain.domain.is_ZZ):
        return matrix
    if domain.is_QQ:
        out = []
        for row in matrix.to_list():
            lcm = ZZ.one
            for e in row:
                lcm = ZZ.lcm(lcm, QQ.denom(e))
            out.append([ZZ(QQ.numer(e) * (lcm // QQ.denom(e))) for e in row])
        return DomainMatrix(out, matrix.shape, ZZ)
    if domain.is_FractionField and (domain.domain.is_ZZ or domain.domain.is_QQ):
        ring = domain.field.ring
        rows = []
        for row in matrix.to_list():
            lcm = ring.one
            for e in row:
                lcm = lcm.lcm(e.denom)
            rows.append([e.numer * lcm.exquo(e.denom) for e in row])
        if ring.domain.is_ZZ:
            return DomainMatrix(rows, matrix.shape, ring.to_domain())
        polynomials = rows
    elif domain.is_PolynomialRing and domain.domain.is_QQ:
        ring = domain.ring
        polynomials = matrix.to_list()
    else:
        return None
    target = PolyRing(ring.symbols, ZZ, ring.order)
    out = []
    for row in polynomials:
        lcm = ZZ.one
        for e in row:
            for c in e.values():
                lcm = ZZ.lcm(lcm, QQ.denom(c))
        out.append([target.from_dict({m: ZZ(QQ.numer(c) * (lcm // QQ.denom(c))) for m, c in e.items()}) for e in row])
    return DomainMatrix(out, matrix.shape, target.to_domain())


def _solve_blocks(matrix: Any, back: dict[Any, Any], groups: list[tuple[int, ...]]) -> list[Any]:
    """Each block of the integral augmented ``matrix`` solved fraction-free, each unknown cancelled and written
    as ``sympy.cancel`` writes it. Raises ``ValueError`` when a block is singular."""
    domain = matrix.domain
    ordered = in_sympy_order(domain.ring, back) if domain.is_PolynomialRing else None
    size = matrix.shape[0]
    out: list[Any] = [sympy.Integer(0)] * size
    for group in groups:
        free, denominator, pivots = matrix.extract(list(group), [*group, size]).rref_den()
        if tuple(pivots[:len(group)]) != tuple(range(len(group))):
            raise ValueError(f"no pivot in column {len(pivots) + 1} of a block of {len(group)} unknowns")
        den = getattr(denominator, "element", denominator)
        for k, i in enumerate(group):
            num = free[k, len(group)].element
            if not domain.is_PolynomialRing:
                out[i] = sympy.Rational(int(num), int(den))
                continue
            numer, denom = num.cancel(den)
            if ordered is not None:
                out[i] = normalized(ordered(numer), ordered(denom))
            else:
                out[i] = cancelled(numer.as_expr().xreplace(back), denom.as_expr().xreplace(back))
    return out


def support_bound(matrix: Any, group: tuple[int, ...], cap: int) -> int | None:
    """An upper bound on the number of terms of the determinant of the block ``group`` of the integral
    ``matrix`` (its last column the right-hand side) and of each numerator of Cramer's rule, or None as soon
    as it passes ``cap`` (module docstring).

    The column sets of r columns hold, after r rows, the support of the permanents of those r×r minors; the
    right-hand side is one more column, so after the last row the column sets are the determinant and, with
    column i replaced by the right-hand side, numerator i."""
    rhs = matrix.shape[1] - 1
    columns = [*group, rhs]
    rows = [[matrix[i, c].element for c in columns] for i in group]
    if not matrix.domain.is_PolynomialRing:
        return 1
    degree = sum(max((sum(m) for e in row if e for m in e), default=0) for row in rows)
    width = max(degree, 1).bit_length() + 1

    def pack(monomial: tuple[int, ...]) -> int:
        out = 0
        for k, e in enumerate(monomial):
            out |= e << (width * k)
        return out

    supports = [[{pack(m) for m in e} if e else set() for e in row] for row in rows]
    ways: dict[int, set[int]] = {0: {0}}
    for row in supports:
        step: dict[int, set[int]] = {}
        for used, found in ways.items():
            for col, entry in enumerate(row):
                if entry and not used & (1 << col):
                    target = step.setdefault(used | (1 << col), set())
                    target.update(a + b for a in found for b in entry)
                    if len(target) > cap:
                        return None
        ways = step
    return max((len(s) for s in ways.values()), default=0)


def cancelled(numer: Any, denom: Any) -> Any:
    """``sympy.cancel(numer / denom)`` for polynomials ``numer`` and ``denom`` (in symbols and function
    atoms, integer coefficients) already without a common factor, as elimination over a fraction field
    leaves them: ``cancel`` writes P/Q with P and Q coprime over the integers and the leading coefficient
    of Q (in the order of its generators) positive, and that is all that is left to do here; the gcd that
    ``cancel`` would look for again is 1. Falls back on ``sympy.cancel`` outside that case."""
    from sympy.polys.rings import sring

    try:
        ring, (P, Q) = sring((numer, denom))
    except (sympy.polys.polyerrors.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
        return sympy.cancel(numer / denom)
    atoms = {a for e in (numer, denom) for a in e.atoms(sympy.Function, sympy.Derivative)}
    if not ring.ngens or not ring.domain.is_ZZ or not Q or not atoms <= set(ring.symbols):
        # (an atom the ring writes through another, exp(2 x) as exp(x)², may share a factor with it)
        return sympy.cancel(numer / denom)
    return normalized(P, Q)


def in_sympy_order(ring: Any, back: dict[Any, Any]) -> Callable[[Any], Any] | None:
    """A map of the polynomials of ``ring`` (over the integers, its generators symbols and the Dummies of
    ``back``) into the ring ``sympy.cancel`` would write them in: the same generators, the Dummies replaced by
    the function atoms they stand for, in SymPy's order of generators. :func:`cancelled` finds that ring by
    reading the expressions again, at a cost many times that of the elimination's own cancelling; here the
    monomials are only permuted. None when that ring may have other generators (an ``exp``, which SymPy
    writes through another: exp(2 x) as exp(x)²; anything but symbols and function atoms)."""
    from sympy.polys.polyutils import _sort_gens
    from sympy.polys.rings import PolyRing

    gens = [back.get(g, g) for g in ring.symbols]
    if not all(g.is_Symbol or (isinstance(g, sympy.Function | sympy.Derivative) and not isinstance(g, sympy.exp))
               for g in gens) or len(set(gens)) != len(gens):
        return None
    order = _sort_gens(gens)
    if len(order) != len(gens):
        return None
    target = PolyRing(order, ring.domain, ring.order)
    place = [gens.index(g) for g in order]

    def ordered(element: Any) -> Any:
        return target.from_dict({tuple(m[k] for k in place): c for m, c in element.items()})

    return ordered


def normalized(P: Any, Q: Any) -> Any:
    """P/Q as ``sympy.cancel`` writes it, for coprime P and Q over the integers in the ring it uses: no common
    integer content, the leading coefficient of Q positive (the last steps of :func:`cancelled`)."""
    if not P:
        return sympy.Integer(0)
    ring = P.ring
    content = ring.domain.gcd(P.content(), Q.content())
    if content != 1:
        P, Q = P.quo_ground(content), Q.quo_ground(content)
    if Q.LC < 0:
        P, Q = -P, -Q
    return known_cancelled(P.as_expr() / Q.as_expr())
