r"""Masses and inertia that cannot give equations of motion, refused before anything is solved.

Two mistakes in a problem file make the augmented system :math:`[[M, -A^T], [A, 0]]` singular,
or its answers unphysical, and are refused with a fix (exit 2) instead of a bare "singular" error:

* **a negative mass or moment of inertia**: ``mass: -m`` (parameters are positive unless declared
  otherwise, so the sign is decided by the factors' assumptions). Zero is allowed: a massless
  particle, or a thin rod's zero moment about its axis, is a fine model as long as every
  coordinate still has inertia (the next check);
* **a coordinate without inertia**: no kinetic energy depends on its velocity (its row of
  :math:`M` is zero) and no constraint involves it (its column of :math:`A` is zero), so nothing
  determines its acceleration.
"""

from __future__ import annotations

from typing import Any

from lagsolve.errors import Issue, SpecError
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.signs import sign_core
from lagsolve.problem.schema import Problem


def check_masses(problem: Problem) -> None:
    """Refuse a particle's or body's mass, or a body's principal moment, that is negative.

    Raises
    ------
    SpecError
        Naming each such field, with its line and a fix.
    """
    issues: list[Issue] = []
    fields: list[tuple[str, Any, str]] = [(f"particles.{p.name}.mass", p.mass, "mass") for p in problem.particles]
    for b in problem.bodies:
        fields.append((f"bodies.{b.name}.mass", b.mass, "mass"))
        fields += [(f"bodies.{b.name}.inertia", i, "moment of inertia") for i in b.inertia]
    for where, value, what in fields:
        if value == 0 or sign_core(value)[0] != -1:
            continue
        issues.append(Issue(problem.source, problem.lines.get(where, 0), where, f"the {what} {value} is negative",
                            f"a {what} cannot be negative: write it with positive parameters (they are positive "
                            "unless declared with positive: false)"))
    if issues:
        raise SpecError(issues)


def check_inertia(problem: Problem, coordinates: tuple[Any, ...], mass_matrix: Any,
                  constraints: tuple[ConstraintTerms, ...]) -> None:
    """Refuse a coordinate whose row of ``mass_matrix`` is zero and that no constraint involves.

    Raises
    ------
    SpecError
        Naming each such coordinate, with its line and a fix.
    """
    issues: list[Issue] = []
    for i, q in enumerate(coordinates):
        if any(not proved_zero(mass_matrix[i, k]) for k in range(len(coordinates))):
            continue
        if any(not proved_zero(c.coefficients[i]) for c in constraints):
            continue
        where = f"coordinates[{i}]"
        line = problem.lines.get(where) or problem.lines.get(f"coordinates.{q.name}", 0)
        issues.append(Issue(problem.source, line, where,
                            f"the coordinate {q.name} has no inertia: the kinetic energy does not depend on "
                            f"{q.name}_dot and no constraint involves it, so nothing determines its motion",
                            f"give it a particle or body whose position depends on {q.name}, or remove {q.name} "
                            "from coordinates"))
    if issues:
        raise SpecError(issues)
