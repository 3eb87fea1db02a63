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
from lagsolve.mechanics.analysis import with_analysis
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
    """A friction contact (``term``, with the symbol N in its forces), the closed form of N (the
    symbol itself when only an implicit equation exists), which ``case`` applies and why, and
    the condition under which that form is valid."""

    term: FrictionTerm
    normal_force: Any
    case: str = ""
    valid_while: Any = None


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one problem (immutable; nothing to "compute first").

    Display forms (simplified): ``kinetic``, ``potential``, ``lagrangian``, ``constraints``
    (coefficients), ``momenta``, ``momenta_rates``, ``gradients``, ``generalized_forces``,
    ``equations`` (left minus right side), ``equation_sides`` and ``constrained_sides``
    (each equation as (left, right), before and after using the constraints), ``accelerations``, ``multipliers``,
    ``constraint_forces``. Raw forms: ``model``, ``lagrange`` (matrix form) and
    ``raw_accelerations``/``raw_multipliers`` (the augmented solve, unsimplified).
    Analysis (:mod:`lagsolve.mechanics.analysis`): ``analysis`` with every step, and the
    contract forms ``reduced``, ``conserved``, ``effective_potential`` (format section 2).
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
    analysis: Any = None  # lagsolve.mechanics.analysis.Analysis: classification, reduction, conservation, ...
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

    normals, cases = _normal_forces(frictions, raw_lam, constraints, reactions, elimination)
    # decoupled normal forces are substituted; coupled ones stay symbols N in the results (as a worked
    # solution writes them), with their closed form given once, in the friction results
    substituted = {f.normal: normals[f.normal] for f in frictions
                   if f.normal in normals and cases[f.name][1] is None}
    raw_lam = tuple(lam.xreplace(substituted) for lam in raw_lam)
    multipliers = {c.name: result(lam) for c, lam in zip(constraints, raw_lam, strict=True)}
    forces = {c.name: _constraint_force(reactions[c.name], multipliers[c.name], c, elimination)
              for c in constraints}
    raw_acc = tuple(a.xreplace(substituted) for a in raw_acc)
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
        friction=tuple(FrictionResult(f, tidy(elimination.apply(normals.get(f.normal, f.normal))), *cases[f.name])
                       for f in frictions),
        form=form,
    )
    _check_free_symbols(derivation)
    return with_analysis(derivation)


def _normal_forces(frictions: tuple[FrictionTerm, ...], multipliers: tuple[Any, ...],
                   constraints: tuple[ConstraintTerms, ...], reactions: dict[str, Reaction],
                   elimination: Elimination) -> tuple[dict[Any, Any], dict[str, tuple[str, Any]]]:
    r"""Each friction contact's normal force :math:`N = |\sum_j \mathbf f_j|`, and which case applies.

    The multipliers are affine in the normal forces, :math:`\lambda = \lambda_0 + \Lambda N`
    (the friction forces are), so with :math:`\mathbf a = \sum_j \lambda_{0j}\mathbf u_j` and
    :math:`\mathbf b = \sum_j \Lambda_j\mathbf u_j` the normal force solves :math:`N = |\mathbf a + \mathbf b N|`:

    * **decoupled** (:math:`\mathbf b = 0`: friction along a direction the constraints do not
      feel — a bead in a tube, on a wire, a block on a fixed incline): :math:`N = |\mathbf a|`;
    * **coupled, one contact**: the quadratic :math:`(1 - b^2)N^2 - 2(\mathbf a\cdot\mathbf b)N - a^2 = 0`
      has the one non-negative root
      :math:`N = \big(\mathbf a\cdot\mathbf b + \sqrt{(\mathbf a\cdot\mathbf b)^2 + (1 - b^2)a^2}\big)/(1 - b^2)`
      while :math:`b^2 < 1` (the sign of the sliding rate is part of :math:`\mathbf b`: one
      formula covers both sign cases);
    * **coupled, several contacts**: no closed form is attempted; N stays a symbol in the
      results and ``simulate`` solves the implicit system at every step.
    """
    out: dict[Any, Any] = {}
    cases: dict[str, tuple[str, Any]] = {}
    index = {c.name: j for j, c in enumerate(constraints)}
    symbols = [f.normal for f in frictions]
    coupled_any = any(tidy(sympy.diff(lam, N)) != 0 for lam in multipliers for N in symbols)
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
            parts.append((sympy.Matrix(pushes[0].direction), multipliers[index[name]]))
        if not coupled_any:
            parts = [(u, elimination.apply(lam)) for u, lam in parts]
            orthogonal = all(tidy((a.T * b)[0]) == 0 for i, (a, _) in enumerate(parts) for b, _ in parts[i + 1:])
            if orthogonal:
                # |sum f_j| = sqrt(sum |f_j|^2): keeps each force's factored form (the textbook's N)
                out[f.normal] = root_of_sum_of_squares([lam * norm(list(u)) for u, lam in parts])
            else:
                total = sum((u * lam for u, lam in parts), sympy.zeros(parts[0][0].rows, 1))
                out[f.normal] = norm(list(total))
            cases[f.name] = ("decoupled: the multipliers do not depend on the friction, so N follows from them "
                             "in closed form", None)
        elif len(frictions) == 1:
            zero = {f.normal: 0}
            a = sum((u * lam.xreplace(zero) for u, lam in parts), sympy.zeros(parts[0][0].rows, 1))
            b = sum((u * sympy.diff(lam, f.normal) for u, lam in parts), sympy.zeros(parts[0][0].rows, 1))
            # sign(v)**2 = 1 while sliding, the case this formula is for
            aa, ab, bb = (tidy(_unit_signs(elimination.apply(e))) for e in ((a.T * a)[0], (a.T * b)[0], (b.T * b)[0]))
            out[f.normal] = tidy(_unit_signs((ab + sympy.sqrt(ab**2 + (1 - bb) * aa)) / (1 - bb)))
            cases[f.name] = ("coupled: the friction changes the multipliers, so N solves N = |a + b N|, a quadratic "
                             "with one non-negative root", sympy.StrictLessThan(bb, 1))
        else:
            cases[f.name] = ("coupled, with several contacts: N stays implicit in the results (N = |a + B N|) and "
                             "simulate solves it at every step", None)
    return out, cases


def _unit_signs(expr: Any) -> Any:
    """Even powers of sign(v) are 1 where v ≠ 0 (while a contact slides)."""
    return expr.replace(lambda e: e.is_Pow and isinstance(e.base, sympy.sign) and e.exp.is_even,
                          lambda e: sympy.Integer(1))


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
    allowed |= {f.term.normal for f in derivation.friction}  # coupled normal forces stay symbols
    for name, expr in {**derivation.accelerations, **derivation.multipliers}.items():
        stray = expr.free_symbols - allowed
        if stray:
            raise DerivationError(
                f"internal error: result for {name} contains undeclared symbols {sorted(map(str, stray))}"
            )
