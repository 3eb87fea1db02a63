"""Wires, tubes, hoops, lines and surfaces of revolution: where the constraints on one particle leave it.

Part of the sketch's geometry (:mod:`lagsolve.mechanics.geometry.shapes`). The constraints that act on one particle
alone (holonomic ones, possibly moving with time, and velocity constraints that hold one coordinate,
:math:`a\\,\\dot q_k + b(t) = 0`, whose value the run knows) are solved together, each for a coordinate of the
particle's position it gives linearly with a constant coefficient. What is left of the position:

* one free coordinate: a **curve** along which the particle moves — a **line** (a :class:`Surface` in the
  plane, drawn as an incline or floor) when it is straight and fixed, else a wire; it **moves** when it holds
  the time or a held coordinate (a tube or hoop that turns), and is **closed** when it is periodic in its
  coordinate (a hoop, a ring), so it is drawn over a whole turn;
* two free coordinates in space: a **surface of revolution** when its height along a coordinate axis is a
  function of the distance from that axis (a cone, a bowl): the Jacobian of (distance², height) with respect
  to the two coordinates is singular.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.geometry.records import SIZE_LIMIT, Curve, Revolution, Surface, fixed_distance, free_part
from lagsolve.problem.schema import ConstraintKind, Problem


def holds(constraint: Any, problem: Problem) -> Any:
    """The coordinate a velocity constraint :math:`a\\,\\dot q_k + b = 0` holds (``a`` and ``b`` free of the
    coordinates, ``b`` possibly of the time): it is then integrated by the run (θ̇ = 0 holds θ at its initial
    value, φ̇ − Ω = 0 turns φ uniformly). None for any other velocity constraint."""
    if constraint.kind == ConstraintKind.HOLONOMIC:
        return None
    expr = constraint.expression
    coordinates = {c.symbol for c in problem.coordinates}
    rates = [c for c in problem.coordinates if expr.has(c.velocity)]
    if len(rates) != 1:
        return None
    rate = rates[0].velocity
    a = sympy.diff(expr, rate)
    b = sympy.expand(expr - a * rate)
    if a == 0 or a.free_symbols & (coordinates | {problem.time}) or b.free_symbols & coordinates or b.has(rate):
        return None
    return rates[0].symbol


def _solve(psi: Any, candidates: list[Any], variables: set[Any]) -> tuple[Any, Any] | None:
    """``(q, value)`` with ψ = 0 ⇔ q = value, for the last candidate ψ holds linearly with a constant
    coefficient."""
    for q in reversed(candidates):
        a = sympy.diff(psi, q)
        if a == 0 or a.free_symbols & variables or a.atoms(sympy.core.function.AppliedUndef):
            continue
        value = sympy.expand(q - psi / a)
        if value.has(q):
            continue
        return q, value
    return None


def solve_together(problem: Problem, position: tuple[Any, ...], constraints: list[Any], coordinates: list[Any],
                   variables: set[Any]) -> tuple[tuple[Any, ...], list[Any], list[Any]] | None:
    """``position`` with the constraints solved: (the position, the coordinates solved or held, the coordinates
    it still moves along). None when a constraint cannot be solved for a coordinate of the position."""
    own = [q for q in coordinates if any(r.has(q) for r in position)]
    subs: dict[Any, Any] = {}
    held: list[Any] = []
    for constraint in constraints:
        if constraint.kind != ConstraintKind.HOLONOMIC:
            q = holds(constraint, problem)
            if q is None or q in held or q in subs:
                return None
            held.append(q)
            continue
        psi = constraint.expression.xreplace(subs)
        solved = _solve(psi, [q for q in own if q not in subs and q not in held], variables)
        if solved is None:
            return None
        q, value = solved
        subs = {k: sympy.expand(v.xreplace({q: value})) for k, v in subs.items()}
        subs[q] = value
    shape = tuple(sympy.expand(r.xreplace(subs)) for r in position)
    free = [q for q in own if q not in subs and q not in held and any(r.has(q) for r in shape)]
    return shape, [*subs, *held], free


def joint(problem: Problem, particle: Any, constraints: list[Any], coordinates: list[Any], variables: set[Any]
          ) -> Surface | Curve | Revolution | None:
    """The line, curve or surface of revolution on which ``constraints`` (all on ``particle`` alone) keep it."""
    solved = solve_together(problem, particle.position, constraints, coordinates, variables)
    if solved is None:
        return None
    shape, fixed, free = solved
    label = ", ".join(c.name for c in constraints)
    unilateral = any(c.unilateral for c in constraints)
    if len(free) == 1:
        return line_or_curve(label, particle.name, shape, free[0], fixed, coordinates, variables, unilateral)
    if len(free) == 2 and len(shape) == 3:
        return revolution(label, particle.name, shape, tuple(free), coordinates)
    return None


def line_or_curve(label: str, member: str, shape: tuple[Any, ...], u: Any, fixed: list[Any], coordinates: list[Any],
                  variables: set[Any], unilateral: bool = False, carrier: str | None = None) -> Surface | Curve:
    """A fixed straight line in the plane as a surface, anything else as a curve of ``u``."""
    time = next(iter(variables - set(coordinates)))
    others = [q for q in coordinates if q != u and any(r.has(q) for r in shape)]
    moving = any(r.has(time) for r in shape) or bool(others)
    direction = [sympy.diff(r, u) for r in shape]
    straight = not any(d.free_symbols & variables for d in direction) and any(d != 0 for d in direction)
    if straight and len(shape) == 2 and not any(r.has(time) for r in shape):
        point = tuple(r.xreplace({u: 0}) for r in shape)
        if not others or carrier is not None:
            return Surface(label, member, point, (-direction[1], direction[0]), unilateral, carrier=carrier)
    closed = all(sympy.expand(r.xreplace({u: u + 2 * sympy.pi}) - r) == 0 for r in shape)
    centre: tuple[Any, ...] = ()
    radius = None
    if closed and not moving:
        centre = free_part(shape, [u])
        radius = fixed_distance([r - c for r, c in zip(shape, centre, strict=True)], [u])
        if radius is None:
            centre = ()
    return Curve(label, member, u, shape, centre, radius, moving=moving, closed=closed, solid=unilateral and closed)


def revolution(label: str, member: str, shape: tuple[Any, ...], free: tuple[Any, ...],
               coordinates: list[Any]) -> Revolution | None:
    """A surface of revolution about a coordinate axis (the vertical one first) through the shape's
    coordinate-free part, or None."""
    if sum(sympy.count_ops(r) for r in shape) > SIZE_LIMIT:
        return None
    centre = free_part(shape, coordinates)
    u, v = free
    for axis in (2, 0, 1):
        across = [k for k in range(3) if k != axis]
        square = sympy.trigsimp(sympy.expand(sum(((shape[k] - centre[k]) ** 2 for k in across), sympy.Integer(0))))
        height = sympy.expand(shape[axis] - centre[axis])
        if not height.free_symbols & set(free) or not square.free_symbols & set(free):
            continue
        jacobian = sympy.diff(square, u) * sympy.diff(height, v) - sympy.diff(square, v) * sympy.diff(height, u)
        if sympy.simplify(jacobian) == 0:
            return Revolution(label, member, shape, free, axis, centre)
    return None
