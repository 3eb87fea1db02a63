r"""Grade one submission step by step against the key's derivation (``lagsolve grade``).

A submission in other coordinates (``coordinates_map:``) is read into the key's coordinates and the key's answers
are carried into the student's (:mod:`.frame`). Each entry of a step (a coordinate's momentum, a constraint's
multiplier, ...) is then judged in this order:

1. **correct** — equivalent to the key's answer as ``lagsolve check`` judges it
   (:class:`lagsolve.check.compare.Comparer`: on the constraint surface, at random consistent states; up to
   a constant in the potential, the Lagrangian, V_eff and conserved quantities). An equation
   (``equations``, ``constraints``) is correct up to a constant factor; equations are compared as functions
   of the coordinates, velocities, accelerations and multipliers (the last two drawn at random too).
2. **follows** — not the key's answer, but what follows from the student's own earlier steps (:mod:`.follow`,
   :mod:`.follow_analysis`): their Lagrangian (their T − V when they give no L) gives their momenta, ∂L/∂q,
   equations and H, and through lagsolve's analysis their V_eff, equilibria and ω²; their equations, with the
   key's constraints at acceleration level, give their q̈ (along which their conserved quantities are checked)
   and λ; their λ gives their forces of constraint and normal forces.
3. **incorrect** — with a named mistake when one explains the difference (:mod:`.mistakes`): check's own
   diagnoses (opposite sign, constant factor, λ convention, a constraint released, a magnitude without
   ``Abs``), a moving constraint taken as still, then the key's answer changed in one known way (the
   potential's sign, one term's sign, the velocity-squared terms dropped, one kinetic term dropped, λ's sign in
   an equation), then a wrong dimension (:mod:`.dimensions`).

A step's points are its weight shared among its entries: full for correct, ``follow_through`` times it for
follows. Each step is graded under a CPU budget (``step_budget``): one that uses it up is ``ungraded``.
Nothing is printed here.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath
import sympy

from lagsolve.check.compare import STATES, TRIVIALLY, Comparer
from lagsolve.check.diagnose import ReleasedConstraints, close
from lagsolve.grade.analysis_steps import (
    angle_coordinates,
    key_lists,
    monomial,
    ratio,
    reduction_constants,
)
from lagsolve.grade.dimensions import INHOMOGENEOUS, Dimensions
from lagsolve.grade.evaluate import (
    DIFFERS,
    FACTOR,
    MINIMUM_STATES,
    OFFSET,
    OPPOSITE,
    SAME,
    SIGN_DEPENDENT,
    UNDECIDED,
    Evaluator,
    Relation,
    constant_in_groups,
    normal_to_surface,
    proportional,
    relation,
)
from lagsolve.grade.follow import follow_through
from lagsolve.grade.follow_analysis import FAILURES, own_analysis
from lagsolve.grade.frame import CARRIED, Frame, answers_in_frame, own_in_key
from lagsolve.grade.key import Grading
from lagsolve.grade.lists import ListSteps
from lagsolve.grade.mistakes import (
    ABS,
    DIMENSION,
    DROPPED,
    FACTOR_MISSING,
    LAMBDA,
    MISTAKES,
    MOVING,
    POTENTIAL_SIGN,
    SIGN,
    candidates,
    flip_multipliers,
    moving,
    moving_answers,
    moving_evidence,
    still_constraint,
)
from lagsolve.grade.numeric_lists import simulation_values
from lagsolve.grade.status import (
    CORRECT,
    FOLLOWS,
    INCORRECT,
    MISSING,
    UNGRADED,
    UNREADABLE,
    GradeStatus,
)
from lagsolve.grade.status import Entry as _Entry
from lagsolve.grade.status import (
    label as _label,
)
from lagsolve.grade.submission import LISTS, STEPS, Submission, names_for
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.equations.constraints import velocity_form
from lagsolve.mechanics.stages import StageTimeout, cpu_limit
from lagsolve.mechanics.symbolic.simplify import reproducible
from lagsolve.problem.names import momentum_name

__all__ = ["MISTAKES", "ClassGrades", "GradeStatus", "GradingKey", "StepGrade", "SubmissionGrade", "grade",
           "key_answers", "unreadable_grade"]

#: steps whose answers may differ from the key's by a constant
SHIFTS = ("potential", "lagrangian", "conserved", "effective_potential", "hamiltonian")
#: steps graded only when the key's derivation has the result, and what it is called
NO_KEY = {"effective_potential": "effective potential", "hamiltonian": "Hamiltonian",
          "equilibria": "equilibria", "frequencies": "frequencies of small oscillations"}


@dataclass(frozen=True)
class StepGrade:
    """The grade of one step: ``status``, ``mistake`` (a name of :data:`MISTAKES` or None), points; ``answer`` is
    the submission's text of the entry the mistake was found in (hostile text: only for the class summary)."""

    step: str
    status: GradeStatus
    mistake: str | None
    points: float
    max_points: float
    message: str
    answer: str = ""


@dataclass(frozen=True)
class SubmissionGrade:
    """The grades of one submission; ``error`` is set (and every step unreadable) when the file could not be
    read at all."""

    student: str
    source: str
    steps: tuple[StepGrade, ...]
    error: str = ""

    @property
    def points(self) -> float:
        return round(sum(s.points for s in self.steps), 6)

    @property
    def max_points(self) -> float:
        return round(sum(s.max_points for s in self.steps), 6)


@dataclass(frozen=True)
class ClassGrades:
    """The key (its name and file) and one grade per submission, in the order given."""

    key: str
    source: str
    grades: tuple[SubmissionGrade, ...]

    @property
    def unreadable(self) -> int:
        """How many submission files could not be read at all."""
        return sum(1 for g in self.grades if g.error)


def unreadable_grade(student: str, source: str, message: str, grading: Grading) -> SubmissionGrade:
    """Every weighted step unreadable: the file could not be read (``message`` says where and why)."""
    steps = tuple(StepGrade(s, UNREADABLE, None, 0.0, w, message) for s, w in _weighted(grading))
    return SubmissionGrade(student, source, steps, message)


def _weighted(grading: Grading) -> list[tuple[str, float]]:
    return [(s, grading.weights[s]) for s in STEPS if s in grading.weights]


def key_answers(derivation: Derivation) -> dict[str, dict[str, Any]]:
    """The key's answer to each step, entry by entry (absent where the derivation gives none)."""
    model, terms = derivation.model, derivation.lagrange
    names = [q.name for q in derivation.problem.coordinates]
    out: dict[str, dict[str, Any]] = {
        "kinetic": {"": model.kinetic}, "potential": {"": model.potential}, "lagrangian": {"": model.lagrangian},
        "constraints": {c.name: c.expression for c in derivation.constraints},
        "momenta": dict(zip(names, terms.momenta, strict=True)),
        "generalized_forces": dict(zip(names, terms.gradients, strict=True)),
        "equations": dict(zip(names, terms.equations, strict=True)),
    }
    if derivation.accelerations is not None:
        out["accelerations"] = dict(derivation.accelerations)
    if derivation.multipliers is not None:
        out["multipliers"] = dict(derivation.multipliers)
    if derivation.constraint_forces is not None:
        out["constraint_forces"] = {k: f.magnitude for k, f in derivation.constraint_forces.items()
                                    if f.magnitude is not None}
    out["normal_force"] = {f.term.name: f.normal_force for f in derivation.friction}
    if derivation.conserved is not None:
        out["conserved"] = {k: v for k, v in derivation.conserved.items() if isinstance(v, sympy.Basic)}
    potential = derivation.effective_potential
    if potential is not None and isinstance(potential.get("expression"), sympy.Basic):
        out["effective_potential"] = {str(potential["coordinate"]): potential["expression"]}
    if derivation.hamiltonian is not None:
        out["hamiltonian"] = {"": derivation.hamiltonian.expression}
    points, squares = key_lists(derivation)
    if points:
        out["equilibria"] = {str(i + 1): p for i, p in enumerate(points)}
    if squares:
        out["frequencies"] = {str(i + 1): w for i, w in enumerate(squares)}
    return out


def grade(derivation: Derivation, grading: Grading, submission: Submission, *, seed: int = 0,
          key: GradingKey | None = None) -> SubmissionGrade:
    """Grade ``submission`` against the key ``derivation`` with the key's ``grading``; pass the same
    :class:`GradingKey` for every submission of a class (the states and the key's values are then made once)."""
    reproducible()
    if key is None or key.derivation is not derivation or key.grading != grading or key.seed != seed:
        key = GradingKey(derivation, grading, seed)
    return _Grader(key, submission).run()


class GradingKey:
    """What grading needs of the key, made once per class: its answers, the shared random states and the
    values of every expression at them (:class:`~lagsolve.grade.evaluate.Evaluator`), the answers a known
    mistake would give, and what follows from each distinct student Lagrangian and set of equations."""

    def __init__(self, derivation: Derivation, grading: Grading, seed: int = 0) -> None:
        self.derivation, self.grading, self.seed = derivation, grading, seed
        self.answers = key_answers(derivation)
        self.coordinates = [q.name for q in derivation.problem.coordinates]
        self.comparer = Comparer(derivation, [], STATES, seed)  # check's preparation and rate of a quantity
        self._values: Evaluator | None = None
        self._equations: Evaluator | None = None
        self._canonical: Evaluator | None = None
        self._released: ReleasedConstraints | None = None
        self._follows: dict[Any, dict[str, dict[str, Any]]] = {}
        self._candidates: dict[tuple[str, Any, Any], list[tuple[str, Any, str]]] = {}
        self._angles: set[str] | None = None
        self._frames: dict[tuple, dict[str, dict[str, Any]]] = {}
        self._moving: dict[Any, dict[str, dict[str, Any]]] = {}
        self._analyses: dict[Any, dict[str, dict[str, Any]]] = {}
        self.dimensions = Dimensions(derivation.problem)
        self.simulation = simulation_values(derivation.problem)

    @property
    def angles(self) -> set[str]:
        """The coordinates that appear only inside sines and cosines (their equilibria are equal modulo 2π)."""
        if self._angles is None:
            self._angles = angle_coordinates(self.derivation)
        return self._angles

    @property
    def values(self) -> Evaluator:
        """Quantities, prepared as check prepares them (multipliers and normal forces put in, constraints used)."""
        if self._values is None:
            derivation = self.derivation
            names = names_for(derivation.problem, normals={f.term.normal.name: f.term.normal
                                                           for f in derivation.friction})
            symbols = [*names.symbols.values(), *(derivation.multipliers or {}).values()]
            extra: set[Any] = set()
            for s in symbols:
                with contextlib.suppress(TypeError, ValueError, AttributeError):
                    extra |= self.comparer.prepare(sympy.sympify(s, strict=True)).free_symbols
            self._values = Evaluator(derivation, extra, self.seed, self.comparer.prepare)
        return self._values

    @property
    def canonical(self) -> Evaluator:
        """Functions of the coordinates and momenta (H): the momenta p_q random anew at each state, so that a
        constant (in H up to a constant) cannot depend on them."""
        if self._canonical is None:
            derivation = self.derivation
            names = names_for(derivation.problem)
            momenta = [names.symbols[momentum_name(q.name)] for q in derivation.problem.coordinates]
            constants = reduction_constants(derivation)

            def prepare(expr: Any) -> Any:
                return self.comparer.prepare(expr.xreplace(constants))

            self._canonical = Evaluator(derivation, momenta, self.seed, prepare, varying=True)
        return self._canonical

    @property
    def equations(self) -> Evaluator:
        """Residuals of equations, with random accelerations, multipliers and normal forces (new ones at each
        state, so that a constant factor between two equations cannot depend on them)."""
        if self._equations is None:
            derivation = self.derivation
            model = derivation.model
            normals = [f.term.normal for f in derivation.friction]
            extra = [*model.accelerations, *derivation.multiplier_symbols, *normals]

            def prepare(expr: Any) -> Any:
                return derivation.elimination.apply(expr.xreplace(derivation.eliminated_accelerations))

            self._equations = Evaluator(derivation, extra, self.seed, prepare, varying=True)
        return self._equations

    def released(self, coordinate: str, found: Relation) -> str | None:
        """The constraint whose release (λ = 0) gives the student's acceleration, if one does."""
        if self._released is None:
            self._released = ReleasedConstraints(self.derivation, self.values.space)
        with contextlib.suppress(TypeError, ValueError, ZeroDivisionError):
            return self._released.which(coordinate, list(found.rows))
        return None

    def follow_through(self, own: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
        """:func:`_follow_through`, once per distinct set of the student's T, V, L, equations and λ."""
        signature = tuple((step, tuple(sorted(own.get(step, {}).items(), key=lambda kv: kv[0])))
                          for step in ("kinetic", "potential", "lagrangian", "equations", "multipliers"))
        if signature not in self._follows:
            self._follows[signature] = follow_through(self.derivation, own, set(self.grading.weights))
        return self._follows[signature]

    def own_analysis(self, lagrangian: Any) -> dict[str, dict[str, Any]]:
        """What lagsolve's analysis gives from a student's own L (V_eff, equilibria, ω²), once per distinct L."""
        if lagrangian not in self._analyses:
            self._analyses[lagrangian] = own_analysis(self.derivation, lagrangian)
        return self._analyses[lagrangian]

    def moving(self, frame: Frame | None) -> dict[str, dict[str, Any]]:
        """The answers with the moving constraints taken as still (:func:`~.mistakes.moving_answers`)."""
        signature = frame.signature() if frame is not None else None
        if signature not in self._moving:
            if None not in self._moving:
                self._moving[None] = moving_answers(self.derivation)
            if frame is not None:
                self._moving[signature] = answers_in_frame(self._moving[None], frame)
        return self._moving[signature]

    def in_frame(self, frame: Frame) -> dict[str, dict[str, Any]]:
        """The key's answers in a submission's coordinates (made once per distinct map)."""
        signature = frame.signature()
        if signature not in self._frames:
            self._frames[signature] = answers_in_frame(self.answers, frame)
        return self._frames[signature]

    def candidates(self, step: str, reference: Any, frame: Frame | None = None) -> list[tuple[str, Any, str]]:
        signature = (step, reference, frame.signature() if frame is not None else None)
        if signature not in self._candidates:
            self._candidates[signature] = candidates(step, reference, self.derivation, frame)
        return self._candidates[signature]


class _Grader(ListSteps):
    def __init__(self, key: GradingKey, submission: Submission) -> None:
        self.context, self.submission = key, submission
        self.derivation, self.grading = key.derivation, key.grading
        self.own = {name: step.entries for name, step in submission.steps.items() if step.issue is None}
        self.frame = submission.frame
        self.coordinates = key.coordinates if self.frame is None else list(self.frame.names)
        self._key: dict[str, dict[str, Any]] | None = None
        self._follows: tuple[dict[str, dict[str, Any]], dict[str, dict[str, Any]]] | None = None
        self._analysis: dict[str, dict[str, Any]] | None = None
        self.lost: list[str] = []  # what used up its budget and is left out (follow-through)

    @property
    def key(self) -> dict[str, dict[str, Any]]:
        """The key's answers, in the submission's coordinates."""
        if self._key is None:
            self._key = self.context.answers if self.frame is None else self.context.in_frame(self.frame)
        return self._key

    @property
    def raw_follows(self) -> dict[str, dict[str, Any]]:
        """What follows from the submission's own steps, in the key's coordinates (made on first use, under the
        step's budget: when that runs out here, nothing follows and the later steps are graded without it)."""
        return self._own()[0]

    @property
    def follows(self) -> dict[str, dict[str, Any]]:
        """:attr:`raw_follows` in the submission's coordinates."""
        return self._own()[1]

    def _own(self) -> tuple[dict[str, dict[str, Any]], dict[str, dict[str, Any]]]:
        if self._follows is None:
            self._follows = ({}, {})  # if the budget runs out inside, follow-through is given up
            self.lost.append("follow-through")
            context, frame = self.context, self.frame
            if frame is None:
                raw = context.follow_through(self.own)
                self._follows = (raw, raw)
            else:
                raw = context.follow_through(own_in_key(self.own, frame))
                self._follows = (raw, answers_in_frame(raw, frame))
            self.lost.remove("follow-through")
        return self._follows

    def analysis_follows(self) -> dict[str, dict[str, Any]]:
        """V_eff, equilibria and ω² from the student's own L (their L, else their T − V), in their coordinates."""
        if self._analysis is None:
            self._analysis = {}  # given up if the budget runs out inside
            lagrangian = self.own.get("lagrangian", {}).get("", self.raw_follows.get("lagrangian", {}).get(""))
            found = self.context.own_analysis(lagrangian) if lagrangian is not None else {}
            self._analysis = found if self.frame is None else answers_in_frame(found, self.frame)
        return self._analysis

    def own_answer(self, step: str, name: str) -> Any:
        """What follows from the student's own earlier steps for one entry (None when nothing does)."""
        if step in ("effective_potential", "equilibria", "frequencies"):
            return self.analysis_follows().get(step, {}).get(name)
        return self.follows.get(step, {}).get(name)

    # -- grading

    def run(self) -> SubmissionGrade:
        grades = []
        budget = self.grading.step_budget
        for step, weight in _weighted(self.grading):
            try:
                with cpu_limit(budget):
                    grades.append(self.step(step, weight))
            except StageTimeout:
                grades.append(StepGrade(step, UNGRADED, None, 0.0, weight, f"not graded: comparing this step used up "
                                        f"its {budget:g} s CPU budget (an answer too large to compare); grade it by "
                                        "hand"))
            except FAILURES as error:  # an answer SymPy cannot handle: this step, not the class
                grades.append(StepGrade(step, UNGRADED, None, 0.0, weight, "not graded: the answer could not be "
                                        f"compared ({type(error).__name__}); grade it by hand"))
        return SubmissionGrade(self.submission.student, self.submission.source, tuple(grades))

    def expected_entries(self, step: str) -> list[str]:
        """The entries a step should have: one per coordinate, constraint, contact; the key's conserved names."""
        if step in ("kinetic", "potential", "lagrangian"):
            return [""]
        if step in ("momenta", "generalized_forces", "equations", "accelerations"):
            return self.coordinates
        if step == "conserved":
            return []  # any names: those given are graded
        return list(self.key.get(step, {}))

    def step(self, step: str, weight: float) -> StepGrade:
        read = self.submission.steps.get(step)
        refused = self.refused(step, read, weight)
        if refused is not None:
            return refused
        assert read is not None
        entries = self.listed_step(step, read) if step in LISTS else self.entries(step, read)
        if not entries:
            return StepGrade(step, INCORRECT, None, 0.0, weight, "the step has no entries")
        share = weight / len(entries)
        points = sum(share if e.status == CORRECT else share * self.grading.follow_through if e.status == FOLLOWS
                     else 0.0 for e in entries)
        statuses = {e.status for e in entries}
        status = CORRECT if statuses == {CORRECT} else FOLLOWS if statuses <= {CORRECT, FOLLOWS} else INCORRECT
        mistake = next((e.mistake for e in entries if e.mistake is not None), None)
        message = "; ".join(e.message for e in entries if e.message) or ("equivalent to the key" if status == CORRECT
                                                                         else "")
        example = _example(entries, mistake, read.texts)
        return StepGrade(step, status, mistake, round(points, 6), weight, message, example)

    def refused(self, step: str, read: Any, weight: float) -> StepGrade | None:
        """The grade of a step that is not compared at all (missing, unreadable, nothing in the key to compare
        with, or the key's answer not carried into the submission's coordinates); None for a step to compare."""
        if read is None:
            return StepGrade(step, MISSING, None, 0.0, weight, "not in the submission")
        if read.issue is not None:
            return StepGrade(step, UNREADABLE, None, 0.0, weight, str(read.issue))
        if step in NO_KEY and step not in self.key:
            return StepGrade(step, INCORRECT, None, 0.0, weight, f"the key gives no {NO_KEY[step]} to compare")
        if self.frame is not None and step in CARRIED and step not in self.key:
            return StepGrade(step, INCORRECT, None, 0.0, weight, "the key's answer to this step could not be "
                             "carried into the submission's coordinates (coordinates_map)")
        return None

    def listed_step(self, step: str, read: Any) -> list[_Entry]:
        """The entries of a step that is a list (equilibria, frequencies): against the key's, or, where they are not
        the key's, against what the submission's own Lagrangian gives (follow-through)."""
        entries = self.listed(step, read.entries)
        own = self.analysis_follows().get(step) if any(e.status != CORRECT for e in entries) else None
        if own:
            mine = self.listed(step, read.entries, list(own.values()))
            if all(e.status == CORRECT for e in mine):
                entries = [_Entry(e.name, FOLLOWS, None, "") for e in mine]
                entries[0] = _Entry(entries[0].name, FOLLOWS, None, f"the {step} of the submission's own "
                                    "Lagrangian (its potential and inertia), not the key's")
        return entries

    def entries(self, step: str, read: Any) -> list[_Entry]:
        """The entries of a step by name: each the key expects (or, for a step without expected names, each the
        submission gives), compared."""
        entries: list[_Entry] = []
        for name in self.expected_entries(step) or list(read.entries):
            if name not in read.entries:
                entries.append(_Entry(name, INCORRECT, None, f"{_label(name)}no entry"))
                continue
            entries.append(self.entry(step, name, read.entries[name]))
        return entries

    def relation(self, value: Any, reference: Any, step: str = "") -> Relation:
        values = self.context.canonical if step == "hamiltonian" else self.context.values
        return relation(values.values(value), values.values(reference), values.states)

    def entry(self, step: str, name: str, value: Any) -> _Entry:
        if step in ("equations", "constraints"):
            return self.equation(step, name, value)
        reference = self.key.get(step, {}).get(name)
        if reference is None and step == "conserved" and self.derivation.accelerations is not None:
            return self.conserved(name, value)
        if reference is None:
            return _Entry(name, INCORRECT, None, f"{_label(name)}the key has no such quantity")
        found = self.relation(value, reference, step)
        if found.kind == SAME or (found.kind == OFFSET and step in SHIFTS):
            note = " up to a constant" if found.kind == OFFSET else ""
            return _Entry(name, CORRECT, None, f"{_label(name)}equivalent to the key{note}" if note else "")
        convention = step == "multipliers" and found.kind == OPPOSITE
        if convention and self.grading.lambda_sign == "either":
            return _Entry(name, CORRECT, None, f"{_label(name)}correct in the opposite sign convention of λ (accepted)")
        own = self.own_answer(step, name)
        if own is not None:
            followed = self.relation(value, own, step)
            if followed.kind == SAME or (followed.kind == OFFSET and step in SHIFTS):
                return _Entry(name, FOLLOWS, None, f"{_label(name)}follows from the submission's own earlier steps")
        if step == "conserved" and self.conserved_along_own(value):
            return _Entry(name, FOLLOWS, None, f"{_label(name)}conserved along the submission's own equations of "
                                               "motion")
        mistake, detail = self.diagnose(step, name, found, value, reference)
        return _Entry(name, INCORRECT, mistake, f"{_label(name)}{detail}")

    def conserved(self, name: str, value: Any) -> _Entry:
        """A conserved quantity the key does not name: its rate along the key's equations of motion is 0, and it is
        not the same at every state of a set of parameters (a constant or a constraint, conserved by any motion)."""
        if self.trivial(value):
            return _Entry(name, INCORRECT, None, f"{_label(name)}{TRIVIALLY}")
        values = self.context.values
        with contextlib.suppress(TypeError, ValueError, AttributeError):
            rate = values.values(self.context.comparer.rate(value))
            real = [v for v in rate or () if isinstance(v, mpmath.mpf)]
            if len(real) >= MINIMUM_STATES and all(close(v, 0) for v in real):
                return _Entry(name, CORRECT, None, f"{_label(name)}conserved along the key's equations of motion")
        if self.conserved_along_own(value):
            return _Entry(name, FOLLOWS, None, f"{_label(name)}conserved along the submission's own equations of "
                                               "motion")
        return _Entry(name, INCORRECT, None, f"{_label(name)}not conserved along the key's equations of motion")

    def conserved_along_own(self, value: Any) -> bool:
        """``value`` is not constant at the shared states but its rate along the student's own q̈ (from their
        equations, or their L's, with the key's constraints), which are not the key's, is zero there."""
        own = self.raw_follows.get("accelerations")
        model = self.derivation.model
        if not own or any(q not in own for q in self.context.coordinates):
            return False
        values = self.context.values
        key = self.context.answers.get("accelerations", {})
        if all(q in key and self.relation(own[q], key[q]).kind == SAME for q in self.context.coordinates):
            return False  # no earlier mistake: what the key's motion conserves is graded against the key
        with contextlib.suppress(TypeError, ValueError, AttributeError):
            if self.trivial(value):
                return False  # constant at each value of the parameters: conserved by any equations
            qdd = {a: own[q] for a, q in zip(model.accelerations, self.context.coordinates, strict=True)}
            rate = model.time_derivative(value, second_order=True).xreplace(qdd)
            found = [v for v in values.values(rate) or () if isinstance(v, mpmath.mpf)]
            return len(found) >= MINIMUM_STATES and all(close(v, 0) for v in found)
        return False

    def trivial(self, value: Any) -> bool:
        """``value`` is the same at the shared states of each group (a constant of the parameters, or a constraint,
        on the constraint surface): :meth:`lagsolve.check.compare._Checker.trivial`, which ``lagsolve check`` uses."""
        with contextlib.suppress(TypeError, ValueError, AttributeError):
            return bool(self.context.comparer.trivial(value))
        return False

    def diagnose(self, step: str, name: str, found: Relation, value: Any, reference: Any) -> tuple[str | None, str]:
        """The mistake and a sentence of evidence: how the values relate first, then the candidates."""
        if found.kind == OPPOSITE:
            if step == "potential":
                return POTENTIAL_SIGN, "the potential has the wrong sign (it is −V)"
            if step == "multipliers":
                return LAMBDA, "λ in the opposite sign convention (lagsolve's: d/dt ∂L/∂q̇ − ∂L/∂q = Q + Σ λ a)"
            return SIGN, "has the opposite sign of the key's answer"
        if step in SHIFTS and found.kind in (FACTOR, OFFSET, DIFFERS) and _opposite_up_to_constant(found):
            if step == "potential":
                return POTENTIAL_SIGN, "the potential has the wrong sign (it is −V, up to a constant)"
            return SIGN, "has the opposite sign of the key's answer (up to a constant)"
        if found.kind == SIGN_DEPENDENT:
            return ABS, "agrees only where a quantity is positive: a magnitude written without Abs"
        if step == "accelerations" and found.kind != UNDECIDED:
            released = self.context.released(name, found)
            if released is not None:
                return DROPPED, (f"it is the acceleration with {released} released (λ = 0), as if the motion "
                                 "were free to leave the constraint surface")
        dimension = self.dimension(step, value, reference)
        if found.kind == FACTOR and not dimension.startswith(INHOMOGENEOUS):
            model = self.derivation.model
            moving_symbols = {model.time, *model.coordinates, *model.velocities}
            return FACTOR_MISSING, (f"off by a constant factor{_factor(found, value, reference, moving_symbols)}"
                                    + (f"; {dimension}" if dimension else ""))
        still = self.context.moving(self.frame).get(step, {}).get(name)
        if still is not None and self.relation(value, still, step).kind == SAME:
            return MOVING, moving_evidence(self.derivation)
        for mistake, candidate, detail in self.context.candidates(step, reference, self.frame):
            same = self.relation(value, candidate, step)
            if same.kind == SAME or (same.kind == OFFSET and step in SHIFTS):
                return mistake or None, detail
        if dimension:
            return DIMENSION, dimension
        return None, (self.not_canonical(value, reference) if step == "hamiltonian" else "") or self.differs(found)

    def not_canonical(self, value: Any, reference: Any) -> str:
        """Why an H is not in the key's variables: written with velocities, or in the momenta of other coordinates
        than the key's H ("" when it is in them)."""
        if value.has(*self.derivation.model.velocities):
            return "written with velocities: H is a function of the coordinates and the momenta p_q"
        names = {momentum_name(c.name) for c in self.derivation.problem.coordinates}
        used = sorted(s.name for s in value.free_symbols if s.name in names)
        keys = sorted(s.name for s in reference.free_symbols if s.name in names)
        if not set(used) - set(keys):
            return ""
        return (f"written in {', '.join(used)}: the key's H is in the momenta of its minimal coordinates "
                f"({', '.join(keys) or 'none'}); write H in those")

    def dimension(self, step: str, value: Any, reference: Any) -> str:
        """The evidence of a wrong dimension ("" when none is found): not for H (its momenta have no units here);
        in a step known up to a constant, a bare number added is that constant, not a term of another dimension."""
        if step == "hamiltonian":
            return ""
        if step in SHIFTS and value.is_Add:
            value = sympy.Add(*(t for t in value.args if not t.is_number))
        return self.context.dimensions.differs(value, reference)

    def differs(self, found: Relation) -> str:
        if found.kind == UNDECIDED:
            return "could not be compared with the key's answer (too few states where both are defined)"
        if found.witness is None:
            return "not equivalent to the key's answer"
        row = next(r for r in found.rows if r[0] is found.witness)
        got, want = row[1][0], row[2][0]
        shown = "" if got is None else f": {float(mpmath.re(got)):.4g} where the key has {float(want):.4g}"
        return f"not equivalent to the key's answer (at {self.context.values.describe(found.witness)}{shown})"

    def equation(self, step: str, name: str, value: Any) -> _Entry:
        """An equation (a Lagrange equation, or a constraint), correct up to a constant factor."""
        if step == "constraints":
            return self.constraint(name, value)
        check = self.context.equations

        def same(other: Any) -> bool:
            return proportional(check.values(value), check.values(other), check.states)

        reference = self.key["equations"][name]
        if same(reference):
            return _Entry(name, CORRECT)
        if same(flip_multipliers(reference, self.derivation)):
            if self.grading.lambda_sign == "either":
                return _Entry(name, CORRECT, None, f"{_label(name)}correct in the opposite sign convention of λ "
                                                   "(accepted)")
            return _Entry(name, INCORRECT, LAMBDA, f"{_label(name)}the multiplier terms have the opposite sign "
                                                   "(λ in the other sign convention)")
        own = self.follows.get("equations", {}).get(name)
        if own is not None and same(own):
            return _Entry(name, FOLLOWS, None, f"{_label(name)}follows from the submission's own Lagrangian")
        for mistake, candidate, detail in self.context.candidates("equations", reference, self.frame):
            if same(candidate):
                return _Entry(name, INCORRECT, mistake, f"{_label(name)}{detail}")
        return _Entry(name, INCORRECT, None, f"{_label(name)}not the key's equation, even up to a constant factor")

    def constraint(self, name: str, value: Any) -> _Entry:
        """ψ (or its velocity form) up to a constant factor, symbolically."""
        derivation = self.derivation
        terms = next(c for c in derivation.constraints if c.name == name)
        model = derivation.model
        variables = {model.time, *model.coordinates, *model.velocities}
        for reference in (terms.expression, velocity_form(terms, model)):
            factor = ratio(value, reference)
            if factor is not None and not (factor.free_symbols & variables) and factor != 0:
                return _Entry(name, CORRECT)
        if terms.name in {c.name for c in moving(derivation)}:
            for form in still_constraint(terms, model.time, model):
                factor = ratio(value, form)
                if factor is not None and not (factor.free_symbols & variables) and factor != 0:
                    return _Entry(name, INCORRECT, MOVING, f"{_label(name)}written as if the constraint did not move:"
                                  f" ∂ψ/∂t = {sympy.sstr(terms.offset)} is missing (ψ = "
                                  f"{sympy.sstr(terms.expression)} = 0)")
        if self.frame is not None and self.holds_on_surface(value, terms):
            return _Entry(name, CORRECT, None, f"{_label(name)}holds on the key's constraint surface (in the "
                                               "submission's coordinates)")
        return _Entry(name, INCORRECT, None, f"{_label(name)}not the key's constraint ψ = "
                                             f"{sympy.sstr(terms.expression)} = 0 up to a constant factor")


    def holds_on_surface(self, value: Any, terms: Any) -> bool:
        """ψ (mapped) is zero at every shared state (on the key's constraint surface), not zero everywhere, and its
        gradient there is not zero and is that of the key's constraint ``terms`` (not a double zero, not another
        constraint that holds on the same surface)."""
        values = self.context.values
        found = values.values(value)
        if found is None or len(found) < MINIMUM_STATES or sympy.simplify(value) == 0:
            return False
        if not all(isinstance(v, mpmath.mpf) and close(v, 0) for v in found):
            return False
        model = self.derivation.model
        return normal_to_surface(values, value, [*terms.coefficients, terms.offset], [*model.coordinates, model.time],
                                 model.velocities)


def _example(entries: list[_Entry], mistake: str | None, texts: dict[str, str]) -> str:
    """The text of the first incorrect entry with the step's mistake, as written (``name: text`` in a mapping)."""
    for e in entries:
        if e.status == INCORRECT and e.mistake == mistake and e.name in texts:
            return f"{_label(e.name)}{texts[e.name]}"
    return ""


def _opposite_up_to_constant(found: Relation) -> bool:
    """E + D is constant at the states of each group (and E is not D up to a constant)."""
    rows = [(state, [-e], d) for state, (e,), d in found.rows if isinstance(e, mpmath.mpf)]
    return len(rows) == len(found.rows) and constant_in_groups(rows, additive=True)


def _factor(found: Relation, value: Any = None, reference: Any = None, variables: frozenset | set = frozenset()
            ) -> str:
    """`` (it is k times the key's)`` when the ratio is one small rational number at every state, or a product of
    powers of the parameters (found by cancelling ``value / reference``)."""
    ratios = [r[1][0] / r[2][0] for r in found.rows if isinstance(r[1][0], mpmath.mpf) and abs(r[2][0]) > 1e-20]
    if not ratios or not all(close(v, ratios[0]) for v in ratios):
        factor = ratio(value, reference) if value is not None and reference is not None else None
        if factor is not None and monomial(factor) and sympy.count_ops(factor) <= 12 \
                and not factor.free_symbols & variables:
            return f" (it is {sympy.sstr(factor)} times the key's)"
        return " (a factor that depends on the parameters)"
    guess = Fraction(float(ratios[0])).limit_denominator(1000)
    if not close(mpmath.mpf(guess.numerator) / guess.denominator, ratios[0]):
        return ""
    return f" (it is {sympy.sstr(sympy.Rational(guess.numerator, guess.denominator))} times the key's)"
