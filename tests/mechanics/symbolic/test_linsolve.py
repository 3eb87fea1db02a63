"""Solving the augmented system by its structure: blocks, the Schur complement, the size bound."""

from __future__ import annotations

import random

import pytest
import sympy

from lagsolve.mechanics.stages import StageSkipped
from lagsolve.mechanics.symbolic.linsolve import blocks, solve_linear, solve_structured


def test_blocks_follow_the_sparsity_pattern() -> None:
    """A matrix with two coupled pairs and a lone entry splits into those three blocks."""
    a, b, c = sympy.symbols("a b c")
    M = sympy.Matrix([[a, 0, b, 0, 0], [0, c, 0, 0, 0], [b, 0, a, 0, 0], [0, 0, 0, a, c], [0, 0, 0, c, b]])
    assert blocks(M) == [[0, 2], [1], [3, 4]]


def _random_system(seed: int) -> tuple[sympy.Matrix, sympy.Matrix, sympy.Matrix, sympy.Matrix]:
    rng = random.Random(seed)
    x, y = sympy.symbols("x y")
    n, m = 4, 2

    def entry() -> sympy.Expr:
        return rng.randint(-3, 3) + rng.randint(0, 2) * x + rng.randint(0, 1) * y**2

    half = sympy.Matrix(n, n, lambda i, k: entry() if (i < 2) == (k < 2) else 0)
    M = half + half.T + 10 * sympy.eye(n)  # symmetric, two blocks, invertible for small x, y
    F = sympy.Matrix(n, 1, lambda i, k: entry())
    A = sympy.Matrix(m, n, lambda i, k: entry())
    beta = sympy.Matrix(m, 1, lambda i, k: entry())
    return M, F, A, beta


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4))
def test_structured_solve_agrees_with_sympy(seed: int) -> None:
    """The block and Schur-complement solve equals SymPy's LU solve of the whole augmented system."""
    M, F, A, beta = _random_system(seed)
    acc, lam = solve_structured(M, F, A, beta, None)
    m = A.rows
    augmented = sympy.Matrix(sympy.BlockMatrix([[M, -A.T], [A, sympy.zeros(m, m)]]))
    reference = augmented.LUsolve(sympy.Matrix.vstack(F, beta))
    x, y = sympy.symbols("x y")
    for point in ({x: sympy.Rational(1, 3), y: sympy.Rational(-2, 7)}, {x: sympy.Rational(3, 5), y: 1}):
        ours = [e.subs(point) for e in (*acc, *lam)]
        theirs = [sympy.nsimplify(e.subs(point)) for e in reference]
        assert [sympy.simplify(a - b) for a, b in zip(ours, theirs, strict=True)] == [0] * len(ours)


def test_singular_mass_matrix_falls_back_to_the_augmented_system() -> None:
    """A coordinate without inertia that a constraint ties to another is still solved (M alone is singular)."""
    m, g = sympy.symbols("m g", positive=True)
    M = sympy.Matrix([[m, 0], [0, 0]])
    F = sympy.Matrix([-m * g, 0])
    A = sympy.Matrix([[1, -1]])
    acc, lam = solve_structured(M, F, A, sympy.Matrix([0]), None)
    assert acc == [-g, -g] and lam == [0]  # m a1 = -m g + λ, 0 = -λ, a1 = a2


def test_size_bound_stops_the_solve() -> None:
    """An elimination whose entries grow past the bound stops with a 'too large' reason."""
    xs = sympy.symbols("x1:6")
    M = sympy.Matrix(5, 5, lambda i, k: sympy.cos(xs[i] - xs[k]) * (5 - max(i, k)))
    F = sympy.Matrix([sympy.sin(x) for x in xs])
    with pytest.raises(StageSkipped, match="too large"):
        solve_structured(M, F, sympy.zeros(0, 5), sympy.zeros(0, 1), 200)


def test_solve_linear_with_several_right_hand_sides() -> None:
    """solve_linear solves for every column of the right-hand side at once."""
    a, b = sympy.symbols("a b")
    system = sympy.Matrix([[a, 1], [1, b]])
    rhs = sympy.Matrix([[1, 0], [0, 1]])
    assert sympy.simplify(solve_linear(system, rhs) - system.inv()) == sympy.zeros(2, 2)


def test_ring_solution_is_written_as_sympy_cancel_writes_it() -> None:
    """Entries of a fraction-free solve (sines, cosines, a declared function's derivative and symbols whose
    names sort in several ways) come out in sympy.cancel's own form, tree for tree, and equal an
    independent solve (Cramer's rule, cancelled by SymPy)."""
    a, b, m, l, z = sympy.symbols("a b m l z_1")  # noqa: E741 - the rod length
    f = sympy.Function("f")
    c, s = sympy.cos(a - b), sympy.sin(b)
    system = sympy.Matrix([[2 * m * l**2, -m * l**2 * c, 0], [-m * l**2 * c, m * l**2, z * s],
                           [0, z * s, 3 + f(a).diff(a)]])
    rhs = sympy.Matrix([[-m * sympy.sin(a), 1], [l * z * s * c, -2], [b * m - 1, 7 * c]])
    solution = solve_linear(system, rhs)
    determinant = system.det()
    for j in range(rhs.cols):
        for i in range(system.rows):
            replaced = system.copy()
            replaced[:, i] = rhs[:, j]
            expected = sympy.cancel(replaced.det() / determinant)
            assert sympy.srepr(solution[i, j]) == sympy.srepr(sympy.cancel(solution[i, j]))
            assert sympy.expand(solution[i, j] - expected) == 0 or sympy.cancel(solution[i, j] - expected) == 0
