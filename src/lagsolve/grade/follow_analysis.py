"""Follow-through into the analysis steps: what a submission's own Lagrangian gives for ``effective_potential``,
``equilibria`` and ``frequencies``, with lagsolve's own analysis (:func:`~lagsolve.mechanics.analysis.equilibria.
effective_potential`, :func:`~lagsolve.mechanics.analysis.linearize.linearize`) run on the student's L in the
key's minimal coordinates (the key's elimination put in, its applied forces and cyclic coordinates kept); and
their normal forces from their multipliers (:func:`~lagsolve.mechanics.solution.normal.normal_forces`)."""

from __future__ import annotations

import contextlib
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.grade.analysis_steps import lists_of
from lagsolve.mechanics.analysis.analyse import LINEARIZE_CAP, NUMERIC_FALLBACK_CAP
from lagsolve.mechanics.analysis.conserved import MotionSystem
from lagsolve.mechanics.analysis.equilibria import effective_potential
from lagsolve.mechanics.analysis.linearize import linearize
from lagsolve.mechanics.analysis.numeric_equilibria import numeric_linearization
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.equations.lagrange import lagrange_terms
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.solution.normal import normal_forces
from lagsolve.mechanics.stages import StageSkipped, StageTimeout, cpu_limit

#: what may go wrong in lagsolve's analysis of a student's L (it is then left out: no follow-through)
FAILURES = (TypeError, ValueError, AttributeError, ZeroDivisionError, NotImplementedError, KeyError, IndexError,
            RecursionError, OverflowError, DerivationError, sympy.PolynomialError)


def own_analysis(derivation: Derivation, lagrangian: Any) -> dict[str, dict[str, Any]]:
    """The effective potential, equilibria and ω² of the student's ``lagrangian`` (key coordinates), by the route
    the key's analysis took; {} when the key has no minimal coordinates or the student's L gives nothing."""
    analysis = derivation.analysis
    if analysis is None or analysis.reduced is None or analysis.system.kind != "reduced":
        return {}
    if analysis.effective_potential is None and analysis.linearization is None:
        return {}
    with contextlib.suppress(*FAILURES):
        return _own_analysis(derivation, lagrangian)
    return {}


def _own_analysis(derivation: Derivation, lagrangian: Any) -> dict[str, dict[str, Any]]:
    analysis = derivation.analysis
    assert analysis is not None and analysis.reduced is not None
    system = analysis.system
    model = system.model
    reduced = sympy.expand(analysis.reduced.substitution.apply(lagrangian))
    student = Model(model.time, model.coordinates, model.velocities, model.accelerations, sympy.Integer(0),
                    sympy.Integer(0), reduced)
    terms = lagrange_terms(student, (), system.generalized_forces)
    mass = sympy.Matrix(terms.mass_matrix)
    if mass.det() == 0:
        return {}
    accelerations = mass.LUsolve(sympy.Matrix(terms.forcing))
    own = MotionSystem(student, system.generalized_forces, dict(zip(model.accelerations, accelerations, strict=True)),
                       kind="reduced")
    out: dict[str, dict[str, Any]] = {}
    potential, linear = None, None
    if analysis.effective_potential is not None:
        potential, _ = effective_potential(own, analysis.conservation, False)
        if potential is None:
            return {}
        out["effective_potential"] = {str(potential.coordinate): potential.expression}
    else:
        problem = derivation.problem
        values = dict(problem.simulation.values) if problem.simulation is not None else None
        simulation = problem.simulation if not problem.functions else None
        linear = _symbolic(own, analysis.conservation.cyclic, values, capped=simulation is not None)
        if linear is None and simulation is not None:
            # the key's own route when no closed form is found: numerically at the simulation values
            with contextlib.suppress(*FAILURES, StageSkipped):
                linear = numeric_linearization(own, dict(simulation.values), dict(simulation.initial))
        if linear is None:
            return {}
    points, squares = lists_of(potential, linear)
    if points:
        out["equilibria"] = {str(i + 1): p for i, p in enumerate(points)}
    if squares:
        out["frequencies"] = {str(i + 1): w for i, w in enumerate(squares)}
    return out


def _symbolic(own: MotionSystem, cyclic: tuple[Any, ...], values: dict[str, float] | None, *, capped: bool
              ) -> Any:
    """The closed-form equilibria and modes of the student's system; when ``capped`` (a numeric search can follow,
    as for the key), given up after the key's own caps (:data:`~lagsolve.mechanics.analysis.analyse.
    NUMERIC_FALLBACK_CAP` s of CPU for a general solve, :data:`~lagsolve.mechanics.analysis.analyse.LINEARIZE_CAP`
    in all)."""
    if not capped:
        return linearize(own, cyclic, False, values)[0]
    try:
        with cpu_limit(LINEARIZE_CAP):
            return linearize(own, cyclic, False, values, NUMERIC_FALLBACK_CAP)[0]
    except StageTimeout:
        return None


def own_normal_forces(derivation: Derivation, multipliers: dict[str, Any]) -> dict[str, Any]:
    """Each friction contact's N from the student's λ (lagsolve's closed forms: N = |Σ λ_j u_j|, or the coupled
    cases); {} without friction or without every multiplier."""
    form = derivation.form
    if form is None or not form.frictions or any(c.name not in multipliers for c in form.constraints):
        return {}
    with contextlib.suppress(*FAILURES):
        found = normal_forces(form.frictions, tuple(multipliers[c.name] for c in form.constraints),
                              form.constraints, form.reactions, form.model, derivation.elimination)
        return {name: n.value for name, n in found.items() if n.value is not None}
    return {}
