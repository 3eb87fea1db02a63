"""The units section of a report, as data (only when the problem file declares units).

The units themselves are decided in :func:`lagsolve.mechanics.result_units.result_units`;
:func:`units_section` lists what a report shows of them, in display order, and :mod:`lagsolve.render.units`
projects that onto the JSON key ``units`` and the templates' table.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.result_units import ResultUnits, result_units

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation


@dataclass(frozen=True)
class UnitRow:
    """A quantity of the results (or a name the file declares) with its unit (None: unknown)."""

    symbol: Any
    unit: str | None
    note: str = ""


@dataclass(frozen=True)
class UnitsSection:
    """``units`` as decided; ``generalized`` the constraints whose force is reported as generalized forces (no
    point where it acts); ``rows`` the results' units, ``declared`` the file's, ``friction`` the contacts."""

    units: ResultUnits
    generalized: frozenset[str]
    rows: tuple[UnitRow, ...]
    declared: tuple[UnitRow, ...]
    friction: tuple[str, ...]
    constrained: bool


def _generalized(derivation: Derivation, name: str) -> bool:
    """Whether the force of constraint ``name`` is reported as generalized forces (no point where it acts)."""
    forces = derivation.constraint_forces
    if forces is not None and name in forces:
        return bool(forces[name].generalized)
    constraint = next(c for c in derivation.problem.constraints if c.name == name)
    return not constraint.on


def units_section(derivation: Derivation) -> UnitsSection | None:
    """The units section of ``derivation``, or None when the problem declares no unit."""
    problem = derivation.problem
    units = result_units(problem, derivation.kinetic)
    if units is None:
        return None
    names = [*units.multipliers, *(c.name for c in derivation.constraints if c.name not in units.multipliers)]
    generalized = frozenset(name for name in names if _generalized(derivation, name))
    rows = [UnitRow(c.acceleration, units.accelerations[c.name]) for c in problem.coordinates]
    for c in derivation.constraints:
        written = units.constraints[c.name]
        rows.append(UnitRow(c.multiplier, units.multipliers[c.name],
                            f"its constraint is written in {written}" if written is not None else ""))
    shown = [c.name for c in derivation.constraints if c.name in generalized]
    rows += [UnitRow(sympy.Symbol(f"F_{c.name}"), units.force, f"force of constraint {c.name}")
             for c in derivation.constraints if c.name not in generalized]
    rows += [UnitRow(sympy.Symbol(f"Q_{q.name}"), units.generalized_forces[q.name],
                     f"generalized force of constraint {', '.join(shown)} on {q.name}")
             for q in (problem.coordinates if shown else ())]
    rows += [UnitRow(sympy.Symbol(f"N_{f.name}"), units.force, f"normal force of contact {f.name}")
             for f in problem.friction]
    declared = tuple(UnitRow(symbol, unit) for symbol, unit in [
        *((p.symbol, p.unit) for p in problem.parameters), *((sympy.Symbol(f.name), f.unit) for f in problem.functions),
        *((c.symbol, c.unit) for c in problem.coordinates)] if unit is not None)
    return UnitsSection(units=units, generalized=generalized, rows=tuple(rows), declared=declared,
                        friction=tuple(f.name for f in problem.friction), constrained=bool(derivation.constraints))
