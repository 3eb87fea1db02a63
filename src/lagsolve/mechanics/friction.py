r"""Coulomb friction, decided once: the kinetic friction force of a contact, its sliding coordinate,
its static coefficient, and its normal force evaluated at a numeric state.

The symbolic side (:func:`friction_term`) gives the force with the normal force a symbol
:math:`N`; :mod:`lagsolve.mechanics.normal` finds :math:`N` in closed form where it can. The numeric
side (:func:`contact_directions`, :func:`normal_forces_at`) gives the numeric stage what it compiles
and the same equation :math:`N = |\mathbf a + B N|` solved at one state, so a simulation follows
exactly the physics the derivation states.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy

from lagsolve.errors import Issue, SimulationError, SpecError
from lagsolve.mechanics.forces import position_jacobian
from lagsolve.mechanics.model import Model
from lagsolve.mechanics.simplify import norm
from lagsolve.problem.schema import Friction, Problem

if TYPE_CHECKING:
    from lagsolve.mechanics.constraints import ConstraintTerms
    from lagsolve.mechanics.reactions import Reaction

def static_coefficient(friction: Friction) -> Any:
    """The coefficient of static friction: the file's ``static``, else the kinetic coefficient."""
    return friction.static if friction.static is not None else friction.coefficient


@dataclass(frozen=True)
class FrictionTerm:
    r"""Kinetic Coulomb friction of one contact, :math:`\mathbf F = -\mu N\,\mathbf v/|\mathbf v|`.

    ``normal`` is the symbol :math:`N` (named ``N_<contact>``) that stands in the
    equations for the magnitude of the combined force of the ``constraints`` on
    ``particle``; ``sliding_velocity`` is :math:`\mathbf v = \sum_{i\in\text{sliding}}
    (\partial\mathbf r_p/\partial q_i)\dot q_i`; ``force`` the friction force vector and
    ``generalized`` its generalized forces :math:`Q_i = \mathbf F\cdot\partial\mathbf r_p/\partial q_i`.

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
    #: the one coordinate whose rate is the sliding rate (stick–slip is followed on it), else None
    slide: int | None = None
    #: |∂r/∂q| of that coordinate (1 when there is none): the sliding speed is slide_length·|q̇|
    slide_length: Any = 1
    #: the static coefficient (the kinetic one when the file gives none)
    static: Any = None


def friction_term(friction: Friction, problem: Problem, model: Model) -> FrictionTerm:
    """The friction force of one contact, with its normal force left as the symbol ``N_<name>``."""
    particle = problem.particle(friction.on)
    jac = position_jacobian(particle.position, model)
    index = {c.name: i for i, c in enumerate(problem.coordinates)}
    sliding = [index[name] for name in friction.sliding]
    velocity = sympy.zeros(jac.rows, 1)
    for i in sliding:
        velocity += jac[:, i] * model.velocities[i]
    moving = [i for i in sliding if any(v != 0 for v in jac[:, i])]
    slide, length = None, sympy.Integer(1)
    if len(moving) == 1:
        # one sliding rate: the direction is sign(q_dot) times a unit vector, as textbooks write it
        i = slide = moving[0]
        column = jac[:, i]
        length = norm(list(column))
        direction = column * sympy.sign(model.velocities[i]) / length
        valid_while = sympy.Ne(model.velocities[i], 0)
    else:
        speed = norm(list(velocity))
        direction = velocity / speed
        valid_while = sympy.Ne(speed, 0)
    normal = sympy.Symbol(f"N_{friction.name}", nonnegative=True)
    force = (-friction.coefficient * normal * direction).applyfunc(_clean)
    generalized = tuple(_clean((force.T * jac[:, i])[0]) for i in range(len(model.coordinates)))
    return FrictionTerm(friction.name, friction.on, friction.coefficient, friction.normal, normal,
                        tuple(velocity), tuple(force), generalized, valid_while, slide, length,
                        static_coefficient(friction))


def _clean(expr: Any) -> Any:
    """Cancel and reduce trigonometric identities, leaving ``sign`` alone (``simplify``
    would turn it into a Piecewise)."""
    return sympy.factor_terms(sympy.trigsimp(sympy.cancel(expr)))


def contact_directions(problem: Problem, frictions: tuple[FrictionTerm, ...], constraints: tuple[ConstraintTerms, ...],
                       reactions: dict[str, Reaction]) -> tuple[list[tuple[tuple[int, int, int], ...]], list[Any]]:
    r"""Per friction contact, the rows ``(constraint j, offset, dims)`` into the returned list of direction
    components: each normal constraint's force direction :math:`\mathbf u_j` on the sliding particle.

    Raises
    ------
    SpecError
        A normal constraint has no known force on the contact's particle.
    """
    contacts: list[tuple[tuple[int, int, int], ...]] = []
    directions: list[Any] = []
    offset = 0
    index = {c.name: j for j, c in enumerate(constraints)}
    for f in frictions:
        rows = []
        for name in f.constraints:
            pushes = [p for p in reactions[name].particles if p.particle == f.particle]
            if not pushes:
                raise SpecError([Issue(problem.source, problem.lines.get(f"friction.{f.name}.normal", 0),
                                       f"friction.{f.name}.normal",
                                       f"constraint {name!r} has no known force on {f.particle!r}, so the "
                                       "normal force cannot be computed", "name constraints that act on it")])
            rows.append((index[name], offset, len(pushes[0].direction)))
            directions += list(pushes[0].direction)
            offset += len(pushes[0].direction)
        contacts.append(tuple(rows))
    return contacts, directions


def normal_forces_at(t: float, contacts: tuple[tuple[tuple[int, int, int], ...], ...], u: np.ndarray,
                     lam: np.ndarray) -> np.ndarray:
    r"""The normal forces at one state, from the multipliers ``lam`` written as :math:`\lambda_0 + \Lambda N`
    (column 0 and one column per contact) and the force directions ``u`` (:func:`contact_directions`).

    Contact :math:`i` has :math:`N_i = |\mathbf a_i + \sum_k \mathbf b_{ik} N_k|` (module
    :mod:`lagsolve.mechanics.normal`): for one contact a quadratic with a unique non-negative root when
    :math:`|\mathbf b| < 1`, for several a fixed-point iteration.

    Raises
    ------
    SimulationError
        No unique normal force (a Painlevé-type inconsistency), or the iteration does not converge.
    """
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
