"""Presentation MathML set the way a textbook sets it, in the browser's own math layout.

SymPy's MathML printer writes what the expression is; browsers following MathML Core then draw an ASCII
hyphen for a minus sign, run ``g m r cos(θ)`` together as "gmrcos(θ)", and draw every parenthesis as a
stretchy fence, whose glyphs stand apart from what they enclose: "( θ )". :func:`typeset` rewrites the
``<math>`` elements of a page: the minus sign U+2212, a thin space before a function's name and the
invisible function application after it, and parentheses that enclose nothing taller than a line
(no fraction, root, table or limits) drawn as text parentheses (``stretchy="false"``).
"""

from __future__ import annotations

import re

#: what makes a parenthesised group taller than a line, so that its parentheses must stretch
_TALL = ("<mfrac", "<mtable", "<msqrt", "<mroot", "<munderover", "<munder")

_MATH = re.compile(r"<math\b[^>]*>.*?</math>", re.S)
_MINUS = re.compile(r"<mo>-</mo>")
_NEGATIVE = re.compile(r"<mn>-([^<]*)</mn>")  # a negative number: the minus sign, then the number
# ⁢ then a function applied to a parenthesised argument: a thin space before the name, ⁡ after it
_FUNCTION = re.compile(r"(<mo>(?:&InvisibleTimes;|&#8290;|\u2062)</mo>)?(<mrow>)?(<mi>[A-Za-z]{2,}</mi>)"
                       r"(?=<mrow><mo>\()")
_PAREN = re.compile(r"<mo>([()])</mo>")


def typeset(page: str) -> str:
    """``page`` with each ``<math>`` element set as the module docstring says; the rest unchanged."""
    return _MATH.sub(lambda m: _math(m.group(0)), page)


def _math(math: str) -> str:
    math = _MINUS.sub("<mo>&#8722;</mo>", math)
    math = _NEGATIVE.sub(r"<mrow><mo>&#8722;</mo><mn>\1</mn></mrow>", math)
    math = _FUNCTION.sub(_function, math)
    return _parentheses(math)


def _function(match: re.Match[str]) -> str:
    times, group, name = match.group(1), match.group(2) or "", match.group(3)
    space = '<mo rspace="0.1667em">&#8290;</mo>' if times else ""
    return f"{space}{group}{name}<mo>&#8289;</mo>"


def _parentheses(math: str) -> str:
    """Each matched pair of parentheses with nothing tall between them marked ``stretchy="false"``."""
    marks = list(_PAREN.finditer(math))
    flat: set[int] = set()
    open_at: list[int] = []
    for index, mark in enumerate(marks):
        if mark.group(1) == "(":
            open_at.append(index)
        elif open_at:
            first = open_at.pop()
            inside = math[marks[first].end(): mark.start()]
            if not any(tag in inside for tag in _TALL):
                flat |= {first, index}
    out, last = [], 0
    for index, mark in enumerate(marks):
        out.append(math[last: mark.start()])
        out.append(f'<mo stretchy="false">{mark.group(1)}</mo>' if index in flat else mark.group(0))
        last = mark.end()
    out.append(math[last:])
    return "".join(out)
