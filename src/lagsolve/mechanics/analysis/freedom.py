"""Degrees of freedom: how many coordinates fix a configuration and how many velocities are free.

With :math:`n` coordinates, :math:`h` holonomic constraints (those given at position level and the velocity
constraints found integrable, :mod:`lagsolve.mechanics.analysis.integrability`) and :math:`k` nonholonomic ones,
a configuration needs :math:`n - h` coordinates and :math:`n - h - k` velocities are free (the number of independent
virtual displacements, Greenwood's degrees of freedom). The two differ exactly for a nonholonomic system: the
knife edge needs three coordinates (x, y, θ) but has two free velocities. A velocity constraint whose integrability
is not settled leaves the first count unknown; the second is known whatever it is.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from lagsolve.mechanics.analysis.integrability import Classification, Integrability
from lagsolve.problem.schema import ConstraintKind, Problem


@dataclass(frozen=True)
class Freedom:
    """The counts of a system: ``coordinates`` (n), ``holonomic`` and ``nonholonomic`` constraints, velocity
    constraints whose integrability is ``unresolved``; the two degrees of freedom follow from them."""

    coordinates: int
    holonomic: int
    nonholonomic: int
    unresolved: int

    @property
    def configuration(self) -> int | None:
        """How many coordinates fix a configuration (None: a velocity constraint's integrability is not settled)."""
        return None if self.unresolved else self.coordinates - self.holonomic

    @property
    def velocities(self) -> int:
        """How many velocities are free: the degrees of freedom, n less every constraint."""
        return self.coordinates - self.holonomic - self.nonholonomic - self.unresolved


def freedom(problem: Problem, classification: Iterable[Classification]) -> Freedom:
    """The degrees of freedom of ``problem`` whose velocity constraints were classified as ``classification``
    says (a velocity constraint missing from it, its stage not finished, counts as unresolved)."""
    kinds = {k.name: k.kind for k in classification}
    holonomic = nonholonomic = unresolved = 0
    for c in problem.constraints:
        kind = Integrability.HOLONOMIC if c.kind == ConstraintKind.HOLONOMIC else kinds.get(
            c.name, Integrability.UNRESOLVED)
        if kind in (Integrability.HOLONOMIC, Integrability.INTEGRABLE):
            holonomic += 1
        elif kind == Integrability.NONHOLONOMIC:
            nonholonomic += 1
        else:
            unresolved += 1
    return Freedom(len(problem.coordinates), holonomic, nonholonomic, unresolved)
