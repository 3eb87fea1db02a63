"""mechanics/surface.newton: the one Newton iteration onto a constraint surface, in floats and in mpmath."""

from __future__ import annotations

import math

import mpmath
import numpy as np

from lagsolve.mechanics.equations.surface import least_squares, newton


def test_least_norm_step_reaches_the_circle_from_any_side():
    """x² + y² = 4 with two unknowns (a least-norm step): the point reached is on the circle, on the ray of
    the start (the least-norm Newton step moves along the gradient, which is radial here)."""
    for start in ([0.3, 0.4], [-3.0, 1.0], [5.0, -5.0]):
        x, ok = newton(lambda x: [x[0] ** 2 + x[1] ** 2 - 4],
                       lambda x: np.array([[2 * x[0], 2 * x[1]]]), start, step=least_squares, tolerance=1e-13)
        assert ok
        assert math.isclose(math.hypot(*x), 2.0, rel_tol=1e-12)
        assert math.isclose(math.atan2(x[1], x[0]), math.atan2(start[1], start[0]), abs_tol=1e-12)


def test_square_system_in_mpmath_to_thirty_digits():
    """cos q = q (the Dottie number, 0.739085133215160641655312087673873...) with LU steps at 40 digits."""
    with mpmath.workdps(40):
        x, ok = newton(lambda x: [mpmath.cos(x[0]) - x[0]], lambda x: mpmath.matrix([[-mpmath.sin(x[0]) - 1]]),
                       [mpmath.mpf(1)], step=lambda J, r: list(mpmath.lu_solve(J, mpmath.matrix(r))),
                       tolerance=mpmath.mpf(10) ** -35)
        assert ok
        assert abs(x[0] - mpmath.findroot(lambda q: mpmath.cos(q) - q, 0.7)) < mpmath.mpf(10) ** -30


def test_stops_without_converging_on_singular_steps_nan_and_divergence():
    singular = newton(lambda x: [x[0] ** 2 + 1], lambda x: mpmath.matrix([[0]]), [mpmath.mpf(0)],
                      step=lambda J, r: list(mpmath.lu_solve(J, mpmath.matrix(r))), tolerance=1e-12)
    assert singular[1] is False
    nan = newton(lambda x: [math.nan], lambda x: np.eye(1), [1.0], step=least_squares, tolerance=1e-12)
    assert nan[1] is False
    # x² + 1 = 0 has no real root: Newton wanders and is stopped at the bound or after its iterations
    wander = newton(lambda x: [x[0] ** 2 + 1], lambda x: np.array([[2 * x[0]]]), [0.5], step=least_squares,
                    tolerance=1e-12, bound=1e6)
    assert wander[1] is False
    complex_residual = newton(lambda x: [mpmath.mpc(1, 1)], lambda x: mpmath.eye(1), [mpmath.mpf(1)],
                              step=lambda J, r: list(mpmath.lu_solve(J, mpmath.matrix(r))), tolerance=1e-12)
    assert complex_residual[1] is False
