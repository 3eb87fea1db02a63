"""Kinetic and potential energy of a problem, and the Lagrangian L = T - V.

Coordinates, velocities and accelerations are plain real symbols (``x``,
``x_dot``, ``x_ddot``); time derivatives are taken with :func:`time_derivative`,
so a declared function of a coordinate differentiates to ``Derivative(f(x), x)``
exactly as the problem format writes it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM, engine_sum, total_rate
from lagsolve.mechanics.symbolic.simplify import tidy_sum
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class Model:
    """Symbols and energies of a problem.

    ``coordinates``, ``velocities`` and ``accelerations`` are tuples of symbols
    in input order; ``kinetic``, ``potential`` and ``lagrangian`` are expressions
    in the coordinates, velocities, parameters and time.
    """

    time: Any
    coordinates: tuple[Any, ...]
    velocities: tuple[Any, ...]
    accelerations: tuple[Any, ...]
    kinetic: Any
    potential: Any
    lagrangian: Any

    def time_derivative(self, expr: Any, *, second_order: bool = False) -> Any:
        """Total time derivative along the motion (see :func:`time_derivative`)."""
        return time_derivative(expr, self, second_order=second_order)


def time_derivative(expr: Any, model: Model, *, second_order: bool = False) -> Any:
    r"""Total time derivative of ``expr``.

    .. math:: \frac{d}{dt}F = \frac{\partial F}{\partial t}
              + \sum_i \frac{\partial F}{\partial q_i}\dot q_i
              + \sum_i \frac{\partial F}{\partial \dot q_i}\ddot q_i

    The last sum is taken only with ``second_order=True`` (``expr`` may depend on
    velocities); otherwise ``expr`` must depend on coordinates and time only.

    >>> import sympy
    >>> t, x, xd, xdd = sympy.symbols("t x x_dot x_ddot")
    >>> f = sympy.Function("f")
    >>> m = Model(t, (x,), (xd,), (xdd,), 0, 0, 0)
    >>> time_derivative(f(x), m)
    x_dot*Derivative(f(x), x)

    A bulk system's (:data:`~lagsolve.mechanics.symbolic.partials.BULK_SYSTEM`) first derivatives are taken by
    SymEngine where the expression allows.
    """
    if not second_order and len(model.coordinates) > BULK_SYSTEM:
        found = total_rate(expr, model.time, tuple(zip(model.coordinates, model.velocities, strict=True)))
        if found is not None:
            return found
    result = sympy.diff(expr, model.time)
    for q, qd in zip(model.coordinates, model.velocities, strict=True):
        result += sympy.diff(expr, q) * qd
    if second_order:
        for qd, qdd in zip(model.velocities, model.accelerations, strict=True):
            result += sympy.diff(expr, qd) * qdd
    return result


#: energies with more operations than this are not tidied when ``tidy=None`` (the cost grows quickly)
TIDY_ENERGY_LIMIT = 300


def build_model(problem: Problem, *, tidy: bool | None = True) -> Model:
    r"""Energies of ``problem``.

    .. math::
        T = \sum_p \tfrac12 m_p |\dot{\mathbf r}_p|^2
            + \sum_b \big(\tfrac12 M_b |\dot{\mathbf r}_b|^2 + T_{rot,b}\big) + T_{extra},\qquad
        V = -\sum m\,\mathbf g\cdot\mathbf r + V_{extra}

    with :math:`T_{rot} = \tfrac12 I\omega^2` for a planar body and
    :math:`\tfrac12\sum_k I_k\omega_k^2` (principal axes, body-frame components) in 3-D.
    ``tidy=None`` tidies them only when they are small (:data:`TIDY_ENERGY_LIMIT`);
    ``tidy=False`` leaves the energies as built (for the numeric stage, which compiles them with
    common-subexpression elimination and has no use for a compact display form).
    """
    q = tuple(c.symbol for c in problem.coordinates)
    qd = tuple(c.velocity for c in problem.coordinates)
    qdd = tuple(c.acceleration for c in problem.coordinates)
    bare = Model(problem.time, q, qd, qdd, 0, 0, 0)

    kinetic, potential = _energies(problem, bare)
    # Simplify the energies once, here: every later expression is built from them,
    # so a compact L keeps the whole derivation small (an identity, not an approximation).
    if tidy or (tidy is None and ops(kinetic) + ops(potential) <= TIDY_ENERGY_LIMIT):
        kinetic, potential = tidy_sum(kinetic), tidy_sum(potential)
    # a bulk system's L by SymEngine, which keeps its form for the stages that differentiate L
    lagrangian = (engine_sum(((1, kinetic), (-1, potential)), expand=False) if len(q) > BULK_SYSTEM
                  else kinetic - potential)
    return Model(problem.time, q, qd, qdd, kinetic, potential, lagrangian)


def _energies(problem: Problem, bare: Model) -> tuple[Any, Any]:
    """T and V as built (:func:`build_model`); a bulk system's summed by SymEngine term by term (its velocities
    are SymEngine's already, :func:`time_derivative`), a smaller one's by SymPy as always."""
    masses = [(p.mass, p.position) for p in problem.particles] + [(b.mass, b.position) for b in problem.bodies]
    if len(bare.coordinates) > BULK_SYSTEM:
        return _bulk_energies(problem, bare, masses)
    kinetic = sympy.Integer(0)
    potential = sympy.Integer(0)
    for mass, position in masses:
        velocity = [time_derivative(component, bare) for component in position]
        kinetic += mass * sum(v**2 for v in velocity) / 2
        if problem.gravity is not None:
            potential -= mass * sum(g * r for g, r in zip(problem.gravity, position, strict=True))
    for body in problem.bodies:
        kinetic += sum(i * w**2 for i, w in zip(body.inertia, body.angular_velocity, strict=True)) / 2
    if problem.kinetic is not None:
        kinetic += problem.kinetic
    if problem.potential is not None:
        potential += problem.potential
    return kinetic, potential


def _bulk_energies(problem: Problem, bare: Model, masses: list[tuple[Any, Any]]) -> tuple[Any, Any]:
    kinetic: list[Any] = []
    potential: list[Any] = []
    for mass, position in masses:
        kinetic += [mass * time_derivative(component, bare) ** 2 / 2 for component in position]
        if problem.gravity is not None:
            potential += [-mass * g * r for g, r in zip(problem.gravity, position, strict=True)]
    for body in problem.bodies:
        kinetic += [i * w**2 / 2 for i, w in zip(body.inertia, body.angular_velocity, strict=True)]
    kinetic += [problem.kinetic] if problem.kinetic is not None else []
    potential += [problem.potential] if problem.potential is not None else []
    # not multiplied out: T stays a sum of ½ m |v|², whose second derivatives are the particles' m Jᵢ·Jⱼ
    return engine_sum(((1, t) for t in kinetic), expand=False), engine_sum(((1, v) for v in potential), expand=False)
