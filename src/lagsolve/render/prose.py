r"""Sentences with mathematics in them, for the reports.

Two kinds of text reach a report as prose:

* **notes of the derivation** (``"phi is cyclic: dL/dphi = 0, Q_phi = 0"``), plain ASCII
  written by lagsolve for the JSON and the terminal. :func:`segments` finds the
  quantities they name — the problem's symbols, ``dL/dq``, ``Q_i``, ``T2 - T0 + V`` —
  and gives them as math, the rest as text;
* **descriptions from the problem file**, which may hold math between ``$...$``.
  :func:`description_segments` keeps such math only when it is made of letters,
  digits, operators and a short list of harmless commands (Greek letters,
  ``\dot``, ``\frac``, ``\sin`` ...); anything else, such as ``$\input{x}$``,
  is shown as literal text.

The format filters (:func:`tex_prose`, :func:`md_prose_math`, ...) escape the text
parts and wrap the math parts for their format.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence

#: LaTeX commands a description's ``$...$`` may use
_SAFE_WORDS = (
    "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu xi pi varpi rho "
    "varrho sigma varsigma tau upsilon phi varphi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi "
    "Psi Omega dot ddot hat bar vec tilde frac tfrac dfrac sqrt sin cos tan cot sec csc arcsin arccos arctan sinh "
    "cosh tanh exp log ln partial nabla cdot times pm mp le leq ge geq ne neq approx sim equiv propto infty sum "
    "prod int oint left right mathrm mathbf boldsymbol mathcal quad qquad ldots cdots prime to rightarrow"
)
SAFE_COMMANDS = frozenset(_SAFE_WORDS.split())
_SAFE_CHARS = re.compile(r"^[A-Za-z0-9 +\-*/=()\[\]|,.;:'^_{}<>!]*$")
_COMMAND = re.compile(r"\\([A-Za-z]+|[,;! ])")

#: names every derivation uses in its notes: (LaTeX, Unicode text)
GENERIC: dict[str, Sequence[str]] = {
    "L": ("L", "L"), "T": ("T", "T"), "V": ("V", "V"), "h": ("h", "h"), "T2": ("T_2", "T₂"),
    "T0": ("T_0", "T₀"), "Q": ("Q", "Q"), "Q_i": ("Q_i", "Qᵢ"), "N": ("N", "N"), "t": ("t", "t"),
}
#: single letters that are math only next to an operator (``b != 0``), words otherwise (``a force``)
WEAK = {"a": ("a", "a"), "b": ("b", "b"), "t": ("t", "t")}

_TOKEN = re.compile(
    r"(?P<sum>sum of Q_i q_i_dot)"
    r"|(?P<rate>\bd(?P<top>[A-Za-z]\w*)/d(?P<bottom>[A-Za-z]\w*)\b)"
    r"|(?P<name>[A-Za-z][A-Za-z0-9_]*)"
    r"|(?P<number>\d+(?:\.\d+)?)"
    r"|(?P<op>\*\*|!=|<=|>=|[=+\-*/|<>^])"
    r"|(?P<space>[ ]+)"
    r"|(?P<other>.)", re.S)


def segments(text: str, symbols: Mapping[str, Sequence[str]]) -> list[tuple[str, str, str]]:
    """``text`` as (kind, LaTeX, Unicode) pieces: kind "math" for the quantities it names, else "text".

    ``symbols`` maps the problem's names (with ``x_dot``, ``p_x``, ``Q_x``) to their LaTeX and text forms.

    >>> segments("dL/dx = 0", {"x": ("x", "x")})
    [('math', '\\\\partial L/\\\\partial x = 0', '∂L/∂x = 0')]
    """
    known = {**GENERIC, **symbols}
    tokens = [(m.lastgroup or "other", m) for m in _TOKEN.finditer(str(text))]
    out: list[tuple[str, str, str]] = []
    run: list[tuple[str, str, str, str]] = []  # (kind, tex, text, source) of the tokens of a candidate run

    def flush() -> None:
        tail = []
        while run and run[-1][0] == "space":
            tail.append(run.pop())
        strong = any(k in ("name", "sum", "rate") for k, _, _, _ in run)
        operator = any(k == "op" for k, _, _, _ in run)
        names = any(k in ("name", "weak", "sum", "rate") for k, _, _, _ in run)
        if run and (strong or operator) and names and (run[-1][0] != "op" or run[-1][3] == "|") and _balanced(run):
            out.append(("math", "".join(t for _, t, _, _ in run).strip(), "".join(u for _, _, u, _ in run).strip()))
        else:
            for *_, source in run:
                _text(out, source)
        for *_, source in tail:
            _text(out, source)
        run.clear()

    for k, (kind, m) in enumerate(tokens):
        word = m.group(0)
        if kind == "sum":
            run.append(("sum", r"\sum_i Q_i\,\dot q_i", "Σ Qᵢ q̇ᵢ", word))
        elif kind == "rate" and m.group("top") in known and m.group("bottom") in known:
            top, bottom = known[m.group("top")], known[m.group("bottom")]
            d, dd = (r"\partial ", "∂") if m.group("top") == "L" else ("d", "d")
            run.append(("rate", f"{d}{top[0]}/{d}{bottom[0]}", f"{dd}{top[1]}/{dd}{bottom[1]}", word))
        elif kind == "name" and word in known and word not in WEAK:
            run.append(("name", known[word][0], known[word][1], word))
        elif kind == "name" and word in WEAK:
            run.append(("weak", WEAK[word][0], WEAK[word][1], word))
        elif kind == "number" and (run or _next_is_op(tokens, k)):
            run.append(("number", word, word, word))
        elif kind == "op" and (run or word in "|-"):
            tex = {"**": "^", "!=": r"\neq", "<=": r"\le", ">=": r"\ge", "*": r"\,"}.get(word, word)
            uni = {"**": "^", "!=": "≠", "<=": "≤", ">=": "≥", "*": "·"}.get(word, word)
            run.append(("op", tex, uni, word))
        elif kind == "space" and run:
            run.append(("space", " ", " ", word))
        else:
            flush()
            _text(out, word)
    flush()
    return _exponents(out)


def _next_is_op(tokens: list[tuple[str, re.Match[str]]], k: int) -> bool:
    for kind, m in tokens[k + 1:]:
        if kind != "space":
            return kind == "op" and m.group(0) != "-"
    return False


def _balanced(run: list[tuple[str, str, str, str]]) -> bool:
    """Absolute-value bars come in pairs."""
    return sum(1 for kind, _, _, source in run if kind == "op" and source == "|") % 2 == 0


def _exponents(out: list[tuple[str, str, str]]) -> list[tuple[str, str, str]]:
    r"""``x^2`` (from ``x**2``) → ``x^{2}`` in the LaTeX of each math piece."""
    return [(k, re.sub(r"\^\s*(\d+)", r"^{\1}", tex) if k == "math" else tex, u) for k, tex, u in out]


def _text(out: list[tuple[str, str, str]], text: str) -> None:
    if out and out[-1][0] == "text":
        out[-1] = ("text", out[-1][1] + text, out[-1][2] + text)
    else:
        out.append(("text", text, text))


def description_segments(text: str) -> list[tuple[str, str]]:
    r"""A description as ("text", ...) and ("math", LaTeX) pieces; unsafe ``$...$`` stays literal text.

    >>> description_segments(r"angle $\theta$ from $\input{x}$")
    [('text', 'angle '), ('math', '\\theta'), ('text', ' from $\\input{x}$')]
    """
    out: list[tuple[str, str]] = []
    parts = re.split(r"(?<!\\)\$", str(text))
    if len(parts) % 2 == 0:  # an unpaired $: no math at all
        return [("text", str(text))]
    for k, part in enumerate(parts):
        if k % 2 and part.strip() and safe_math(part):
            out.append(("math", part.strip()))
        else:
            piece = f"${part}$" if k % 2 else part
            if out and out[-1][0] == "text":
                out[-1] = ("text", out[-1][1] + piece)
            elif piece:
                out.append(("text", piece))
    return out


def safe_math(tex: str) -> bool:
    """Only letters, digits, operators, balanced braces and the commands of :data:`SAFE_COMMANDS`, put together so
    that TeX accepts them (:func:`_well_formed`: ``$\\frac{a}$`` or ``$x_1_2$`` would stop pdflatex)."""
    body = _COMMAND.sub(lambda m: "" if m.group(1) in SAFE_COMMANDS or not m.group(1).isalpha() else "\0", tex)
    if "\0" in body or "\\" in body or not _SAFE_CHARS.match(body):
        return False
    depth = 0
    for ch in body:
        depth += {"{": 1, "}": -1}.get(ch, 0)
        if depth < 0:
            return False
    return depth == 0 and _well_formed(tex)


#: the arguments each safe command takes (the others take none); ``\sqrt`` may have ``[n]`` first
_ARGUMENTS = {"frac": 2, "tfrac": 2, "dfrac": 2, "dot": 1, "ddot": 1, "hat": 1, "bar": 1, "vec": 1, "tilde": 1,
              "sqrt": 1, "mathrm": 1, "mathbf": 1, "boldsymbol": 1, "mathcal": 1}
_DELIMITERS = frozenset("()[]|./<>")
_MATH_TOKEN = re.compile(r"\\([A-Za-z]+|[,;! ])|(\s+)|(.)")


def _well_formed(tex: str) -> bool:
    """Whether TeX takes ``tex`` (made of safe pieces) as math: each command has its arguments, ``^`` and ``_``
    theirs and at most one each per atom (primes are its superscript, and may only be followed by ``^``),
    ``\\left`` and ``\\right`` pair up within a group, each with a delimiter."""
    tokens = [("cmd", m.group(1)) if m.group(1) else ("char", m.group(3))
              for m in _MATH_TOKEN.finditer(tex) if not m.group(2)]
    position = 0

    def take() -> tuple[str, str] | None:
        nonlocal position
        position += 1
        return tokens[position - 1] if position <= len(tokens) else None

    def argument() -> bool:
        token = take()
        if token is None:
            return False
        kind, value = token
        if kind == "cmd":
            return value not in _ARGUMENTS and value not in ("left", "right")
        return group("}") if value == "{" else value not in "}^_'"

    def command(value: str) -> bool:
        if value in ("left", "right"):
            token = take()
            return token is not None and token[0] == "char" and token[1] in _DELIMITERS
        if value == "sqrt" and position < len(tokens) and tokens[position] == ("char", "["):
            take()
            if not group("]"):
                return False
        return all(argument() for _ in range(_ARGUMENTS.get(value, 0)))

    def group(closing: str | None) -> bool:
        lefts, sup, sub, primed = 0, False, False, False
        while (token := take()) is not None:
            kind, value = token
            if kind == "char" and value == closing:
                return lefts == 0
            if kind == "char" and value in "^_'":
                if value == "_" and sub or value != "_" and sup and not primed:
                    return False
                sub, sup, primed = sub or value == "_", sup or value != "_", value == "'"
                if value != "'" and not argument():
                    return False
                continue
            sup = sub = primed = False  # a new atom
            if kind == "char" and value == "}" or kind == "char" and value == "{" and not group("}"):
                return False
            if kind == "cmd":
                lefts += {"left": 1, "right": -1}.get(value, 0)
                if lefts < 0 or not command(value):
                    return False
        return closing is None and lefts == 0

    return group(None)


def render_segments(pieces: list[tuple[str, str]], text: Callable[[str], str], math: Callable[[str], str]) -> str:
    """Join pieces, each text part through ``text`` and each math part through ``math``."""
    return "".join(math(p) if kind == "math" else text(p) for kind, p in pieces)
