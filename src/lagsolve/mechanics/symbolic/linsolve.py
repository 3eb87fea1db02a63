r"""Solving the augmented system by its structure, with a bound on the size of what comes out.

Where the entries are polynomials in symbols and functions of them (every shipped problem), the whole
augmented system is solved at once, fraction-free, in a polynomial ring, after a bound on the size of
the result that declines a too large solve before it starts (:mod:`~lagsolve.mechanics.symbolic.ringsolve`).
Otherwise (floats, algebraic numbers) the equations :math:`M\ddot q = F + A^T\lambda`,
:math:`A\ddot q = \beta` are solved

* block by block: :math:`M` is split into the diagonal blocks its sparsity pattern allows
  (a diagonal :math:`M`, bodies that do not share coordinates), and each block is solved on
  its own, a 1×1 block by a division;
* for the multipliers through the Schur complement: with :math:`y = M^{-1}F` and
  :math:`X = M^{-1}A^T`,

  .. math:: (A X)\,\lambda = \beta - A y, \qquad \ddot q = y + X\lambda,

  an :math:`m\times m` system however many coordinates there are;
* in each small dense block by fraction-free elimination in a polynomial ring (one gcd per entry
  at the end; over the field of fractions when the coefficients are rational), each entry then
  written as ``sympy.cancel`` writes a rational function (:func:`cancelled`), or, where the entries are not
  polynomials in their functions, by elimination that cancels as it goes; and by the whole
  augmented matrix only when :math:`M` itself is singular (a coordinate without inertia).

Explicit accelerations of a large coupled system (a 4-link pendulum) are far too long to
read; as soon as an intermediate expression passes :data:`SIZE_LIMIT` operations the solve
stops with :class:`~lagsolve.mechanics.stages.StageSkipped`, and the matrix form is the
result, as textbooks write big systems.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.stages import StageTooLarge
from lagsolve.mechanics.symbolic.algebra import cancel, ops
from lagsolve.mechanics.symbolic.ringsolve import MAX_TERMS, cancelled, in_sympy_order, normalized, solve_in_ring
from lagsolve.mechanics.symbolic.ringsolve import (
    coupled as blocks,  # the diagonal blocks: the pattern's connected components
)

#: an explicit result (or an intermediate of the elimination) with more operations than this is not produced
SIZE_LIMIT = 1500


def _size(expr: Any) -> int:
    return ops(expr) if isinstance(expr, sympy.Basic) else 0


def _guard(exprs: list[Any], limit: int | None) -> None:
    if limit is None:
        return
    largest = max((_size(e) for e in exprs), default=0)
    if largest > limit:
        raise StageTooLarge(f"the explicit solution grows past {limit} operations per expression "
                           f"(one has {largest}); the matrix form M q̈ = F + Aᵀλ above is the result")


def solve_linear(system: sympy.Matrix, rhs: sympy.Matrix, limit: int | None = None) -> sympy.Matrix:
    """Solve a square symbolic system (``rhs`` may have several columns): over a polynomial fraction
    field when the entries allow it (:func:`_solve_in_ring`), else by Gaussian elimination that
    cancels as it goes. Either way each entry comes out cancelled, in the same form.

    Raises ``ValueError`` when no non-zero pivot is found (a singular system) and
    :class:`StageSkipped` when an entry grows past ``limit`` operations.
    """
    fast = _solve_in_ring(system, rhs)
    if fast is not None and (limit is None or max((_size(e) for e in fast), default=0) <= limit):
        return fast
    size, columns = system.rows, rhs.cols
    if size == 1:
        if not _nonzero(system[0, 0]):
            raise ValueError("no pivot in column 1")
        out = sympy.Matrix(1, columns, [cancel(rhs[0, j] / system[0, 0]) for j in range(columns)])
        _guard(list(out), limit)
        return out
    work = [list(system.row(i)) + list(rhs.row(i)) for i in range(size)]
    width = size + columns
    for col in range(size):
        pivot = min((r for r in range(col, size) if _nonzero(work[r][col])),
                    key=lambda r: (_size(work[r][col]), r), default=None)
        if pivot is None:
            raise ValueError(f"no pivot in column {col + 1}")
        work[col], work[pivot] = work[pivot], work[col]
        p = work[col][col]
        for r in range(col + 1, size):
            factor = work[r][col]
            if factor == 0:
                continue
            ratio = sympy.cancel(factor / p)
            work[r] = [sympy.cancel(work[r][k] - ratio * work[col][k]) if k >= col else work[r][k]
                       for k in range(width)]
            _guard(work[r][col:], limit)
    solution = [[sympy.Integer(0)] * columns for _ in range(size)]
    for r in reversed(range(size)):
        for j in range(columns):
            acc = work[r][size + j] - sum((work[r][k] * solution[k][j] for k in range(r + 1, size)), sympy.Integer(0))
            solution[r][j] = cancel(acc / work[r][r])
        _guard(solution[r], limit)
    return sympy.Matrix(solution)


def _solve_in_ring(system: sympy.Matrix, rhs: sympy.Matrix) -> sympy.Matrix | None:
    """The solution :func:`solve_linear` gives, found by elimination over the field of fractions of a
    polynomial ring (each sine, cosine or other function in the entries a variable of its own), which is
    many times faster than cancelling SymPy expressions at every step. Each entry is then cancelled, as
    elimination leaves it: ``cancel`` writes a rational function in one way, so the result is the same
    expression. None when the entries are not polynomials in such variables, or the system is singular
    (elimination then says why)."""
    from sympy.polys.matrices import DomainMatrix

    size = system.rows
    augmented = system.row_join(rhs)
    atoms = sorted({f for e in augmented for f in e.atoms(sympy.Function, sympy.Derivative)},
                   key=sympy.default_sort_key)
    variables = {f: sympy.Dummy() for f in atoms}
    try:
        matrix = DomainMatrix.from_Matrix(augmented.xreplace(variables))
        ring = matrix.domain
        if not (ring.is_ZZ or ring.is_QQ or (ring.is_PolynomialRing and (ring.domain.is_ZZ or ring.domain.is_QQ))):
            return None
        if ring.is_PolynomialRing and ring.domain.is_ZZ:
            # fraction-free (Bareiss) elimination, one gcd per entry at the end instead of one per step
            free, denominator, pivots = matrix.rref_den()
        else:
            field = matrix.to_field()
            reduced, pivots = field.rref()
    except (sympy.polys.polyerrors.PolynomialError, sympy.CoercionFailed, ValueError, TypeError,
            NotImplementedError):
        return None
    if tuple(pivots[:size]) != tuple(range(size)):
        return None
    back = {v: f for f, v in variables.items()}
    if ring.is_PolynomialRing and ring.domain.is_ZZ:
        ordered = in_sympy_order(ring.ring, back)

        def fraction(i: int, j: int) -> Any:
            numer, denom = free[i, size + j].element.cancel(denominator)
            if ordered is not None:
                return normalized(*(ordered(e) for e in (numer, denom)))
            return cancelled(numer.as_expr().xreplace(back), denom.as_expr().xreplace(back))

        return sympy.Matrix(size, rhs.cols, fraction)
    to_sympy = reduced.domain.to_sympy
    integral = reduced.domain.is_FractionField and reduced.domain.domain.is_ZZ

    def entry(i: int, j: int) -> Any:
        element = reduced[i, size + j].element
        if integral:
            return cancelled(element.numer.as_expr().xreplace(back), element.denom.as_expr().xreplace(back))
        return cancel(to_sympy(element).xreplace(back))

    return sympy.Matrix(size, rhs.cols, entry)


def _nonzero(value: Any) -> bool:
    if value == 0:
        return False
    return sympy.cancel(value) != 0


#: a dense block of M this large, with entries that vary, is not inverted symbolically at all (its determinant
#: alone has up to k! terms): the solve is known to be too large before it starts
DENSE_LIMIT = 4


def _solve_blocks(M: sympy.Matrix, rhs: sympy.Matrix, limit: int | None) -> sympy.Matrix:
    """:math:`M^{-1}` applied to ``rhs`` block by block."""
    out = sympy.zeros(M.rows, rhs.cols)
    groups = blocks(M)
    for group in groups:
        varying = sum(1 for i in group for k in group if i != k and M[i, k].free_symbols)
        if limit is not None and len(group) >= DENSE_LIMIT and varying > len(group) * (len(group) - 1) // 2:
            raise StageTooLarge(f"M has a dense {len(group)}×{len(group)} block whose entries vary, so "
                               "the explicit solution would be far too long to read; the matrix form M q̈ = F + Aᵀλ "
                               "above is the result")
    for group in groups:
        sub = M.extract(group, group)
        part = solve_linear(sub, rhs.extract(group, list(range(rhs.cols))), limit)
        for k, i in enumerate(group):
            for j in range(rhs.cols):
                out[i, j] = part[k, j]
    return out


def solve_structured(M: Any, F: Any, A: Any, beta: Any, limit: int | None = SIZE_LIMIT,
                     terms: int | None = MAX_TERMS) -> tuple[list[Any], list[Any]]:
    r"""(:math:`\ddot q`, :math:`\lambda`) of the augmented system, unsimplified (module docstring): in a
    polynomial ring when the entries allow it (:func:`~lagsolve.mechanics.symbolic.ringsolve.solve_in_ring`, after a
    bound on the size of the result that declines at once past ``terms`` terms), else by the structure below.

    Raises ``ValueError`` when the system is singular and :class:`StageSkipped` when the result
    would be larger than ``terms`` terms or ``limit`` operations per expression (``None``: no bound).
    """
    ring = solve_in_ring(M, F, A, beta, terms)
    if ring is not None:
        _guard([*ring[0], *ring[1]], limit)
        return ring
    M, F, A, beta = sympy.Matrix(M), sympy.Matrix(F), sympy.Matrix(A), sympy.Matrix(beta)
    m = A.rows
    try:
        if m == 0:
            return list(_solve_blocks(M, F, limit)), []
        both = _solve_blocks(M, sympy.Matrix.hstack(F, A.T), limit)
    except ValueError:
        if m == 0:
            raise
        return _solve_full(M, F, A, beta, limit)  # M alone is singular; the augmented system may not be
    y, X = both[:, 0], both[:, 1:]
    schur = (A * X).applyfunc(sympy.cancel)
    residual = (beta - A * y).applyfunc(sympy.cancel)
    lam = solve_linear(schur, residual, limit)
    acc = (y + X * lam).applyfunc(sympy.cancel)
    _guard(list(acc), limit)
    return list(acc), list(lam)


def _solve_full(M: sympy.Matrix, F: sympy.Matrix, A: sympy.Matrix, beta: sympy.Matrix,
                limit: int | None) -> tuple[list[Any], list[Any]]:
    n, m = M.rows, A.rows
    system = sympy.Matrix(sympy.BlockMatrix([[M, -A.T], [A, sympy.zeros(m, m)]]))
    solution = list(solve_linear(system, sympy.Matrix.vstack(F, beta), limit))
    return solution[:n], solution[n:]
