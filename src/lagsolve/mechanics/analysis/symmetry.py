r"""Noether's theorem beyond cyclic coordinates: translations and rotations of the whole system.

A translation along a Cartesian axis :math:`e` moves every particle and body by
:math:`\delta\mathbf r = \varepsilon\,e`; a rotation about an axis :math:`e` through the origin by
:math:`\delta\mathbf r = \varepsilon\,e\times\mathbf r` (in the plane, about z:
:math:`(-y, x)`), and it turns every planar body by :math:`\varepsilon`. In the coordinates this is a
flow :math:`\delta q = \varepsilon\,\xi(q, t)` found from the positions,

.. math:: \sum_i \frac{\partial\mathbf r_p}{\partial q_i}\,\xi_i = \delta\mathbf r_p(q, t)
          \quad\text{for every particle and body } p,

with :math:`\partial\omega/\partial\dot q\cdot\xi = 1` (rotation) or 0 (translation) for a planar
body's angular velocity :math:`\omega`, and :math:`W\xi = 0` under a translation (
:math:`|W\xi| = 1` under a rotation) for a 3-D body's :math:`\omega = W\dot q`; a coordinate the
positions leave free gets :math:`\xi_i = 0`. The system is solved where the positions determine
:math:`\xi` (picked at a random point, then solved exactly and checked row by row). The flow is a
*symmetry* when it leaves T and V invariant, :math:`X^{(1)}T = X^{(1)}V = 0` with
:math:`\delta\dot q = \dot\xi`, every remaining constraint is unmoved (:math:`a_j\cdot\xi = 0`) and
no generalized force does work along it (:math:`Q\cdot\xi = 0`). Then

.. math:: \frac{d}{dt}\sum_i p_i\,\xi_i = X^{(1)}L + \sum_i Q_i\xi_i + \sum_j\lambda_j\,a_j\cdot\xi = 0,

so :math:`C = \sum_i p_i\xi_i` is conserved: :math:`L_z = m(x\dot y - y\dot x)` for a rotation about
z, :math:`P_x = m_1\dot x_1 + m_2\dot x_2` for a translation along x. Each is then verified like every
other conserved quantity (its time derivative along the equations of motion, on the constraint
surface, simplifies to zero). A flow that is the shift of a cyclic coordinate gives that coordinate's
momentum, already found: it is named, not repeated (the spherical pendulum's :math:`p_\phi` is
:math:`L_z`).

Notes
-----
* Only the six (in the plane three) basic generators are tried, about axes through the origin.
* A problem without particles and bodies (T and V given directly) has no positions to move: declined.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.analysis.conserved import Conservation, Conserved, MotionSystem, unverified_caveat
from lagsolve.mechanics.equations.surface import on_surface
from lagsolve.mechanics.stages import StageSkipped, StageTooLarge
from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.partials import partial
from lagsolve.mechanics.symbolic.simplify import tidy
from lagsolve.problem.names import symmetry_name

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.elimination import Elimination
    from lagsolve.problem.schema import Problem

AXES = ("x", "y", "z")
#: positions (all of them together) larger than this many operations are declined at once
SIZE_LIMIT = 600
#: relative size of a residual that counts as zero in the numeric pivoting
TOLERANCE = 1e-9


@dataclass(frozen=True)
class Generator:
    """One basic motion of the whole system: ``kind`` "translation" or "rotation", along/about ``axis``."""

    kind: str
    axis: str

    @property
    def text(self) -> str:
        return f"translation along {self.axis}" if self.kind == "translation" else f"rotation about {self.axis}"


@dataclass(frozen=True)
class _Point:
    """A particle or body: its position, and for a body its angular velocity (planar: one component)."""

    position: tuple[Any, ...]
    angular_velocity: tuple[Any, ...] = ()


def symmetries(problem: Problem, system: MotionSystem, conservation: Conservation,
               substitution: Elimination | None = None) -> Conservation:
    """``conservation`` with the momenta of the translations and rotations that are symmetries (module
    docstring): new quantities after the cyclic momenta, and a cyclic momentum that is one of them named."""
    if not system.model.coordinates:  # no coordinate left to move: the constraints prescribe the motion
        return conservation
    points = _points(problem, substitution)
    quantities = list(conservation.quantities)
    found: list[Conserved] = []
    notes = list(conservation.notes)
    taken = {*problem.symbols, *(f.name for f in problem.functions), *(q.name for q in quantities)}
    for generator in _generators(points):
        flow = _flow(system, points, generator)
        if flow is None or not _invariant(system, flow):
            continue
        if _named_known(system, conservation, quantities, flow, generator):
            continue
        charge = _charge(system, flow)
        if proved_zero(charge):
            continue
        name = symmetry_name(generator.kind, generator.axis, taken)
        taken.add(name)
        if system.accelerations and not system.constant(charge):
            notes.append(f"{name}: the {generator.text} leaves L invariant but dC/dt did not simplify to 0; "
                         "not claimed")
            continue
        found.append(Conserved(name, "noether", tidy(charge), None, _reason(system, generator),
                               symmetry=generator.text, generator=flow))
    return Conservation(_before_the_energy(quantities, found), conservation.cyclic, tuple(notes),
                        conservation.energy)


def _generators(points: list[_Point]) -> list[Generator]:
    """The translations along and rotations about the axes of the points' space (about z alone in the plane);
    :class:`StageSkipped` without points or with positions of different dimensions, :class:`StageTooLarge` for
    positions too large to try."""
    if not points:
        raise StageSkipped("no particle or body positions to move")
    dims = {len(p.position) for p in points}
    if len(dims) != 1:
        raise StageSkipped("the positions have different numbers of components")
    if sum(ops(e) for p in points for e in p.position) > SIZE_LIMIT:
        raise StageTooLarge(f"the positions have more than {SIZE_LIMIT} operations")
    dim = dims.pop()
    generators = [Generator("translation", a) for a in AXES[:dim]]
    generators += [Generator("rotation", a) for a in (AXES if dim == 3 else ("z",) if dim == 2 else ())]
    return generators


def _named_known(system: MotionSystem, conservation: Conservation, quantities: list[Conserved],
                 flow: tuple[Any, ...], generator: Generator) -> bool:
    """Whether the flow's charge is a quantity already found (a cyclic momentum); that quantity, in
    ``quantities``, is then named after the generator unless it is named already."""
    known = _known(system, conservation, quantities, flow)
    if known is None:
        return False
    i, quantity = known
    if not quantity.symmetry:
        quantities[i] = replace(quantity, symmetry=generator.text, generator=flow)
    return True


def _charge(system: MotionSystem, flow: tuple[Any, ...]) -> Any:
    """Noether's charge of the flow ξ: :math:`\\sum_i p_i\\xi_i`."""
    return sum((partial(system.model.lagrangian, v) * xi
                for v, xi in zip(system.model.velocities, flow, strict=True) if xi != 0), sympy.Integer(0))


def _before_the_energy(quantities: list[Conserved], found: list[Conserved]) -> tuple[Conserved, ...]:
    """``quantities`` with ``found`` put in before the energy (the Jacobi integral), else at the end."""
    energy = [i for i, q in enumerate(quantities) if q.kind == "jacobi"]
    at = energy[0] if energy else len(quantities)
    return tuple(quantities[:at] + found + quantities[at:])


def _reason(system: MotionSystem, generator: Generator) -> str:
    what = "T, V and every constraint" if system.constraints else "T and V"
    forces = "" if all(f == 0 for f in system.generalized_forces) else ", and no force does work along it"
    return f"the {generator.text} leaves {what} invariant{forces} (Noether's theorem)" + unverified_caveat(system)


def _points(problem: Problem, substitution: Elimination | None) -> list[_Point]:
    def put(e: Any) -> Any:
        return substitution.apply(e) if substitution is not None else e

    points = [_Point(tuple(put(x) for x in p.position)) for p in problem.particles]
    points += [_Point(tuple(put(x) for x in b.position), tuple(put(w) for w in b.angular_velocity))
               for b in problem.bodies]
    return points


def _displacement(generator: Generator, position: tuple[Any, ...]) -> tuple[Any, ...]:
    r""":math:`\delta\mathbf r` of one point per unit :math:`\varepsilon`."""
    zero, one = sympy.Integer(0), sympy.Integer(1)
    if generator.kind == "translation":
        return tuple(one if AXES[j] == generator.axis else zero for j in range(len(position)))
    if len(position) == 2:
        x, y = position
        return (-y, x)
    x, y, z = position
    return {"x": (zero, -z, y), "y": (z, zero, -x), "z": (-y, x, zero)}[generator.axis]


def _rows(system: MotionSystem, points: list[_Point], generator: Generator) -> list[tuple[list[Any], Any]] | None:
    """The linear equations ξ must satisfy: (coefficients, right side); None when no flow can exist."""
    model = system.model
    rows: list[tuple[list[Any], Any]] = []
    for point in points:
        for r, d in zip(point.position, _displacement(generator, point.position), strict=True):
            rows.append(([sympy.diff(r, q) for q in model.coordinates], d))
        if len(point.angular_velocity) == 1:
            if generator.kind == "rotation" and generator.axis != "z":
                return None  # a planar body cannot turn about an axis in its plane
            w = point.angular_velocity[0]
            rows.append(([sympy.diff(w, v) for v in model.velocities],
                         sympy.Integer(1 if generator.kind == "rotation" else 0)))
        elif point.angular_velocity and generator.kind == "translation":
            rows += [([sympy.diff(w, v) for v in model.velocities], sympy.Integer(0)) for w in point.angular_velocity]
    return rows


def _flow(system: MotionSystem, points: list[_Point], generator: Generator) -> tuple[Any, ...] | None:
    """ξ for ``generator`` (module docstring), or None when the positions cannot move that way."""
    import numpy

    rows = _rows(system, points, generator)
    if rows is None:
        return None
    n = len(system.model.coordinates)
    point = _random_point(rows)
    matrix = numpy.array([[_number(a, point) for a in row] for row, _ in rows])
    rhs = numpy.array([_number(b, point) for _, b in rows])
    if not numpy.all(numpy.isfinite(matrix)) or not numpy.all(numpy.isfinite(rhs)):
        return None
    scale = max(1.0, float(numpy.abs(matrix).max()))
    pivots: list[int] = []
    for j in range(n):
        if numpy.linalg.matrix_rank(matrix[:, [*pivots, j]], tol=TOLERANCE * scale) > len(pivots):
            pivots.append(j)
    if not pivots:
        return None
    solution, *_ = numpy.linalg.lstsq(matrix[:, pivots], rhs, rcond=None)
    if numpy.abs(matrix[:, pivots] @ solution - rhs).max() > 1e-7 * max(1.0, float(numpy.abs(rhs).max())):
        return None  # the positions cannot move this way
    chosen: list[int] = []
    for i in range(len(rows)):
        if numpy.linalg.matrix_rank(matrix[[*chosen, i]][:, pivots], tol=TOLERANCE * scale) > len(chosen):
            chosen.append(i)
        if len(chosen) == len(pivots):
            break
    A = sympy.Matrix([[rows[i][0][j] for j in pivots] for i in chosen])
    b = sympy.Matrix([rows[i][1] for i in chosen])
    try:
        values = A.LUsolve(b)
    except (ValueError, ZeroDivisionError, NotImplementedError):
        return None
    xi = [sympy.Integer(0)] * n
    for j, value in zip(pivots, values, strict=True):
        xi[j] = tidy(sympy.cancel(value))
    if not all(proved_zero(sum((a * x for a, x in zip(row, xi, strict=True)), -b)) for row, b in rows):
        return None
    if generator.kind == "rotation" and not _bodies_turn(system, points, xi):
        return None
    return tuple(xi)


def _bodies_turn(system: MotionSystem, points: list[_Point], xi: list[Any]) -> bool:
    r"""Every 3-D body turns at unit rate under the rotation's flow: :math:`|W\xi|^2 = 1`."""
    velocities = system.model.velocities
    for point in points:
        if len(point.angular_velocity) != 3:
            continue
        turn = [sum((sympy.diff(w, v) * x for v, x in zip(velocities, xi, strict=True)), sympy.Integer(0))
                for w in point.angular_velocity]
        if not proved_zero(sum(c**2 for c in turn) - 1):
            return False
    return True


def _random_point(rows: list[tuple[list[Any], Any]]) -> dict[Any, Any]:
    """Rational values for every symbol of ``rows`` (positive where declared positive), from a fixed seed."""
    symbols: set[Any] = set()
    for row, b in rows:
        for e in (*row, b):
            symbols |= sympy.sympify(e, strict=True).free_symbols
    rng = random.Random(7)
    ordered = sorted(symbols, key=sympy.default_sort_key)
    return {s: sympy.Rational(rng.randint(5, 20) if s.is_positive else rng.choice((-1, 1)) * rng.randint(5, 20), 13)
            for s in ordered}


def _number(expr: Any, point: dict[Any, Any]) -> float:
    """``expr`` at ``point`` as a float (a declared function replaced by a smooth stand-in); NaN where undefined."""
    expr = sympy.sympify(expr, strict=True)
    for i, fn in enumerate(sorted({f.func for f in expr.atoms(sympy.core.function.AppliedUndef)}, key=str)):
        u = sympy.Dummy("u")
        expr = expr.replace(fn, sympy.Lambda(u, (sympy.sin(u) + u**2 / 3, sympy.exp(u / 2) - u)[i % 2])).doit()
    try:
        value = complex(sympy.N(expr.xreplace(point), 20))
    except (TypeError, ValueError, ZeroDivisionError):
        return float("nan")
    return value.real if abs(value.imag) <= 1e-12 * max(1.0, abs(value.real)) else float("nan")


def _invariant(system: MotionSystem, xi: tuple[Any, ...]) -> bool:
    r""":math:`X^{(1)}T = X^{(1)}V = 0`, :math:`a_j\cdot\xi = 0` and :math:`Q\cdot\xi = 0`, on the constraint
    surface."""
    model = system.model
    rates = [model.time_derivative(x) for x in xi]

    def change(expr: Any) -> Any:
        out = sum((sympy.diff(expr, q) * x for q, x in zip(model.coordinates, xi, strict=True) if x != 0),
                  sympy.Integer(0))
        out += sum((sympy.diff(expr, v) * r for v, r in zip(model.velocities, rates, strict=True) if r != 0),
                   sympy.Integer(0))
        return on_surface(out, system.surface)

    def along(row: tuple[Any, ...]) -> Any:
        return on_surface(sum((a * x for a, x in zip(row, xi, strict=True)), sympy.Integer(0)), system.surface)

    return (proved_zero(change(model.kinetic)) and proved_zero(change(model.potential))
            and all(proved_zero(along(c.coefficients)) for c in system.constraints)
            and proved_zero(along(system.generalized_forces)))


def _known(system: MotionSystem, conservation: Conservation, quantities: list[Conserved],
           xi: tuple[Any, ...]) -> tuple[int, Conserved] | None:
    """The quantity already found that this flow's charge is: the momentum of a cyclic coordinate it shifts."""
    model = system.model
    ones = [i for i, x in enumerate(xi) if x != 0]
    if len(ones) == 1 and xi[ones[0]] == 1 and model.coordinates[ones[0]] in conservation.cyclic:
        q = model.coordinates[ones[0]]
        for i, quantity in enumerate(quantities):
            if quantity.kind == "momentum" and quantity.coordinate == q:
                return i, quantity
    return None
