"""Follow-through for ``lagsolve grade``: what follows from a submission's own earlier steps (their L gives their
momenta, ∂L/∂q and equations; their equations their q̈ and λ; their λ their forces of constraint; ...)."""

from __future__ import annotations

import contextlib
from collections.abc import Collection
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.grade.analysis_steps import legendre
from lagsolve.grade.follow_analysis import own_normal_forces
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.equations.lagrange import LagrangeTerms, lagrange_terms
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.reactions import force_scale
from lagsolve.mechanics.symbolic.linsolve import solve_linear


def follow_through(derivation: Derivation, own: dict[str, dict[str, Any]], steps: Collection[str] = ()
                   ) -> dict[str, dict[str, Any]]:
    """The answers that follow from the submission's own Lagrangian and equations, step by step (the normal forces
    from their λ only when ``steps``, the graded ones, has ``normal_force``; the analysis steps:
    :mod:`.follow_analysis`)."""
    model = derivation.model
    names = [q.name for q in derivation.problem.coordinates]
    out: dict[str, dict[str, Any]] = {}
    kinetic = own.get("kinetic", {}).get("")
    potential = own.get("potential", {}).get("")
    if kinetic is not None or potential is not None:
        out["lagrangian"] = {"": (model.kinetic if kinetic is None else kinetic)
                             - (model.potential if potential is None else potential)}
    lagrangian = own.get("lagrangian", {}).get("", out.get("lagrangian", {}).get(""))
    terms: LagrangeTerms | None = None
    if lagrangian is not None:
        form = derivation.form
        forces = form.generalized_forces if form is not None else tuple(0 for _ in names)
        student = Model(model.time, model.coordinates, model.velocities, model.accelerations,
                        sympy.Integer(0), sympy.Integer(0), lagrangian)
        with contextlib.suppress(TypeError, ValueError, AttributeError, NotImplementedError):
            terms = lagrange_terms(student, tuple(constraint_terms(derivation)), tuple(forces))
    if lagrangian is not None:
        with contextlib.suppress(TypeError, ValueError, AttributeError, NotImplementedError, ZeroDivisionError):
            own_h = legendre(derivation, lagrangian)
            if own_h is not None:
                out["hamiltonian"] = {"": own_h}
    if terms is not None:
        out["momenta"] = dict(zip(names, terms.momenta, strict=True))
        out["generalized_forces"] = dict(zip(names, terms.gradients, strict=True))
        out["equations"] = dict(zip(names, terms.equations, strict=True))
    equations = [own.get("equations", {}).get(q, (terms.equations[i] if terms is not None else None))
                 for i, q in enumerate(names)]
    if "equations" in own or terms is not None:
        solved = solve(derivation, equations)
        if solved is not None:
            accelerations, multipliers = solved
            out["accelerations"] = dict(zip(names, accelerations, strict=True))
            constraints = [c.name for c in derivation.constraints]
            out["multipliers"] = dict(zip(constraints, multipliers, strict=True))
    lam = own.get("multipliers") or out.get("multipliers")
    if lam and derivation.form is not None:
        magnitudes = {}
        for c in derivation.constraints:
            scale = force_scale(derivation.form.reactions[c.name])
            if c.name in lam and scale is not sympy.nan:
                magnitudes[c.name] = sympy.Abs(lam[c.name]) * scale
        out["constraint_forces"] = magnitudes
        if "normal_force" in steps:
            out["normal_force"] = own_normal_forces(derivation, lam)
    return out


def constraint_terms(derivation: Derivation) -> tuple[Any, ...]:
    form = derivation.form
    return form.constraints if form is not None else derivation.constraints


def still_rhs(c: Any, model: Model) -> Any:
    r"""β of a constraint as if it did not move: :math:`-\sum_{jk} \partial a_j/\partial q_k \dot q_k \dot q_j`
    (its offset b = ∂ψ/∂t and every explicit t-derivative dropped)."""
    return -sum((sympy.diff(a, q) * qd_k * qd_j
                 for a, qd_j in zip(c.coefficients, model.velocities, strict=True)
                 for q, qd_k in zip(model.coordinates, model.velocities, strict=True)), sympy.Integer(0))


def solve(derivation: Derivation, equations: list[Any], *, still: bool = False
          ) -> tuple[list[Any], list[Any]] | None:
    r"""q̈ and λ from the submission's equations (linear in them) and the key's constraints, A q̈ = β (with
    ``still``, each constraint's β as if it did not move: :func:`still_rhs`)."""
    if any(e is None for e in equations):
        return None
    model = derivation.model
    constraints = constraint_terms(derivation)
    unknowns = [*model.accelerations, *(c.multiplier for c in constraints)]
    rows = list(equations)
    for c in constraints:
        rhs = still_rhs(c, model) if still else c.acceleration_rhs
        rows.append(sum((a * qdd for a, qdd in zip(c.coefficients, model.accelerations, strict=True)),
                        sympy.Integer(0)) - rhs)
    zero = {u: 0 for u in unknowns}
    try:
        matrix = sympy.Matrix([[sympy.diff(r, u) for u in unknowns] for r in rows])
        if any(entry.has(*unknowns) for entry in matrix):
            return None  # not linear in the accelerations and multipliers
        rhs = sympy.Matrix([-r.xreplace(zero) for r in rows])
        solution = list(solve_linear(matrix, rhs))
    except (ValueError, ZeroDivisionError, TypeError, DerivationError):
        return None
    n = len(model.accelerations)
    return solution[:n], solution[n:]
