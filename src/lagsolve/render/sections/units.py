"""The units section of a report, as data (only when the problem file declares units).

The units themselves are decided in :func:`lagsolve.mechanics.units.result_units.result_units`;
:func:`units_section` lists what a report shows of them, in display order: the JSON key ``units``
(``docs/format.md``, *Units*) and the templates' table (``templates/*/_units.*.j2``) are both
:func:`lagsolve.render.model.present` of the one record.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy

from lagsolve.mechanics.units.result_units import result_units
from lagsolve.render.model import Expr, shown
from lagsolve.render.units import Unit

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation


@dataclass(frozen=True)
class UnitRow:
    """A quantity of the results (or a name the file declares) with its unit, for the reports' table."""

    symbol: Expr = shown()
    unit: Unit = shown()
    note: str = shown("")


@dataclass(frozen=True)
class MultiplierUnit:
    """A multiplier's unit and the unit of its constraint's expression as written (they go together)."""

    unit: Unit = shown()
    constraint: Unit = shown()


@dataclass(frozen=True)
class GeneralizedUnits:
    """A force of constraint reported as generalized forces (no point where it acts): their units."""

    generalized: Mapping[str, Unit] = shown()


@dataclass(frozen=True)
class UnitsSection:
    """The unit of each result: the JSON's maps by name, and the reports' rows (``rows`` the results',
    ``declared`` the file's); ``constraints`` whether there are multipliers to explain."""

    time: Unit = shown()
    energy: Unit = shown()
    coordinates: Mapping[str, Unit] = shown(template=False)
    accelerations: Mapping[str, Unit] = shown(template=False)
    generalized_forces: Mapping[str, Unit] = shown(template=False)
    multipliers: Mapping[str, MultiplierUnit] = shown(template=False)
    constraint_forces: Mapping[str, Unit | GeneralizedUnits] = shown(template=False)
    friction: Mapping[str, Unit] = shown(optional=True, template=False)
    missing: tuple[str, ...] = shown(optional=True)
    rows: tuple[UnitRow, ...] = shown(json=None)
    declared: tuple[UnitRow, ...] = shown(json=None)
    constraints: bool = shown(json=None)


def _generalized(derivation: Derivation, name: str) -> bool:
    """Whether the force of constraint ``name`` is reported as generalized forces (no point where it acts)."""
    forces = derivation.constraint_forces
    if forces is not None and name in forces:
        return bool(forces[name].generalized)
    constraint = next(c for c in derivation.problem.constraints if c.name == name)
    return not constraint.on


def _units(values: Mapping[str, str | None]) -> dict[str, Unit]:
    return {name: Unit(text) for name, text in values.items()}


def units_section(derivation: Derivation) -> UnitsSection | None:
    """The units section of ``derivation``, or None when the problem declares no unit."""
    problem = derivation.problem
    units = result_units(problem, derivation.kinetic)
    if units is None:
        return None
    names = [*units.multipliers, *(c.name for c in derivation.constraints if c.name not in units.multipliers)]
    generalized = frozenset(name for name in names if _generalized(derivation, name))
    rows = [UnitRow(c.acceleration, Unit(units.accelerations[c.name])) for c in problem.coordinates]
    for c in derivation.constraints:
        written = units.constraints[c.name]
        rows.append(UnitRow(c.multiplier, Unit(units.multipliers[c.name]),
                            f"its constraint is written in {written}" if written is not None else ""))
    shown_as_generalized = [c.name for c in derivation.constraints if c.name in generalized]
    rows += [UnitRow(sympy.Symbol(f"F_{c.name}"), Unit(units.force), f"force of constraint {c.name}")
             for c in derivation.constraints if c.name not in generalized]
    rows += [UnitRow(sympy.Symbol(f"Q_{q.name}"), Unit(units.generalized_forces[q.name]),
                     f"generalized force of constraint {', '.join(shown_as_generalized)} on {q.name}")
             for q in (problem.coordinates if shown_as_generalized else ())]
    rows += [UnitRow(sympy.Symbol(f"N_{f.name}"), Unit(units.force), f"normal force of contact {f.name}")
             for f in problem.friction]
    declared = tuple(UnitRow(symbol, Unit(unit)) for symbol, unit in [
        *((p.symbol, p.unit) for p in problem.parameters), *((sympy.Symbol(f.name), f.unit) for f in problem.functions),
        *((c.symbol, c.unit) for c in problem.coordinates)] if unit is not None)
    forces: dict[str, Unit | GeneralizedUnits] = {
        name: GeneralizedUnits(_units(units.generalized_forces)) if name in generalized else Unit(units.force)
        for name in units.multipliers}
    return UnitsSection(
        time=Unit(units.time), energy=Unit(units.energy), coordinates=_units(units.coordinates),
        accelerations=_units(units.accelerations), generalized_forces=_units(units.generalized_forces),
        multipliers={name: MultiplierUnit(Unit(units.multipliers[name]), Unit(units.constraints[name]))
                     for name in units.multipliers},
        constraint_forces=forces, friction={f.name: Unit(units.force) for f in problem.friction},
        missing=tuple(units.missing), rows=tuple(rows), declared=declared, constraints=bool(derivation.constraints))
