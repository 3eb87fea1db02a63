"""``lagsolve variants``: one derivation, many verified sets of numbers.

The problem is derived once (symbolically) and its equations compiled once; each candidate only substitutes
its numbers (the sweep's mechanism: the bound system with its parameter array replaced), completes its initial
state, runs the simulation, builds its key and passes the sanity rules, or is replaced by the next draw. The
draws come from ``numpy.random.default_rng(seed)`` in a fixed order, so a seed gives the same variants.
Nothing here prints, exits or writes files.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from lagsolve.errors import Issue, LagsolveError, SpecError
from lagsolve.mechanics.results import Derivation
from lagsolve.numeric.integrate import Trajectory, integrate_motion
from lagsolve.numeric.system import NumericSystem, bind
from lagsolve.problem.schema import Problem
from lagsolve.variants import sanity
from lagsolve.variants.generate import Candidate, candidate, draw
from lagsolve.variants.key import Key, KeyBuilder, StateNumbers, expected_section
from lagsolve.variants.spec import Request, check_request
from lagsolve.variants.yamlfile import variant_text

#: samples of each variant's run (fine enough for the finite differences of a start from rest)
SAMPLES = 2001
#: right-hand-side evaluations a variant's run may take (a normal run takes a few hundred; stick–slip chattering
#: can take millions). A count, not a time, so that a seed gives the same variants on any machine.
MAX_EVALUATIONS = 20_000


class _Stalled(Exception):
    """A run used up :data:`MAX_EVALUATIONS` (raised from the integrator's progress callback)."""


@dataclass(frozen=True)
class Variant:
    """One accepted variant: its numbers, its key, its problem file (text) and its simulation summary."""

    index: int
    varied: dict[str, float]
    values: dict[str, float]
    initial: dict[str, float]
    key: Key
    text: str
    summary: str
    figures: dict[str, bytes] = dataclasses.field(default_factory=dict)  # PNG by name, with --figures


@dataclass(frozen=True)
class VariantSet:
    """The variants of one problem, the rejections per rule, the derived ``expected:`` answers and the report
    they share (Markdown), and notes (answers left out of the key because they did not pass ``check``)."""

    problem: Problem
    request: Request
    variants: tuple[Variant, ...]
    rejections: dict[str, int]
    attempts: int
    expected: dict[str, dict[str, str]]
    report: str
    notes: tuple[str, ...] = ()
    submission: str = ""  # the key as a lagsolve grade submission (the same for every variant)

    @property
    def slug(self) -> str:
        return self.problem.slug

    def answer_names(self, *, every: bool = False) -> list[str]:
        """The answers' names in order of first appearance (``every``: only those every variant has)."""
        names: list[str] = []
        for v in self.variants:
            names += [a.name for a in v.key.answers if a.name not in names]
        if every:
            names = [n for n in names if all(any(a.name == n for a in v.key.answers) for v in self.variants)]
        return names

    def exported(self) -> list[str]:
        """The answers a quiz asks for: those every variant has, except those that are 0 in every variant."""
        names = self.answer_names(every=True)
        return [n for n in names if any(a.name == n and a.value != 0 for v in self.variants for a in v.key.answers)]

    def answer(self, variant: Variant, name: str) -> Any:
        """``variant``'s answer ``name`` (an :class:`~lagsolve.variants.key.Answer`)."""
        return next(a for a in variant.key.answers if a.name == name)


@dataclass(frozen=True)
class _Shared:
    """What every candidate reuses: the derivation, the compiled system, the original text."""

    problem: Problem
    derivation: Derivation
    system: NumericSystem
    minimal: bool
    original: str
    expected: dict[str, dict[str, str]]


def verified_expected(derivation: Derivation, original: str) -> tuple[dict[str, dict[str, str]], tuple[str, ...]]:
    """The derivation's answers as an ``expected:`` section that ``lagsolve check`` passes: the section is written
    into the file, read back through the problem reader, and checked; an entry that does not pass is left out
    (with a note). The section does not depend on the numbers, so this runs once."""
    from lagsolve.check.compare import check
    from lagsolve.problem.load import load_text

    expected = expected_section(derivation)
    notes = []
    while True:  # an entry the reader refuses (an expression over its length limit) is left out, with a note
        try:
            problem = load_text(variant_text(original, {}, {}, expected, ""), derivation.problem.source)
            break
        except SpecError as error:
            refused: dict[tuple[str, str], str] = {}
            for issue in error.issues:
                quantity, name = ([*issue.where.split(".")[1:3], ""])[:2]
                if not issue.where.startswith("expected.") or name not in expected.get(quantity, {}):
                    raise
                refused.setdefault((quantity, name), issue.message)
            for (quantity, name), message in refused.items():
                del expected[quantity][name]
                notes.append(f"{quantity}.{name} left out of the key: the problem reader refuses it ({message})")
    form = dataclasses.replace(derivation.form, problem=problem)
    report = check(dataclasses.replace(derivation, form=form))
    for verdict in report.verdicts:
        if verdict.status != "ok" and verdict.name in expected.get(verdict.quantity, {}):
            del expected[verdict.quantity][verdict.name]
            notes.append(f"{verdict.quantity}.{verdict.name} left out of the key: check says {verdict.status}")
    return {k: v for k, v in expected.items() if v}, tuple(notes)


def _prepare(path: str | Path, request: Request, budget: float) -> tuple[_Shared, tuple[str, ...], str, str]:
    from lagsolve.mechanics.analysis.minimal_chart import minimal_chart
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem
    from lagsolve.render.report import render

    problem = load_problem(path)
    check_request(problem, request)
    original = Path(path).read_text(encoding="utf-8")
    derivation = derive(problem, budget=budget)
    if not derivation.accelerations:
        raise SpecError([Issue(problem.source, 0, "", "the accelerations were not solved in closed form, so there "
                               "is no key to verify", "give a larger --timeout, or a smaller problem")])
    expected, notes = verified_expected(derivation, original)
    chart, _ = minimal_chart(derivation.analysis, derivation.model) if derivation.analysis else (None, "")
    middle = {v.name: (v.low + v.high) / 2 for v in request.vary if not v.initial}
    energy_note = derivation.analysis.conservation.energy.reason() if derivation.analysis else ""
    system = bind(derivation.form, middle, derivation.conserved or {}, chart, energy_note)
    shared = _Shared(problem, derivation, system, chart is not None, original, expected)
    from lagsolve.variants.submission import model_submission

    return shared, notes, render(derivation, "md"), model_submission(derivation)


def _own_system(shared: _Shared, varied: dict[str, float]) -> NumericSystem:
    system = shared.system
    parameters = np.array(system.parameters, dtype=float)
    for name, value in varied.items():
        if name in system.parameter_names:
            parameters[system.parameter_names.index(name)] = value
    return dataclasses.replace(system, parameters=parameters, evaluations=[0])


def _simulate(shared: _Shared, system: NumericSystem, start: Candidate) -> Trajectory:
    spec = shared.problem.simulation
    assert spec is not None and spec.t_end is not None  # check_request refused a file without them
    from lagsolve.problem.methods import DEFAULT

    def watch(t: float) -> None:
        if system.evaluations[0] > MAX_EVALUATIONS:
            raise _Stalled(f"the run stalls at t = {t:.6g} (more than {MAX_EVALUATIONS} evaluations of the "
                           "equations: stick-slip chattering or a stiff stretch)")

    return integrate_motion(system, start.q0, start.qd0, spec.t_end, samples=SAMPLES, method=spec.method or DEFAULT,
                            rtol=spec.rtol or 1e-10, atol=spec.atol or 1e-12, minimal=shared.minimal,
                            progress=watch)


def _try(shared: _Shared, request: Request, varied: dict[str, float]) -> tuple[Any, sanity.Rejection | None]:
    """One candidate: (its start, run and key) or the rule it fails."""
    system = _own_system(shared, varied)
    try:
        start = candidate(shared.problem, system, varied, request.vary)
    except LagsolveError as error:
        return None, sanity.Rejection("simulation", f"no initial state: {error}")
    numbers = StateNumbers(shared.derivation, start.values, start.q0, start.qd0, system.coordinates)
    mass = np.array([[numbers(x) for x in row] for row in shared.derivation.mass_matrix.tolist()], dtype=float)
    rejection = sanity.conditioning(mass)
    if rejection:
        return None, rejection
    try:
        run = _simulate(shared, system, start)
    except (LagsolveError, _Stalled) as error:
        return None, sanity.Rejection("simulation", str(error))
    rejection = sanity.normal_force(run, request.require)
    builder = KeyBuilder(shared.derivation, system, start.values, run)
    key = builder.build()
    rejection = (rejection or sanity.regime(run, request.require, key.regime) or sanity.energy_drift(run)
                 or (sanity.Rejection("key", "; ".join(builder.faults)) if builder.faults else None))
    return (start, run, key), rejection


def generate(path: str | Path, request: Request, *, budget: float = 120.0,
             progress: Callable[[int, int], None] | None = None) -> VariantSet:
    """``request.count`` verified variants of the problem at ``path``.

    Raises
    ------
    SpecError
        The request cannot be met: a bad option (before any work), or the attempts ran out before enough
        variants passed (the message gives the rejections per rule and what to change).
    """
    from lagsolve.render.trajectory import summary

    shared, notes, report, submission = _prepare(path, request, budget)
    rng = np.random.default_rng(request.seed)
    limit = request.attempts or max(50, 20 * request.count)
    rejections = dict.fromkeys(sanity.RULES, 0)
    reasons: dict[str, str] = {}
    accepted: list[Variant] = []
    attempts = 0
    while len(accepted) < request.count and attempts < limit:
        attempts += 1
        varied = draw(rng, request.vary, request.sig_figs)
        outcome, rejection = _try(shared, request, varied)
        if rejection is not None:
            rejections[rejection.rule] += 1
            reasons.setdefault(rejection.rule, rejection.reason)
            continue
        start, run, key = outcome
        index = len(accepted) + 1
        variant = _variant(shared, request, index, start, key, summary(run, shared.problem.name, timing=False))
        if request.figures:
            from lagsolve.variants.figures import variant_figures

            title = f"{shared.problem.name}, variant {index}"
            variant = dataclasses.replace(variant, figures=variant_figures(run, title))
        accepted.append(variant)
        if progress is not None:
            progress(len(accepted), attempts)
    if len(accepted) < request.count:
        raise SpecError([_exhausted(shared.problem, request, len(accepted), attempts, rejections, reasons)])
    return VariantSet(shared.problem, request, tuple(accepted), rejections, attempts, shared.expected, report, notes,
                      submission)


def _variant(shared: _Shared, request: Request, index: int, start: Candidate, key: Key, text: str) -> Variant:
    varied_parameters = {k: v for k, v in start.varied.items() if k in start.values}
    note = (f"lagsolve variants: variant {index} of {request.count} (seed {request.seed}); varied: "
            + ", ".join(f"{k} = {v:g}" for k, v in start.varied.items()))
    written = variant_text(shared.original, varied_parameters, start.initial, shared.expected, note)
    return Variant(index, dict(start.varied), dict(start.values), dict(start.initial), key, written, text)


def _exhausted(problem: Problem, request: Request, found: int, attempts: int, rejections: dict[str, int],
               reasons: dict[str, str]) -> Issue:
    counts = ", ".join(f"{rule} {n}" for rule, n in rejections.items() if n)
    example = "; ".join(f"{rule}: {why}" for rule, why in reasons.items())
    return Issue(problem.source, 0, "--count",
                 f"only {found} of {request.count} variants passed in {attempts} attempts (rejected: {counts}; "
                 f"e.g. {example})",
                 "widen or move the --vary ranges toward the required regime, drop --require, or raise --attempts")
