r"""The units of a derivation's results, from the units a problem declares.

A multiplier's unit depends on how its constraint is written: with the constraint's unit
:math:`U`, :math:`a_{jq} = \partial\psi_j/\partial q` has unit :math:`U/[q]` and
:math:`\lambda_j a_{jq}` is a generalized force, so :math:`[\lambda_j] = [E]/U` for a holonomic
constraint and :math:`[E]/(U\,[t])` for a velocity constraint (:func:`result_units`).

A force of constraint is an energy over the unit of the positions; a generalized force an energy
over its coordinate's unit (a force for a length, a torque for an angle). Results are written with
SI names where they fit (:func:`unit_text`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from lagsolve.mechanics.units.dimensions import LENGTH, algebra, dimension, fraction_text
from lagsolve.problem.schema import ConstraintKind, Problem
from lagsolve.problem.units import DEFAULT_TIME_UNIT, format_unit, registry


def missing_units(problem: Problem) -> list[str]:
    """The parameters, functions and coordinates without a unit in a file that declares some (else [])."""
    if not problem.has_units:
        return []
    return [name for name, unit in problem.units.items() if unit is None]


def unit_text(unit: Any, *, angle: bool = False, torque: bool = False) -> str | None:
    """A result's unit for people: ``N``, ``N/m``, ``J`` (``N*m`` with ``torque``), ``m/s^2``.

    SI units are named (kg, m, s, N, J, W); radians are kept only with ``angle`` (``rad/s^2``).
    Units that are not coherent SI (``km``, ``min``, ``g``) are written as declared and combined, with the
    radians likewise left out unless ``angle`` (an energy ``g*cm^2/s^2``, not ``cm^2*g*rad^2/s^2``).
    None stays None (unknown).
    """
    if unit is None:
        return None
    ureg = registry()
    base = ureg.Quantity(1, unit).to_base_units()
    exps = dict(base.unit_items())
    rad = exps.pop("radian", 0)
    declared = dict(ureg.Quantity(1, unit).unit_items()).get("radian", 0)  # (a degree is left as it is)
    as_declared = unit if angle or not declared else (ureg.Quantity(1, unit) / ureg.radian ** declared).units
    if abs(float(base.magnitude) - 1.0) > 1e-12:
        return format_unit(as_declared)  # g*cm^2/s^2 for an energy in CGS (radians left out, as J leaves them)
    if any(name not in ("kilogram", "meter", "second", "ampere", "kelvin", "mole", "candela") for name in exps):
        return format_unit(as_declared)
    kg, m, s = exps.pop("kilogram", 0), exps.pop("meter", 0), exps.pop("second", 0)
    rest = [(format_unit(ureg.parse_units(n)), e) for n, e in exps.items()]
    if kg == 1 and (m, s) == (2, -2):
        parts = [("N", 1), ("m", 1)] if torque else [("J", 1)]
    elif kg == 1 and (m, s) == (2, -3):
        parts = [("W", 1)]
    elif kg == 1 and s < 0:
        parts = [("N", 1), ("m", m - 1), ("s", s + 2)]
    else:
        parts = [("kg", kg), ("m", m), ("s", s)]
    if angle and rad:
        parts.insert(0, ("rad", rad))
    return fraction_text([(n, e) for n, e in [*parts, *rest] if e]) or "1"


def _dimensionless(unit: Any) -> bool:
    return unit is not None and not dimension(unit)


@dataclass(frozen=True)
class ResultUnits:
    """The unit of each result (text, None when unknown): see :func:`result_units`."""

    time: str
    energy: str | None
    coordinates: Mapping[str, str | None]
    velocities: Mapping[str, str | None]
    accelerations: Mapping[str, str | None]
    generalized_forces: Mapping[str, str | None]
    constraints: Mapping[str, str | None]  # the unit of each constraint's expression as written
    multipliers: Mapping[str, str | None]
    force: str | None  # the unit of a physical force (a force of constraint, a friction normal force)
    missing: tuple[str, ...]


def result_units(problem: Problem, kinetic: Any) -> ResultUnits | None:
    """The units of ``problem``'s results, or None when it declares none.

    ``kinetic`` is the kinetic energy the derivation built (it fixes the unit of energy, so that kg and
    m give J, g and cm give g*cm^2/s^2). A force is an energy over the unit of the positions.
    """
    if not problem.has_units:
        return None
    units = algebra(problem)

    safe = units.known
    energy = safe(kinetic) if kinetic is not None else None
    if energy is None and problem.potential is not None:
        energy = safe(problem.potential)
    time = units.time
    coordinates: dict[str, str | None] = {}
    velocities: dict[str, str | None] = {}
    accelerations: dict[str, str | None] = {}
    generalized: dict[str, str | None] = {}
    for c in problem.coordinates:
        q = units.symbols.get(c.symbol)
        coordinates[c.name] = unit_text(q, angle=True)
        velocities[c.name] = unit_text(q / time, angle=True) if q is not None else None
        accelerations[c.name] = unit_text(q / time ** 2, angle=True) if q is not None else None
        generalized[c.name] = (unit_text(energy / q, torque=_dimensionless(q))
                               if q is not None and energy is not None else None)
    constraints: dict[str, str | None] = {}
    multipliers: dict[str, str | None] = {}
    for con in problem.constraints:
        u = safe(con.expression)
        constraints[con.name] = unit_text(u, angle=True)
        if u is None or energy is None:
            multipliers[con.name] = None
            continue
        lam = energy / u if con.kind == ConstraintKind.HOLONOMIC else energy / (u * time)
        multipliers[con.name] = unit_text(lam, torque=_dimensionless(u))
    positions = [r for p in problem.particles for r in p.position] + [r for b in problem.bodies for r in b.position]
    length = next((u for u in map(safe, positions) if u is not None and dimension(u) == LENGTH), None)
    force = unit_text(energy / length) if energy is not None and length is not None else None
    return ResultUnits(unit_text(time) or DEFAULT_TIME_UNIT, unit_text(energy), coordinates, velocities,
                       accelerations, generalized, constraints, multipliers, force, tuple(missing_units(problem)))


def column_units(problem: Problem, kinetic: Any) -> dict[str, str]:
    """Units of the trajectory table's columns (``t``, ``x``, ``x_dot``, ``lambda_c``, ``F_c``, ``energy``,
    ``N_contact``) for a problem with units; empty without units, and a column of unknown unit is left out."""
    units = result_units(problem, kinetic)
    if units is None:
        return {}
    out: dict[str, str | None] = {"t": units.time}
    out.update({c: u for c, u in units.coordinates.items()})
    out.update({f"{c}_dot": u for c, u in units.velocities.items()})
    out.update({f"lambda_{c}": u for c, u in units.multipliers.items()})
    out.update({f"F_{c}": units.force for c in units.multipliers})
    out["energy"] = units.energy
    out.update({f"N_{f.name}": units.force for f in problem.friction})
    out["position"] = _position_unit(problem)
    return {k: v for k, v in out.items() if v is not None}


def _position_unit(problem: Problem) -> str | None:
    units = algebra(problem)
    for r in [r for p in problem.particles for r in p.position]:
        u = units.known(r)
        if u is not None:
            return unit_text(u)
    return None
