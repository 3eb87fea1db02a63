"""Zero tests (``lagsolve.mechanics.symbolic.identities``): proved, disproved, or honestly undecided."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.symbolic.identities import Zero, numerically_zero, proved_zero, zero_status

x = sympy.Symbol("x", real=True)
f = sympy.Function("f", real=True)


def test_pythagoras_is_proved():
    """sin^2 + cos^2 - 1 is proved zero by exact rewriting."""
    assert zero_status(sympy.sin(x) ** 2 + sympy.cos(x) ** 2 - 1) is Zero.PROVED
    assert proved_zero(sympy.Integer(0))


def test_non_zero_is_shown_by_a_value():
    """sin^2 - 1 is non-zero at a random point."""
    assert zero_status(sympy.sin(x) ** 2 - 1) is Zero.NONZERO


def test_identity_beyond_the_rewriting_is_undecided_not_claimed():
    """cos^2 - (1 + cos 2x)/2 is zero, but not proved by the cheap rewriting: undecided, never PROVED."""
    status = zero_status(sympy.cos(x) ** 2 - (1 + sympy.cos(2 * x)) / 2)
    assert status in (Zero.PROVED, Zero.UNDECIDED)
    assert status is not Zero.NONZERO


def test_declared_functions_get_concrete_bodies():
    """Numeric probes replace f by concrete functions, so f(x) - f(x)**1 is zero and f'(x) is not."""
    assert numerically_zero(f(x) - f(x) ** 1)
    assert not numerically_zero(sympy.Derivative(f(x), x))


def test_probes_evaluate_unevaluated_objects():
    """An unevaluated derivative or integral is evaluated before a probe (its value, not the object, is compared),
    and a plain expression is probed as it is."""
    y = sympy.Symbol("y", real=True)
    assert numerically_zero(sympy.Derivative(x**2, x, evaluate=False) - 2 * x)
    assert not numerically_zero(sympy.Derivative(x**2, x, evaluate=False) - 3 * x)
    assert numerically_zero(sympy.Integral(2 * y, (y, 0, x)) - x**2)
    assert numerically_zero(sympy.sin(x - y) - sympy.sin(x) * sympy.cos(y) + sympy.cos(x) * sympy.sin(y))
    assert not numerically_zero(sympy.sin(x - y) - sympy.sin(x) * sympy.cos(y))


def test_signs_of_products_are_split():
    """The wedge's friction in two routes: sign((Ẋ − ẋ) cos α) sign(cos α) against sign(Ẋ − ẋ) is proved zero; a
    sign that really differs (sign(Ẋ − ẋ) against sign(Ẋ + ẋ)) is not."""
    X, v, a, m = sympy.symbols("X_dot x_dot alpha m", real=True)
    one = m * sympy.sign(X * sympy.cos(a) - v * sympy.cos(a)) * sympy.sign(sympy.cos(a)) / (1 + m ** 2)
    other = m * sympy.sign(X - v) / (1 + m ** 2)
    assert zero_status(one - other) is Zero.PROVED
    assert zero_status(-2 * sympy.sign(-3 * (X - v)) / 3 - 2 * sympy.sign(X - v) / 3) is Zero.PROVED
    assert zero_status(sympy.sign(X - v) - sympy.sign(X + v)) is Zero.NONZERO
