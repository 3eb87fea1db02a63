r"""The energy function of a Lagrangian, decided once.

:func:`jacobi_integral` is :math:`h = \sum_i \dot q_i\,\partial L/\partial\dot q_i - L`
(:math:`T_2 - T_0 + V` for :math:`T = T_2 + T_1 + T_0`; :math:`T + V` when :math:`T` is quadratic in
the velocities). Whether it is conserved is decided by :mod:`lagsolve.mechanics.analysis.conserved`; the
numeric stage compiles this same expression to report its drift.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.symbolic.partials import partial


def jacobi_integral(model: Model) -> Any:
    r""":math:`h = \sum_i \dot q_i\,\partial L/\partial\dot q_i - L` of ``model``'s Lagrangian (raw, unsimplified)."""
    L = model.lagrangian
    return sum((v * partial(L, v) for v in model.velocities), sympy.Integer(0)) - L
