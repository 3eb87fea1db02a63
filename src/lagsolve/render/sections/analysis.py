"""The analysis sections of a report, as data: how each constraint integrates, the minimal coordinates,
the conserved quantities, the effective potential with its equilibria, and the normal modes.

Built once by :func:`analysis_section`; :mod:`lagsolve.render.analysis_report` projects it onto the
templates (``templates/*/_analysis.*.j2``), the JSON key ``analysis`` and the terminal. Each record holds
the expressions a report shows (an equilibrium's conditions already in the symbol of its value, q₀), and,
where the JSON contract gives them as derived, those too. Nothing here simplifies.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.integrability import Integrability
from lagsolve.render.sections.core import Substitution

if TYPE_CHECKING:
    from lagsolve.mechanics.equilibria import EffectivePotential
    from lagsolve.mechanics.integrability import Classification
    from lagsolve.mechanics.linearize import Linearization
    from lagsolve.mechanics.minimal import ReducedSystem
    from lagsolve.mechanics.results import Derivation
    from lagsolve.mechanics.steady import SteadyMotion

Expr = Any

#: how the equations in minimal coordinates compare with the multiplier route (``Reduced.agreement``): the
#: terminal's phrase, the reports' sentence (the same in every format), and whether it is a warning
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
class Classified:
    """A constraint by integrability: its Pfaffian form Σ w dx (``differential``), an integrating ``factor``,
    the ``integral`` and its ``constant``, the coordinate it ``solved`` for, a Frobenius ``witness``."""

    name: str
    kind: Integrability
    note: str
    differential: tuple[tuple[Expr, Expr], ...]  # (coefficient, variable)
    exact: bool
    factor: Expr | None
    integral: Expr | None
    constant: Expr | None
    solved: tuple[Expr, Expr] | None
    witness: tuple[tuple[Expr, Expr, Expr], Expr] | None


@dataclass(frozen=True)
class Reduced:
    """The system in minimal coordinates (``trivial``: no coordinate was eliminated)."""

    independent: tuple[Expr, ...]
    dependent: tuple[Substitution, ...]
    velocities: tuple[tuple[Expr, Expr], ...]
    constants: tuple[Expr, ...]
    kinetic: Expr
    potential: Expr
    lagrangian: Expr
    forces: tuple[tuple[Expr, Expr], ...]  # (coordinate, generalized force), every coordinate
    equations: tuple[tuple[Expr, Expr, Expr], ...]  # (coordinate, lhs, rhs)
    accelerations: tuple[tuple[Expr, Expr], ...]  # (q̈, value)
    agreement: str
    all_coordinates: bool

    @property
    def trivial(self) -> bool:
        return not self.dependent

    @property
    def agreement_text(self) -> tuple[str, str, bool]:
        """(terminal phrase, report sentence, warning) for ``agreement`` (:data:`AGREEMENT`)."""
        return AGREEMENT.get(self.agreement, AGREEMENT["differ"])


@dataclass(frozen=True)
class Conserved:
    """A conserved quantity, ``symbol`` = ``expression`` (p_q for a momentum, h for the energy function)."""

    name: str
    kind: str
    symbol: Expr
    expression: Expr
    coordinate: Expr | None
    reason: str
    equals_energy: bool | None
    moving: bool
    flags: tuple[str, ...]
    symmetry: str = ""  # the translation or rotation whose momentum it is (Noether)
    generator: tuple[tuple[Expr, Expr], ...] = ()  # (coordinate, ξ) for each coordinate the flow moves


@dataclass(frozen=True)
class Contact:
    """A unilateral constraint's multiplier ``symbol`` = ``value`` at an equilibrium; ``admissible`` False when
    it would pull, None when its sign depends on the parameters."""

    constraint: str
    symbol: Expr
    value: Expr
    admissible: bool | None


@dataclass(frozen=True)
class Contacts:
    """The unilateral constraints at one equilibrium, with the verdict over all of them."""

    checks: tuple[Contact, ...]

    @property
    def admissible(self) -> bool | None:
        verdicts = [c.admissible for c in self.checks]
        return False if False in verdicts else (None if None in verdicts else True)


@dataclass(frozen=True)
class Equilibrium:
    """An equilibrium of the effective potential as shown (in q₀) and, ``derived``, as the JSON gives it."""

    value: Expr | None  # None: shown by its condition
    condition: Expr
    exists_if: Expr | None
    curvature: Expr | None
    stable: bool | None
    stability_condition: Expr | None
    frequency: Expr | None
    frequency_squared: Expr | None
    contact: Contacts
    derived: Any  # the mechanics Equilibrium (in q): condition, exists_if, ... for the contract


@dataclass(frozen=True)
class CyclicValue:
    coordinate: Expr
    momentum: Expr
    velocity: Expr  # the symbol q_dot
    value: Expr


@dataclass(frozen=True)
class Effective:
    """The effective potential of one coordinate q, with the symbol ``at`` (q₀) of its equilibria."""

    coordinate: Expr
    at: Expr
    velocity: Expr
    cyclic: tuple[CyclicValue, ...]
    routhian: Expr
    mass: Expr
    expression: Expr
    equation: tuple[Expr, Expr]
    damped: bool
    equilibria: tuple[Equilibrium, ...]


@dataclass(frozen=True)
class Steady:
    """The steady motions about the effective potential's coordinate, written in its symbol ``at`` (q₀); the
    rate's velocity symbol ``velocity`` stands for the constant rate Ω (``derived``: the mechanics record)."""

    coordinate: Expr
    coordinate_velocity: Expr
    coordinate_acceleration: Expr
    at: Expr
    rate: Expr
    velocity: Expr
    held: tuple[tuple[Expr, Expr, Expr], ...]  # (coordinate, momentum symbol, ∂L/∂q̇) of each held momentum
    velocities: tuple[tuple[Expr, Expr], ...]  # (velocity symbol, value) of the held coordinates
    momentum: tuple[Expr, Expr]  # (p of the rate, its value at the steady motion)
    condition: Expr
    excluded: tuple[Expr, ...]
    roots: tuple[Expr, ...]
    square: Expr | None
    exists_if: Expr | None
    limits: tuple[Expr, Expr] | None
    mass: Expr
    frequency_squared: Expr
    frequency_squared_at: Expr | None
    eliminated: tuple[Expr, Expr] | None
    stable: bool | None
    stability_condition: Expr | None
    verified: str
    derived: Any


@dataclass(frozen=True)
class Mode:
    """An equilibrium of the linearization and its small oscillations."""

    point: tuple[tuple[Expr, Expr], ...]
    free: tuple[Expr, ...]
    mass: Expr
    stiffness: Expr
    gyroscopic: Expr
    damping: Expr
    squared_frequencies: tuple[Expr, ...] | None
    frequencies: tuple[Expr | None, ...] | None
    stable: bool | None
    note: str
    contact: Contacts
    shapes: tuple[tuple[Expr, ...], ...] | None = None  # one mode shape per ω², in the same order


@dataclass(frozen=True)
class Modes:
    coordinates: tuple[Expr, ...]
    equilibria: tuple[Mode, ...]
    search: str = ""  # how the equilibria were found, when they may not be all


@dataclass(frozen=True)
class AnalysisSection:
    """Every part of the analysis a report shows; each ``*_note`` says why a part is absent."""

    constraints: tuple[Classified, ...]
    reduced: Reduced | None
    reduced_note: str
    system: str
    conserved: tuple[Conserved, ...]
    conserved_notes: tuple[str, ...]
    cyclic: tuple[Expr, ...]
    effective: Effective | None
    effective_note: str
    modes: Modes | None
    linearization_note: str
    steady: Steady | None = None
    steady_note: str = ""

    @property
    def velocity_constraints(self) -> bool:
        return any(k.kind != Integrability.HOLONOMIC for k in self.constraints)

    @property
    def verified(self) -> str:
        """How every conserved quantity was verified: one sentence, the same in every report format."""
        full = ", with the constraints," if self.system == "full" else ""
        return f"Each was verified: its time derivative along the equations of motion{full} simplifies to zero."

    @property
    def equilibria_note(self) -> str:
        """Why no equilibrium is shown: the linearization's note when the coordinates are left, else the
        effective potential's."""
        return self.linearization_note if "coordinates are left" in self.effective_note else self.effective_note


def analysis_section(derivation: Derivation) -> AnalysisSection | None:
    """The analysis sections of ``derivation`` (None when it carries no analysis), built once."""
    analysis = derivation.analysis
    if analysis is None:
        return None
    conservation = analysis.conservation
    return AnalysisSection(
        constraints=tuple(_classified(k) for k in analysis.classification),
        reduced=_reduced(analysis.reduced, derivation) if analysis.reduced is not None else None,
        reduced_note=analysis.reduced_note,
        system=analysis.system.kind,
        conserved=tuple(
            Conserved(c.name, c.kind, sympy.Symbol("h") if c.kind == "jacobi" else sympy.Symbol(c.name),
                      c.expression, c.coordinate, c.reason, c.equals_energy, c.moving, tuple(c.flags), c.symmetry,
                      _generator(c.generator, analysis.system.model.coordinates))
            for c in conservation.quantities),
        conserved_notes=tuple(conservation.notes),
        cyclic=tuple(conservation.cyclic),
        effective=(_effective(analysis.effective_potential, analysis.effective_contact, derivation)
                   if analysis.effective_potential is not None else None),
        effective_note=analysis.effective_note,
        modes=_modes(analysis.linearization, analysis.modes_contact) if analysis.linearization is not None else None,
        linearization_note=analysis.linearization_note,
        steady=_steady(analysis.steady, derivation) if analysis.steady is not None else None,
        steady_note=analysis.steady_note,
    )


def _generator(flow: tuple[Any, ...], coordinates: tuple[Any, ...]) -> tuple[tuple[Any, Any], ...]:
    """The coordinates a symmetry's flow moves, with its component ξ for each."""
    return tuple((q, x) for q, x in zip(coordinates, flow, strict=False) if x != 0)


def _steady(s: SteadyMotion, derivation: Derivation) -> Steady:
    q0 = equilibrium_symbol(s.coordinate, derivation.problem.symbols)

    def at(expr: Any) -> Any:
        return expr.xreplace({s.coordinate: q0}) if isinstance(expr, sympy.Basic) else expr

    model = derivation.model
    k = model.coordinates.index(s.coordinate)
    return Steady(
        coordinate=s.coordinate, coordinate_velocity=model.velocities[k],
        coordinate_acceleration=model.accelerations[k], at=q0, rate=s.rate, velocity=s.velocity,
        held=tuple((c, p, value) for c, p, value in s.held),
        velocities=tuple((v, at(value)) for v, value in s.velocities),
        momentum=(s.momentum[0], at(s.momentum[1])), condition=at(s.condition),
        excluded=tuple(at(e) for e in s.excluded), roots=tuple(at(r) for r in s.roots), square=at(s.square),
        exists_if=at(s.exists_if), limits=(at(s.limits[0]), at(s.limits[1])) if s.limits is not None else None,
        mass=at(s.mass), frequency_squared=at(s.frequency_squared), frequency_squared_at=at(s.frequency_squared_at),
        eliminated=(s.eliminated[0], at(s.eliminated[1])) if s.eliminated is not None else None,
        stable=s.stable, stability_condition=at(s.stability_condition), verified=s.verified, derived=s)


def _classified(k: Classification) -> Classified:
    return Classified(
        name=k.name, kind=k.kind, note=k.note, differential=tuple(zip(k.form, k.variables, strict=True)),
        exact=k.exact, factor=k.factor, integral=k.integral, constant=k.constant,
        solved=tuple(k.solved) if k.solved else None,
        witness=(tuple(k.witness[0]), k.witness[1]) if k.witness is not None else None,
    )


def _reduced(r: ReducedSystem, derivation: Derivation) -> Reduced:
    return Reduced(
        independent=tuple(r.independent),
        dependent=tuple(Substitution(q, v, r.substitution.sources.get(q, ""))
                        for q, v in r.substitution.positions.items()),
        velocities=tuple(r.substitution.velocities.items()),
        constants=tuple(r.constants),
        kinetic=r.kinetic, potential=r.potential, lagrangian=r.lagrangian,
        forces=tuple(zip(r.independent, r.generalized_forces, strict=True)),
        equations=tuple((q, lhs, rhs) for q, (lhs, rhs) in zip(r.independent, r.equation_sides, strict=True))
        if r.equation_sides else (),
        accelerations=tuple((c.acceleration, r.accelerations[c.name]) for c in derivation.problem.coordinates
                            if c.name in r.accelerations),
        agreement=r.agreement,
        all_coordinates=len(r.independent) == len(derivation.problem.coordinates),
    )


def _contacts(checks: Any) -> Contacts:
    return Contacts(tuple(Contact(c.constraint, sympy.Symbol(f"lambda_{c.constraint}"), c.multiplier, c.admissible)
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
        equilibria.append(Equilibrium(
            value=e.value if e.value is not None and not power else None,
            condition=at(e.condition), exists_if=at(e.exists_if),
            curvature=at(e.curvature_at if e.curvature_at is not None else e.curvature)
            if e.curvature is not None else None,
            stable=e.stable, stability_condition=at(e.stability_condition), frequency=at(e.frequency),
            frequency_squared=at(e.frequency_squared_at if e.frequency_squared_at is not None else e.frequency_squared)
            if e.frequency_squared is not None else None,
            contact=_contacts(check), derived=e))
    model = derivation.model
    return Effective(
        coordinate=q, at=q0, velocity=model.velocities[model.coordinates.index(q)],
        cyclic=tuple(CyclicValue(c, p, sympy.Symbol(f"{c.name}_dot"), w) for c, p, w in v.cyclic),
        routhian=v.routhian, mass=v.mass, expression=v.expression, equation=tuple(v.equation),
        damped=v.damped, equilibria=tuple(equilibria))


def _modes(lin: Linearization, contact: Any) -> Modes:
    return Modes(tuple(lin.coordinates), tuple(
        Mode(point=tuple(m.point), free=tuple(m.free), mass=m.mass, stiffness=m.stiffness, gyroscopic=m.gyroscopic,
             damping=m.damping, squared_frequencies=m.squared_frequencies, frequencies=m.frequencies,
             stable=m.stable, note=m.note, contact=_contacts(check), shapes=m.shapes)
        for m, check in zip(lin.modes, contact or ((),) * len(lin.modes), strict=True)), lin.search)
