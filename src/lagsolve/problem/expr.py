"""The only gateway from text to SymPy.

Problem files may come from strangers, so expression text is never handed to
``eval``, ``exec``, ``sympify`` or ``parse_expr``. Instead a small tokenizer and
recursive-descent parser accept exactly the grammar of the problem format::

    expr   := term (('+' | '-') term)*
    term   := unary (('*' | '/') unary)*
    unary  := ('+' | '-') unary | power
    power  := atom (('**' | '^') unary)?
    atom   := NUMBER | NAME | NAME '(' args ')' | '(' expr ')'
            | 'Derivative' '(' expr ',' var (',' var)* ')'    var := NAME | '(' NAME ',' INT ')'

Only names in the caller's :class:`Namespace`, the fixed functions below and the
constants ``pi`` and ``E`` are accepted. Length, token count, nesting depth,
literal size, exponents and the size of exact numbers are bounded, and every
constant sub-expression is evaluated in floating point *before* SymPy combines it
further, so that nothing astronomically large (``9**9**9**9``, ``exp(exp(exp(9)))``)
ever reaches SymPy's evaluator. A sub-expression that SymPy itself reduces to a
number (``0*x``, ``x - x``, ``x**0``) counts as a constant too, so such tricks
cannot smuggle a huge constant past the check.

Example
-------
>>> import sympy
>>> x = sympy.Symbol("x")
>>> parse("x^2/2 + 0.5", Namespace(symbols={"x": x}))
x**2/2 + 1/2
"""

from __future__ import annotations

import cmath
import difflib
import keyword
import math
import re
import unicodedata
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import sympy

from lagsolve.errors import ExpressionError

MAX_LENGTH = 2000
MAX_TOKENS = 800
MAX_DEPTH = 40
#: how high powers with a variable exponent may be nested (x**x**x is 2 high): x**x**x**x**x**x at x = 1.7 has
#: ~10^(10^27) digits, and evaluating it exactly ran out of memory (check) or never ended
MAX_TOWER = 3
MAX_LITERAL = 40
MAX_DECIMAL_EXPONENT = 300
MAX_POWER = 1000
MAX_CONSTANT = 1e100
#: longest declared name (a coordinate, parameter, particle, constraint, ...)
MAX_NAME_LENGTH = 64
#: the range of a number's size in the text, both ends included (exact: "1e-300" itself is allowed)
_SMALLEST, _LARGEST = Fraction(1, 10**300), Fraction(10**100)
MAX_DERIVATIVE_ORDER = 8
#: Exact numbers (integers, numerators, denominators) are limited to this many bits
#: (about 1200 digits), far above anything a problem needs, far below what makes
#: SymPy slow or Python's ``str(int)`` refuse.
MAX_EXACT_BITS = 4000

_c = cmath


def _sign(z: complex) -> complex:
    return complex((z.real > 0) - (z.real < 0))


# name -> (SymPy callable, float evaluator, number of arguments)
FUNCTIONS: dict[str, tuple[Any, Callable[..., complex], int]] = {
    "sin": (sympy.sin, _c.sin, 1),
    "cos": (sympy.cos, _c.cos, 1),
    "tan": (sympy.tan, _c.tan, 1),
    "cot": (sympy.cot, lambda z: 1 / _c.tan(z), 1),
    "sec": (sympy.sec, lambda z: 1 / _c.cos(z), 1),
    "csc": (sympy.csc, lambda z: 1 / _c.sin(z), 1),
    "asin": (sympy.asin, _c.asin, 1),
    "acos": (sympy.acos, _c.acos, 1),
    "atan": (sympy.atan, _c.atan, 1),
    "atan2": (sympy.atan2, lambda y, x: complex(math.atan2(y.real, x.real)), 2),
    "sinh": (sympy.sinh, _c.sinh, 1),
    "cosh": (sympy.cosh, _c.cosh, 1),
    "tanh": (sympy.tanh, _c.tanh, 1),
    "exp": (sympy.exp, _c.exp, 1),
    "log": (sympy.log, _c.log, 1),
    "sqrt": (sympy.sqrt, _c.sqrt, 1),
    "Abs": (sympy.Abs, lambda z: complex(abs(z)), 1),
    "sign": (sympy.sign, _sign, 1),
}
CONSTANTS: dict[str, tuple[Any, complex]] = {
    "pi": (sympy.pi, complex(math.pi)),
    "E": (sympy.E, complex(math.e)),
}
DERIVATIVE = "Derivative"

#: Names a problem may not declare: built-in functions and constants, SymPy's
#: own single-letter objects that its printer and ``parse_expr`` treat specially.
RESERVED = frozenset(FUNCTIONS) | frozenset(CONSTANTS) | {
    DERIVATIVE, "oo", "zoo", "nan", "Function", "Symbol", "Integer", "Rational", "Float",
}
# Single letters such as I (a moment of inertia, as in the format's own example), S, N, O and Q
# are ordinary names here: this parser gives them no meaning, and the JSON output reads back with
# parse_expr when the problem's names are passed as its local_dict.

#: SymPy function class -> float evaluator, to size numbers SymPy made by itself.
_EVALUATORS: dict[Any, Callable[..., complex]] = {
    fn: evaluator for fn, evaluator, _ in FUNCTIONS.values() if isinstance(fn, type)
}
_UNDEFINED = (sympy.nan, sympy.zoo, sympy.oo, -sympy.oo)


@dataclass(frozen=True)
class Namespace:
    """The names an expression may use.

    ``symbols`` maps a name to the SymPy object it stands for; ``functions`` maps
    a declared function name to its SymPy function class; ``forbidden`` maps a
    name that exists in the problem but is not allowed in this field (an
    acceleration, say) to the reason, for a precise message.
    """

    symbols: Mapping[str, Any]
    functions: Mapping[str, Any] = field(default_factory=dict)
    forbidden: Mapping[str, str] = field(default_factory=dict)


def describe_char(ch: str) -> str:
    """``'а' (U+0430 CYRILLIC SMALL LETTER A)`` for a message about a stray character."""
    return f"{ch!r} (U+{ord(ch):04X} {unicodedata.name(ch, 'UNNAMED')})"


_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


def name_problem(name: str) -> str | None:
    """Why ``name`` cannot be declared (a parameter, coordinate, ...), or ``None`` if it can."""
    if not isinstance(name, str) or not name:
        return "a name must be a non-empty string"
    if len(name) > MAX_NAME_LENGTH:
        return (f"a name of {len(name)} characters ({name[:20]!r}...) is too long; "
                f"names are limited to {MAX_NAME_LENGTH} characters")
    for ch in name:
        if not ch.isascii():
            return (f"non-ASCII character {describe_char(ch)} in name {name!r}; "
                    "names use ASCII letters, digits and '_'")
    if not _NAME_RE.match(name):
        return f"{name!r} is not a valid name; start with a letter, then letters, digits or '_'"
    if "__" in name or name.endswith("_"):
        return f"{name!r} is not a valid name; no double underscores and no trailing '_'"
    if keyword.iskeyword(name) or keyword.issoftkeyword(name):
        return (f"{name!r} is a Python keyword, which would make the JSON output unreadable; "
                "choose another name")
    if name in RESERVED:
        return f"{name!r} is the name of a built-in function or constant; choose another name"
    return None


# ---------------------------------------------------------------------------------------------
# tokenizer

_TOKEN_RE = re.compile(
    r"""
    (?P<ws>\s+)
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>\*\*|[-+*/^(),])
    """,
    re.VERBOSE | re.ASCII,
)


@dataclass(frozen=True)
class _Token:
    kind: str  # "number" | "name" | "op" | "end"
    text: str
    column: int  # 1-based


def _tokenize(text: str) -> list[_Token]:
    tokens: list[_Token] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN_RE.match(text, pos)
        if m is None:
            ch = text[pos]
            col = pos + 1
            if ch == ".":
                raise ExpressionError(
                    f"'.' at column {col} is not allowed (attribute access)",
                    "write numbers like 0.5 and names without dots",
                )
            if not ch.isascii():
                raise ExpressionError(
                    f"non-ASCII character {describe_char(ch)} at column {col}",
                    "type names with ASCII letters (a look-alike letter is a different name)",
                )
            raise ExpressionError(
                f"unexpected character {ch!r} at column {col}",
                "expressions use numbers, names, + - * / ** ^, parentheses and function calls",
            )
        kind = m.lastgroup or ""
        if kind != "ws":
            tokens.append(_Token(kind, m.group(), pos + 1))
            if len(tokens) > MAX_TOKENS:
                raise ExpressionError(
                    f"expression has more than {MAX_TOKENS} tokens",
                    "split it with parameters or simplify it",
                )
        pos = m.end()
    tokens.append(_Token("end", "", len(text) + 1))
    return tokens


# ---------------------------------------------------------------------------------------------
# parser: text -> small tuple AST


class _Parser:
    def __init__(self, tokens: list[_Token]) -> None:
        self.tokens = tokens
        self.pos = 0
        self.depth = 0

    def peek(self) -> _Token:
        return self.tokens[self.pos]

    def take(self) -> _Token:
        tok = self.tokens[self.pos]
        if tok.kind != "end":
            self.pos += 1
        return tok

    def expect(self, text: str) -> _Token:
        tok = self.take()
        if tok.text != text or tok.kind == "end":
            found = "end of expression" if tok.kind == "end" else repr(tok.text)
            raise ExpressionError(f"expected {text!r} at column {tok.column}, found {found}")
        return tok

    def enter(self, tok: _Token) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ExpressionError(
                f"expression is nested more than {MAX_DEPTH} levels deep (at column {tok.column})",
                "remove redundant parentheses or split the expression",
            )

    def parse(self) -> tuple:
        node = self.expr()
        tok = self.peek()
        if tok.kind != "end":
            raise ExpressionError(f"unexpected {tok.text!r} at column {tok.column}")
        return node

    def expr(self) -> tuple:
        node = self.term()
        while self.peek().text in ("+", "-"):
            op = self.take()
            node = ("bin", op.text, node, self.term(), op.column)
        return node

    def term(self) -> tuple:
        node = self.unary()
        while self.peek().text in ("*", "/"):
            op = self.take()
            node = ("bin", op.text, node, self.unary(), op.column)
        return node

    def unary(self) -> tuple:
        tok = self.peek()
        if tok.text in ("+", "-"):
            self.take()
            self.enter(tok)
            operand = self.unary()
            self.depth -= 1
            return ("neg", operand) if tok.text == "-" else operand
        return self.power()

    def power(self) -> tuple:
        base = self.atom()
        tok = self.peek()
        if tok.text in ("**", "^"):
            self.take()
            self.enter(tok)
            exponent = self.unary()
            self.depth -= 1
            return ("bin", "**", base, exponent, tok.column)
        return base

    def atom(self) -> tuple:
        tok = self.take()
        if tok.kind == "number":
            return ("num", _number(tok))
        if tok.kind == "name":
            if self.peek().text == "(":
                return self.call(tok)
            return ("name", tok.text, tok.column)
        if tok.text == "(":
            self.enter(tok)
            node = self.expr()
            self.expect(")")
            self.depth -= 1
            return node
        found = "end of expression" if tok.kind == "end" else repr(tok.text)
        raise ExpressionError(
            f"expected a number, name or '(' at column {tok.column}, found {found}"
        )

    def call(self, name: _Token) -> tuple:
        open_tok = self.expect("(")
        self.enter(open_tok)
        if name.text == DERIVATIVE:
            node = self.derivative(name)
        else:
            args = [self.expr()]
            while self.peek().text == ",":
                self.take()
                args.append(self.expr())
            self.expect(")")
            node = ("call", name.text, name.column, tuple(args))
        self.depth -= 1
        return node

    def derivative(self, name: _Token) -> tuple:
        target = self.expr()
        variables: list[tuple[str, int, int]] = []
        while self.peek().text == ",":
            self.take()
            tok = self.take()
            if tok.kind == "name":
                variables.append((tok.text, tok.column, 1))
            elif tok.text == "(":
                var = self.take()
                if var.kind != "name":
                    raise ExpressionError(f"expected a variable name at column {var.column}")
                self.expect(",")
                order_tok = self.take()
                if order_tok.kind != "number" or not order_tok.text.isdigit():
                    raise ExpressionError(
                        f"expected a whole-number derivative order at column {order_tok.column}"
                    )
                order = int(order_tok.text[:4])
                if not 1 <= order <= MAX_DERIVATIVE_ORDER:
                    raise ExpressionError(
                        f"derivative order {order_tok.text[:20]} at column {order_tok.column} "
                        "is out of range",
                        f"use 1 to {MAX_DERIVATIVE_ORDER}",
                    )
                self.expect(")")
                variables.append((var.text, var.column, order))
            else:
                raise ExpressionError(
                    f"expected a variable after ',' at column {tok.column} of Derivative"
                )
        self.expect(")")
        if not variables:
            raise ExpressionError(
                f"Derivative at column {name.column} needs a variable",
                "write Derivative(f(x), x) or Derivative(f(x), (x, 2))",
            )
        return ("deriv", name.column, target, tuple(variables))


def _number(tok: _Token) -> Fraction:
    text = tok.text
    mantissa, _, exponent = text.lower().partition("e")
    digits = mantissa.replace(".", "").lstrip("0")
    if len(digits) > MAX_LITERAL:
        raise ExpressionError(
            f"number at column {tok.column} has more than {MAX_LITERAL} digits",
            "use fewer digits or a parameter",
        )
    # the exponent is read in full (``1e-0000000000009999`` has a huge exponent): the text is
    # at most MAX_LENGTH characters, so int() is cheap, and 10**exponent is computed only
    # once the exponent is known to be small
    power = int(exponent) if exponent else 0
    if abs(power) > MAX_DECIMAL_EXPONENT:
        raise ExpressionError(
            f"number {text[:30]!r} at column {tok.column} is out of range",
            f"decimal exponents are limited to ±{MAX_DECIMAL_EXPONENT}",
        )
    value = Fraction(mantissa) * Fraction(10) ** power
    # compared exactly: the float 1e-300 is a little above 10**-300, which the message says is allowed
    if value != 0 and not (_SMALLEST <= abs(value) <= _LARGEST):
        raise ExpressionError(
            f"number {text[:30]!r} at column {tok.column} is out of range",
            f"numbers must lie between 1e-300 and {MAX_CONSTANT:g} in size",
        )
    return value


# ---------------------------------------------------------------------------------------------
# AST -> SymPy, with every constant sub-expression evaluated first in floating point


class _Builder:
    """Builds SymPy from the AST; each step returns ``(expr, value)``.

    ``value`` is the complex floating-point value of ``expr`` when ``expr`` is a number,
    else ``None``. It is known *before* the next operation hands ``expr`` to SymPy, so a
    constant that would be too large, undefined or complex is refused first.
    """

    def __init__(self, names: Namespace) -> None:
        self.names = names

    def build(self, node: tuple) -> tuple[Any, complex | None]:
        expr, const = self.node(node)
        if const is None and getattr(expr, "is_number", False):
            # SymPy reduced something written with symbols to a number (0*x, x - x, x**0,
            # atan2(m, m)); size it now so that the tree above cannot build on a giant
            const = _value_of(expr)
        if const is not None and expr in _UNDEFINED:
            raise ExpressionError(
                "the expression has an infinite or undefined part",
                "check for a division by zero or a function at a singular point, like tan(pi/2)",
            )
        return expr, const

    def node(self, node: tuple) -> tuple[Any, complex | None]:
        kind = node[0]
        if kind == "num":
            value: Fraction = node[1]
            return sympy.Rational(value.numerator, value.denominator), complex(float(value))
        if kind == "name":
            return self.name(node[1], node[2])
        if kind == "neg":
            expr, const = self.build(node[1])
            return -expr, (None if const is None else -const)
        if kind == "bin":
            return self.binary(node[1], node[2], node[3], node[4])
        if kind == "call":
            return self.call(node[1], node[2], node[3])
        if kind == "deriv":
            return self.derivative(node[1], node[2], node[3])
        raise AssertionError(kind)  # pragma: no cover - the parser makes no other nodes

    def name(self, name: str, column: int) -> tuple[Any, complex | None]:
        if name in CONSTANTS:
            expr, value = CONSTANTS[name]
            return expr, value
        if name in self.names.symbols:
            return self.names.symbols[name], None
        if name in self.names.forbidden:
            raise ExpressionError(f"{name!r} at column {column}: {self.names.forbidden[name]}")
        if name in FUNCTIONS or name in self.names.functions or name == DERIVATIVE:
            raise ExpressionError(
                f"function {name!r} at column {column} is used without arguments",
                f"write {name}(...)",
            )
        if name.startswith("_") or "__" in name:
            raise ExpressionError(
                f"name {name!r} at column {column} is not allowed",
                "names may not start with '_' or contain '__'",
            )
        known = sorted(self.names.symbols)
        close = difflib.get_close_matches(name, known + sorted(self.names.functions), n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        listing = ", ".join(known[:30]) + (", ..." if len(known) > 30 else "")
        raise ExpressionError(
            f"unknown name {name!r} at column {column} (known: {listing})",
            hint + "declare it under parameters, coordinates or functions",
        )

    def binary(self, op: str, left: tuple, right: tuple, column: int) -> tuple[Any, complex | None]:
        a, ca = self.build(left)
        b, cb = self.build(right)
        where = f"'{op}' at column {column}"
        const: complex | None = None
        if op == "**" and cb is not None:
            if abs(cb) > MAX_POWER:
                raise ExpressionError(
                    f"exponent {_show(cb)} of {where} is too large",
                    f"powers are limited to exponents of size {MAX_POWER}",
                )
            _check_exact(_exact_bits(a) * abs(cb), where)
        if op == "**" and cb is None and 1 + _tower(b) > MAX_TOWER:
            raise ExpressionError(
                f"a tower of powers {1 + _tower(b)} high ({where}): its value at ordinary numbers has more digits "
                "than memory holds", f"powers with a variable exponent may be nested {MAX_TOWER} high")
        if op == "/" and cb is not None and cb == 0:
            raise ExpressionError(f"division by zero ({where})")
        if ca is not None and cb is not None:
            const = _checked(lambda: _apply(op, ca, cb), where)
        if op == "+":
            result = a + b
        elif op == "-":
            result = a - b
        elif op == "*":
            result = a * b
        elif op == "/":
            result = a / b
        else:
            result = a**b
        if op in ("*", "/"):
            _check_exact(_exact_bits(result), where)
        return result, const

    def call(self, name: str, column: int, args: tuple) -> tuple[Any, complex | None]:
        where = f"{name}(...) at column {column}"
        if name in FUNCTIONS:
            fn, evaluator, arity = FUNCTIONS[name]
            if len(args) != arity:
                raise ExpressionError(
                    f"{name} at column {column} takes {arity} argument{'s' if arity > 1 else ''}, "
                    f"got {len(args)}"
                )
            built = [self.build(arg) for arg in args]
            consts = [c for _, c in built]
            const = None
            if all(c is not None for c in consts):
                const = _checked(lambda: evaluator(*consts), where)
            return fn(*(e for e, _ in built)), const
        if name in self.names.functions:
            if len(args) > 4:
                raise ExpressionError(f"{name} at column {column} has more than 4 arguments")
            exprs = [self.build(arg)[0] for arg in args]
            return self.names.functions[name](*exprs), None
        if name in self.names.symbols or name in CONSTANTS:
            raise ExpressionError(
                f"{name!r} at column {column} is not a function",
                f"write {name}*(...) for a product",
            )
        if name.startswith("_") or "__" in name:
            raise ExpressionError(
                f"name {name!r} at column {column} is not allowed",
                "names may not start with '_' or contain '__'",
            )
        known = sorted(FUNCTIONS) + sorted(self.names.functions)
        close = difflib.get_close_matches(name, known, n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise ExpressionError(
            f"unknown function {name!r} at column {column}",
            hint + "declare it under functions, or use one of: " + ", ".join(known),
        )

    def derivative(self, column: int, target: tuple, variables: tuple) -> tuple[Any, None]:
        usage = "write Derivative(f(x), x) or Derivative(f(x), (x, 2)) for a declared function f"
        if target[0] != "call" or target[1] not in self.names.functions:
            raise ExpressionError(
                f"Derivative at column {column} must be of a declared function applied to "
                "variables",
                usage,
            )
        expr, _ = self.build(target)
        arguments = set(expr.args)
        if not all(getattr(arg, "is_Symbol", False) for arg in expr.args):
            raise ExpressionError(
                f"Derivative at column {column}: the arguments of {target[1]} must be plain "
                "variables",
                usage,
            )
        total = sum(order for _, _, order in variables)
        if total > MAX_DERIVATIVE_ORDER:
            raise ExpressionError(
                f"Derivative at column {column} has total order {total}",
                f"orders are limited to {MAX_DERIVATIVE_ORDER}",
            )
        spec = []
        for var_name, var_column, order in variables:
            var = self.names.symbols.get(var_name)
            if var is None or not getattr(var, "is_Symbol", False):
                raise ExpressionError(
                    f"Derivative at column {column}: {var_name!r} (column {var_column}) is not a "
                    "coordinate or the time",
                    "differentiate with respect to a coordinate, e.g. Derivative(f(x), x)",
                )
            if var not in arguments:
                raise ExpressionError(
                    f"Derivative at column {column}: {target[1]}(...) does not depend on "
                    f"{var_name!r} (column {var_column}), so the derivative would be 0",
                    f"differentiate with respect to an argument of {target[1]}",
                )
            spec.append((var, order))
        return sympy.diff(expr, *spec), None


def _apply(op: str, a: complex, b: complex) -> complex:
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        return a / b
    return a**b


def _show(value: complex) -> str:
    return f"{value.real:.6g}" if value.imag == 0 else f"{value:.6g}"


def _checked(compute: Callable[[], complex], what: str) -> complex:
    """Evaluate a constant in floating point; reject what is undefined, complex or too large."""
    try:
        value = complex(compute())
    except ZeroDivisionError:
        raise ExpressionError(f"division by zero in a constant ({what})") from None
    except OverflowError:
        raise ExpressionError(
            f"a constant in {what} is too large to evaluate",
            f"constants are limited to {MAX_CONSTANT:g} in size",
        ) from None
    except ValueError:
        raise ExpressionError(
            f"a constant in {what} is undefined (outside the function's domain)"
        ) from None
    if not (math.isfinite(value.real) and math.isfinite(value.imag)) or abs(value) > MAX_CONSTANT:
        raise ExpressionError(
            f"a constant in {what} is too large",
            f"constants are limited to {MAX_CONSTANT:g} in size",
        )
    if abs(value.imag) > 1e-12 * max(1.0, abs(value.real)):
        raise ExpressionError(
            f"a constant in {what} is a complex number; expressions must be real",
            "check square roots and logarithms of negative numbers",
        )
    return value


def _value_of(expr: Any) -> complex:
    """The floating-point value of a SymPy number built from bounded pieces."""
    if expr in _UNDEFINED:
        raise ExpressionError(
            "the expression has an infinite or undefined part",
            "check for a division by zero or a function at a singular point",
        )
    if expr.is_Rational:
        _check_exact(_exact_bits(expr), "a constant")
        return _checked(lambda: complex(Fraction(int(expr.p), int(expr.q))), "a constant")
    if expr is sympy.pi:
        return CONSTANTS["pi"][1]
    if expr is sympy.E:
        return CONSTANTS["E"][1]
    if expr is sympy.I:
        raise ExpressionError("the expression is a complex number; expressions must be real")
    args = [_value_of(arg) for arg in expr.args]
    if expr.is_Add:
        return _checked(lambda: sum(args, complex(0)), "a sum")
    if expr.is_Mul:
        return _checked(lambda: math.prod(args, start=complex(1)), "a product")
    if expr.is_Pow:
        return _checked(lambda: _apply("**", args[0], args[1]), "a power")
    if expr.func in _EVALUATORS:
        return _checked(lambda: _EVALUATORS[expr.func](*args), f"{expr.func.__name__}(...)")
    raise ExpressionError(  # pragma: no cover - SymPy makes no other numbers from our pieces
        f"cannot check the size of the constant {str(expr)[:40]}", "write it more simply"
    )


def _exact_bits(expr: Any) -> float:
    """Bits of the largest exact number SymPy holds in ``expr``'s numeric factors."""
    if expr.is_Rational:
        return float(max(int(expr.p).bit_length(), int(expr.q).bit_length()))
    if expr.is_Pow and expr.base.is_Rational and expr.exp.is_Rational:
        return _exact_bits(expr.base) * abs(float(expr.exp))
    if expr.is_Mul:
        return sum(_exact_bits(arg) for arg in expr.args if arg.is_Rational or arg.is_Pow)
    if expr.is_Add:
        return max((_exact_bits(arg) for arg in expr.args), default=0.0)
    return 0.0


def _tower(expr: Any) -> int:
    """How high powers with a non-constant exponent are nested in ``expr`` (x**y is 1, x**x**x is 2)."""
    if not isinstance(expr, sympy.Basic) or not expr.args:
        return 0
    if isinstance(expr, sympy.Pow) and not expr.exp.is_number:
        return max(1 + _tower(expr.exp), _tower(expr.base))
    return max(_tower(a) for a in expr.args)


def _check_exact(bits: float, where: str) -> None:
    if bits > MAX_EXACT_BITS:
        raise ExpressionError(
            f"{where} would make an exact number of about {int(bits * 0.30103)} digits",
            f"exact numbers are limited to about {int(MAX_EXACT_BITS * 0.30103)} digits; "
            "use smaller powers or a parameter",
        )


def parse(text: object, names: Namespace) -> Any:
    """Parse one expression of the problem format into a SymPy expression.

    Parameters
    ----------
    text : str, int or float
        The expression as written in the file. Numbers are read exactly (``0.1`` is 1/10).
    names : Namespace
        The symbols and declared functions this field may use.

    Returns
    -------
    sympy.Expr

    Raises
    ------
    ExpressionError
        With a message that says what is wrong and where in the text.
    """
    if isinstance(text, bool) or not isinstance(text, str | int | float):
        raise ExpressionError(
            f"expected an expression (text or number), found {type(text).__name__}",
            'write it as a string, e.g. "m*g*y"',
        )
    if isinstance(text, float) and not math.isfinite(text):
        raise ExpressionError("number is not finite", "give a finite number")
    # ints are compared exactly (a huge int cannot be converted to float)
    if isinstance(text, int | float) and text != 0 and not 1e-300 <= abs(text) <= MAX_CONSTANT:
        raise ExpressionError(
            "number is out of range",
            f"numbers must lie between 1e-300 and {MAX_CONSTANT:g} in size",
        )
    if isinstance(text, float):
        text = repr(text)
    text = str(text)
    if len(text) > MAX_LENGTH:
        raise ExpressionError(
            f"expression is {len(text)} characters long (limit {MAX_LENGTH})",
            "introduce parameters or split it",
        )
    if not text.strip():
        raise ExpressionError("empty expression", "write an expression such as 0 or m*g*y")
    node = _Parser(_tokenize(text)).parse()
    expr, const = _Builder(names).build(node)
    if const is not None and abs(const.imag) > 1e-12 * max(1.0, abs(const.real)):
        raise ExpressionError("the expression is a complex number; expressions must be real")
    if expr.has(*_UNDEFINED):
        raise ExpressionError(
            "the expression has an infinite or undefined part",
            "check for a division by zero or a function at a singular point, like tan(pi/2)",
        )
    return expr
