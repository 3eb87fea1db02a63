r"""``expected: normal_modes:`` against the derivation: an equilibrium of several coordinates and its small
oscillations (``lagsolve check``).

For each expected item:

* **at**: the equilibrium lagsolve lists at the same place (each value equal, an angle up to a multiple of
  :math:`2\pi`; a value given numerically at the simulation values compared there, to 1e-6). When none is,
  the expected point is put into the equations at rest, :math:`F(q, 0)`: not zero there is a mismatch (*not an
  equilibrium*); zero there is a mismatch too when lagsolve's list is complete, and *not checked* when it may
  miss equilibria (found without a general solve).
* **stable**: lagsolve's verdict there.
* **squared_frequencies**: as a list in any order; each expected :math:`\omega^2` must equal a different one of
  lagsolve's, symbolically or at random states as other answers are (numerically at the simulation values when
  lagsolve's are numeric). A list that leaves out a non-zero one of lagsolve's is a warning (*incomplete*).
* **shapes**: each expected shape u (paired with its :math:`\omega^2`) must be one of lagsolve's shapes for that
  :math:`\omega^2` up to a non-zero factor (for a repeated :math:`\omega^2`, lie in their span): every 2 × 2 minor
  of the two vectors is zero, symbolically or at random parameter values.
"""

from __future__ import annotations

import random
from typing import TYPE_CHECKING, Any, Protocol

import sympy

from lagsolve.check.verdicts import (
    ABSENT,
    DIFFERS,
    INCOMPLETE,
    MISMATCH,
    NOT_DERIVED,
    NUMERIC,
    OK,
    SAME,
    SYMBOLIC,
    UNCHECKED,
    WARNING,
    Item,
    Verdict,
    symbolically_equal,
)

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.linearize import Mode
    from lagsolve.mechanics.derivation import Derivation

#: reason of a comparison made at the simulation values (lagsolve's result there is numeric)
AT_VALUES = "at the simulation values"
#: reason of an expected equilibrium where F(q, 0) is not zero
NOT_EQUILIBRIUM = "not an equilibrium"

QUANTITY = "normal_modes"
TOLERANCE = 1e-6


class Comparer(Protocol):
    """What these verdicts need of :class:`lagsolve.check.compare._Checker`: one comparison, made."""

    def verdict(self, item: Item) -> Verdict: ...


def mode_verdicts(checker: Comparer, derivation: Derivation) -> list[Verdict]:
    """The verdicts on every item of ``expected.normal_modes``, in order."""
    expected = derivation.problem.expected.normal_modes
    if not expected:
        return []
    analysis = derivation.analysis
    linear = analysis.linearization if analysis is not None else None
    out: list[Verdict] = []
    for i, spec in enumerate(expected):
        label = f"{QUANTITY}[{i}]"
        at = tuple(spec.at.values())
        if linear is None:
            note = (analysis.linearization_note if analysis is not None else "") or "no analysis"
            out.append(Verdict(QUANTITY, f"{label}.at", UNCHECKED, NOT_DERIVED, at,
                               note=f"lagsolve gives no equilibria of several coordinates here: {note}"))
            continue
        context = _Context(checker, derivation)
        match = next((m for m in linear.modes if context.same_point(spec.at, m)), None)
        if match is None:
            out.append(context.absent(spec.at, label, linear.modes, linear.complete))
            continue
        out.append(Verdict(QUANTITY, f"{label}.at", OK, context.how(match), at,
                           tuple(v for _, v in match.point)))
        if spec.stable is not None:
            out.append(_stable(spec.stable, match, label))
        if spec.squared_frequencies is not None:
            out += context.frequencies(spec.squared_frequencies, spec.shapes, match, label)
    return out


def _stable(expected: bool, mode: Mode, label: str) -> Verdict:
    flag = (sympy.true if expected else sympy.false,)
    if mode.stable is None:
        return Verdict(QUANTITY, f"{label}.stable", UNCHECKED, NOT_DERIVED, flag,
                       note="lagsolve does not decide the stability of this equilibrium")
    same = mode.stable == expected
    return Verdict(QUANTITY, f"{label}.stable", OK if same else MISMATCH, SAME if same else DIFFERS, flag,
                   (sympy.true if mode.stable else sympy.false,))


def _left_out(squares: tuple[Any, ...], derived: tuple[Any, ...], used: set[int], label: str) -> list[Verdict]:
    """A warning when every expected ω² is one of lagsolve's but some non-zero ones of lagsolve's are not
    expected: the list is true as far as it goes, and incomplete (a zero ω², a free direction, may be left out)."""
    nonzero = [j for j, d in enumerate(derived) if not (d == 0 or getattr(d, "is_zero", False))]
    missing = [derived[j] for j in nonzero if j not in used]
    if not missing or len(used) < len(squares):
        return []
    shown = ", ".join(str(d) for d in missing)
    listed = len(used & set(nonzero))  # a zero ω² listed is no non-zero one of lagsolve's
    return [Verdict(QUANTITY, f"{label}.squared_frequencies", WARNING, INCOMPLETE, squares, tuple(missing),
                    note=f"lists {listed} of lagsolve's {len(nonzero)} non-zero squared frequencies "
                         f"here; it leaves out {shown}")]


def _numeric(values: Any) -> bool:
    """Whether ``values`` (lagsolve's) are floating-point numbers, found or evaluated at the simulation values."""
    return any(isinstance(v, sympy.Float) for v in values)


class _Context:
    """What the comparisons of one derivation share: its names, the simulation values, the periodic coordinates."""

    def __init__(self, checker: Comparer, derivation: Derivation) -> None:
        from lagsolve.mechanics.analysis.numeric_equilibria import periodic

        self.checker = checker
        self.derivation = derivation
        problem = derivation.problem
        self.by_name = {c.name: c.symbol for c in problem.coordinates}
        spec = problem.simulation
        self.values = dict(spec.values) if spec is not None else {}
        system = derivation.analysis.system
        coordinates = list(system.model.coordinates)
        flags = periodic([system.model.lagrangian, *system.generalized_forces], coordinates)
        self.periodic = {q.name for q, flag in zip(coordinates, flags, strict=True) if flag}

    # -- numbers

    def at_values(self, expr: Any) -> complex | None:
        """``expr`` at the simulation values (None when a symbol has none)."""
        numbers = {s: sympy.Float(self.values[s.name]) for s in expr.free_symbols if s.name in self.values}
        value = expr.xreplace(numbers)
        if value.free_symbols:
            return None
        try:
            return complex(value)
        except TypeError:
            return None

    def close(self, expected: Any, derived: Any, angle: bool = False) -> bool:
        """``expected`` (at the simulation values) equals the number ``derived`` to :data:`TOLERANCE`."""
        e, d = self.at_values(expected), self.at_values(derived)
        if e is None or d is None or abs(e.imag) > TOLERANCE:
            return False
        gap = e.real - d.real
        if angle:
            gap = (gap + float(sympy.pi)) % (2 * float(sympy.pi)) - float(sympy.pi)
        return abs(gap) <= TOLERANCE * max(1.0, abs(d.real))

    # -- the equilibrium

    def same_point(self, at: Any, mode: Mode) -> bool:
        """``mode`` is at ``at``: the same coordinates determined, each value equal (an angle modulo 2π)."""
        point = {q.name: v for q, v in mode.point}
        if set(point) != set(at):
            return False
        numeric = _numeric(point.values())
        for name, e in at.items():
            d, angle = point[name], name in self.periodic
            if numeric:
                if not self.close(e, d, angle):
                    return False
            elif not (symbolically_equal(e, d) or (angle and _turns(e - d))):
                return False
        return True

    def how(self, mode: Mode) -> str:
        return AT_VALUES if _numeric(v for _, v in mode.point) else SYMBOLIC

    def absent(self, at: Any, label: str, modes: tuple[Mode, ...], complete: bool) -> Verdict:
        """The verdict when no equilibrium lagsolve lists is at ``at``."""
        from lagsolve.mechanics.equations.lagrange import lagrange_terms
        from lagsolve.mechanics.symbolic.identities import proved_zero

        expected = tuple(at.values())
        found = "; ".join(", ".join(f"{q.name} = {v}" for q, v in m.point) or "anywhere" for m in modes) or "none"
        system = self.derivation.analysis.system
        terms = lagrange_terms(system.model, (), system.generalized_forces, engine="symengine")
        rest = dict.fromkeys(system.model.velocities, 0)
        point = {self.by_name[name]: value for name, value in at.items()}
        at_rest = [f.xreplace(rest) for f in terms.forcing]
        if not all(proved_zero(f.xreplace(point)) or self.rounding(f, point) for f in at_rest):
            return Verdict(QUANTITY, f"{label}.at", MISMATCH, NOT_EQUILIBRIUM, expected,
                           note=f"F(q, 0) is not zero there, so it is no equilibrium (lagsolve finds: {found})")
        if complete:
            return Verdict(QUANTITY, f"{label}.at", MISMATCH, ABSENT, expected,
                           note=f"an equilibrium, but lagsolve lists none there (it finds: {found})")
        return Verdict(QUANTITY, f"{label}.at", UNCHECKED, NOT_DERIVED, expected,
                       note=f"F(q, 0) = 0 there, but lagsolve does not list this equilibrium (it finds: {found}; "
                            "its list may not be complete)")

    def rounding(self, force: Any, point: dict[Any, Any]) -> bool:
        """A component of F(q, 0) that is zero at a ``point`` given to the digits of a float (y =
        0.7390851332151607, the root of y = cos y, which the file's reader keeps as that exact decimal), at the
        simulation values, up to the rounding of its terms (1e-9 of their size, each term evaluated there)."""
        value = self.at_values(force.xreplace(point))
        terms = [sympy.Abs(t.xreplace(point)) for t in sympy.Add.make_args(sympy.expand(force))]
        size = self.at_values(sympy.Add(*terms))
        return value is not None and size is not None and abs(value) <= 1e-9 * abs(size)

    # -- the normal modes

    def frequencies(self, squares: tuple[Any, ...], shapes: tuple[tuple[Any, ...], ...] | None, mode: Mode,
                    label: str) -> list[Verdict]:
        """Each expected ω² matched with a different one of ``mode``'s, then each shape with that ω²'s shapes."""
        derived = mode.squared_frequencies
        if derived is None:
            note = mode.note or "lagsolve gives no squared frequencies here"
            return [Verdict(QUANTITY, f"{label}.squared_frequencies[{k}]", UNCHECKED, NOT_DERIVED, (e,), note=note)
                    for k, e in enumerate(squares)]
        out: list[Verdict] = []
        used: set[int] = set()
        for k, e in enumerate(squares):
            name = f"{label}.squared_frequencies[{k}]"
            j, verdict = self.match(e, derived, used, name, _numeric(derived))
            if j is None or verdict is None:
                shown = ", ".join(str(d) for d in derived)
                again, _ = self.match(e, derived, set(), name, _numeric(derived)) if used else (None, None)
                note = (f"it equals {derived[again]}, which an earlier item matched already: lagsolve has it once "
                        f"({shown})" if again is not None else
                        f"none of lagsolve's squared frequencies here equals it ({shown})")
                out.append(Verdict(QUANTITY, name, MISMATCH, ABSENT, (e,), note=note))
                if shapes is not None:
                    out.append(Verdict(QUANTITY, f"{label}.shapes[{k}]", UNCHECKED, NOT_DERIVED, shapes[k],
                                       note="its squared frequency is none of lagsolve's"))
                continue
            used.add(j)
            out.append(verdict)
            if shapes is not None:
                out.append(self.shape(shapes[k], mode, derived[j], f"{label}.shapes[{k}]"))
        return out + _left_out(squares, derived, used, label)

    def match(self, e: Any, derived: tuple[Any, ...], used: set[int], name: str,
              numeric: bool) -> tuple[int | None, Verdict | None]:
        for j, d in enumerate(derived):
            if j in used:
                continue
            if numeric:
                if self.close(e, d):
                    return j, Verdict(QUANTITY, name, OK, AT_VALUES, (e,), (d,))
                continue
            verdict = self.checker.verdict(Item(QUANTITY, name, (e,), (d,), real=False))
            if verdict.status == OK:
                return j, verdict
        return None, None

    def shape(self, e: tuple[Any, ...], mode: Mode, square: Any, name: str) -> Verdict:
        """The expected shape ``e`` is in the span of ``mode``'s shapes for the ω² ``square``."""
        if mode.shapes is None:
            return Verdict(QUANTITY, name, UNCHECKED, NOT_DERIVED, e, note="lagsolve gives no mode shapes here")
        if all(x == 0 for x in e):
            return Verdict(QUANTITY, name, MISMATCH, DIFFERS, e, note="a mode shape is never zero")
        derived = mode.squared_frequencies or ()
        basis = [u for u, w in zip(mode.shapes, derived, strict=True) if w == square]
        numeric = _numeric(x for u in basis for x in u)
        if len(basis) == 1 and all(symbolically_equal(a * y, b * x) for (a, b), (x, y) in _pairs(e, basis[0])):
            return Verdict(QUANTITY, name, OK, SYMBOLIC, e, basis[0])
        inside = self.in_span(e, basis, numeric)
        if inside is None:
            return Verdict(QUANTITY, name, UNCHECKED, NOT_DERIVED, e, note="could not be evaluated")
        shown = basis[0] if len(basis) == 1 else None
        if inside:
            return Verdict(QUANTITY, name, OK, AT_VALUES if numeric else NUMERIC, e, shown)
        return Verdict(QUANTITY, name, MISMATCH, DIFFERS, e, shown,
                       note="not a multiple of lagsolve's shape for this squared frequency")

    def in_span(self, e: tuple[Any, ...], basis: list[tuple[Any, ...]], numeric: bool) -> bool | None:
        """``e`` lies in the span of ``basis``: at the simulation values when lagsolve's are numeric, else at random
        values of the parameters (positive unless declared otherwise)."""
        import numpy as np

        draws = [self.values] if numeric else self.draws()
        for values in draws:
            numbers = {s: sympy.Float(values[s.name]) for v in (e, *basis) for x in v for s in x.free_symbols
                       if s.name in values}
            try:
                rows = np.array([[complex(x.xreplace(numbers)) for x in v] for v in (*basis, e)])
            except TypeError:
                return None
            if np.max(np.abs(rows.imag)) > TOLERANCE:
                return False
            rank = np.linalg.matrix_rank(rows.real, tol=TOLERANCE * max(1.0, float(np.max(np.abs(rows)))))
            if rank > len(basis):
                return False
        return True

    def draws(self, count: int = 6, seed: int = 7) -> list[dict[str, float]]:
        rng = random.Random(seed)
        parameters = self.derivation.problem.parameters
        return [{p.name: rng.uniform(0.5, 2.5) if p.symbol.is_positive else rng.uniform(-2.0, 2.0)
                 for p in parameters} for _ in range(count)]


def _turns(difference: Any) -> bool:
    """``difference`` is a whole number of turns, 2πk."""
    from lagsolve.mechanics.symbolic.simplify import tidy

    turns = tidy(difference / (2 * sympy.pi))
    return bool(turns.is_Integer)


def _pairs(e: tuple[Any, ...], d: tuple[Any, ...]) -> list[tuple[tuple[Any, Any], tuple[Any, Any]]]:
    """Each pair of components (i < j) of ``e`` and of ``d``: ``e`` ∥ ``d`` when e_i d_j = e_j d_i for all."""
    n = len(e)
    return [((e[i], e[j]), (d[i], d[j])) for i in range(n) for j in range(i + 1, n)]
