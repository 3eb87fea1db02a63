"""Signs of symbolic expressions (``lagsolve.mechanics.symbolic.signs``)."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.symbolic.signs import relation, sign_core

m, g, R, W, k = sympy.symbols("m g R Omega k", positive=True)
theta, p = sympy.symbols("theta p", real=True)


def test_positive_factors_are_dropped():
    """m R (g - R Omega^2) has the sign of g - R Omega^2."""
    assert sign_core(m * R * (g - R * W**2)) == (None, g - R * W**2)


def test_known_signs_are_decided():
    """-3 g/R is negative; 3 p^2/(m r^4)-like terms with even powers are positive."""
    assert sign_core(-3 * g / R) == (-1, 1)
    assert sign_core(3 * p**2 * g / m) == (1, 1)
    assert sign_core(sympy.Abs(p) ** sympy.Rational(-8, 3) * g) == (1, 1)


def test_odd_powers_keep_their_base():
    """g (1 + 3 cos^2)/(l cos) has the sign of cos(theta)."""
    l = sympy.Symbol("l", positive=True)  # noqa: E741 - a length
    expr = g * (1 + 3 * sympy.cos(theta) ** 2) / (l * sympy.cos(theta))
    assert sign_core(expr) == (None, sympy.cos(theta))


def test_relation_moves_negative_terms_right():
    """g - R Omega^2 > 0 is written g > R Omega^2 (and >= when not strict)."""
    assert relation(g - R * W**2) == sympy.StrictGreaterThan(g, R * W**2, evaluate=False)
    assert isinstance(relation(g - R * W**2, strict=False), sympy.GreaterThan)
