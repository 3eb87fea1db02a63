r"""What is wrong with an answer that disagrees: the diagnoses of ``lagsolve check``.

Each function looks at *rows*: for every random state on the constraint surface
(:mod:`lagsolve.check.states`), the expected values E and the derived values D, one per component.

* :func:`constant_relation` — :math:`E/D` (or :math:`E - D`) the same at every state that
  shares the parameters: a missing factor 2 or m, a shifted zero level;
* :func:`sign_condition` — :math:`E = D` where some :math:`u > 0` and :math:`E = -D` elsewhere:
  a magnitude written without ``Abs``;
* :class:`ReleasedConstraints` — E is the acceleration the system would have with a
  constraint released (:math:`\lambda_j = 0`): the answer ignores that constraint.
"""

from __future__ import annotations

import contextlib
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import mpmath
import sympy

from lagsolve.check.states import DIGITS, Compiled, State, StateSpace
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.symbolic.simplify import tidy

#: relative tolerance of a numeric agreement (values carry 30 digits)
TOLERANCE = mpmath.mpf(10) ** -12
#: above this many operations symbolic steps are skipped (numeric decides)
SYMBOLIC_LIMIT = 400

Row = tuple[State, list[Any], list[Any]]


def close(e: Any, d: Any) -> bool:
    """|E − D| ≤ 10⁻¹² max(1, |E|, |D|); an undefined value is never close."""
    if e is None or d is None:
        return False
    return bool(abs(e - d) <= TOLERANCE * max(1, abs(d), abs(e)))


def all_close(values: Sequence[Any]) -> bool:
    return all(close(v, values[0]) for v in values[1:])


def constant_relation(rows: Sequence[Row], expected: tuple[Any, ...], derived: tuple[Any, ...],
                      derivation: Derivation, additive: bool) -> tuple[bool, Any]:
    """Whether E/D (E − D when ``additive``) is the same at every state with the same parameters,
    and if so its value, or ``None`` when it is constant but not identified.

    The value is found symbolically when E/D simplifies to an expression free of the time,
    coordinates, velocities and functions; otherwise as a small rational times a power or
    product of parameters that matches the numbers. States come in groups that share their
    parameter values: within a group the value must not change.
    """
    by_group = _relations_by_group(rows, additive)
    if by_group is None or not _constant_in_each_group(by_group, additive):
        return False, None
    symbolic = _symbolic_constant(expected, derived, derivation, additive)
    if symbolic is not None:
        return True, symbolic
    return True, _fitted_constant([values[0] for values in by_group.values()], derivation)


def _relations_by_group(rows: Sequence[Row], additive: bool) -> dict[int, list[tuple[State, Any]]] | None:
    """E/D (E − D when ``additive``) of every component at every state, by parameter group, leaving out the
    components where both vanish; None where no constant can relate them (E undefined, or D zero where E
    is not)."""
    by_group: dict[int, list[tuple[State, Any]]] = {}
    for state, es, ds in rows:
        for e, d in zip(es, ds, strict=True):
            if e is None or not isinstance(e, mpmath.mpf):
                return None
            if additive:
                value = e - d
            elif abs(d) > TOLERANCE:
                value = e / d
            elif abs(e) > TOLERANCE:
                return None  # D vanishes where E does not: no factor relates them
            else:
                continue
            by_group.setdefault(state.group, []).append((state, value))
    return by_group


def _constant_in_each_group(by_group: dict[int, list[tuple[State, Any]]], additive: bool) -> bool:
    """The relation has values and is the same within each group of states sharing the parameters; a
    difference that is zero everywhere (E = D) is no relation to report."""
    if not by_group or any(not all_close([v for _, v in values]) for values in by_group.values()):
        return False
    return not (additive and all(close(v, 0) for values in by_group.values() for _, v in values))


def _fitted_constant(samples: list[tuple[State, Any]], derivation: Derivation) -> Any:
    """A small rational times one of the :func:`_candidates` that gives the relation's value at every sample
    (one state per parameter group); None where none does."""
    for candidate in _candidates(derivation):
        ratios = _ratios(samples, candidate)
        if ratios is not None and all_close(ratios):
            number = _rational(ratios[0])
            if number is not None and number != 0:
                return number * candidate
    return None


def _ratios(samples: list[tuple[State, Any]], candidate: Any) -> list[Any] | None:
    """The relation's value over ``candidate`` at each sample; None where the candidate is undefined or zero
    at one of them."""
    ratios = []
    for state, value in samples:
        c = _evaluate_constant(candidate, state)
        if c is None or c == 0:
            return None
        ratios.append(value / c)
    return ratios


def _symbolic_constant(expected: tuple[Any, ...], derived: tuple[Any, ...], derivation: Derivation,
                       additive: bool) -> Any:
    """E − D or E/D simplified, when that is free of the time, coordinates, velocities and functions."""
    if len(expected) != 1:
        return None
    model = derivation.model
    variables = {model.time, *model.coordinates, *model.velocities}
    value = expected[0] - derived[0] if additive else expected[0] / derived[0]
    if sympy.count_ops(value) > SYMBOLIC_LIMIT:
        return None
    with contextlib.suppress(sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
        value = tidy(sympy.cancel(value))
        if value.free_symbols & variables or value.atoms(sympy.core.function.AppliedUndef) or value.has(sympy.nan):
            return None
        return value
    return None


def _candidates(derivation: Derivation) -> list[Any]:
    """1, p, 1/p, p², 1/p² and p·q, p/q over the parameters: the factors a student drops."""
    params = [p.symbol for p in derivation.problem.parameters]
    out: list[Any] = [sympy.Integer(1)]
    out += [p**k for p in params for k in (1, -1, 2, -2)]
    out += [a * b**k for i, a in enumerate(params) for b in params[i + 1:] for k in (1, -1)]
    return out


def _rational(value: Any) -> Any:
    """``value`` as a small rational (denominator up to 1000) when it is one, else ``None``."""
    guess = Fraction(float(value)).limit_denominator(1000)
    if abs(value - mpmath.mpf(guess.numerator) / guess.denominator) <= TOLERANCE * max(1, abs(value)):
        return sympy.Rational(guess.numerator, guess.denominator)
    return None


def _evaluate_constant(expr: Any, state: State) -> Any:
    if expr.is_Number:
        return mpmath.mpf(int(expr.p)) / int(expr.q)
    with mpmath.workdps(DIGITS):
        try:
            values = {s: sympy.Float(state.values[s], DIGITS) for s in expr.free_symbols}
            return mpmath.mpf(expr.xreplace(values).evalf(DIGITS))
        except (TypeError, KeyError):
            return None


def sign_condition(rows: Sequence[Row], agree: list[bool], expected: tuple[Any, ...], derived: tuple[Any, ...],
                   space: StateSpace) -> Any:
    """Where an answer that is right up to sign holds: ``u > 0`` (or ``u < 0``) for the argument
    ``u`` of an ``Abs`` or ``sign`` in the derived result, or for the answer itself, whose sign
    separates the states where it agrees from those where it has the opposite sign."""
    candidates: list[Any] = []
    for d in derived:
        for atom in sorted(d.atoms(sympy.Abs, sympy.sign), key=sympy.default_sort_key):
            if atom.args[0] not in candidates:
                candidates.append(atom.args[0])
    if len(expected) == 1:
        candidates.append(expected[0])
    for u in candidates:
        compiled = Compiled(u, space)
        values: list[Any] = [compiled(state) for state, _, _ in rows]
        if any(v is None or not isinstance(v, mpmath.mpf) or v == 0 for v in values):
            continue
        positive = [v > 0 for v in values]
        if positive == agree:
            return sympy.StrictGreaterThan(u, 0, evaluate=False)
        if [not p for p in positive] == agree:
            return sympy.StrictLessThan(u, 0, evaluate=False)
    return None


class ReleasedConstraints:
    r"""Accelerations with constraints released, to recognise an answer that ignores one.

    At a state the augmented system of :mod:`lagsolve.mechanics.equations.lagrange` is solved numerically
    with only the kept constraints S,

    .. math:: M\ddot q - A_S^T\lambda_S = F, \qquad A_S\ddot q = \beta_S,

    with friction normal forces at their derived values.
    """

    def __init__(self, derivation: Derivation, space: StateSpace) -> None:
        self.derivation = derivation
        self.space = space
        self._compiled: tuple[list[list[Compiled]], ...] | None = None

    def which(self, coordinate: str, rows: Sequence[Row]) -> str | None:
        """``"constraint 'rod'"`` (or ``"constraint 'a' or 'b'"``, ``"every constraint"``) when the
        expected acceleration of ``coordinate`` equals the one with that released, at every state."""
        names = [c.name for c in self.derivation.constraints]
        if not names:
            return None
        index = [c.name for c in self.derivation.problem.coordinates].index(coordinate)
        options = [(repr(name), [k for k in range(len(names)) if k != j]) for j, name in enumerate(names)]
        if len(names) > 1:
            options.append(("every constraint", []))
        systems = [self._system(state) for state, _, _ in rows]
        if any(s is None for s in systems):
            return None
        matches = []
        for label, kept in options:
            values = [_solve_kept(system, kept, index) for system in systems]  # type: ignore[arg-type]
            if all(close(es[0], v) for (_, es, _), v in zip(rows, values, strict=True)):
                matches.append(label)
        singles = [m for m in matches if m != "every constraint"]
        if singles:
            return "constraint " + " or ".join(singles)
        return matches[0] if matches else None

    def _system(self, state: State) -> tuple[Any, Any, Any, Any] | None:
        """M, F, A and β evaluated at ``state`` (lists of rows), or ``None`` where undefined."""
        if self._compiled is None:
            lagrange = self.derivation.lagrange
            normals = {f.term.normal: f.normal_force for f in self.derivation.friction}

            def compile_matrix(matrix: Any) -> list[list[Compiled]]:
                return [[Compiled(matrix[i, j].xreplace(normals), self.space) for j in range(matrix.cols)]
                        for i in range(matrix.rows)]

            self._compiled = tuple(compile_matrix(m) for m in (
                lagrange.mass_matrix, lagrange.forcing, lagrange.constraint_jacobian, lagrange.constraint_rhs))
        values = []
        for matrix in self._compiled:
            rows = [[entry(state) for entry in row] for row in matrix]
            if any(v is None or not isinstance(v, mpmath.mpf) for row in rows for v in row):
                return None
            values.append(rows)
        return values[0], values[1], values[2], values[3]


def _solve_kept(system: tuple[Any, Any, Any, Any], kept: list[int], index: int) -> Any | None:
    """q̈[index] from the augmented system with only the constraints ``kept`` (None when singular)."""
    M, F, A, beta = system
    n, m = len(M), len(kept)
    with mpmath.workdps(DIGITS):
        matrix = mpmath.zeros(n + m, n + m)
        rhs = mpmath.zeros(n + m, 1)
        for i in range(n):
            rhs[i] = F[i][0]
            for k in range(n):
                matrix[i, k] = M[i][k]
            for r, j in enumerate(kept):
                matrix[i, n + r] = -A[j][i]
                matrix[n + r, i] = A[j][i]
        for r, j in enumerate(kept):
            rhs[n + r] = beta[j][0]
        try:
            return mpmath.lu_solve(matrix, rhs)[index]
        except ZeroDivisionError:
            return None
