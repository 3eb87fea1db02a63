"""The ``lagsolve check`` table: one line per expected quantity, ✓ ok, ! warning, ✗ mismatch, – not checked.

For a warning or a mismatch the table adds both expressions (plain text with dots and primes,
see :class:`~lagsolve.render.notation.Notation`) and a state where they differ.
"""

from __future__ import annotations

import unicodedata
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.check.status import Status
from lagsolve.problem.names import momentum_name
from lagsolve.render.notation import Notation

if TYPE_CHECKING:
    from lagsolve.check.compare import CheckReport, Verdict, Witness

MARKS = {Status.OK: "✓", Status.WARNING: "!", Status.MISMATCH: "✗", Status.UNCHECKED: "–"}


def check_table(report: CheckReport) -> str:
    """The verdicts of ``report`` as an aligned text table, with a closing count."""
    note = Notation(report.coordinates)
    lines = [f"{report.name} ({report.source})"]
    if not report.verdicts:
        lines.append("  no expected answers to check")
        return "\n".join(lines) + "\n"
    labels = [label(v, note, report.coordinates) for v in report.verdicts]
    width = max(_width(text) for text in labels)
    for verdict, text in zip(report.verdicts, labels, strict=True):
        pad = " " * (width - _width(text))
        lines.append(f"  {MARKS[verdict.status]} {text}{pad}  {describe(verdict, note)}")
        if verdict.status in (Status.WARNING, Status.MISMATCH) and verdict.derived is not None:
            lines.append(f"      expected: {_components(verdict.expected, note)}")
            lines.append(f"      derived:  {_components(verdict.derived, note)}")
            if verdict.witness is not None:
                lines.append(f"      differ at {_state(verdict.witness, note)}")
        elif verdict.status == Status.MISMATCH and verdict.witness is not None:  # a claimed constant that changes
            lines.append(f"      claimed: {_components(verdict.expected, note)}")
            lines.append(f"      dC/dt ≠ 0 at {_state(verdict.witness, note, rate=True)}")
    counts = [(report.count(Status.OK), "ok"), (report.count(Status.WARNING), "warning"),
              (report.count(Status.MISMATCH), "mismatch"), (report.count(Status.UNCHECKED), "not checked")]
    parts = [f"{n} {_plural(word, n)}" for n, word in counts if n]
    lines.append("  " + ", ".join(parts))
    return "\n".join(lines) + "\n"


def label(verdict: Verdict, note: Notation, coordinates: tuple[str, ...] = ()) -> str:
    """``ẍ``, ``λ_wire``, ``|F_wire|``, ``F_wire``, ``ẍ (reduced)``, ``p_θ``, ``V_eff``, ``equilibrium 1 …``."""
    name = verdict.name
    if verdict.quantity == "accelerations":
        return note.text(sympy.Symbol(f"{name}_ddot"))
    if verdict.quantity == "reduced":
        return note.text(sympy.Symbol(f"{name}_ddot")) + " (reduced)"
    if verdict.quantity == "multipliers":
        return note.text(sympy.Symbol(f"lambda_{name}"))
    if verdict.quantity == "constraint_forces":
        if name.endswith(".vector"):
            return f"F_{name[:-len('.vector')]}"
        return f"|F_{name}|"
    if verdict.quantity == "conserved" and name.endswith(".poisson_bracket"):
        import dataclasses

        inner = dataclasses.replace(verdict, name=name.removesuffix(".poisson_bracket"))
        return "{" + label(inner, note, coordinates) + ", H}"
    if verdict.quantity == "conserved":
        conjugate = next((q for q in coordinates if momentum_name(q) == name), None)
        if conjugate is not None:
            return momentum_name(note.text(sympy.Symbol(conjugate)))
        return note.text(sympy.Symbol(name))
    if verdict.quantity == "steady_motions":
        return {"values": "steady rates", "frequency": "steady ω²", "stable": "steady stability"}.get(name, name)
    if name == "expression":
        return "V_eff"
    if verdict.quantity == "normal_modes":
        index, _, part = name.partition("].")
        what, _, k = part.partition("[")
        words = {"squared_frequencies": "ω²", "shapes": "shape"}
        return f"modes {int(index.split('[')[1]) + 1}: {words.get(what, what)}" + (f" {int(k[:-1]) + 1}" if k else "")
    index, _, part = name.partition("].")
    number = int(index.split("[")[1]) + 1
    return f"equilibrium {number}: {part}"


def describe(verdict: Verdict, note: Notation) -> str:
    """The verdict in words."""
    for words in (_agreement, _relation, _conservation, _disagreement):
        text = words(verdict, note)
        if text is not None:
            return text
    prefix = {Status.MISMATCH: "mismatch: ", Status.WARNING: "warning: "}.get(verdict.status, "")
    return prefix + verdict.note


def _agreement(verdict: Verdict, note: Notation) -> str | None:
    """How the expression was found equal: symbolically, at random states, identically, at the simulation
    values (None: another reason)."""
    from lagsolve.check import compare as c

    reason = verdict.reason
    if reason == c.SYMBOLIC:
        return "ok (symbolic)" if verdict.status == "ok" else "differs"
    if reason == c.NUMERIC:
        return f"ok (numeric, {verdict.states} states on the constraint surface)"
    if reason == c.SAME:
        return "ok"
    if reason == "at the simulation values":  # check.modes.AT_VALUES
        return "ok (numeric, at the simulation values)" if verdict.status == Status.OK else "mismatch"
    return None


def _relation(verdict: Verdict, note: Notation) -> str | None:
    """How expected and derived are related when they differ by a sign convention, a sign, a factor or a
    constant (None: another reason)."""
    from lagsolve.check import compare as c

    reason = verdict.reason
    if reason == c.CONVENTION:
        if verdict.factor == -1:
            return "mismatch: λ with the opposite sign convention (expected = −derived; otherwise it agrees)"
        return (f"mismatch: λ with the opposite sign convention and a factor {note.text(-verdict.factor)} "
                f"(expected = {_times(verdict.factor, note)})")
    if reason == c.OPPOSITE_SIGN:
        return "mismatch: opposite sign (expected = −derived)"
    if reason == c.FACTOR:
        if verdict.factor is None:
            return "mismatch: off by a factor that depends only on the parameters"
        return f"mismatch: {_factor_words(verdict.factor, note)} (expected = {_times(verdict.factor, note)})"
    if reason == c.OFFSET:
        shown = "a constant" if verdict.offset is None else note.text(verdict.offset)
        if verdict.status == "ok":
            return f"ok up to an additive constant (expected = derived + {shown}; the zero level is free)"
        return f"mismatch: differs by a constant (expected = derived + {shown})"
    return None


def _conservation(verdict: Verdict, note: Notation) -> str | None:
    """Whether a claimed constant of the motion is one: by its Poisson bracket with H or its rate along the
    equations of motion (None: another reason)."""
    from lagsolve.check import compare as c

    reason = verdict.reason
    if reason == c.BRACKET:
        where = "symbolically" if not verdict.states else f"numerically, at {verdict.states} random points"
        return f"ok (conserved: {{C, H}} + ∂C/∂t = 0, {where})"
    if reason == c.NOT_BRACKET:
        rate = note.text(verdict.derived[0]) if verdict.derived else "?"
        return f"mismatch: not conserved, {{C, H}} + ∂C/∂t = {rate} ≠ 0"
    if reason == c.CONSERVED:
        where = f"at {verdict.states} states on the constraint surface" if verdict.states else "symbolically"
        return f"ok (conserved: dC/dt = 0 along the equations of motion, {where})"
    if reason == c.TRIVIAL:
        return "warning: trivially constant, " + verdict.note
    if reason == c.NOT_CONSERVED:
        return (f"mismatch: not conserved, dC/dt ≠ 0 along the equations of motion at "
                f"{verdict.states - verdict.agreeing} of {verdict.states} states")
    return None


def _disagreement(verdict: Verdict, note: Notation) -> str | None:
    """Where expected and derived disagree: at some states only, where one is undefined, or anywhere (None:
    another reason)."""
    from lagsolve.check import compare as c

    reason = verdict.reason
    if reason == c.SIGN_DEPENDENT:
        where = note.text(verdict.condition) if verdict.condition is not None else "some states"
        return (f"warning: holds only where {where} (agrees at {verdict.agreeing} of {verdict.states} states, "
                "opposite sign at the others; a magnitude needs Abs)")
    if reason == c.UNDEFINED:
        return "mismatch: " + verdict.note
    if reason == c.DIFFERS:
        if verdict.states:
            return f"mismatch: differs at {verdict.states - verdict.agreeing} of {verdict.states} states"
        return "mismatch: differs"
    return None


def _factor_words(factor: Any, note: Notation) -> str:
    sign = "opposite sign and " if factor.is_negative else ""
    size = -factor if factor.is_negative else factor
    numerator, denominator = sympy.fraction(size)
    if numerator == 1:
        return f"{sign}a missing factor {note.text(denominator)}"
    return f"{sign}an extra factor {note.text(size)}"


def _times(factor: Any, note: Notation) -> str:
    if factor == -1:
        return "−derived"
    numerator, denominator = sympy.fraction(factor)
    if numerator == 1:
        return f"derived/{_grouped(denominator, note)}"
    if numerator == -1:
        return f"−derived/{_grouped(denominator, note)}"
    return f"{_grouped(factor, note)}·derived"


def _grouped(expr: Any, note: Notation) -> str:
    text = note.text(expr)
    return f"({text})" if (expr.is_Add or expr.is_Mul) else text


def _components(exprs: tuple[Any, ...], note: Notation) -> str:
    if len(exprs) == 1:
        return note.text(exprs[0])
    return "[" + ", ".join(note.text(e) for e in exprs) + "]"


def _number(value: complex | None) -> str:
    if value is None:
        return "undefined"
    if abs(value.imag) <= 1e-12 * max(1.0, abs(value.real)):
        return f"{value.real:.6g}"
    return f"{value.real:.6g}{value.imag:+.6g}i"


def _state(witness: Witness, note: Notation, *, rate: bool = False) -> str:
    values = [f"{note.text(sympy.Symbol(name))} = {value:.4g}" for name, value in witness.values]
    for name, lam in witness.functions:
        variables = lam.variables
        if len(variables) == 1:
            u = sympy.Symbol("u")
            body = lam.expr.xreplace({variables[0]: u})
            values.append(f"{name}(u) = {note.text(body)}")
        else:
            values.append(f"{name}({', '.join(map(str, variables))}) = {note.text(lam.expr)}")
    expected = ", ".join(_number(v) for v in witness.expected)
    if rate:
        return f"{', '.join(values)}: dC/dt = {expected}"
    derived = ", ".join(_number(v) for v in witness.derived)
    return f"{', '.join(values)}: expected {expected}, derived {derived}"


def _width(text: str) -> int:
    """Columns ``text`` takes in a terminal: combining marks (the dots of ẍ) take none."""
    return sum(0 if unicodedata.combining(ch) else 1 for ch in text)


def _plural(word: str, n: int) -> str:
    if n == 1 or word in ("ok", "not checked"):
        return word
    return {"mismatch": "mismatches"}.get(word, word + "s")
