"""SymPy's factor_terms, cancel, factor, expand and count_ops by lagsolve's cheaper routes
(``lagsolve.mechanics.symbolic.algebra``): each gives SymPy's own result, tree for tree, on samples, on random
polynomials and quotients, and on every expression the derivation of a shipped problem passes through it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import sympy

m, g, mu = sympy.symbols("m g mu", positive=True)
x, v, th, t = sympy.symbols("x v theta t", real=True)
_a, _b, _c, _l = sympy.symbols("a b c l", positive=True)
_p, _q = sympy.symbols("p q", real=True)

FACTOR_TERMS_SAMPLES = [
    3 * _l**2 * _c * _p**2 / 2 + 2 * _l**2 * _c * _p * _q * sympy.cos(_a - _b) - 3 * _b * _l * _c * sympy.cos(_a),
    -2 * _b * _l * _c * sympy.sin(_a) - _b * _l * _c * sympy.sin(_a) ** 2 * sympy.cos(_b),
    6 * _p * sympy.sin(_a) - 4 * _q * sympy.cos(_a - _b) + 2 * _p * _q,
    _p / 3 + _q / 6 - sympy.Rational(5, 9) * _p * _q,
    (_p**2 * _l + _p * _q * _l) / (_l**2 * sympy.cos(_a) ** 2 - _l**2 * sympy.sin(_a) * _b),
    -_p - _q,
    _p * _q + _c,
]


@pytest.mark.parametrize("expr", FACTOR_TERMS_SAMPLES)
def test_factor_terms_is_sympys_on_sums_of_monomials(expr):
    """The direct route for sums of monomials gives exactly SymPy's factor_terms (same tree, not just equal)."""
    from lagsolve.mechanics.symbolic.algebra import _plain_factor_terms

    ours = _plain_factor_terms(expr)
    assert ours is not None
    assert sympy.srepr(ours) == sympy.srepr(sympy.factor_terms(expr))


def test_factor_terms_leaves_other_shapes_to_sympy():
    from lagsolve.mechanics.symbolic.algebra import _plain_factor_terms, factor_terms

    odd = sympy.exp(-(_p + 2)) * _q + sympy.sqrt(_p) * _q + sympy.sin(_p / 2 + _q / 2)
    assert _plain_factor_terms(odd) is None
    assert factor_terms(odd) == sympy.factor_terms(odd)


FACTOR_SAMPLES = [
    "(x**2 - 1)/(x + 1)", "(2*x + 2)/(4*g)", "sin(th)**2 - 1", "sqrt(x**2 - g**2)", "-x - g", "2*x",
    "sqrt(2)*x + 2*x", "(x + 1)**2/(-x - 1)**3", "exp(x)*x + x", "I*x + x", "(x**2 - g**2)**(3/2)/(x - g)",
    "m*g*sin(th)*cos(th) + m*x*sin(th)**2*cos(th)", "-(g*sin(th) - x*cos(th))/(m*(cos(th)**2 - 2))",
    "(-2*g*sin(th)*cos(x - th) + 2*g*sin(x) - 2*m*x**2*sin(x - th))/(m*cos(x - th)**2 - 2*m)",
    "x**3*g - x*g**3", "6*x**2*g + 4*x*g**2", "(x + g)**2*(x - g)", "pi*x + pi", "0", "m", "3/4",
    "(2*x + 2*g)/(4*m*x + 4*m)", "x/2 + g/2", "(x*g + x)/(x**2*m)", "-2*x - 2*g", "-(6*x*sin(th) - 4*g)/(2*m - 2*x)",
    "(x**2*sin(th)**2 - g**2)/(x*sin(th) + g)**2", "3*x*g/(2*(x + 1)) + x/(x + 1)", "(x + 1/x)*(g - 2)",
]


@pytest.mark.parametrize("text", FACTOR_SAMPLES)
def test_factor_is_sympys_factor(text):
    """algebra.factor, which remembers each polynomial's factorization, gives SymPy's factor tree for tree."""
    from lagsolve.mechanics.symbolic.algebra import factor

    expr = sympy.sympify(text, locals={"x": x, "g": g, "m": m, "th": th})  # test data, not a problem file
    assert sympy.srepr(factor(expr)) == sympy.srepr(sympy.factor(expr))


def _derive_comparing(name: str, attribute: str, same: Any, monkeypatch: Any) -> list[Any]:
    """Derive ``problems/<name>.yaml`` with ``simplify.<attribute>`` (the cheaper route the display simplification
    calls) checked against SymPy's on every expression it is given: ``same(expr, result)`` must hold. The
    expressions checked are returned."""
    import functools
    from pathlib import Path

    from lagsolve.mechanics.derivation import derive
    from lagsolve.mechanics.symbolic import simplify
    from lagsolve.problem.load import load_problem

    original = getattr(simplify, attribute)
    inner = getattr(original, "__wrapped__", original)
    checked: list[Any] = []

    def compare(expr: Any) -> Any:
        result = inner(expr)
        assert same(expr, result), expr
        checked.append(expr)
        return result

    caches = (simplify.tidy, simplify.tidy_sum, simplify._weight, simplify.compound_angles)
    monkeypatch.setattr(simplify, attribute, functools.lru_cache(maxsize=None)(compare))
    for cache in caches:
        cache.cache_clear()
    try:
        derive(load_problem(Path(__file__).resolve().parents[3] / "problems" / f"{name}.yaml"))
    finally:
        for cache in caches:
            cache.cache_clear()
    return checked


@pytest.mark.slow
@pytest.mark.parametrize("name", ["double_pendulum", "wedge", "heavy_top", "rotating_tube"])
def test_factor_is_sympys_factor_on_every_expression_a_derivation_factors(name, monkeypatch):
    """Every expression the derivation of a shipped problem factors (fractions of trigonometric polynomials,
    momenta, frequencies) is factored as SymPy's own factor does, tree for tree."""
    checked = _derive_comparing(name, "factor", lambda e, r: sympy.srepr(r) == sympy.srepr(sympy.factor(e)),
                                monkeypatch)
    assert len(checked) >= 5


@pytest.mark.slow
@pytest.mark.parametrize("name", ["double_pendulum", "wedge", "cone", "incline_pulley"])
def test_cancel_and_expand_are_sympys_on_every_expression_a_derivation_passes(name, monkeypatch):
    """Every quotient a derivation cancels and every expression it expands comes out as SymPy's cancel and
    expand write it, tree for tree."""
    cancelled = _derive_comparing(name, "cancel", lambda e, r: sympy.srepr(r) == sympy.srepr(sympy.cancel(e)),
                                  monkeypatch)
    expanded = _derive_comparing(name, "expand", lambda e, r: sympy.srepr(r) == sympy.srepr(sympy.expand(e)),
                                 monkeypatch)
    assert cancelled and len(expanded) >= 5


COUNT_SAMPLES = [
    "x", "-x", "1/x", "-1/x", "x - g", "-x - g", "-x + g", "2*x/3", "-2*x/(3*g)", "exp(x)", "E", "E**2*x",
    "exp(-x)/g", "sqrt(x + 1)", "1/(x + g)", "Max(x, g, m)", "Derivative(f(x), x)", "Integral(x, x)",
    "sin(th)**2 - cos(g)/x", "-1/3", "-4", "2.5*x", "3*I*x", "x**(-2)", "(x - 1)/(2*(g - 3))",
    "-(x - g)/(m*(x + 1))", "Abs(x - g)/sign(m)", "-(-2*g*sin(th) + g*cos(x - th))/(m*(cos(x - th)**2 - 2))",
]


@pytest.mark.parametrize("text", COUNT_SAMPLES)
def test_count_ops_is_sympys(text):
    """algebra.count_ops counts as sympy.count_ops does (the measure that picks every display form)."""
    from lagsolve.mechanics.symbolic.algebra import count_ops

    expr = sympy.sympify(text, locals={"x": x, "g": g, "m": m, "th": th, "f": sympy.Function("f")})  # test data
    assert count_ops(expr) == sympy.count_ops(expr)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["double_pendulum", "wedge", "rolling_disc", "ladder_rough_floor"])
def test_count_ops_is_sympys_on_every_expression_a_derivation_measures(name, monkeypatch):
    """Every expression a derivation of a shipped problem measures has SymPy's count of operations."""
    checked = _derive_comparing(name, "ops", lambda e, r: r == sympy.count_ops(e), monkeypatch)
    assert len(checked) >= 20


EXPAND_SAMPLES = [
    "m*((l*x*sin(th) + l*g*cos(th))**2 + (l*x*cos(th))**2)/2", "(x + g)**3*(m - 1)/4", "-(sin(x - th) - 2*cos(x))**2",
    "g*m*(-l*cos(th) - l*cos(x)) - g*l*m*cos(th)", "(2*x - 3*g)*(x + g)*sin(th + x)**2", "x", "3", "m*(x + 1)",
]


@pytest.mark.parametrize("text", EXPAND_SAMPLES)
def test_expand_by_symengine_is_sympys_expand(text, monkeypatch):
    """algebra.expand, by SymEngine for polynomials in symbols, sines and cosines, is SymPy's expand tree for tree,
    with the expression's own symbols (their assumptions kept); other expressions go to SymPy. (SymEngine is made
    to take the small samples too, which it leaves to SymPy by default.)"""
    from lagsolve.mechanics.symbolic import algebra
    from lagsolve.mechanics.symbolic.algebra import _engine_polynomial, expand

    monkeypatch.setattr(algebra, "ENGINE_FROM", 1)
    expand.cache_clear()
    names = {"x": x, "g": g, "m": m, "th": th, "l": sympy.Symbol("l", positive=True)}
    expr = sympy.sympify(text, locals=names)  # test data, not a problem file
    assert _engine_polynomial(expr)
    assert sympy.srepr(expand(expr)) == sympy.srepr(sympy.expand(expr))
    assert expand(expr).free_symbols <= expr.free_symbols


def test_small_expressions_do_not_load_symengine():
    """Deriving the bead (every expansion under ENGINE_FROM nodes, and its Lagrangian) in a fresh interpreter does not
    load SymEngine (with the NumPy it imports, about 0.09 s of its start-up), and a large polynomial is still
    expanded by SymEngine."""
    import subprocess
    import sys

    code = ("import sys\n"
            "from lagsolve.mechanics.derivation import derive\n"
            "from lagsolve.problem.load import load_problem\n"
            "derive(load_problem('problems/bead.yaml'))\n"
            "print('symengine' in sys.modules)\n"
            "import sympy\n"
            "from lagsolve.mechanics.symbolic.algebra import expand, small\n"
            "x, y = sympy.symbols('x y')\n"
            "big = sum(((x + k*y)**2*(k - x) for k in range(1, 8)), x)\n"
            "assert not small(big) and expand(big) == sympy.expand(big)\n"
            "print('symengine' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parents[3]).stdout.split("\n")
    assert out[:2] == ["False", "True"]


def test_expand_leaves_other_expressions_to_sympy():
    from lagsolve.mechanics.symbolic.algebra import _engine_polynomial, expand

    d = sympy.Dummy("d")
    for expr in ((x + g) ** -2, sympy.sqrt(x * g + 1) * (x + 1), sympy.exp(x) * (x + g), 2.5 * (x + g) ** 2,
                 sympy.sin(2 * (x + g)) * (x + 1), (d + x) ** 2, sympy.pi * (x + 1)):
        assert not _engine_polynomial(expr)
        assert expand(expr) == sympy.expand(expr)


def test_linear_factor_list_is_sympys_factor_list():
    """Where a polynomial is linear in a generator with coprime coefficients, the shortcut's factorization (content,
    monomials, the polynomial) is SymPy's factor_list exactly; reducible ones (products, common factors) are left to
    SymPy. Random polynomials in two to four generators, a third of them products."""
    import random

    from lagsolve.mechanics.symbolic.algebra import _linear_factor_list

    gens_all = sympy.symbols("x y z w")
    rng = random.Random(7)
    used = declined = 0
    for _ in range(600):
        gens = gens_all[:rng.randint(2, 4)]

        def polynomial(gens=gens):
            return sum(rng.randint(-3, 3) * sympy.Mul(*[v ** rng.randint(0, 2) for v in gens])
                       for _ in range(rng.randint(1, 4)))

        expr = sympy.expand(polynomial() * (polynomial() if rng.random() < 0.35 else 1) * gens[0] ** rng.randint(0, 2))
        if expr.is_number:
            continue
        poly = sympy.Poly(expr, *gens)
        found = _linear_factor_list(poly)
        if found is None:
            declined += 1
            continue
        used += 1
        assert found == poly.factor_list(), expr
        assert len([f for f, _ in found[1] if f.total_degree() > 1 or len(f.terms()) > 1]) == 1
    assert used > 100 and declined > 100
    u = sympy.Poly(gens_all[0] ** 2 + 1, gens_all[0])
    assert _linear_factor_list(u) is None  # one generator: SymPy's own univariate route


def test_cancel_results_are_known_to_be_cancelled():
    """What algebra.cancel returns is its own cancel (SymPy's cancel is idempotent on it), and is then not searched
    again; a fraction that is not cancelled still is."""
    from lagsolve.mechanics.symbolic import algebra

    expr = (m * x**2 - m) / (x + 1) + g * sympy.sin(th) ** 2 / (g * sympy.cos(th))
    once = algebra.cancel(expr)
    assert sympy.srepr(sympy.cancel(once)) == sympy.srepr(once)
    assert once in algebra._CANCELLED
    assert algebra.cancel(once) is once
    assert algebra.cancel((x**2 - 1) / (x - 1)) == x + 1


CANCEL_SAMPLES = [
    "(x**2 - 1)/(x + 1)", "(x**2 - 1)/(1 - x)", "(2*x + 2*g)/(4*m*x + 4*m)", "x/2 + g/3", "-(x - g)/(g - x)**2",
    "(m*sin(th)**2 - m)/(g*cos(th)**2)", "(exp(2*x) - 1)/(exp(x) + 1)", "1/(x + 1) + 1/(x - 1)", "(-x - g)/(-m)",
    "(2*g*sin(th) - g*sin(x)*cos(th - x))/(m*cos(th - x)**2 - 2*m)", "x", "m*g", "3*x/(6*g)", "Derivative(f(x), x)/x",
]


@pytest.mark.parametrize("text", CANCEL_SAMPLES)
def test_ring_cancel_is_sympys_cancel(text):
    """algebra's cancel of a quotient of integer polynomials (in symbols and functions) is sympy.cancel, tree for
    tree; expressions with roots, floats or Piecewise go to sympy.cancel itself."""
    from lagsolve.mechanics.symbolic.algebra import _ring_cancel

    expr = sympy.sympify(text, locals={"x": x, "g": g, "m": m, "th": th, "f": sympy.Function("f")})  # test data
    assert sympy.srepr(_ring_cancel(expr)) == sympy.srepr(sympy.cancel(expr))
    for other in (expr + sympy.sqrt(2) * x, expr * 1.5, expr + sympy.Piecewise((x, x > 0), (0, True))):
        assert sympy.srepr(_ring_cancel(other)) == sympy.srepr(sympy.cancel(other))


def test_ring_cancel_of_random_quotients_is_sympys():
    import random

    from lagsolve.mechanics.symbolic.algebra import _ring_cancel

    rng = random.Random(11)
    atoms = [x, g, m, sympy.sin(th), sympy.cos(th)]

    def polynomial():
        return sum(rng.randint(-4, 4) * sympy.Mul(*[a ** rng.randint(0, 2) for a in rng.sample(atoms, 2)])
                   for _ in range(rng.randint(1, 3)))

    for _ in range(150):
        common = polynomial() if rng.random() < 0.5 else 1
        numerator, denominator = polynomial() * common, polynomial() * common
        if denominator == 0:
            continue
        expr = numerator / denominator
        assert sympy.srepr(_ring_cancel(expr)) == sympy.srepr(sympy.cancel(expr)), expr
