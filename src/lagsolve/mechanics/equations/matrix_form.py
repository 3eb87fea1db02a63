"""The equations of motion in matrix form, without solving or simplifying them.

``matrix_form(problem)`` is the cheap first half of a derivation: energies,
constraint coefficients, generalized forces (friction with its normal force left
as the symbol ``N_<contact>``), Lagrange's equations as ``M q̈ = F + Aᵀλ`` with
``A q̈ = β``, and the direction of each force of constraint per unit multiplier.
It is all the numeric stage needs, so ``simulate`` never waits for the symbolic
solve and the display simplification, which grow quickly with the size of a system.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.equations.constraints import ConstraintTerms, constraint_terms
from lagsolve.mechanics.equations.elimination import eliminate
from lagsolve.mechanics.equations.forces import ForceTerm, force_terms
from lagsolve.mechanics.equations.friction import FrictionTerm, friction_term
from lagsolve.mechanics.equations.inertia import check_inertia, check_masses
from lagsolve.mechanics.equations.lagrange import LagrangeTerms, lagrange_terms
from lagsolve.mechanics.equations.model import Model, build_model
from lagsolve.mechanics.equations.reactions import Reaction, reaction
from lagsolve.mechanics.equations.regularity import check_constraints
from lagsolve.mechanics.equations.surface import Surface
from lagsolve.mechanics.units.unit_system import check_units
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class MatrixForm:
    """Everything up to (not including) solving for the accelerations.

    ``generalized_forces`` are the total :math:`Q_i` (loads and friction, N symbolic);
    ``reactions`` map each constraint to the direction of its force per unit λ.
    """

    problem: Problem
    model: Model
    constraints: tuple[ConstraintTerms, ...]
    loads: tuple[ForceTerm, ...]
    frictions: tuple[FrictionTerm, ...]
    generalized_forces: tuple[Any, ...]
    lagrange: LagrangeTerms
    reactions: dict[str, Reaction]


def matrix_form(problem: Problem, *, display: bool = True) -> MatrixForm:
    """Build the matrix form of ``problem``'s equations of motion (no solve, no display simplification).

    The derivatives are taken with SymEngine (see :func:`~lagsolve.mechanics.equations.lagrange.lagrange_terms`); the
    reports show them through the display simplification, which writes them as it would SymPy's.
    ``display=False`` is the core of a derivation and what the numeric stage compiles: the energies are
    tidied only when they are small. The equations are the same; only their written shape differs.
    """
    check_units(problem)  # with units: wrong dimensions and mixed scales refused before anything is derived
    check_masses(problem)  # negative masses: refused with a fix
    model = build_model(problem, tidy=True if display else None)
    constraints = tuple(constraint_terms(c, model) for c in problem.constraints)
    check_constraints(problem, model, constraints)  # degenerate or redundant ones: refused with a fix
    loads = force_terms(problem, model)
    # a force is claimed where it matches λ·a on the constraint surface, which is all the motion sees
    zero = Surface(constraints, model, eliminate(constraints, model)).is_zero
    reactions = {c.name: reaction(problem, model, c, zero) for c in constraints}
    frictions = tuple(friction_term(f, problem, model, reactions, zero) for f in problem.friction)
    n = len(model.coordinates)
    terms: tuple[ForceTerm | FrictionTerm, ...] = (*loads, *frictions)
    q_forces = tuple(sum((t.generalized[i] for t in terms), sympy.Integer(0)) for i in range(n))
    lagrange = lagrange_terms(model, constraints, q_forces, engine="symengine")
    check_inertia(problem, model.coordinates, lagrange.mass_matrix, constraints)  # undetermined coordinates
    return MatrixForm(problem, model, constraints, loads, frictions, q_forces, lagrange, reactions)
