"""The canvas every figure is drawn on: its width and tallest height, a titled figure of panels, text wrapped to a
width, and the figures' unit keys. Shared by ``render/plots.py`` and ``render/sketch.py``, which import it and not
each other."""

from __future__ import annotations

import textwrap
from collections.abc import Mapping
from typing import Any

Units = Mapping[str, str] | None

#: the width of every figure, inches (the LaTeX report's text width)
WIDTH = 6.5

#: the tallest figure, inches (a page of the LaTeX report less its caption)
MAX_HEIGHT = 8.2


def fit(text: str, width_inches: float, fontsize: float = 12.0) -> str:
    """``text`` wrapped to lines that fit ``width_inches`` at ``fontsize`` points (about 0.55 em a character)."""
    chars = max(16, int(width_inches * 72 / (0.55 * fontsize)))
    return "\n".join(textwrap.wrap(text, chars)) or text


def figure(title: str, rows: int = 1, cols: int = 1, **kwargs: Any) -> tuple[Any, Any]:
    """A titled figure of ``rows`` × ``cols`` panels at the text width: 1.1 in a row (at least 2.6 in in all), so
    that a three-row figure and a one-row one share a printed page (the hole table's coordinates and phase
    portraits) instead of each leaving half a page empty; the text stays at its size."""
    from lagsolve.render.picture import Picture

    size = kwargs.pop("figsize", (WIDTH, min(max(2.6, 1.15 + 1.1 * rows), MAX_HEIGHT)))
    fig = Picture(figsize=size, layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False, **kwargs)
    fig.suptitle(fit(title, size[0] - 0.3), parse_math=False)  # user text: a "$" in a name is not mathtext
    return fig, axes


def axis_units(units: Units) -> Units:
    """The figures' unit keys from a table's column units: ``length`` from ``position``, ``force`` from the
    first force column (``F_c``, ``N_c`` or ``friction_c``); keys already given win."""
    if not units:
        return units
    out = dict(units)
    if "position" in units:
        out.setdefault("length", units["position"])
    force = next((u for k, u in units.items() if k.startswith(("F_", "N_", "friction_"))), None)
    if force is not None:
        out.setdefault("force", force)
    return out
