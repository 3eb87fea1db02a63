"""Printing expressions the way a worked solution writes them.

* LaTeX: dot notation (:math:`\\dot x`, :math:`\\ddot\\theta`), primes for declared
  functions (:math:`f'(x)`, :math:`f''(x)`), Greek names as Greek letters;
* plain text for terminals: ``ẋ``, ``θ̈``, ``f'(x)``;
* TeX and Markdown escaping of user text (names, descriptions).

The filters are registered in one table, :data:`FILTERS`, used by the Jinja2
environment in :mod:`lagsolve.render.report`.
"""

from __future__ import annotations

import functools
import re
import textwrap
import unicodedata
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import sympy
from markupsafe import Markup, escape
from sympy.printing.latex import LatexPrinter
from sympy.printing.mathml import MathMLPresentationPrinter
from sympy.printing.str import StrPrinter

from lagsolve.problem.names import momentum_name
from lagsolve.render.breaking import boxed, broken, equation, formula, matrix, vector
from lagsolve.render.prose import description_segments, render_segments, segments

_GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ", "eta": "η",
    "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν", "xi": "ξ",
    "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω",
    "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ",
    "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
}
_DOT = "\u0307"
_DDOT = "\u0308"


def _split_rate(name: str) -> tuple[str, int]:
    """``theta_ddot`` → (``theta``, 2); ``x_dot`` → (``x``, 1); other names → (name, 0)."""
    if name.endswith("_ddot"):
        return name[:-5], 2
    if name.endswith("_dot"):
        return name[:-4], 1
    return name, 0


def _prime(order: int) -> str:
    return "'" * order if order <= 3 else f"^{{({order})}}"


def _single_function_derivative(expr: Any) -> tuple[Any, int] | None:
    """``Derivative(f(x), (x, n))`` of a one-argument declared function → (f(x), n)."""
    inner = expr.expr
    if not isinstance(inner, sympy.core.function.AppliedUndef) or len(inner.args) != 1:
        return None
    if len(expr.variable_count) != 1:
        return None
    var, order = expr.variable_count[0]
    return (inner, int(order)) if var == inner.args[0] else None


#: the subexpressions one printer remembers (:class:`_RememberedOrder`) before it starts again
PRINTED_LIMIT = 100_000


@functools.lru_cache(maxsize=16384)
def _ordered_terms(expr: Any, order: str | None) -> tuple[Any, ...]:
    """``expr.as_ordered_terms(order=order)``, remembered: sorting a sum's terms evaluates each coefficient, and
    the same sums are printed by the LaTeX, text and JSON printers (a chain's equations hold hundreds)."""
    return tuple(expr.as_ordered_terms(order=order))


class _RememberedOrder:
    """A printer mixin: the terms of a sum ordered once per process (:func:`_ordered_terms`), and each subexpression
    printed once per printer (its text does not depend on where it stands: the caller adds the brackets), as a
    chain's sines, cosines and products come back in every equation."""

    _settings: dict[str, Any]

    def _print(self, expr: Any, **kwargs: Any) -> str:
        if kwargs or not isinstance(expr, sympy.Basic):
            return str(super()._print(expr, **kwargs))  # type: ignore[misc]
        memo: dict[Any, str] = self.__dict__.setdefault("_printed", {})
        text = memo.get(expr)
        if text is None:
            if len(memo) >= PRINTED_LIMIT:
                memo.clear()
            text = memo[expr] = str(super()._print(expr))  # type: ignore[misc]
        return text

    def _as_ordered_terms(self, expr: Any, order: str | None = None) -> list[Any]:
        order = order or self._settings["order"]
        if order in ("old", "none"):
            return super()._as_ordered_terms(expr, order=order)  # type: ignore[misc]
        return list(_ordered_terms(expr, order))


class MechanicsLatexPrinter(_RememberedOrder, LatexPrinter):
    """LaTeX with dots for rates and primes for declared functions of one variable."""

    def __init__(self, rates: frozenset[str] = frozenset(), settings: dict | None = None) -> None:
        super().__init__(settings or {})
        self.rates = rates

    def _print_Symbol(self, expr: Any, style: str = "plain") -> str:
        base, order = _split_rate(expr.name)
        if order and base in self.rates:
            inner = super()._print_Symbol(sympy.Symbol(base))
            return ("\\dot{%s}" if order == 1 else "\\ddot{%s}") % inner
        for prefix, head in (("lambda_", "\\lambda"), ("N_", "N")):
            label = expr.name[len(prefix):]
            if expr.name.startswith(prefix) and _worded(label):
                # a multiplier or normal force named after its constraint: the label is a word, set upright
                escaped = label.replace("_", "\\_")
                return f"{head}_{{\\mathrm{{{escaped}}}}}"
        head, sep, tail = expr.name.partition("_")
        if sep and head and _worded(tail) and "_" not in tail:
            return f"{super()._print_Symbol(sympy.Symbol(head))}_{{\\mathrm{{{tail}}}}}"
        return super()._print_Symbol(expr)

    def _print_Mul(self, expr: Any) -> str:
        flipped = _positive_denominators(expr)
        return super()._print_Mul(expr) if flipped is expr else self._print(flipped)

    def ordered_terms(self, expr: Any) -> list[Any]:
        """The terms of a sum in the order this printer writes them."""
        return list(self._as_ordered_terms(expr, order=None))

    def _print_Derivative(self, expr: Any) -> str:
        found = _single_function_derivative(expr)
        if found is None:
            return super()._print_Derivative(expr)
        inner, order = found
        name = self._print(sympy.Symbol(inner.func.__name__))
        return f"{name}{_prime(order)}\\left({self._print(inner.args[0])}\\right)"


def _worded(label: str) -> bool:
    """A subscript that is a word (``wire``, ``cart``, ``floor_1``), not a Greek letter or an index."""
    letters = label.rstrip("0123456789")
    return len(letters) > 1 and letters not in _GREEK and letters.replace("_", "").isalpha()


def _positive_denominators(expr: Any) -> Any:
    """``x/(-M - m)`` → ``-x/(M + m)``, ``x/(-3 R + 3 r)`` → ``-x/(3 R - 3 r)``: a denominator that would be
    printed with a leading minus (its first term in the printers' order is negative) gives up its sign."""
    factors = list(sympy.Mul.make_args(expr))
    sign = 1
    for k, f in enumerate(factors):
        if (isinstance(f, sympy.Pow) and f.exp.is_Integer and f.exp < 0 and isinstance(f.base, sympy.Add)
                and f.base.as_ordered_terms()[0].could_extract_minus_sign()):
            factors[k] = sympy.Pow(-f.base, f.exp)
            sign *= -1 if f.exp % 2 else 1
    if all(a is b for a, b in zip(factors, sympy.Mul.make_args(expr), strict=True)):
        return expr
    return sympy.Mul(sign, *factors)


def _greek(name: str, mark: str = "") -> str:
    """``theta1`` → ``θ1`` (``θ̇1`` with a dot ``mark``): a Greek name, then any digits."""
    letters = name.rstrip("0123456789")
    return _GREEK.get(letters, letters) + mark + name[len(letters):]


class MechanicsTextPrinter(_RememberedOrder, StrPrinter):
    """One-line text for terminals: ``ẋ``, ``θ̈``, ``f'(x)``, Greek letters."""

    def __init__(self, rates: frozenset[str] = frozenset()) -> None:
        super().__init__({})
        self.rates = rates

    def _print_Symbol(self, expr: Any) -> str:
        base, order = _split_rate(expr.name)
        if order and base in self.rates:
            return _greek(base, _DOT if order == 1 else _DDOT)
        head, sep, tail = expr.name.partition("_")
        return _greek(head) + sep + _GREEK.get(tail, tail) if sep else _greek(expr.name)

    def _print_Pow(self, expr: Any, rational: bool = False) -> str:
        base, exp = expr.args
        if exp.is_Integer and 2 <= exp <= 9 and (base.is_Symbol or base.is_Function or base.is_Derivative):
            return self._print(base) + "⁰¹²³⁴⁵⁶⁷⁸⁹"[int(exp)]
        return super()._print_Pow(expr, rational)

    def _print_Mul(self, expr: Any) -> str:
        flipped = _positive_denominators(expr)
        return super()._print_Mul(expr) if flipped is expr else self._print(flipped)

    def _print_Derivative(self, expr: Any) -> str:
        found = _single_function_derivative(expr)
        if found is None:
            return super()._print_Derivative(expr)
        inner, order = found
        return f"{inner.func.__name__}{_prime(order) if order <= 3 else f'^({order})'}({self._print(inner.args[0])})"


class MechanicsMathMLPrinter(MathMLPresentationPrinter):
    """Presentation MathML with dots for rates, primes for declared functions and upright word subscripts."""

    def __init__(self, rates: frozenset[str] = frozenset(), settings: dict | None = None) -> None:
        super().__init__(settings or {})
        self.rates = rates

    def _element(self, tag: str, text: str | None = None, **attributes: str) -> Any:
        node = self.dom.createElement(tag)
        for key, value in attributes.items():
            node.setAttribute(key, value)
        if text is not None:
            node.appendChild(self.dom.createTextNode(text))
        return node

    def _print_Symbol(self, sym: Any, style: str = "plain") -> Any:
        base, order = _split_rate(sym.name)
        if order and base in self.rates:
            letters = base.rstrip("0123456789")
            over = self._element("mover", accent="true")
            over.appendChild(self._print(sympy.Symbol(letters or base)))
            over.appendChild(self._element("mo", "\u02d9" if order == 1 else "\u00a8"))
            if not letters or letters == base:
                return over
            sub = self._element("msub")  # θ̇ with its index below: the dot sits on the letter
            sub.appendChild(over)
            sub.appendChild(self._element("mn", base[len(letters):]))
            return sub
        head, sep, tail = sym.name.partition("_")
        if sep and head and _worded(tail):
            sub = self._element("msub")
            sub.appendChild(self._print(sympy.Symbol(head)))
            sub.appendChild(self._element("mi", tail, mathvariant="normal"))
            return sub
        return super()._print_Symbol(sym, style)

    def _print_Mul(self, expr: Any) -> Any:
        flipped = _positive_denominators(expr)
        return super()._print_Mul(expr) if flipped is expr else self._print(flipped)

    def parenthesize(self, item: Any, level: int, strict: bool = False) -> Any:
        """f'(x) needs no parentheses of its own in a product, as in the LaTeX."""
        if isinstance(item, sympy.Derivative) and _single_function_derivative(item) is not None:
            return self._print(item)
        return super().parenthesize(item, level, strict)

    def _print_Derivative(self, expr: Any) -> Any:
        found = _single_function_derivative(expr)
        if found is None:
            return super()._print_Derivative(expr)
        inner, order = found
        row = self._element("mrow")
        name = self._element("msup")
        name.appendChild(self._element("mi", inner.func.__name__))
        name.appendChild(self._element("mo", "\u2032" * order) if order <= 3 else self._element("mn", f"({order})"))
        row.appendChild(name)
        row.appendChild(self._element("mo", "("))
        row.appendChild(self._print(inner.args[0]))
        row.appendChild(self._element("mo", ")"))
        return row


class Notation:
    """Printers bound to one problem's coordinates (which names get dots)."""

    def __init__(self, coordinates: list[str] | tuple[str, ...]) -> None:
        rates = frozenset(coordinates)
        self.coordinates = tuple(coordinates)
        self._latex = MechanicsLatexPrinter(rates, {"mul_symbol": None})
        self._inline = MechanicsLatexPrinter(rates, {"mul_symbol": None, "fold_short_frac": True, "order": "none"})
        self._text = MechanicsTextPrinter(rates)
        self._mathml = MechanicsMathMLPrinter(rates)

    def latex(self, expr: Any) -> str:
        """LaTeX of ``expr``, remembered per problem's coordinates: the Markdown and LaTeX reports (and the HTML
        page's figures) print the same expressions, and a large system's take seconds each time."""
        try:
            return _latex_of(self.coordinates, expr)
        except TypeError:  # not hashable
            return self._latex.doprint(expr)

    def inline(self, expr: Any) -> str:
        """LaTeX for one line of figure text (matplotlib's mathtext): short fractions on the line (``k x^{2} / 2``)
        and, in each sum, the terms with a minus sign after the others, a coordinate's before a parameter's
        (``x_{2} - x_{1} - L_{0}``, not ``- L_{0} - x_{1} + x_{2}``)."""
        return self._inline.doprint(self._signs_last(expr))

    def _signs_last(self, expr: Any) -> Any:
        """``expr`` rebuilt unevaluated (so that nothing is reordered or distributed again), its sums reordered."""
        if not expr.args or not isinstance(expr, sympy.Basic) or isinstance(expr, sympy.Derivative):
            return expr
        args = [self._signs_last(a) for a in expr.args]
        if isinstance(expr, sympy.Add):
            args.sort(key=lambda term: (term.could_extract_minus_sign(), not self._moves(term)))
        try:
            return expr.func(*args, evaluate=False)
        except TypeError:  # a class that takes no ``evaluate``
            return expr

    def _moves(self, term: Any) -> bool:
        return any(_split_rate(s.name)[0] in self.coordinates for s in term.free_symbols if isinstance(s, sympy.Symbol))

    def text(self, expr: Any) -> str:
        return self._text.doprint(expr)

    def mathml(self, expr: Any) -> str:
        """Presentation MathML (without the ``<math>`` element), as browsers render it natively."""
        return self._mathml.doprint(expr)


@functools.lru_cache(maxsize=16)
def _latex_printer(coordinates: tuple[str, ...]) -> Any:
    return MechanicsLatexPrinter(frozenset(coordinates), {"mul_symbol": None})


@functools.lru_cache(maxsize=8192, typed=True)
def _latex_of(coordinates: tuple[str, ...], expr: Any) -> str:
    return str(_latex_printer(coordinates).doprint(expr))


class _JsonPrinter(_RememberedOrder, StrPrinter):
    """SymPy's ``sstr`` (its ``StrPrinter``), the terms of each sum ordered once per process."""


_JSON = _JsonPrinter({"order": None})


def to_json(expr: Any) -> str:
    """SymPy's ``str()`` syntax with the input's names (``x_dot``, ``Derivative(f(x), x)``): ``sympy.sstr(expr,
    order=None)``."""
    return str(_JSON.doprint(expr))


_TEX_ESCAPES = {
    "\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#",
    "^": r"\textasciicircum{}", "_": r"\_", "%": r"\%", "~": r"\textasciitilde{}",
    "<": r"\textless{}", ">": r"\textgreater{}", "|": r"\textbar{}",
}


def tex_escape(text: str) -> str:
    r"""User text as literal TeX: ``\input{/etc/passwd}`` prints, never runs.

    >>> tex_escape(r"\input{x} 50% & $1")
    '\\textbackslash{}input\\{x\\} 50\\% \\& \\$1'
    """
    out = []
    for k, piece in enumerate(_MARKED.split(str(text))):
        if k % 2:  # a letter with a dot or two above it, or a superscript T (q̈, Aᵀ in the notes)
            accent = {"\u0307": "\\dot", "\u0308": "\\ddot"}.get(piece[-1])
            out.append(f"$\\{accent[1:]}{{{piece[0]}}}$" if accent else "$^{T}$")
        else:
            out.append("".join(_tex_char(ch) for ch in piece if ch in "\n\t" or ch.isprintable()))
    return "".join(out)


_MARKED = re.compile("([A-Za-z][\u0307\u0308]|\u1d40)")


def _tex_char(ch: str) -> str:
    if ch in _TEX_ESCAPES:
        return _TEX_ESCAPES[ch]
    if ord(ch) < 256:
        return ch  # ASCII and Latin-1 letters work with inputenc/T1
    name = unicodedata.name(ch, "")
    if name.startswith("GREEK ") and " LETTER " in name:
        letter = name.rsplit(" ", 1)[-1].lower().replace("lamda", "lambda")  # Unicode spells it LAMDA
        if "CAPITAL" in name:
            letter = letter.capitalize()
        if letter in _GREEK:
            return f"$\\{letter}$"
    return "?"


_MD_SPECIAL = set("\\`*_{}[]()<>#+-.!|$~&")


def md_escape(text: str) -> str:
    """User text as literal Markdown (names): every Markdown and HTML special character escaped."""
    out = []
    for ch in str(text):
        if ch == "<":
            out.append("&lt;")
        elif ch == ">":
            out.append("&gt;")
        elif ch == "&":
            out.append("&amp;")
        elif ch in _MD_SPECIAL:
            out.append("\\" + ch)
        else:
            out.append(ch)
    return "".join(out)


_FENCE_RE = re.compile(r"^( {0,3})([`~])(?=\2\2)", re.MULTILINE)


def md_prose(text: str) -> str:
    r"""A description for the Markdown report: Markdown is kept, raw HTML, math delimiters and code
    fences are not (a fence would turn the rest of the report into code).

    >>> md_prose("See <b> $x$\n```python")
    'See &lt;b&gt; \\$x\\$\n\\```python'
    """
    text = str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace("$", "\\$")
    return _FENCE_RE.sub(r"\1\\\2", text)


def tex_lines(text: str) -> str:
    r"""Preformatted user text (a simulation summary) as TeX lines: every character escaped, spaces kept
    as ties so columns line up in ``\ttfamily``, each line ended by ``\\``. Unlike ``verbatim``, no
    text can end the environment.

    >>> print(tex_lines("a  b\n\\end{verbatim}"))
    a~~b\\
    \textbackslash{}end\{verbatim\}
    """
    lines = [tex_escape(part).replace(" ", "~") or "~" for line in str(text).rstrip("\n").split("\n")
             for part in _wrapped(line)]
    return "\\\\\n".join(lines)


#: characters of \small\ttfamily that fit the printed line (A4, 2.2 cm margins: about 96; kept below)
TT_LINE = 90


def _wrapped(line: str) -> list[str]:
    """A line longer than :data:`TT_LINE` broken at spaces, continued under its own indentation plus two."""
    if len(line) <= TT_LINE:
        return [line]
    indent = " " * (len(line) - len(line.lstrip()) + 2)
    return textwrap.wrap(line, TT_LINE, subsequent_indent=indent, break_long_words=True,
                         break_on_hyphens=False) or [line]


def md_code(text: str) -> str:
    """Preformatted user text as a fenced Markdown code block whose fence no backtick run in it can close.

    >>> print(md_code("a ``` b"))
    ````text
    a ``` b
    ````
    """
    body = str(text).rstrip("\n")
    longest = max((len(run) for run in re.findall(r"`+", body)), default=0)
    fence = "`" * max(3, longest + 1)
    return f"{fence}text\n{body}\n{fence}"


_ASCII = {
    _DOT: "_dot", _DDOT: "_ddot", "\u2212": "-", "\u2013": "-", "\u2014": "--", "\u2192": "->",
    "\u00b7": "*", "\u2202": "d", "\u2264": "<=", "\u2265": ">=", "\u2260": "!=", "\u2026": "...",
    "\u2713": "+", "\u2717": "X", "\u25cb": "o", "\u25a1": "[]", "\u1d40": "^T", "\u221a": "sqrt",
    "\u00d7": "*", "\u00b1": "+/-",
    "\u2248": "~", "\u221e": "oo", "\u2227": "^", "\u00a0": " ",
}


def ascii_text(text: str) -> str:
    """Text in ASCII for a terminal that cannot show Unicode: ẍ → x_ddot, θ̇ → theta_dot, λ → lambda,
    ² → **2, ✓ → +, ✗ → X; other accents are dropped and anything else unknown becomes '?'.

    >>> ascii_text("λ_wire = m*(g + ẋ²*f''(x)) ✓ θ̇₀ −1 → é")
    "lambda_wire = m*(g + x_dot**2*f''(x)) + theta_dot0 -1 -> e"
    """
    out: list[str] = []
    exponent = False  # inside a run of superscripts: ⁻¹⁰ → **-10
    for ch in unicodedata.normalize("NFD", str(text)):
        name = "" if ch.isascii() else unicodedata.name(ch, "")
        if name.startswith("SUPERSCRIPT ") and (name.endswith("MINUS") or unicodedata.digit(ch, None) is not None):
            out.append(("" if exponent else "**") + ("-" if name.endswith("MINUS") else str(unicodedata.digit(ch))))
            exponent = True
            continue
        exponent = False
        if ch.isascii():
            out.append(ch)
        elif ch in _ASCII:
            out.append(_ASCII[ch])
        elif unicodedata.combining(ch):
            continue
        elif name.startswith("GREEK ") and " LETTER " in name:
            letter = name.rsplit(" ", 1)[-1].lower().replace("lamda", "lambda")
            out.append(letter.capitalize() if "CAPITAL" in name else letter)
        elif name.startswith("SUBSCRIPT ") and unicodedata.digit(ch, None) is not None:
            out.append(str(unicodedata.digit(ch)))
        else:
            out.append("?")
    return "".join(out)


def ascii_fallback(error: UnicodeError) -> tuple[str, int]:
    """A codec error handler (``codecs.register_error``) writing :func:`ascii_text` for what the
    stream's encoding cannot hold."""
    if not isinstance(error, UnicodeEncodeError):
        raise error
    return ascii_text(error.object[error.start: error.end]), error.end


def tex_prose(text: str, symbols: Mapping[str, Sequence[str]]) -> str:
    """A note of the derivation for LaTeX: the quantities it names as math, the rest escaped."""
    return "".join(f"${tex}$" if kind == "math" else tex_escape(tex) for kind, tex, _ in segments(text, symbols))


def md_math_prose(text: str, symbols: Mapping[str, Sequence[str]]) -> str:
    """A note of the derivation for Markdown: the quantities it names as GitHub math, the rest escaped."""
    return "".join(f"$`{tex}`$" if kind == "math" else md_prose(tex) for kind, tex, _ in segments(text, symbols))


def tex_description(text: str) -> str:
    """A description from the file for LaTeX: its safe ``$...$`` math kept, everything else escaped."""
    return render_segments(description_segments(text), tex_escape, lambda m: f"${m}$")


#: what a Markdown renderer would turn into a link by itself (GitHub's extended autolinks: a scheme and ``//``,
#: ``www.``, ``mailto:``/``xmpp:``, an e-mail address), up to a space or a character that ends one
_AUTOLINK = re.compile(r"(?:\b[A-Za-z][A-Za-z0-9+.\-]*://|\bwww\.|\b(?:mailto|xmpp):)[^\s<>`|\[\]\\]*"
                       r"|[A-Za-z0-9._%+\-]+@[A-Za-z0-9\-]+(?:\.[A-Za-z0-9\-]+)+")
#: what closes a link or an image (``](url)``), joins a reference (``][x]``) or defines one (``]: url``), and a table
#: cell's end: escaped, the rest of the brackets stay as written (``[[a, b], [c, d]]`` is no link)
_MD_LINK = re.compile(r"(\](?=[(\[:])|\|)")
#: a line that a Markdown renderer would read as a heading (``# x``) or as the underline of one (``===``, ``---``)
_MD_HEADING = re.compile(r"^( {0,3})(#|=+[ \t]*$|-+[ \t]*$)", re.MULTILINE)


def _md_inert(text: str, *, inline: bool) -> str:
    r"""Text from a problem file as Markdown that renders as the same text and nothing else: raw HTML, math
    delimiters and fences as in :func:`md_prose`, and no link, image, autolink or heading (a ``]`` that would
    close one, backslashes, ``|`` and line-initial ``#`` escaped; a URL or an e-mail address as literal code:
    no link reference can be defined, so ``[x]`` alone links nowhere). With
    ``inline`` (a table cell, a parenthesis) a line break is a space, so the text cannot end its row.

    >>> _md_inert("see [here](javascript:alert(1)) ![b](https://t.example/p.png)", inline=True)
    'see [here\\](javascript:alert(1)) ![b\\](`https://t.example/p.png`)'
    >>> _md_inert("a\n# Forged | heading", inline=True)
    'a # Forged \\| heading'
    >>> print(_md_inert("a\n# Forged heading\n===", inline=False))
    a
    \# Forged heading
    \===
    """
    text = str(text)
    if inline:
        text = re.sub(r"[ \t]*(?:\r\n|\r|\n)[ \t]*", " ", text)
    pieces: list[tuple[bool, str]] = []  # (is a link target, text)
    at = 0
    for found in _AUTOLINK.finditer(str(text)):
        link = found.group(0)
        while link.endswith(")") and link.count(")") > link.count("("):  # "(see https://x.org)": not its ")"
            link = link[:-1]
        pieces += [(False, text[at: found.start()]), (True, link)]
        at = found.start() + len(link)
    pieces.append((False, text[at:]))
    out = []
    for is_link, piece in pieces:
        if is_link:
            out.append(md_code_span(piece))
            continue
        escaped = md_prose(piece.replace("\\", "\\\\"))
        escaped = _MD_LINK.sub(r"\\\1", escaped)
        out.append(escaped if inline else _MD_HEADING.sub(r"\1\\\2", escaped))
    return "".join(out)


def md_code_span(text: str) -> str:
    """``text`` as an inline Markdown code span (literal: no link, emphasis or HTML inside), with a backtick fence
    longer than any run of backticks in it."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * (longest + 1)
    pad = " " if text.startswith("`") or text.endswith("`") else ""
    return f"{fence}{pad}{text}{pad}{fence}"


def md_description(text: str) -> str:
    """A description from the file for Markdown: its safe ``$...$`` math as GitHub math, the rest as inert text
    (:func:`_md_inert`: no link, image, autolink, raw HTML or heading comes from it)."""
    return render_segments(description_segments(text), lambda t: _md_inert(t, inline=False), lambda m: f"$`{m}`$")


def md_cell(text: str) -> str:
    """A description for one line of Markdown, a table cell or a parenthesis: as :func:`md_description`, with
    line breaks as spaces and every ``|`` escaped (in the math too), so that it cannot end its row."""
    return render_segments(description_segments(text), lambda t: _md_inert(t, inline=True),
                           lambda m: "$`" + m.replace("|", "\\|") + "`$")


def mathml_fragment(mathml: str) -> Markup:
    """MathML printed by :class:`MechanicsMathMLPrinter` (from expressions, never from file text), unescaped."""
    return Markup(mathml)  # noqa: S704 - SymPy's printer escapes text; names are validated identifiers


def mathml_inline(mathml: str) -> Markup:
    """An expression's MathML as inline math."""
    return Markup("<math>{}</math>").format(mathml_fragment(mathml))


_UNICODE_TEX = {**{f"\\{name}": letter for name, letter in _GREEK.items()}, "\\partial": "∂", "\\cdot": "·",
                "\\times": "×", "\\le": "≤", "\\ge": "≥", "\\ne": "≠", "\\infty": "∞", "\\pm": "±"}


def _tex_to_text(tex: str) -> str:
    r"""Safe description math as readable Unicode for HTML: ``\dot{\theta}^2`` → ``θ̇²``, ``\sqrt{x}`` → ``√(x)``."""
    out = re.sub(r"\\(dot|ddot)\s*\{?\s*(\\?[A-Za-z]+)\s*\}?",
                 lambda m: m.group(2) + (_DDOT if m.group(1) == "ddot" else _DOT), tex)
    for _ in range(4):  # nested groups, innermost first
        out = re.sub(r"\\sqrt\s*\{([^{}]*)\}", r"√(\1)", out)
        out = re.sub(r"\\[dt]?frac\s*\{([^{}]*)\}\s*\{([^{}]*)\}", r"(\1)/(\2)", out)
    out = re.sub(r"\\(sin|cos|tan|cot|sec|csc|sinh|cosh|tanh|exp|log|ln|arcsin|arccos|arctan)\b\s*", r"\1 ", out)
    for command, letter in sorted(_UNICODE_TEX.items(), key=lambda kv: -len(kv[0])):
        out = re.sub(re.escape(command) + r"(?![A-Za-z])", letter, out)
    out = out.replace("\\,", "\u2009").replace("\\;", " ").replace("\\!", "").replace("\\ ", " ")
    out = re.sub(r"\^\{?(\d)\}?", lambda m: "⁰¹²³⁴⁵⁶⁷⁸⁹"[int(m.group(1))], out)
    return re.sub(r"\\[A-Za-z]+\s*", "", out).replace("{", "").replace("}", "")


def html_description(text: str) -> Markup:
    """A description for the HTML report: text escaped, its safe ``$...$`` math in italics as Unicode."""
    return Markup("").join(Markup('<i class="m">{}</i>').format(_tex_to_text(p)) if kind == "math" else escape(p)
                           for kind, p in description_segments(text))


def html_prose(text: str, symbols: Mapping[str, Sequence[str]]) -> Markup:
    """A note of the derivation for HTML: the quantities it names in italics (Unicode), the rest escaped."""
    return Markup("").join(Markup('<i class="m">{}</i>').format(uni) if kind == "math" else escape(uni)
                           for kind, _, uni in segments(text, symbols))


def symbol_table(names: dict[str, Any], note: Notation) -> dict[str, list[str]]:
    """The problem's names (and ``x_dot``, ``p_x``, ``Q_x`` of each coordinate) → [LaTeX, text] (plain data)."""
    table = {name: [note.latex(sym), note.text(sym)] for name, sym in names.items() if isinstance(sym, sympy.Symbol)}
    for name in note.coordinates:
        for extra in (f"{name}_dot", f"{name}_ddot", momentum_name(name), f"Q_{name}"):
            sym = sympy.Symbol(extra)
            table[extra] = [note.latex(sym), note.text(sym)]
    return table


FILTERS: dict[str, Callable[..., str]] = {
    "m": mathml_inline,
    "mml": mathml_fragment,
    "html_prose": html_prose,
    "html_description": html_description,
    "tex_prose": tex_prose,
    "md_math": md_math_prose,
    "tex_description": tex_description,
    "md_description": md_description,
    "md_cell": md_cell,
    "tex": tex_escape,
    "tex_lines": tex_lines,
    "boxed": boxed,
    "broken": broken,
    "formula": formula,
    "equation": equation,
    "matrix": matrix,
    "vector": vector,
    "md": md_escape,
    "md_prose": md_prose,
    "md_code": md_code,
}
