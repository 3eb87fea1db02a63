r"""Coulomb friction, decided once: the kinetic friction force of a contact between two members, its sliding
direction and rate, its static coefficient, and its normal force evaluated at a numeric state.

A contact acts at a point :math:`P` of the member that slides (a particle, or a planar body at ``at:``) against
the member that carries the surface (a particle or planar body; none: the surroundings). Its sliding velocity
is the velocity of :math:`P` relative to the surface, :math:`\mathbf v = \sum_{i\in\text{sliding}}
J_{rel,i}\,\dot q_i` (:mod:`lagsolve.mechanics.equations.pair`), taken in the tangent space of the contact (orthogonal
to
the forces of its normal constraints). The friction force is :math:`-\mu N\,\mathbf v/|\mathbf v|` on the first
member at :math:`P` and the opposite on the second, so its generalized forces are
:math:`Q_i = \mathbf F\cdot J_{rel,i}` (Newton's third law: a block on a wedge on a smooth floor gives the
floor direction no net force).

Where the tangent is one line (a contact in a plane; in space, two normal constraints, or one sliding
coordinate), the sliding is one signed rate :math:`\sigma = \mathbf t\cdot\mathbf v = \sum_i w_i\dot q_i` along
a unit tangent :math:`\mathbf t`, the force is :math:`-\mu N\,\mathrm{sign}(\sigma)\,\mathbf t`, as textbooks
write it, and the contact can stick (:math:`\sigma = 0` held by a tangential force :math:`\Phi\mathbf t` while
:math:`|\Phi| \le \mu_s N`).

The symbolic side (:func:`friction_term`) gives the force with the normal force a symbol :math:`N`;
:mod:`lagsolve.mechanics.solution.normal` finds :math:`N` in closed form where it can. The numeric side
(:func:`contact_directions`, :func:`normal_forces_at`) gives the numeric stage what it compiles and the same
equation :math:`N = |\mathbf a + B N|` solved at one state, so a simulation follows exactly the physics the
derivation states.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.errors import Issue, SimulationError, SpecError
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.pair import point_jacobian, relative_jacobian
from lagsolve.mechanics.symbolic.signs import sign_core
from lagsolve.mechanics.symbolic.simplify import common_factor, norm, plain_signs, tidy
from lagsolve.problem.schema import Friction, Problem

if TYPE_CHECKING:
    import numpy as np

    from lagsolve.mechanics.equations.constraints import ConstraintTerms
    from lagsolve.mechanics.equations.reactions import Reaction


def static_coefficient(friction: Friction) -> Any:
    """The coefficient of static friction: the file's ``static``, else the kinetic coefficient."""
    return friction.static if friction.static is not None else friction.coefficient


@dataclass(frozen=True)
class FrictionTerm:
    r"""Kinetic Coulomb friction of one contact, :math:`\mathbf F = -\mu N\,\mathbf v/|\mathbf v|`.

    ``particle`` is the member that slides (a particle or a planar body) and ``against`` the one that carries the
    surface (None: the surroundings), touching at ``point``. ``normal`` is the symbol :math:`N` (named
    ``N_<contact>``) that stands in the equations for the magnitude of the combined force of the ``constraints``
    on the first member; ``sliding_velocity`` is :math:`\mathbf v`, the tangential velocity of the point relative
    to the surface; ``force`` the friction force on the first member (the second gets its opposite) and
    ``generalized`` the generalized forces of the pair, :math:`Q_i = \mathbf F\cdot J_{rel,i}`.

    Where the sliding is along one line, ``tangent`` is the unit tangent :math:`\mathbf t`, ``rate`` the
    coefficients :math:`w_i` of the sliding rate :math:`\sigma = \sum_i w_i\dot q_i` and ``unit_generalized`` the
    generalized forces :math:`J_{rel}^T\mathbf t` of a unit tangential force (the force that holds a stuck
    contact); otherwise all three are None (kinetic friction only).

    Notes
    -----
    * valid while the contact slides, :math:`\mathbf v \neq 0` (the sign of the sliding
      rate is assumed constant along a solution);
    * :math:`N \ge 0` is a magnitude; whether the constraint pushes or pulls does not
      change the friction force.
    """

    name: str
    particle: str
    coefficient: Any
    constraints: tuple[str, ...]
    normal: Any
    sliding_velocity: tuple[Any, ...]
    force: tuple[Any, ...]
    generalized: tuple[Any, ...]
    valid_while: Any
    static: Any = None  # the static coefficient (the kinetic one when the file gives none)
    against: str | None = None
    point: tuple[Any, ...] = ()
    tangent: tuple[Any, ...] | None = None
    rate: tuple[Any, ...] | None = None
    unit_generalized: tuple[Any, ...] | None = None
    sliding_rate: Any = None  # σ = Σ w_i q̇_i, where it slides along one line


def friction_term(friction: Friction, problem: Problem, model: Model, reactions: dict[str, Reaction],
                  zero: Callable[[Any], bool]) -> FrictionTerm:
    """The friction force of one contact, with its normal force left as the symbol ``N_<name>``.

    ``zero`` tells whether an expression vanishes on the constraint surface.

    Raises
    ------
    SpecError
        The contact cannot be modelled: a normal constraint has no known force on the member that slides, the
        normal constraints leave no direction to slide in, or the sliding coordinates do not move the point
        along the surface.
    """
    J = relative_jacobian(problem, model, friction.on, friction.against, friction.at)
    n = len(model.coordinates)
    index = {c.name: i for i, c in enumerate(problem.coordinates)}
    # the sliding coordinates, those that move the member that slides first: the tangent points the way they move it
    own = point_jacobian(problem, model, friction.on, friction.at)
    sliding = sorted((index[name] for name in friction.sliding), key=lambda i: (all(e == 0 for e in own[:, i]), i))
    normals = _normal_directions(friction, problem, reactions, zero)
    tangent = _tangent(friction, problem, J, normals, sliding, zero)
    normal = sympy.Symbol(f"N_{friction.name}", nonnegative=True)
    mu = friction.coefficient
    if tangent is not None:
        t, w = tangent
        rate = tidy(sum((w[i] * model.velocities[i] for i in range(n)), sympy.Integer(0)))
        unit = tuple(tidy((t.T * J[:, i])[0]) for i in range(n))
        _, core = sign_core(rate)  # the rate without its factors of known sign (it has the sign of core)
        direction = plain_signs(sympy.sign(core))
        force = tuple(-mu * normal * direction * c for c in t)
        generalized = tuple(-mu * normal * direction * u for u in unit)
        velocity = tuple(tidy(rate * c) for c in t)
        return FrictionTerm(friction.name, friction.on, mu, friction.normal, normal, velocity, force, generalized,
                            sympy.Ne(core, 0), static_coefficient(friction), friction.against, friction.at,
                            tuple(t), tuple(w), unit, rate)
    velocity = sympy.zeros(J.rows, 1)
    for i in sliding:
        velocity += J[:, i] * model.velocities[i]
    velocity = _tangential(velocity, normals, zero)
    speed = norm(list(velocity))
    force = (-mu * normal * velocity / speed).applyfunc(_clean)
    generalized = tuple(_clean((force.T * J[:, i])[0]) for i in range(n))
    return FrictionTerm(friction.name, friction.on, mu, friction.normal, normal, tuple(velocity), tuple(force),
                        generalized, sympy.Ne(speed, 0), static_coefficient(friction), friction.against,
                        friction.at)


def _refuse(problem: Problem, friction: Friction, field: str, message: str, fix: str) -> SpecError:
    line = problem.lines.get(f"friction.{friction.name}.{field}", problem.lines.get(f"friction.{friction.name}", 0))
    return SpecError([Issue(problem.source, line, f"friction.{friction.name}.{field}", message, fix)])


def _normal_directions(friction: Friction, problem: Problem, reactions: dict[str, Reaction],
                       zero: Callable[[Any], bool]) -> list[sympy.Matrix]:
    """The direction of each normal constraint's force on the member that slides, the independent ones."""
    out: list[sympy.Matrix] = []
    for name in friction.normal:
        pushes = [p for p in reactions[name].particles if p.particle == friction.on]
        if not pushes:
            raise _refuse(problem, friction, "normal",
                          f"constraint {name!r} has no known force on {friction.on!r} "
                          f"({reactions[name].note or 'it acts elsewhere'}), so the normal force cannot be found",
                          "name constraints that act on it, with 'at:' the contact point of a body")
        u = sympy.Matrix(pushes[0].direction)
        if all(zero(c) for c in u):
            continue
        if not any(_parallel(u, v, zero) for v in out):
            out.append(u)
    if not out:
        raise _refuse(problem, friction, "normal", f"the normal constraints {', '.join(friction.normal)} exert no "
                      f"force on {friction.on!r}", "name the constraint that keeps it on the surface")
    return out


def _parallel(u: sympy.Matrix, v: sympy.Matrix, zero: Callable[[Any], bool]) -> bool:
    """Whether two vectors (2 or 3 components) are parallel on the constraint surface."""
    if u.rows == 2:
        return zero(u[0] * v[1] - u[1] * v[0])
    return all(zero(c) for c in u.cross(v))


def _tangent(friction: Friction, problem: Problem, J: sympy.Matrix, normals: list[sympy.Matrix], sliding: list[int],
             zero: Callable[[Any], bool]) -> tuple[sympy.Matrix, list[Any]] | None:
    """The unit tangent t and the sliding rate's coefficients w (zero outside the sliding coordinates) where the
    contact slides along one line; None where it slides in a plane. t points the way the first sliding
    coordinate moves the point (``sliding`` is in that order).

    Raises
    ------
    SpecError
        The normal constraints leave no direction to slide in, or the sliding coordinates do not move the point.
    """
    dims = J.rows
    if len(normals) >= dims:
        raise _refuse(problem, friction, "normal", f"the normal constraints {', '.join(friction.normal)} hold the "
                      f"contact point of {friction.on!r} in every direction, so nothing can slide",
                      "name only the constraints that push it off the surface under 'normal:'")
    U = sympy.Matrix.hstack(*normals)
    gram = (U.T * U).applyfunc(tidy)

    def along_surface(v: sympy.Matrix) -> sympy.Matrix:
        off = U.T * v
        if all(zero(c) for c in off):
            return v  # tangent already, on the surface
        try:
            return (v - U * gram.LUsolve(off)).applyfunc(tidy)
        except (ValueError, ZeroDivisionError) as exc:  # the normal directions are not independent everywhere
            raise _refuse(problem, friction, "normal", f"the normal constraints {', '.join(friction.normal)} give "
                          f"no tangent plane at the contact of {friction.on!r} ({exc})",
                          "name under 'normal:' only constraints whose forces are independent") from None

    moving = [along_surface(J[:, i]) for i in sliding]
    moving = [v for v in moving if not all(zero(c) for c in v)]
    if not moving:
        raise _refuse(problem, friction, "sliding", f"the sliding coordinates {', '.join(friction.sliding)} do not "
                      f"move the contact point of {friction.on!r} along the surface",
                      "list the coordinates whose motion makes it slide, or leave 'sliding:' out")
    if dims - len(normals) > 1 and not all(_parallel(moving[0], v, zero) for v in moving[1:]):
        return None  # it slides in a plane
    # the direction without the factor its components share (cos(alpha) (cos(alpha), -sin(alpha)) points along
    # (cos(alpha), -sin(alpha)), whatever the sign of cos(alpha)): the tangent's orientation is a convention
    direction = [tidy(c) for c in moving[0]]
    shared = common_factor(direction)
    direction = [tidy(c / shared) for c in direction]
    t = (sympy.Matrix(direction) / norm(direction)).applyfunc(tidy)
    w: list[Any] = [tidy((t.T * J[:, i])[0]) if i in sliding else sympy.Integer(0) for i in range(J.cols)]
    return t, w


def _tangential(velocity: sympy.Matrix, normals: list[sympy.Matrix], zero: Callable[[Any], bool]) -> sympy.Matrix:
    """The part of ``velocity`` in the tangent plane (unchanged where it is tangent on the surface already, as
    for a surface that does not move with the time)."""
    u = normals[0]
    along = (u.T * velocity)[0]
    if zero(along):
        return velocity
    return (velocity - u * along / sum((c**2 for c in u), sympy.Integer(0))).applyfunc(tidy)


def _clean(expr: Any) -> Any:
    """Cancel and reduce trigonometric identities, leaving ``sign`` alone (``simplify``
    would turn it into a Piecewise)."""
    return sympy.factor_terms(sympy.trigsimp(sympy.cancel(expr)))


def contact_directions(problem: Problem, frictions: tuple[FrictionTerm, ...], constraints: tuple[ConstraintTerms, ...],
                       reactions: dict[str, Reaction]) -> tuple[list[tuple[tuple[int, int, int], ...]], list[Any]]:
    r"""Per friction contact, the rows ``(constraint j, offset, dims)`` into the returned list of direction
    components: each normal constraint's force direction :math:`\mathbf u_j` on the member that slides (found by
    :func:`friction_term`, which refuses a contact without one)."""
    contacts: list[tuple[tuple[int, int, int], ...]] = []
    directions: list[Any] = []
    offset = 0
    index = {c.name: j for j, c in enumerate(constraints)}
    for f in frictions:
        rows = []
        for name in f.constraints:
            push = next(p for p in reactions[name].particles if p.particle == f.particle)
            rows.append((index[name], offset, len(push.direction)))
            directions += list(push.direction)
            offset += len(push.direction)
        contacts.append(tuple(rows))
    return contacts, directions


def normal_forces_at(t: float, contacts: tuple[tuple[tuple[int, int, int], ...], ...], u: np.ndarray,
                     lam: np.ndarray) -> np.ndarray:
    r"""The normal forces at one state, from the multipliers ``lam`` written as :math:`\lambda_0 + \Lambda N`
    (column 0 and one column per contact) and the force directions ``u`` (:func:`contact_directions`).

    Contact :math:`i` has :math:`N_i = |\mathbf a_i + \sum_k \mathbf b_{ik} N_k|` (module
    :mod:`lagsolve.mechanics.solution.normal`): for one contact a quadratic with a unique non-negative root when
    :math:`|\mathbf b| < 1`, for several a fixed-point iteration.

    Raises
    ------
    SimulationError
        No unique normal force (a Painlevé-type inconsistency), or the iteration does not converge.
    """
    import numpy as np  # here: the derivation, which imports this module, needs no NumPy (0.05 s of start-up)

    k = len(contacts)
    a_parts, b_parts = [], []
    for contact in contacts:
        dims = contact[0][2]
        a = np.zeros(dims)
        b = np.zeros((dims, k))
        for j, offset, _ in contact:
            direction = u[offset: offset + dims]
            a += lam[j, 0] * direction
            b += np.outer(direction, lam[j, 1:])
        a_parts.append(a)
        b_parts.append(b)
    if k == 1:
        a, b = a_parts[0], b_parts[0][:, 0]
        bb, ab, aa = float(b @ b), float(a @ b), float(a @ a)
        if bb >= 1.0:
            raise SimulationError(
                f"at t = {t:.6g} the friction feeds back into its own normal force so strongly "
                "(|dN/dN| >= 1) that no unique normal force exists (a Painlevé-type inconsistency)")
        return np.array([(ab + np.sqrt(ab * ab + (1.0 - bb) * aa)) / (1.0 - bb)])
    normal = np.array([np.linalg.norm(a) for a in a_parts])
    for _ in range(100):
        new = np.array([np.linalg.norm(a + b @ normal) for a, b in zip(a_parts, b_parts, strict=True)])
        if np.max(np.abs(new - normal)) <= 1e-13 * max(1.0, float(np.max(new))):
            return new
        normal = new
    raise SimulationError(f"at t = {t:.6g} the normal forces of the friction contacts did not converge")
