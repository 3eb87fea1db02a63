r"""Numeric comparisons for grading a class: one set of random states per key, each expression compiled once.

``lagsolve check`` compares one problem's answers with one derivation; grading compares hundreds of
students' answers with the same key, so here the states (:class:`lagsolve.check.states.StateSpace`, the
same random consistent states as check's) are drawn once per key, and an expression's values at them are
computed once, whoever wrote it (a dict keyed by the prepared SymPy expression). The key's answers, the
answers a known mistake would give, and the answers that follow from a student's own Lagrangian are all
compiled once per class.

:func:`relation` tells how a student's values E relate to the reference's D at the shared states, in the
order ``lagsolve check`` does (:meth:`lagsolve.check.compare.Comparer.numeric`): the same, the opposite
sign, the same only where a quantity is positive, a constant factor, a constant offset, or different.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import mpmath
import sympy

from lagsolve.check.diagnose import close
from lagsolve.check.states import Compiled, State, StateSpace, describe
from lagsolve.mechanics.derivation import Derivation

#: the number of states (check's own) and the fewest at which both sides must be real to judge
STATES, MINIMUM_STATES = 24, 8

SAME, OPPOSITE, SIGN_DEPENDENT, FACTOR, OFFSET, DIFFERS, UNDECIDED = (
    "same", "opposite", "sign_dependent", "factor", "offset", "differs", "undecided")

Values = tuple[Any, ...]


class _Quick(Compiled):
    """:class:`~lagsolve.check.states.Compiled` without renaming every symbol to a dummy first (the symbols
    of a problem are plain identifiers; lambdify still renames any that is not): the renaming is most of
    the time lambdify takes."""

    def __init__(self, expr: Any, space: StateSpace) -> None:
        self.expr = expr
        concrete = space.concrete(expr)
        self.symbols = tuple(sorted(concrete.free_symbols, key=sympy.default_sort_key))
        undefined = concrete.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo)
        self._fn = None if undefined else sympy.lambdify(self.symbols, concrete, modules="mpmath", dummify=False)


@dataclass(frozen=True)
class Relation:
    """How E relates to D: ``kind`` (one of the names above), the rows (state, E, D) where D is real, and a
    state where they differ (``witness``)."""

    kind: str
    rows: tuple[tuple[State, list[Any], list[Any]], ...] = ()
    witness: State | None = None


class Evaluator:
    """The values of expressions at one key's shared states.

    ``prepare`` turns an expression into what is compiled (the constraints used, the derived multipliers
    put in, ...); ``extra`` lists the symbols other than the problem's that get random values: like the
    parameters, one value per group of states, unless ``varying`` (the unknowns of an equation: accelerations,
    multipliers, normal forces), when each state has its own. A ratio constant in a group then depends on the
    parameters only, never on those unknowns: ``m2*z_ddot + m2*g + lambda`` is not ``m2*z_ddot - m2*g + lambda``
    times a constant, although both are the same at every state of a group when the unknowns are per group.
    """

    def __init__(self, derivation: Derivation, extra: Iterable[Any], seed: int,
                 prepare: Callable[[Any], Any], *, varying: bool = False) -> None:
        self.derivation = derivation
        self.space = StateSpace(derivation, extra, seed)
        self.states = self.space.states(STATES)
        if varying and self.space.extra:
            rng = random.Random(f"lagsolve-grade-{seed}")  # a str seed: the same whatever PYTHONHASHSEED
            self.states = [replace(state, values={**state.values, **{s: mpmath.mpf(rng.uniform(-2.0, 2.0))
                                                                     for s in self.space.extra}})
                           for state in self.states]
        self.prepare = prepare
        model = derivation.model
        coefficients: set[Any] = set()
        for _, symbols in self.space._functions.values():  # noqa: SLF001 - the random functions' coefficients
            coefficients |= set(symbols)
        self.known = {self.space.time, *self.space.parameters, *self.space.extra, *model.coordinates,
                      *model.velocities, *coefficients}
        self._values: dict[Any, Values | None] = {}

    def values(self, expr: Any) -> Values | None:
        """``expr``'s value at each state (None where undefined), or None when it cannot be evaluated."""
        try:
            prepared = self.prepare(expr)
        except (TypeError, ValueError, AttributeError):
            return None
        if prepared in self._values:
            return self._values[prepared]
        out: Values | None = None
        try:
            compiled = _Quick(prepared, self.space)
            if set(compiled.symbols) <= self.known:
                out = tuple(compiled(s) for s in self.states)
        except (TypeError, ValueError, AttributeError, SyntaxError, NameError, RecursionError):
            out = None
        self._values[prepared] = out
        return out

    def describe(self, state: State) -> str:
        model = self.derivation.model
        return ", ".join(f"{n} = {v:.3g}" for n, v in describe(state, (*model.coordinates, *model.velocities))[:6])


def _real(value: Any) -> bool:
    return isinstance(value, mpmath.mpf)


def constant_in_groups(rows: Sequence[tuple[State, list[Any], list[Any]]], *, additive: bool) -> bool:
    """Whether E/D (E − D when ``additive``) is the same at every state of a group (the same parameters);
    False when E is undefined somewhere or D vanishes where E does not."""
    by_group: dict[int, list[Any]] = {}
    for state, (e,), (d,) in rows:
        if not _real(e):
            return False
        if additive:
            value = e - d
        elif abs(d) > 1e-20:
            value = e / d
        elif abs(e) > 1e-20:
            return False
        else:
            continue
        by_group.setdefault(state.group, []).append(value)
    if not by_group:
        return False
    return all(all(close(v, values[0]) for v in values[1:]) for values in by_group.values())


def relation(student: Values | None, reference: Values | None, states: Sequence[State]) -> Relation:
    """How the student's values relate to the reference's (see the module's docstring)."""
    if student is None or reference is None:
        return Relation(UNDECIDED)
    rows = tuple((s, [e], [d]) for s, e, d in zip(states, student, reference, strict=True) if _real(d))
    if len(rows) < MINIMUM_STATES:
        return Relation(UNDECIDED, rows)
    agree = [close(r[1][0], r[2][0]) for r in rows]
    if all(agree):
        return Relation(SAME, rows)
    witness = rows[agree.index(False)][0]
    if any(not _real(r[1][0]) for r in rows):
        return Relation(DIFFERS, rows, witness)
    flipped = [close(r[1][0], -r[2][0]) for r in rows]
    if all(a or f for a, f in zip(agree, flipped, strict=True)):
        return Relation(OPPOSITE if not any(agree) else SIGN_DEPENDENT, rows, witness)
    if constant_in_groups(rows, additive=False) and not all(close(r[1][0], 0) for r in rows):
        return Relation(FACTOR, rows, witness)
    if constant_in_groups(rows, additive=True):
        return Relation(OFFSET, rows, witness)
    return Relation(DIFFERS, rows, witness)


def proportional(student: Values | None, reference: Values | None, states: Sequence[State]) -> bool:
    """Whether an equation's residuals are a constant multiple (not 0) of the reference's."""
    found = relation(student, reference, states)
    if found.kind in (SAME, OPPOSITE, FACTOR):
        return not all(close(r[2][0], 0) for r in found.rows)
    return False


def normal_to_surface(values: Evaluator, value: Any, row: Sequence[Any], variables: Sequence[Any],
                      velocities: Sequence[Any]) -> bool:
    """Whether the constraint ``value`` (ψ, or a velocity form a·q̇ + b) has, at every shared state, a gradient that is
    not zero and is parallel to the key's constraint row ``row`` = (a, b) (over ``variables`` = the coordinates, then
    the time): its zero set is the key's constraint's surface near each state, not a double zero of it (``(r -
    l)**2``, whose gradient vanishes there) nor another constraint that also holds there."""
    if value.has(*velocities):
        at_rest = value.xreplace(dict.fromkeys(velocities, 0))
        gradient = [sympy.diff(value, v) for v in velocities] + [at_rest]
    else:
        gradient = [sympy.diff(value, x) for x in variables]
    found = [values.values(g) for g in gradient]
    key = [values.values(a) for a in row]
    if any(f is None for f in found) or any(k is None for k in key):
        return False
    checked = 0
    for i in range(len(values.states)):
        g = [f[i] for f in found]  # type: ignore[index]
        a = [k[i] for k in key]  # type: ignore[index]
        if not all(_real(x) for x in (*g, *a)):
            continue
        norm_a = mpmath.sqrt(sum(x * x for x in a))
        if norm_a < 1e-12:
            continue  # a singular point of the key's constraint: nothing to compare with
        norm_g = mpmath.sqrt(sum(x * x for x in g))
        if norm_g <= 1e-12 * norm_a:
            return False
        along = sum(x * y for x, y in zip(g, a, strict=True)) / norm_a**2
        if mpmath.sqrt(sum((x - along * y) ** 2 for x, y in zip(g, a, strict=True))) > 1e-10 * norm_g:
            return False
        checked += 1
    return checked >= MINIMUM_STATES
