"""Mode shapes of the normal modes (``lagsolve.mechanics.analysis.mode_shapes``), against the textbook ones and the
eigenvectors NumPy/SciPy give."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
import sympy

from lagsolve.mechanics.analysis.mode_shapes import exact_shapes, numeric_shapes

g, l, k, m = sympy.symbols("g l k m", positive=True)  # noqa: E741 - the rod length


def _parallel(u: np.ndarray, v: np.ndarray) -> bool:
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    return bool(abs(abs(u @ v) - np.linalg.norm(u) * np.linalg.norm(v)) <= 1e-9 * np.linalg.norm(u) * np.linalg.norm(v))


def test_coupled_pendulums_in_and_out_of_phase() -> None:
    """Two pendulums joined by a spring, hanging down (Taylor, ch. 11): (1, 1) for ω² = g/l, (1, -1) for
    ω² = g/l + 2k/m."""
    M0 = m * l**2 * sympy.eye(2)
    K = sympy.Matrix([[m * g * l + k * l**2, -k * l**2], [-k * l**2, m * g * l + k * l**2]])
    assert exact_shapes(M0, K, (g / l, g / l + 2 * k / m)) == ((1, 1), (1, -1))


def test_double_pendulum_shapes() -> None:
    """The double pendulum of equal masses and lengths (Taylor, §11.4): θ2/θ1 = √2 in the slow mode
    ω² = (2 - √2) g/l and -√2 in the fast one; each solves (K - ω² M0) u = 0 exactly."""
    M0 = m * l**2 * sympy.Matrix([[2, 1], [1, 1]])
    K = m * g * l * sympy.diag(2, 1)
    squares = ((2 - sympy.sqrt(2)) * g / l, (2 + sympy.sqrt(2)) * g / l)
    shapes = exact_shapes(M0, K, squares)
    assert shapes == ((1, sympy.sqrt(2)), (1, -sympy.sqrt(2)))
    for w, u in zip(squares, shapes, strict=True):
        assert sympy.simplify((K - w * M0) * sympy.Matrix(u)) == sympy.zeros(2, 1)


def test_repeated_frequencies_get_a_basis() -> None:
    """A repeated ω² has as many independent shapes: the isotropic bowl gets (1, 0) and (0, 1); a 3 × 3 system
    with a double root gets two vectors that span its null space."""
    assert exact_shapes(m * sympy.eye(2), m * g * sympy.eye(2), (g, g)) == ((1, 0), (0, 1))
    M0 = sympy.eye(3)
    K = sympy.Matrix([[2 * k, k, 0], [k, 2 * k, 0], [0, 0, 3 * k]])  # eigenvalues k, 3k, 3k
    shapes = exact_shapes(M0, K, (k, 3 * k, 3 * k))
    assert shapes is not None
    assert sympy.Matrix(shapes[0]).T * sympy.Matrix([1, 1, 0]) == sympy.zeros(1, 1)
    double = sympy.Matrix([list(shapes[1]), list(shapes[2])])
    assert double.rank() == 2
    for u in shapes[1:]:
        assert (K - 3 * k * M0) * sympy.Matrix(u) == sympy.zeros(3, 1)


def test_large_shapes_are_declined() -> None:
    """The general double pendulum's ω² hold two different square roots: their shapes are not written in
    closed form (None, quickly), the numeric ones are given instead."""
    m1, m2, l1, l2 = sympy.symbols("m1 m2 l1 l2", positive=True)
    M0 = sympy.Matrix([[(m1 + m2) * l1**2, m2 * l1 * l2], [m2 * l1 * l2, m2 * l2**2]])
    K = sympy.diag((m1 + m2) * g * l1, m2 * g * l2)
    s = sympy.Symbol("s")
    squares = tuple(sympy.roots(sympy.Poly((K - s * M0).det(), s)))
    assert exact_shapes(M0, K, squares) is None


@pytest.mark.parametrize("seed", range(5))
def test_numeric_shapes_are_scipys_eigenvectors(seed: int) -> None:
    """At numbers, each shape is parallel to the eigenvector SciPy's generalized symmetric solver gives for its
    ω², with its first component 1."""
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(3, 3))
    m0 = a @ a.T + 3 * np.eye(3)
    b = rng.normal(size=(3, 3))
    k0 = b + b.T
    w, vectors = scipy.linalg.eigh(k0, m0)
    shapes = numeric_shapes(m0, k0, list(w))
    assert shapes is not None
    for u, v in zip(shapes, vectors.T, strict=True):
        assert u[0] == 1.0
        assert _parallel(np.array(u), v)


def test_numeric_shapes_refuse_a_wrong_frequency() -> None:
    """A value that is no ω² of the pencil has no shape: None."""
    assert numeric_shapes(np.eye(2), np.diag([1.0, 2.0]), [1.0, 3.0]) is None
