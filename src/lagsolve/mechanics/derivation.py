"""``derive(problem) -> Derivation``: the frozen result of the whole mechanics stage.

Every step a worked solution shows is recorded here (T, V, L; each constraint's
a and b; each ∂L/∂q̇, its time derivative, ∂L/∂q; the augmented system; the
results), so reports can never disagree with the results. The raw matrix form
(``lagrange``) is kept unsimplified for numeric work; the display forms are
simplified once, in :mod:`lagsolve.mechanics.simplify`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.analysis import with_analysis
from lagsolve.mechanics.constraints import ConstraintTerms
from lagsolve.mechanics.forces import ForceTerm, FrictionTerm
from lagsolve.mechanics.hamiltonian import with_hamiltonian
from lagsolve.mechanics.lagrange import LagrangeTerms, solve_augmented
from lagsolve.mechanics.linsolve import SIZE_LIMIT
from lagsolve.mechanics.matrix_form import MatrixForm, matrix_form
from lagsolve.mechanics.model import Model
from lagsolve.mechanics.normal import NormalForce, normal_forces
from lagsolve.mechanics.reactions import Reaction
from lagsolve.mechanics.reduce import Elimination, eliminate
from lagsolve.mechanics.simplify import compound_angles, norm, tidy, tidy_sum, tidy_sum_light
from lagsolve.mechanics.stages import DEFAULT_BUDGET, StageNote, Stages, StageTimeout, cpu_limit
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class ConstraintForce:
    """Result for one constraint: the force on its particle, or at the named point of a body (``vector``,
    ``magnitude``), per-particle forces when it acts on several, and a ``note`` when no force is claimed
    (then, with no particles at all, the generalized forces of constraint λ·a, ``generalized``)."""

    name: str
    vector: tuple[Any, ...] | None
    magnitude: Any | None
    particles: tuple[tuple[str, tuple[Any, ...], Any], ...]
    note: str
    generalized: tuple[Any, ...] = ()  # λ·a per coordinate, when no physical force is known (no point named)


@dataclass(frozen=True)
class FrictionResult:
    """A friction contact (``term``, with the symbol N in its forces), the closed form of N (the
    symbol itself when only an implicit equation exists), which ``case`` applies and why, the
    condition under which that form is valid, the equation N solves (``system``), and the friction
    force and its generalized forces with the closed form put in."""

    term: FrictionTerm
    normal_force: Any
    case: str = ""
    valid_while: Any = None
    system: Any = None  # the equation N solves, Eq(N, |a + B N|)
    force: tuple[Any, ...] | None = None  # the friction force with N put in (None: as in ``term``)
    generalized: tuple[Any, ...] | None = None  # its generalized forces with N put in


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one problem (immutable; nothing to "compute first").

    Display forms (simplified): ``kinetic``, ``potential``, ``lagrangian``, ``constraints``
    (coefficients), ``momenta``, ``momenta_rates``, ``gradients``, ``generalized_forces``,
    ``equations`` (left minus right side), ``equation_sides`` and ``constrained_sides``
    (each equation as (left, right), before and after using the constraints), ``mass_matrix``
    and ``forcing`` (the matrix form), ``accelerations``, ``multipliers``,
    ``constraint_forces``. Raw forms: ``model``, ``lagrange`` (matrix form) and
    ``raw_accelerations``/``raw_multipliers`` (the augmented solve, unsimplified).
    Analysis (:mod:`lagsolve.mechanics.analysis`): ``analysis`` with every step, and the
    contract forms ``reduced``, ``conserved``, ``effective_potential`` (format section 2).

    The matrix form is always there. A later stage that ran out of its share of the budget,
    or did not apply, leaves its results ``None`` and says why in ``notes``
    (:mod:`lagsolve.mechanics.stages`).
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
    raw_accelerations: tuple[Any, ...] | None
    raw_multipliers: tuple[Any, ...] | None
    accelerations: dict[str, Any] | None
    multipliers: dict[str, Any] | None
    constraint_forces: dict[str, ConstraintForce] | None
    friction: tuple[FrictionResult, ...] = ()
    reduced: dict[str, Any] | None = None
    conserved: dict[str, Any] | None = None
    effective_potential: dict[str, Any] | None = None
    analysis: Any = None  # lagsolve.mechanics.analysis.Analysis: classification, reduction, conservation, ...
    form: MatrixForm | None = None  # the unsolved matrix form the numeric stage compiles
    mass_matrix: Any = None  # display form of M
    forcing: Any = None  # display form of F
    notes: tuple[StageNote, ...] = ()
    hamiltonian: Any = None  # lagsolve.mechanics.hamiltonian.Hamiltonian: momenta, H, Hamilton's equations, Routhian
    hamiltonian_note: str = ""  # why there is no Hamiltonian (not applicable, or its stage did not finish)

    @property
    def multiplier_symbols(self) -> tuple[Any, ...]:
        return tuple(c.multiplier for c in self.constraints)

    @property
    def complete(self) -> bool:
        """True when every stage that applies gave its result (no stage ran out of budget or size)."""
        return not any(n.kind in ("budget", "size") for n in self.notes)

    # notebook display (IPython calls these); the renderers are imported only when a result is shown

    def _repr_latex_(self) -> str:
        from lagsolve.render.display import derivation_latex

        return derivation_latex(self)

    def _repr_markdown_(self) -> str:
        from lagsolve.render.display import derivation_markdown

        return derivation_markdown(self)

    def _repr_html_(self) -> str:
        from lagsolve.render.display import derivation_html

        return derivation_html(self)


#: above this many coordinates the equation pieces get the light display simplification
LARGE_SYSTEM = 4


def derive(problem: Problem, *, budget: float | None = None, analysis: bool = True,
           on_core: Callable[[Derivation], None] | None = None) -> Derivation:
    """Derive the equations of motion, multipliers and forces of constraint of ``problem``.

    The core, the matrix form, always comes out; each later stage runs with its share of
    ``budget`` CPU seconds (default :data:`~lagsolve.mechanics.stages.DEFAULT_BUDGET`) and
    leaves a note instead of a result when it cannot finish (:class:`Derivation`). With
    ``analysis=False`` the analysis after the equations is left out. ``on_core``, when given, is
    called with the core alone (the matrix form, nothing solved or simplified) as soon as it is
    built, so that a caller can still answer if a later stage is stopped from outside.

    Raises
    ------
    DerivationError
        When the accelerations and multipliers are not determined (singular system).
    """
    stages = Stages(DEFAULT_BUDGET if budget is None else budget)
    form = matrix_form(problem, display=False)
    model, constraints, frictions = form.model, form.constraints, form.frictions
    lagrange, reactions = form.lagrange, form.reactions
    if on_core is not None:
        on_core(core(form))
    solved = stages.run("explicit solve", _solve, lagrange)
    raw_acc, raw_lam = solved if solved is not None else (None, None)
    elimination = eliminate(constraints, model)

    found: dict[str, NormalForce] = {}
    if frictions and raw_lam is None:
        stages.skip("normal forces", "needs the explicit multipliers, which were not found (see above)")
    elif frictions:
        found = stages.run("normal forces", normal_forces, frictions, raw_lam, constraints, reactions, model,
                           elimination) or {}
    else:
        stages.skip("normal forces", "no friction acts", "n/a")
    # every normal force with a closed form is substituted in the results (q̈, λ, the forces); the
    # closed form itself is given once, in the friction results. Only an implicit N stays a symbol.
    # Decoupled ones go in before display simplification (they simplify with the rest); a coupled one
    # after it, into the tidied results, which keeps them readable: λ = λ₀ + Λ N with N written out.
    substituted = {f.normal: found[f.name].value for f in frictions
                   if f.name in found and found[f.name].value is not None}
    decoupled = {N: v for N, v in substituted.items() if not any(found[f.name].valid_while is not None
                                                                 for f in frictions if f.normal == N)}
    if raw_lam is not None and raw_acc is not None:
        raw_lam = tuple(lam.xreplace(decoupled) for lam in raw_lam)
        raw_acc = tuple(a.xreplace(decoupled) for a in raw_acc)

    # a large system gets a lighter display simplification of its many equation pieces (one rewriting each)
    show_sum = tidy_sum if len(model.coordinates) <= LARGE_SYSTEM else tidy_sum_light
    shown = stages.run("display simplification", _display, form, elimination, raw_acc, raw_lam, tidy, show_sum)
    if shown is None:
        shown = _display(form, elimination, raw_acc, raw_lam, _plain, _plain)
    # the forces of constraint are found from the multipliers with a coupled N still a symbol (compact: |λ| |d|),
    # and the closed form is put in afterwards, like everywhere else
    multipliers = shown["multipliers"]
    closed: dict[Any, Any] = {}
    if len(decoupled) < len(substituted) and raw_lam is not None and raw_acc is not None:
        closed = {N: _shown_normal(v, elimination) for N, v in substituted.items() if N not in decoupled}
        raw_lam = tuple(lam.xreplace(closed) for lam in raw_lam)
        raw_acc = tuple(a.xreplace(closed) for a in raw_acc)
        for key in ("accelerations", "multipliers"):
            if shown[key] is not None:
                shown[key] = {k: v.xreplace(closed) for k, v in shown[key].items()}
    forces: dict[str, ConstraintForce] | None = None
    if not constraints:
        forces = {}
        stages.skip("forces of constraint", "there are no constraints", "n/a")
    elif multipliers is None:
        stages.skip("forces of constraint", "needs the explicit multipliers, which were not found (see above)")
    else:
        forces = stages.run("forces of constraint", lambda: {
            c.name: _closed_in(_constraint_force(reactions[c.name], multipliers[c.name], c, elimination), closed)
            for c in constraints})
    friction = tuple(_friction_result(f, found.get(f.name), substituted, elimination) for f in frictions)
    derivation = Derivation(
        problem=problem, model=model, constraints=shown["constraints"], force_terms=shown["force_terms"],
        lagrange=lagrange, elimination=elimination, raw_accelerations=raw_acc, raw_multipliers=raw_lam,
        constraint_forces=forces, friction=friction, form=form, **{k: v for k, v in shown.items()
                                                                    if k not in ("constraints", "force_terms")},
    )
    _check_free_symbols(derivation)
    if analysis:
        derivation = with_hamiltonian(with_analysis(derivation, stages), stages)
    return dataclasses.replace(derivation, notes=stages.shown())


def core(form: MatrixForm, note: str = "") -> Derivation:
    """The derivation's core alone: the matrix form with nothing solved or simplified (``note``, when
    given, says why the later stages are missing)."""
    elimination = eliminate(form.constraints, form.model)
    shown = _display(form, elimination, None, None, _plain, _plain)
    notes = (StageNote("later stages", note, "budget"),) if note else ()
    return Derivation(problem=form.problem, model=form.model, lagrange=form.lagrange, elimination=elimination,
                      raw_accelerations=None, raw_multipliers=None, constraint_forces=None, form=form,
                      notes=notes, **shown)


def _solve(lagrange: LagrangeTerms) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """The explicit accelerations and multipliers, solved from M and F with products of sines and cosines
    contracted to functions of sums (``cos(θ1 − θ2)``), which keeps the solution in textbook form."""
    contracted = dataclasses.replace(
        lagrange, mass_matrix=sympy.ImmutableMatrix(lagrange.mass_matrix.applyfunc(compound_angles)),
        forcing=sympy.ImmutableMatrix(lagrange.forcing.applyfunc(compound_angles)))
    return solve_augmented(contracted, SIZE_LIMIT)


def _plain(expr: Any) -> Any:
    """The display form when display simplification ran out of budget: the expression as derived."""
    return expr if isinstance(expr, sympy.Basic) else sympy.Integer(expr)


def _closed_in(force: ConstraintForce, closed: dict[Any, Any]) -> ConstraintForce:
    """``force`` with the closed forms of the coupled normal forces put in."""
    if not closed:
        return force

    def put(e: Any) -> Any:
        return e.xreplace(closed) if isinstance(e, sympy.Basic) else e

    return dataclasses.replace(
        force, vector=None if force.vector is None else tuple(put(v) for v in force.vector),
        magnitude=put(force.magnitude) if force.magnitude is not None else None,
        particles=tuple((p, tuple(put(v) for v in vec), put(mag)) for p, vec, mag in force.particles),
        generalized=tuple(put(v) for v in force.generalized))


def _friction_result(term: FrictionTerm, found: NormalForce | None, substituted: dict[Any, Any],
                     elimination: Elimination) -> FrictionResult:
    """The friction results of one contact: N (its closed form, or the symbol with the system it solves),
    and the friction force and its generalized forces with every closed-form N put in."""
    if found is None:
        return FrictionResult(term, term.normal)
    value = term.normal if found.value is None else _shown_normal(found.value, elimination)
    force = tuple(_shown_normal(v.xreplace(substituted), elimination) for v in term.force)
    generalized = tuple(_shown_normal(v.xreplace(substituted), elimination) for v in term.generalized)
    return FrictionResult(term, value, found.case, found.valid_while, found.system, force, generalized)


def _shown_normal(value: Any, elimination: Elimination) -> Any:
    try:
        with cpu_limit(5.0):
            return tidy(elimination.apply(value))
    except StageTimeout:
        return elimination.apply(value)


def _display(form: MatrixForm, elimination: Elimination, raw_acc: tuple[Any, ...] | None,
             raw_lam: tuple[Any, ...] | None, show: Any, show_sum: Any) -> dict[str, Any]:
    """The display forms of the derivation's steps and results (``show``/``show_sum``: :func:`tidy` and
    :func:`tidy_sum`, or the identity when display simplification ran out of budget)."""
    problem, model, constraints, lagrange = form.problem, form.model, form.constraints, form.lagrange
    eliminated_acc = _eliminated_accelerations(constraints, model, elimination)
    multipliers = None if raw_lam is None else {
        c.name: show(elimination.apply(lam)) for c, lam in zip(constraints, raw_lam, strict=True)}
    accelerations = None if raw_acc is None else {
        c.name: show(elimination.apply(a)) for c, a in zip(problem.coordinates, raw_acc, strict=True)}
    lhs = tuple(r - g for r, g in zip(lagrange.momenta_rates, lagrange.gradients, strict=True))
    rhs = tuple(q + c for q, c in zip(form.generalized_forces, lagrange.constraint_forces, strict=True))
    kinetic, potential = show_sum(model.kinetic), show_sum(model.potential)
    return {
        "kinetic": kinetic,
        "potential": potential,
        "lagrangian": kinetic - potential,
        "constraints": tuple(
            ConstraintTerms(c.name, c.kind, c.expression, c.on, tuple(show(a) for a in c.coefficients),
                            show(c.offset), show(c.acceleration_rhs), c.multiplier)
            for c in constraints),
        "force_terms": tuple(ForceTerm(t.label, tuple(show(x) for x in t.generalized)) for t in form.loads),
        "momenta": tuple(show_sum(p) for p in lagrange.momenta),
        "momenta_rates": tuple(show_sum(p) for p in lagrange.momenta_rates),
        "gradients": tuple(show_sum(g) for g in lagrange.gradients),
        "generalized_forces": tuple(show(x) for x in form.generalized_forces),
        "equations": tuple(show_sum(e) for e in lagrange.equations),
        "equation_sides": tuple((show_sum(a), show_sum(b)) for a, b in zip(lhs, rhs, strict=True)),
        "eliminated_accelerations": eliminated_acc,
        "constrained_sides": tuple(
            (show_sum(elimination.apply(a.xreplace(eliminated_acc))), show_sum(elimination.apply(b)))
            for a, b in zip(lhs, rhs, strict=True)),
        "mass_matrix": sympy.ImmutableMatrix(lagrange.mass_matrix.applyfunc(show_sum)),
        "forcing": sympy.ImmutableMatrix(lagrange.forcing.applyfunc(show_sum)),
        "accelerations": accelerations,
        "multipliers": multipliers,
    }


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
        generalized: tuple[Any, ...] = ()
        if react.generalized:
            # the generalized forces λ a: a force for a length, a torque for an angle; no magnitude mixes them
            generalized = tuple(tidy(elimination.apply(multiplier * a)) for a in terms.coefficients)
        return ConstraintForce(react.name, None, None, (), react.note, generalized)
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
    for name, expr in {**(derivation.accelerations or {}), **(derivation.multipliers or {})}.items():
        stray = expr.free_symbols - allowed
        if stray:
            raise DerivationError(
                f"internal error: result for {name} contains undeclared symbols {sorted(map(str, stray))}"
            )
