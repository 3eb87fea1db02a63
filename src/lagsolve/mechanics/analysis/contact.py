r"""Whether an equilibrium is admissible where a constraint is unilateral.

A ``unilateral`` constraint (a surface that can only push) holds while its multiplier
is non-negative, :math:`\lambda \ge 0` (``docs/format.md``). An equilibrium found from
the equations *with* the constraint is therefore a real equilibrium only if the
constraint's force there pushes: with the particle at rest at :math:`q_0`,

.. math::

    \lambda_0 = \lambda(q_0, \dot q = 0) \ge 0 .

A particle at rest at the bottom of a sphere it sits *outside* of satisfies the
equations with :math:`\lambda_0 < 0`: the sphere would have to pull, so the particle
falls off and the point is not an equilibrium of the real system.

Notes
-----
- :math:`\lambda` is the explicit multiplier of the derivation, written in the minimal
  coordinates when the analysis has them; the velocities of the cyclic coordinates of an
  effective potential are their values at the given momenta.
- The sign is decided from the parameters' assumptions (``positive: true``); when it is
  not, the condition :math:`\lambda_0 \ge 0` is given instead of a verdict.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

#: above this many operations a multiplier at the equilibrium is not simplified further
SIMPLIFY_LIMIT = 300


@dataclass(frozen=True)
class ContactCheck:
    """The force of one unilateral constraint at one equilibrium: ``multiplier`` is
    :math:`\\lambda_0`, ``admissible`` True (it pushes or is zero), False (it would pull) or None
    (its sign depends on the parameters: the equilibrium exists only where ``multiplier >= 0``)."""

    constraint: str
    multiplier: Any
    admissible: bool | None


def check_point(multipliers: dict[str, Any], unilateral: tuple[str, ...], point: dict[Any, Any],
                velocities: dict[Any, Any], substitution: Any = None) -> tuple[ContactCheck, ...]:
    """The unilateral constraints' multipliers at rest at ``point``.

    Parameters
    ----------
    multipliers
        Constraint name → explicit multiplier (in coordinates and velocities).
    unilateral
        The names of the unilateral constraints.
    point
        Coordinate symbol → its equilibrium value (the independent coordinates).
    velocities
        Velocity symbol → its value at the equilibrium (0, or a cyclic velocity in terms of its momentum).
    substitution
        An :class:`~lagsolve.mechanics.equations.elimination.Elimination` writing dependent coordinates in independent
        ones.

    >>> x, xd, m, g = sympy.symbols("x x_dot m g", positive=True)
    >>> check_point({"floor": -m * g * sympy.cos(x)}, ("floor",), {x: sympy.pi}, {xd: 0})[0].admissible
    True
    """
    out = []
    for name in unilateral:
        lam = multipliers.get(name)
        if lam is None:
            continue
        if substitution is not None:
            lam = substitution.apply(lam)
        value = lam.xreplace(velocities).xreplace(point)
        if sympy.count_ops(value) <= SIMPLIFY_LIMIT:
            value = sympy.simplify(value)
        out.append(ContactCheck(name, value, _sign(value)))
    return tuple(out)


def _sign(value: Any) -> bool | None:
    if value.is_nonnegative:
        return True
    if value.is_negative:
        return False
    return None
