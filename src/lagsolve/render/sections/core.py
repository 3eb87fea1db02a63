"""The sections of a report about the equations of motion, as data: what each shows, in display order.

:func:`core_sections` walks a :class:`~lagsolve.mechanics.results.Derivation` once and returns frozen
records that carry SymPy expressions and names, never printed strings. Every field says with
:func:`~lagsolve.render.model.shown` how each output shows it: the JSON contract (format section 2: the keys
from ``format_version`` to ``effective_potential``, and ``notes``), the templates' partials
(``templates/*/_core.*.j2`` and the partials it includes, reading the field names) and the terminal summary
(``templates/text/_core.txt.j2``, ``_notes.txt.j2``: the fields marked ``terminal``); each is
:func:`~lagsolve.render.model.present` of the same records, so the outputs cannot list different things.
Where the JSON and the reports show different values of one result (the contract's friction force with N put
in, the report's with the symbol N), each is its own field. Nothing here simplifies: every expression arrives
in display form (``factor_terms`` on the matrix form is the one tidying the reports have always shown).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import sympy

from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM
from lagsolve.problem.schema import ConstraintKind
from lagsolve.render.model import Expr, Rows, shown

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation

#: the ``format_version`` of the JSON result (format section 2)
FORMAT_VERSION: Literal[1] = 1
#: above this many coordinates the reports write the matrix form one equation per row instead of as matrices
LARGE = 3


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate: its name (the JSON's), the symbols q, q̇, q̈ and the file's description."""

    name: str = shown(inline=True)
    symbol: Expr = shown(json=None)
    velocity: Expr = shown(json=None)
    acceleration: Expr = shown(json=None)
    description: str = shown(json=None)


@dataclass(frozen=True)
class Parameter:
    """A parameter: its name (the JSON's), symbol, description and assumption ("positive", "real" or "")."""

    name: str = shown(inline=True)
    symbol: Expr = shown(json=None)
    description: str = shown(json=None)
    assumption: str = shown(json=None)


@dataclass(frozen=True)
class Function:
    """An unspecified function: its name, the name as a symbol (how the report writes f), its description."""

    name: str = shown()
    symbol: Expr = shown()
    description: str = shown()


@dataclass(frozen=True)
class Particle:
    name: str = shown()
    mass: Expr = shown()
    position: tuple[Expr, ...] = shown()


@dataclass(frozen=True)
class Body:
    name: str = shown()
    mass: Expr = shown()
    position: tuple[Expr, ...] = shown()
    inertia: tuple[Expr, ...] = shown()
    angular_velocity: tuple[Expr, ...] = shown()
    planar: bool = shown()


@dataclass(frozen=True)
class CoordinateValue:
    """One coordinate's value (a coefficient, a generalized force): in the JSON ``name: value`` of an object by
    coordinate; in the reports its symbol (``coordinate``) and value."""

    name: str = shown(json=None, terminal=True)
    coordinate: Expr = shown(json=None)
    value: Expr = shown(inline=True, terminal=True)


def _by_coordinate(coords: tuple[Coordinate, ...], values: Any, zeros: bool = True) -> tuple[CoordinateValue, ...]:
    """``values`` (one per coordinate) as :class:`CoordinateValue` rows; ``zeros=False`` leaves out the zeros."""
    return tuple(CoordinateValue(q.name, q.symbol, v) for q, v in zip(coords, values, strict=True) if zeros or v != 0)


@dataclass(frozen=True)
class Load:
    """A force term (a load, a spring, a damper ...) by its nonzero generalized forces."""

    label: str = shown()
    generalized: tuple[CoordinateValue, ...] = shown()


@dataclass(frozen=True)
class Constraint:
    """A constraint with its multiplier: f = 0 (or its velocity form Σ a q̇ + b = 0), A q̈ = β."""

    name: str = shown(json=None, terminal=True)
    kind: ConstraintKind = shown()
    multiplier: Expr = shown(json=None)
    expression: Expr = shown()
    velocity_form: Expr = shown(json=None)
    coefficients: tuple[CoordinateValue, ...] = shown(keyed="name")  # a, one per coordinate
    offset: Expr = shown()  # b
    acceleration_rhs: Expr = shown(json=None)
    on: tuple[str, ...] = shown(json=None)
    unilateral: bool = shown(optional=True)


@dataclass(frozen=True)
class Equation:
    """Lagrange's equation of one coordinate, step by step: d/dt ∂L/∂q̇ − ∂L/∂q = Q (+ Σ λ a)."""

    coordinate: Coordinate = shown()
    momentum: Expr = shown()  # ∂L/∂q̇
    rate: Expr = shown()  # d/dt ∂L/∂q̇
    gradient: Expr = shown()  # ∂L/∂q
    force: Expr = shown(blank_zero=True)  # Q
    lhs: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class Substitution:
    """A quantity written through the constraints (``source`` names the constraint, when known)."""

    symbol: Expr = shown()
    value: Expr = shown()
    source: str = shown()


@dataclass(frozen=True)
class Side:
    """An equation as its two sides (the i-th coordinate's)."""

    coordinate: Coordinate = shown()
    lhs: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class MatrixRow:
    """Row i of M q̈ = F + Aᵀλ: Σ_k M_ik q̈_k, F_i, the multipliers' part (Aᵀλ)_i and the right side F_i + (Aᵀλ)_i."""

    coordinate: Coordinate = shown()
    lhs: Expr = shown(terminal=True)
    forcing: Expr = shown(terminal=True)
    constraint_part: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class MatrixForm:
    """The matrix form as the contract gives it (``mass_matrix``, ``forcing``) and as a report shows it (the
    matrices tidied, or row by row when ``by_rows``: more than :data:`LARGE` coordinates)."""

    mass: Rows = shown(json="mass_matrix", template=False)
    forcing: tuple[Expr, ...] = shown(template=False)
    mass_shown: Expr = shown(json=None)
    forcing_shown: Expr = shown(json=None)
    jacobian: Expr | None = shown(json=None)  # None without constraints
    rhs_shown: Expr | None = shown(json=None)
    unknowns: Expr = shown(json=None)
    rows: tuple[MatrixRow, ...] = shown(json=None, terminal=True)
    by_rows: bool = shown(json=None)


@dataclass(frozen=True)
class Solved:
    """An explicit result: an acceleration q̈ = ..., or a multiplier λ = ... (``name``: its coordinate's
    or constraint's; the JSON writes ``name: value``)."""

    name: str = shown(json=None, terminal=True)
    symbol: Expr = shown(json=None, terminal=True)
    value: Expr = shown(inline=True, terminal=True)


@dataclass(frozen=True)
class ParticleForce:
    name: str = shown(json=None, terminal=True)
    vector: tuple[Expr, ...] = shown()
    magnitude: Expr = shown(terminal=True)


@dataclass(frozen=True)
class ConstraintForce:
    """The force of one constraint: on its particle or point (``vector``, ``magnitude``), on each of its
    particles when several, or, with no point named, its generalized forces λ a (``generalized`` in the JSON,
    every coordinate; ``generalized_shown`` in the reports, the nonzero ones)."""

    name: str = shown(json=None, terminal=True)
    vector: tuple[Expr, ...] | None = shown(optional=True, unit="force")
    magnitude: Expr | None = shown(terminal=True, unit="force")
    particles: tuple[ParticleForce, ...] = shown(keyed="name", optional=True, terminal=True)  # when several
    generalized: tuple[CoordinateValue, ...] = shown(
        keyed="name", optional=True, template=False,
        doc="the generalized forces of constraint λ·a, when no physical force is known")
    note: str = shown(optional=True, terminal=True)
    generalized_shown: tuple[CoordinateValue, ...] = shown(json=None, terminal=True)


@dataclass(frozen=True)
class ContactMember:
    """The force of a friction contact on one member: normal part, friction, their sum and its magnitude."""

    name: str = shown(json=None, terminal=True)
    normal: tuple[Expr, ...] = shown()
    friction: tuple[Expr, ...] = shown()
    total: tuple[Expr, ...] = shown()
    magnitude: Expr = shown(terminal=True)


@dataclass(frozen=True)
class Held:
    """While a contact sticks: the force Φ that holds it, N, and |Φ|/N (the least static coefficient)."""

    force: Expr = shown(terminal=True)
    normal: Expr = shown(json="normal_force")
    ratio: Expr | None = shown(json="least_static_coefficient", terminal=True)


@dataclass(frozen=True)
class Friction:
    """A friction contact: its term (with the symbol N), and N in closed form with the case that applies.

    The JSON gives the force and generalized forces with N put in (``force``, ``generalized``), the reports the
    term with the symbol N (``term_force``, ``term_generalized``: the nonzero ones)."""

    name: str = shown(json=None, terminal=True)
    # the closed form of N (N itself when only an implicit equation)
    normal_force: Expr = shown(template=False, unit="force")
    force: tuple[Expr, ...] = shown(template=False)
    generalized: tuple[CoordinateValue, ...] = shown(keyed="name", template=False)
    valid_while: Expr = shown()
    case: str = shown()
    condition: Expr | None = shown(json="normal_force_valid_while")  # when the closed form holds
    system: Expr | None = shown(json="normal_force_equation", template=False)  # Eq(N, |a + B N|)
    particle: str = shown(json="on")  # the member that slides (a particle or a planar body)
    against: str | None = shown()  # the member that carries the surface (None: the surroundings)
    point: tuple[Expr, ...] | None = shown()  # the contact point, for a body (a particle's is its position)
    rate: Expr | None = shown(json="sliding_rate")  # the sliding rate σ, where it slides along one line
    tangent: tuple[Expr, ...] | None = shown()  # the unit tangent t along which it slides
    held: Held | None = shown(json="sticking", terminal=True)
    members: tuple[ContactMember, ...] = shown(keyed="name", terminal=True)  # empty when the forces are unknown
    coefficient: Expr = shown(json=None)
    normal: Expr = shown(json=None, terminal=True)  # the symbol N
    constraints: tuple[str, ...] = shown(json=None)
    term_force: tuple[Expr, ...] = shown(json=None)
    term_generalized: tuple[CoordinateValue, ...] = shown(json=None)
    static: Expr = shown(json=None)
    normal_shown: Expr = shown(json=None, terminal=True)  # after "N =": the equation N solves when N is implicit


@dataclass(frozen=True)
class Note:
    """Why one stage of the derivation gave no result (:class:`~lagsolve.mechanics.stages.StageNote`)."""

    stage: str = shown()
    kind: str = shown()
    reason: str = shown()
    sentence: str = shown(json=None, terminal=True)


@dataclass(frozen=True)
class ReducedForm:
    """The contract's ``reduced``: the independent coordinates and their accelerations."""

    independent: tuple[str, ...] = shown()
    accelerations: Mapping[str, Expr] = shown()


@dataclass(frozen=True)
class EquilibriumForm:
    """An equilibrium of the contract's ``effective_potential`` (a condition where it has no closed form)."""

    value: Expr = shown()
    stable: bool | None = shown()
    frequency: Expr | None = shown()


@dataclass(frozen=True)
class EffectiveForm:
    """The contract's ``effective_potential``: its coordinate, expression and equilibria."""

    coordinate: str = shown()
    expression: Expr = shown()
    equilibria: tuple[EquilibriumForm, ...] = shown()


@dataclass(frozen=True)
class CoreSections:
    """Everything a report shows about the equations of motion, in display order (the JSON's keys in its order).

    ``solve_note`` is why the explicit solution is not written out (when it is not); ``symbols`` the problem's
    names, for the prose of notes and descriptions (the page's, not a section's)."""

    format_version: Literal[1] = shown(template=False)
    name: str = shown(terminal=True)
    description: str = shown(json=None)
    slug: str = shown(json=None)
    time: Expr = shown(json=None)
    coordinates: tuple[Coordinate, ...] = shown()
    parameters: tuple[Parameter, ...] = shown()
    functions: tuple[Function, ...] = shown(json=None)
    particles: tuple[Particle, ...] = shown(json=None)
    bodies: tuple[Body, ...] = shown(json=None)
    gravity: tuple[Expr, ...] | None = shown(json=None)
    kinetic: Expr = shown(unit="energy")
    potential: Expr = shown(unit="energy")
    lagrangian: Expr = shown(unit="energy")
    loads: tuple[Load, ...] = shown(json=None)
    constraints: tuple[Constraint, ...] = shown(keyed="name", terminal=True)
    equations: tuple[Equation, ...] = shown(json=None)
    equation_forms: tuple[Expr, ...] = shown(json="equations", template=False)  # left minus right side
    substitutions: tuple[Substitution, ...] = shown(json=None)
    constrained: tuple[Side, ...] = shown(json=None)  # the equations with the constraints used (none without)
    matrix: MatrixForm = shown(inline=True, terminal=True)
    accelerations: tuple[Solved, ...] | None = shown(keyed="name", terminal=True,
                                                      unit="each coordinate's acceleration (units.accelerations)")
    multipliers: tuple[Solved, ...] | None = shown(keyed="name", terminal=True,
                                                    unit="each multiplier (units.multipliers)")
    solve_note: str = shown(json=None)
    forces: tuple[ConstraintForce, ...] | None = shown(json="constraint_forces", keyed="name", terminal=True)
    friction: tuple[Friction, ...] = shown(keyed="name", terminal=True)
    reduced: ReducedForm | None = shown(template=False)
    conserved: Mapping[str, Expr] | None = shown(template=False)
    effective_potential: EffectiveForm | None = shown(template=False)
    notes: tuple[Note, ...] = shown(terminal=True)
    symbols: tuple[tuple[str, Expr], ...] = shown(json=None, template=False)


def core_sections(derivation: Derivation) -> CoreSections:
    """The sections about the equations of motion of ``derivation``, built once."""
    problem = derivation.problem
    coords = tuple(Coordinate(c.name, c.symbol, c.velocity, c.acceleration, c.description)
                   for c in problem.coordinates)
    substitutions = _substitutions(derivation)
    return CoreSections(
        format_version=FORMAT_VERSION, name=problem.name, description=problem.description, slug=problem.slug,
        time=problem.time, coordinates=coords,
        parameters=tuple(Parameter(p.name, p.symbol, p.description,
                                   "positive" if p.positive else ("real" if p.real else ""))
                         for p in problem.parameters),
        functions=tuple(Function(f.name, sympy.Symbol(f.name), f.description) for f in problem.functions),
        particles=tuple(Particle(p.name, p.mass, tuple(p.position)) for p in problem.particles),
        bodies=tuple(Body(b.name, b.mass, tuple(b.position), tuple(b.inertia), tuple(b.angular_velocity), b.planar)
                     for b in problem.bodies),
        gravity=tuple(problem.gravity) if problem.gravity is not None else None,
        kinetic=derivation.kinetic, potential=derivation.potential, lagrangian=derivation.lagrangian,
        loads=tuple(Load(t.label, _by_coordinate(coords, t.generalized, zeros=False)) for t in derivation.force_terms),
        constraints=_constraints(derivation, coords),
        equations=tuple(
            Equation(coords[i], derivation.momenta[i], derivation.momenta_rates[i], derivation.gradients[i],
                     derivation.generalized_forces[i], lhs, rhs)
            for i, (lhs, rhs) in enumerate(derivation.equation_sides)),
        equation_forms=tuple(derivation.equations),
        substitutions=substitutions,
        constrained=tuple(Side(coords[i], lhs, rhs) for i, (lhs, rhs) in enumerate(derivation.constrained_sides))
        if substitutions else (),
        matrix=_matrix_form(derivation, coords),
        accelerations=None if derivation.accelerations is None else tuple(
            Solved(c.name, c.acceleration, derivation.accelerations[c.name]) for c in problem.coordinates),
        multipliers=None if derivation.multipliers is None else tuple(
            Solved(c.name, c.multiplier, derivation.multipliers[c.name]) for c in derivation.constraints),
        solve_note=next((n.reason for n in derivation.notes if n.stage == "explicit solve"), "it did not finish"),
        forces=_forces(derivation, coords),
        friction=tuple(_friction(f, coords, derivation) for f in derivation.friction),
        **_contract(derivation),
        notes=tuple(Note(n.stage, n.kind, n.reason, n.sentence()) for n in derivation.notes),
        symbols=tuple(problem.symbols.items()),
    )


def _constraints(derivation: Derivation, coords: tuple[Coordinate, ...]) -> tuple[Constraint, ...]:
    unilateral = {c.name for c in derivation.problem.constraints if c.unilateral}
    velocities = derivation.model.velocities
    return tuple(
        Constraint(c.name, c.kind, c.multiplier, c.expression,
                   sum((a * v for a, v in zip(c.coefficients, velocities, strict=True)), c.offset),
                   _by_coordinate(coords, c.coefficients), c.offset, c.acceleration_rhs, tuple(c.on),
                   c.name in unilateral)
        for c in derivation.constraints)


def _substitutions(derivation: Derivation) -> tuple[Substitution, ...]:
    elimination = derivation.elimination
    out = tuple(Substitution(sym, val, elimination.sources.get(sym, ""))
                for sym, val in [*elimination.positions.items(), *elimination.velocities.items()])
    return out + tuple(Substitution(sym, val, "") for sym, val in derivation.eliminated_accelerations.items())


def _matrix_form(derivation: Derivation, coords: tuple[Coordinate, ...]) -> MatrixForm:
    lagrange, accelerations = derivation.lagrange, derivation.model.accelerations
    mass, forcing = derivation.mass_matrix, derivation.forcing
    rows = []
    for i, coordinate in enumerate(coords):
        lhs = sum((mass[i, k] * a for k, a in enumerate(accelerations)), sympy.Integer(0))
        part = lagrange.constraint_forces[i]
        rows.append(MatrixRow(coordinate, lhs, forcing[i], part, forcing[i] + part))
    constrained = bool(derivation.constraints)
    # a bulk system's M and F are display forms already, their common factors out (bulk.light): not again
    shown = (lambda m: m) if len(coords) > BULK_SYSTEM else (lambda m: m.applyfunc(sympy.factor_terms))
    return MatrixForm(
        mass=mass, forcing=tuple(forcing), mass_shown=shown(mass), forcing_shown=shown(forcing),
        jacobian=lagrange.constraint_jacobian if constrained else None,
        rhs_shown=lagrange.constraint_rhs.applyfunc(sympy.factor_terms) if constrained else None,
        unknowns=sympy.Matrix(list(accelerations) + list(derivation.multiplier_symbols)),
        rows=tuple(rows), by_rows=len(coords) > LARGE,
    )


def _forces(derivation: Derivation, coords: tuple[Coordinate, ...]) -> tuple[ConstraintForce, ...] | None:
    if derivation.constraint_forces is None:
        return None
    out = []
    for c in derivation.constraints:
        result = derivation.constraint_forces[c.name]
        generalized = _by_coordinate(coords, result.generalized) if result.generalized else ()
        out.append(ConstraintForce(
            name=c.name,
            vector=tuple(result.vector) if result.vector is not None else None,
            magnitude=result.magnitude,
            particles=tuple(ParticleForce(p, tuple(vec), mag) for p, vec, mag in result.particles)
            if len(result.particles) > 1 else (),
            generalized=generalized,
            note=result.note,
            generalized_shown=tuple(g for g in generalized if g.value != 0),
        ))
    return tuple(out)


def _friction(f: Any, coords: tuple[Coordinate, ...], derivation: Derivation) -> Friction:
    term = f.term
    implicit = f.normal_force == term.normal and f.system is not None
    body = any(b.name == term.particle for b in derivation.problem.bodies)
    return Friction(
        name=term.name, normal_force=f.normal_force, force=tuple(f.force or term.force),
        generalized=_by_coordinate(coords, f.generalized or term.generalized),
        valid_while=term.valid_while, case=f.case, condition=f.valid_while, system=f.system,
        particle=term.particle, against=term.against, point=tuple(term.point) if body else None,
        rate=term.sliding_rate, tangent=None if term.tangent is None else tuple(term.tangent),
        held=None if f.sticking is None else Held(f.sticking.force, f.sticking.normal, f.sticking.ratio),
        members=tuple(ContactMember(m.member, tuple(m.normal), tuple(m.friction), tuple(m.total), m.magnitude)
                      for m in f.members),
        coefficient=term.coefficient, normal=term.normal, constraints=tuple(term.constraints),
        term_force=tuple(term.force), term_generalized=_by_coordinate(coords, term.generalized, zeros=False),
        static=term.static,
        # an implicit N is shown by the equation it solves, N = |a + B N|, not as "N = N"
        normal_shown=f.system.rhs if implicit else f.normal_force,
    )


def _contract(derivation: Derivation) -> dict[str, Any]:
    """The contract forms ``reduced``, ``conserved``, ``effective_potential`` (format section 2) as records."""
    reduced, effective = derivation.reduced, derivation.effective_potential
    return {
        "reduced": None if reduced is None else ReducedForm(tuple(reduced["independent"]),
                                                            dict(reduced["accelerations"])),
        "conserved": None if derivation.conserved is None else dict(derivation.conserved),
        "effective_potential": None if effective is None else EffectiveForm(
            effective["coordinate"], effective["expression"],
            tuple(EquilibriumForm(e["value"], e["stable"], e["frequency"]) for e in effective["equilibria"])),
    }
