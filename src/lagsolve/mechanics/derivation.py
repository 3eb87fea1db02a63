"""``derive(problem) -> Derivation``: the frozen result of the whole mechanics stage.

Every step a worked solution shows is recorded here (T, V, L; each constraint's
a and b; each ∂L/∂q̇, its time derivative, ∂L/∂q; the augmented system; the
results), so reports can never disagree with the results. The raw matrix form
(``lagrange``) is kept unsimplified for numeric work; the display forms are
simplified once, in :mod:`lagsolve.mechanics.symbolic.simplify`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.analysis.analyse import analyse, contract_forms
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.elimination import Elimination, eliminate
from lagsolve.mechanics.equations.forces import ForceTerm
from lagsolve.mechanics.equations.friction import FrictionTerm
from lagsolve.mechanics.equations.lagrange import LagrangeTerms, solve_augmented
from lagsolve.mechanics.equations.matrix_form import MatrixForm, matrix_form
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.reactions import Reaction
from lagsolve.mechanics.hamiltonian import canonical_form
from lagsolve.mechanics.results import (
    Canonical,
    ConstraintForce,
    ContactForce,
    Contract,
    Derivation,
    Display,
    FrictionResult,
    Solution,
)
from lagsolve.mechanics.solution.normal import NormalForce, normal_forces
from lagsolve.mechanics.solution.sticking import Sticking, sticking
from lagsolve.mechanics.stages import DEFAULT_BUDGET, STAGES, StageNote, Stages, StageTimeout, cpu_limit
from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.linsolve import SIZE_LIMIT
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM, engine_sum
from lagsolve.mechanics.symbolic.ringsolve import too_coupled
from lagsolve.mechanics.symbolic.simplify import (
    compound_angles,
    display_forms,
    measure,
    norm,
    reproducible,
    tidy,
)
from lagsolve.problem.schema import Problem

#: above this many operations the magnitude of a contact's force is not simplified
CONTACT_LIMIT = 60

#: the note of a bulk system's display forms (more than ``n`` coordinates), which are written once each, not searched
LIGHT_FORM = ("light form, for a system of more than {n} coordinates: each expression is expanded, with sin² + cos² "
              "and products of sines and cosines contracted and common factors taken out, without the search for "
              "its shortest form")

#: up to this many coordinates and constraints q̈ and λ are given explicitly however long they are, when the bound
#: on their size lets the solve run (:mod:`~lagsolve.mechanics.symbolic.ringsolve`); whether a report prints one is
#: decided
#: there. A larger system's explicit results are given only while they are at most SIZE_LIMIT operations long
EXPLICIT_COORDINATES = 6
EXPLICIT_CONSTRAINTS = 3


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
    reproducible()  # SymPy's factorisation draws random numbers: the same problem, the same work
    stages = Stages(DEFAULT_BUDGET if budget is None else budget)
    form = matrix_form(problem, display=False)
    model, constraints, frictions = form.model, form.constraints, form.frictions
    lagrange = form.lagrange
    if on_core is not None:
        on_core(core(form))
    solved = stages.run("explicit solve", _solve, lagrange)
    raw_acc, raw_lam = solved if solved is not None else (None, None)
    elimination = eliminate(constraints, model)

    found = _normal_forces(stages, form, raw_lam, elimination)
    # every normal force with a closed form is substituted in the results (q̈, λ, the forces); the
    # closed form itself is given once, in the friction results. Only an implicit N stays a symbol.
    # Decoupled ones go in before display simplification (they simplify with the rest); a coupled one
    # after it, into the tidied results, which keeps them readable: λ = λ₀ + Λ N with N written out.
    substituted, decoupled = _substitutions(found, frictions)
    raw_acc, raw_lam = _put_in(raw_acc, raw_lam, decoupled)
    # a large system gets a lighter display simplification of its many equation pieces (one rewriting each), a bulk
    # one that rewriting by SymEngine
    _, show_sum = display_forms(len(model.coordinates))
    shown = stages.run("display simplification", _display, form, elimination, raw_acc, raw_lam, tidy, show_sum)
    if shown is None:
        shown = _display(form, elimination, raw_acc, raw_lam, _plain, _plain)
    elif len(model.coordinates) > BULK_SYSTEM:
        stages.notes.append(StageNote("display simplification", LIGHT_FORM.format(n=BULK_SYSTEM), "size"))
    display, accelerations, multipliers = shown
    # the forces of constraint are found from the multipliers with a coupled N still a symbol (compact: |λ| |d|),
    # and the closed form is put in afterwards, like everywhere else
    closed = {N: _shown_normal(v, elimination) for N, v in substituted.items() if N not in decoupled}
    if raw_lam is None or raw_acc is None:
        closed = {}
    forces = _forces_of_constraint(stages, form, multipliers, elimination, closed)
    if closed:
        raw_acc, raw_lam = _put_in(raw_acc, raw_lam, closed)
        accelerations, multipliers = _closed_in_results(accelerations, closed), _closed_in_results(multipliers, closed)
    solution = Solution(raw_acc, raw_lam, accelerations, multipliers, forces)
    friction = tuple(_friction_result(f, found.get(f.name), substituted, elimination) for f in frictions)
    friction = _contacts(stages, form, friction, forces, decoupled, elimination, raw_lam)
    _check_free_symbols(form, display, solution, friction)
    studied = analyse(form, solution, friction, stages) if analysis else None
    contract = Contract(**contract_forms(studied)) if studied is not None else Contract()
    canonical = canonical_form(studied, problem, stages) if studied is not None else Canonical()
    return Derivation(form=form, elimination=elimination, display=display, solution=solution, friction=friction,
                      analysis=studied, contract=contract, canonical=canonical, notes=stages.shown())


def _closed_in_results(values: dict[str, Any] | None, closed: dict[Any, Any]) -> dict[str, Any] | None:
    """Display results (accelerations or multipliers by name) with the coupled normal forces' closed forms put in."""
    return None if values is None else {k: v.xreplace(closed) for k, v in values.items()}


def _substitutions(found: dict[str, NormalForce], frictions: tuple[FrictionTerm, ...]) -> tuple[dict[Any, Any],
                                                                                         dict[Any, Any]]:
    """Each normal force N with a closed form → that form; and those of them that hold without a condition
    (decoupled: a coupled one is valid only while its contact holds)."""
    substituted = {f.normal: found[f.name].value for f in frictions
                   if f.name in found and found[f.name].value is not None}
    decoupled = {N: v for N, v in substituted.items() if not any(found[f.name].valid_while is not None
                                                                 for f in frictions if f.normal == N)}
    return substituted, decoupled


def _put_in(raw_acc: Any, raw_lam: Any, values: dict[Any, Any]) -> tuple[Any, Any]:
    """The raw accelerations and multipliers with ``values`` put in (both None when not solved)."""
    if raw_lam is None or raw_acc is None:
        return raw_acc, raw_lam
    return tuple(a.xreplace(values) for a in raw_acc), tuple(lam.xreplace(values) for lam in raw_lam)


def _normal_forces(stages: Stages, form: MatrixForm, raw_lam: Any,
                   elimination: Elimination) -> dict[str, NormalForce]:
    """The normal forces of the friction contacts in closed form (the stage), by contact name."""
    if form.frictions and raw_lam is None:
        stages.skip("normal forces", "needs the explicit multipliers, which were not found (see above)")
        return {}
    if not form.frictions:
        stages.skip("normal forces", "no friction acts", "n/a")
        return {}
    return stages.run("normal forces", normal_forces, form.frictions, raw_lam, form.constraints, form.reactions,
                      form.model, elimination) or {}


def _forces_of_constraint(stages: Stages, form: MatrixForm, multipliers: Any, elimination: Elimination,
                          closed: dict[Any, Any]) -> dict[str, ConstraintForce] | None:
    """The force of each constraint from its multiplier (the stage); None when the multipliers are not known."""
    constraints, reactions = form.constraints, form.reactions
    if not constraints:
        stages.skip("forces of constraint", "there are no constraints", "n/a")
        return {}
    if multipliers is None:
        stages.skip("forces of constraint", "needs the explicit multipliers, which were not found (see above)")
        return None
    return stages.run("forces of constraint", lambda: {
        c.name: _closed_in(_constraint_force(reactions[c.name], multipliers[c.name], c, elimination), closed)
        for c in constraints})


def _contacts(stages: Stages, form: MatrixForm, friction: tuple[FrictionResult, ...],
              forces: dict[str, ConstraintForce] | None, decoupled: dict[Any, Any], elimination: Elimination,
              raw_lam: Any) -> tuple[FrictionResult, ...]:
    """The friction results with their contact forces and whether each contact holds (the stages)."""
    frictions = form.frictions
    if not frictions:
        stages.skip("contact forces", "no friction acts", "n/a")
    elif forces is None:
        stages.skip("contact forces", "needs the forces of constraint, which were not found (see above)")
    else:
        known = forces
        friction = stages.run("contact forces", lambda: tuple(_contact_forces(r, known) for r in friction)) or friction
    friction = _held(form, friction, decoupled, elimination, stages) if frictions and raw_lam is not None else friction
    if not frictions:
        stages.skip("sticking", "no friction acts", "n/a")
    elif raw_lam is None:
        stages.skip("sticking", "needs the explicit multipliers, which were not found (see above)")
    return friction


def core(form: MatrixForm, note: str = "", *, analysis: bool = True) -> Derivation:
    """The derivation's core alone: the matrix form with nothing solved or simplified. ``note``, when
    given, says why the later stages are missing: each stage that would have run (:func:`later_stages`)
    gets a note of its own with that reason, so every missing part is named."""
    elimination = eliminate(form.constraints, form.model)
    display, _, _ = _display(form, elimination, None, None, _plain, _plain)
    notes = tuple(StageNote(stage, note, "budget") for stage in later_stages(form, analysis=analysis)) if note else ()
    return Derivation(form=form, elimination=elimination, display=display, notes=notes)


def later_stages(form: MatrixForm, *, analysis: bool = True) -> tuple[str, ...]:
    """The stages (:data:`~lagsolve.mechanics.stages.STAGES`, in order) a derivation of ``form`` runs after its
    core, leaving out those with nothing to do: normal and contact forces without friction, forces of constraint and the
    constraints' classification and minimal coordinates without constraints, the effective potential with
    friction, and numeric equilibria (a fallback, run only when the symbolic ones do not finish)."""
    absent = {"numeric equilibria"}
    if not form.frictions:
        absent |= {"normal forces", "contact forces", "sticking"}
    else:
        absent |= {"effective potential", "steady motions"}
    if not form.constraints:
        absent |= {"forces of constraint", "constraint classification", "minimal coordinates"}
    if not analysis:
        absent |= {"constraint classification", "minimal coordinates", "conserved quantities", "effective potential",
                   "equilibria and normal modes", "hamiltonian", "symmetries", "steady motions"}
    return tuple(stage for stage in STAGES if stage not in absent)


def _solve(lagrange: LagrangeTerms) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """The explicit accelerations and multipliers, solved from M and F with products of sines and cosines
    contracted to functions of sums (``cos(θ1 − θ2)``), which keeps the solution in textbook form. A system
    whose unknowns are coupled in a block too large to solve explicitly is declined first, from its pattern."""
    too_coupled(lagrange.mass_matrix, lagrange.constraint_jacobian)
    contracted = dataclasses.replace(
        lagrange, mass_matrix=sympy.ImmutableMatrix(lagrange.mass_matrix.applyfunc(compound_angles)),
        forcing=sympy.ImmutableMatrix(lagrange.forcing.applyfunc(compound_angles)))
    n, m = lagrange.constraint_jacobian.cols, lagrange.constraint_jacobian.rows
    explicit = n <= EXPLICIT_COORDINATES and m <= EXPLICIT_CONSTRAINTS
    return solve_augmented(contracted, None if explicit else SIZE_LIMIT)


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


def _held(form: MatrixForm, friction: tuple[FrictionResult, ...], known: dict[Any, Any], elimination: Elimination,
          stages: Stages) -> tuple[FrictionResult, ...]:
    """Each contact that slides along one line, held (:mod:`lagsolve.mechanics.solution.sticking`): the force that
    holds it
    and the least static coefficient that can."""
    def all_held() -> tuple[FrictionResult, ...]:
        out = []
        for result in friction:
            if result.term.rate is None:
                out.append(result)
                continue
            found = sticking(form, result.term, known, elimination)
            out.append(dataclasses.replace(result, sticking=found) if isinstance(found, Sticking)
                       else dataclasses.replace(result, sticking_note=found))
        return tuple(out)

    return stages.run("sticking", all_held) or friction


def _contact_forces(result: FrictionResult, forces: dict[str, ConstraintForce]) -> FrictionResult:
    """``result`` with the force of the contact on each member: on the one that slides, the combined force of the
    normal constraints plus the friction force; on the one carrying the surface, the opposite."""
    term = result.term
    if result.force is None:
        return result
    parts = [vec for c in term.constraints for p, vec, _ in forces[c].particles if p == term.particle]
    if len(parts) != len(term.constraints):
        return result

    def shown(expr: Any) -> Any:  # a large sum (a coupled normal force written out) stays as it is
        return tidy(expr) if ops(expr) <= CONTACT_LIMIT else expr

    normal = parts[0] if len(parts) == 1 else tuple(shown(sum(c, sympy.Integer(0))) for c in zip(*parts, strict=True))
    friction = tuple(result.force)
    total = tuple(shown(a + b) for a, b in zip(normal, friction, strict=True))
    # the normal part has length N and the friction, orthogonal to it, μ N while it slides
    magnitude = shown(result.normal_force * sympy.sqrt(1 + term.coefficient**2))
    members = [ContactForce(term.particle, normal, friction, total, magnitude)]
    if term.against is not None:
        members.append(ContactForce(term.against, tuple(-c for c in normal), tuple(-c for c in friction),
                                    tuple(-c for c in total), magnitude))
    return dataclasses.replace(result, members=tuple(members))


def _shown_normal(value: Any, elimination: Elimination) -> Any:
    try:
        with cpu_limit(5.0):
            return tidy(elimination.apply(value))
    except StageTimeout:
        return elimination.apply(value)


def _display(form: MatrixForm, elimination: Elimination, raw_acc: tuple[Any, ...] | None,
             raw_lam: tuple[Any, ...] | None, show: Any, show_sum: Any) -> tuple[Display, dict[str, Any] | None,
                                                                             dict[str, Any] | None]:
    """The display forms of the derivation's steps, and of its accelerations and multipliers by name (None when not
    solved); ``show``/``show_sum`` are :func:`tidy` and :func:`tidy_sum`, or the identity when display simplification
    ran out of budget."""
    problem, model, constraints, lagrange = form.problem, form.model, form.constraints, form.lagrange
    eliminated_acc = _eliminated_accelerations(constraints, model, elimination)
    multipliers = None if raw_lam is None else {
        c.name: show(elimination.apply(lam)) for c, lam in zip(constraints, raw_lam, strict=True)}
    accelerations = None if raw_acc is None else {
        c.name: show(elimination.apply(a)) for c, a in zip(problem.coordinates, raw_acc, strict=True)}
    if len(model.coordinates) > BULK_SYSTEM:  # added by SymEngine, whose forms of the pieces are kept
        lhs = tuple(engine_sum(((1, r), (-1, g))) for r, g in zip(lagrange.momenta_rates, lagrange.gradients,
                                                                   strict=True))
    else:
        lhs = tuple(r - g for r, g in zip(lagrange.momenta_rates, lagrange.gradients, strict=True))
    rhs = tuple(q + c for q, c in zip(form.generalized_forces, lagrange.constraint_forces, strict=True))
    kinetic, potential = show_sum(model.kinetic), show_sum(model.potential)
    display = Display(
        kinetic=kinetic,
        potential=potential,
        lagrangian=kinetic - potential,
        constraints=tuple(
            ConstraintTerms(c.name, c.kind, c.expression, c.on, tuple(show(a) for a in c.coefficients),
                            show(c.offset), show(c.acceleration_rhs), c.multiplier)
            for c in constraints),
        force_terms=tuple(ForceTerm(t.label, tuple(show(x) for x in t.generalized)) for t in form.loads),
        momenta=tuple(show_sum(p) for p in lagrange.momenta),
        momenta_rates=tuple(show_sum(p) for p in lagrange.momenta_rates),
        gradients=tuple(show_sum(g) for g in lagrange.gradients),
        generalized_forces=tuple(show(x) for x in form.generalized_forces),
        equations=tuple(show_sum(e) for e in lagrange.equations),
        equation_sides=tuple((show_sum(a), show_sum(b)) for a, b in zip(lhs, rhs, strict=True)),
        eliminated_accelerations=eliminated_acc,
        constrained_sides=tuple(
            (show_sum(elimination.apply(a.xreplace(eliminated_acc))), show_sum(elimination.apply(b)))
            for a, b in zip(lhs, rhs, strict=True)),
        mass_matrix=sympy.ImmutableMatrix(lagrange.mass_matrix.applyfunc(show_sum)),
        forcing=sympy.ImmutableMatrix(lagrange.forcing.applyfunc(show_sum)),
    )
    return display, accelerations, multipliers


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
    sizes = [m for _, _, m in per_particle]
    # the same size written two ways (one side's direction simplified further) is still one size
    common = min(sizes, key=measure) if all(proved_zero(m - sizes[0]) for m in sizes[1:]) else None
    return ConstraintForce(react.name, None, common, tuple(per_particle), react.note)


def _check_free_symbols(form: MatrixForm, display: Display, solution: Solution,
                        friction: tuple[FrictionResult, ...]) -> None:
    """Every symbol in a result must be declared (style rule 5): a cheap guard against slips."""
    allowed = set(form.problem.symbols.values()) | {c.multiplier for c in display.constraints}
    allowed |= set(form.model.accelerations)
    allowed |= {f.term.normal for f in friction}  # coupled normal forces stay symbols
    for name, expr in {**(solution.accelerations or {}), **(solution.multipliers or {})}.items():
        stray = expr.free_symbols - allowed
        if stray:
            raise DerivationError(
                f"internal error: result for {name} contains undeclared symbols {sorted(map(str, stray))}"
            )
