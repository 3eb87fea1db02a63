"""The units of a derivation's results, for the JSON result and the reports (only when the file declares units).

The units themselves are decided in :func:`lagsolve.mechanics.result_units.result_units` and listed in
:class:`~lagsolve.render.sections.units.UnitsSection`; this module projects that section:
:func:`units_json` is the ``units`` key of the JSON result (``docs/format.md``, *Units*),
:func:`units_context` the rows the Markdown, LaTeX and HTML templates show.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from lagsolve.render.sections.units import UnitsSection

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


def units_json(section: UnitsSection | None) -> dict[str, Any] | None:
    """The ``units`` of the JSON result, or None when the problem declares no unit (then the key is absent)."""
    if section is None:
        return None
    units = section.units
    forces: dict[str, Any] = {}
    for name in units.multipliers:
        forces[name] = {"generalized": dict(units.generalized_forces)} if name in section.generalized else units.force
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
    if section.friction:
        out["friction"] = {name: units.force for name in section.friction}
    if units.missing:
        out["missing"] = list(units.missing)
    return out


def units_context(section: UnitsSection | None, tex: Callable[[Any], str]) -> dict[str, Any] | None:
    """Rows ``{symbol, unit, unit_text, note}`` for the report's table of units (``symbol`` through ``tex``,
    ``unit`` in LaTeX), or None without units."""
    if section is None:
        return None
    units = section.units
    rows = [{"symbol": tex(r.symbol), "unit": unit_tex(r.unit), "unit_text": r.unit or "?", "note": r.note}
            for r in section.rows]
    declared = [{"symbol": tex(r.symbol), "unit": unit_tex(r.unit), "unit_text": r.unit} for r in section.declared]
    return {"declared": declared, "time": unit_tex(units.time), "energy": unit_tex(units.energy),
            "time_text": units.time, "energy_text": units.energy or "?", "rows": rows, "missing": list(units.missing),
            "constraints": section.constrained}
