"""Units in the problem file: ``unit: N/m`` on a parameter, coordinate, declared function or the time.

The text is parsed by `pint <https://pint.readthedocs.io>`_'s own unit grammar (a tokenizer and
an evaluation tree over its registry; never Python's ``eval``), after a character whitelist and
a length limit. SI and derived units, prefixes and powers are accepted (``m/s^2``, ``N*m``,
``kg*m^2``, ``rad``, ``km``, ``1`` for a pure number); a unit with an offset (``degC``), a
scale factor (``2*m``) or an exponent beyond :data:`MAX_EXPONENT` is refused with a fix.

A unit is kept as the text written (checked, with ``·`` read as ``*``), so the
:class:`~lagsolve.problem.schema.Problem` stays plain data; the dimensional checks
(:mod:`lagsolve.mechanics.units.dimensions`) read it back with :func:`unit_of`.

>>> canonical("kg·m^2")
'kg*m^2'
>>> dict(unit_of("N/m").dimensionality)
{'[mass]': 1, '[time]': -2}
"""

from __future__ import annotations

import re
from fractions import Fraction
from functools import cache
from typing import Any

from lagsolve.errors import ExpressionError
from lagsolve.problem.yamlread import kind_of

#: the longest unit text accepted
MAX_UNIT_LENGTH = 60
#: the largest |exponent| of one unit in a unit text
MAX_EXPONENT = 12
#: letters (any script: µ, Ω), digits, spaces and the operators of a unit text
_ALLOWED = re.compile(r"^[\w\s*/^()·⋅-]+$")
_EXAMPLES = "write it like kg, m/s^2, N*m, kg*m^2, rad or 1"
#: the time's unit when the file does not declare one
DEFAULT_TIME_UNIT = "s"


@cache
def registry() -> Any:
    """pint's unit registry, made once per process (loading it takes about 0.4 s, so only when a file has units)."""
    from lagsolve.caches import pint_cache
    from lagsolve.pint_import import import_pint

    pint = import_pint()
    folder = pint_cache(pint.__version__)  # definitions parsed by make, read only; else parsed here
    return pint.UnitRegistry(autoconvert_offset_to_baseunit=False,
                             cache_folder=str(folder) if folder is not None else None)


def canonical(text: Any) -> str:
    """The canonical text of the unit ``text``.

    Raises
    ------
    ExpressionError
        Not text, too long, characters outside units, an unknown unit, a scale factor or offset, or a
        huge exponent; the hint says how to write it.
    """
    if isinstance(text, bool) or not isinstance(text, str | int) or (isinstance(text, int) and text != 1):
        raise ExpressionError(f"a unit is text, found {kind_of(text)}", _EXAMPLES)
    text = str(text).strip()
    if not text:
        raise ExpressionError("the unit is empty", "write 1 for a pure number, or " + _EXAMPLES)
    if len(text) > MAX_UNIT_LENGTH:
        raise ExpressionError(f"the unit has {len(text)} characters; the limit is {MAX_UNIT_LENGTH}", _EXAMPLES)
    if not _ALLOWED.match(text) or "_" in text:
        raise ExpressionError(f"{text!r} is not a unit", _EXAMPLES)
    text = _normal(text)
    _check_grammar(text)
    _parse(text)
    return text


#: a unit text's tokens: a power, an operator, a name (letters, then ² or ³), a whole number, a minus sign
_TOKENS = re.compile(r"\s*(\*\*|[*/^()-]|[^\W\d_]+[²³]?|\d+)")
#: deepest nesting of parentheses in a unit
_MAX_NESTING = 4


def _check_grammar(text: str) -> None:
    """Accept only ``factor (('*' | '/' | ' ') factor)*`` with ``factor := (name | 1 | '(' unit ')') ['^' exponent]``
    and a small whole or fractional exponent (``m^2``, ``s^-1``, ``m^(1/2)``), before pint evaluates anything: its
    grammar computes numbers, and ``m^9^9^9`` would never finish."""
    tokens: list[str] = []
    position = 0
    while position < len(text):
        match = _TOKENS.match(text, position)
        if match is None or match.end() == position:
            raise ExpressionError(f"{text!r} is not a unit", _EXAMPLES)
        tokens.append(match.group(1))
        position = match.end()
    tokens = ["^" if t == "**" else t for t in tokens]
    index = 0

    def peek() -> str | None:
        return tokens[index] if index < len(tokens) else None

    def take() -> str:
        nonlocal index
        if index >= len(tokens):
            raise ExpressionError(f"{text!r} is not a unit (it ends too early)", _EXAMPLES)
        index += 1
        return tokens[index - 1]

    def small(token: str) -> None:
        if not token.isdigit() or len(token) > 2:
            raise ExpressionError(f"the exponent {token!r} in {text!r} is not a small whole number",
                                  f"exponents are small numbers (at most {MAX_EXPONENT}), like m^2, s^-1 or m^(1/2)")

    def exponent() -> None:
        token = take()
        if token == "(":
            if peek() == "-":
                take()
            small(take())
            if peek() == "/":
                take()
                small(take())
            if take() != ")":
                raise ExpressionError(f"{text!r}: write a fractional exponent as ^(1/2)", _EXAMPLES)
            return
        if token == "-":
            token = take()
        small(token)

    def factor(depth: int) -> None:
        token = take()
        if token == "(":
            if depth >= _MAX_NESTING:
                raise ExpressionError(f"{text!r} nests parentheses too deeply", _EXAMPLES)
            unit(depth + 1)
            if take() != ")":
                raise ExpressionError(f"{text!r} is not a unit (unbalanced parentheses)", _EXAMPLES)
        elif not (token == "1" or token[0].isalpha()):
            raise ExpressionError(f"{text!r} is not a unit", "a unit has no number in front; " + _EXAMPLES)
        if peek() == "^":
            take()
            exponent()
            if peek() == "^":
                raise ExpressionError(f"{text!r} raises a power to a power", "give each unit one exponent, like m^2")

    def unit(depth: int) -> None:
        factor(depth)
        while peek() not in (None, ")"):
            if peek() in ("*", "/"):
                take()
            factor(depth)

    unit(0)
    if index != len(tokens):
        raise ExpressionError(f"{text!r} is not a unit (unbalanced parentheses)", _EXAMPLES)


def _parse(text: str) -> Any:
    from lagsolve.pint_import import import_pint

    pint = import_pint()
    ureg = registry()
    try:
        unit = ureg.parse_units(text)
    except pint.errors.UndefinedUnitError as exc:
        name = getattr(exc, "unit_names", None) or text
        name = name[0] if isinstance(name, list | tuple) and name else name
        raise ExpressionError(f"unknown unit {name!r} in {text!r}",
                              "use SI names and symbols with prefixes (kg, m, s, N, J, W, rad, km, ms); "
                              + _EXAMPLES) from None
    except ValueError as exc:  # a scale factor ("2*m"), among others
        raise ExpressionError(f"{text!r} is not a unit ({_first_line(exc)})",
                              "a unit has no number in front; " + _EXAMPLES) from None
    except Exception as exc:  # noqa: BLE001 - pint's grammar raises tokenizer and type errors of its own
        raise ExpressionError(f"{text!r} is not a unit ({type(exc).__name__})", _EXAMPLES) from None
    for name, power in (1 * unit).unit_items():
        exponent = Fraction(power).limit_denominator(12)
        if abs(exponent) > MAX_EXPONENT or abs(float(exponent) - float(power)) > 1e-12:
            raise ExpressionError(f"the exponent {power!r} of {name} in {text!r} is out of range",
                                  f"exponents are small numbers (at most {MAX_EXPONENT})")
        if ureg.Quantity(0, name).to_base_units().magnitude != 0:
            raise ExpressionError(f"{text!r} has an offset ({name}, a temperature scale)",
                                  "use an absolute unit such as K")
    return unit


def unit_of(text: str) -> Any:
    """The pint unit of a canonical unit text (as made by :func:`canonical`)."""
    return registry().parse_units(_normal(text))


def _normal(text: str) -> str:
    """``kg·m²`` → ``kg*m²``, ``s**2`` → ``s^2``; runs of spaces become one."""
    return " ".join(text.replace("·", "*").replace("⋅", "*").replace("**", "^").split())


def format_unit(unit: Any) -> str:
    """``kilogram * meter / second ** 2`` → ``kg*m/s^2`` (pint's compact symbols, ``^`` for powers)."""
    text = f"{unit:~C}"
    if text in ("", "dimensionless"):
        return "1"
    return text.replace("**", "^")


def _first_line(exc: Exception) -> str:
    return str(exc).splitlines()[0][:80] if str(exc) else type(exc).__name__
