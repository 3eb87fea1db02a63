"""Frozen dataclasses of the problem format (``shared/problem-format.md``, section 1).

No SymPy import and no I/O here: expression fields hold whatever the loader's
parser produced (SymPy objects), typed ``Any`` at this boundary.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, fields
from typing import Any

from lagsolve.enums import TextEnum

Expr = Any  # a SymPy expression, made only by lagsolve.problem.expr


@dataclass(frozen=True)
class Parameter:
    """A constant symbol; ``value`` is an optional default used by simulation."""

    name: str
    description: str
    positive: bool
    real: bool
    value: float | None
    symbol: Expr
    unit: str | None = None  # as written in the file (checked by lagsolve.problem.units); None: not declared


@dataclass(frozen=True)
class FunctionDecl:
    """An unspecified function such as the wire shape ``f``."""

    name: str
    description: str
    function: Any  # sympy UndefinedFunction
    unit: str | None = None  # the unit of its value


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate with its velocity and acceleration symbols."""

    name: str
    description: str
    symbol: Expr
    velocity: Expr
    acceleration: Expr
    unit: str | None = None


@dataclass(frozen=True)
class Particle:
    name: str
    mass: Expr
    position: tuple[Expr, ...]


@dataclass(frozen=True)
class Body:
    """A rigid body: planar (scalar ``inertia`` and ``angular_velocity``) or 3-D
    (principal moments and body-frame angular velocity components)."""

    name: str
    mass: Expr
    position: tuple[Expr, ...]
    inertia: tuple[Expr, ...]
    angular_velocity: tuple[Expr, ...]

    @property
    def planar(self) -> bool:
        return len(self.inertia) == 1


class ConstraintKind(TextEnum):
    """How a constraint is written: at position level, psi(q, t) = 0, or at velocity level."""

    HOLONOMIC = "holonomic"
    NONHOLONOMIC = "nonholonomic"


@dataclass(frozen=True)
class Constraint:
    """``holonomic``: psi(q, t) = 0; ``nonholonomic``: sum a_i q_i_dot + b = 0 as written."""

    name: str
    kind: ConstraintKind
    expression: Expr
    on: tuple[str, ...]  # particles it acts on (or the one body, with ``at``); empty when unknown
    line: int
    unilateral: bool = False  # holds only while its force pushes (lambda >= 0); see docs/format.md
    # the point of ``on[0]`` where it acts (problem coordinates). Given, the constraint is a *contact*: with a
    # second name in ``on`` that member gets the opposite force at the same point (Newton's third law)
    at: tuple[Expr, ...] | None = None


@dataclass(frozen=True)
class Force:
    """A generalized force on one coordinate, or a physical force on a particle."""

    coordinate: str | None
    on: str | None
    value: tuple[Expr, ...]  # one component for a generalized force


@dataclass(frozen=True)
class Friction:
    """A Coulomb friction contact between ``on`` (the particle or planar body that slides) and ``against``
    (the particle or planar body that carries the surface; None: the fixed surroundings), acting at the
    point ``at`` of ``on`` (a particle's own position). ``normal`` names the constraints whose combined
    force on ``on`` is the normal force; ``sliding`` the coordinates whose rates make the sliding velocity."""

    name: str
    coefficient: Expr
    static: Expr | None
    on: str
    normal: tuple[str, ...]
    sliding: tuple[str, ...]
    against: str | None = None
    at: tuple[Expr, ...] = ()


@dataclass(frozen=True)
class ConcreteFunction:
    """``"f(u)": "u**2/2"``: a declared function made concrete for simulation."""

    name: str
    arguments: tuple[Expr, ...]
    expression: Expr


@dataclass(frozen=True)
class Simulation:
    values: Mapping[str, float] = field(default_factory=dict)
    functions: Mapping[str, ConcreteFunction] = field(default_factory=dict)
    initial: Mapping[str, float] = field(default_factory=dict)
    t_end: float | None = None
    samples: int | None = None
    method: str | None = None
    rtol: float | None = None
    atol: float | None = None


class _Record(Mapping[str, Any]):
    """A typed record that also reads as the mapping of its given fields (those not None), as the file
    wrote it: ``"vector" in force``, ``force["magnitude"]``, ``force == {"magnitude": 0}``."""

    def _given(self) -> list[str]:
        return [f.name for f in fields(self) if getattr(self, f.name) is not None]  # type: ignore[arg-type]

    def __getitem__(self, key: str) -> Any:
        if key not in self._given():
            raise KeyError(key)
        return getattr(self, key)

    def __iter__(self) -> Iterator[str]:
        return iter(self._given())

    def __len__(self) -> int:
        return len(self._given())


@dataclass(frozen=True, eq=False)
class ExpectedForce(_Record):
    """An expected force of constraint: its magnitude, its vector, or both."""

    magnitude: Expr | None = None
    vector: tuple[Expr, ...] | None = None


@dataclass(frozen=True, eq=False)
class ExpectedEquilibrium(_Record):
    """An expected equilibrium of the effective potential: where, whether stable, the small-oscillation frequency."""

    value: Expr
    stable: bool | None = None
    frequency: Expr | None = None


@dataclass(frozen=True, eq=False)
class ExpectedPotential(_Record):
    """The expected effective potential: its coordinate, its expression, its equilibria."""

    coordinate: str
    expression: Expr | None = None
    equilibria: tuple[ExpectedEquilibrium, ...] = ()


@dataclass(frozen=True, eq=False)
class ExpectedModes(_Record):
    """Expected small oscillations about an equilibrium of several coordinates: where (``at``, coordinate name →
    value; a coordinate left out is free along a continuum of equilibria), whether stable, the squared frequencies
    ω² of the normal modes, and their shapes (one per ω², in that order; components in the order of the file's
    coordinates, up to a non-zero factor)."""

    at: Mapping[str, Expr]
    stable: bool | None = None
    squared_frequencies: tuple[Expr, ...] | None = None
    shapes: tuple[tuple[Expr, ...], ...] | None = None


@dataclass(frozen=True, eq=False)
class ExpectedSteady(_Record):
    """Expected steady motions: the coordinate held fixed (its name stands for the fixed value), the cyclic
    coordinate turning at the constant rate (its velocity's name stands for the rate), the values of that rate,
    whether they are stable, and the frequency of small oscillations about them."""

    coordinate: str
    rate: str
    roots: tuple[Expr, ...] = ()  # the file's ``values``
    stable: bool | None = None
    frequency: Expr | None = None


@dataclass(frozen=True)
class Expected:
    """Answers given in the file; each maps a name to a parsed expression (or a typed record)."""

    accelerations: Mapping[str, Expr] = field(default_factory=dict)
    multipliers: Mapping[str, Expr] = field(default_factory=dict)
    constraint_forces: Mapping[str, ExpectedForce] = field(default_factory=dict)
    reduced: Mapping[str, Expr] = field(default_factory=dict)
    conserved: Mapping[str, Expr] = field(default_factory=dict)
    effective_potential: ExpectedPotential | None = None
    normal_modes: tuple[ExpectedModes, ...] = ()
    steady_motions: ExpectedSteady | None = None

    def is_empty(self) -> bool:
        return not (
            self.accelerations or self.multipliers or self.constraint_forces or self.reduced
            or self.conserved or self.effective_potential or self.normal_modes or self.steady_motions
        )


@dataclass(frozen=True)
class Problem:
    """A validated problem: every name declared once, every expression parsed.

    ``symbols`` maps each name an expression may use (time, parameters,
    coordinates, velocities) to its SymPy object; ``lines`` maps a dotted field
    path to its line in the file, for later messages. ``independent`` names the
    coordinates to keep as minimal coordinates (empty: chosen automatically).
    """

    source: str
    name: str
    description: str
    time: Expr
    parameters: tuple[Parameter, ...]
    functions: tuple[FunctionDecl, ...]
    coordinates: tuple[Coordinate, ...]
    particles: tuple[Particle, ...]
    bodies: tuple[Body, ...]
    gravity: tuple[Expr, ...] | None
    kinetic: Expr | None
    potential: Expr | None
    dissipation: Expr | None
    forces: tuple[Force, ...]
    constraints: tuple[Constraint, ...]
    friction: tuple[Friction, ...]
    expected: Expected
    simulation: Simulation | None
    symbols: Mapping[str, Expr]
    lines: Mapping[str, int]
    independent: tuple[str, ...] = ()  # optional choice of minimal coordinates (names, input order)
    time_unit: str | None = None  # declared with ``time: {name: t, unit: ms}``; seconds otherwise
    texts: Mapping[str, str] = field(default_factory=dict)  # dotted field -> expression as written
    # the units passed ``check_units`` already (in the command's process, where pint is loaded): a budgeted child
    # that derives it does not import pint and check them again
    units_checked: bool = False

    def __repr__(self) -> str:
        def count(n: int, what: str) -> str:
            return f"{n} {what}{'s' * (n != 1)}"

        parts = [count(len(self.coordinates), "coordinate")]
        parts += [count(len(items), what) for items, what in ((self.particles, "particle"), (self.bodies, "body"),
                                                              (self.constraints, "constraint"),
                                                              (self.friction, "friction contact")) if items]
        return f"<Problem {self.name!r} from {self.source}: {', '.join(parts)}>".replace("bodys", "bodies")

    @property
    def units(self) -> dict[str, str | None]:
        """The declared unit of each parameter, declared function and coordinate (None: not declared)."""
        return {**{p.name: p.unit for p in self.parameters}, **{f.name: f.unit for f in self.functions},
                **{c.name: c.unit for c in self.coordinates}}

    @property
    def has_units(self) -> bool:
        """Whether the file declares any unit (then its dimensions are checked and results carry units)."""
        return self.time_unit is not None or any(u is not None for u in self.units.values())

    @property
    def slug(self) -> str:
        """The file's stem: ``problems/bead.yaml`` → ``bead`` (names output files)."""
        stem = self.source.replace("\\", "/").rsplit("/", 1)[-1]
        return stem.rsplit(".", 1)[0] if "." in stem else stem

    def body(self, name: str) -> Body:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def particle(self, name: str) -> Particle:
        for p in self.particles:
            if p.name == name:
                return p
        raise KeyError(name)
