"""Units as a report prints them: :class:`Unit`, a result's unit that prints itself in each format.

The units themselves are decided in :func:`lagsolve.mechanics.units.result_units.result_units` and listed in
:class:`~lagsolve.render.sections.units.UnitsSection`; a unit is text such as ``m/s^2`` (None: unknown). The
JSON writes the text (or null), LaTeX ``\\mathrm{m/s^{2}}`` (:func:`unit_tex`), MathML and the terminal the
text, with ``?`` for an unknown unit.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any, ClassVar

from lagsolve.render.model import Printer

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


@dataclass(frozen=True)
class Unit:
    """A result's unit as text (None: unknown), printed by each format in its own way."""

    text: str | None

    #: what the JSON printer writes (the output schema's description of a unit)
    SCHEMA: ClassVar[dict[str, Any]] = {"type": ["string", "null"]}

    def present(self, printer: Printer) -> str | None:
        if printer.kind == "json":
            return self.text
        if printer.kind == "latex":
            return unit_tex(self.text)
        return self.text or "?"
