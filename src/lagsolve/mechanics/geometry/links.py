"""Strings, axles, springs, dampers, centres of force, knife edges and supports: what joins or holds members.

Part of the sketch's geometry (:mod:`lagsolve.mechanics.geometry.shapes`), decided symbolically from the problem:

* a **string** is a holonomic constraint on two particles whose force on each, the least-norm solution
  :math:`\\mathbf f` of :math:`J^T\\mathbf f = \\partial\\psi/\\partial q`, has the same magnitude on both and lies
  along the strand: from the particle to the coordinate-free part of its position (a hole, a pulley), either
  turning about that point or keeping a fixed direction (then the pulley may be anywhere along it);
* an **axle** is a velocity constraint with constant coefficients (integrable: :math:`\\sum_i a_i q_i` stays
  constant) that keeps the offset of two members fixed, the wheel's centre that moves with the cart;
* a **spring** is a potential term :math:`h(w)` with :math:`h'' > 0` constant, where :math:`w` is the distance
  of two members, of a member from a fixed point, or their offset along a coordinate axis (or a member's
  distance from a wall across that axis); a **damper** a dissipation term in the rate of such a :math:`w` (or a
  generalized force :math:`-b\\,\\dot q`); a **centre** of force any other potential of a member's distance
  from a fixed point (the attracting sun). :math:`T = h(w)` is tested by the vanishing of every 2 × 2 minor of
  :math:`(\\partial T/\\partial q, \\partial w/\\partial q)`;
* a **knife edge** is a homogeneous velocity constraint :math:`\\mathbf n\\cdot\\mathbf v_p = 0` on one particle,
  which lets it move only across :math:`\\mathbf n`;
* a **support** (floor, table, rail) is implied where the coordinates let a particle move only across gravity
  and nothing else holds it (no rod, wire or surface);
* **markers**: a problem without particles or bodies whose kinetic energy is :math:`c\\,\\dot q^2/2` in one
  coordinate (not an angle) is a mass on a line, drawn at :math:`(q, 0)`.
"""

from __future__ import annotations

from itertools import combinations
from typing import Any

import sympy

from lagsolve.mechanics.geometry.records import (
    SIZE_LIMIT,
    Anchor,
    Blade,
    Rod,
    Spring,
    String,
    Surface,
    fixed_distance,
    free_part,
)
from lagsolve.mechanics.symbolic.points import random_point
from lagsolve.problem.schema import ConstraintKind, Problem


def _zero(expr: Any) -> bool:
    if expr == 0:
        return True
    if sympy.count_ops(expr) > SIZE_LIMIT:
        return False
    return bool(sympy.simplify(expr) == 0)


def _least_norm(J: sympy.Matrix, a: sympy.Matrix) -> sympy.Matrix | None:
    """The least-norm f with Jᵀ f = a (through the metric JᵀJ), simplified; None when it cannot be formed or does
    not reproduce a."""
    gram = (J.T * J).applyfunc(lambda e: sympy.trigsimp(sympy.expand(e)))
    if gram.det() == 0:
        return None
    try:
        y = gram.LUsolve(a)
    except (ValueError, ZeroDivisionError):
        return None
    f = (J * y).applyfunc(lambda e: sympy.trigsimp(sympy.cancel(e)))
    if not all(_zero(e) for e in (J.T * f - a)):
        return None
    return f


def string(problem: Problem, constraint: Any, particles: list[Any], coordinates: list[Any]) -> String | None:
    """A string between the two particles of a holonomic, time-independent constraint, or None."""
    psi = constraint.expression
    if psi.has(problem.time) or len(particles) != 2 or len(particles[0].position) != len(particles[1].position):
        return None
    used = [q for q in coordinates if psi.has(q) or any(r.has(q) for p in particles for r in p.position)]
    if not used or sum(sympy.count_ops(r) for p in particles for r in p.position) > SIZE_LIMIT:
        return None
    J = sympy.Matrix.vstack(*(sympy.Matrix(p.position).jacobian(used) for p in particles))
    a = sympy.Matrix([sympy.diff(psi, q) for q in used])
    f = _least_norm(J, a)
    if f is None:
        return None
    d = len(particles[0].position)
    forces = [list(f[:d]), list(f[d:])]
    lengths = [sum((c * c for c in part), sympy.Integer(0)) for part in forces]
    if _zero(lengths[0]) or not _zero(lengths[0] - lengths[1]):
        return None
    anchors, slides = [], []
    for p, force in zip(particles, forces, strict=True):
        anchor = free_part(p.position, coordinates)
        if not any(c.free_symbols & set(coordinates) for c in force):
            slides.append(tuple(force))
        elif _parallel(force, [r - c for r, c in zip(p.position, anchor, strict=True)]):
            slides.append(())
        else:
            return None
        anchors.append(anchor)
    return String(constraint.name, (particles[0].name, particles[1].name), (anchors[0], anchors[1]),
                  (slides[0], slides[1]))


def _parallel(u: list[Any], v: list[Any]) -> bool:
    if len(u) == 2:
        return _zero(u[0] * v[1] - u[1] * v[0])
    return all(_zero(u[i] * v[j] - u[j] * v[i]) for i, j in ((0, 1), (0, 2), (1, 2)))


def _members(problem: Problem, markers: tuple[tuple[str, tuple[Any, ...]], ...] = ()) -> list[tuple[str, tuple]]:
    return ([(p.name, tuple(p.position)) for p in problem.particles] + [(b.name, tuple(b.position))
            for b in problem.bodies] + list(markers))


def axles(problem: Problem, coordinates: list[Any]) -> list[Rod]:
    """Rods from velocity constraints with constant coefficients that keep two members' offset fixed."""
    variables = {*coordinates, problem.time}
    out: list[Rod] = []
    rates = [c.velocity for c in problem.coordinates]
    for constraint in problem.constraints:
        if constraint.kind != ConstraintKind.NONHOLONOMIC:
            continue
        a = [sympy.diff(constraint.expression, v) for v in rates]
        rest = sympy.expand(constraint.expression - sum((c * v for c, v in zip(a, rates, strict=True)),
                                                        sympy.Integer(0)))
        if rest != 0 or any(c.free_symbols & variables or c.has(*rates) for c in a):
            continue
        for (name1, r1), (name2, r2) in combinations(_members(problem), 2):
            if len(r1) != len(r2):
                continue
            offset = [sympy.expand(x - y) for x, y in zip(r1, r2, strict=True)]
            rows = [[sympy.diff(o, q) for q in coordinates] for o in offset]
            if not any(any(e != 0 for e in row) for row in rows):
                continue
            if all(_proportional(row, a) for row in rows):
                out.append(Rod(Anchor(name2), Anchor(name1), None, constraint.name))
    return out


def frames(problem: Problem, coordinates: list[Any], rods: list[Rod], drawn: list[Any]) -> list[Rod]:
    """The frame that joins bodies the coordinates move as one (pairwise fixed distances, no rod between them):
    the cart's axle between its two wheels, and from it to the chassis. In a group of three or more, the pair
    the others' feet fall between at a fixed fraction is the spine (the axle), each other member joined to its
    foot on it (a joint that moves with the frame); else each pair is joined. A body drawn turning about a member
    (``drawn``: the bodies' drawings, a bar pivoted on a block) is joined to it already."""
    members = [(p.name, tuple(p.position)) for p in problem.particles] + [(b.name, tuple(b.position))
                                                                           for b in problem.bodies]
    joined = {frozenset((r.start.particle, r.end.particle)) for r in rods}
    joined |= {frozenset((b.name, b.pivot.particle)) for b in drawn if b.pivot is not None}
    moving = [(n, r) for n, r in members if any(c.free_symbols & set(coordinates) for c in r)]
    if len(moving) > 8 or sum(sympy.count_ops(c) for _, r in moving for c in r) > SIZE_LIMIT:
        return []
    rigid = _rigid_pairs(moving, {b.name for b in problem.bodies}, joined, coordinates)
    out: list[Rod] = []
    for group in _groups(rigid, [n for n, _ in moving]):
        position = dict(moving)
        out += _spine(group, position, coordinates, rigid) or [
            Rod(Anchor(a), Anchor(b), rigid[frozenset((a, b))], None) for a, b in combinations(group, 2)
            if frozenset((a, b)) in rigid]
    return out


def _rigid_pairs(moving: list[tuple[str, tuple[Any, ...]]], bodies: set[str], joined: set[frozenset],
                 coordinates: list[Any]) -> dict[frozenset, Any]:
    """Each pair of moving members, one of them a body, not joined yet, whose distance the coordinates keep fixed,
    with that distance."""
    rigid: dict[frozenset, Any] = {}
    for (n1, r1), (n2, r2) in combinations(moving, 2):
        if len(r1) == len(r2) and frozenset((n1, n2)) not in joined and (n1 in bodies or n2 in bodies):
            length = fixed_distance([a - b for a, b in zip(r1, r2, strict=True)], coordinates)
            if length is not None:
                rigid[frozenset((n1, n2))] = length
    return rigid


def _groups(pairs: dict[frozenset, Any], order: list[str]) -> list[list[str]]:
    """The members each pairwise rigid group holds (every pair of the group in ``pairs``), in ``order``."""
    out: list[list[str]] = []
    for name in order:
        for group in out:
            if all(frozenset((name, m)) in pairs for m in group):
                group.append(name)
                break
        else:
            if any(name in pair for pair in pairs):
                out.append([name])
    return [g for g in out if len(g) > 1]


def _spine(group: list[str], position: dict[str, tuple[Any, ...]], coordinates: list[Any],
           rigid: dict[frozenset, Any]) -> list[Rod] | None:
    """The spine of a rigid group of three or more (the pair every other member's foot lies between at a fixed
    fraction) and the rods to it; None when no pair is one, or for two members."""
    if len(group) < 3:
        return None
    for a, b in combinations(group, 2):
        ra, rb = position[a], position[b]
        along = [y - x for x, y in zip(ra, rb, strict=True)]
        square = sympy.trigsimp(sympy.expand(sum((c * c for c in along), sympy.Integer(0))))
        rods = [Rod(Anchor(a), Anchor(b), rigid[frozenset((a, b))], None)]
        for c in (m for m in group if m not in (a, b)):
            dot = sum(((z - x) * d for x, z, d in zip(ra, position[c], along, strict=True)), sympy.Integer(0))
            k = sympy.simplify(sympy.trigsimp(sympy.expand(dot)) / square)
            if k.free_symbols & set(coordinates) or not (k.is_number and 0 < k < 1):
                break
            foot = tuple(sympy.expand(x + k * d) for x, d in zip(ra, along, strict=True))
            rods.append(Rod(Anchor(None, foot), Anchor(c), None, None))
        else:
            return rods
    return None


def _proportional(row: list[Any], a: list[Any]) -> bool:
    """row = κ a with κ constant (possibly 0)."""
    k = next((i for i, c in enumerate(a) if c != 0), None)
    if k is None:
        return False
    kappa = sympy.simplify(row[k] / a[k])
    return bool(kappa.is_constant()) and all(_zero(r - kappa * c) for r, c in zip(row, a, strict=True))


def markers(problem: Problem) -> tuple[tuple[str, tuple[Any, ...]], ...]:
    """A mass on a line for a problem without particles and bodies whose one coordinate has the kinetic energy
    c q̇²/2 (and is not an angle)."""
    if problem.particles or problem.bodies or problem.kinetic is None or len(problem.coordinates) != 1:
        return ()
    (c,) = problem.coordinates
    if c.unit is not None and c.unit.strip() in ("rad", "radian", "deg", "degree"):
        return ()
    inertia = sympy.diff(problem.kinetic, c.velocity, 2)
    if inertia.free_symbols & {c.symbol, c.velocity} or sympy.expand(problem.kinetic - inertia * c.velocity ** 2 / 2):
        return ()
    return ((c.name, (c.symbol, sympy.Integer(0))),)


def _measures(problem: Problem, coordinates: list[Any], members: list[tuple[str, tuple]]) -> list[tuple]:
    """Candidate distances: (w, start anchor, end anchor, wall normal), pair distances first, then distances from
    a fixed point, offsets along an axis, distances from a wall."""
    out: list[tuple] = []
    for (n1, r1), (n2, r2) in combinations(members, 2):
        if len(r1) == len(r2):
            w = _signed_length([b - a for a, b in zip(r1, r2, strict=True)], coordinates)
            if w is not None:
                out.append((w, Anchor(n1), Anchor(n2), ()))
    for name, r in members:
        if sum(1 for x in r if x.free_symbols & set(coordinates)) < 2:
            continue  # moves along one axis: a spring to a wall across it (below), not to a point
        centre = free_part(r, coordinates)
        w = _signed_length([x - c for x, c in zip(r, centre, strict=True)], coordinates)
        if w is not None:
            out.append((w, Anchor(None, centre), Anchor(name), ()))
    for (n1, r1), (n2, r2) in combinations(members, 2):
        if len(r1) == len(r2):
            for k in range(len(r1)):
                w = sympy.expand(r2[k] - r1[k])
                if w.free_symbols & set(coordinates):
                    out.append((w, Anchor(n1), Anchor(n2), ()))
    for name, r in members:
        for k in range(len(r)):
            w = sympy.expand(r[k])
            if w.free_symbols & set(coordinates):
                foot = tuple(sympy.Integer(0) if j == k else x for j, x in enumerate(r))
                wall = tuple(sympy.Integer(int(j == k)) for j in range(len(r)))
                out.append((w, Anchor(None, foot), Anchor(name), wall))
    return out


def _signed_length(difference: list[Any], coordinates: list[Any]) -> Any:
    """|difference| as an expression without a root (the argument of an absolute value), or None."""
    if not any(d.free_symbols & set(coordinates) for d in difference):
        return None
    square = sum((d * d for d in difference), sympy.Integer(0))
    if sympy.count_ops(square) > SIZE_LIMIT:
        return None
    root = sympy.sqrt(sympy.factor(sympy.trigsimp(sympy.expand(square))))
    if isinstance(root, sympy.Abs):
        root = root.args[0]
    if root.has(sympy.Abs) or any(isinstance(p, sympy.Pow) and not p.exp.is_integer
                                  for p in sympy.preorder_traversal(root)):
        return None
    return root if root.free_symbols & set(coordinates) else None


def _function_of(term: Any, w: Any, variables: list[Any]) -> bool:
    """Whether ``term`` depends on ``variables`` only through ``w`` (every 2 × 2 minor of the gradients is 0)."""
    dt = [sympy.diff(term, q) for q in variables]
    dw = [sympy.diff(w, q) for q in variables]
    if all(e == 0 for e in dt) or all(e == 0 for e in dw):
        return False
    return all(_zero(dt[i] * dw[j] - dt[j] * dw[i]) for i, j in combinations(range(len(variables)), 2)) and all(
        e != 0 or dt[i] == 0 for i, e in enumerate(dw))


def springs(problem: Problem, coordinates: list[Any], marked: tuple[tuple[str, tuple], ...] = ()) -> list[Spring]:
    """Springs and centres of force from the potential's terms, dampers from the dissipation's terms and from
    generalized forces -b q̇."""
    members = _members(problem, marked)
    if not members:
        return []
    measures = _measures(problem, coordinates, members)
    terms = list(sympy.Add.make_args(problem.potential)) if problem.potential is not None else []
    out: list[Spring] = []
    for term in terms:
        spring = _spring(term, measures, coordinates)
        if spring is not None:
            out.append(spring)
    for term in _damping_terms(problem, coordinates):
        damper = _damper(term, measures, problem, coordinates)
        if damper is not None:
            out.append(damper)
    return out


def _spring(term: Any, measures: list[tuple], coordinates: list[Any]) -> Spring | None:
    """The spring (a term h(w) with constant h''(w): its natural length is where h' vanishes) or centre of force
    (a term in the distance from a fixed point) that a term of the potential is, through the first measure it is a
    function of that makes it one; None when it is neither."""
    for w, start, end, wall in measures:
        if not _function_of(term, w, coordinates):
            continue
        k = next(i for i, q in enumerate(coordinates) if sympy.diff(w, q) != 0)
        q = coordinates[k]
        slope = sympy.simplify(sympy.diff(term, q) / sympy.diff(w, q))  # h'(w)
        curvature = sympy.simplify(sympy.diff(slope, q) / sympy.diff(w, q))  # h''(w)
        if curvature != 0 and not curvature.free_symbols & set(coordinates):
            length = sympy.simplify(w - slope / curvature)
            return Spring(_label(term, "spring"), "spring", start, end, wall, length, term)
        if start.particle is None and not wall:
            return Spring(_label(term, "centre"), "centre", start, end, term=term)
    return None


def _damping_terms(problem: Problem, coordinates: list[Any]) -> list[Any]:
    """The terms of the dissipation function, then b q̇²/2 for each generalized force -b q̇ (b constant)."""
    rates = {c.velocity: c.symbol for c in problem.coordinates}
    damping = list(sympy.Add.make_args(problem.dissipation)) if problem.dissipation is not None else []
    for force in problem.forces:
        if force.coordinate is not None and len(force.value) == 1:
            q = next(c for c in problem.coordinates if c.name == force.coordinate)
            b = -sympy.diff(force.value[0], q.velocity)
            if b != 0 and not b.free_symbols & (set(rates) | set(coordinates)) and sympy.expand(
                    force.value[0] + b * q.velocity) == 0:
                damping.append(b * q.velocity ** 2 / 2)
    return damping


def _damper(term: Any, measures: list[tuple], problem: Problem, coordinates: list[Any]) -> Spring | None:
    """The damper a dissipation term is along the first linear measure it is a function of (of its rate), or
    None."""
    rates = {c.velocity: c.symbol for c in problem.coordinates}
    moved = term.xreplace(rates)  # the rate of w is a function of the rates as w is of the coordinates
    for w, start, end, wall in measures:
        if _linear(w, coordinates) and _function_of(moved, w, coordinates):
            return Spring(_label(term, "damper"), "damper", start, end, wall, term=term)
    return None


def _linear(w: Any, coordinates: list[Any]) -> bool:
    return all(not sympy.diff(w, q).free_symbols & set(coordinates) for q in coordinates)


def _label(term: Any, kind: str) -> str:
    """The element's name in the element list (tests, checks): the kind, with the term in SymPy's syntax where it
    is short; a sketch's legend prints ``term`` itself (``render/sketch.py``)."""
    text = sympy.sstr(term)
    return kind if len(text) > 24 else f"{kind} ({text})"


def blades(problem: Problem, coordinates: list[Any]) -> list[Blade]:
    """Knife edges: homogeneous velocity constraints n·v = 0 on a member in the plane: the one the constraint is
    ``on``, or, for a constraint on none, every particle or body whose velocity it is n·v = 0 of (the wheels on a
    cart's axle: the axle's sideways velocity is each wheel's)."""
    from lagsolve.mechanics.geometry.curves import holds

    out: list[Blade] = []
    rates = [c.velocity for c in problem.coordinates]
    members = {name: position for name, position in _members(problem) if len(position) == 2}
    for constraint in problem.constraints:
        if constraint.kind != ConstraintKind.NONHOLONOMIC or len(constraint.on) > 1 or constraint.at is not None:
            continue
        if holds(constraint, problem) is not None:
            continue
        a = sympy.Matrix([sympy.diff(constraint.expression, v) for v in rates])
        if sympy.expand(constraint.expression - (a.T * sympy.Matrix(rates))[0]) != 0:
            continue
        names = list(constraint.on) if constraint.on else list(members)
        for name in names:
            if name in members:
                n = _across(members[name], coordinates, a)
                if n is not None:
                    out.append(Blade(constraint.name, name, (-n[1], n[0])))
    return out


def _across(position: tuple[Any, ...], coordinates: list[Any], a: sympy.Matrix) -> Any:
    """The n with Jᵀ n = a (J the Jacobian of ``position``): the velocity constraint a·q̇ = 0 is n·v = 0 of that
    point; None when there is none. n = (J Jᵀ)⁻¹ J a is left unsimplified: the sketch only evaluates it. Whether it
    exists is tested at random states (J Jᵀ regular, Jᵀ n = a), symbolically where a declared function is in it
    (simplifying n symbolically took the differential drive's sketch 12 s)."""
    J = sympy.Matrix(position).jacobian(coordinates)
    gram = J * J.T
    if any(m.has(sympy.core.function.AppliedUndef, sympy.Derivative) for m in (J, a)):
        return _across_symbolic(gram, J, a)
    solvable = _solvable(gram, J, a)
    if solvable is None:  # no random state could be evaluated: decide symbolically
        return _across_symbolic(gram, J, a)
    return gram.LUsolve(J * a) if solvable else None


def _across_symbolic(gram: sympy.Matrix, J: sympy.Matrix, a: sympy.Matrix) -> Any:
    gram = gram.applyfunc(sympy.trigsimp)
    if gram.det() == 0:
        return None
    n = (gram.LUsolve(J * a)).applyfunc(sympy.trigsimp)
    return n if all(_zero(e) for e in (J.T * n - a)) else None


#: random states at which a knife edge's n is tested (each of up to four times as many draws may fall outside the
#: expressions' domain and is then skipped)
ACROSS_STATES = 4


def _solvable(gram: sympy.Matrix, J: sympy.Matrix, a: sympy.Matrix) -> bool | None:
    """Whether J Jᵀ is regular and Jᵀ n = a has a solution, at :data:`ACROSS_STATES` random states (numbers); None
    when no state could be evaluated."""
    import random

    import numpy as np

    symbols = sorted(gram.free_symbols | J.free_symbols | a.free_symbols, key=sympy.default_sort_key)
    values = sympy.lambdify(symbols, [gram.tolist(), J.tolist(), a.tolist()], modules="math")
    rng = random.Random(11)
    seen = 0
    for _ in range(4 * ACROSS_STATES):
        try:
            g, j, coefficients = (np.array(m, dtype=float) for m in values(*random_point(symbols, rng)))
        except (ArithmeticError, TypeError, ValueError):  # outside a domain (a complex value): another state
            continue
        scale = max(1.0, float(np.abs(g).max()))
        if abs(float(np.linalg.det(g))) <= 1e-12 * scale ** len(g):
            return False
        n = np.linalg.solve(g, j @ coefficients)
        if float(np.abs(j.T @ n - coefficients).max()) > 1e-9 * max(1.0, float(np.abs(coefficients).max())):
            return False
        seen += 1
        if seen == ACROSS_STATES:
            return True
    return None if seen == 0 else True


def supports(problem: Problem, coordinates: list[Any], holding: set[str | None],
             surfaces: list[Surface]) -> list[Surface]:
    """A floor or table through each particle the coordinates move only across gravity and nothing holds."""
    gravity = problem.gravity
    out: list[Surface] = []
    if gravity is None or all(g == 0 for g in gravity):
        return out
    for p in problem.particles:
        if p.name in holding or len(p.position) != len(gravity):
            continue
        moves = [[sympy.diff(r, q) for r in p.position] for q in coordinates]
        if not any(any(c != 0 for c in m) for m in moves):
            continue
        if all(_zero(sum((g * c for g, c in zip(gravity, m, strict=True)), sympy.Integer(0))) for m in moves):
            out.append(Surface(f"surface under {p.name}", p.name, tuple(p.position), tuple(gravity), implied=True))
    return out
