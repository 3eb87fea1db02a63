r"""Equilibria a key knows only numerically, or only by their condition (issue 31).

The key's analysis may give an equilibrium as a number (the normal modes found numerically at the problem's
``simulation: values`` when no closed form was found; their ω² are numbers too), or only by its condition
(the effective potential's ``V_eff'(q) = 0`` that SymPy cannot solve: :class:`Condition`). A student's value is
then compared:

- with a number: at the simulation values (the student's expression with the parameters put in), to a relative
  tolerance of :data:`TOLERANCE` (an angle modulo 2π);
- with a condition: the condition's residual at the student's value is zero, at the simulation values when the
  value is a number, else at the shared random states.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy

#: relative tolerance of a comparison with a numerically found value (the root finder's, not 10⁻¹²)
TOLERANCE = 1e-6


@dataclass(frozen=True)
class Condition:
    """An equilibrium of ``coordinate`` known only as a root of ``residual`` (the condition's lhs − rhs)."""

    coordinate: Any
    residual: Any

    def __str__(self) -> str:
        return f"a root of {sympy.sstr(self.residual)} = 0"


def numeric(reference: Any) -> bool:
    """A number found numerically (a Float, with no symbol)."""
    return isinstance(reference, sympy.Basic) and bool(reference.atoms(sympy.Float)) and not reference.free_symbols


def at_values(expr: Any, values: dict[Any, float]) -> complex | None:
    """``expr`` with the simulation ``values`` put in, as a number (None when a symbol is left or it fails)."""
    with contextlib.suppress(TypeError, ValueError, AttributeError, ZeroDivisionError, OverflowError):
        found = sympy.sympify(expr, strict=True).xreplace({s: sympy.Float(v) for s, v in values.items()})
        if found.free_symbols:
            return None
        number = complex(found.evalf())
        return number if mpmath.isfinite(number) else None
    return None


def close_to(a: complex, b: complex, *, angle: bool = False) -> bool:
    gap = a - b
    if angle:
        gap = complex(gap.real - 2 * mpmath.pi * round(gap.real / (2 * float(mpmath.pi))), gap.imag)
    return abs(gap) <= TOLERANCE * max(1.0, abs(b))


def same_number(value: Any, reference: Any, values: dict[Any, float], *, angle: bool = False) -> bool:
    """The student's value at the simulation ``values`` is the key's number."""
    found, want = at_values(value, values), at_values(reference, values)
    return found is not None and want is not None and close_to(found, want, angle=angle)


def simulation_values(problem: Any) -> dict[Any, float]:
    """The problem's ``simulation: values`` by symbol ({} without a simulation)."""
    if problem.simulation is None:
        return {}
    return {problem.symbols[name]: float(v) for name, v in problem.simulation.values.items() if name in problem.symbols}
