"""The expression gateway: the grammar it accepts and the hostile text it refuses, quickly."""

from __future__ import annotations

import builtins
import time
from typing import Any

import pytest
import sympy

from lagsolve.errors import ExpressionError, LagsolveError
from lagsolve.problem import expr
from lagsolve.problem.expr import Namespace, name_problem, parse

x, y, t = sympy.symbols("x y t", real=True)
x_dot, y_dot = sympy.symbols("x_dot y_dot", real=True)
m, g = sympy.symbols("m g", positive=True)
f = sympy.Function("f", real=True)
h = sympy.Function("h", real=True)

NAMES = Namespace(
    symbols={"x": x, "y": y, "t": t, "x_dot": x_dot, "y_dot": y_dot, "m": m, "g": g},
    functions={"f": f, "h": h},
    forbidden={"x_ddot": "accelerations may not appear in problem expressions"},
)

#: A rejection must come back at once: this is a guard against hangs, not a benchmark.
FAST = 2.0  # CPU seconds: the bound for any refusal; a hang would take far longer


def read(text: Any) -> Any:
    return parse(text, NAMES)


def rejection(text: Any) -> str:
    """Parse ``text``, expecting a refusal within FAST seconds; return the message."""
    start = time.process_time()
    with pytest.raises(ExpressionError) as caught:
        read(text)
    cpu = time.process_time() - start
    assert cpu < FAST, f"rejection took {cpu:.2f} s"
    return str(caught.value)


# ------------------------------------------------------------------------------------------
# the grammar


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1 + 2*x", 1 + 2 * x),
        ("(1 + 2)*x", 3 * x),
        ("x - y - 1", (x - y) - 1),
        ("x/y/2", x / (2 * y)),
        ("2*x**2", 2 * x**2),
        ("m*g*y + x/2", m * g * y + x / 2),
        ("x*(y + 1)", x * (y + 1)),
        ("+x", x),
    ],
    ids=["mul-before-add", "parentheses", "left-assoc-minus", "left-assoc-divide",
         "power-before-mul", "mixed", "grouping", "unary-plus"],
)
def test_operator_precedence(text: str, expected: Any) -> None:
    """Operators bind as in ordinary mathematics and Python, left to right within a level."""
    assert read(text) == expected


def test_caret_is_power() -> None:
    """`^` means power, not bitwise xor."""
    assert read("x^2") == x**2
    assert read("2^3") == 8


def test_power_is_right_associative() -> None:
    """`a**b**c` is `a**(b**c)`, with either spelling of the operator."""
    assert read("2**3**2") == 512
    assert read("2^3^2") == 512
    assert read("x**2**3") == x**8


def test_unary_minus_binds_looser_than_power() -> None:
    """`-x**2` is `-(x**2)` and `-2**2` is -4, as in Python."""
    assert read("-x**2") == -(x**2)
    assert read("-2**2") == -4
    assert read("2**-1") == sympy.Rational(1, 2)
    assert read("--x") == x


def test_decimals_are_exact() -> None:
    """Decimal numbers become exact rationals, so `0.1` is 1/10 and `0.1 + 0.2` is 3/10."""
    tenth = read("0.1")
    assert tenth == sympy.Rational(1, 10) and isinstance(tenth, sympy.Rational)
    assert read("0.1 + 0.2") == sympy.Rational(3, 10)
    assert read(".5") == sympy.Rational(1, 2)


def test_scientific_notation() -> None:
    """Numbers like `1e-8` and `2.5E3` are read exactly."""
    assert read("1e-8") == sympy.Rational(1, 10**8)
    assert read("2.5E3") == 2500
    assert read("1e+2*x") == 100 * x


def test_yaml_numbers_are_accepted() -> None:
    """A YAML number (int or float) is an expression too, read exactly from its shortest text."""
    assert read(3) == 3
    assert read(1e-8) == sympy.Rational(1, 10**8)
    assert read(0.1) == sympy.Rational(1, 10)
    assert read(0) == 0


def test_derivative_of_declared_function() -> None:
    """`Derivative(f(x), x)` and `Derivative(f(x), (x, 2))` build SymPy Derivative objects."""
    first = read("Derivative(f(x), x)")
    second = read("Derivative(f(x), (x, 2))")
    assert isinstance(first, sympy.Derivative) and first == sympy.Derivative(f(x), x)
    assert isinstance(second, sympy.Derivative) and second == sympy.Derivative(f(x), (x, 2))
    assert read("Derivative(f(x), x, x)") == second


def test_mixed_partial_derivative() -> None:
    """A function of several variables is differentiated with respect to each of them."""
    assert read("Derivative(h(x, t), x, t)") == sympy.diff(h(x, t), x, t)


def test_declared_functions_are_applied() -> None:
    """A declared function is called like a built-in one, with any expression as argument."""
    assert read("f(x)") == f(x)
    assert read("f(x**2 + 1)*h(x, y)") == f(x**2 + 1) * h(x, y)


def test_builtin_functions() -> None:
    """The fixed list of functions maps to SymPy's functions."""
    assert read("sin(x)**2 + cos(x)") == sympy.sin(x) ** 2 + sympy.cos(x)
    assert read("atan2(y, x)") == sympy.atan2(y, x)
    assert read("sqrt(m)*Abs(x)*sign(y)") == sympy.sqrt(m) * sympy.Abs(x) * sympy.sign(y)
    assert read("exp(x) + log(m)") == sympy.exp(x) + sympy.log(m)


def test_pi_and_e_are_constants() -> None:
    """`pi` and `E` are SymPy's exact constants."""
    assert read("pi") is sympy.pi
    assert read("E") is sympy.E
    assert read("E**x") == sympy.exp(x)
    assert read("2*pi*m") == 2 * sympy.pi * m


def test_the_round_trip_of_a_textbook_answer() -> None:
    """The bead's acceleration, as SymPy prints it, reads back to the same expression."""
    fp, fpp = sympy.Derivative(f(x), x), sympy.Derivative(f(x), (x, 2))
    answer = -fp * (fpp * x_dot**2 + g) / (1 + fp**2)
    assert sympy.simplify(read(str(answer)) - answer) == 0


def test_parse_never_uses_eval_or_sympify(monkeypatch: pytest.MonkeyPatch) -> None:
    """Parsing works with eval, sympify and parse_expr disabled: text never reaches them."""
    import sympy.parsing.sympy_parser as sympy_parser

    read("sin(x) + 1")  # import SymPy's lazily loaded modules before eval is disabled

    def forbidden(*args: object, **kwargs: object) -> None:
        raise AssertionError("eval-like function called")

    monkeypatch.setattr(builtins, "eval", forbidden)
    monkeypatch.setattr(sympy, "sympify", forbidden)
    monkeypatch.setattr(sympy, "parse_expr", forbidden)
    monkeypatch.setattr(sympy_parser, "parse_expr", forbidden)
    result = read("sin(x)**2/3 + 0.5*Derivative(f(x), (x, 2)) - pi*E^x + atan2(x, 1)")
    assert result.has(sympy.Derivative(f(x), (x, 2)))


def test_expression_error_is_a_value_error() -> None:
    """ExpressionError belongs to lagsolve's error family and is also a ValueError."""
    with pytest.raises(ExpressionError) as caught:
        read("nope")
    assert isinstance(caught.value, LagsolveError) and isinstance(caught.value, ValueError)
    assert caught.value.message.startswith("unknown name 'nope'")
    assert caught.value.hint.endswith("declare it under parameters, coordinates or functions")


# ------------------------------------------------------------------------------------------
# rejections: every case must say what is wrong (and where), and come back at once

REJECTIONS = [
    # unknown names and functions
    ("unknown-name", "m*gg", ["unknown name 'gg' at column 3", "did you mean 'g'?"]),
    ("unknown-name-listing", "q", ["unknown name 'q' at column 1 (known: g, m, t, x, x_dot",
                                   "declare it under parameters, coordinates or functions"]),
    ("unknown-function", "k(x)", ["unknown function 'k' at column 1",
                                  "declare it under functions, or use one of: Abs"]),
    ("misspelt-function", "sinn(x)", ["unknown function 'sinn'", "did you mean 'sin'?"]),
    ("forbidden-acceleration", "m*x_ddot",
     ["'x_ddot' at column 3: accelerations may not appear in problem expressions"]),
    # code, not mathematics
    ("attribute-access", "a.b", ["'.' at column 2 is not allowed (attribute access)"]),
    ("dunder-attribute", "x.__class__", ["'.' at column 2 is not allowed (attribute access)"]),
    ("dunder-name", "__import__", ["name '__import__' at column 1 is not allowed",
                                   "names may not start with '_' or contain '__'"]),
    ("dunder-call", "__import__(x)", ["name '__import__' at column 1 is not allowed"]),
    ("import-os", "__import__('os')", ["unexpected character \"'\" at column 12"]),
    ("underscore-name", "_x", ["name '_x' at column 1 is not allowed"]),
    ("lambda", "lambda: 0", ["unexpected character ':' at column 7"]),
    ("lambda-call", "(lambda x: x)(1)", ["unexpected character ':' at column 10"]),
    ("keyword-name", "import", ["unknown name 'import' at column 1"]),
    ("string-literal", "'abc'", ["unexpected character \"'\" at column 1"]),
    ("assignment", "x = 1", ["unexpected character '=' at column 3"]),
    ("semicolon", "x; y", ["unexpected character ';' at column 2"]),
    ("cyrillic-a", "\u0430*x", ["non-ASCII character '\u0430' (U+0430 CYRILLIC SMALL LETTER A) "
                                "at column 1", "a look-alike letter is a different name"]),
    ("cyrillic-in-name", "m\u0430", ["U+0430 CYRILLIC SMALL LETTER A) at column 2"]),
    ("arabic-digit", "\u0663", ["non-ASCII character", "U+0663 ARABIC-INDIC DIGIT THREE"]),
    # huge numbers and constants: refused before SymPy evaluates them
    ("power-tower", "9**9**9**9", ["exponent 3.8742e+08 of '**' at column 5 is too large",
                                   "powers are limited to exponents of size 1000"]),
    ("big-exponent", "x**1001", ["exponent 1001 of '**' at column 2 is too large"]),
    ("constant-overflow", "2**1000", ["a constant in '**' at column 2 is too large"]),
    ("huge-literal", "1e999999999", ["number '1e999999999' at column 1 is out of range",
                                     "decimal exponents are limited to ±300"]),
    ("zero-padded-exponent", "1e-000000000000999999999", ["at column 1 is out of range"]),
    ("tiny-literal", "1e-400", ["number '1e-400' at column 1 is out of range"]),
    ("long-literal", "1" * 41, ["number at column 1 has more than 40 digits"]),
    ("sin-exp-tower", "sin(exp(exp(exp(3))))",
     ["a constant in exp(...) at column 5 is too large to evaluate"]),
    ("cos-exp-tower-plus-one", "cos(exp(exp(exp(3)))) + 1",
     ["a constant in exp(...) at column 5 is too large to evaluate"]),
    ("tower-hidden-by-0x", "cos(exp(exp(exp(3 + 0*x)))) + 1",
     ["a constant in exp(...) at column 5 is too large to evaluate"]),
    ("tower-hidden-by-x-minus-x", "cos(exp(exp(exp(3 + x - x)))) + 1",
     ["a constant in exp(...) at column 5 is too large to evaluate"]),
    ("power-hidden-by-0x", "9**9**(9 + 0*x)", ["exponent 3.8742e+08 of '**' at column 2"]),
    ("exact-rational-growth", "(999999/1000000)**1000",
     ["would make an exact number of about 6020 digits"]),
    ("exact-coefficient-growth", "((2*x)**1000)**1000",
     ["'**' at column 14 would make an exact number of about 301331 digits"]),
    # bad values
    ("division-by-zero", "1/0", ["division by zero ('/' at column 2)"]),
    ("division-by-zero-constant", "x/(2 - 2)", ["division by zero ('/' at column 2)"]),
    ("zero-to-negative-power", "0**-1", ["division by zero in a constant ('**' at column 2)"]),
    ("complex-constant", "sqrt(-1)", ["a constant in sqrt(...) at column 1 is a complex number",
                                      "expressions must be real"]),
    ("complex-inside", "x*log(-1)", ["a constant in log(...) at column 3 is a complex number"]),
    ("complex-root", "(-8)**(1/3)", ["is a complex number"]),
    ("log-of-zero", "log(0)", ["a constant in log(...) at column 1 is undefined"]),
    ("tan-singular", "x*tan(pi/2)", ["the expression has an infinite or undefined part"]),
    ("atan2-origin", "atan2(0, 0)", ["the expression has an infinite or undefined part"]),
    # calls
    ("wrong-arity", "sin(x, y)", ["sin at column 1 takes 1 argument, got 2"]),
    ("wrong-arity-atan2", "atan2(x)", ["atan2 at column 1 takes 2 arguments, got 1"]),
    ("function-without-call", "sin*x", ["function 'sin' at column 1 is used without arguments",
                                        "write sin(...)"]),
    ("declared-function-without-call", "2*f", ["function 'f' at column 3 is used without"]),
    ("call-of-a-symbol", "x(2)", ["'x' at column 1 is not a function",
                                  "write x*(...) for a product"]),
    ("call-of-a-constant", "pi(2)", ["'pi' at column 1 is not a function"]),
    ("too-many-arguments", "f(x, x, x, x, x)", ["f at column 1 has more than 4 arguments"]),
    # derivatives
    ("derivative-of-builtin", "Derivative(sin(x), x)",
     ["Derivative at column 1 must be of a declared function applied to variables"]),
    ("derivative-of-composite", "Derivative(f(x**2), x)",
     ["the arguments of f must be plain variables"]),
    ("derivative-zero", "Derivative(f(x), t)",
     ["f(...) does not depend on 't' (column 18), so the derivative would be 0"]),
    ("derivative-order", "Derivative(f(x), (x, 9))",
     ["derivative order 9 at column 22 is out of range", "use 1 to 8"]),
    ("derivative-total-order", "Derivative(f(x), " + ", ".join(["x"] * 9) + ")",
     ["Derivative at column 1 has total order 9"]),
    ("derivative-no-variable", "Derivative(f(x))", ["Derivative at column 1 needs a variable"]),
    ("derivative-wrt-function", "Derivative(f(x), f)",
     ["'f' (column 18) is not a coordinate or the time"]),
    ("derivative-without-call", "Derivative", ["function 'Derivative' at column 1 is used"]),
    # syntax and size
    ("dangling-operator", "x +", ["expected a number, name or '(' at column 4, "
                                  "found end of expression"]),
    ("missing-operator", "x y", ["unexpected 'y' at column 3"]),
    ("unclosed-parenthesis", "(x", ["expected ')' at column 3, found end of expression"]),
    ("unclosed-call", "f(x", ["expected ')' at column 4, found end of expression"]),
    ("nested-50", "(" * 50 + "x" + ")" * 50, ["expression is nested more than 40 levels deep"]),
    ("nested-500", "(" * 500 + "x" + ")" * 500, ["expression has more than 800 tokens"]),
    ("nested-100000", "(" * 100_000 + "x" + ")" * 100_000,
     ["expression is 200001 characters long (limit 2000)"]),
    ("unary-chain", "-" * 60 + "x", ["expression is nested more than 40 levels deep"]),
    ("function-chain", "sin(" * 45 + "x" + ")" * 45, ["nested more than 40 levels deep"]),
    ("very-long", "x + " * 600 + "x", ["expression is 2401 characters long (limit 2000)",
                                       "introduce parameters or split it"]),
    ("too-many-tokens", "+".join(["x"] * 500), ["expression has more than 800 tokens"]),
    ("empty", "", ["empty expression", "write an expression such as 0 or m*g*y"]),
    ("blank", "   ", ["empty expression"]),
]


@pytest.mark.parametrize(("text", "fragments"), [(c[1], c[2]) for c in REJECTIONS],
                         ids=[c[0] for c in REJECTIONS])
def test_rejections_explain_themselves(text: str, fragments: list[str]) -> None:
    """Each refused expression gets a message saying what is wrong and where, at once."""
    message = rejection(text)
    for fragment in fragments:
        assert fragment in message


@pytest.mark.parametrize(
    ("value", "found"),
    [([1, 2], "list"), ({"a": 1}, "dict"), (True, "bool"), (None, "NoneType")],
    ids=["list", "dict", "bool", "null"],
)
def test_non_text_values_are_refused(value: Any, found: str) -> None:
    """A list, mapping, boolean or null is not an expression; the message names what it is."""
    message = rejection(value)
    assert f"expected an expression (text or number), found {found}" in message
    assert 'write it as a string, e.g. "m*g*y"' in message


@pytest.mark.parametrize(
    ("value", "fragment"),
    [(10**400, "number is out of range"), (1e200, "number is out of range"),
     (float("inf"), "number is not finite"), (float("nan"), "number is not finite")],
    ids=["huge-int", "huge-float", "inf", "nan"],
)
def test_out_of_range_yaml_numbers_are_refused(value: Any, fragment: str) -> None:
    """Numbers from YAML are range-checked like written ones (a huge int must not overflow)."""
    assert fragment in rejection(value)


def test_the_complete_message_of_an_unknown_name() -> None:
    """The full message names the symbol, its column, the known names and a fix."""
    assert rejection("m*gg") == (
        "unknown name 'gg' at column 3 (known: g, m, t, x, x_dot, y, y_dot); "
        "did you mean 'g'? declare it under parameters, coordinates or functions"
    )


def test_limits_are_what_the_docs_promise() -> None:
    """The bounds are those documented in the module (length, tokens, depth, exponent)."""
    assert (expr.MAX_LENGTH, expr.MAX_TOKENS, expr.MAX_DEPTH, expr.MAX_POWER) == (2000, 800, 40,
                                                                                  1000)
    assert read("(" * 39 + "x" + ")" * 39) == x
    assert read("x**1000") == x**1000


# ------------------------------------------------------------------------------------------
# declarable names


@pytest.mark.parametrize("name", ["x", "theta", "m1", "x_0", "Omega", "phi_dot_ref", "lam"])
def test_valid_names(name: str) -> None:
    """Ordinary identifiers can be declared."""
    assert name_problem(name) is None


@pytest.mark.parametrize(
    ("name", "fragment"),
    [
        ("", "a name must be a non-empty string"),
        (3, "a name must be a non-empty string"),
        ("2x", "'2x' is not a valid name; start with a letter"),
        ("x-y", "'x-y' is not a valid name"),
        ("_x", "'_x' is not a valid name"),
        ("x__y", "'x__y' is not a valid name; no double underscores and no trailing '_'"),
        ("x_", "no double underscores and no trailing '_'"),
        ("lambda", "'lambda' is a Python keyword, which would make the JSON output unreadable"),
        ("match", "'match' is a Python keyword"),
        ("sin", "'sin' is the name of a built-in function or constant; choose another name"),
        ("pi", "'pi' is the name of a built-in function or constant"),
        ("E", "'E' is the name of a built-in function or constant"),
        ("oo", "'oo' is the name of a built-in function or constant"),
        ("Derivative", "'Derivative' is the name of a built-in function or constant"),
        ("\u0430", "non-ASCII character '\u0430' (U+0430 CYRILLIC SMALL LETTER A) in name"),
        ("x\u0430", "names use ASCII letters, digits and '_'"),
    ],
    ids=["empty", "not-text", "leading-digit", "dash", "leading-underscore", "double-underscore",
         "trailing-underscore", "keyword", "soft-keyword", "function", "pi", "E", "oo",
         "Derivative", "cyrillic", "cyrillic-inside"],
)
def test_names_that_cannot_be_declared(name: Any, fragment: str) -> None:
    """Names that would shadow a function or constant, or are not plain ASCII, are refused."""
    problem = name_problem(name)
    assert problem is not None and fragment in problem


@pytest.mark.parametrize("name", ["I", "S", "N", "O", "Q", "theta", "m_1", "Omega"])
def test_ordinary_names_can_be_declared(name: str) -> None:
    """Single capital letters such as I (a moment of inertia) and Greek names are ordinary names."""
    assert name_problem(name) is None


def test_number_bounds_are_inclusive_as_the_message_says() -> None:
    """1e-300 and 1e100, the bounds the message states, are accepted; numbers just outside them are not."""
    assert read("1e-300*x") == x / sympy.Integer(10) ** 300
    assert read("0.001e-297") == sympy.Integer(1) / sympy.Integer(10) ** 300
    assert read("1e100") == sympy.Integer(10) ** 100
    assert read(1e-300) == sympy.Integer(1) / sympy.Integer(10) ** 300
    for text in ("0.999e-300", "1.0000001e100"):
        assert "numbers must lie between 1e-300 and 1e+100 in size" in rejection(text)


def test_names_paragraph_of_the_format_doc_matches_the_rule() -> None:
    """docs/format.md's Names paragraph says what name_problem does: each built-in it lists is refused,
    and each SymPy-looking letter it calls an ordinary name (I, S, N, O, Q) is accepted."""
    import re
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[2] / "docs" / "format.md").read_text(encoding="utf-8")
    paragraph = " ".join(doc.split("\nNames: ", 1)[1].split("\n\n", 1)[0].split())
    refused = re.search(r"not the name of a built-in function or constant of expressions \(([^)]*)\)", paragraph)
    accepted = re.search(r"Single letters that mean something to SymPy — (.*?) — are accepted", paragraph)
    assert refused is not None and accepted is not None, paragraph
    refused_names = re.findall(r"`(\w+)`", refused.group(1))
    accepted_names = re.findall(r"`(\w+)`", accepted.group(1))
    assert refused_names and all(name_problem(n) is not None for n in refused_names), refused_names
    assert "I" in accepted_names and all(name_problem(n) is None for n in accepted_names), accepted_names
    assert "64 characters" in paragraph and name_problem("a" * 64) is None and name_problem("a" * 65)
