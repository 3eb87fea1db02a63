"""The sections of a report about the equations of motion, as data: what each shows, in display order.

:func:`core_sections` walks a :class:`~lagsolve.mechanics.results.Derivation` once and returns frozen
records that carry SymPy expressions and names, never printed strings. The projections
(:func:`lagsolve.render.report.context` for the templates, :func:`~lagsolve.render.report.result_dict` for
the JSON contract, :func:`~lagsolve.render.report.summary` for a terminal) print them, each in its own way,
so the outputs cannot list different things. Nothing here simplifies: every expression arrives in display
form (``factor_terms`` on the matrix form is the one tidying the reports have always shown).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation
    from lagsolve.mechanics.stages import StageNote

#: a SymPy expression (or matrix) as the derivation holds it
Expr = Any


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate: its name, the symbols q, q̇, q̈ and the file's description."""

    name: str
    symbol: Expr
    velocity: Expr
    acceleration: Expr
    description: str


@dataclass(frozen=True)
class Parameter:
    name: str
    symbol: Expr
    description: str
    assumption: str  # "positive", "real" or ""


@dataclass(frozen=True)
class Function:
    name: str
    symbol: Expr  # the function's name as a symbol (how the report writes f)
    description: str


@dataclass(frozen=True)
class Particle:
    name: str
    mass: Expr
    position: tuple[Expr, ...]


@dataclass(frozen=True)
class Body:
    name: str
    mass: Expr
    position: tuple[Expr, ...]
    inertia: tuple[Expr, ...]
    angular_velocity: tuple[Expr, ...]
    planar: bool


@dataclass(frozen=True)
class Load:
    """A force term (a load, a spring, a damper ...) by its generalized forces, one per coordinate."""

    label: str
    generalized: tuple[Expr, ...]


@dataclass(frozen=True)
class Constraint:
    """A constraint with its multiplier: f = 0 (or its velocity form Σ a q̇ + b = 0), A q̈ = β."""

    name: str
    kind: str
    multiplier: Expr
    expression: Expr
    velocity_form: Expr
    coefficients: tuple[Expr, ...]  # a, one per coordinate
    offset: Expr  # b
    acceleration_rhs: Expr
    on: tuple[str, ...]
    unilateral: bool


@dataclass(frozen=True)
class Equation:
    """Lagrange's equation of one coordinate, step by step: d/dt ∂L/∂q̇ − ∂L/∂q = Q (+ Σ λ a)."""

    coordinate: Coordinate
    momentum: Expr  # ∂L/∂q̇
    rate: Expr  # d/dt ∂L/∂q̇
    gradient: Expr  # ∂L/∂q
    force: Expr  # Q
    lhs: Expr
    rhs: Expr


@dataclass(frozen=True)
class Substitution:
    """A quantity written through the constraints (``source`` names the constraint, when known)."""

    symbol: Expr
    value: Expr
    source: str


@dataclass(frozen=True)
class Side:
    """An equation as its two sides (the i-th coordinate's)."""

    coordinate: Coordinate
    lhs: Expr
    rhs: Expr


@dataclass(frozen=True)
class MatrixRow:
    """Row i of M q̈ = F + Aᵀλ: Σ_k M_ik q̈_k, F_i and the multipliers' part (Aᵀλ)_i."""

    coordinate: Coordinate
    lhs: Expr
    forcing: Expr
    constraint_part: Expr


@dataclass(frozen=True)
class MatrixForm:
    """The matrix form as the contract gives it (``mass``, ``forcing``) and as a report shows it."""

    mass: Expr
    forcing: Expr
    mass_shown: Expr
    forcing_shown: Expr
    jacobian: Expr | None  # None without constraints
    rhs_shown: Expr | None
    unknowns: Expr
    rows: tuple[MatrixRow, ...]


@dataclass(frozen=True)
class Solved:
    """An explicit result: an acceleration q̈ = ..., or a multiplier λ = ... (``name``: its coordinate's
    or constraint's)."""

    name: str
    symbol: Expr
    value: Expr


@dataclass(frozen=True)
class ParticleForce:
    name: str
    vector: tuple[Expr, ...]
    magnitude: Expr


@dataclass(frozen=True)
class ConstraintForce:
    """The force of one constraint: on its particle or point (``vector``, ``magnitude``), on each of its
    particles when several, or, with no point named, its generalized forces λ a (``generalized``)."""

    name: str
    vector: tuple[Expr, ...] | None
    magnitude: Expr | None
    particles: tuple[ParticleForce, ...]  # only when it acts on more than one particle
    note: str
    generalized: tuple[tuple[Coordinate, Expr], ...]  # every coordinate (zeros too), or empty


@dataclass(frozen=True)
class ContactMember:
    """The force of a friction contact on one member: normal part, friction, their sum and its magnitude."""

    name: str
    normal: tuple[Expr, ...]
    friction: tuple[Expr, ...]
    total: tuple[Expr, ...]
    magnitude: Expr


@dataclass(frozen=True)
class Friction:
    """A friction contact: its term (with the symbol N), and N in closed form with the case that applies."""

    name: str
    particle: str  # the member that slides (a particle or a planar body)
    against: str | None  # the member that carries the surface (None: the surroundings)
    point: tuple[Expr, ...] | None  # the contact point, for a body (a particle's is its position)
    rate: Expr | None  # the sliding rate σ along the tangent, where it slides along one line
    tangent: tuple[Expr, ...] | None  # the unit tangent t along which it slides
    coefficient: Expr
    normal: Expr  # the symbol N
    constraints: tuple[str, ...]
    term_force: tuple[Expr, ...]  # with N as a symbol
    term_generalized: tuple[tuple[Coordinate, Expr], ...]
    valid_while: Expr
    static: Expr
    normal_force: Expr  # the closed form of N (N itself when only an implicit equation exists)
    normal_shown: Expr  # what a report writes after "N =": the equation N solves when N is implicit
    case: str
    condition: Expr | None  # when the closed form holds
    system: Expr | None  # Eq(N, |a + B N|)
    force: tuple[Expr, ...]  # the friction force with N put in
    generalized: tuple[tuple[Coordinate, Expr], ...]  # its generalized forces with N put in
    members: tuple[ContactMember, ...]  # the force on each member (empty when the forces are not known)
    held: tuple[Expr, Expr, Expr] | None = None  # while it sticks: the force Φ that holds it, N, and |Φ|/N
    held_note: str = ""  # why ``held`` is not given


@dataclass(frozen=True)
class CoreSections:
    """Everything a report shows about the equations of motion, in display order."""

    name: str
    description: str
    slug: str
    time: Expr
    coordinates: tuple[Coordinate, ...]
    parameters: tuple[Parameter, ...]
    functions: tuple[Function, ...]
    particles: tuple[Particle, ...]
    bodies: tuple[Body, ...]
    gravity: tuple[Expr, ...] | None
    kinetic: Expr
    potential: Expr
    lagrangian: Expr
    loads: tuple[Load, ...]
    constraints: tuple[Constraint, ...]
    equations: tuple[Equation, ...]
    equation_forms: tuple[Expr, ...]  # each equation as left minus right side (the contract's)
    substitutions: tuple[Substitution, ...]
    constrained: tuple[Side, ...]
    matrix: MatrixForm
    accelerations: tuple[Solved, ...] | None
    multipliers: tuple[Solved, ...] | None
    forces: tuple[ConstraintForce, ...] | None
    friction: tuple[Friction, ...]
    notes: tuple[StageNote, ...]
    symbols: tuple[tuple[str, Expr], ...]  # the problem's names, for the prose of notes and descriptions
    contract: tuple[tuple[str, Any], ...]  # the contract forms: reduced, conserved, effective_potential (or None)


def core_sections(derivation: Derivation) -> CoreSections:
    """The sections about the equations of motion of ``derivation``, built once."""
    problem, model = derivation.problem, derivation.model
    coords = tuple(Coordinate(c.name, c.symbol, c.velocity, c.acceleration, c.description)
                   for c in problem.coordinates)
    unilateral = {c.name for c in problem.constraints if c.unilateral}
    constraints = tuple(
        Constraint(c.name, c.kind, c.multiplier, c.expression,
                   sum((a * v for a, v in zip(c.coefficients, model.velocities, strict=True)), c.offset),
                   tuple(c.coefficients), c.offset, c.acceleration_rhs, tuple(c.on), c.name in unilateral)
        for c in derivation.constraints)
    equations = tuple(
        Equation(coords[i], derivation.momenta[i], derivation.momenta_rates[i], derivation.gradients[i],
                 derivation.generalized_forces[i], lhs, rhs)
        for i, (lhs, rhs) in enumerate(derivation.equation_sides))
    elimination = derivation.elimination
    substitutions = tuple(
        Substitution(sym, val, elimination.sources.get(sym, ""))
        for sym, val in [*elimination.positions.items(), *elimination.velocities.items()])
    substitutions += tuple(Substitution(sym, val, "") for sym, val in derivation.eliminated_accelerations.items())
    return CoreSections(
        name=problem.name, description=problem.description, slug=problem.slug, time=problem.time,
        coordinates=coords,
        parameters=tuple(Parameter(p.name, p.symbol, p.description,
                                   "positive" if p.positive else ("real" if p.real else ""))
                         for p in problem.parameters),
        functions=tuple(Function(f.name, sympy.Symbol(f.name), f.description) for f in problem.functions),
        particles=tuple(Particle(p.name, p.mass, tuple(p.position)) for p in problem.particles),
        bodies=tuple(Body(b.name, b.mass, tuple(b.position), tuple(b.inertia), tuple(b.angular_velocity), b.planar)
                     for b in problem.bodies),
        gravity=tuple(problem.gravity) if problem.gravity is not None else None,
        kinetic=derivation.kinetic, potential=derivation.potential, lagrangian=derivation.lagrangian,
        loads=tuple(Load(t.label, tuple(t.generalized)) for t in derivation.force_terms),
        constraints=constraints,
        equations=equations,
        equation_forms=tuple(derivation.equations),
        substitutions=substitutions,
        constrained=tuple(Side(coords[i], lhs, rhs) for i, (lhs, rhs) in enumerate(derivation.constrained_sides)),
        matrix=_matrix_form(derivation, coords),
        accelerations=None if derivation.accelerations is None else tuple(
            Solved(c.name, c.acceleration, derivation.accelerations[c.name]) for c in problem.coordinates),
        multipliers=None if derivation.multipliers is None else tuple(
            Solved(c.name, c.multiplier, derivation.multipliers[c.name]) for c in derivation.constraints),
        forces=_forces(derivation, coords),
        friction=tuple(_friction(f, coords, derivation) for f in derivation.friction),
        notes=tuple(derivation.notes),
        symbols=tuple(problem.symbols.items()),
        contract=(("reduced", derivation.reduced), ("conserved", derivation.conserved),
                  ("effective_potential", derivation.effective_potential)),
    )


def _matrix_form(derivation: Derivation, coords: tuple[Coordinate, ...]) -> MatrixForm:
    lagrange, accelerations = derivation.lagrange, derivation.model.accelerations
    mass, forcing = derivation.mass_matrix, derivation.forcing
    rows = tuple(
        MatrixRow(coordinate, sum((mass[i, k] * a for k, a in enumerate(accelerations)), sympy.Integer(0)),
                  forcing[i], lagrange.constraint_forces[i])
        for i, coordinate in enumerate(coords))
    constrained = bool(derivation.constraints)
    return MatrixForm(
        mass=mass, forcing=forcing,
        mass_shown=mass.applyfunc(sympy.factor_terms), forcing_shown=forcing.applyfunc(sympy.factor_terms),
        jacobian=lagrange.constraint_jacobian if constrained else None,
        rhs_shown=lagrange.constraint_rhs.applyfunc(sympy.factor_terms) if constrained else None,
        unknowns=sympy.Matrix(list(accelerations) + list(derivation.multiplier_symbols)),
        rows=rows,
    )


def _forces(derivation: Derivation, coords: tuple[Coordinate, ...]) -> tuple[ConstraintForce, ...] | None:
    if derivation.constraint_forces is None:
        return None
    out = []
    for c in derivation.constraints:
        result = derivation.constraint_forces[c.name]
        out.append(ConstraintForce(
            name=c.name,
            vector=tuple(result.vector) if result.vector is not None else None,
            magnitude=result.magnitude,
            particles=tuple(ParticleForce(p, tuple(vec), mag) for p, vec, mag in result.particles)
            if len(result.particles) > 1 else (),
            note=result.note,
            generalized=tuple(zip(coords, result.generalized, strict=True)) if result.generalized else (),
        ))
    return tuple(out)


def _friction(f: Any, coords: tuple[Coordinate, ...], derivation: Derivation) -> Friction:
    term = f.term
    implicit = f.normal_force == term.normal and f.system is not None
    body = any(b.name == term.particle for b in derivation.problem.bodies)
    return Friction(
        name=term.name, particle=term.particle, against=term.against, point=tuple(term.point) if body else None,
        rate=term.sliding_rate, tangent=None if term.tangent is None else tuple(term.tangent),
        coefficient=term.coefficient, normal=term.normal,
        constraints=tuple(term.constraints), term_force=tuple(term.force),
        term_generalized=tuple(zip(coords, term.generalized, strict=True)),
        valid_while=term.valid_while, static=term.static,
        normal_force=f.normal_force,
        # an implicit N is shown by the equation it solves, N = |a + B N|, not as "N = N"
        normal_shown=f.system.rhs if implicit else f.normal_force,
        case=f.case, condition=f.valid_while, system=f.system,
        force=tuple(f.force or term.force),
        generalized=tuple(zip(coords, f.generalized or term.generalized, strict=True)),
        members=tuple(ContactMember(m.member, tuple(m.normal), tuple(m.friction), tuple(m.total), m.magnitude)
                      for m in f.members),
        held=None if f.sticking is None else (f.sticking.force, f.sticking.normal, f.sticking.ratio),
        held_note=f.sticking_note,
    )
