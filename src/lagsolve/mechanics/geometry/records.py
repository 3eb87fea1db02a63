"""The records of a sketch (:mod:`lagsolve.mechanics.geometry.shapes` decides them): anchors, rods, surfaces, curves,
surfaces of revolution, strings, springs, blades, bodies, arrows and the :class:`Geometry` that lists them, and two
helpers every part of the decision uses (the fixed part of a position, a distance the coordinates keep fixed).
Kept apart so that ``geometry.py`` and its parts (``geometry_curves.py``, ``geometry_links.py``,
``geometry_bodies.py``, ``geometry_forces.py``) import it and not each other."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy

#: an expression larger than this (in operations) is not simplified to look for a fixed distance
SIZE_LIMIT = 400


@dataclass(frozen=True)
class Anchor:
    """One end of a rod, string or spring: the particle (or body) ``particle``, or (``particle`` None) the point
    ``point``, whose components hold time and parameters only (a pivot, fixed or driven), or the coordinates of
    what it moves with (the foot of a spring on a wall)."""

    particle: str | None
    point: tuple[Any, ...] = ()


@dataclass(frozen=True)
class Rod:
    """A fixed distance ``length`` between ``start`` and ``end``; ``constraint`` names the
    constraint that fixes it, or is None where the coordinates do."""

    start: Anchor
    end: Anchor
    length: Any
    constraint: str | None


@dataclass(frozen=True)
class Surface:
    """The line (a plane in 3-D) through ``point`` across ``normal`` on which ``particle`` stays.

    ``point`` may hold the coordinates of ``carrier``, the particle that carries the surface (the wedge). The
    material is on the side of the line that ``solid`` points to (its component along the normal decides; empty:
    nothing is solid). ``implied``: no constraint names it, the coordinates hold the particle across gravity (a
    floor or table), and ``constraint`` is its equation."""

    constraint: str
    particle: str
    point: tuple[Any, ...]
    normal: tuple[Any, ...]
    unilateral: bool = False
    solid: tuple[Any, ...] = ()
    carrier: str | None = None
    implied: bool = False


@dataclass(frozen=True)
class Curve:
    """The curve ``shape(u)`` (one expression per component of ``particle``'s position) along
    which the constraint ``constraint`` lets the particle move; ``coordinate`` is u.
    A circle of a unilateral distance constraint has ``coordinate`` None and ``centre``,
    ``radius`` set instead.

    ``shape`` may hold the time or other coordinates (``moving``: drawn where it is at each sample); ``closed``:
    periodic in u (an angle), drawn over a whole turn; ``solid``: the inside is material (a sphere, a cylinder)."""

    constraint: str
    particle: str
    coordinate: Any
    shape: tuple[Any, ...]
    centre: tuple[Any, ...] = ()
    radius: Any = None
    moving: bool = False
    closed: bool = False
    solid: bool = False


@dataclass(frozen=True)
class Revolution:
    """A surface of revolution on which ``particle`` stays: ``shape`` is its position with the constraints
    solved, a function of the two ``coordinates``; its axis is the coordinate axis ``axis`` (0, 1, 2) through
    ``centre``, and its height along the axis is a function of the distance from it."""

    constraint: str
    particle: str
    shape: tuple[Any, ...]
    coordinates: tuple[Any, ...]
    axis: int
    centre: tuple[Any, ...]


@dataclass(frozen=True)
class String:
    """A string of constant length from ``ends[0]`` to its pulley point ``anchors[0]``, on to ``anchors[1]`` and
    down to ``ends[1]``: the constraint's force on each end has the same magnitude and lies along the strand.
    ``slides[i]`` is the strand's fixed direction where the pulley's place along the strand is not given (the
    run places it so that no strand has a negative length); empty where the strand turns about the anchor."""

    constraint: str
    ends: tuple[str, str]
    anchors: tuple[tuple[Any, ...], tuple[Any, ...]]
    slides: tuple[tuple[Any, ...], tuple[Any, ...]]


@dataclass(frozen=True)
class Spring:
    """A ``spring`` (a potential term quadratic in a distance), a ``damper`` (a dissipation term quadratic in its
    rate) or a ``centre`` of force (any other potential of a distance) between ``start`` and ``end``; ``wall``
    is the normal of the plane ``start`` lies on (a spring fixed to a wall), else empty. ``length`` is the
    spring's natural length (None for the others). ``term`` is the potential or dissipation term it stands for
    (a SymPy expression, printed by ``render/``); ``label`` names it in the element list (the kind, with the term in
    SymPy's syntax where it is short)."""

    label: str
    kind: str
    start: Anchor
    end: Anchor
    wall: tuple[Any, ...] = ()
    length: Any = None
    term: Any = None


@dataclass(frozen=True)
class Blade:
    """A knife edge (a skate) of ``particle``: the velocity constraint ``constraint`` lets it move only along
    ``direction``."""

    constraint: str
    particle: str
    direction: tuple[Any, ...]


@dataclass(frozen=True)
class Body:
    """How a rigid body is drawn (``geometry_bodies.py``).

    ``shape``: ``disc`` (round, of ``radius``: its contact point keeps its direction from the centre while the
    body turns), ``bar`` (it hangs from ``pivot``, a point or a member, and the line to it turns with the body),
    ``plate`` (anything else), or in space ``disc``/``top``. In the plane ``angle`` is its angle as an expression
    of the coordinates, or None where only its rate ``rate`` is known (integrated along the run). In space
    ``rotation`` holds the 3 × 3 matrix from body axes to space axes, ``axis`` the body axis of symmetry and
    ``spin`` the rate of turn about it not in ``rotation`` (None: none). ``contact`` is the point where a disc
    touches what it rolls or slides on (in the plane); ``rolls``: a disc in space rolls on a floor across gravity
    at the lowest point of its rim."""

    name: str
    shape: str
    centre: tuple[Any, ...]
    radius: Any = None
    angle: Any = None
    rate: Any = None
    pivot: Anchor | None = None
    rotation: tuple[tuple[Any, ...], ...] = ()
    axis: int = 0
    spin: Any = None
    contact: tuple[Any, ...] = ()
    rolls: bool = False


@dataclass(frozen=True)
class Arrow:
    """A force drawn as an arrow: of the constraint (``kind`` ``constraint``, index ``index`` into the
    multipliers) or friction contact (``friction``, index into the contacts) named ``label``, on ``member`` at
    ``point``. A constraint's force is the multiplier times ``direction``; a friction force is the run's friction
    value times ``direction`` (the unit tangent) or, where ``planar``, that magnitude along minus ``direction``
    (the sliding velocity) normalised. ``sign`` is −1 for the second member of a pair (the opposite force)."""

    label: str
    kind: str
    index: int
    member: str
    point: tuple[Any, ...]
    direction: tuple[Any, ...]
    sign: int = 1
    planar: bool = False


@dataclass(frozen=True)
class Geometry:
    """Everything a sketch of the problem draws besides the particles."""

    rods: tuple[Rod, ...]
    surfaces: tuple[Surface, ...]
    curves: tuple[Curve, ...]
    revolutions: tuple[Revolution, ...] = ()
    strings: tuple[String, ...] = ()
    springs: tuple[Spring, ...] = ()
    blades: tuple[Blade, ...] = ()
    bodies: tuple[Body, ...] = ()
    arrows: tuple[Arrow, ...] = ()
    markers: tuple[tuple[str, tuple[Any, ...]], ...] = ()
    gravity: tuple[Any, ...] = field(default=())

    @property
    def pivots(self) -> tuple[Anchor, ...]:
        """The fixed or driven points things hang from or turn about (rods' ends that are points, bodies'
        pivots, springs' fixed ends that are not on a wall), each once."""
        out: list[Anchor] = []
        ends = [end for rod in self.rods for end in (rod.start, rod.end)]
        ends += [b.pivot for b in self.bodies if b.pivot is not None]
        ends += [s.start for s in self.springs if not s.wall and s.kind != "centre"]
        for end in ends:
            if end.particle is None and end not in out:
                out.append(end)
        return tuple(out)

    def elements(self) -> tuple[tuple[str, str, tuple[str, ...]], ...]:
        """Every element as (kind, label, members): ``("rod", "", ("upper", "lower"))``, ``("surface", "floor",
        ("foot",))``, ``("string", "string", ("m1", "m2"))``, ... in a fixed order (what the tests check)."""
        out: list[tuple[str, str, tuple[str, ...]]] = []
        for rod in self.rods:
            out.append(("rod", rod.constraint or "", tuple(e.particle or "pivot" for e in (rod.start, rod.end))))
        out += [("pivot", "", ()) for _ in self.pivots]
        for s in self.surfaces:
            kind = "support" if s.implied else "surface"
            out.append((kind, s.constraint, (s.particle,) + ((s.carrier,) if s.carrier else ())))
        for c in self.curves:
            kind = "solid" if c.solid else ("moving wire" if c.moving else "wire")
            out.append((kind, c.constraint, (c.particle,)))
        out += [("revolution", r.constraint, (r.particle,)) for r in self.revolutions]
        out += [("string", s.constraint, s.ends) for s in self.strings]
        out += [(s.kind, s.label, tuple(e.particle or "fixed" for e in (s.start, s.end))) for s in self.springs]
        out += [("blade", b.constraint, (b.particle,)) for b in self.blades]
        out += [(f"body {b.shape}", b.name, (b.pivot.particle or "pivot",) if b.pivot else ()) for b in self.bodies]
        out += [(f"arrow {a.kind}", a.label, (a.member,)) for a in self.arrows]
        out += [("marker", name, ()) for name, _ in self.markers]
        return tuple(out)


def free_part(position: tuple[Any, ...], coordinates: list[Any]) -> tuple[Any, ...]:
    """The terms of each (expanded) component that hold no coordinate: the point a pendulum hangs from."""
    expanded = [sympy.expand(r) for r in position]
    return tuple(sum((t for t in sympy.Add.make_args(r) if not t.free_symbols & set(coordinates)), sympy.Integer(0))
                 for r in expanded)


def fixed_distance(difference: list[Any], coordinates: list[Any]) -> Any:
    """|difference| when it depends on coordinates component-wise but its length does not; else None."""
    if not any(d.free_symbols & set(coordinates) for d in difference):
        return None
    square = sum((d * d for d in difference), sympy.Integer(0))
    if sympy.count_ops(square) > SIZE_LIMIT:
        return None
    square = sympy.trigsimp(sympy.expand(square))
    if square.free_symbols & set(coordinates) or square == 0:
        return None
    return sympy.sqrt(square)
