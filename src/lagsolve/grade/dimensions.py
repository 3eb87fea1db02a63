"""The mistake ``wrong_dimension`` (when the key has units): a student's answer whose dimension differs from the
key's, or a sum whose terms are not all of one dimension, found with the project's unit algebra
(:func:`lagsolve.mechanics.units.dimensions.algebra`: the key's declared units of its parameters, coordinates
and functions; a symbol without a unit, a multiplier or a momentum, makes a dimension unknown, never wrong)."""

from __future__ import annotations

import contextlib
from typing import Any

from lagsolve.mechanics.units.dimensions import UnitAlgebra, _Mismatch, algebra, describe, dimension
from lagsolve.problem.schema import Problem

#: the evidence of a sum whose terms have different dimensions starts so
INHOMOGENEOUS = "its terms do not all have one dimension"


class Dimensions:
    """The dimensions of answers in the key's symbols; inert for a key without units."""

    def __init__(self, problem: Problem) -> None:
        declared = any(p.unit is not None for p in problem.parameters) or any(
            q.unit is not None for q in problem.coordinates)
        self.units: UnitAlgebra | None = algebra(problem) if declared else None

    def unit(self, expr: Any) -> Any:
        """The unit of ``expr``, None when unknown; raises ``_Mismatch`` for an inhomogeneous sum."""
        assert self.units is not None
        return self.units.of(expr)

    def differs(self, value: Any, reference: Any) -> str:
        """A sentence of evidence when ``value``'s dimension is not the key's ``reference``'s, else ""; it starts
        with :data:`INHOMOGENEOUS` when the answer's terms have different dimensions."""
        if self.units is None:
            return ""
        try:
            key = self.unit(reference)
        except _Mismatch:
            return ""
        except (TypeError, ValueError, AttributeError, KeyError):
            return ""
        if key is None:
            return ""
        try:
            found = self.unit(value)
        except _Mismatch as error:
            return f"{INHOMOGENEOUS} ({error.message})"
        except (TypeError, ValueError, AttributeError, KeyError):
            return ""
        with contextlib.suppress(TypeError, ValueError, AttributeError):
            if found is not None and dimension(found) != dimension(key):
                return (f"its dimension is {describe(dimension(found))} where the key's answer is "
                        f"{describe(dimension(key))}")
        return ""
