"""What a problem looks like: what its sketch (and each frame of its animation) draws, read from its structure.

This module decides, symbolically and from the problem alone (never from the file's name), what each part of
the system is; ``numeric/scene.py`` evaluates it along a trajectory and ``render/sketch.py`` only draws. The
record, :class:`Geometry`, lists every element (:meth:`Geometry.elements`):

* **rods** — a distance that stays fixed: a holonomic constraint :math:`k\\,(|\\mathbf r_i-\\mathbf r_j|^2-l^2)`
  between two particles or :math:`k\\,(|\\mathbf r_i-\\mathbf c|^2-l^2)` from a fixed point (the pivot), with
  the particles in Cartesian coordinates; a distance the coordinates keep fixed (:math:`|\\mathbf r_i-\\mathbf
  a_i|` free of the coordinates, :math:`\\mathbf a_i` the part of :math:`\\mathbf r_i` without coordinates:
  the pivot of a pendulum in angles, which may be driven); an integrated velocity constraint that keeps two
  members' offset fixed (the axle of a cart's wheel); the frame of bodies the coordinates move as one (the
  differential drive's axle between its wheels and the chassis at its midpoint, ``links.frames``);
* **surfaces** — a constraint linear in a particle's Cartesian position with constant coefficients (a floor, a
  wall, an incline, possibly carried by another particle: the face of a wedge), a straight line a constraint
  leaves a particle on, the straight locus of a body's contact point (``at:``), and the **support** the
  coordinates imply: a particle that only moves across gravity and is held by nothing else rests on a floor
  or table through it. ``solid`` says on which side the material is (where a unilateral constraint forbids,
  or the side gravity presses on);
* **curves** (wires, tubes, hoops) — the constraints on one particle, solved together, leave its position a
  function of one coordinate; a curve that holds the time or another coordinate moves (a rotating tube or
  hoop is drawn where it is at each instant); a closed one is drawn whole; a unilateral distance constraint or
  the circle a body's contact point keeps to is a solid (a sphere, a cylinder);
* **surfaces of revolution** (a cone, a bowl) — the constraints leave the position on a surface whose height
  along a coordinate axis is a function of the distance from that axis (``geometry_curves.py``);
* **strings**, **springs**, **dampers**, **centres of force** and **knife edges** (``links.py``);
* **bodies** — discs, bars and plates in the plane, and bodies in space with their orientation
  (``bodies.py``);
* **arrows** — each force of constraint and each friction force at its point (``geometry_forces.py``, from
  the matrix form: :func:`sketch`).

A problem without particles or bodies whose kinetic energy is that of a mass on a line (the driven
oscillator) is drawn as one: a *marker* for each such coordinate.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.geometry import bodies as geometry_bodies
from lagsolve.mechanics.geometry import curves as geometry_curves
from lagsolve.mechanics.geometry import links as geometry_links
from lagsolve.mechanics.geometry.records import (
    SIZE_LIMIT,
    Anchor,
    Arrow,
    Blade,
    Body,
    Curve,
    Geometry,
    Revolution,
    Rod,
    Spring,
    String,
    Surface,
    fixed_distance,
    free_part,
)
from lagsolve.problem.schema import ConstraintKind, Problem

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.matrix_form import MatrixForm

__all__ = ["SIZE_LIMIT", "Anchor", "Arrow", "Blade", "Body", "Curve", "Geometry", "Revolution", "Rod", "Spring",
           "String", "Surface", "fixed_distance", "free_part", "geometry", "sketch"]


def geometry(problem: Problem) -> Geometry:
    """Classify the problem's constraints, particles, bodies and energies into the elements of its sketch.

    >>> from lagsolve.problem.load import load_problem
    >>> g = geometry(load_problem("problems/double_pendulum.yaml"))
    >>> [(r.start.particle, r.end.particle) for r in g.rods]
    [(None, 'upper'), ('upper', 'lower')]
    """

    coordinates = [c.symbol for c in problem.coordinates]
    variables = {*coordinates, problem.time}
    particles = {p.name: p for p in problem.particles}
    shapes, rest = _constraint_shapes(problem, particles, coordinates, variables)
    shapes += _joint_shapes(problem, particles, rest, coordinates, variables)
    rods: list[Rod] = _of_kind(shapes, Rod)
    surfaces: list[Surface] = [replace(s, solid=_solid(s, problem)) for s in _of_kind(shapes, Surface)]
    curves: list[Curve] = _of_kind(shapes, Curve)
    revolutions: list[Revolution] = _of_kind(shapes, Revolution)
    held = {c.particle for c in curves} | {r.particle for r in revolutions}
    rods += _implied_rods(problem, coordinates, variables, rods, held)
    rods += geometry_links.axles(problem, coordinates)
    bodies, contact_surfaces, contact_curves, rods = geometry_bodies.bodies(problem, coordinates, variables, rods)
    rods += geometry_links.frames(problem, coordinates, rods, bodies)
    surfaces += [replace(s, solid=_solid(s, problem)) for s in contact_surfaces]
    curves += contact_curves
    markers = geometry_links.markers(problem)
    springs = geometry_links.springs(problem, coordinates, markers)
    blades = geometry_links.blades(problem, coordinates)
    holding = _holding(rods, held, surfaces)
    surfaces += [replace(s, solid=_solid(s, problem))
                 for s in geometry_links.supports(problem, coordinates, holding, surfaces)]
    gravity = tuple(problem.gravity) if problem.gravity is not None else ()
    return Geometry(tuple(rods), tuple(surfaces), tuple(curves), tuple(revolutions), tuple(_of_kind(shapes, String)),
                    tuple(springs), tuple(blades), tuple(bodies), (), markers, gravity)


def _constraint_shapes(problem: Problem, particles: dict[str, Any], coordinates: list[Any],
                       variables: set[Any]) -> tuple[list[Any], dict[str, list[Any]]]:
    """The rods, surfaces, curves and strings the constraints on one or two particles are each alone, in the
    constraints' order, and per particle the constraints on it alone that are none of these (for
    :func:`_joint_shapes`)."""
    shapes: list[Any] = []
    rest: dict[str, list[Any]] = {}  # per particle, the constraints on it alone that are no rod or plane
    for constraint in problem.constraints:
        on = _acted_on(constraint, particles)
        if not on:
            continue
        if constraint.kind != ConstraintKind.HOLONOMIC:
            if len(on) == 1 and geometry_curves.holds(constraint, problem) is not None:
                rest.setdefault(on[0], []).append(constraint)
            continue
        shape = _classify(constraint, [particles[name] for name in on], coordinates, variables)
        if shape is None and len(on) == 1:
            rest.setdefault(on[0], []).append(constraint)
        elif shape is None:
            shape = geometry_links.string(problem, constraint, [particles[n] for n in on], coordinates)
        if shape is not None:
            shapes.append(shape)
    return shapes, rest


def _acted_on(constraint: Any, particles: dict[str, Any]) -> list[str]:
    """The one or two particles a constraint acts on (the one particle, for a constraint without ``on`` in a
    problem with one); none when it names no particle, more than two, or a body."""
    on = [name for name in constraint.on if name in particles]
    if not on and not constraint.on and len(particles) == 1:
        on = list(particles)  # the one particle a constraint without "on" can act on
    if not on or len(on) > 2 or len(on) != len(constraint.on or on):
        return []
    return on


def _joint_shapes(problem: Problem, particles: dict[str, Any], rest: dict[str, list[Any]], coordinates: list[Any],
                  variables: set[Any]) -> list[Any]:
    """The surface, curve or surface of revolution each particle's remaining constraints leave it on together."""
    shapes: list[Any] = []
    for name, constraints in rest.items():
        shape = geometry_curves.joint(problem, particles[name], constraints, coordinates, variables)
        if shape is not None:
            shapes.append(shape)
    return shapes


def _of_kind(shapes: list[Any], kind: type) -> list[Any]:
    """The shapes of one kind, in their order."""
    return [s for s in shapes if isinstance(s, kind)]


def _holding(rods: list[Rod], held: set[str], surfaces: list[Surface]) -> set[Any]:
    """The particles something other than a floor holds against gravity: a rod from a fixed point, a wire or
    surface of revolution (``held``), a surface."""
    return {r.end.particle for r in rods if r.start.particle is None} | held | {s.particle for s in surfaces}


def sketch(form: MatrixForm) -> Geometry:
    """:func:`geometry` of the form's problem, with an arrow for each force of constraint and friction force
    whose point and direction the matrix form knows (``geometry_forces.py``)."""
    from lagsolve.mechanics.geometry.forces import arrows

    return replace(geometry(form.problem), arrows=arrows(form))


def _solid(surface: Surface, problem: Problem) -> tuple[Any, ...]:
    """The side of a surface that is material: as decided already (beyond a body's contact point), where a
    unilateral constraint forbids (against its force), else the side gravity presses a particle on it against;
    none without gravity."""
    if surface.solid:
        return surface.solid
    if surface.unilateral:
        return tuple(-n for n in surface.normal)
    if problem.gravity is not None and len(problem.gravity) == len(surface.normal):
        return tuple(problem.gravity)
    return ()


def _classify(constraint: Any, particles: list[Any], coordinates: list[Any], variables: set[Any]) -> Any:
    psi = constraint.expression
    if sympy.diff(psi, next(iter(variables - set(coordinates)))) != 0:  # moves with time: a curve, if any
        return None
    cartesian = [_cartesian_symbols(p.position, coordinates) for p in particles]
    if all(c is not None for c in cartesian):
        shape = _cartesian_shape(constraint, particles, cartesian, coordinates)
        if shape is not None:
            return shape
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
    gradient = [sympy.diff(psi, s) if s is not None else sympy.Integer(0) for s in cartesian[0]]
    if _linear(gradient, coordinates):
        return _surface(constraint, psi, particles, cartesian[0], gradient, coordinates)
    sphere = _sphere(psi, cartesian[0], coordinates)
    if sphere is None:
        return None
    centre, length = sphere
    if len(particles) == 2:
        return _rod_between(constraint, particles, cartesian[0], centre, length)
    return _about_a_fixed_centre(constraint, particles[0], cartesian[0], centre, length, coordinates)


def _linear(gradient: list[Any], coordinates: list[Any]) -> bool:
    """Whether a constraint with this gradient in a particle's Cartesian coordinates is linear in them (and not
    free of them)."""
    return all(not (g.free_symbols & set(coordinates)) for g in gradient) and any(g != 0 for g in gradient)


def _surface(constraint: Any, psi: Any, particles: list[Any], symbols: list[Any], gradient: list[Any],
             coordinates: list[Any]) -> Surface | None:
    """The plane of a linear constraint: n . r + c = 0, or n . (r - r_other) + c = 0 for a surface carried by the
    second particle; None when the rest of the constraint holds coordinates."""
    first = particles[0]
    base = particles[1].position if len(particles) == 2 else tuple(sympy.Integer(0) for _ in gradient)
    if len(base) != len(gradient):
        return None
    rest = sympy.expand(psi - sum((g * (s - b) for g, s, b in zip(gradient, symbols, base, strict=True)
                                   if s is not None), sympy.Integer(0)))
    if rest.free_symbols & set(coordinates):
        return None
    size = sum((g * g for g in gradient), sympy.Integer(0))
    point = tuple(sympy.simplify(b - rest * g / size) for g, b in zip(gradient, base, strict=True))
    carrier = particles[1].name if len(particles) == 2 else None
    return Surface(constraint.name, first.name, point, tuple(gradient), constraint.unilateral, carrier=carrier)


def _sphere(psi: Any, symbols: list[Any], coordinates: list[Any]) -> tuple[list[Any], Any] | None:
    """The centre and radius of a quadratic constraint psi = k |r - c|^2 + const with the same k for every
    component (every component a coordinate, the centre free of them); None for any other."""
    if any(s is None for s in symbols):
        return None
    second = [sympy.diff(psi, s, 2) for s in symbols]
    if len(set(second)) != 1:
        return None
    k: Any = second[0] / 2
    if k == 0 or k.free_symbols & set(coordinates):
        return None
    centre = [sympy.expand(s - sympy.diff(psi, s) / (2 * k)) for s in symbols]
    if any(c.free_symbols & set(symbols) for c in centre):
        return None
    mixed = sympy.expand(psi - k * sum(((s - c) ** 2 for s, c in zip(symbols, centre, strict=True)),
                                       sympy.Integer(0)))
    if mixed.free_symbols & set(coordinates):
        return None
    square = sympy.simplify(-mixed / k)
    return centre, sympy.sqrt(square)


def _rod_between(constraint: Any, particles: list[Any], symbols: list[Any], centre: list[Any], length: Any
                 ) -> Rod | None:
    """A rod between two particles, when the sphere's centre is the second particle (and the constraint is
    two-sided)."""
    first, other = particles
    target = [v for s, v in zip(symbols, first.position, strict=True) if s is not None]
    partner = [v for s, v in zip(symbols, other.position, strict=True) if s is not None]
    if len(partner) != len(target) or any(sympy.expand(c - p) != 0 for c, p in zip(centre, partner, strict=True)):
        return None
    if constraint.unilateral:
        return None
    return Rod(Anchor(other.name), Anchor(first.name), length, constraint.name)


def _about_a_fixed_centre(constraint: Any, particle: Any, symbols: list[Any], centre: list[Any], length: Any,
                          coordinates: list[Any]) -> Rod | Curve | None:
    """A rod from a pivot at the sphere's centre, or a solid sphere or cylinder for a unilateral constraint; None
    when the centre moves with another coordinate."""
    others = set(coordinates) - set(symbols)
    if any(c.free_symbols & others for c in centre):
        return None
    full = []
    it = iter(centre)
    for s, v in zip(symbols, particle.position, strict=True):
        full.append(next(it) if s is not None else v)
    if constraint.unilateral:
        return Curve(constraint.name, particle.name, None, (), tuple(full), length, closed=True, solid=True)
    return Rod(Anchor(None, tuple(full)), Anchor(particle.name), length, constraint.name)


def _implied_rods(problem: Problem, coordinates: list[Any], variables: set[Any], explicit: list[Rod],
                  held: set[str]) -> list[Rod]:
    """Distances the coordinates keep fixed: from each particle's coordinate-free part (its pivot),
    and between pairs of particles. A particle on a wire or surface of revolution is held by it, not by a rod
    (the bead on a hoop keeps its distance from the centre because the hoop is round)."""
    known = {frozenset((r.start.particle, r.end.particle)) for r in explicit}
    out: list[Rod] = []
    particles = problem.particles
    for i, p in enumerate(particles):
        if p.name in held or not any(r.free_symbols & set(coordinates) for r in p.position):
            continue
        for other in particles[:i]:
            if frozenset((other.name, p.name)) in known or len(other.position) != len(p.position):
                continue
            length = fixed_distance([a - b for a, b in zip(p.position, other.position, strict=True)], coordinates)
            if length is not None:
                out.append(Rod(Anchor(other.name), Anchor(p.name), length, None))
        if any(r.end.particle == p.name for r in out) or frozenset((None, p.name)) in known:
            continue  # hangs from another particle already
        pivot = free_part(p.position, coordinates)
        length = fixed_distance([r - c for r, c in zip(p.position, pivot, strict=True)], coordinates)
        if length is not None:
            out.append(Rod(Anchor(None, pivot), Anchor(p.name), length, None))
        elif not any(r.end.particle == p.name for r in explicit):
            out += _jointed_rod(problem, p, coordinates)
    names = [x.name for x in particles]
    out.sort(key=lambda r: names.index(r.end.particle or ""))
    return out


def _jointed_rod(problem: Problem, particle: Any, coordinates: list[Any]) -> list[Rod]:
    """A rod that hangs ``particle`` from a joint on another member: the other member whose coordinates are the
    most of the particle's (the compound pendulum a bob hangs from), the particle's offset from it split into the
    terms in the particle's own further coordinates (a vector of fixed length: the rod) and the rest, free of them
    (the joint, which moves with the member). PyDy's bob a length l below the end of a bar: a rod from the bar's
    end. Nothing when no member leaves such a split."""
    own = set().union(*(r.free_symbols for r in particle.position)) & set(coordinates)
    candidates: list[Any] = [*problem.particles, *problem.bodies]
    members = [m for m in candidates if m.name != particle.name and len(m.position) == len(particle.position)]
    ranked = []
    for m in members:
        theirs = set().union(*(r.free_symbols for r in m.position)) & set(coordinates)
        if theirs and theirs < own:
            ranked.append((-len(theirs), m.name, m, own - theirs))
    for _, _, member, further in sorted(ranked, key=lambda x: (x[0], x[1])):
        offset = [sympy.expand(a - b) for a, b in zip(particle.position, member.position, strict=True)]
        rod = [sum((t for t in sympy.Add.make_args(d) if t.free_symbols & further), sympy.Integer(0)) for d in offset]
        rest = [d - r for d, r in zip(offset, rod, strict=True)]
        if any(r.free_symbols & further for r in rest) or all(r == 0 for r in rest):
            continue
        length = fixed_distance(rod, coordinates)
        if length is not None:
            joint = tuple(sympy.simplify(b + r) for b, r in zip(member.position, rest, strict=True))
            return [Rod(Anchor(None, joint), Anchor(particle.name), length, None)]
    return []
