r"""A friction contact while it sticks: the tangential force that holds it, and when it can.

A contact that slides along one line (:mod:`lagsolve.mechanics.equations.friction`) sticks when its sliding rate
:math:`\sigma = w\cdot\dot q` stays zero: the kinetic friction is replaced by a tangential force
:math:`\Phi\,\mathbf t` at the contact, whose generalized forces are :math:`\Phi\,w` (the contact's sliding
coordinates being all the coordinates, :math:`w = J_{rel}^T\mathbf t`), so :math:`\sigma = 0` is one more
velocity constraint and :math:`\Phi` its multiplier:

.. math:: M\ddot q = F_0 + A^T\lambda + w\,\Phi,\qquad A\ddot q = \beta,\qquad w\cdot\ddot q = -\dot w\cdot\dot q .

Solved symbolically this gives :math:`\Phi`, the normal force :math:`N = |\sum_j\lambda_j\mathbf u_j|` while it
sticks, and the condition of Coulomb's law for sticking, :math:`|\Phi| \le \mu_s N`, written as the least static
coefficient, :math:`\mu_s \ge |\Phi|/N`: a disc on an incline rolls while :math:`\mu_s \ge |\tan\alpha|/3`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.equations.elimination import Elimination
from lagsolve.mechanics.equations.friction import FrictionTerm
from lagsolve.mechanics.equations.matrix_form import MatrixForm
from lagsolve.mechanics.equations.surface import Surface
from lagsolve.mechanics.symbolic.linsolve import SIZE_LIMIT, solve_structured
from lagsolve.mechanics.symbolic.simplify import norm, tidy


@dataclass(frozen=True)
class Sticking:
    """One contact held: ``force`` the tangential force Φ along its tangent t, ``normal`` N while it sticks,
    ``ratio`` |Φ|/N, the least static coefficient that holds it (``None`` where N is not known)."""

    force: Any
    normal: Any
    ratio: Any


def sticking(form: MatrixForm, term: FrictionTerm, known: dict[Any, Any], elimination: Elimination) -> Sticking | str:
    """``term`` held at rest relative to its surface, the other contacts as they are (their closed-form normal
    forces ``known`` put in), or the reason it is not given."""
    if term.rate is None or term.unit_generalized is None:
        return "it slides in a plane: its sticking is not one constraint"
    if any(sympy.simplify(w - g) != 0 for w, g in zip(term.rate, term.unit_generalized, strict=True)):
        return ("its sliding coordinates do not move the whole system: the force that holds it is not given in "
                "closed form (the simulation computes it)")
    model, lagrange = form.model, form.lagrange
    others = {f.normal for f in form.frictions if f.normal != term.normal}
    forcing = lagrange.forcing.xreplace({term.normal: 0}).xreplace(known)
    if forcing.free_symbols & others:
        return "another contact's normal force has no closed form here"
    w = sympy.Matrix([list(term.rate)])
    drift = sum((model.time_derivative(c) * v for c, v in zip(term.rate, model.velocities, strict=True)),
                sympy.Integer(0))
    A = sympy.Matrix.vstack(lagrange.constraint_jacobian, w)
    beta = sympy.Matrix.vstack(lagrange.constraint_rhs, sympy.Matrix([-drift]))
    try:
        _, multipliers = solve_structured(lagrange.mass_matrix, forcing, A, beta, SIZE_LIMIT)
    except (ValueError, ZeroDivisionError):
        return "held, the system is singular (the contact is the only thing that moves)"
    lam, force = list(multipliers[:-1]), multipliers[-1]
    index = {c.name: j for j, c in enumerate(form.constraints)}
    parts = []
    for name in term.constraints:
        push = next(p for p in form.reactions[name].particles if p.particle == term.particle)
        parts.append(sympy.Matrix(push.direction) * lam[index[name]])
    total = sum(parts[1:], parts[0])
    held = _held_velocity(term, form, elimination)
    surface = Surface(form.constraints, model, elimination)

    def on_surface(expr: Any) -> Any:  # the constraints used, and the sliding rate zero
        return surface.apply(elimination.apply(expr).xreplace(held)).xreplace(held)

    shown_force = tidy(on_surface(force))
    shown_normal = norm([tidy(on_surface(c)) for c in total])
    ratio = tidy(sympy.Abs(shown_force) / shown_normal) if shown_normal != 0 else None
    return Sticking(shown_force, shown_normal, ratio)


def _held_velocity(term: FrictionTerm, form: MatrixForm, elimination: Elimination) -> dict[Any, Any]:
    """The sliding rate σ = 0 solved for one velocity the constraints leave free (the simplest coefficient)."""
    assert term.rate is not None
    model = form.model
    rate = sympy.expand(elimination.apply(sum((w * v for w, v in zip(term.rate, model.velocities, strict=True)),
                                              sympy.Integer(0))))
    options = [(sympy.count_ops(sympy.diff(rate, v)), i, v) for i, v in enumerate(model.velocities)
               if v not in elimination.velocities and sympy.diff(rate, v) != 0
               and not sympy.diff(rate, v).has(*model.velocities)]
    if not options:
        return {}
    _, _, v = min(options, key=lambda o: (o[0], o[1]))
    return {v: sympy.cancel(v - rate / sympy.diff(rate, v))}
