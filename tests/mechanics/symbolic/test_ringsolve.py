"""The augmented system solved fraction-free in a polynomial ring, and the bound on its size known before."""

from __future__ import annotations

import random

import numpy as np
import pytest
import sympy
from sympy.polys.matrices import DomainMatrix

from lagsolve.mechanics.stages import StageSkipped
from lagsolve.mechanics.symbolic.ringsolve import MAX_BLOCK, coupled, kkt, solve_in_ring, support_bound


def _chain(n: int) -> tuple[sympy.Matrix, sympy.Matrix]:
    """M and F of a planar n-link pendulum (equal masses and lengths), in the form the explicit solve receives them:
    products of cosines contracted to cos(θi − θk)."""
    th = sympy.symbols(f"th1:{n + 1}")
    w = sympy.symbols(f"w1:{n + 1}")
    m, length, g = sympy.symbols("m l g", positive=True)
    M = sympy.Matrix(n, n, lambda i, k: m * length**2 * (n - max(i, k)) * sympy.cos(th[i] - th[k]))
    F = sympy.Matrix([-m * length**2 * sum((n - max(i, k)) * sympy.sin(th[i] - th[k]) * w[k]**2 for k in range(n))
                      - (n - i) * m * g * length * sympy.sin(th[i]) for i in range(n)])
    return M, F


def _integral(K: sympy.Matrix, rhs: sympy.Matrix) -> tuple[DomainMatrix, list[sympy.Expr]]:
    augmented = K.row_join(rhs)
    atoms = sorted({f for e in augmented for f in e.atoms(sympy.Function)}, key=sympy.default_sort_key)
    dummies = {f: sympy.Dummy() for f in atoms}
    return DomainMatrix.from_Matrix(augmented.xreplace(dummies)), list(dummies.values())


def _terms(expr: sympy.Expr, gens: list[sympy.Expr]) -> int:
    return len(sympy.Poly(sympy.expand(expr), *gens).terms()) if expr != 0 else 0


@pytest.mark.parametrize("n", [2, 3, 4])
def test_support_bound_bounds_the_determinant_and_every_numerator(n: int) -> None:
    """The bound found before any algebra is at least the number of terms of det M and of each numerator of
    Cramer's rule, counted by SymPy's own determinant, and close to the largest of them."""
    M, F = _chain(n)
    matrix, dummies = _integral(M, F)
    bound = support_bound(matrix, tuple(range(n)), 10**6)
    plain = M.row_join(F).xreplace(dict(zip(sorted({f for e in M.row_join(F) for f in e.atoms(sympy.Function)},
                                                   key=sympy.default_sort_key), dummies, strict=True)))
    gens = sorted(plain.free_symbols, key=str)
    counts = [_terms(plain[:, :n].det(method="berkowitz"), gens)]
    for i in range(n):
        replaced = plain[:, :n].copy()
        replaced[:, i] = plain[:, n]
        counts.append(_terms(replaced.det(method="berkowitz"), gens))
    assert bound is not None and bound >= max(counts)
    assert bound <= 2 * max(counts)


def test_support_bound_gives_up_past_its_cap() -> None:
    """Past the cap the bound says so (None) instead of counting on."""
    M, F = _chain(5)
    matrix, _ = _integral(M, F)
    assert support_bound(matrix, tuple(range(5)), 100) is None


def test_a_large_dense_block_is_declined_before_any_elimination(monkeypatch: pytest.MonkeyPatch) -> None:
    """The 5-link pendulum's numerators have 545 terms: the solve declines at once, with the bound as its reason,
    and no elimination is started."""
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("the elimination started")

    monkeypatch.setattr(DomainMatrix, "rref_den", refuse)
    M, F = _chain(5)
    with pytest.raises(StageSkipped, match="too large: .* more than 400 terms"):
        solve_in_ring(M, F, sympy.zeros(0, 5), sympy.zeros(0, 1))


def test_too_many_coupled_unknowns_are_declined_at_once() -> None:
    """A block of more coupled unknowns than MAX_BLOCK is declined without bounding it."""
    n = MAX_BLOCK + 1
    x = sympy.symbols(f"x1:{n + 1}")
    M = sympy.Matrix(n, n, lambda i, k: 2 if i == k else (sympy.cos(x[i]) if abs(i - k) == 1 else 0))
    with pytest.raises(StageSkipped, match=f"{n} unknowns .* are coupled"):
        solve_in_ring(M, sympy.Matrix(x), sympy.zeros(0, n), sympy.zeros(0, 1))


def _random_system(seed: int) -> tuple[sympy.Matrix, ...]:
    rng = random.Random(seed)
    a, b = sympy.symbols("a b")
    s, c = sympy.sin(a), sympy.cos(a)
    pool = [0, 1, 2, a, b, s, c, a * c, b * s + 1, sympy.Rational(2, 3) * c]

    def entry() -> sympy.Expr:
        return rng.choice(pool)

    half = sympy.Matrix(4, 4, lambda i, k: entry() if (i < 2) == (k < 2) else 0)
    M = half + half.T + 7 * sympy.eye(4)
    F = sympy.Matrix(4, 1, lambda i, k: entry())
    A = sympy.Matrix(2, 4, lambda i, k: entry())
    beta = sympy.Matrix(2, 1, lambda i, k: sympy.sympify(entry()) / 3)
    return M, F, A, beta


@pytest.mark.parametrize("seed", range(3))
def test_ring_solution_equals_a_numeric_solve_and_is_cancelled(seed: int) -> None:
    """q̈ and λ (rational coefficients, sines and cosines, two coupled blocks) equal a numeric solve of the whole
    augmented system at random points, and each is written as sympy.cancel writes it (its own cancel, tree for
    tree)."""
    M, F, A, beta = _random_system(seed)
    found = solve_in_ring(M, F, A, beta)
    assert found is not None
    acc, lam = found
    K, rhs = kkt(M, F, A, beta)
    a, b = sympy.symbols("a b")
    system = sympy.lambdify((a, b), K, "numpy")
    right = sympy.lambdify((a, b), rhs, "numpy")
    ours = sympy.lambdify((a, b), [*acc, *lam], "numpy")
    rng = random.Random(seed)
    for _ in range(5):
        point = (rng.uniform(-1, 1), rng.uniform(-1, 1))
        reference = np.linalg.solve(np.array(system(*point), dtype=float), np.array(right(*point), dtype=float))
        assert np.allclose(np.array(ours(*point), dtype=float), reference.ravel(), rtol=1e-10, atol=1e-12)
    for e in (*acc, *lam):
        assert sympy.srepr(e) == sympy.srepr(sympy.cancel(e))


def test_rows_with_denominators_are_cleared_first() -> None:
    """Entries with polynomial denominators (a central force k/r², a rate over r) are solved as the rows
    cleared of them: the solution is that of the system as written."""
    r, th, k, m, w = sympy.symbols("r theta k m w")
    M = sympy.Matrix([[m, 0], [0, m * r**2]])
    F = sympy.Matrix([m * r * w**2 - k / r**2, -2 * m * r * w / r])
    found = solve_in_ring(M, F, sympy.zeros(0, 2), sympy.zeros(0, 1))
    assert found is not None
    acc, _ = found
    assert sympy.cancel(acc[0] - (r * w**2 - k / (m * r**2))) == 0
    assert sympy.cancel(acc[1] + 2 * w / r**2) == 0


def test_singular_block_raises() -> None:
    """Two identical constraints make the augmented system singular: ValueError, as the other routes raise."""
    m = sympy.Symbol("m")
    M = sympy.Matrix([[m, 0], [0, m]])
    A = sympy.Matrix([[1, 1], [2, 2]])
    with pytest.raises(ValueError, match="no pivot"):
        solve_in_ring(M, sympy.Matrix([0, -m]), A, sympy.zeros(2, 1))


def test_blocks_follow_the_pattern_of_the_augmented_matrix() -> None:
    """A constraint joins the blocks of the coordinates it involves; untouched coordinates stay apart."""
    a, b = sympy.symbols("a b")
    M = sympy.diag(a, b, a)
    K, _ = kkt(M, sympy.zeros(3, 1), sympy.Matrix([[1, 0, -1]]), sympy.zeros(1, 1))
    assert coupled(K) == [[0, 2, 3], [1]]


def test_a_system_too_coupled_is_declined_from_its_pattern() -> None:
    """too_coupled looks at the non-zero pattern only: a dense 11 × 11 M (eleven coupled accelerations) is declined
    with the explicit solve's note, a 20 × 20 M of 2 × 2 blocks (ten pairs) and a 10 × 10 dense M with one
    constraint on two of them (11 unknowns in one block) as the ring solve would judge them."""
    from lagsolve.mechanics.stages import StageTooLarge
    from lagsolve.mechanics.symbolic.ringsolve import MAX_BLOCK, too_coupled

    x = sympy.symbols("x0:20")
    dense = sympy.Matrix(11, 11, lambda i, j: sympy.cos(x[i] - x[j]))
    with pytest.raises(StageTooLarge, match="11 unknowns .* are coupled"):
        too_coupled(dense, sympy.zeros(0, 11))
    blocks = sympy.Matrix(20, 20, lambda i, j: sympy.cos(x[i] - x[j]) if i // 2 == j // 2 else 0)
    too_coupled(blocks, sympy.zeros(0, 20))  # ten blocks of two: fine
    ten = sympy.Matrix(MAX_BLOCK, MAX_BLOCK, lambda i, j: 1 + x[i] * x[j])
    too_coupled(ten, sympy.zeros(0, MAX_BLOCK))
    with pytest.raises(StageTooLarge):
        too_coupled(ten, sympy.Matrix([[1, -1] + [0] * (MAX_BLOCK - 2)]))
