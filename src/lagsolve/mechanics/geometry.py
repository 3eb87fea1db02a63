"""What a problem looks like: rods, pivots, surfaces and wires, read from its constraints.

The sketch of a system (and each frame of its animation) draws what this module
decides; ``numeric/scene.py`` evaluates it along a trajectory and ``render/plots.py``
only draws. Three kinds of shape are recognised, symbolically:

* **rods** — a distance that stays fixed:

  - a holonomic constraint :math:`k\\,(|\\mathbf r_i-\\mathbf r_j|^2-l^2)` between two
    particles, or :math:`k\\,(|\\mathbf r_i-\\mathbf c|^2-l^2)` from a fixed point
    :math:`\\mathbf c` (the pivot), with the particles in Cartesian coordinates;
  - a distance the coordinates themselves keep fixed: :math:`|\\mathbf r_i-\\mathbf r_j|`
    or :math:`|\\mathbf r_i-\\mathbf a_i|` free of the coordinates, where
    :math:`\\mathbf a_i` is the part of :math:`\\mathbf r_i` without coordinates (the
    pivot of a pendulum in angles, which may move with time);

* **surfaces** — a constraint linear in a particle's Cartesian position with constant
  coefficients and no explicit time (a floor, a wall, an incline, possibly carried by
  another particle: the block on a wedge); drawn as the line through ``point`` across
  ``normal``;
* **curves** — a constraint that, solved for one coordinate, leaves the particle's
  position a function of a single other coordinate ``u`` and not of time (a wire
  :math:`y=f(x)`, a circle :math:`r=R` in polar coordinates); a unilateral distance
  constraint (a particle on a sphere) is a curve too, the circle it must stay outside
  or inside of, not a rod.

Anything else (velocity constraints, constraints that move with time, bodies) is not
drawn; the sketch then shows the particles alone.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.problem.schema import Problem

#: an expression larger than this (in operations) is not simplified to look for a fixed distance
SIZE_LIMIT = 400


@dataclass(frozen=True)
class Anchor:
    """One end of a rod: the particle ``particle``, or (``particle`` None) the point ``point``,
    whose components hold time and parameters only (a pivot, fixed or driven)."""

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
    ``point`` may hold the coordinates of the particle that carries the surface."""

    constraint: str
    particle: str
    point: tuple[Any, ...]
    normal: tuple[Any, ...]
    unilateral: bool = False


@dataclass(frozen=True)
class Curve:
    """The curve ``shape(u)`` (one expression per component of ``particle``'s position) along
    which the constraint ``constraint`` lets the particle move; ``coordinate`` is u.
    A circle of a unilateral distance constraint has ``coordinate`` None and ``centre``,
    ``radius`` set instead."""

    constraint: str
    particle: str
    coordinate: Any
    shape: tuple[Any, ...]
    centre: tuple[Any, ...] = ()
    radius: Any = None


@dataclass(frozen=True)
class Geometry:
    """Everything a sketch of the problem draws besides the particles."""

    rods: tuple[Rod, ...]
    surfaces: tuple[Surface, ...]
    curves: tuple[Curve, ...]

    @property
    def pivots(self) -> tuple[Anchor, ...]:
        """The rods' ends that are points, not particles, each once."""
        out: list[Anchor] = []
        for rod in self.rods:
            for end in (rod.start, rod.end):
                if end.particle is None and end not in out:
                    out.append(end)
        return tuple(out)


def geometry(problem: Problem) -> Geometry:
    """Classify the problem's constraints and particles into rods, surfaces and curves.

    >>> from lagsolve.problem.load import load_problem
    >>> g = geometry(load_problem("problems/double_pendulum.yaml"))
    >>> [(r.start.particle, r.end.particle) for r in g.rods]
    [(None, 'upper'), ('upper', 'lower')]
    """
    coordinates = [c.symbol for c in problem.coordinates]
    variables = {*coordinates, problem.time}
    rods: list[Rod] = []
    surfaces: list[Surface] = []
    curves: list[Curve] = []
    particles = {p.name: p for p in problem.particles}
    for constraint in problem.constraints:
        if constraint.kind != "holonomic":
            continue
        on = [name for name in constraint.on if name in particles]
        if not on and not constraint.on and len(particles) == 1:
            on = list(particles)  # the one particle a constraint without "on" can act on
        if not on or len(on) > 2 or len(on) != len(constraint.on or on):
            continue
        shape = _classify(constraint, [particles[name] for name in on], coordinates, variables)
        if isinstance(shape, Rod):
            rods.append(shape)
        elif isinstance(shape, Surface):
            surfaces.append(shape)
        elif isinstance(shape, Curve):
            curves.append(shape)
    rods += _implied_rods(problem, coordinates, variables, rods)
    return Geometry(tuple(rods), tuple(surfaces), tuple(curves))


def _classify(constraint: Any, particles: list[Any], coordinates: list[Any], variables: set[Any]) -> Any:
    psi = constraint.expression
    if sympy.diff(psi, next(iter(variables - set(coordinates)))) != 0:  # moves with time: not drawn
        return None
    cartesian = [_cartesian_symbols(p.position, coordinates) for p in particles]
    if all(c is not None for c in cartesian):
        shape = _cartesian_shape(constraint, particles, cartesian, coordinates)
        if shape is not None:
            return shape
    if len(particles) == 1:
        return _curve(constraint, particles[0], coordinates, variables)
    return None


def _cartesian_symbols(position: tuple[Any, ...], coordinates: list[Any]) -> list[Any] | None:
    """For a position whose components are each a coordinate or free of coordinates: those
    components (None for a fixed one); None when a component mixes coordinates."""
    out = []
    for component in position:
        if component in coordinates:
            out.append(component)
        elif component.free_symbols & set(coordinates):
            return None
        else:
            out.append(None)
    return out if any(s is not None for s in out) else None


def _cartesian_shape(constraint: Any, particles: list[Any], cartesian: list[Any], coordinates: list[Any]) -> Any:
    """A surface (linear in the first particle's position) or a distance (quadratic) constraint."""
    psi = sympy.expand(constraint.expression)
    mine = [s for s in cartesian[0] if s is not None]
    own = set(mine)
    others = set(coordinates) - own
    gradient = [sympy.diff(psi, s) if s is not None else sympy.Integer(0) for s in cartesian[0]]
    first = particles[0]
    if all(not (g.free_symbols & set(coordinates)) for g in gradient) and any(g != 0 for g in gradient):
        # linear: n . r + c = 0, or n . (r - r_other) + c = 0 for a surface carried by another particle
        base = particles[1].position if len(particles) == 2 else tuple(sympy.Integer(0) for _ in gradient)
        if len(base) != len(gradient):
            return None
        rest = sympy.expand(psi - sum((g * (s - b) for g, s, b in zip(gradient, cartesian[0], base, strict=True)
                                       if s is not None), sympy.Integer(0)))
        if rest.free_symbols & set(coordinates):
            return None
        size = sum((g * g for g in gradient), sympy.Integer(0))
        point = tuple(sympy.simplify(b - rest * g / size) for g, b in zip(gradient, base, strict=True))
        return Surface(constraint.name, first.name, point, tuple(gradient), constraint.unilateral)
    # quadratic: psi = k |r - c|^2 + const with the same k for every component
    if any(s is None for s in cartesian[0]):
        return None
    second = [sympy.diff(psi, s, 2) for s in cartesian[0]]
    if len(set(second)) != 1:
        return None
    k: Any = second[0] / 2
    if k == 0 or k.free_symbols & set(coordinates):
        return None
    centre = [sympy.expand(s - sympy.diff(psi, s) / (2 * k)) for s in mine]
    if any(c.free_symbols & own for c in centre):
        return None
    mixed = sympy.expand(psi - k * sum(((s - c) ** 2 for s, c in zip(mine, centre, strict=True)), sympy.Integer(0)))
    if mixed.free_symbols & set(coordinates):
        return None
    square = sympy.simplify(-mixed / k)
    length = sympy.sqrt(square)
    if len(particles) == 2:
        other = particles[1]
        target = [v for s, v in zip(cartesian[0], first.position, strict=True) if s is not None]
        partner = [v for s, v in zip(cartesian[0], other.position, strict=True) if s is not None]
        if len(partner) != len(target) or any(sympy.expand(c - p) != 0 for c, p in zip(centre, partner, strict=True)):
            return None
        if constraint.unilateral:
            return None
        return Rod(Anchor(other.name), Anchor(first.name), length, constraint.name)
    if any(c.free_symbols & others for c in centre):
        return None
    full = []
    it = iter(centre)
    for s, v in zip(cartesian[0], first.position, strict=True):
        full.append(next(it) if s is not None else v)
    if constraint.unilateral:
        return Curve(constraint.name, first.name, None, (), tuple(full), length)
    return Rod(Anchor(None, tuple(full)), Anchor(first.name), length, constraint.name)


def _curve(constraint: Any, particle: Any, coordinates: list[Any], variables: set[Any]) -> Curve | None:
    """Solve the constraint for the last coordinate it gives linearly with a constant coefficient;
    a curve when one coordinate is left in the particle's position."""
    psi = constraint.expression
    position = particle.position
    used = [q for q in coordinates if any(r.has(q) for r in position)]
    for q in reversed(used):
        a = sympy.diff(psi, q)
        if a == 0 or a.free_symbols & variables or a.atoms(sympy.core.function.AppliedUndef):
            continue
        value = sympy.expand(q - psi / a)
        shape = tuple(r.xreplace({q: value}) for r in position)
        left = [u for u in coordinates if any(r.has(u) for r in shape)]
        if len(left) == 1 and not any(r.has(next(iter(variables - set(coordinates)))) for r in shape):
            return Curve(constraint.name, particle.name, left[0], shape)
        return None
    return None


def _implied_rods(problem: Problem, coordinates: list[Any], variables: set[Any], explicit: list[Rod]) -> list[Rod]:
    """Distances the coordinates keep fixed: from each particle's coordinate-free part (its pivot),
    and between pairs of particles."""
    known = {frozenset((r.start.particle, r.end.particle)) for r in explicit}
    out: list[Rod] = []
    particles = problem.particles
    for i, p in enumerate(particles):
        if not any(r.free_symbols & set(coordinates) for r in p.position):
            continue
        for other in particles[:i]:
            if frozenset((other.name, p.name)) in known or len(other.position) != len(p.position):
                continue
            length = _fixed_distance([a - b for a, b in zip(p.position, other.position, strict=True)], coordinates)
            if length is not None:
                out.append(Rod(Anchor(other.name), Anchor(p.name), length, None))
        if any(r.end.particle == p.name for r in out) or frozenset((None, p.name)) in known:
            continue  # hangs from another particle already
        expanded = [sympy.expand(r) for r in p.position]
        pivot = tuple(sum((t for t in sympy.Add.make_args(r) if not t.free_symbols & set(coordinates)),
                          sympy.Integer(0)) for r in expanded)
        length = _fixed_distance([r - c for r, c in zip(expanded, pivot, strict=True)], coordinates)
        if length is not None:
            out.append(Rod(Anchor(None, pivot), Anchor(p.name), length, None))
    names = [x.name for x in particles]
    out.sort(key=lambda r: names.index(r.end.particle or ""))
    return out


def _fixed_distance(difference: list[Any], coordinates: list[Any]) -> Any:
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
