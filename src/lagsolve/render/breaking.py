r"""Long displayed equations broken into lines that fit a printed page.

TeX cannot break a displayed formula by itself, and a ``\left( ... \right)`` pair
cannot span two lines. :func:`tex_lines` therefore breaks SymPy's LaTeX where a
textbook would: between the terms of a sum; a product ``c \left(a + b + ...\right)``
as ``c \Bigl(a + b`` / ``+ ... \Bigr)``; a fraction with a long numerator as
``\frac{1}{d} \Bigl(...\Bigr)``. Every line is a complete TeX group, so the lines
can be joined by ``\\`` inside ``align*``. A matrix too wide for the page is
written entry by entry, a vector component by component.

Widths are estimated from the LaTeX text in *glyphs* (about 6 pt each at 11 pt),
which is enough to decide where to break.
"""

from __future__ import annotations

import functools
import re

#: glyphs on a line of the LaTeX report (A4, 2.2 cm margins, 11 pt: about 490 pt; a glyph is about 6 pt)
LINE = 76
_COMMAND = re.compile(r"\\([A-Za-z]+|.)")
_FUNCTIONS = {"sin", "cos", "tan", "log", "exp", "sec", "csc", "cot", "sinh", "cosh", "tanh", "asin", "acos", "atan"}
_SILENT = {"left", "right", "Bigl", "Bigr", "bigl", "bigr", "mathbf", "dot", "ddot", "limits", "displaystyle",
           "begin", "end", "boxed", ",", ";", "!", " "}


@functools.lru_cache(maxsize=65536)
def width(tex: str) -> float:
    r"""Estimated width of LaTeX math ``tex`` in glyphs (``\frac`` counts its wider part), remembered (the Markdown
    and LaTeX reports break the same equations, term by term).

    >>> width(r"\frac{a + b}{c}") < width("a + b + c")
    True
    """
    return _width(tex, 0)[0]


def _group(tex: str, i: int) -> tuple[float, int]:
    """Width of the argument starting at ``tex[i]`` (a ``{...}`` group or one token) and the index after it."""
    while i < len(tex) and tex[i] == " ":
        i += 1
    if i < len(tex) and tex[i] == "{":
        return _width(tex, i + 1, closing=True)
    if i < len(tex) and tex[i] == "\\":
        m = _COMMAND.match(tex, i)
        return 1.0, (m.end() if m else i + 1)
    return (1.0 if i < len(tex) else 0.0), i + 1


def _width(tex: str, i: int, closing: bool = False) -> tuple[float, int]:
    total = 0.0
    while i < len(tex):
        ch = tex[i]
        if ch == "}" and closing:
            return total, i + 1
        if ch == "{":
            w, i = _width(tex, i + 1, closing=True)
            total += w
        elif ch == "\\":
            m = _COMMAND.match(tex, i)
            name = m.group(1) if m else ""
            i = m.end() if m else i + 1
            if name in ("frac", "tfrac", "dfrac"):
                a, i = _group(tex, i)
                b, i = _group(tex, i)
                total += max(a, b) + 0.5
            elif name in _FUNCTIONS:
                total += len(name)
            elif name in ("mathrm", "operatorname", "text", "textbf"):
                w, i = _group(tex, i)
                total += w
            elif name in ("quad", "qquad"):
                total += 2 if name == "quad" else 4
            elif name not in _SILENT:
                total += 1
        elif ch in "^_":
            w, i = _group(tex, i + 1)
            total += 0.7 * w
        elif ch in "+-=<>":
            total += 2.2
            i += 1
        elif ch in " &":
            i += 1
        else:
            total += 1
            i += 1
    return total, i


# -- the top level of a formula ---------------------------------------------------------------------


def _items(tex: str) -> list[tuple[str, str]]:
    r"""``tex`` cut into top-level items: ("group", "{...}"), ("paren", "\left(...\right)"), ("token", ...)."""
    items: list[tuple[str, str]] = []
    i = 0
    while i < len(tex):
        if tex[i] == "{":
            j = _close_brace(tex, i)
            items.append(("group", tex[i:j]))
            i = j
        elif tex.startswith("\\left", i):
            j = _close_left(tex, i)
            items.append(("paren", tex[i:j]))
            i = j
        elif tex[i] == "\\":
            m = _COMMAND.match(tex, i)
            j = m.end() if m else i + 1
            items.append(("token", tex[i:j]))
            i = j
        else:
            items.append(("token", tex[i]))
            i += 1
    return items


def _close_brace(tex: str, i: int) -> int:
    depth = 0
    while i < len(tex):
        if tex[i] == "\\":
            i += 2
            continue
        depth += {"{": 1, "}": -1}.get(tex[i], 0)
        i += 1
        if depth == 0:
            return i
    return len(tex)


def _close_left(tex: str, i: int) -> int:
    depth = 0
    while i < len(tex):
        if tex.startswith("\\left", i) and not tex[i + 5:i + 6].isalpha():
            depth += 1
            i += 5
        elif tex.startswith("\\right", i) and not tex[i + 6:i + 7].isalpha():
            depth -= 1
            i += 6
            if depth == 0:
                m = _COMMAND.match(tex, i)
                return m.end() if m and tex[i] == "\\" else i + 1
        elif tex[i] == "\\":
            i += 2
        else:
            i += 1
    return len(tex)


def _terms(tex: str) -> list[str]:
    """``tex`` cut at its top-level binary ``+`` and ``-``; each term after the first keeps its sign."""
    terms: list[str] = []
    current = ""
    for kind, text in _items(tex):
        if kind == "token" and text in "+-" and current.strip() and current.endswith(" "):
            terms.append(current.strip())
            current = text
        else:
            current += text
    if current.strip():
        terms.append(current.strip())
    return terms


# -- breaking -----------------------------------------------------------------------------------------


def tex_lines(tex: str, room: float = LINE) -> list[str]:
    r"""``tex`` as lines of at most about ``room`` glyphs, each a complete TeX group (remembered: the Markdown and
    LaTeX reports break the same equations).

    >>> tex_lines("a + b + c", room=6)
    ['a + b', '+ c']
    """
    return list(_tex_lines(tex, room))


@functools.lru_cache(maxsize=8192)
def _tex_lines(tex: str, room: float) -> tuple[str, ...]:
    return tuple(_lines(tex, room))


def _lines(tex: str, room: float) -> list[str]:
    tex = tex.strip()
    if width(tex) <= room:
        return [tex]
    terms = _terms(tex)
    if len(terms) > 1:
        return _pack(terms, room)
    return _factor_lines(tex, room) or [tex]


def _pack(terms: list[str], room: float) -> list[str]:
    lines: list[str] = []
    current = ""
    for term in terms:
        if width(term) > room:
            sign = term[0] + " " if term[0] in "+-" else ""
            body = term[1:].strip() if sign else term
            sub = tex_lines(body, room - 2)
            if current:
                lines.append(current)
            lines += [sign + sub[0], *sub[1:-1]] if len(sub) > 1 else []
            current = sub[-1] if len(sub) > 1 else sign + sub[0]
            continue
        joined = f"{current} {term}" if current else term
        if current and width(joined) > room:
            lines.append(current)
            current = term
        else:
            current = joined
    if current:
        lines.append(current)
    return lines


def _factor_lines(tex: str, room: float) -> list[str] | None:
    sign = ""
    if tex.startswith("-"):
        sign, tex = "- ", tex[1:].strip()
    items = _items(tex)
    if len(items) == 3 and items[0][1] in ("\\frac", "\\dfrac") and items[1][0] == items[2][0] == "group":
        numerator, denominator = items[1][1][1:-1], items[2][1][1:-1]
        head = rf"{sign}\frac{{1}}{{{denominator}}} "
        if width(numerator) <= room and width(denominator) <= room:
            return None
        if width(head) <= room * 0.6:
            return _around(head, "", numerator, room)
        # numerator and denominator both long: (numerator) / (denominator), each broken
        if len(_terms(numerator)) > 1:
            top = _around(sign, "", numerator, room)
        else:  # a product, such as r (a long sum): broken inside its parentheses
            inner = tex_lines(numerator, room)
            top = [sign + inner[0], *inner[1:]]
        return top + _around(r"\Big/ ", "", denominator, room)
    candidates = [k for k, (kind, text) in enumerate(items) if kind == "paren" and text[5:6] in "(|"
                  and not (k and items[k - 1][0] == "group") and len(_terms(_inner(text))) > 1]
    if not candidates:
        return None
    k = max(candidates, key=lambda n: width(items[n][1]))
    head = sign + "".join(text for _, text in items[:k])
    tail = "".join(text for _, text in items[k + 1:])
    if width(head) + width(tail) > room * 0.6:
        return None
    bar = items[k][1][5] == "|"
    return _around(head, tail, _inner(items[k][1]), room, bar)


def _around(head: str, tail: str, inner: str, room: float, bar: bool = False) -> list[str]:
    r"""``head \Bigl(inner\Bigr) tail`` broken: a short head opens the first line, a long one a line of its own
    (``\Bigl| ... \Bigr|`` for an absolute value when ``bar``)."""
    if width(head) <= room / 3:
        return _wrapped(head, tail, tex_lines(inner, room - width(head) - 2), bar)
    lines = tex_lines(inner, room - 4)
    return _wrapped(head, tail, ["", *lines], bar)


def _inner(paren: str) -> str:
    r"""``\left( x \right)`` → ``x``; ``\left|{x}\right|`` → ``x``."""
    inner = paren[len("\\left("):paren.rindex("\\right")].strip()
    if inner.startswith("{") and _close_brace(inner, 0) == len(inner):
        inner = inner[1:-1].strip()
    return inner


def _wrapped(head: str, tail: str, inner: list[str], bar: bool = False) -> list[str]:
    r"""``head \Bigl( line1`` ... ``lineN \Bigr) tail`` (with ``|`` for ``(`` and ``)`` when ``bar``)."""
    left, right = (r"\Bigl|", r"\Bigr|") if bar else (r"\Bigl(", r"\Bigr)")
    if len(inner) == 1:
        return [rf"{head}{left}{inner[0]}{right}{tail}"]
    return [rf"{head}{left}{inner[0]}", *inner[1:-1], rf"{inner[-1]}{right}{tail}"]


# -- filters for align* -----------------------------------------------------------------------------


def broken(tex: str, room: float = LINE) -> str:
    r"""``tex`` broken for the right-hand side of an ``align*`` row (continuation lines indented)."""
    return " \\\\\n&\\qquad ".join(tex_lines(tex, room))


def equation(lhs: str, rhs: str, relation: str = "=", line: float = LINE) -> str:
    r"""``lhs &= rhs`` as rows of ``align*``, either side broken when long.

    >>> equation("a", "b")
    'a &= b'
    """
    if width(lhs) <= line / 3:
        rhs_lines = tex_lines(rhs, line - width(lhs) - 3)
        rows = [f"{lhs} &{relation} {rhs_lines[0]}"] + [rf"&\qquad {r}" for r in rhs_lines[1:]]
    else:
        lhs_lines = tex_lines(lhs, line - 2)
        rows = [f"&{lhs_lines[0]}"] + [rf"&\qquad {r}" for r in lhs_lines[1:]]
        rows += [f"&{relation} {r}" if k == 0 else rf"&\qquad {r}" for k, r in enumerate(tex_lines(rhs, line - 4))]
    return " \\\\\n".join(rows)


_MATRIX = re.compile(r"^\\left\[\\begin\{matrix\}(.*)\\end\{matrix\}\\right\]$", re.S)


def _cells(tex: str) -> list[list[str]] | None:
    r"""The cells of SymPy's ``\left[\begin{matrix}...\end{matrix}\right]``, or None for anything else."""
    m = _MATRIX.match(tex.strip())
    if m is None:
        return None
    rows: list[list[str]] = [[]]
    current = ""
    for kind, text in _items(m.group(1)):
        if kind == "token" and text == "&":
            rows[-1].append(current.strip())
            current = ""
        elif kind == "token" and text == "\\\\":
            rows[-1].append(current.strip())
            rows.append([])
            current = ""
        else:
            current += text
    rows[-1].append(current.strip())
    return rows


def matrix(tex: str, name: str) -> str:
    r"""``name = [matrix]`` as rows of ``align*``: the matrix when it fits, else entry by entry.

    A column vector too wide is written one component per line (``F_{1} = ...``); a wider matrix one
    non-zero entry per line (``M_{12} = ...``), saying that the others are zero.
    """
    cells = _cells(tex)
    if cells is None or width(tex) + width(name) + 3 <= LINE:
        return f"{name} &= {tex}"
    column = all(len(r) == 1 for r in cells)
    rows = []
    for i, row in enumerate(cells, 1):
        for j, cell in enumerate(row, 1):
            if cell != "0" or column:
                label = f"{name}_{{{i}}}" if column else f"{name}_{{{i}{j}}}" if len(cells) < 10 else \
                    f"{name}_{{{i},{j}}}"
                rows.append(equation(label, cell))
    if not column and len(rows) < sum(len(r) for r in cells):
        rows.append(rf"&\text{{(the other entries of ${name}$ are 0)}}")
    return " \\\\\n".join(rows)


def vector(components: list[str], name: str, labels: tuple[str, ...] = ("x", "y", "z")) -> str:
    r"""``name = (a, b, c)`` inline when it fits in a line of text, else displayed one component per line."""
    inline = rf"{name} = \left({', '.join(components)}\right)"
    if width(inline) <= LINE * 0.35:
        return f"${inline}$"
    named = labels if len(components) <= len(labels) else tuple(str(k) for k in range(1, len(components) + 1))
    rows = [equation(f"{name}_{{{label}}}", c, line=LINE - 6) for label, c in zip(named, components, strict=False)]
    return "\n\\begin{align*}\n" + " \\\\\n".join(rows) + "\n\\end{align*}\n"


def boxed(lhs: str, rhs: str) -> str:
    r"""``lhs &= \boxed{rhs}`` for a final answer; a long ``rhs`` is broken inside the box.

    >>> boxed("a", "b")
    'a &= \\boxed{b}'
    """
    lines = tex_lines(rhs, LINE - width(lhs) - 5)
    if len(lines) == 1:
        return rf"{lhs} &= \boxed{{{lines[0]}}}"
    body = " \\\\\n&\\qquad ".join(lines)
    return rf"{lhs} &= \boxed{{\begin{{aligned}}[t] &{body}\end{{aligned}}}}"


def formula(lhs: str, rhs: str, punctuation: str = "") -> str:
    r"""``$lhs = rhs$`` in running text when it fits in most of a line, else displayed and broken; a
    ``punctuation`` mark that follows goes after the inline math or at the end of the display.

    >>> formula("h", "m", ":")
    '$h = m$:'
    """
    if width(lhs) + width(rhs) + 2 <= LINE * 0.45:
        return f"${lhs} = {rhs}${punctuation}"
    end = rf"\text{{{punctuation}}}" if punctuation else ""
    # in a list item: the indentation takes about six glyphs of the line
    return "\n\\begin{align*}\n" + equation(lhs, rhs, line=LINE - 6) + end + "\n\\end{align*}\n"
