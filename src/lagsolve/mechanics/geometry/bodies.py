"""Rigid bodies in the sketch: discs, bars and plates in the plane, tops and discs in space, with their orientation.

Part of the sketch's geometry (:mod:`lagsolve.mechanics.geometry.shapes`).

**In the plane** a body's angle is :math:`\\sum_i c_i q_i` when its angular velocity is :math:`\\sum_i c_i\\dot q_i`
with constant :math:`c_i`, else its rate is integrated along the run. Its shape:

* a **bar** when it hangs from a pivot or a member: a point of it that constraints hold fixed (the axle of a
  physical pendulum, two constraints at one ``at:`` point), or a member or fixed point at a distance from its
  centre that the coordinates keep, the line to which turns with the body (a compound pendulum on a block);
* a **disc** when a point where it touches something keeps its direction from the centre while the body turns
  (the offset does not turn with the body, so the rim is round): a contact ``at:`` a fixed distance from the
  centre, or a rolling velocity constraint :math:`\\mathbf n\\cdot(\\mathbf v_C + \\omega\\,\\hat z\\times
  \\boldsymbol\\rho) = 0` (the wheels of a cart), solved for :math:`\\mathbf n` and :math:`\\boldsymbol\\rho
  \\perp\\mathbf n`. The locus of the contact point (relative to what carries the surface) is the line or curve
  it rolls on;
* a **plate** otherwise.

**In space** the orientation :math:`R(q)` is found by matching the body-frame angular velocity to
:math:`R^T\\dot R` for products of up to three rotations about body axes by ± the coordinates (numerically at
random states, as ``reactions.internal`` tests): exactly, or for an axisymmetric body up to a spin about its axis
(a disc whose angular velocity is given in a frame that does not spin). :math:`R` is fixed up to a constant
rotation :math:`C` on the left; a body that rolls (velocity constraints without a point) takes the :math:`C`
about the vertical for which the lowest point of its rim has zero velocity, and the radius that makes it so (a
parameter of the problem). A body at a fixed distance from a fixed point is a **top** on a rod from it.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import permutations, product
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.geometry.curves import line_or_curve, solve_together
from lagsolve.mechanics.geometry.records import Anchor, Body, Curve, Rod, Surface, fixed_distance, free_part
from lagsolve.problem.schema import ConstraintKind, Problem

#: random states at which a candidate orientation is compared with the given angular velocity
STATES = 4


def bodies(problem: Problem, coordinates: list[Any], variables: set[Any], rods: list[Rod]
           ) -> tuple[list[Body], list[Surface], list[Curve], list[Rod]]:
    """Each body's drawing, the surfaces and curves its contacts touch, and the rods (less those a bar replaces,
    plus the links of bodies that do not turn with them)."""
    out: list[Body] = []
    surfaces: list[Surface] = []
    curves: list[Curve] = []
    rods = list(rods)
    for body in problem.bodies:
        if body.planar and len(body.position) == 2:
            drawn, touched, links = _planar(problem, body, coordinates, variables)
            for element in touched:
                if isinstance(element, Surface):
                    surfaces.append(element)
                else:
                    curves.append(element)
            rods += links
        else:
            drawn, links = _spatial(problem, body, coordinates)
            rods += links
        out.append(drawn)
    return out, surfaces, curves, rods


def _angle(omega: Any, problem: Problem) -> Any:
    """Σ c_i q_i for ω = Σ c_i q̇_i with constant c_i, else None."""
    total = sympy.Integer(0)
    rest = omega
    for c in problem.coordinates:
        k = sympy.diff(omega, c.velocity)
        if k.free_symbols & ({x.symbol for x in problem.coordinates} | {x.velocity for x in problem.coordinates}):
            return None
        total += k * c.symbol
        rest -= k * c.velocity
    return total if sympy.expand(rest) == 0 else None


def _turns_with(offset: list[Any], omega: Any, problem: Problem) -> bool:
    """Whether the direction of ``offset`` (from the centre) turns at the body's rate ω: a point fixed in it."""
    rate = [sum((sympy.diff(o, c.symbol) * c.velocity for c in problem.coordinates), sympy.Integer(0)) for o in offset]
    square = offset[0] ** 2 + offset[1] ** 2
    turn = (offset[0] * rate[1] - offset[1] * rate[0]) - omega * square
    return bool(sympy.simplify(sympy.expand_trig(turn)) == 0)


def _position(problem: Problem, name: str) -> tuple[Any, ...]:
    for particle in problem.particles:
        if particle.name == name:
            return tuple(particle.position)
    return tuple(problem.body(name).position)


def _planar(problem: Problem, body: Any, coordinates: list[Any], variables: set[Any]
            ) -> tuple[Body, list[Surface | Curve], list[Rod]]:
    """A body in the plane drawn as a bar, disc or plate (module docstring), the lines and curves its contacts
    touch, and the rods that link it to a member when they do not turn with it."""
    centre = tuple(body.position)
    omega = body.angular_velocity[0]
    angle = _angle(omega, problem)
    pivot, radius, contact, touched = _held_points(problem, body, coordinates, variables)
    links: list[Rod] = []
    if radius is None and pivot is None:
        radius, contact, floor = _rolling(problem, body, coordinates)
        touched += floor
    if pivot is None and radius is None:
        pivot, link = _link(problem, body, coordinates, omega)
        links += link
    kind = "bar" if pivot is not None else "disc" if radius is not None else "plate"
    rate = None if angle is not None else omega
    return Body(body.name, kind, centre, radius, angle, rate, pivot, contact=contact), touched, links


def _held_points(problem: Problem, body: Any, coordinates: list[Any], variables: set[Any]
                 ) -> tuple[Anchor | None, Any, tuple[Any, ...], list[Surface | Curve]]:
    """What the constraints ``at:`` points of the body make of it: the pivot (the last point they hold fixed),
    the radius and contact point of the first point that keeps its direction from the centre (a disc's rim),
    and the lines and curves the points touch."""
    centre = tuple(body.position)
    omega = body.angular_velocity[0]
    pivot: Anchor | None = None
    radius = None
    contact: tuple[Any, ...] = ()
    touched: list[Surface | Curve] = []
    for group in _groups_at(problem, body).values():
        at = tuple(group[0].at)
        offset = [p - c for p, c in zip(at, centre, strict=True)]
        attached = _turns_with(offset, omega, problem)
        held, element = _held_point(problem, body, group, offset, attached, coordinates, variables)
        if held is not None:
            pivot = held
        if element is not None:
            touched.append(element)
        if not attached and radius is None:
            radius = _length(offset, coordinates)
            contact = at if radius is not None else ()
    return pivot, radius, contact, touched


def _groups_at(problem: Problem, body: Any) -> dict[str, list[Any]]:
    """The constraints ``at:`` a point of the body (named first in ``on``), grouped by the point."""
    groups: dict[str, list[Any]] = {}
    for constraint in problem.constraints:
        if constraint.at is not None and constraint.on and constraint.on[0] == body.name:
            groups.setdefault(str(constraint.at), []).append(constraint)
    return groups


def _held_point(problem: Problem, body: Any, group: list[Any], offset: list[Any], attached: bool,
                coordinates: list[Any], variables: set[Any]) -> tuple[Anchor | None, Surface | Curve | None]:
    """What the constraints ``group`` at one point of the body make of it: a pivot when they hold it fixed (on
    nothing that moves), the line or curve it slides or rolls along when they leave it one coordinate and it does
    not turn with the body (``attached``), else neither."""
    at = tuple(group[0].at)
    carrier = group[0].on[1] if len(group[0].on) > 1 else None
    base = _position(problem, carrier) if carrier is not None else tuple(sympy.Integer(0) for _ in at)
    relative = tuple(p - b for p, b in zip(at, base, strict=True))
    holonomic = _restricting(group, relative, coordinates)
    solved = solve_together(problem, relative, holonomic, coordinates, variables)
    if solved is None:
        return None, None
    shape, _, free = solved
    if not free and carrier is None and not any(s.free_symbols & variables for s in shape):
        return Anchor(None, shape), None
    if len(free) == 1 and not attached:
        absolute = tuple(b + s for b, s in zip(base, shape, strict=True))
        return None, _touched(body, holonomic, absolute, free[0], offset, carrier, coordinates, variables)
    return None, None


def _restricting(group: list[Any], relative: tuple[Any, ...], coordinates: list[Any]) -> list[Any]:
    """The holonomic constraints of ``group`` that restrict where the point can be (one relating it to a
    coordinate it does not hold, the rolling angle, leaves its locus alone)."""
    inside = {q for q in coordinates if any(p.has(q) for p in relative)}
    return [c for c in group if c.kind == ConstraintKind.HOLONOMIC
            and not (c.expression.free_symbols & set(coordinates)) - inside]


def _touched(body: Any, holonomic: list[Any], absolute: tuple[Any, ...], free: Any, offset: list[Any],
             carrier: str | None, coordinates: list[Any], variables: set[Any]) -> Surface | Curve:
    """The line or curve a point of the body moves along (``absolute``, a function of ``free``); a line is solid
    beyond the contact, away from the centre."""
    unilateral = any(c.unilateral for c in holonomic)
    label = ", ".join(c.name for c in holonomic)
    element = line_or_curve(label, body.name, absolute, free, [], coordinates, variables, unilateral, carrier)
    if isinstance(element, Surface):  # the material is beyond the contact, away from the centre
        element = replace(element, solid=tuple(offset))
    return element


def _length(offset: list[Any], coordinates: list[Any]) -> Any:
    """|offset| when the coordinates do not change it, else None."""
    if not any(o.free_symbols & set(coordinates) for o in offset):
        size = sympy.sqrt(sympy.simplify(sum((o * o for o in offset), sympy.Integer(0))))
        return size if size != 0 else None
    return fixed_distance(offset, coordinates)


def _rolling(problem: Problem, body: Any, coordinates: list[Any]) -> tuple[Any, tuple[Any, ...], list[Surface]]:
    """A velocity constraint n·(v_C + ω ẑ×ρ) = 0 with ρ ⊥ n and the body's own rates only: the radius |ρ|, the
    contact point C + ρ and the line it rolls on."""
    rates = [c.velocity for c in problem.coordinates]
    centre = sympy.Matrix(body.position)
    jacobian = centre.jacobian(coordinates)
    w = [sympy.diff(body.angular_velocity[0], v) for v in rates]
    n1, n2, m = sympy.symbols("_n1 _n2 _m")
    for constraint in problem.constraints:
        if constraint.kind == ConstraintKind.HOLONOMIC or constraint.at is not None:
            continue  # (its 'on' may name a particle by default: the solve below says whose rates it holds)
        a = [sympy.diff(constraint.expression, v) for v in rates]
        if sympy.expand(constraint.expression - sum((c * v for c, v in zip(a, rates, strict=True)), sympy.Integer(0))):
            continue
        equations = [n1 * jacobian[0, i] + n2 * jacobian[1, i] - m * w[i] - a[i] for i in range(len(rates))]
        solutions = sympy.linsolve(equations, [n1, n2, m])
        if not isinstance(solutions, sympy.FiniteSet) or not solutions.args:
            continue
        values = [sympy.sympify(e, strict=True).subs({n1: 0, n2: 0, m: 0}) for e in solutions.args[0]]
        n = values[:2]
        size = sympy.simplify(n[0] ** 2 + n[1] ** 2)
        if size == 0 or any(x.free_symbols & set(coordinates) for x in n):
            continue  # a normal that turns with the body is a blade's (a cart's axle), not a line rolled on
        rho = [sympy.simplify(-values[2] * n[1] / size), sympy.simplify(values[2] * n[0] / size)]
        radius = sympy.simplify(sympy.sqrt(rho[0] ** 2 + rho[1] ** 2))
        if radius == 0 or radius.free_symbols & set(coordinates):
            continue
        contact = tuple(c + r for c, r in zip(body.position, rho, strict=True))
        floor = Surface(constraint.name, body.name, contact, tuple(rho), solid=tuple(rho))
        return radius, contact, [floor]
    return None, (), []


def _link(problem: Problem, body: Any, coordinates: list[Any], omega: Any) -> tuple[Anchor | None, list[Rod]]:
    """A member or fixed point at a distance the coordinates keep from the body's centre: the pivot of a bar when
    the line to it turns with the body, else a rod."""
    centre = tuple(body.position)
    candidates = [(Anchor(p.name), tuple(p.position)) for p in problem.particles if len(p.position) == len(centre)]
    pivot = free_part(centre, coordinates)
    candidates.append((Anchor(None, pivot), pivot))
    for anchor, where in candidates:
        offset = [c - p for c, p in zip(centre, where, strict=True)]
        if fixed_distance(offset, coordinates) is None:
            continue
        if _turns_with(offset, omega, problem):
            return anchor, []
        return None, [Rod(anchor, Anchor(body.name), fixed_distance(offset, coordinates), None)]
    return None, []


# --- bodies in space ---------------------------------------------------------------------------------------


def _symmetry_axis(inertia: tuple[Any, ...]) -> int:
    """The body axis whose moment differs from the other two (equal), else the third."""
    for k in range(3):
        others = [inertia[j] for j in range(3) if j != k]
        if sympy.simplify(others[0] - others[1]) == 0 and sympy.simplify(inertia[k] - others[0]) != 0:
            return k
    return 2


def _rotation(axis: int, angle: Any) -> sympy.Matrix:
    c, s = sympy.cos(angle), sympy.sin(angle)
    if axis == 0:
        return sympy.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 1:
        return sympy.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sympy.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def _numeric_rotation(axis: int, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """The rotation about ``axis`` by ``angle`` and its derivative in the angle."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    out, rate = np.eye(3), np.zeros((3, 3))
    out[i, i], out[i, j], out[j, i], out[j, j] = c, -s, s, c
    rate[i, i], rate[i, j], rate[j, i], rate[j, j] = -s, -c, c, -s
    return out, rate


class _States:
    """Random states (coordinates, velocities, parameters) and the given angular velocity at each."""

    def __init__(self, problem: Problem, body: Any) -> None:
        rng = np.random.default_rng(11)
        self.coordinates = [c.symbol for c in problem.coordinates]
        self.rates = [c.velocity for c in problem.coordinates]
        self.parameters = [p.symbol for p in problem.parameters]
        arguments = [problem.time, *self.coordinates, *self.rates, *self.parameters]
        self.omega = sympy.lambdify(arguments, list(body.angular_velocity), modules="numpy")
        self.centre = sympy.lambdify(arguments, list(sympy.Matrix(body.position).jacobian(self.coordinates)),
                                     modules="numpy")
        self.states = []
        for _ in range(STATES):
            q = rng.uniform(-1.2, 1.2, len(self.coordinates))
            qd = rng.uniform(-1.5, 1.5, len(self.coordinates))
            p = np.array([rng.uniform(0.6, 1.8) for _ in self.parameters])
            self.states.append((q, qd, p))

    def given(self, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        return np.array(self.omega(0.0, *q, *qd, *p), dtype=float)


def _match(sequence: tuple[tuple[int, int, int], ...], states: _States, free: int | None) -> bool:
    """Whether R = Π rotation(axis, sign q) has Rᵀ Ṙ equal to the given angular velocity (all components, or all
    but ``free``)."""
    for q, qd, p in states.states:
        factors = [_numeric_rotation(axis, sign * q[k]) for axis, sign, k in sequence]
        total = np.eye(3)
        for f, _ in factors:
            total = total @ f
        rate = np.zeros((3, 3))
        for i, (_, sign, k) in enumerate(sequence):
            part = np.eye(3)
            for j, (f, d) in enumerate(factors):
                part = part @ (d * sign * qd[k] if j == i else f)
            rate += part
        w = total.T @ rate
        body = np.array([w[2, 1], w[0, 2], w[1, 0]])
        given = states.given(q, qd, p)
        keep = [i for i in range(3) if i != free]
        if not np.allclose(body[keep], given[keep], atol=1e-9 * (1 + np.abs(given).max())):
            return False
    return True


def orientation(problem: Problem, body: Any, axis: int) -> tuple[sympy.Matrix | None, Any]:
    """R(q) from body to space axes (up to a constant rotation on the left) and the spin about ``axis`` it leaves
    out (None when R matches every component); (None, None) when no product of rotations matches."""
    omega = body.angular_velocity
    if any(w.atoms(sympy.core.function.AppliedUndef) for w in omega):
        return None, None
    used = [k for k, c in enumerate(problem.coordinates) if any(w.has(c.velocity) for w in omega)]
    if not used or len(used) > 3:
        return None, None
    states = _States(problem, body)
    for free in (None, axis):
        for length in range(1, len(used) + 1):
            for axes in product(range(3), repeat=length):
                if any(a == b for a, b in zip(axes, axes[1:], strict=False)):
                    continue
                for chosen in permutations(used, length):
                    for signs in product((1, -1), repeat=length):
                        sequence = tuple(zip(axes, signs, chosen, strict=True))
                        if _match(sequence, states, free):
                            return _symbolic(sequence, problem, omega, free)
    return None, None


def _symbolic(sequence: tuple[tuple[int, int, int], ...], problem: Problem, omega: tuple[Any, ...],
              free: int | None) -> tuple[sympy.Matrix, Any]:
    R = sympy.eye(3)
    for axis, sign, k in sequence:
        R = R * _rotation(axis, sign * problem.coordinates[k].symbol)
    if free is None:
        return R, None
    rate = sympy.zeros(3, 3)
    for c in problem.coordinates:
        rate += sympy.diff(R, c.symbol) * c.velocity
    w = (R.T * rate).applyfunc(sympy.trigsimp)
    body = [w[2, 1], w[0, 2], w[1, 0]]
    return R, sympy.simplify(omega[free] - body[free])


def _spatial(problem: Problem, body: Any, coordinates: list[Any]) -> tuple[Body, list[Rod]]:
    axis = _symmetry_axis(tuple(body.inertia))
    R, spin = orientation(problem, body, axis)
    centre = tuple(body.position)
    pivot = free_part(centre, coordinates)
    length = fixed_distance([c - p for c, p in zip(centre, pivot, strict=True)], coordinates)
    if R is None:
        return Body(body.name, "disc", centre), []
    if length is not None:
        rod = Rod(Anchor(None, pivot), Anchor(body.name), length, None)
        return Body(body.name, "top", centre, length / 2, rotation=_rows(R), axis=axis, spin=spin,
                    pivot=Anchor(None, pivot)), [rod]
    turn, radius = _rolls(problem, body, R, axis)
    if turn is not None:
        return Body(body.name, "disc", centre, radius, rotation=_rows(turn * R), axis=axis, spin=spin,
                    rolls=True), []
    return Body(body.name, "disc", centre, rotation=_rows(R), axis=axis, spin=spin), []


def _rows(R: sympy.Matrix) -> tuple[tuple[Any, ...], ...]:
    return tuple(tuple(R[i, j] for j in range(3)) for i in range(3))


def _rolls(problem: Problem, body: Any, R: sympy.Matrix, axis: int) -> tuple[sympy.Matrix | None, Any]:
    """For a body with velocity constraints without a point: the turn C about the vertical (a multiple of a
    quarter turn) and the radius (a parameter) for which the lowest point of the rim has zero velocity whenever
    the constraints hold; (None, None) otherwise."""
    gravity = problem.gravity
    constraints = [c for c in problem.constraints if c.kind == ConstraintKind.NONHOLONOMIC and c.at is None
                   and not c.on]
    if gravity is None or len(gravity) != 3 or not constraints or problem.functions:
        return None, None
    vertical = [k for k, g in enumerate(gravity) if g != 0]
    if len(vertical) != 1:
        return None, None
    up = vertical[0]
    states = _States(problem, body)
    rates = [c.velocity for c in problem.coordinates]
    arguments = [problem.time, *states.coordinates, *rates, *states.parameters]
    A = sympy.lambdify(arguments, [[sympy.diff(c.expression, v) for v in rates] for c in constraints], modules="numpy")
    rotation = sympy.lambdify(arguments, R, modules="numpy")
    g = sympy.lambdify(arguments, list(gravity), modules="numpy")
    for quarter in range(4):
        turn = _rotation(up, sympy.pi * quarter / 2)
        C = np.array(turn, dtype=float)
        radii: list[list[float]] = []
        for q, qd, p in states.states:
            args = (0.0, *q, *qd, *p)
            matrix = np.array(A(*args), dtype=float)
            _, singular, vt = np.linalg.svd(matrix)
            basis = vt[int(np.sum(singular > 1e-10)):]
            if not basis.size:
                break
            qd = basis.T @ np.linspace(0.7, 1.3, len(basis))
            args = (0.0, *q, *qd, *p)
            space = C @ np.array(rotation(*args), dtype=float)
            a = space[:, axis]
            down = np.array(g(*args), dtype=float)
            down /= np.linalg.norm(down)
            d = down - (down @ a) * a
            if np.linalg.norm(d) < 1e-6:
                break
            d /= np.linalg.norm(d)
            w = space @ states.given(q, qd, p)
            v = np.array(states.centre(*args), dtype=float).reshape(3, -1) @ qd
            lever = np.cross(w, d)
            rho = -float(v @ lever) / max(float(lever @ lever), 1e-300)
            if np.linalg.norm(v + rho * lever) > 1e-8 * (1 + np.linalg.norm(v)):
                break
            radii.append([rho, *p])
        else:
            for parameter_index, parameter in enumerate(states.parameters):
                if all(abs(r[0] - r[1 + parameter_index]) < 1e-8 * (1 + abs(r[0])) for r in radii):
                    return turn, parameter
    return None, None
