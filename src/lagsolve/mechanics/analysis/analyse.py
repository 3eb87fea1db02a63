"""After the equations: what kind of constraints, how many degrees of freedom, what is conserved,
what the motion looks like near equilibrium.

:func:`analyse` runs, in order,

1. :mod:`~lagsolve.mechanics.analysis.integrability` — each velocity constraint integrable
   (integrated, :math:`\\theta = \\theta_0`) or truly nonholonomic (Frobenius);
2. :mod:`~lagsolve.mechanics.analysis.minimal` — the reduced Lagrangian in minimal coordinates and
   its equations, checked against the multiplier route;
3. :mod:`~lagsolve.mechanics.analysis.conserved` — cyclic momenta and the Jacobi integral of the
   reduced system (or of the full one with its constraints when no reduction exists),
   each verified along the equations;
4. :mod:`~lagsolve.mechanics.analysis.symmetry` — the momenta of the translations and rotations of the
   whole system that leave T, V and the constraints invariant (Noether), each verified;
5. :mod:`~lagsolve.mechanics.analysis.equilibria` — with one degree of freedom left after the cyclic
   ones, the effective potential, its equilibria, stability and frequencies;
6. :mod:`~lagsolve.mechanics.analysis.steady` — with cyclic coordinates too, the steady motions about it
   (the heavy top's steady precession), their stability and the frequency of small oscillations;
7. :mod:`~lagsolve.mechanics.analysis.linearize` — with several left, equilibria and normal modes.

:func:`lagsolve.mechanics.derivation.derive` builds the analysis part of a derivation
(:class:`~lagsolve.mechanics.analysis.results.Analysis`) with :func:`analyse`, and its
:class:`~lagsolve.mechanics.results.Contract` part (``reduced``, ``conserved`` and ``effective_potential``,
format section 2, SymPy expressions) with :func:`contract_forms`.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.analysis.conserved import Conservation, MotionSystem, conserved_quantities
from lagsolve.mechanics.analysis.contact import ContactCheck, check_point
from lagsolve.mechanics.analysis.equilibria import EffectivePotential, effective_potential
from lagsolve.mechanics.analysis.freedom import freedom
from lagsolve.mechanics.analysis.integrability import classify_all
from lagsolve.mechanics.analysis.linearize import Linearization, applies, linearize
from lagsolve.mechanics.analysis.minimal import ReducedSystem, reduce_system
from lagsolve.mechanics.analysis.minimal_chart import MinimalChart, minimal_chart
from lagsolve.mechanics.analysis.numeric_equilibria import NUMERIC_SEARCH, complete_numerically, numeric_linearization
from lagsolve.mechanics.analysis.results import Analysis
from lagsolve.mechanics.analysis.steady import SteadyMotion, steady_motions
from lagsolve.mechanics.analysis.symmetry import symmetries
from lagsolve.mechanics.equations.surface import constraint_surface
from lagsolve.mechanics.stages import Stages
from lagsolve.problem.names import momentum_name

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.matrix_form import MatrixForm
    from lagsolve.mechanics.results import FrictionResult, Solution


#: CPU seconds the general symbolic solve of the equilibria may take, when the cheap search found none and numeric
#: equilibria can be given instead: a coupled trigonometric system it does not finish would hold the whole
#: derivation up (two pendulums on torsion springs)
NUMERIC_FALLBACK_CAP = 2.0
#: CPU seconds the whole stage (solve and modes) may take then: the slowest shipped problem, the two pendulums
#: joined by a spring, takes about 1 s here (0.5 s of it the capped general solve); the cap leaves six times that,
#: since a slower or busier machine must give the same report (a 2 s cap on the whole was once exceeded on CI).
#: ``bench/margins.py`` shows every stage's use against its slice.
LINEARIZE_CAP = 6.0


def analyse(form: MatrixForm, solution: Solution, friction_results: tuple[FrictionResult, ...] = (),
            stages: Stages | None = None) -> Analysis:
    """The analysis of a derivation's matrix form, explicit solve and friction results (see the module docstring),
    each part a stage of ``stages`` (a fresh budget when None): a part that runs out of its share, or does not
    apply, says why in its note."""
    stages = stages if stages is not None else Stages()
    problem = form.problem
    normals = _kept_normals(solution, friction_results)
    classes, reduced, reduced_note = _classify_and_reduce(stages, form, solution, normals)
    system = _motion_system(form, solution, reduced, normals)
    friction = bool(problem.friction)
    conservation = _conservation(stages, problem, system, reduced, friction)
    effective, effective_note = _effective(stages, system, conservation, friction)
    steady, steady_note = _steady(stages, system, effective)
    linear, linear_note = _linear(stages, problem, system, conservation, effective, friction)
    effective_contact, modes_contact = _contact(form, solution, reduced, effective, linear)
    return Analysis(classes, reduced, reduced_note, system, conservation, effective, effective_note,
                    linear, linear_note, effective_contact, modes_contact, steady, steady_note,
                    freedom(problem, classes))


def _kept_normals(solution: Solution, friction_results: tuple[FrictionResult, ...]) -> dict[Any, Any]:
    """The normal forces of friction to put in: a normal force the multiplier route keeps as a symbol N
    (coupled friction) stays a symbol here too, the others are replaced by their expression."""
    raw = solution.raw_accelerations
    return {f.term.normal: f.normal_force for f in friction_results
            if raw is not None and not any(a.has(f.term.normal) for a in raw)}


def _classify_and_reduce(stages: Stages, form: MatrixForm, solution: Solution,
                         normals: dict[Any, Any]) -> tuple[tuple[Any, ...], ReducedSystem | None, str]:
    """The constraint classes (stage ``constraint classification``) and the system in minimal coordinates
    (stage ``minimal coordinates``), or why there is none: no classes means no reduction is tried."""
    problem, model, constraints = form.problem, form.model, form.constraints
    taken = set(problem.symbols) | {f.name for f in problem.functions} | {momentum_name(c.symbol)
                                                                          for c in problem.coordinates}
    classes = stages.run("constraint classification", classify_all, constraints, model, problem.constraints, taken)
    if classes is None:
        note = _stage_reason(stages, "constraint classification")
        stages.skip("minimal coordinates", "needs the constraint classification, which did not finish")
        return (), None, note
    found = stages.run("minimal coordinates", reduce_system, model, constraints, classes,
                       form.lagrange.generalized_forces, normals, solution.raw_accelerations,
                       problem.independent)
    reduced, reduced_note = found if found is not None else (None, _stage_reason(stages, "minimal coordinates"))
    return classes, reduced, reduced_note


def _motion_system(form: MatrixForm, solution: Solution, reduced: ReducedSystem | None,
                   normals: dict[Any, Any]) -> MotionSystem:
    """The system the rest of the analysis studies: the reduced one when minimal coordinates exist, else the
    full one with its constraints (and the raw accelerations, when the derivation solved for them)."""
    if reduced is not None:
        return MotionSystem(reduced.model, reduced.generalized_forces, reduced.acceleration_map(), kind="reduced")
    model, raw, constraints = form.model, solution.raw_accelerations, form.constraints
    forces = tuple(f.xreplace(normals) for f in form.lagrange.generalized_forces)
    accelerations = dict(zip(model.accelerations, raw, strict=True)) if raw is not None else {}
    return MotionSystem(model, forces, accelerations, constraints, constraint_surface(constraints, model),
                        kind="full")


def _conservation(stages: Stages, problem: Any, system: MotionSystem, reduced: ReducedSystem | None,
                  friction: bool) -> Conservation:
    """The conserved quantities (stage ``conserved quantities``) with the symmetries' momenta, or none and why."""
    conservation = stages.run("conserved quantities", conserved_quantities, system, friction=friction)
    if conservation is None:
        return Conservation((), (), (_stage_reason(stages, "conserved quantities"),))
    return _with_symmetries(stages, problem, system, conservation, reduced)


def _effective(stages: Stages, system: MotionSystem, conservation: Conservation,
               friction: bool) -> tuple[EffectivePotential | None, str]:
    """The effective potential (stage ``effective potential``), or why none: Coulomb friction rules it out."""
    if friction:
        stages.skip("effective potential", "Coulomb friction acts: equilibria are not isolated points", "n/a")
        return None, "Coulomb friction acts"
    found = stages.run("effective potential", effective_potential, system, conservation, friction)
    return found if found is not None else (None, _stage_reason(stages, "effective potential"))


def _linear(stages: Stages, problem: Any, system: MotionSystem, conservation: Conservation,
            effective: EffectivePotential | None, friction: bool) -> tuple[Linearization | None, str]:
    """The equilibria and normal modes (stage ``equilibria and normal modes``) when no effective potential
    covers the system and linearizing applies, or why none."""
    if effective is not None:
        stages.skip("equilibria and normal modes", "the effective potential covers this system", "n/a")
        return None, "the effective potential covers this system"
    why_not = applies(system, conservation.cyclic, friction)
    if why_not:
        stages.skip("equilibria and normal modes", why_not, "n/a")
        return None, why_not
    values = dict(problem.simulation.values) if problem.simulation is not None else None
    # with numbers to fall back on, a symbolic solve that has not finished in a few seconds will not help
    fallback = values is not None and not problem.functions
    found = stages.run("equilibria and normal modes", linearize, system, conservation.cyclic, friction, values,
                       NUMERIC_FALLBACK_CAP if fallback else None, cap=LINEARIZE_CAP if fallback else None,
                       instead="numeric equilibria at the simulation values are given instead")
    linear, linear_note = found if found is not None else (None, _stage_reason(stages, "equilibria and normal modes"))
    if problem.simulation is None or problem.functions:
        return linear, linear_note
    return _numeric_equilibria(stages, problem.simulation, system, linear, linear_note)


def _numeric_equilibria(stages: Stages, spec: Any, system: MotionSystem, linear: Linearization | None,
                        linear_note: str) -> tuple[Linearization | None, str]:
    """With simulation values: the equilibria found numerically (stage ``numeric equilibria``) when the
    symbolic solve gave none, or the closed-form ones completed by those it may have missed."""
    if linear is None:
        numeric = stages.run("numeric equilibria", numeric_linearization, system, dict(spec.values),
                             dict(spec.initial))
        if numeric is not None:  # the report says why the equilibria are numeric only
            search = f"No equilibrium in closed form ({linear_note}); {NUMERIC_SEARCH} found these"
            return dataclasses.replace(numeric, search=search), f"numeric: {linear_note}"
        linear_note += f"; {_stage_reason(stages, 'numeric equilibria')}"
        stages.settle("numeric equilibria")  # the analysis section says it
        return None, linear_note
    if not linear.complete:
        # closed-form equilibria that may not be all: the others are looked for numerically
        completed = stages.run("numeric equilibria", complete_numerically, linear, system, dict(spec.values),
                               dict(spec.initial))
        linear = completed if completed is not None else linear
    return linear, linear_note


def _with_symmetries(stages: Stages, problem: Any, system: MotionSystem, conservation: Conservation,
                     reduced: ReducedSystem | None) -> Conservation:
    """``conservation`` with the momenta of the system's translations and rotations (stage ``symmetries``)."""
    if not problem.particles and not problem.bodies:
        stages.skip("symmetries", "no particle or body positions to move", "n/a")
        return conservation
    found = stages.run("symmetries", symmetries, problem, system, conservation,
                       reduced.substitution if reduced is not None else None)
    return found if found is not None else conservation


def _steady(stages: Stages, system: MotionSystem, effective: EffectivePotential | None) -> tuple[SteadyMotion | None,
                                                                                                   str]:
    """The steady motions about the effective potential's coordinate (stage ``steady motions``), or why none."""
    if effective is None:
        stages.skip("steady motions", "needs the effective potential", "n/a")
        return None, "needs the effective potential"
    if not effective.cyclic:
        reason = "no coordinate is cyclic: the equilibria of the effective potential are states of rest"
        stages.skip("steady motions", reason, "n/a")
        return None, reason
    found = stages.run("steady motions", steady_motions, system, effective)
    return found if found is not None else (None, _stage_reason(stages, "steady motions"))


def _contact(form: MatrixForm, solution: Solution, reduced: ReducedSystem | None,
             effective: EffectivePotential | None,
             linear: Linearization | None) -> tuple[tuple[tuple[ContactCheck, ...], ...], ...]:
    """Each equilibrium's unilateral constraint forces at rest (:mod:`lagsolve.mechanics.analysis.contact`)."""
    unilateral = tuple(c.name for c in form.problem.constraints if c.unilateral)
    multipliers = solution.multipliers
    if not unilateral or multipliers is None:
        return (), ()
    substitution = reduced.substitution if reduced is not None else None
    velocities = dict.fromkeys(form.model.velocities, sympy.Integer(0))
    if reduced is not None:
        velocities.update(dict.fromkeys(reduced.model.velocities, sympy.Integer(0)))
    effective_checks: list[tuple[ContactCheck, ...]] = []
    equilibria = effective.equilibria if effective is not None else ()
    for e in equilibria:
        assert effective is not None
        if e.value is None:
            effective_checks.append(())
            continue
        rates = {q: v for model in (form.model, *((reduced.model,) if reduced is not None else ()))
                 for q, v in zip(model.coordinates, model.velocities, strict=True)}
        moving = {rates[c]: w for c, _, w in effective.cyclic if c in rates}
        effective_checks.append(check_point(multipliers, unilateral, {effective.coordinate: e.value},
                                            {**velocities, **moving}, substitution))
    modes_checks = [check_point(multipliers, unilateral, dict(m.point), velocities, substitution)
                    for m in (linear.modes if linear is not None else ())]
    return tuple(effective_checks), tuple(modes_checks)


def _stage_reason(stages: Stages, stage: str) -> str:
    note = stages.note_for(stage)
    return note.reason if note is not None else "did not finish"


def contract_forms(analysis: Analysis) -> dict[str, Any]:
    r"""``reduced``, ``conserved`` and ``effective_potential`` shaped as format section 2 says
    (expressions left as SymPy objects; a condition ``Eq`` where a value has no closed form).

    Only the input's names appear: a constant of integration is written back as the integral
    it stands for (:math:`\theta_0 \to \theta`, :math:`\phi_0 \to \phi - \Omega t`), which has that
    value along every motion.
    """
    back = {k.constant: k.integral for k in analysis.classification if k.constant is not None}
    reduced = None
    if analysis.reduced is not None:
        reduced = {"independent": list(analysis.reduced.names),
                   "accelerations": {q: a.xreplace(back) for q, a in analysis.reduced.accelerations.items()}}
    conserved = {c.name: c.expression.xreplace(back) for c in analysis.conservation.quantities}
    effective = None
    v = analysis.effective_potential
    if v is not None:
        effective = {
            "coordinate": v.coordinate.name,
            "expression": v.expression.xreplace(back),
            "equilibria": [{"value": (e.value if e.value is not None else e.condition).xreplace(back),
                            "stable": e.stable,
                            "frequency": e.frequency.xreplace(back) if e.frequency is not None else None}
                           for e in v.equilibria],
        }
    return {"reduced": reduced, "conserved": conserved, "effective_potential": effective}


def monitored(form: MatrixForm, budget: float = 30.0) -> tuple[dict[str, Any], MinimalChart | None, str, str]:
    """What a simulation needs from the analysis, decided cheaply from the matrix form: the conserved
    quantities to monitor (by the same criteria :func:`analyse` uses, without verifying them along
    explicit accelerations) and the chart of minimal coordinates (or the reason there is none).
    Nothing is solved or simplified for display, so a simulation never waits for symbolic analysis.
    The last item says why the energy is not conserved ("" when it is)."""
    stages = Stages(budget)
    problem, model, constraints = form.problem, form.model, form.constraints
    taken = set(problem.symbols) | {f.name for f in problem.functions} | {momentum_name(c.symbol)
                                                                          for c in problem.coordinates}
    classes = stages.run("constraint classification", classify_all, constraints, model, problem.constraints, taken)
    reduced, note = None, "the constraint classification did not finish"
    if classes is not None:
        found = stages.run("minimal coordinates", reduce_system, model, constraints, classes,
                           form.generalized_forces, {}, None, problem.independent, solve=False)
        reduced, note = found if found is not None else (None, _stage_reason(stages, "minimal coordinates"))
    if reduced is not None:
        system = MotionSystem(reduced.model, reduced.generalized_forces, {}, kind="reduced")
    else:
        system = MotionSystem(model, form.generalized_forces, {}, constraints, constraint_surface(constraints, model),
                              kind="full")
    conservation = stages.run("conserved quantities", conserved_quantities, system, friction=bool(problem.friction))
    if conservation is None:
        conservation = Conservation((), (), ())
    else:
        conservation = _with_symmetries(stages, problem, system, conservation, reduced)
    analysis = Analysis(classes or (), reduced, note, system, conservation, None, "", None, "")
    chart, chart_note = minimal_chart(analysis, model)
    return contract_forms(analysis)["conserved"], chart, chart_note, conservation.energy.reason()
