"""Read a submission for ``lagsolve grade`` (the contract: ``docs/grading.md``).

A submission is a small YAML file: ``student`` (an id; the file's stem when absent) and ``steps``, any
subset of :data:`STEPS`. Student text is hostile input: the YAML is read by the problem format's safe
reader (:func:`lagsolve.problem.yamlread.read_document`) and every expression by its only gateway
(:func:`lagsolve.problem.expr.parse`), with the key problem's names. A step that cannot be read keeps an
:class:`~lagsolve.errors.Issue` (file, line, field, what is wrong, how to fix it) and the other steps are
read on; a file that cannot be read at all raises :class:`~lagsolve.errors.SpecError`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import sympy

from lagsolve.errors import ExpressionError, Issue, SpecError
from lagsolve.files import read_input
from lagsolve.grade.frame import Frame, MapError, build_frame
from lagsolve.mechanics.stages import StageTimeout, cpu_limit
from lagsolve.problem import expr as gateway
from lagsolve.problem.names import momentum_name, momentum_symbol
from lagsolve.problem.readers.base import line_of
from lagsolve.problem.schema import Problem
from lagsolve.problem.yamlread import MAX_BYTES, SUBMISSION, Document, dotted, kind_of, read_document

#: the steps a submission may contain, in the order of a derivation (names fixed by the contract)
STEPS = ("kinetic", "potential", "lagrangian", "constraints", "momenta", "generalized_forces", "equations",
         "accelerations", "multipliers", "constraint_forces", "normal_force", "conserved", "effective_potential",
         "equilibria", "frequencies", "hamiltonian")
#: one expression
SCALAR = ("kinetic", "potential", "lagrangian", "hamiltonian")
#: one expression per coordinate, per constraint, per friction contact
PER_COORDINATE = ("momenta", "generalized_forces", "equations", "accelerations")
PER_CONSTRAINT = ("constraints", "multipliers", "constraint_forces")
PER_CONTACT = ("normal_force",)
#: steps whose entries may be written ``lhs = rhs`` (read as lhs − rhs)
EQUATIONS = ("constraints", "equations")
#: the steps whose answers are functions of the state (t, q, q̇): no multiplier, no momentum in them
STATE_STEPS = ("accelerations", "multipliers", "constraint_forces", "normal_force", "conserved")
#: lists compared as a set (equilibria) or a multiset (frequencies): entries are named 1, 2, ... in order
LISTS = ("equilibria", "frequencies")
#: most items in a list step
MAX_ITEMS = 32
MAX_NAME = 200
#: CPU seconds to make a coordinates_map's chain rule (its Jacobian and inverse)
MAP_BUDGET = 10.0


@dataclass(frozen=True)
class Step:
    """One step of a submission: ``entries`` maps an entry name (a coordinate, a constraint, a quantity;
    ``""`` for a single expression) to its SymPy expression; ``issue`` says why the step cannot be read;
    ``texts`` keeps each entry as written (hostile text: for a class summary's examples, escaped there)."""

    name: str
    entries: dict[str, Any] = field(default_factory=dict)
    issue: Issue | None = None
    line: int = 0
    texts: dict[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class Submission:
    """A read submission: the student's id, the file, and the steps it contains (by name); ``frame`` is the
    change of coordinates of its ``coordinates_map:`` (None in the key's coordinates), every entry already
    mapped into the key's coordinates."""

    student: str
    source: str
    steps: dict[str, Step]
    frame: Frame | None = None


def names_for(problem: Problem, contacts: tuple[str, ...] = (), normals: dict[str, Any] | None = None,
              *, accelerations: bool = False, frame: Frame | None = None, state: bool = False,
              multipliers: bool = True) -> gateway.Namespace:
    """The names a submission's expressions may use: the key's own (``expected:``'s) plus, in the equations,
    the accelerations ``q_ddot``, and ``N_<contact>``; with a ``frame``, the student's coordinates too (their
    ``_dot``, ``_ddot`` and ``p_`` names). With ``state`` (a step whose answer is a function of the state:
    :data:`STATE_STEPS`) the momenta ``p_<q>`` are refused (one was read as a constant), and without
    ``multipliers`` the multipliers ``lambda_<c>`` too (``multipliers: {rod: lambda_rod}`` restated what is asked
    and was graded correct; a force of constraint may be written λ∇ψ, as in ``expected:``)."""
    symbols = dict(problem.symbols)  # (the loader refuses a declared lambda_<c> or p_<q>)
    forbidden: dict[str, str] = {}
    multiplier_names = {f"lambda_{c.name}": sympy.Symbol(f"lambda_{c.name}", real=True) for c in problem.constraints}
    momentum_names = {momentum_name(q.name): momentum_symbol(q.name) for q in problem.coordinates}
    if state and not multipliers:
        forbidden |= dict.fromkeys(multiplier_names, "a multiplier is allowed only in equations and constraint_forces;"
                                   " write the answer in t, the parameters, coordinates and velocities")
    else:
        symbols |= multiplier_names
    if state:
        forbidden |= dict.fromkeys(momentum_names, "a momentum is not allowed here; write it in the velocities")
    else:
        symbols |= momentum_names
    symbols.update(normals or {})
    ddots = [(q.acceleration.name, q.acceleration) for q in problem.coordinates]
    if frame is not None:
        for own in frame.coordinates:
            symbols.update({own.name: own.symbol, own.velocity.name: own.velocity})
            if state:
                forbidden[own.momentum.name] = "a momentum is not allowed here; write it in the velocities"
            else:
                symbols[own.momentum.name] = own.momentum
        ddots += [(own.acceleration.name, own.acceleration) for own in frame.coordinates]
    for name, acceleration in ddots:
        if accelerations:
            symbols[name] = acceleration
        else:
            forbidden[name] = "accelerations may appear only in the equations step"
    return gateway.Namespace(symbols, {f.name: f.function for f in problem.functions}, forbidden)


def read_submission(path: str | Path, problem: Problem, normals: dict[str, Any] | None = None) -> Submission:
    """Read the submission file ``path`` against the key ``problem`` (see :func:`read_text`)."""
    path = Path(path)
    try:
        raw = read_input(path, MAX_BYTES)  # at most one byte over the limit: /dev/zero or a pipe never hangs here
    except OSError as error:
        raise SpecError([Issue(str(path), 0, "", f"cannot read the file: {error.strerror or error}",
                               "check the path")]) from None
    return read_text(raw, problem, str(path), path.stem, normals)


def read_text(raw: bytes | str, problem: Problem, source: str = "<text>", stem: str = "",
              normals: dict[str, Any] | None = None) -> Submission:
    """Read a submission's text.

    ``normals`` maps ``N_<contact>`` to the key's normal-force symbols.

    Raises
    ------
    SpecError
        The file is not one YAML mapping with ``steps`` (nothing in it can be graded).
    """
    document = read_document(raw.encode("utf-8") if isinstance(raw, str) else raw, source, SUBMISSION)
    return _Reader(document, problem, source, normals or {}).submission(stem or "student")


class _Reader:
    def __init__(self, document: Document, problem: Problem, source: str, normals: dict[str, Any]) -> None:
        self.data, self.lines, self.problem, self.source = document.data, document.lines, problem, source
        self.normals = normals
        self.frame: Frame | None = None
        self.plain = names_for(problem, normals=normals)
        self.state = names_for(problem, normals=normals, state=True, multipliers=False)
        self.forces = names_for(problem, normals=normals, state=True)
        self.with_accelerations = names_for(problem, normals=normals, accelerations=True)
        self.coordinates = tuple(q.name for q in problem.coordinates)

    def line(self, path: tuple) -> int:
        return line_of(self.lines, path)

    def issue(self, path: tuple, message: str, hint: str = "") -> Issue:
        return Issue(self.source, self.line(path), dotted(path), message, hint)

    def submission(self, stem: str) -> Submission:
        data = self.data
        if not isinstance(data, dict):
            raise SpecError([self.issue((), f"expected a mapping with 'student' and 'steps', found {kind_of(data)}",
                                        "see docs/grading.md for the submission format")])
        unknown = [k for k in data if k not in ("student", "steps", "coordinates_map")]
        if unknown:
            raise SpecError([self.issue((unknown[0],), f"unknown key {unknown[0]!r}",
                                        "a submission has only 'student', 'steps' and 'coordinates_map'")])
        if "coordinates_map" in data:
            self.read_map(data["coordinates_map"])
        student = data.get("student", stem)
        if isinstance(student, int) and not isinstance(student, bool):
            student = str(student)
        if not isinstance(student, str) or not student.strip() or len(student) > MAX_NAME or "\n" in student:
            raise SpecError([self.issue(("student",), f"expected a one-line id, found {kind_of(student)}",
                                        "write e.g. 'student: ada_lovelace'")])
        steps = data.get("steps")
        if not isinstance(steps, dict):
            raise SpecError([self.issue(("steps",), f"expected a mapping of steps, found {kind_of(steps)}",
                                        f"write 'steps:' with any of: {', '.join(STEPS)}")])
        out: dict[str, Step] = {}
        for name, value in steps.items():
            path = ("steps", name)
            if name not in STEPS:
                raise SpecError([self.issue(path, f"unknown step {name!r}", f"the steps are: {', '.join(STEPS)}")])
            out[name] = self.step(name, value, path)
        return Submission(student.strip(), self.source, out, self.frame)

    def read_map(self, spec: Any) -> None:
        """``coordinates_map:``: each student coordinate as an expression of the key's coordinates and t."""
        path = ("coordinates_map",)
        example = "write e.g. 'coordinates_map: {phi: theta - pi}' (each of your coordinates in the key's)"
        if not isinstance(spec, dict) or not spec or len(spec) > MAX_ITEMS:
            raise SpecError([self.issue(path, f"expected a mapping of coordinates, found {kind_of(spec)}", example)])
        problem = self.problem
        keys = {q.name for q in problem.coordinates}
        taken = set(self.plain.symbols) | set(self.with_accelerations.symbols) | {f.name for f in problem.functions}
        parsed = {}
        for name, text in spec.items():
            where = (*path, name)
            why = gateway.name_problem(name) if isinstance(name, str) else "a name must be a string"
            if why is None and name not in keys and any(n in taken for n in (name, f"{name}_dot", f"{name}_ddot",
                                                                              momentum_name(name))):
                why = f"{name!r} (or its _dot, _ddot, p_ name) is already a name of the key"
            if why is not None:
                raise SpecError([self.issue(where, why, "name your coordinate with a new word")])
            try:
                parsed[name] = gateway.parse(text, self.plain)
            except ExpressionError as error:
                raise SpecError([self.issue(where, error.message, error.hint)]) from None
        qs = tuple(q.symbol for q in problem.coordinates)
        try:
            with cpu_limit(MAP_BUDGET):
                self.frame = build_frame(parsed, dict(problem.symbols), problem.time, qs,
                                         tuple(q.velocity for q in problem.coordinates),
                                         tuple(q.acceleration for q in problem.coordinates))
        except StageTimeout:
            raise SpecError([self.issue(path, f"the map is too large to use (its Jacobian was not inverted within "
                                              f"{MAP_BUDGET:g} s of CPU)", example)]) from None
        except MapError as error:
            raise SpecError([self.issue(path, str(error), example)]) from None
        except (TypeError, ValueError, ZeroDivisionError, NotImplementedError):
            raise SpecError([self.issue(path, "the map is not a change of coordinates that can be used", example)]
                            ) from None
        self.plain = names_for(problem, normals=self.normals, frame=self.frame)
        self.state = names_for(problem, normals=self.normals, frame=self.frame, state=True, multipliers=False)
        self.forces = names_for(problem, normals=self.normals, frame=self.frame, state=True)
        self.with_accelerations = names_for(problem, normals=self.normals, accelerations=True, frame=self.frame)
        self.coordinates = self.frame.names

    def step(self, name: str, value: Any, path: tuple) -> Step:
        line = self.line(path)
        try:
            entries = self.entries(name, value, path)
        except _Unreadable as bad:
            return Step(name, {}, bad.issue, line)
        return Step(name, entries, None, line, _texts(name, value, entries))

    def entries(self, name: str, value: Any, path: tuple) -> dict[str, Any]:
        if name in SCALAR:
            parsed = self.expression(value, path, self.plain)
            if self.frame is not None and name == "hamiltonian":
                self.mapped(parsed, path)  # refused like the others when it cannot be written in the key's
                return {"": self.frame.hamiltonian(parsed)}
            return {"": self.mapped(parsed, path)}
        if name in LISTS:
            return self.items(name, value, path)
        if name == "effective_potential":
            spec = self.mapping(value, path, "{coordinate: r, expression: ...}")
            self.known(path, spec, ("coordinate", "expression"), "the keys")
            coordinate = spec.get("coordinate")
            coordinates = list(self.coordinates)
            if coordinate not in coordinates:
                raise _Unreadable(self.issue((*path, "coordinate"), f"unknown coordinate {coordinate!r}",
                                             f"the coordinates are: {', '.join(coordinates)}"))
            if "expression" not in spec:
                raise _Unreadable(self.issue(path, "no 'expression'", "write the effective potential as 'expression'"))
            where = (*path, "expression")
            return {coordinate: self.mapped(self.expression(spec["expression"], where, self.plain), where)}
        spec = self.mapping(value, path, "{name: expression, ...}")
        known: tuple[str, ...] = ()
        what = "names"
        if name in PER_COORDINATE:
            known, what = self.coordinates, "coordinates"
        elif name in PER_CONSTRAINT:
            known, what = tuple(c.name for c in self.problem.constraints), "constraints"
        elif name in PER_CONTACT:
            known, what = tuple(f.name for f in self.problem.friction), "friction contacts"
        if known:
            self.known(path, spec, known, what)
        names = {"equations": self.with_accelerations, "constraint_forces": self.forces}.get(
            name, self.state if name in STATE_STEPS else self.plain)
        out = {}
        for key, text in spec.items():
            if not isinstance(key, str) or not key or len(key) > MAX_NAME:
                raise _Unreadable(self.issue(path, f"{key!r} is not a name", "write names as plain words"))
            out[key] = self.mapped(self.expression(text, (*path, key), names, equation=name in EQUATIONS), (*path, key))
        return out

    def items(self, name: str, value: Any, path: tuple) -> dict[str, Any]:
        """A list step: ``equilibria`` as points (a mapping coordinate → value, or a bare value for a system
        with one coordinate left: a tuple of (coordinate or "", expression) pairs), ``frequencies`` as
        expressions (ω² or ω); one item may be written without the list."""
        items = value if isinstance(value, list) else [value]
        example = ("[{theta1: 0, theta2: 0}, ...] or, with one coordinate, [0, pi, ...]" if name == "equilibria"
                   else '["g/l", "g/l + 2*k/m"]')
        if not items or len(items) > MAX_ITEMS:
            raise _Unreadable(self.issue(path, f"expected a list of 1 to {MAX_ITEMS} items, found {len(items)}",
                                         f"write {example}"))
        coordinates = self.coordinates
        out: dict[str, Any] = {}
        for i, item in enumerate(items):
            where = (*path, i) if isinstance(value, list) else path
            if name == "equilibria":
                item, where = _as_expected(item, where, coordinates)
            if name == "frequencies" or not isinstance(item, dict):
                if isinstance(item, dict | list):
                    raise _Unreadable(self.issue(where, f"expected an expression, found {kind_of(item)}",
                                                 f"write {example}"))
                parsed = self.expression(item, where, self.plain)
                out[str(i + 1)] = parsed if name == "frequencies" else (("", parsed),)
                continue
            if not item:
                raise _Unreadable(self.issue(where, "an equilibrium with no coordinate", f"write {example}"))
            self.known(where, item, coordinates, "coordinates")
            out[str(i + 1)] = tuple((q, self.expression(item[q], (*where, q), self.plain)) for q in item)
        return out

    def mapped(self, expr: Any, path: tuple) -> Any:
        """``expr`` in the key's coordinates (the student's put in through the map)."""
        if self.frame is None:
            return expr
        try:
            return self.frame.entry(expr)
        except (TypeError, ValueError, AttributeError):
            raise _Unreadable(self.issue(path, "cannot be written in the key's coordinates (a derivative with respect "
                                               "to one of your coordinates that the map replaces)",
                                         "write that derivative with the key's coordinate")) from None

    def mapping(self, value: Any, path: tuple, example: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise _Unreadable(self.issue(path, f"expected a mapping, found {kind_of(value)}", f"write {example}"))
        return value

    def known(self, path: tuple, spec: dict[str, Any], known: tuple[str, ...], what: str) -> None:
        for key in spec:
            if key not in known:
                raise _Unreadable(self.issue((*path, key), f"unknown name {key!r}",
                                             f"the {what} are: {', '.join(known) or 'none'}"))

    def expression(self, text: Any, path: tuple, names: gateway.Namespace, *, equation: bool = False) -> Any:
        try:
            if equation and isinstance(text, str) and "=" in text:
                sides = _sides(text)
                if sides is None:
                    raise ExpressionError("an equation has one '=' between its two sides",
                                          "write 'lhs = rhs' or one expression equal to 0")
                return gateway.parse(sides[0], names) - gateway.parse(sides[1], names)
            return gateway.parse(text, names)
        except ExpressionError as error:
            raise _Unreadable(self.issue(path, error.message, error.hint)) from None


#: an equilibrium written as in a problem file's ``expected:`` (the contract): the point under this key, and the
#: other keys allowed beside it (read, not graded here: stability is not a step, ω² is ``frequencies``)
EXPECTED_FORMS = {"value": ("stable", "frequency"), "at": ("stable", "squared_frequencies", "shapes")}


def _as_expected(item: Any, where: tuple, coordinates: tuple[str, ...] | list[str]) -> tuple[Any, tuple]:
    """An equilibrium item as ``expected:`` writes it — ``{value: q0, stable: ..., frequency: ...}`` (the effective
    potential's) or ``{at: {q: value}, stable: ..., squared_frequencies: [...]}`` (normal modes') — as its point
    (and where it is); any other item as it is (a mapping whose keys are all coordinates is a point)."""
    if not isinstance(item, dict) or all(k in coordinates for k in item):
        return item, where
    for point, others in EXPECTED_FORMS.items():
        if point in item and all(k == point or k in others for k in item):
            return item[point], (*where, point)
    return item, where


def _texts(name: str, value: Any, entries: dict[str, Any]) -> dict[str, str]:
    """Each read entry as the student wrote it (``value`` is the step's YAML, already read without error)."""
    if name in SCALAR:
        return {"": str(value)}
    if name == "effective_potential":
        return {k: str(value["expression"]) for k in entries}
    if name in LISTS:
        items = value if isinstance(value, list) else [value]
        return {str(i + 1): _shown(item) for i, item in enumerate(items)}
    return {k: str(value[k]) for k in entries if k in value}


def _shown(item: Any) -> str:
    """A list step's item as written: ``theta1: 0, theta2: pi`` for a point."""
    if isinstance(item, dict):
        return ", ".join(f"{k}: {v}" for k, v in item.items())
    return str(item)


def _sides(text: str) -> tuple[str, str] | None:
    """``lhs = rhs`` split at its one ``=`` (None when there are several, or a comparison like ``==``)."""
    parts = re.split(r"=", text)
    if len(parts) != 2 or any(not p.strip() for p in parts) or re.search(r"[<>!]$", parts[0]):
        return None
    return parts[0], parts[1]


class _Unreadable(Exception):
    def __init__(self, issue: Issue) -> None:
        self.issue = issue
        super().__init__(str(issue))
