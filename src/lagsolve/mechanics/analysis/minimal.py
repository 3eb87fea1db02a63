r"""Minimal coordinates: the constraints solved for the dependent coordinates, then Lagrange again.

The homework's "alternate method". With every constraint holonomic (as given, or a
velocity constraint integrated by :mod:`~lagsolve.mechanics.analysis.integrability`), each one is
solved in closed form for a dependent coordinate, :math:`q_d = \varphi_d(q_I, t)`, and
substituted into the energies:

.. math::
    L_{red}(q_I, \dot q_I, t) = L\big(q_I, \varphi(q_I, t), \dot q_I, \dot\varphi\big), \qquad
    Q^{red}_k = \sum_i Q_i \frac{\partial q_i}{\partial q_k}\ (k \in I),

and :math:`\frac{d}{dt}\partial L_{red}/\partial\dot q_k - \partial L_{red}/\partial q_k = Q^{red}_k`
gives the independent accelerations with no multipliers at all. Both routes must agree:
the multiplier route's :math:`\ddot q_k`, with the dependent variables substituted, equals
the reduced one (checked here, symbolically when possible).

Notes
-----
* A constraint is solved when it is linear in a coordinate; without an ``independent:``
  list the choice is :func:`lagsolve.mechanics.equations.elimination.eliminate`'s (constant coefficient,
  last such coordinate in input order).
* A nonholonomic constraint cannot be substituted into L (that gives wrong equations), so
  no reduced system is formed when one remains.
* Friction forces enter with their normal force in closed form from the multiplier route.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.analysis.integrability import HOLONOMIC, INTEGRABLE, Classification
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.elimination import Elimination, eliminate
from lagsolve.mechanics.equations.lagrange import LagrangeTerms, lagrange_terms, solve_augmented
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.symbolic.identities import Zero, zero_status
from lagsolve.mechanics.symbolic.linsolve import SIZE_LIMIT
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM
from lagsolve.mechanics.symbolic.simplify import tidy, tidy_sum, tidy_sum_bulk


@dataclass(frozen=True)
class ReducedSystem:
    r"""The system in its independent coordinates alone.

    ``independent`` are coordinate symbols; ``substitution`` gives each dependent
    coordinate and velocity (``sources`` names the constraint); ``constants`` are the
    integration constants it uses (:math:`\theta_0`). ``model`` holds the raw reduced
    energies, ``generalized_forces`` :math:`Q^{red}`, ``lagrange`` the matrix form and
    ``raw_accelerations`` its solution. Display forms: ``kinetic``, ``potential``,
    ``lagrangian``, ``equation_sides`` ((left, right) per independent coordinate) and
    ``accelerations`` (by name). ``agreement`` is ``"symbolic"`` when the multiplier
    route's accelerations were proved equal, ``"numeric"`` when they agree at random
    points only, ``"differ"`` otherwise (a bug).
    """

    independent: tuple[Any, ...]
    substitution: Elimination
    constants: tuple[Any, ...]
    model: Model
    generalized_forces: tuple[Any, ...]
    lagrange: LagrangeTerms
    raw_accelerations: tuple[Any, ...]
    kinetic: Any
    potential: Any
    lagrangian: Any
    equation_sides: tuple[tuple[Any, Any], ...]
    accelerations: dict[str, Any]
    agreement: str

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(q.name for q in self.independent)

    def acceleration_map(self) -> dict[Any, Any]:
        """:math:`\\ddot q_k \\to` its raw expression, for substitution."""
        if not self.raw_accelerations:
            return {}
        return dict(zip(self.model.accelerations, self.raw_accelerations, strict=True))


def holonomic_set(constraints: tuple[ConstraintTerms, ...],
                  classes: tuple[Classification, ...]) -> tuple[tuple[ConstraintTerms, ...], str]:
    """Every constraint as a holonomic one, or ``((), reason)`` when one is not holonomic."""
    out = []
    for c, k in zip(constraints, classes, strict=True):
        if k.kind == HOLONOMIC:
            out.append(c)
        elif k.kind == INTEGRABLE and k.holonomic is not None:
            out.append(k.holonomic)
        else:
            return (), (f"constraint {c.name!r} is {k.kind}: substituting it into L would give wrong "
                        "equations, so the multiplier route above is the one to use")
    return tuple(out), ""


def choose_dependent(constraints: tuple[ConstraintTerms, ...], model: Model,
                     independent: tuple[str, ...]) -> tuple[Elimination | None, str]:
    """Solve each holonomic constraint for a dependent coordinate.

    Without ``independent`` names this is :func:`eliminate`; with them, each constraint is
    solved for a coordinate outside the list that it contains linearly (constant
    coefficients preferred). Returns the substitution, or None and the reason.
    """
    if not independent:
        elimination = eliminate(constraints, model)
    else:
        elimination = _eliminate_for(constraints, model, set(independent))
    solved = {elimination.sources.get(q) for q in model.coordinates} - {None}
    for c in constraints:
        if c.name not in solved:
            return None, (f"constraint {c.name!r} ({sympy.sstr(c.expression)} = 0) is not solved for any "
                          + ("coordinate outside the independent list " if independent else "coordinate ")
                          + "in closed form (lagsolve solves a constraint that is linear in a coordinate); "
                          "choose coordinates in which it is linear")
    if independent:
        free = [q.name for q in model.coordinates if q not in elimination.positions]
        if sorted(free) != sorted(independent):
            return None, (f"the constraints fix {len(elimination.positions)} coordinate(s), so "
                          f"{len(model.coordinates) - len(elimination.positions)} are independent, "
                          f"but the file lists {', '.join(independent)}")
    dependent = set(elimination.positions)
    for value in elimination.positions.values():
        if elimination.apply(value).free_symbols & dependent:
            return None, "the constraints could not be solved one after another for the dependent coordinates"
    return elimination, ""


def _eliminate_for(constraints: tuple[ConstraintTerms, ...], model: Model, independent: set[str]) -> Elimination:
    positions: dict[Any, Any] = {}
    velocities: dict[Any, Any] = {}
    sources: dict[Any, str] = {}
    variables = set(model.coordinates) | {model.time}
    for c in constraints:
        options = []
        for i in reversed(range(len(model.coordinates))):
            q, a = model.coordinates[i], c.coefficients[i]
            if q.name in independent or q in positions or a == 0 or q in a.free_symbols:
                continue
            if sympy.diff(c.expression, q, 2) != 0:
                continue
            options.append((bool(a.free_symbols & variables), i))
        if not options:
            continue
        _, i = min(options, key=lambda o: o[0])  # constant coefficient first, then input order from the end
        q, a, qd = model.coordinates[i], c.coefficients[i], model.velocities[i]
        positions[q] = sympy.cancel(q - c.expression / a)
        rate = sum((aj * v for aj, v in zip(c.coefficients, model.velocities, strict=True)), c.offset)
        velocities[qd] = sympy.cancel(qd - rate / a)
        sources[q] = c.name
    return Elimination(positions, velocities, sources)


def reduce_system(model: Model, constraints: tuple[ConstraintTerms, ...], classes: tuple[Classification, ...],
                  generalized_forces: tuple[Any, ...], normal_forces: dict[Any, Any],
                  full_accelerations: tuple[Any, ...] | None,
                  independent: tuple[str, ...] = (), *, solve: bool = True) -> tuple[ReducedSystem | None, str]:
    """The reduced system (see the module docstring), or None and the reason it is not formed.

    ``generalized_forces`` are the full :math:`Q_i` (friction with its normal-force symbols,
    replaced by ``normal_forces``); ``full_accelerations`` the multiplier route's raw
    :math:`\\ddot q` for the agreement check. ``solve=False`` stops after the reduced energies and
    forces (no equations, no accelerations): what a simulation needs, cheaply.
    """
    holonomic, reason = holonomic_set(constraints, classes)
    if reason:
        return None, reason
    elimination, reason = choose_dependent(holonomic, model, independent)
    if elimination is None:
        return None, reason
    kept, reduced_model = _reduced_model(model, elimination)
    q_ind, kinetic, potential = reduced_model.coordinates, reduced_model.kinetic, reduced_model.potential
    q_red = _reduced_forces(model, elimination, generalized_forces, normal_forces, q_ind)
    terms = lagrange_terms(reduced_model, (), q_red, engine="symengine")
    if not elimination.positions and full_accelerations is None:
        solve = False  # nothing eliminated, and the full system's explicit solve was too large: the same here
    constants = tuple(k.constant for k in classes if k.constant is not None)
    if not solve:
        return ReducedSystem(independent=q_ind, substitution=elimination, constants=constants, model=reduced_model,
                             generalized_forces=q_red, lagrange=terms, raw_accelerations=(), kinetic=kinetic,
                             potential=potential, lagrangian=kinetic - potential, equation_sides=(),
                             accelerations={}, agreement="unchecked"), ""
    if not elimination.positions and full_accelerations is not None:
        raw = tuple(full_accelerations)  # nothing eliminated: the reduced system is the full one
    else:
        try:
            raw, _ = solve_augmented(terms, SIZE_LIMIT)
        except DerivationError as exc:
            return None, f"the reduced equations are singular ({exc})"
    sides = tuple((tidy_sum(r - g), tidy_sum(f))
                  for r, g, f in zip(terms.momenta_rates, terms.gradients, q_red, strict=True))
    return ReducedSystem(
        independent=q_ind, substitution=elimination, constants=constants, model=reduced_model,
        generalized_forces=q_red, lagrange=terms, raw_accelerations=tuple(raw), kinetic=kinetic,
        potential=potential, lagrangian=kinetic - potential, equation_sides=sides,
        accelerations={q.name: tidy(a) for q, a in zip(q_ind, raw, strict=True)},
        agreement=_agreement(kept, elimination, full_accelerations, raw),
    ), ""


def _reduced_model(model: Model, elimination: Elimination) -> tuple[tuple[int, ...], Model]:
    """The indices of the coordinates kept (those not eliminated) and the model in them: the energies with
    the eliminated coordinates put in."""
    kept = tuple(i for i, q in enumerate(model.coordinates) if q not in elimination.positions)
    q_ind = tuple(model.coordinates[i] for i in kept)
    show = tidy_sum_bulk if len(model.coordinates) > BULK_SYSTEM else tidy_sum  # a bulk one's by SymEngine
    kinetic = show(elimination.apply(model.kinetic))
    potential = show(elimination.apply(model.potential))
    return kept, Model(model.time, q_ind, tuple(model.velocities[i] for i in kept),
                       tuple(model.accelerations[i] for i in kept), kinetic, potential, kinetic - potential)


def _reduced_forces(model: Model, elimination: Elimination, generalized_forces: tuple[Any, ...],
                    normal_forces: dict[Any, Any], q_ind: tuple[Any, ...]) -> tuple[Any, ...]:
    """The generalized forces along the kept coordinates: Σ_i Q_i ∂q_i/∂q_k along the elimination's path."""
    path = [elimination.apply(model.coordinates[i]) for i in range(len(model.coordinates))]
    forces = [elimination.apply(f.xreplace(normal_forces)) for f in generalized_forces]
    return tuple(tidy(sum((forces[i] * sympy.diff(path[i], q) for i in range(len(path))), sympy.Integer(0)))
                 for q in q_ind)


def _agreement(kept: tuple[int, ...], elimination: Elimination, full_accelerations: tuple[Any, ...] | None,
               raw: tuple[Any, ...]) -> str:
    """How the reduced accelerations agree with the multiplier route's: "symbolic", "numeric" (some difference
    not decided zero symbolically), "differ", or "unchecked" without the multiplier route's."""
    if full_accelerations is None:
        return "unchecked"
    agreement = "symbolic"
    for k, i in enumerate(kept):
        status = zero_status(elimination.apply(full_accelerations[i]) - raw[k])
        if status is Zero.NONZERO:
            return "differ"
        if status is Zero.UNDECIDED:
            agreement = "numeric"
    return agreement
