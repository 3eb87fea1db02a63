r"""The shapes of the normal modes: for each :math:`\omega^2` of :math:`\det(K - \omega^2 M_0) = 0`, a vector
:math:`u \ne 0` with

.. math:: (K - \omega^2 M_0)\,u = 0,

so that :math:`\delta q = u \cos(\omega t)` solves the linearized equations :math:`M_0\,\delta\ddot q + K\,\delta q
= 0`. Each shape is scaled so that its first non-zero component is 1 (the two pendulums joined by a spring:
:math:`(1, 1)` in phase, :math:`(1, -1)` out of phase).

:func:`exact_shapes` finds them symbolically for up to three coordinates: a simple root leaves
:math:`N = K - \omega^2 M_0` of rank :math:`n - 1`, and every non-zero column of its adjugate is a shape
(:math:`N \operatorname{adj} N = \det N\, I = 0`); a double root of a 3 × 3 system leaves one independent row
:math:`w`, and :math:`e_j - (w_j/w_i)\,e_i` span what is orthogonal to it; where :math:`N = 0` every direction is a
shape. Each one is checked, :math:`N u` proved zero. :func:`numeric_shapes` gives them at numbers, from the
singular vectors of :math:`N` for its smallest singular values.

Notes
-----
* Shapes are given only where the normal modes are (no gyroscopic or damping terms).
* The shapes of a repeated :math:`\omega^2` are one basis of its space of shapes, not the only one.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.symbolic.algebra import expand, ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.simplify import tidy

#: a shape component larger than this (operations) is not given in closed form
SHAPE_LIMIT = 60


def exact_shapes(M0: Any, K: Any, squares: tuple[Any, ...]) -> tuple[tuple[Any, ...], ...] | None:
    """One shape per entry of ``squares`` (a repeated ω² gets as many independent ones), in their order; None
    when one is not found exactly, not proved, or too large.

    >>> import sympy
    >>> g, l, k, m = sympy.symbols("g l k m", positive=True)
    >>> M0 = m*l**2*sympy.eye(2)
    >>> K = sympy.Matrix([[m*g*l + k*l**2, -k*l**2], [-k*l**2, m*g*l + k*l**2]])
    >>> exact_shapes(M0, K, (g/l, g/l + 2*k/m))
    ((1, 1), (1, -1))
    """
    M0, K = sympy.Matrix(M0), sympy.Matrix(K)
    n = K.rows
    if n > 3 or M0.rows != n:
        return None
    bases: dict[Any, list[tuple[Any, ...]]] = {}
    if any(ops(r) > SHAPE_LIMIT or len(_radicals(r)) > 1 for r in squares):
        return None  # its shape would be larger still (the general double pendulum's, with two roots)
    for r in dict.fromkeys(squares):
        N = (K - r * M0).applyfunc(expand)
        basis = _null_space(N, squares.count(r))
        if basis is None:
            return None
        bases[r] = basis
    used: dict[Any, int] = {}
    out = []
    for r in squares:
        out.append(bases[r][used.get(r, 0)])
        used[r] = used.get(r, 0) + 1
    return tuple(out)


def _simpler(e: Any) -> Any:
    """``e`` tidied, with a radical out of its denominator when it has one (rationalizing several is dear)."""
    if ops(e) > 2 * SHAPE_LIMIT:
        return e
    if len(_radicals(e)) == 1:
        e = sympy.radsimp(e)
    return tidy(e)


def _radicals(e: Any) -> set[Any]:
    """The roots (non-integer powers) in ``e``."""
    return {p for p in e.atoms(sympy.Pow) if p.exp.is_Rational and not p.exp.is_Integer}


def _null_space(N: Any, multiplicity: int) -> list[tuple[Any, ...]] | None:
    """``multiplicity`` independent vectors u with N u = 0, each scaled and checked; None when not found."""
    n = N.rows
    nonzero = [[not _zero(e) for e in N.row(i)] for i in range(n)]
    if not any(any(row) for row in nonzero):
        return _unit_vectors(n, multiplicity)
    if multiplicity == 1:
        return _adjugate_vector(N)
    if multiplicity == n - 1 and n == 3:
        return _plane_of_a_row(N, nonzero)
    return None


def _unit_vectors(n: int, multiplicity: int) -> list[tuple[Any, ...]] | None:
    """The first ``multiplicity`` unit vectors of n dimensions (N = 0: every vector is in its null space)."""
    vectors = [tuple(sympy.Integer(1 if i == j else 0) for i in range(n)) for j in range(n)]
    return vectors[:multiplicity] if multiplicity <= n else None


def _adjugate_vector(N: Any) -> list[tuple[Any, ...]] | None:
    """The one vector of N's null space (N of rank n - 1): the first non-zero column of its adjugate, scaled and
    checked; None when a column is too large or none passes."""
    n = N.rows
    adjugate = N.adjugate(method="berkowitz")
    for j in range(n):
        column = [expand(adjugate[i, j]) for i in range(n)]
        if any(ops(c) > 2 * SHAPE_LIMIT for c in column):
            return None
        if all(_zero(c) for c in column):
            continue
        u = _scaled(column)
        return [u] if u is not None and _checked(N, u) else None
    return None


def _plane_of_a_row(N: Any, nonzero: list[list[bool]]) -> list[tuple[Any, ...]] | None:
    """The two vectors of the null space of a 3 × 3 N of rank 1 (``nonzero`` marks its non-zero entries): those
    orthogonal to its first non-zero row w, one for each component j but w's first non-zero one (lead), with
    u_j = 1 and u_lead = -w_j/w_lead; None when one is too large or fails the check."""
    n = N.rows
    i, w = next((i, N.row(i)) for i in range(n) if any(nonzero[i]))
    lead = next(j for j in range(n) if nonzero[i][j])
    vectors = []
    for j in range(n):
        if j == lead:
            continue
        column = [sympy.Integer(0)] * n
        column[j] = sympy.Integer(1)
        column[lead] = -w[j] / w[lead]
        u = _scaled(column)
        if u is None or not _checked(N, u):
            return None
        vectors.append(u)
    return vectors


def _scaled(column: list[Any]) -> tuple[Any, ...] | None:
    """``column`` divided by its first non-zero component, each component simplified; None when too large."""
    lead = next(c for c in column if not _zero(c))
    u = tuple(sympy.Integer(0) if _zero(c) else _simpler(sympy.cancel(c / lead)) for c in column)
    return None if any(ops(c) > SHAPE_LIMIT for c in u) else u


def _zero(e: Any) -> bool:
    """``e`` is proved zero: it expands to 0, or (when small) the exact rewritings of ``proved_zero`` show it."""
    e = expand(e)
    return e == 0 or (ops(e) <= 2 * SHAPE_LIMIT and proved_zero(e))


def _checked(N: Any, u: tuple[Any, ...]) -> bool:
    """N u is proved zero."""
    return all(_zero(sympy.cancel(e)) for e in N * sympy.Matrix(u))


def numeric_shapes(m0: Any, k0: Any, squares: list[float]) -> tuple[tuple[float, ...], ...] | None:
    """The shapes at numbers (arrays ``m0``, ``k0``; ``squares`` the ω², a repeated one given as often as it
    repeats), each with its first component above rounding equal to 1; None when N is not singular enough at a
    given ω² (the ω² is not one of the pencil's)."""
    import numpy as np

    m0, k0 = np.asarray(m0, dtype=float), np.asarray(k0, dtype=float)
    scale = max(1.0, float(np.max(np.abs(k0))), float(np.max(np.abs(m0))))
    groups: dict[int, list[int]] = {}
    for i, w in enumerate(squares):
        key = next((j for j in groups if abs(squares[j] - w) <= 1e-9 * max(1.0, abs(w))), i)
        groups.setdefault(key, []).append(i)
    shapes: dict[int, tuple[float, ...]] = {}
    for first, members in groups.items():
        _, sigma, vt = np.linalg.svd(k0 - squares[first] * m0)
        k = len(members)
        if np.any(sigma[len(sigma) - k:] > 1e-7 * scale * max(1.0, abs(squares[first]))):
            return None
        basis = sorted((_numeric_scaled(v) for v in vt[len(sigma) - k:]),
                       key=lambda u: (next(i for i, x in enumerate(u) if x != 0), u))
        for member, u in zip(members, basis, strict=True):
            shapes[member] = u
    return tuple(shapes[i] for i in range(len(squares)))


def _numeric_scaled(v: Any) -> tuple[float, ...]:
    """``v`` divided by its first component that is not rounding noise, rounded to 8 significant digits."""
    import numpy as np

    size = float(np.max(np.abs(v)))
    lead = next(x for x in v if abs(x) > 1e-9 * size)
    return tuple(0.0 if abs(x) <= 1e-12 * size else float(f"{x / lead:.8g}") for x in v)
