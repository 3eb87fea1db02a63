"""The units of a derivation's results, for the JSON result and the reports (only when the file declares units).

The units themselves are decided in :func:`lagsolve.mechanics.result_units.result_units`; this module
projects them: :func:`units_json` is the ``units`` key of the JSON result (``docs/format.md``,
*Units*), :func:`units_context` the rows the Markdown, LaTeX and HTML templates show.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from lagsolve.mechanics.result_units import ResultUnits, result_units

_POWER = re.compile(r"\^(-?[0-9.]+|\(-?[0-9]+/[0-9]+\))")
#: pint's non-ASCII unit symbols, in LaTeX math
_TEX = {"µ": r"\mu ", "μ": r"\mu ", "Ω": r"\Omega ", "°": r"^{\circ}", "Å": r"\mathring{A}"}


def unit_tex(text: str | None) -> str:
    r"""``m/s^2`` → ``\mathrm{m/s^{2}}``; ``N*s/m`` → ``\mathrm{N\,s/m}``; None → ``?``."""
    if text is None:
        return r"\text{?}"
    body = _POWER.sub(lambda m: "^{" + m.group(1).strip("()") + "}", text).replace("*", r"\,").replace(" ", r"\,")
    body = "".join(_TEX.get(ch, ch) if ord(ch) > 127 else ch for ch in body)
    return r"\mathrm{" + "".join(ch if ord(ch) < 128 else "?" for ch in body) + "}"


def _units(derivation: Any) -> ResultUnits | None:
    return result_units(derivation.problem, derivation.kinetic)


def _generalized(derivation: Any, name: str) -> bool:
    """Whether the force of constraint ``name`` is reported as generalized forces (no point where it acts)."""
    forces = derivation.constraint_forces
    if forces is not None and name in forces:
        return bool(forces[name].generalized)
    constraint = next(c for c in derivation.problem.constraints if c.name == name)
    return not constraint.on


def units_json(derivation: Any) -> dict[str, Any] | None:
    """The ``units`` of the JSON result, or None when the problem declares no unit (then the key is absent)."""
    units = _units(derivation)
    if units is None:
        return None
    forces: dict[str, Any] = {}
    for name in units.multipliers:
        forces[name] = ({"generalized": dict(units.generalized_forces)} if _generalized(derivation, name)
                        else units.force)
    out: dict[str, Any] = {
        "time": units.time,
        "energy": units.energy,
        "coordinates": dict(units.coordinates),
        "accelerations": dict(units.accelerations),
        "generalized_forces": dict(units.generalized_forces),
        "multipliers": {name: {"unit": units.multipliers[name], "constraint": units.constraints[name]}
                        for name in units.multipliers},
        "constraint_forces": forces,
    }
    if derivation.problem.friction:
        out["friction"] = {f.name: units.force for f in derivation.problem.friction}
    if units.missing:
        out["missing"] = list(units.missing)
    return out


def units_context(derivation: Any, tex: Callable[[Any], str]) -> dict[str, Any] | None:
    """Rows ``{symbol, unit, unit_text, note}`` for the report's table of units (``symbol`` through ``tex``,
    ``unit`` in LaTeX), or None without units."""
    units = _units(derivation)
    if units is None:
        return None
    import sympy

    rows: list[dict[str, str]] = []

    def row(symbol: Any, unit: str | None, note: str = "") -> None:
        rows.append({"symbol": tex(symbol), "unit": unit_tex(unit), "unit_text": unit or "?", "note": note})

    problem = derivation.problem
    for c in problem.coordinates:
        row(c.acceleration, units.accelerations[c.name])
    for c in derivation.constraints:
        written = units.constraints[c.name]
        row(c.multiplier, units.multipliers[c.name],
            f"its constraint is written in {written}" if written is not None else "")
    generalized = [c.name for c in derivation.constraints if _generalized(derivation, c.name)]
    for c in derivation.constraints:
        if c.name not in generalized:
            row(sympy.Symbol(f"F_{c.name}"), units.force, f"force of constraint {c.name}")
    for q in problem.coordinates if generalized else ():
        row(sympy.Symbol(f"Q_{q.name}"), units.generalized_forces[q.name],
            f"generalized force of constraint {', '.join(generalized)} on {q.name}")
    for f in problem.friction:
        row(sympy.Symbol(f"N_{f.name}"), units.force, f"normal force of contact {f.name}")
    declared = [{"symbol": tex(symbol), "unit": unit_tex(unit), "unit_text": unit}
                 for symbol, unit in [*((p.symbol, p.unit) for p in problem.parameters),
                                      *((sympy.Symbol(f.name), f.unit) for f in problem.functions),
                                      *((c.symbol, c.unit) for c in problem.coordinates)] if unit is not None]
    return {"declared": declared, "time": unit_tex(units.time), "energy": unit_tex(units.energy),
            "time_text": units.time, "energy_text": units.energy or "?", "rows": rows, "missing": list(units.missing),
            "constraints": bool(derivation.constraints)}
