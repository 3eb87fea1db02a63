"""The analysis sections of a report, as data: how each constraint integrates, the minimal coordinates,
the conserved quantities, the effective potential with its equilibria, the steady motions and the normal modes.

Built once by :func:`analysis_section`. Every field says how each format shows it
(:func:`lagsolve.render.model.shown`): the templates (``templates/*/_analysis.*.j2``), the JSON key ``analysis``
and the terminal lines (``templates/text/_analysis.txt.j2``) are all :func:`lagsolve.render.model.present` of the
one record. Each record holds the expressions a report shows (an equilibrium's conditions already in the symbol
of its value, q₀) and, where the JSON contract gives them as derived (in q), those too, as records the templates
do not see. A layout one format needs is a value that prints itself (:class:`Pfaffian`, :class:`Indices`,
:class:`ModeShape`, :class:`Agreement`). Nothing here simplifies.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy

from lagsolve.enums import TextEnum
from lagsolve.mechanics.analysis.integrability import Integrability
from lagsolve.render.model import Expr, Printer, Rows, shown

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.equilibria import EffectivePotential
    from lagsolve.mechanics.analysis.integrability import Classification
    from lagsolve.mechanics.analysis.linearize import Linearization
    from lagsolve.mechanics.analysis.minimal import ReducedSystem
    from lagsolve.mechanics.analysis.steady import SteadyMotion
    from lagsolve.mechanics.results import Derivation

_STRINGS: dict[str, Any] = {"type": "array", "items": {"type": "string"}}


# -- values that print themselves -----------------------------------------------------------------


class Agreement(TextEnum):
    """How the equations in minimal coordinates compare with the multiplier route: the JSON writes the word;
    the templates and the terminal get it with its sentence (the same in every report format), whether that is
    a warning, and the terminal's phrase (:data:`AGREEMENT`)."""

    SYMBOLIC = "symbolic"
    UNCHECKED = "unchecked"
    NUMERIC = "numeric"
    DIFFER = "differ"

    @property
    def phrase(self) -> str:
        return AGREEMENT[self.value][0]

    @property
    def sentence(self) -> str:
        return AGREEMENT[self.value][1]

    @property
    def warning(self) -> bool:
        return AGREEMENT[self.value][2]

    def present(self, printer: Printer) -> Any:
        if printer.kind == "json":
            return self.value
        return {"kind": self.value, "phrase": self.phrase, "sentence": self.sentence, "warning": self.warning}


#: each :class:`Agreement`: the terminal's phrase, the reports' sentence, and whether it is a warning
AGREEMENT: dict[str, tuple[str, str, bool]] = {
    "symbolic": ("agrees with the multiplier route",
                 "Solved for the accelerations they give exactly the accelerations of the multiplier route above, "
                 "with the same substitutions (checked symbolically):", False),
    "unchecked": ("not compared with the multiplier route (it has no explicit accelerations)",
                  "Solved for the accelerations they give (the multiplier route has no explicit accelerations to "
                  "compare with here):", False),
    "numeric": ("agrees with the multiplier route (numerically)",
                "Solved for the accelerations they agree with the multiplier route above at random states "
                "(the symbolic check was inconclusive):", False),
    "differ": ("DIFFERS from the multiplier route",
               "solved for the accelerations they differ from the multiplier route above; please report this as a "
               "bug:", True),
}


@dataclass(frozen=True)
class Pfaffian:
    """A velocity constraint's Pfaffian form Σ w dx: in LaTeX ``a dq_1 + ... + b dt`` with zero terms left out,
    elsewhere the sum of the terms w·dx (a template value: the JSON does not write it)."""

    differential: tuple[tuple[Any, Any], ...]  # (coefficient, variable)

    def present(self, printer: Printer) -> str:
        if printer.kind != "latex":
            return printer.expr(sum((w * sympy.Symbol(f"d{x.name}") for w, x in self.differential), sympy.Integer(0)))
        out = ""
        for w, x in self.differential:
            if w == 0:
                continue
            negative = not isinstance(w, sympy.Add) and w.could_extract_minus_sign()
            size = -w if negative else w
            coefficient = "" if size == 1 else (r"\left(" + printer.expr(size) + r"\right)\,"
                                                if isinstance(size, sympy.Add) else printer.expr(size) + r"\,")
            sign = ("-" if negative else "") if not out else (" - " if negative else " + ")
            out += f"{sign}{coefficient}d{printer.expr(x)}"
        return out or "0"


@dataclass(frozen=True)
class Indices:
    """The variables of a component of ω∧dω: a list in the JSON, the subscript ``xyt`` (``x,y,t`` when a name
    is longer than one character) in the templates."""

    variables: tuple[Any, ...]

    SCHEMA: ClassVar[dict[str, Any]] = _STRINGS

    def present(self, printer: Printer) -> Any:
        printed = [printer.expr(x) for x in self.variables]
        if printer.kind == "json":
            return printed
        return "".join(printed) if all(len(p) == 1 for p in printed) else ",".join(printed)


@dataclass(frozen=True)
class ModeShape:
    """A normal mode's shape u: by coordinate in the JSON, a row (1, -1) in the templates and the terminal."""

    coordinates: tuple[Any, ...]
    components: tuple[Any, ...]

    SCHEMA: ClassVar[dict[str, Any]] = {"type": "object", "additionalProperties": {"type": "string"}}

    def present(self, printer: Printer) -> Any:
        if printer.kind == "json":
            return {q.name: printer.expr(x) for q, x in zip(self.coordinates, self.components, strict=True)}
        if printer.kind == "latex":
            return r"\left(" + ", ".join(printer.expr(c) for c in self.components) + r"\right)"
        return printer.expr(sympy.Tuple(*self.components))


# -- records --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Binding:
    """``symbol`` = ``value`` (a coordinate, velocity or momentum and what it equals); ``{name: value}`` in the
    JSON where a field lists them ``keyed``."""

    symbol: Expr = shown(json=None, terminal=True)
    value: Expr = shown(terminal=True)


@dataclass(frozen=True)
class Witness:
    """A non-zero component of ω∧dω: the constraint is nonholonomic (Frobenius)."""

    variables: Indices = shown()
    value: Expr = shown()


@dataclass(frozen=True)
class Classified:
    """A constraint by integrability: its Pfaffian ``form``, an integrating ``factor`` (1 when ``exact``), the
    ``integral`` ψ and its ``constant``, the coordinate it ``solved`` for (``restated``: the solved form says more
    than ψ = C), a Frobenius ``witness``."""

    name: str = shown(json=None, terminal=True)
    kind: Integrability = shown(json="class", terminal=True)
    form: Pfaffian | None = shown(json=None)  # None: holonomic as given
    exact: bool = shown(json=None)
    factor: Expr | None = shown(optional=True)
    integral: Expr | None = shown(optional=True)
    constant: Expr | None = shown(optional=True)
    solved: Binding | None = shown(optional=True, keyed="symbol", keyed_value="value", terminal=True)
    restated: bool = shown(json=None)
    witness: Witness | None = shown(json="frobenius", optional=True)
    note: str = shown(optional=True)


@dataclass(frozen=True)
class Dependent:
    """A coordinate the constraints fix, ``symbol`` = ``value`` (``source``: the constraint, when known)."""

    symbol: Expr = shown(json=None)
    value: Expr = shown()
    source: str = shown(json=None)


@dataclass(frozen=True)
class Equation:
    """Lagrange's equation for ``coordinate``: ``lhs`` = ``rhs``."""

    coordinate: Expr = shown()
    lhs: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class Reduced:
    """The system in minimal coordinates (trivial when no coordinate was eliminated): the JSON gives every
    coordinate's generalized force, the templates only those that are not zero (``forces``)."""

    independent: tuple[Expr, ...] = shown(json=None, terminal=True)
    dependent: tuple[Dependent, ...] = shown(keyed="symbol", keyed_value="value", terminal=True)
    velocities: tuple[Binding, ...] = shown(json=None)
    constants: tuple[Expr, ...] = shown()
    kinetic: Expr = shown(json=None)
    potential: Expr = shown(json=None)
    lagrangian: Expr = shown()
    generalized_forces: tuple[Binding, ...] = shown(keyed="symbol", keyed_value="value", template=False)
    forces: tuple[Binding, ...] = shown(json=None)
    equations: tuple[Equation, ...] = shown(json=None)
    accelerations: tuple[Binding, ...] = shown(json=None)
    agreement: Agreement = shown(terminal=True)
    all_coordinates: bool = shown(json=None)

    @property
    def trivial(self) -> bool:
        return not self.dependent


@dataclass(frozen=True)
class Jacobi:
    """What the Jacobi integral h is: the total energy T + V or not."""

    equals_total_energy: bool = shown(terminal=True)


@dataclass(frozen=True)
class Shift:
    """A symmetry's flow on one coordinate, δq = ξ ε (``is_one``: ξ = 1, written as δq = ε)."""

    coordinate: Expr = shown(json=None)
    value: Expr = shown()
    is_one: bool = shown(json=None)


@dataclass(frozen=True)
class Symmetry:
    """The translation or rotation whose momentum a conserved quantity is (Noether), with its flow ξ on each
    coordinate it moves."""

    symmetry: str = shown(terminal=True)
    generator: tuple[Shift, ...] = shown(keyed="coordinate", keyed_value="value")


@dataclass(frozen=True)
class Conserved:
    """A conserved quantity, ``symbol`` = ``expression`` (p_q for a momentum, h for the energy function), with
    why it is conserved."""

    name: str = shown(json=None)
    kind: str = shown(json=None, terminal=True)
    symbol: Expr = shown(json=None, terminal=True)
    expression: Expr = shown(json=None, terminal=True)
    coordinate: Expr | None = shown(json=None)
    reason: str = shown()
    jacobi: Jacobi | None = shown(inline=True, terminal=True)  # the Jacobi integral's
    flags: tuple[str, ...] = shown(json=None)
    flow: Symmetry | None = shown(inline=True, terminal=True)  # a symmetry's momentum's


@dataclass(frozen=True)
class Contact:
    """A unilateral constraint's ``multiplier`` = ``value`` at an equilibrium; ``admissible`` False when it would
    pull, None when its sign depends on the parameters."""

    constraint: str = shown(json=None, terminal=True)
    multiplier: Expr = shown(json=None)
    value: Expr = shown(terminal=True)
    admissible: bool | None = shown(json=None, terminal=True)


@dataclass(frozen=True)
class Contacts:
    """The unilateral constraints at one equilibrium, with the verdict over all of them (False: one would pull,
    None: a sign depends on the parameters, True: all push)."""

    admissible: bool | None = shown(terminal=True)
    checks: tuple[Contact, ...] = shown(json="contact", keyed="constraint", keyed_value="value", terminal=True)


@dataclass(frozen=True)
class DerivedEquilibrium:
    """An equilibrium of the effective potential as the JSON gives it, in the coordinate q itself."""

    condition: Expr = shown()
    exists_if: Expr | None = shown()
    stability_condition: Expr | None = shown()
    frequency_squared_at: Expr | None = shown()


@dataclass(frozen=True)
class Equilibrium:
    """An equilibrium of the effective potential as shown (in q₀: ``value``, or None when shown by its
    ``condition`` = ``lhs`` = ``rhs``) and, ``derived``, as the JSON gives it."""

    value: Expr | None = shown(json=None, terminal=True)
    condition: Expr = shown(json=None)
    lhs: Expr = shown(json=None, terminal=True)
    rhs: Expr = shown(json=None, terminal=True)
    exists_if: Expr | None = shown(json=None)
    curvature: Expr | None = shown(json=None)
    stable: bool | None = shown(json=None, terminal=True)
    stability_condition: Expr | None = shown(json=None, terminal=True)
    frequency_squared: Expr | None = shown(json=None, terminal=True)
    derived: DerivedEquilibrium = shown(inline=True, template=False)
    contact: Contacts | None = shown(inline=True, terminal=True)  # None: no unilateral constraint


@dataclass(frozen=True)
class CyclicValue:
    """A cyclic coordinate's constant momentum and the velocity it gives."""

    coordinate: Expr = shown()
    momentum: Expr = shown()
    velocity: Expr = shown()
    value: Expr = shown()


@dataclass(frozen=True)
class Effective:
    """The effective potential of one coordinate q, with the symbol ``at`` (q₀) of its equilibria."""

    coordinate: Expr = shown(json=None, terminal=True)
    at: Expr = shown(json=None, terminal=True)
    velocity: Expr = shown(json=None)
    cyclic: tuple[CyclicValue, ...] = shown(json=None)
    mass: Expr = shown()
    routhian: Expr = shown()
    expression: Expr = shown(json=None, terminal=True)
    lhs: Expr = shown(json=None)
    rhs: Expr = shown(json=None)
    damped: bool = shown(json=None)
    equilibria: tuple[Equilibrium, ...] = shown(terminal=True)


@dataclass(frozen=True)
class Held:
    """A momentum held at its value during a steady motion: its ``coordinate``, ``momentum`` = ``value``."""

    coordinate: Expr = shown()
    momentum: Expr = shown(terminal=True)
    value: Expr = shown()


@dataclass(frozen=True)
class Limits:
    """The slow and the fast steady rate, well inside the range where both are real."""

    slow: Expr = shown()
    fast: Expr = shown()


@dataclass(frozen=True)
class DerivedSteady:
    """The steady motions as the JSON gives them, in the coordinate's own name (standing for its steady value)."""

    coordinate: Expr = shown()
    rate: Expr = shown()
    held: tuple[Binding, ...] = shown(keyed="symbol", keyed_value="value")
    velocities: tuple[Binding, ...] = shown(keyed="symbol", keyed_value="value")
    momentum: Binding = shown(keyed="symbol", keyed_value="value")
    condition: Expr = shown()
    coefficients: tuple[Expr, ...] = shown()
    excluded: tuple[Expr, ...] = shown()
    values: tuple[Expr, ...] = shown()
    exists_if: Expr | None = shown()
    slow_fast: tuple[Expr, Expr] | None = shown()
    mass: Expr = shown()
    curvature: Expr = shown()
    frequency_squared: Expr = shown()
    frequency_squared_at: Expr | None = shown()
    eliminated: Binding | None = shown(keyed="symbol", keyed_value="value")
    stable: bool | None = shown()
    stability_condition: Expr | None = shown()
    verified: str = shown()


@dataclass(frozen=True)
class Steady:
    """The steady motions about the effective potential's coordinate, written in its symbol ``at`` (q₀); the
    rate's velocity symbol ``velocity`` stands for the constant rate Ω (``derived``: as the JSON gives them)."""

    coordinate: Expr = shown(json=None)
    qdot: Expr = shown(json=None)
    qddot: Expr = shown(json=None)
    at: Expr = shown(json=None, terminal=True)
    rate: Expr = shown(json=None)
    velocity: Expr = shown(json=None, terminal=True)
    held: tuple[Held, ...] = shown(json=None, terminal=True)
    velocities: tuple[Binding, ...] = shown(json=None)
    momentum: Binding = shown(json=None)
    condition: Expr = shown(json=None)
    lhs: Expr = shown(json=None, terminal=True)
    rhs: Expr = shown(json=None, terminal=True)
    excluded: tuple[Expr, ...] = shown(json=None)  # each as the equation e = 0
    roots: tuple[Expr, ...] = shown(json=None, terminal=True)  # empty when ``square`` gives them
    square: Expr | None = shown(json=None, terminal=True)
    exists_if: Expr | None = shown(json=None, terminal=True)
    limits: Limits | None = shown(json=None)
    mass: Expr = shown(json=None)
    frequency_squared: Expr = shown(json=None, terminal=True)
    frequency_squared_at: Expr | None = shown(json=None, terminal=True)
    eliminated: Binding | None = shown(json=None)
    stable: bool | None = shown(json=None, terminal=True)
    stability_condition: Expr | None = shown(json=None, terminal=True)
    verified: str = shown(json=None)
    derived: DerivedSteady = shown(inline=True, template=False)


@dataclass(frozen=True)
class Mode:
    """An equilibrium of the linearization and its small oscillations (``free``: coordinates left arbitrary)."""

    point: tuple[Binding, ...] = shown(keyed="symbol", keyed_value="value", terminal=True)
    mass: Rows = shown()
    stiffness: Rows = shown()
    gyroscopic: Rows = shown(blank_zero=True)
    damping: Rows = shown(blank_zero=True)
    squared_frequencies: tuple[Expr, ...] | None = shown(terminal=True)
    shapes: tuple[ModeShape, ...] | None = shown(json="mode_shapes", terminal=True)  # one per ω², in order
    stable: bool | None = shown(terminal=True)
    free: tuple[Expr, ...] = shown(optional=True, terminal=True)
    note: str = shown(optional=True)
    contact: Contacts | None = shown(inline=True, terminal=True)


@dataclass(frozen=True)
class Modes:
    """The equilibria of the linearization (``search``: how they were found, when they may not be all)."""

    coordinates: tuple[Expr, ...] = shown()
    equilibria: tuple[Mode, ...] = shown(terminal=True)
    search: str = shown("", optional=True)


def _count(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


@dataclass(frozen=True)
class Freedom:
    """The degrees of freedom (:mod:`lagsolve.mechanics.analysis.freedom`): the counts, how many coordinates fix a
    ``configuration`` (None: not settled) and how many ``velocities`` are free, and the one sentence every format
    prints."""

    coordinates: int = shown()
    holonomic: int = shown()
    nonholonomic: int = shown()
    unresolved: int = shown()
    configuration: int | None = shown(terminal=True)
    velocities: int = shown(terminal=True)
    sentence: str = shown(json=None, terminal=True)


def _freedom_sentence(n: int, h: int, k: int, u: int, free: int) -> str:
    """The degrees of freedom in words: n coordinates less the constraints, and, for a nonholonomic system, the
    coordinates a configuration needs beside the free velocities."""
    coordinates, degrees = _count(n, "coordinate", "coordinates"), _count(free, "degree", "degrees")
    if h + k + u == 0:
        return f"{coordinates} and no constraint: {degrees} of freedom."
    holonomic = _count(h, "holonomic constraint", "holonomic constraints")
    if k + u == 0:
        return f"{coordinates} less {holonomic}: {degrees} of freedom."
    velocities = _count(free, "velocity is", "velocities are")
    if u:
        unsettled = _count(u, "velocity constraint is", "velocity constraints are")
        return (f"{coordinates} less {_count(h + k + u, 'constraint', 'constraints')}: {velocities} free, "
                f"{degrees} of freedom. Whether {unsettled} integrable is not settled, so how many coordinates a "
                "configuration needs is not known.")
    configuration = _count(n - h, "coordinate", "coordinates")
    binding = _count(k, "nonholonomic constraint binds", "nonholonomic constraints bind")
    fixed = f"{coordinates} less {holonomic} leave {configuration}" if h else f"All {coordinates} are needed"
    return (f"{fixed} to fix a configuration, but {binding} the velocities as well, so {velocities} free: "
            f"{degrees} of freedom, fewer than the coordinates a configuration needs: the system is nonholonomic.")


def _freedom(f: Any) -> Freedom:
    return Freedom(f.coordinates, f.holonomic, f.nonholonomic, f.unresolved, f.configuration, f.velocities,
                   _freedom_sentence(f.coordinates, f.holonomic, f.nonholonomic, f.unresolved, f.velocities))


@dataclass(frozen=True)
class AnalysisSection:
    """Every part of the analysis a report shows; each ``*_note`` says why a part is absent (the JSON writes
    ``{"note": ...}`` in its place)."""

    constraints: tuple[Classified, ...] = shown(keyed="name", terminal=True)
    freedom: Freedom | None = shown(json="degrees_of_freedom", terminal=True)
    reduced: Reduced | None = shown(absent="reduced_note", terminal=True)
    reduced_note: str = shown(json=None)
    system: str = shown(json=None)
    conserved: tuple[Conserved, ...] = shown(keyed="name", terminal=True)
    conserved_notes: tuple[str, ...] = shown()
    verified: str = shown(json=None)  # how each conserved quantity was verified
    effective: Effective | None = shown(json="effective_potential", absent="effective_note", terminal=True)
    effective_note: str = shown(json=None)
    steady: Steady | None = shown(json="steady_motions", absent="steady_note", terminal=True)
    steady_note: str = shown(json=None)
    modes: Modes | None = shown(json="linearization", absent="linearization_note", terminal=True)
    linearization_note: str = shown(json=None)
    equilibria_note: str = shown(json=None)  # why no equilibrium is shown


# -- the builder ----------------------------------------------------------------------------------


def analysis_section(derivation: Derivation) -> AnalysisSection | None:
    """The analysis sections of ``derivation`` (None when it carries no analysis), built once."""
    analysis = derivation.analysis
    if analysis is None:
        return None
    conservation = analysis.conservation
    full = ", with the constraints," if analysis.system.kind == "full" else ""
    return AnalysisSection(
        constraints=tuple(_classified(k) for k in analysis.classification),
        freedom=_freedom(analysis.freedom) if analysis.freedom is not None else None,
        reduced=_reduced(analysis.reduced, derivation) if analysis.reduced is not None else None,
        reduced_note=analysis.reduced_note,
        system=analysis.system.kind,
        conserved=tuple(_conserved(c, analysis.system.model.coordinates) for c in conservation.quantities),
        conserved_notes=tuple(conservation.notes),
        verified=f"Each was verified: its time derivative along the equations of motion{full} simplifies to zero.",
        effective=(_effective(analysis.effective_potential, analysis.effective_contact, derivation)
                   if analysis.effective_potential is not None else None),
        effective_note=analysis.effective_note,
        steady=_steady(analysis.steady, derivation) if analysis.steady is not None else None,
        steady_note=analysis.steady_note,
        modes=_modes(analysis.linearization, analysis.modes_contact) if analysis.linearization is not None else None,
        linearization_note=analysis.linearization_note,
        equilibria_note=(analysis.linearization_note if "coordinates are left" in analysis.effective_note
                         else analysis.effective_note),
    )


def _conserved(c: Any, coordinates: tuple[Any, ...]) -> Conserved:
    """A conserved quantity, with the coordinates its symmetry's flow moves and ξ for each."""
    generator = tuple(Shift(q, x, x == 1) for q, x in zip(coordinates, c.generator, strict=False) if x != 0)
    return Conserved(
        name=c.name, kind=c.kind, symbol=sympy.Symbol("h") if c.kind == "jacobi" else sympy.Symbol(c.name),
        expression=c.expression, coordinate=c.coordinate, reason=c.reason,
        jacobi=Jacobi(bool(c.equals_energy)) if c.kind == "jacobi" else None, flags=tuple(c.flags),
        flow=Symmetry(c.symmetry, generator) if c.symmetry else None)


def _classified(k: Classification) -> Classified:
    solved = Binding(*k.solved) if k.solved else None
    return Classified(
        name=k.name, kind=k.kind,
        form=Pfaffian(tuple(zip(k.form, k.variables, strict=True))) if k.kind != Integrability.HOLONOMIC else None,
        exact=k.exact, factor=k.factor, integral=k.integral, constant=k.constant, solved=solved,
        restated=solved is not None and k.integral != solved.symbol,
        witness=Witness(Indices(tuple(k.witness[0])), k.witness[1]) if k.witness is not None else None,
        note=k.note,
    )


def _reduced(r: ReducedSystem, derivation: Derivation) -> Reduced:
    forces = tuple(Binding(q, f) for q, f in zip(r.independent, r.generalized_forces, strict=True))
    return Reduced(
        independent=tuple(r.independent),
        dependent=tuple(Dependent(q, v, r.substitution.sources.get(q, ""))
                        for q, v in r.substitution.positions.items()),
        velocities=tuple(Binding(v, e) for v, e in r.substitution.velocities.items()),
        constants=tuple(r.constants),
        kinetic=r.kinetic, potential=r.potential, lagrangian=r.lagrangian,
        generalized_forces=forces, forces=tuple(f for f in forces if f.value != 0),
        equations=tuple(Equation(q, lhs, rhs) for q, (lhs, rhs) in zip(r.independent, r.equation_sides, strict=True))
        if r.equation_sides else (),
        accelerations=tuple(Binding(c.acceleration, r.accelerations[c.name]) for c in derivation.problem.coordinates
                            if c.name in r.accelerations),
        agreement=Agreement(r.agreement),
        all_coordinates=len(r.independent) == len(derivation.problem.coordinates),
    )


def _contacts(checks: Any) -> Contacts | None:
    """The unilateral constraints at one equilibrium (None when there are none)."""
    if not checks:
        return None
    verdicts = [c.admissible for c in checks]
    return Contacts(False if False in verdicts else (None if None in verdicts else True),
                    tuple(Contact(c.constraint, sympy.Symbol(f"lambda_{c.constraint}"), c.multiplier, c.admissible)
                          for c in checks))


def equilibrium_symbol(q: Any, taken: Any = ()) -> Any:
    """The display symbol of an equilibrium value: ``r`` → ``r_0`` (``r_eq`` when the problem
    already uses ``r0`` or ``r_0``, which print alike)."""
    if f"{q.name}0" in taken or f"{q.name}_0" in taken:
        return sympy.Symbol(f"{q.name}_eq")
    return sympy.Symbol(f"{q.name}_0")


def _effective(v: EffectivePotential, contact: Any, derivation: Derivation) -> Effective:
    q = v.coordinate
    q0 = equilibrium_symbol(q, derivation.problem.symbols)

    def at(expr: Any) -> Any:
        return expr.xreplace({q: q0}) if expr is not None else None

    equilibria = []
    for e, check in zip(v.equilibria, contact or ((),) * len(v.equilibria), strict=True):
        power = e.condition.lhs == q or (isinstance(e.condition.lhs, sympy.Pow) and e.condition.lhs.base == q)
        condition = at(e.condition)
        equilibria.append(Equilibrium(
            value=e.value if e.value is not None and not power else None,
            condition=condition, lhs=condition.lhs, rhs=condition.rhs, exists_if=at(e.exists_if),
            curvature=at(e.curvature_at if e.curvature_at is not None else e.curvature)
            if e.curvature is not None else None,
            stable=e.stable, stability_condition=at(e.stability_condition),
            frequency_squared=at(e.frequency_squared_at if e.frequency_squared_at is not None else e.frequency_squared)
            if e.frequency_squared is not None else None,
            derived=DerivedEquilibrium(e.condition, e.exists_if, e.stability_condition, e.frequency_squared_at),
            contact=_contacts(check)))
    model = derivation.model
    return Effective(
        coordinate=q, at=q0, velocity=model.velocities[model.coordinates.index(q)],
        cyclic=tuple(CyclicValue(c, p, sympy.Symbol(f"{c.name}_dot"), w) for c, p, w in v.cyclic),
        routhian=v.routhian, mass=v.mass, expression=v.expression, lhs=v.equation[0], rhs=v.equation[1],
        damped=v.damped, equilibria=tuple(equilibria))


def _derived_steady(d: SteadyMotion) -> DerivedSteady:
    return DerivedSteady(
        coordinate=d.coordinate, rate=d.rate, held=tuple(Binding(p, value) for _, p, value in d.held),
        velocities=tuple(Binding(v, value) for v, value in d.velocities), momentum=Binding(*d.momentum),
        condition=d.condition.lhs, coefficients=tuple(d.coefficients), excluded=tuple(d.excluded),
        values=tuple(d.roots), exists_if=d.exists_if, slow_fast=tuple(d.limits) if d.limits is not None else None,
        mass=d.mass, curvature=d.curvature, frequency_squared=d.frequency_squared,
        frequency_squared_at=d.frequency_squared_at,
        eliminated=Binding(*d.eliminated) if d.eliminated is not None else None,
        stable=d.stable, stability_condition=d.stability_condition, verified=d.verified)


def _steady(s: SteadyMotion, derivation: Derivation) -> Steady:
    q0 = equilibrium_symbol(s.coordinate, derivation.problem.symbols)

    def at(expr: Any) -> Any:
        return expr.xreplace({s.coordinate: q0}) if isinstance(expr, sympy.Basic) else expr

    model = derivation.model
    k = model.coordinates.index(s.coordinate)
    condition = at(s.condition)
    return Steady(
        coordinate=s.coordinate, qdot=model.velocities[k], qddot=model.accelerations[k], at=q0, rate=s.rate,
        velocity=s.velocity, held=tuple(Held(c, p, value) for c, p, value in s.held),
        velocities=tuple(Binding(v, at(value)) for v, value in s.velocities),
        momentum=Binding(s.momentum[0], at(s.momentum[1])), condition=condition, lhs=condition.lhs,
        rhs=condition.rhs, excluded=tuple(sympy.Eq(at(e), 0) for e in s.excluded),
        roots=tuple(at(r) for r in s.roots) if s.square is None else (), square=at(s.square),
        exists_if=at(s.exists_if), limits=Limits(at(s.limits[0]), at(s.limits[1])) if s.limits is not None else None,
        mass=at(s.mass), frequency_squared=at(s.frequency_squared), frequency_squared_at=at(s.frequency_squared_at),
        eliminated=Binding(s.eliminated[0], at(s.eliminated[1])) if s.eliminated is not None else None,
        stable=s.stable, stability_condition=at(s.stability_condition), verified=s.verified,
        derived=_derived_steady(s))


def _modes(lin: Linearization, contact: Any) -> Modes:
    coordinates = tuple(lin.coordinates)
    return Modes(coordinates, tuple(
        Mode(point=tuple(Binding(q, x) for q, x in m.point), mass=m.mass, stiffness=m.stiffness,
             gyroscopic=m.gyroscopic, damping=m.damping, squared_frequencies=m.squared_frequencies,
             shapes=tuple(ModeShape(coordinates, tuple(u)) for u in m.shapes) if m.shapes is not None else None,
             stable=m.stable, free=tuple(m.free), note=m.note, contact=_contacts(check))
        for m, check in zip(lin.modes, contact or ((),) * len(lin.modes), strict=True)), lin.search)
