"""A bulk system's route through SymEngine gives SymPy's own trees: the one-walk conversion (products and sums put in
SymPy's canonical order without its flattening, sines and cosines of a difference without its evaluation) equals
SymEngine's ``_sympy_()`` with the symbols put back, and the light display form written by SymEngine equals
:func:`tidy_sum_light`'s, on the pieces of an 8-link chain and on assorted expressions."""

from __future__ import annotations

import itertools
import random

import sympy
from symengine.lib.symengine_wrapper import sympy2symengine

from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.mechanics.symbolic.bulk import light
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM, _sine_or_cosine, engine_converter, engine_sum
from lagsolve.mechanics.symbolic.simplify import tidy_sum_light
from lagsolve.problem.load import load_text

m, l, g = sympy.symbols("m l g", positive=True)  # noqa: E741 - the rod length
ANGLES = sympy.symbols("th1 th2 th3 th10 x_1", real=True)
RATES = sympy.symbols("th1_dot th2_dot th3_dot", real=True)
a, b, c, d, e = ANGLES
u, v, w = RATES


def _chain(n: int) -> str:
    names = [f"th{i}" for i in range(1, n + 1)]
    lines = ["name: chain", "parameters: {m: mass, l: length, g: gravity}", f"coordinates: [{', '.join(names)}]",
             "particles:"]
    for i in range(1, n + 1):
        x = " + ".join(f"l*sin({q})" for q in names[:i])
        y = " - ".join(f"l*cos({q})" for q in names[:i])
        lines.append(f"  p{i}: {{mass: m, position: [{x}, -{y}]}}")
    return "\n".join([*lines, "gravity: [0, -g]"]) + "\n"


def _reference(value: object, own: dict[str, object]) -> object:
    back = value._sympy_()  # type: ignore[attr-defined]
    return back.xreplace({s: own[s.name] for s in back.free_symbols})


def _assorted() -> list[sympy.Expr]:
    rng = random.Random(5)
    pieces = [sympy.sin(a - b), sympy.cos(b - a), sympy.sin(c + a - e), sympy.cos(a), u, v**2, m * l**2, g,
              sympy.Rational(3, 2), sympy.sin(d - a) ** 2, 1 / sympy.cos(b), sympy.sqrt(m), sympy.exp(a) * w]
    exprs = []
    for _ in range(60):
        terms = [sympy.Mul(*rng.sample(pieces, rng.randint(1, 4))) * rng.choice([1, -1, 2, sympy.Rational(-1, 3)])
                 for _ in range(rng.randint(1, 6))]
        exprs.append(sympy.Add(*terms) * rng.choice([1, u, (a + b)]))
    return exprs


def test_one_walk_conversion_gives_sympys_own_trees() -> None:
    own = {s.name: s for s in (*ANGLES, *RATES, m, l, g)}
    convert = engine_converter(own)
    for expr in _assorted():
        for form in (sympy2symengine(expr), sympy2symengine(expr).expand()):
            back = convert(form)
            reference = _reference(form, own)
            assert back == reference and sympy.srepr(back) == sympy.srepr(reference), expr


def test_sine_and_cosine_of_a_difference_as_sympy_evaluates_them() -> None:
    for kind, r in itertools.product((sympy.sin, sympy.cos), (2, 3)):
        for names in itertools.permutations(ANGLES, r):
            for signs in itertools.product((1, -1), repeat=r):
                arg = sympy.Add(*[s * x for s, x in zip(signs, names, strict=True)])
                built = _sine_or_cosine(kind, arg)
                assert built is not None
                assert sympy.srepr(built) == sympy.srepr(kind(arg))
    assert _sine_or_cosine(sympy.sin, a + sympy.pi) is None  # π: SymPy's rules apply
    assert _sine_or_cosine(sympy.tan, a - b) is None
    assert _sine_or_cosine(sympy.sin, 2 * a - b) is None


def test_light_form_of_a_chain_is_tidy_sum_lights() -> None:
    n = BULK_SYSTEM + 2
    form = matrix_form(load_text(_chain(n), "chain.yaml"), display=False)
    terms = form.lagrange
    pieces = [form.model.kinetic, form.model.potential, *terms.momenta, *terms.momenta_rates, *terms.gradients,
              *terms.equations, *terms.mass_matrix, *terms.forcing]
    for piece in pieces:
        assert sympy.srepr(light(piece)) == sympy.srepr(tidy_sum_light(piece))


def test_light_form_where_symengine_cannot_go() -> None:
    f = sympy.Function("f")
    assert light(f(a) * u**2) is None
    assert light(sympy.Abs(a) + u) is None
    assert light(sympy.Integer(3)) == 3


def test_engine_sum_equals_sympys_sum() -> None:
    parts = [(1, m * l**2 * u * v * sympy.cos(a - b)), (-1, g * l * m * sympy.cos(a)), (2, u**2 * (a + b))]
    total = engine_sum(parts)
    assert sympy.expand(total - sum(k * p for k, p in parts)) == 0
    assert engine_sum([(1, sympy.Integer(0))]) == 0
