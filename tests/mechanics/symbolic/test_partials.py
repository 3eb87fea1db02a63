"""Partial derivatives taken by SymEngine and converted back equal SymPy's own ``diff`` (an independent route),
keep the expression's symbols (with their assumptions), and fall back to SymPy where SymEngine is not used."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.symbolic.partials import _engine, partial

m, l, g, k = sympy.symbols("m l g k", positive=True)  # noqa: E741 - the rod length
a, b, t = sympy.symbols("th1 th2 t", real=True)
ad, bd = sympy.symbols("th1_dot th2_dot", real=True)

DOUBLE_PENDULUM = (m * l**2 * (ad**2 + ad * bd * sympy.cos(a - b) + bd**2 / 2)
                   + g * l * m * (2 * sympy.cos(a) + sympy.cos(b)))
ASSORTED = [
    DOUBLE_PENDULUM,
    m * (ad**2 + (a * bd) ** 2) / 2 - k * (sympy.sqrt(a**2 + b**2) - l) ** 2 / 2,
    m * ad**2 * sympy.exp(-k * t) / 2 - m * g * l * sympy.log(1 + a**2) + sympy.atan(b) * bd,
    sympy.tan(a) * sympy.sinh(b) * ad + sympy.pi * sympy.cosh(ad * t) - sympy.E * sympy.asin(a / 2) * bd**3,
    m * l**2 * ad**2 / (2 + sympy.sin(a - b) ** 2) + sympy.Rational(3, 7) * sympy.sec(b) * sympy.cot(a) * bd,
]
VARIABLES = [a, b, ad, bd, t, m]


def test_first_and_second_partials_equal_sympy_diff() -> None:
    for expr in ASSORTED:
        assert _engine(expr) is not None
        for x in VARIABLES:
            assert sympy.simplify(partial(expr, x) - sympy.diff(expr, x)) == 0
            for y in (a, ad, bd):
                assert sympy.simplify(partial(expr, x, y) - sympy.diff(expr, x, y)) == 0
        assert sympy.simplify(partial(expr, ad, ad, ad) - sympy.diff(expr, ad, 3)) == 0


def test_results_keep_the_expression_own_symbols() -> None:
    derivative = partial(DOUBLE_PENDULUM, a)
    assert derivative.free_symbols <= DOUBLE_PENDULUM.free_symbols
    assert derivative.xreplace({ad: 0, bd: 0}) == -2 * g * l * m * sympy.sin(a)
    assert derivative == sympy.diff(DOUBLE_PENDULUM, a)  # the pendulum's comes back in SymPy's own form
    assert partial(DOUBLE_PENDULUM, ad, ad, ad) == 0
    assert partial(DOUBLE_PENDULUM, t) == 0  # t does not occur


def test_sympy_is_used_where_symengine_is_not() -> None:
    f = sympy.Function("f")
    x = sympy.Dummy("x", real=True)
    not_by_engine = [
        m * ad**2 / 2 - f(a),  # a declared function
        sympy.Abs(a) * ad,  # d|a|/da is sign(a) for real a, which SymEngine leaves as a Derivative
        sympy.Float("9.81") * m * sympy.cos(a),  # a float keeps its precision
        sympy.Piecewise((a, a > 0), (0, True)) * ad,
    ]
    for expr in not_by_engine:
        assert _engine(expr) is None
        for y in (a, ad):
            assert partial(expr, y) == sympy.diff(expr, y)
    # a Dummy converts to a new Dummy: SymPy's diff is used, the Dummy is kept
    dummy = m * x**2 * sympy.sin(a)
    assert partial(dummy, a) == sympy.diff(dummy, a)
    assert partial(dummy, x) == sympy.diff(dummy, x)
    assert partial(0, a) == 0
