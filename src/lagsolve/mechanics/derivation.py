"""``derive(problem) -> Derivation``: the frozen result of the whole mechanics stage.

Every step a worked solution shows is recorded here (T, V, L; each constraint's
a and b; each ∂L/∂q̇, its time derivative, ∂L/∂q; the augmented system; the
results), so reports can never disagree with the results. The raw matrix form
(``lagrange``) is kept unsimplified for numeric work; the display forms are
simplified once, in :mod:`lagsolve.mechanics.simplify`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.constraints import ConstraintTerms
from lagsolve.mechanics.forces import ForceTerm, FrictionTerm
from lagsolve.mechanics.lagrange import LagrangeTerms, solve_augmented
from lagsolve.mechanics.matrix_form import MatrixForm, matrix_form
from lagsolve.mechanics.model import Model
from lagsolve.mechanics.reactions import Reaction
from lagsolve.mechanics.reduce import Elimination, eliminate
from lagsolve.mechanics.simplify import norm, root_of_sum_of_squares, tidy, tidy_sum
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class ConstraintForce:
    """Result for one constraint: the force on its particle (``vector``, ``magnitude``),
    per-particle forces when it acts on several, and a ``note`` when no force is claimed."""

    name: str
    vector: tuple[Any, ...] | None
    magnitude: Any | None
    particles: tuple[tuple[str, tuple[Any, ...], Any], ...]
    note: str


@dataclass(frozen=True)
class FrictionResult:
    """A friction contact (``term``, with the symbol N in its forces) and the closed form of N."""

    term: FrictionTerm
    normal_force: Any


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one problem (immutable; nothing to "compute first").

    Display forms (simplified): ``kinetic``, ``potential``, ``lagrangian``, ``constraints``
    (coefficients), ``momenta``, ``momenta_rates``, ``gradients``, ``generalized_forces``,
    ``equations`` (left minus right side), ``equation_sides`` and ``constrained_sides``
    (each equation as (left, right), before and after using the constraints), ``accelerations``, ``multipliers``,
    ``constraint_forces``. Raw forms: ``model``, ``lagrange`` (matrix form) and
    ``raw_accelerations``/``raw_multipliers`` (the augmented solve, unsimplified).
    """

    problem: Problem
    model: Model
    kinetic: Any
    potential: Any
    lagrangian: Any
    constraints: tuple[ConstraintTerms, ...]
    force_terms: tuple[ForceTerm, ...]
    lagrange: LagrangeTerms
    momenta: tuple[Any, ...]
    momenta_rates: tuple[Any, ...]
    gradients: tuple[Any, ...]
    generalized_forces: tuple[Any, ...]
    equations: tuple[Any, ...]
    equation_sides: tuple[tuple[Any, Any], ...]
    elimination: Elimination
    eliminated_accelerations: dict[Any, Any]
    constrained_sides: tuple[tuple[Any, Any], ...]
    raw_accelerations: tuple[Any, ...]
    raw_multipliers: tuple[Any, ...]
    accelerations: dict[str, Any]
    multipliers: dict[str, Any]
    constraint_forces: dict[str, ConstraintForce]
    friction: tuple[FrictionResult, ...] = ()
    reduced: dict[str, Any] | None = None
    conserved: dict[str, Any] | None = None
    effective_potential: dict[str, Any] | None = None
    form: MatrixForm | None = None  # the unsolved matrix form the numeric stage compiles

    @property
    def multiplier_symbols(self) -> tuple[Any, ...]:
        return tuple(c.multiplier for c in self.constraints)


def derive(problem: Problem) -> Derivation:
    """Derive the equations of motion, multipliers and forces of constraint of ``problem``.

    Raises
    ------
    DerivationError
        When the accelerations and multipliers are not determined (singular system).
    """
    form = matrix_form(problem)
    model, constraints, loads, frictions = form.model, form.constraints, form.loads, form.frictions
    q_forces, lagrange, reactions = form.generalized_forces, form.lagrange, form.reactions
    raw_acc, raw_lam = solve_augmented(lagrange)

    elimination = eliminate(constraints, model)
    eliminated_acc = _eliminated_accelerations(constraints, model, elimination)

    def result(expr: Any) -> Any:
        return tidy(elimination.apply(expr))

    multipliers = {c.name: result(lam) for c, lam in zip(constraints, raw_lam, strict=True)}
    forces = {c.name: _constraint_force(reactions[c.name], multipliers[c.name], c, elimination)
              for c in constraints}
    normals = _normal_forces(frictions, raw_lam, constraints, reactions, elimination)
    raw_acc = tuple(a.xreplace(normals) for a in raw_acc)
    accelerations = {c.name: result(a) for c, a in zip(problem.coordinates, raw_acc, strict=True)}

    lhs = tuple(r - g for r, g in zip(lagrange.momenta_rates, lagrange.gradients, strict=True))
    rhs = tuple(q + c for q, c in zip(q_forces, lagrange.constraint_forces, strict=True))
    sides = tuple((tidy_sum(a), tidy_sum(b)) for a, b in zip(lhs, rhs, strict=True))
    constrained = tuple(
        (tidy_sum(elimination.apply(a.xreplace(eliminated_acc))), tidy_sum(elimination.apply(b)))
        for a, b in zip(lhs, rhs, strict=True)
    )
    display_constraints = tuple(
        ConstraintTerms(c.name, c.kind, c.expression, c.on, tuple(tidy(a) for a in c.coefficients),
                        tidy(c.offset), tidy(c.acceleration_rhs), c.multiplier)
        for c in constraints
    )
    derivation = Derivation(
        problem=problem,
        model=model,
        kinetic=tidy_sum(model.kinetic),
        potential=tidy_sum(model.potential),
        lagrangian=model.kinetic - model.potential,
        constraints=display_constraints,
        force_terms=tuple(ForceTerm(t.label, tuple(tidy(x) for x in t.generalized)) for t in loads),
        lagrange=lagrange,
        momenta=tuple(tidy_sum(p) for p in lagrange.momenta),
        momenta_rates=tuple(tidy_sum(p) for p in lagrange.momenta_rates),
        gradients=tuple(tidy_sum(g) for g in lagrange.gradients),
        generalized_forces=tuple(tidy(x) for x in q_forces),
        equations=tuple(tidy_sum(e) for e in lagrange.equations),
        equation_sides=sides,
        elimination=elimination,
        eliminated_accelerations=eliminated_acc,
        constrained_sides=constrained,
        raw_accelerations=raw_acc,
        raw_multipliers=raw_lam,
        accelerations=accelerations,
        multipliers=multipliers,
        constraint_forces=forces,
        friction=tuple(FrictionResult(f, tidy(elimination.apply(normals[f.normal]))) for f in frictions),
        form=form,
    )
    _check_free_symbols(derivation)
    return derivation


def _normal_forces(frictions: tuple[FrictionTerm, ...], multipliers: tuple[Any, ...],
                   constraints: tuple[ConstraintTerms, ...], reactions: dict[str, Reaction],
                   elimination: Elimination) -> dict[Any, Any]:
    r"""Closed form of each friction contact's normal force :math:`N = |\sum_j \mathbf f_j|`.

    Solved when the multipliers do not depend on any N (friction acts along a
    direction that the constraints do not feel: a bead in a tube, on a wire, a
    block on a fixed incline). Otherwise N and the multipliers are coupled; that
    case is not handled yet and is reported as such.
    """
    out: dict[Any, Any] = {}
    symbols = [f.normal for f in frictions]
    for lam, c in zip(multipliers, constraints, strict=True):
        coupled = [str(N) for N in symbols if tidy(sympy.diff(lam, N)) != 0]
        if coupled:
            raise DerivationError(
                f"the multiplier of constraint {c.name!r} depends on the friction (through {', '.join(coupled)}): "
                "the normal force and the friction are coupled, which lagsolve cannot solve yet; "
                "friction along a direction the constraints do not feel is supported"
            )
    index = {c.name: j for j, c in enumerate(constraints)}
    for f in frictions:
        parts = []
        for name in f.constraints:
            react = reactions[name]
            pushes = [p for p in react.particles if p.particle == f.particle]
            if not pushes:
                raise DerivationError(
                    f"friction {f.name!r}: constraint {name!r} has no known force on {f.particle!r} "
                    f"({react.note or 'it acts on other particles'}), so the normal force is unknown"
                )
            parts.append((sympy.Matrix(pushes[0].direction), elimination.apply(multipliers[index[name]])))
        orthogonal = all(tidy((a.T * b)[0]) == 0 for i, (a, _) in enumerate(parts) for b, _ in parts[i + 1:])
        if orthogonal:
            # |sum f_j| = sqrt(sum |f_j|^2): keeps each force's factored form (the textbook's N)
            out[f.normal] = root_of_sum_of_squares([lam * norm(list(u)) for u, lam in parts])
        else:
            total = sum((u * lam for u, lam in parts), sympy.zeros(parts[0][0].rows, 1))
            out[f.normal] = norm([elimination.apply(v) for v in total])
    return out


def _eliminated_accelerations(constraints: tuple[ConstraintTerms, ...], model: Model,
                              elimination: Elimination) -> dict[Any, Any]:
    """q̈_k of each eliminated variable, from its constraint at acceleration level."""
    out: dict[Any, Any] = {}
    by_name = {c.name: c for c in constraints}
    index = {**{q: i for i, q in enumerate(model.coordinates)}, **{v: i for i, v in enumerate(model.velocities)}}
    for symbol, source in elimination.sources.items():
        c = by_name[source]
        k = index[symbol]
        rest = sum((c.coefficients[i] * model.accelerations[i] for i in range(len(model.coordinates)) if i != k),
                   sympy.Integer(0))
        out[model.accelerations[k]] = elimination.apply(sympy.cancel((c.acceleration_rhs - rest) / c.coefficients[k]))
    return out


def _constraint_force(react: Reaction, multiplier: Any, terms: ConstraintTerms,
                      elimination: Elimination) -> ConstraintForce:
    if not react.particles:
        magnitude = None
        if react.generalized:
            magnitude = norm([elimination.apply(multiplier * a) for a in terms.coefficients])
        return ConstraintForce(react.name, None, magnitude, (), react.note)
    per_particle = []
    for p in react.particles:
        vector = tuple(tidy(elimination.apply(multiplier * d)) for d in p.direction)
        per_particle.append((p.particle, vector, norm(vector)))
    if len(per_particle) == 1:
        _, vector, magnitude = per_particle[0]
        return ConstraintForce(react.name, vector, magnitude, tuple(per_particle), react.note)
    sizes = {sympy.srepr(m) for _, _, m in per_particle}
    common = per_particle[0][2] if len(sizes) == 1 else None
    return ConstraintForce(react.name, None, common, tuple(per_particle), react.note)


def _check_free_symbols(derivation: Derivation) -> None:
    """Every symbol in a result must be declared (style rule 5): a cheap guard against slips."""
    problem = derivation.problem
    allowed = set(problem.symbols.values()) | set(derivation.multiplier_symbols)
    allowed |= set(derivation.model.accelerations)
    for name, expr in {**derivation.accelerations, **derivation.multipliers}.items():
        stray = expr.free_symbols - allowed
        if stray:
            raise DerivationError(
                f"internal error: result for {name} contains undeclared symbols {sorted(map(str, stray))}"
            )
