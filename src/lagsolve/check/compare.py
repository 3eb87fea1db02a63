r"""Compare a problem's ``expected:`` answers with its derivation (``lagsolve check``).

An answer is right when it agrees with the derivation *on the constraint surface*; how it is
written does not matter (the format's "Expected answers"). For each expected quantity E and the
derived D:

1. **Symbolic.** E is written with the constraints used as the derivation does (multipliers
   :math:`\lambda_j` replaced by their derived values, explicitly solvable dependent coordinates
   and velocities eliminated), and :math:`E - D` is reduced by cheap steps first (structural
   equality, ``cancel``), then :func:`lagsolve.mechanics.symbolic.simplify.tidy`. Zero → *ok (symbolic)*.
2. **Numeric.** Otherwise both are evaluated at random states on the constraint surface
   (:mod:`lagsolve.check.states`; declared functions become random smooth functions). Agreement at
   every state → *ok (numeric)*.
3. **Diagnosis** of a disagreement, from the values at those states:

   * :math:`E = -D` everywhere: *opposite sign*; for a multiplier, *λ with the opposite sign
     convention* (lagsolve's convention is :math:`\frac{d}{dt}\frac{\partial L}{\partial\dot q_i}
     - \frac{\partial L}{\partial q_i} = Q_i + \sum_j\lambda_j a_{ji}`);
   * for an acceleration, E is the acceleration with one constraint (or all) *released*
     (:math:`\lambda = 0`): the answer ignores that constraint;
   * :math:`E = D` at some states and :math:`E = -D` at the others: the answer *holds only where*
     some quantity is positive (a magnitude written without ``Abs``) — a **warning**, not ok;
   * :math:`E/D` constant (a number, or a power of a parameter times a number): a *constant
     factor*, e.g. a missing 2 or m;
   * :math:`E - D` constant: a *constant offset* — ok for a conserved quantity or a potential,
     whose zero level is free (the verdict says so); a mismatch elsewhere;
   * otherwise the two simply *differ*; a state where they do is reported.

A claimed **conserved quantity** C that lagsolve's analysis does not give under the same name is
checked on its own: its rate along the equations of motion,

.. math:: \frac{dC}{dt} = \frac{\partial C}{\partial t} + \sum_i \frac{\partial C}{\partial q_i}\dot q_i
          + \sum_i \frac{\partial C}{\partial \dot q_i}\ddot q_i,

with :math:`\ddot q` the derived accelerations, must vanish: symbolically (*conserved, symbolic*)
or at every random state on the constraint surface (*conserved, numeric*); otherwise the claim is a
mismatch (*not conserved*) with a state where :math:`dC/dt \ne 0` (the witness holds that rate as
``expected`` and 0 as ``derived``). A quantity lagsolve does give under that name (``energy``, a
cyclic momentum ``p_<q>``) is compared with it as above.

Agreement only off the constraint surface does not count: every state satisfies every
constraint. The result is a frozen :class:`CheckReport`; nothing is printed here.
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from lagsolve.check.diagnose import (
    ReleasedConstraints,
    Row,
    close,
    constant_relation,
    sign_condition,
)
from lagsolve.check.modes import mode_verdicts
from lagsolve.check.states import Compiled, State, StateSpace
from lagsolve.check.verdicts import (
    ABSENT,
    BRACKET,
    CONSERVED,
    CONVENTION,
    DIFFERS,
    FACTOR,
    MISMATCH,
    NOT_BRACKET,
    NOT_CONSERVED,
    NOT_DERIVED,
    NUMERIC,
    OFFSET,
    OK,
    OPPOSITE_SIGN,
    RELEASED,
    SAME,
    SHAPE,
    SIGN_DEPENDENT,
    SYMBOLIC,
    TOO_FEW_STATES,
    TRIVIAL,
    UNCHECKED,
    UNDEFINED,
    WARNING,
    CheckReport,
    Item,
    Verdict,
    Witness,
    symbolically_equal,
)
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.symbolic.simplify import reproducible
from lagsolve.problem.names import momentum_name, momentum_symbol

__all__ = [  # the verdicts and reasons are defined in verdicts.py; callers may name them here
    "CheckReport", "Verdict", "Witness", "check", "OK", "WARNING", "MISMATCH", "UNCHECKED", "SYMBOLIC", "NUMERIC",
    "OPPOSITE_SIGN", "CONVENTION", "FACTOR", "OFFSET", "SIGN_DEPENDENT", "UNDEFINED", "DIFFERS", "ABSENT", "SHAPE",
    "RELEASED", "CONSERVED", "NOT_CONSERVED", "TRIVIAL", "NOT_DERIVED", "TOO_FEW_STATES", "SAME", "BRACKET",
    "NOT_BRACKET",
]

STATES = 24
MINIMUM_STATES = 8


def check(derivation: Derivation, *, states: int = STATES, seed: int = 0) -> CheckReport:
    """Compare the problem's expected answers with ``derivation``.

    Parameters
    ----------
    derivation : Derivation
        The derived problem; its ``problem.expected`` holds the answers.
    states : int
        How many random states on the constraint surface a numeric comparison uses.
    seed : int
        Seed of those states (the same seed gives the same states, so a report is reproducible).

    Returns
    -------
    CheckReport
        One :class:`Verdict` per expected quantity.

    Examples
    --------
    >>> from lagsolve.problem.load import load_text
    >>> from lagsolve.mechanics.derivation import derive
    >>> problem = load_text('''
    ... name: falling mass
    ... parameters: {m: mass, g: gravity}
    ... coordinates: [y]
    ... particles: {p: {mass: m, position: [0, y]}}
    ... gravity: [0, -g]
    ... expected: {accelerations: {y: "g"}}
    ... ''')
    >>> report = check(derive(problem))
    >>> [(v.status, v.reason) for v in report.verdicts]
    [('mismatch', 'opposite sign')]
    """
    reproducible()  # the comparisons simplify too: SymPy's factorisation draws random numbers
    problem = derivation.problem
    items = _items(derivation)
    checker = _Checker(derivation, items, states, seed)
    verdicts = [checker.verdict(item) for item in items]
    verdicts += checker.equilibria()
    verdicts += _steady_stability(derivation)
    verdicts += mode_verdicts(checker, derivation)
    return CheckReport(problem.name, problem.source, tuple(c.name for c in problem.coordinates), tuple(verdicts))


# -- what to compare ----------------------------------------------------------------------------


def _items(derivation: Derivation) -> list[Item]:
    expected = derivation.problem.expected
    items: list[Item] = []
    missing = "; ".join(n.sentence() for n in derivation.notes) or "not derived"
    accelerations, multipliers = derivation.accelerations, derivation.multipliers
    for q, e in expected.accelerations.items():
        items.append(Item("accelerations", q, (e,), None if accelerations is None else (accelerations[q],),
                           missing))
    for c, e in expected.multipliers.items():
        items.append(Item("multipliers", c, (e,), None if multipliers is None else (multipliers[c],), missing))
    for c, spec in expected.constraint_forces.items():
        if derivation.constraint_forces is None:
            for key in ("magnitude", "vector"):
                if key in spec:
                    items.append(Item("constraint_forces", c if key == "magnitude" else f"{c}.vector",
                                       tuple(spec[key]) if key == "vector" else (spec[key],), None, missing))
            continue
        force = derivation.constraint_forces[c]
        note = force.note or "lagsolve gives no single force for this constraint"
        if "magnitude" in spec:
            derived = None if force.magnitude is None else (force.magnitude,)
            items.append(Item("constraint_forces", c, (spec["magnitude"],), derived, note))
        if "vector" in spec:
            derived = None if force.vector is None else tuple(force.vector)
            items.append(Item("constraint_forces", f"{c}.vector", tuple(spec["vector"]), derived, note))
    items += _analysis_items(derivation)
    items += _steady_items(derivation)
    return items


def _steady_items(derivation: Derivation) -> list[Item]:
    r"""Expected steady motions against the derived ones: the rates as a set (their sum and product, so the
    order and the branch of a square root do not matter), and :math:`\omega^2` at each derived rate (both
    sides written with the rate put in, so either may use the condition or not)."""
    spec = derivation.problem.expected.steady_motions
    if spec is None:
        return []
    analysis = derivation.analysis
    steady = analysis.steady if analysis is not None else None
    values = tuple(spec.roots)
    note = NOT_YET if analysis is None or not analysis.steady_note else \
        f"lagsolve gives no steady motions: {analysis.steady_note}"
    missing = UNCHECKED
    if steady is not None and (steady.coordinate.name != spec.coordinate or steady.rate.name != spec.rate):
        note = (f"expected {spec.coordinate} fixed and {spec.rate} turning; lagsolve keeps {steady.coordinate.name} "
                f"fixed and takes {steady.rate.name} as the rate")
        steady, missing = None, MISMATCH
    items = [Item("steady_motions", "values", _symmetric(values), None if steady is None else
                   _symmetric(steady.roots), note, real=False, missing=missing)]
    if steady is not None and len(steady.roots) != len(values):
        items[0] = Item("steady_motions", "values", values, tuple(steady.roots), real=False)
    if spec.frequency is not None:
        derived = None
        expected: tuple[Any, ...] = (spec.frequency**2,)
        if steady is not None:
            omega = steady.velocity
            expected = tuple(spec.frequency.xreplace({omega: r})**2 for r in steady.roots)
            derived = tuple(steady.frequency_squared.xreplace({omega: r}) for r in steady.roots)
        items.append(Item("steady_motions", "frequency", expected, derived, note, real=False, missing=missing))
    return items


def _symmetric(values: tuple[Any, ...]) -> tuple[Any, ...]:
    """The elementary symmetric functions of one or two values (the values themselves when more)."""
    if len(values) == 2:
        return (values[0] + values[1], values[0] * values[1])
    return values


def _steady_stability(derivation: Derivation) -> list[Verdict]:
    """The expected stability of the steady motions against the derived one."""
    spec = derivation.problem.expected.steady_motions
    if spec is None or spec.stable is None:
        return []
    steady = derivation.analysis.steady if derivation.analysis is not None else None
    expected = (sympy.true if spec.stable else sympy.false,)
    if steady is None or steady.stable is None:
        return [Verdict("steady_motions", "stable", UNCHECKED, NOT_DERIVED, expected,
                        note="lagsolve does not decide the stability of the steady motions")]
    same = bool(steady.stable) == bool(spec.stable)
    return [Verdict("steady_motions", "stable", OK if same else MISMATCH, SAME if same else DIFFERS, expected,
                    (sympy.true if steady.stable else sympy.false,))]


#: a claimed constant of the motion is the same at two states when its state-dependent terms differ by at most
#: this fraction of their size (the sum of their absolute values)
TRIVIAL_TOLERANCE = 1e-12
#: why a claimed constant of the motion that is the same at every state of one set of parameters is true but says
#: nothing (a warning: ``lagsolve grade`` gives such an answer no credit)
TRIVIALLY = ("it has the same value at every state on the constraint surface (for given parameters): a constant of "
             "the parameters or a constraint, conserved by any motion; a constant of the motion is a quantity of "
             "the coordinates and velocities")
NOT_YET = "not derived yet (lagsolve's analysis does not give it for this problem)"


def _analysis_items(derivation: Derivation) -> list[Item]:
    """``reduced``, ``conserved`` and ``effective_potential`` in the shapes of the format's section 2."""
    expected = derivation.problem.expected
    names = _names(derivation)
    items: list[Item] = []
    reduced = derivation.reduced
    for q, e in expected.reduced.items():
        table = (reduced or {}).get("accelerations") or {}
        value = _as_expr(table.get(q), names)
        note = NOT_YET
        if reduced is not None and value is None:
            independent = ", ".join(map(str, reduced.get("independent") or ())) or "none"
            note = f"{q} is not an independent coordinate of lagsolve's reduced system (independent: {independent})"
        items.append(Item("reduced", q, (e,), None if value is None else (value,), note))
    conserved = derivation.conserved
    for name, e in expected.conserved.items():
        value = _as_expr((conserved or {}).get(name), names)
        if value is None:
            found = "no analysis" if conserved is None else ", ".join(conserved) or "nothing"
            # its rate along the equations needs the explicit accelerations; without them it stays unchecked
            items.append(Item("conserved", name, (e,), None, f"lagsolve's analysis does not find {name!r} "
                               f"(it finds: {found})", shifts=True, rate=derivation.accelerations is not None))
            continue
        items.append(Item("conserved", name, (e,), (value,), shifts=True))
    items += _bracket_items(derivation)
    spec = expected.effective_potential
    if spec and "expression" in spec:
        derived = derivation.effective_potential
        value = _as_expr((derived or {}).get("expression"), names)
        note, missing = NOT_YET, UNCHECKED
        if derived is not None and str(derived.get("coordinate")) != spec["coordinate"]:
            note = (f"expected a potential in {spec['coordinate']}, lagsolve reduces to "
                    f"{derived.get('coordinate')}")
            value, missing = None, MISMATCH
        items.append(Item("effective_potential", "expression", (spec["expression"],),
                           None if value is None else (value,), note, shifts=True, missing=missing))
    return items


def _bracket_items(derivation: Derivation) -> list[Item]:
    """Each claimed constant C checked again in Hamiltonian form, {C, H} + ∂C/∂t = 0, where H applies."""
    h = derivation.hamiltonian
    if h is None or derivation.analysis is None or derivation.analysis.reduced is None:
        return []
    from lagsolve.mechanics.hamiltonian import claimed_rate

    items = []
    substitution = derivation.analysis.reduced.substitution
    for name, e in derivation.problem.expected.conserved.items():
        rate, status = claimed_rate(h, e, substitution)
        items.append(Item("conserved", f"{name}.poisson_bracket", (e,), None, shifts=True,
                           extra={"bracket": (rate, status)}))
    return items


def _names(derivation: Derivation) -> Any:
    """The names a derived analysis result (when given as text) may use."""
    from lagsolve.problem import expr as gateway

    problem = derivation.problem
    symbols = dict(problem.symbols)
    for c in problem.coordinates:
        symbols.setdefault(momentum_name(c.name), momentum_symbol(c.name))
    functions = {f.name: f.function for f in problem.functions}
    return gateway.Namespace(symbols, functions)


def _as_expr(value: Any, names: Any) -> Any:
    """A derived analysis value as a SymPy expression: kept when it is one, read through the
    safe parser when it is text (the JSON form), ``None`` when absent or unreadable."""
    if value is None or isinstance(value, bool):
        return None
    if isinstance(value, sympy.Basic):
        return None if isinstance(value, sympy.logic.boolalg.Boolean) else value
    if isinstance(value, int | float | str):
        from lagsolve.errors import ExpressionError
        from lagsolve.problem import expr as gateway

        try:
            return gateway.parse(value, names)
        except ExpressionError:
            return None
    return None


# -- the comparisons ------------------------------------------------------------------------------


class _Checker:
    """Shared state of one check: the prepared expressions and, when needed, the random states."""

    def __init__(self, derivation: Derivation, items: list[Item], count: int, seed: int) -> None:
        self.derivation = derivation
        self.count = count
        self.seed = seed
        self.items = items
        self._by_name = {s.name: s for s in derivation.problem.symbols.values()}
        self._space: StateSpace | None = None
        self._states: list[State] | None = None
        self._extra: set[Any] = set()
        self._released: ReleasedConstraints | None = None
        self._rates: dict[str, Any] = {}
        self._trivial: dict[str, bool] = {}
        for item in items:
            for e in (*item.expected, *(item.derived or ())):
                self._extra |= self.prepare(e).free_symbols
            if item.rate:
                self._rates[item.name] = self.rate(item.expected[0])
                self._extra |= self._rates[item.name].free_symbols

    # preparation

    def _unify(self, expr: Any) -> Any:
        """Symbols that carry a problem name are the problem's symbols (a derived ``p_theta`` made
        elsewhere, with other assumptions, is the same quantity)."""
        swap = {s: self._by_name[s.name] for s in expr.free_symbols
                if s.name in self._by_name and self._by_name[s.name] != s}
        return expr.xreplace(swap) if swap else expr

    def prepare(self, expr: Any) -> Any:
        """``expr`` with the derived multipliers and friction normal forces put in (results of coupled
        friction keep the symbol ``N_<contact>``) and the constraints used as the derivation does."""
        derivation = self.derivation
        known = {c.multiplier: derivation.multipliers[c.name] for c in derivation.constraints
                 if derivation.multipliers is not None}
        known |= {f.term.normal: f.normal_force for f in derivation.friction}
        expr = self._unify(expr)
        for _ in range(3):  # a multiplier may hold N, and N the multipliers' pieces
            expr = expr.xreplace(known)
        return derivation.elimination.apply(expr)

    def rate(self, expr: Any) -> Any:
        r""":math:`dC/dt` of ``expr`` along the equations of motion (the derived accelerations put in),
        with the constraints used as in :meth:`prepare`."""
        model = self.derivation.model
        derived = self.derivation.accelerations or {}  # items with a rate exist only when they are derived
        accelerations = {a: derived[q.name] for q, a in zip(model.coordinates, model.accelerations, strict=True)}
        rate = model.time_derivative(self._unify(expr), second_order=True).xreplace(accelerations)
        return self.prepare(rate)

    def space(self) -> StateSpace:
        if self._space is None:
            self._space = StateSpace(self.derivation, self._extra, self.seed)
        return self._space

    def states(self) -> list[State]:
        if self._states is None:
            self._states = self.space().states(self.count)
        return self._states

    # verdicts

    def verdict(self, item: Item) -> Verdict:
        if (item.rate or "bracket" in item.extra) and self.trivial(item.expected[0]):
            return Verdict(quantity=item.quantity, name=item.name, expected=item.expected, status=WARNING,
                           reason=TRIVIAL, note=TRIVIALLY)
        if item.rate:
            return self.conservation(item)
        if "bracket" in item.extra:
            return _bracket_verdict(item)
        expected = tuple(self.prepare(e) for e in item.expected)
        base: dict[str, Any] = {"quantity": item.quantity, "name": item.name, "expected": item.expected}
        if item.derived is None:
            return Verdict(**base, status=item.missing,
                           reason=NOT_DERIVED if item.missing == UNCHECKED else ABSENT, note=item.note)
        derived = tuple(self.prepare(d) for d in item.derived)
        base["derived"] = item.derived
        if len(expected) != len(derived):
            return Verdict(**base, status=MISMATCH, reason=SHAPE,
                           note=f"expected {len(expected)} components, lagsolve has {len(derived)}")
        if all(symbolically_equal(e, d) for e, d in zip(expected, derived, strict=True)):
            return Verdict(**base, status=OK, reason=SYMBOLIC)
        return self.numeric(item, expected, derived, base)

    def numeric(self, item: Item, expected: tuple[Any, ...], derived: tuple[Any, ...],
                base: dict[str, Any]) -> Verdict:
        rows = self.sampled_rows(item, expected, derived)
        if len(rows) < MINIMUM_STATES:
            return Verdict(**base, status=UNCHECKED, reason=TOO_FEW_STATES, states=len(rows),
                           note=f"only {len(rows)} states on the constraint surface where the derived value is "
                                "defined were found")
        agree = [all(close(e, d) for e, d in zip(es, ds, strict=True)) for _, es, ds in rows]
        n, k = len(rows), sum(agree)
        base |= {"states": n, "agreeing": k}
        if k == n:
            return Verdict(**base, status=OK, reason=NUMERIC)
        witness_row = rows[agree.index(False)]
        base["witness"] = self.witness(witness_row, expected, derived)
        if any(e is None for _, es, _ in rows for e in es):
            return Verdict(**base, status=MISMATCH, reason=UNDEFINED,
                           note="the expected answer is undefined at a state that satisfies the constraints")
        verdict = self.sign_verdict(item, base, rows, agree, expected, derived)
        if verdict is None:
            verdict = self.released_verdict(item, base, rows)
        return verdict if verdict is not None else self.relation_verdict(item, base, rows, expected, derived)

    def sampled_rows(self, item: Item, expected: tuple[Any, ...], derived: tuple[Any, ...]) -> list[Row]:
        """The expected and derived values at each sampled state where the derived result is defined (and
        real, for a real quantity)."""
        space = self.space()
        got = [Compiled(e, space) for e in expected]
        want = [Compiled(d, space) for d in derived]
        rows: list[Row] = []
        for state in self.states():
            d = [w(state) for w in want]
            if any(v is None or (item.real and not isinstance(v, mpmath.mpf)) for v in d):
                continue  # outside the derived result's domain
            rows.append((state, [g(state) for g in got], d))
        return rows

    def sign_verdict(self, item: Item, base: dict[str, Any], rows: list[Row], agree: list[bool],
                     expected: tuple[Any, ...], derived: tuple[Any, ...]) -> Verdict | None:
        """When the answers differ by their sign only: everywhere (the opposite sign, or the other λ convention)
        or where a condition fails (a sign-dependent answer). None when they differ otherwise."""
        flipped = [all(close(e, -d) for e, d in zip(es, ds, strict=True)) for _, es, ds in rows]
        if not all(a or f for a, f in zip(agree, flipped, strict=True)):
            return None
        if sum(agree) == 0:
            if item.quantity == "multipliers":
                return Verdict(**base, status=MISMATCH, reason=CONVENTION, factor=sympy.Integer(-1),
                               note="λ with the opposite sign convention: expected = −derived, and that is the "
                                    "only difference")
            return Verdict(**base, status=MISMATCH, reason=OPPOSITE_SIGN, factor=sympy.Integer(-1))
        condition = sign_condition(rows, agree, expected, derived, self.space())
        return Verdict(**base, status=WARNING, reason=SIGN_DEPENDENT, condition=condition,
                       note="agrees where the condition holds and has the opposite sign elsewhere")

    def released_verdict(self, item: Item, base: dict[str, Any], rows: list[Row]) -> Verdict | None:
        """An expected acceleration that is the one with a constraint released (λ = 0); None otherwise."""
        if item.quantity != "accelerations":
            return None
        if self._released is None:
            self._released = ReleasedConstraints(self.derivation, self.space())
        released = self._released.which(item.name, rows)
        if released is None:
            return None
        return Verdict(**base, status=MISMATCH, reason=RELEASED,
                       note=f"it is the acceleration with {released} released (λ = 0), as if the motion "
                            "were free to leave the constraint surface")

    def relation_verdict(self, item: Item, base: dict[str, Any], rows: list[Row], expected: tuple[Any, ...],
                         derived: tuple[Any, ...]) -> Verdict:
        """Answers that differ by a constant factor (or the other λ convention with one), by a constant offset
        (harmless for a quantity with an arbitrary zero level), or otherwise."""
        constant, factor = constant_relation(rows, expected, derived, self.derivation, additive=False)
        if constant:
            opposite = factor is not None and factor.is_negative and item.quantity == "multipliers"
            note = "λ with the opposite sign convention, and a constant factor" if opposite else ""
            if factor is None:
                note = "the ratio depends only on the parameters"
            return Verdict(**base, status=MISMATCH, reason=CONVENTION if opposite else FACTOR, factor=factor,
                           note=note)
        constant, offset = constant_relation(rows, expected, derived, self.derivation, additive=True)
        if constant:
            harmless = item.shifts
            note = "the same quantity with another zero level" if harmless else ""
            return Verdict(**base, status=OK if harmless else MISMATCH, reason=OFFSET, offset=offset, note=note)
        return Verdict(**base, status=MISMATCH, reason=DIFFERS)

    def conservation(self, item: Item) -> Verdict:
        """A claimed constant of the motion: ok when dC/dt = 0 along the equations, on the constraint surface."""
        rate = self._rates[item.name]
        base: dict[str, Any] = {"quantity": item.quantity, "name": item.name, "expected": item.expected}
        along = "its rate dC/dt along the equations of motion"
        if symbolically_equal(rate, sympy.Integer(0)):
            return Verdict(**base, status=OK, reason=CONSERVED, note=f"{item.note}; {along} simplifies to 0")
        compiled = Compiled(rate, self.space())
        rows: list[Row] = []
        for state in self.states():
            value = compiled(state)
            if isinstance(value, mpmath.mpf):
                rows.append((state, [value], [mpmath.mpf(0)]))
        if len(rows) < MINIMUM_STATES:
            return Verdict(**base, status=UNCHECKED, reason=TOO_FEW_STATES, states=len(rows),
                           note=f"{item.note}; only {len(rows)} states on the constraint surface where "
                                "dC/dt is defined were found")
        zero = [close(es[0], 0) for _, es, _ in rows]
        base |= {"states": len(rows), "agreeing": sum(zero)}
        if all(zero):
            return Verdict(**base, status=OK, reason=CONSERVED,
                           note=f"{item.note}; {along} is 0 at {len(rows)} states on the constraint surface")
        row = rows[zero.index(False)]
        prepared = self.prepare(item.expected[0])
        return Verdict(**base, status=MISMATCH, reason=NOT_CONSERVED, witness=self.witness(row, (prepared,), (rate,)),
                       note=f"{item.note}; {along} is not 0 at {len(rows) - sum(zero)} of {len(rows)} states "
                            "on the constraint surface")

    def trivial(self, expr: Any) -> bool:
        """``expr`` has one value at all the states of each group (one set of parameters) while the coordinates or
        velocities differ between them: a constant of the parameters, or a constraint (x² + y² on a rod), which any
        motion conserves (its rate is 0) and which is no answer. Where no state differs from another (no degree of
        freedom, constraints fixed in time) nothing is trivial."""
        key = str(sympy.srepr(expr))
        if key not in self._trivial:
            space = self.space()
            free = (*space.coordinates, *space.velocities)
            # the terms that depend on the state, each compared at the size of those terms (a constant added, 1e14
            # m g l, or a small factor, 1e-14 E, does not hide how much the rest varies; rounding in a sum that is
            # 0 on the surface, x ẋ + y ẏ, is measured against its terms)
            terms = [t for t in sympy.Add.make_args(self.prepare(expr)) if t.has(space.time, *free)]
            compiled = Compiled(sympy.Add(*terms), space)
            size = Compiled(sympy.Add(*(sympy.Abs(t) for t in terms)), space)
            groups: dict[int, list[tuple[Any, Any, tuple[Any, ...]]]] = {}
            for state in self.states():
                value, scale = compiled(state), size(state)
                if isinstance(value, mpmath.mpf) and isinstance(scale, mpmath.mpf):
                    groups.setdefault(state.group, []).append((value, scale, tuple(state.values[s] for s in free)))
            moving = [g for g in groups.values() if len({point for *_, point in g}) > 1]
            self._trivial[key] = (sum(len(g) for g in moving) >= MINIMUM_STATES and all(
                abs(v - g[0][0]) <= TRIVIAL_TOLERANCE * max(scale, g[0][1]) for g in moving for v, scale, _ in g))
        return self._trivial[key]

    # diagnosis helpers

    def witness(self, row: Row, expected: tuple[Any, ...], derived: tuple[Any, ...]) -> Witness:
        """The state of ``row`` as numbers: what the answers use, the parameters, and the coordinates
        and velocities of the constraints (which define the surface), with the functions used there."""
        state, es, ds = row
        used: set[Any] = set(self.space().parameters)
        calls: set[str] = set()
        model = self.derivation.model
        for c in self.derivation.constraints:
            used |= c.expression.free_symbols & {*model.coordinates, *model.velocities}
        for expr in (*expected, *derived):
            used |= expr.free_symbols
            calls |= {f.func.__name__ for f in expr.atoms(sympy.core.function.AppliedUndef)}
        space = self.space()
        order = {s: i for i, s in enumerate((space.time, *model.coordinates, *model.velocities, *space.parameters,
                                             *space.extra))}
        values = tuple((str(s), float(mpmath.re(state.values[s])))
                       for s in sorted(used & set(state.values), key=lambda s: order.get(s, len(order))))
        functions = tuple((name, lam) for name, lam in state.functions.items() if name in calls)
        return Witness(values, functions, tuple(_complex(v) for v in es), tuple(_complex(v) for v in ds))

    def equilibria(self) -> list[Verdict]:
        """Each expected equilibrium of the effective potential: its value, stability and frequency."""
        spec = self.derivation.problem.expected.effective_potential
        if not spec or not spec.get("equilibria"):
            return []
        derived = self.derivation.effective_potential
        names = _names(self.derivation)
        out: list[Verdict] = []
        found = [] if derived is None else list(derived.get("equilibria") or [])
        for i, eq in enumerate(spec["equilibria"]):
            label = f"equilibria[{i}]"
            if derived is None or str(derived.get("coordinate")) != spec["coordinate"]:
                out.append(Verdict("effective_potential", label, UNCHECKED, NOT_DERIVED, (eq["value"],), note=NOT_YET))
                continue
            match = None
            for candidate in found:
                value = _as_expr(candidate.get("value"), names)
                if value is None:
                    continue
                verdict = self.verdict(Item("effective_potential", f"{label}.value", (eq["value"],), (value,),
                                             real=False))
                if verdict.status == OK:
                    match = (candidate, verdict)
                    break
            if match is None:
                shown = ", ".join(str(c.get("value")) for c in found) or "none"
                out.append(Verdict("effective_potential", f"{label}.value", MISMATCH, ABSENT, (eq["value"],),
                                   note=f"no equilibrium lagsolve finds has this value (it finds: {shown})"))
                continue
            candidate, verdict = match
            out.append(verdict)
            if "stable" in eq:
                stable = candidate.get("stable")
                if stable is None:
                    out.append(Verdict("effective_potential", f"{label}.stable", UNCHECKED, NOT_DERIVED,
                                       (sympy.true if eq["stable"] else sympy.false,),
                                       note="lagsolve does not decide the stability of this equilibrium"))
                else:
                    same = bool(stable) == bool(eq["stable"])
                    out.append(Verdict("effective_potential", f"{label}.stable", OK if same else MISMATCH,
                                       SAME if same else DIFFERS, (sympy.true if eq["stable"] else sympy.false,),
                                       (sympy.true if stable else sympy.false,)))
            if "frequency" in eq:
                frequency = _as_expr(candidate.get("frequency"), names)
                out.append(self.verdict(Item("effective_potential", f"{label}.frequency", (eq["frequency"],),
                                              None if frequency is None else (frequency,),
                                              "lagsolve gives no frequency for this equilibrium", real=False)))
        return out


def _bracket_verdict(item: Item) -> Verdict:
    """The verdict of a claimed constant's Poisson bracket with H (see :func:`_bracket_items`)."""
    rate, status = item.extra["bracket"]
    base: dict[str, Any] = {"quantity": item.quantity, "name": item.name, "expected": item.expected}
    what = "{C, H} + dC/dt (explicit) + sum of dC/dp_i Q_i, with C written in the momenta,"
    if status == "differ":
        return Verdict(**base, derived=(rate,), status=MISMATCH, reason=NOT_BRACKET, note=f"{what} is not 0")
    how = "simplifies to 0" if status == "symbolic" else "is 0 at random states"
    return Verdict(**base, status=OK, reason=BRACKET, note=f"{what} {how}", states=0 if status == "symbolic" else 6)


# -- small numeric helpers -------------------------------------------------------------------------




def _complex(value: Any) -> complex | None:
    return None if value is None else complex(value)


#: ``lagsolve grade`` (:mod:`lagsolve.grade.grader`) compares a student's steps with the key's the way a check
#: compares expected answers with the derivation: one comparison, and the shared states of all of them
Comparison = Item
Comparer = _Checker
