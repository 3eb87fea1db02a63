"""Pictures of a sweep (matplotlib figures on their own Agg canvas, :mod:`lagsolve.render.picture`; returned,
never shown, and no backend is chosen).

* two swept inputs: a **regime map**, each run a cell (a grid) or a dot (random draws), coloured by
  its outcome (ok, flipped, stick, slip, released, failed) or by a chosen numeric column;
* one swept input: a **bifurcation-style scatter**, the input against the Poincaré crossings of a
  state variable (with ``--poincare``), or against a chosen column (default: the final value of the
  first coordinate).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from lagsolve.errors import Issue, SpecError

#: outcome → colour (colour-blind-safe palette, Okabe–Ito)
OUTCOMES = {"ok": "#56B4E9", "no flip": "#56B4E9", "flipped": "#D55E00", "stick": "#009E73", "slip": "#E69F00",
            "released": "#CC79A7", "failed": "#000000"}


def check_color(color: str | None, numeric: dict[str, bool]) -> None:
    """Refuse a ``--color`` that is not a numeric column (``numeric`` maps each column of the table to whether it
    is numeric) or ``outcome``: checked before any run starts, and again on the table.

    Raises
    ------
    SpecError
        ``color`` is not a column of the table, or not numeric.
    """
    if color is None or color == "outcome":
        return
    if color not in numeric:
        raise SpecError([Issue("<command line>", 0, "--color", f"no column {color!r} in the sweep's table",
                               "known: " + ", ".join(numeric))])
    if not numeric[color]:
        raise SpecError([Issue("<command line>", 0, "--color", f"column {color!r} is not numeric",
                               "give a numeric column (final_theta1, energy_drift, ...) or outcome")])


def figures(frame: Any, swept: Sequence[str], title: str, color: str | None = None) -> dict[str, Any]:
    """The figures for the swept inputs: ``{"regime": Figure}`` for two or more (the first two are
    the axes), ``{"bifurcation": Figure}`` for one.

    Raises
    ------
    SpecError
        ``color`` is not a column of the table, or not numeric (outcome is the categorical choice).
    """
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    check_color(color, {str(c): bool(is_numeric_dtype(frame[c]) or is_bool_dtype(frame[c])) for c in frame.columns})
    if len(swept) >= 2:
        return {"regime": _regime(frame, swept[0], swept[1], title, None if color == "outcome" else color)}
    return {"bifurcation": _bifurcation(frame, swept[0], title, None if color == "outcome" else color)}


def _regime(frame: Any, x: str, y: str, title: str, color: str | None) -> Any:
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from lagsolve.render.picture import Picture as Figure

    figure = Figure(figsize=(5.2, 4.2), dpi=100, layout="constrained")
    axes = figure.add_subplot()
    xs, ys = np.unique(frame[x].to_numpy()), np.unique(frame[y].to_numpy())
    full_grid = len(xs) * len(ys) == len(frame) and len(xs) > 1 and len(ys) > 1
    present = [k for k in OUTCOMES if (frame["outcome"] == k).any()]
    cmap: Any = "viridis"
    vmin = vmax = None
    if color is None:
        values = frame["outcome"].map({k: i for i, k in enumerate(present)}).to_numpy(dtype=float)
        cmap = ListedColormap([OUTCOMES[k] for k in present])
        vmin, vmax = -0.5, len(present) - 0.5
    else:
        values = frame[color].to_numpy(dtype=float)
    mesh: Any
    if full_grid:
        grid = np.full((len(ys), len(xs)), np.nan)
        grid[np.searchsorted(ys, frame[y].to_numpy()), np.searchsorted(xs, frame[x].to_numpy())] = values
        mesh = axes.pcolormesh(_edges(xs), _edges(ys), grid, cmap=cmap, vmin=vmin, vmax=vmax)
    else:
        mesh = axes.scatter(frame[x], frame[y], c=values, cmap=cmap, s=12, vmin=vmin, vmax=vmax)
    if color is None:
        axes.legend(handles=[Patch(color=OUTCOMES[k], label=k) for k in present], loc="upper left",
                    bbox_to_anchor=(1.01, 1.0), frameon=False, title="outcome")
    else:
        figure.colorbar(mesh, ax=axes, label=color)
    axes.set_xlabel(x)
    axes.set_ylabel(y)
    axes.set_title(f"{title}: {len(frame)} runs", fontsize=10)
    return figure


def _edges(centres: np.ndarray) -> np.ndarray:
    middle = (centres[1:] + centres[:-1]) / 2
    return np.concatenate([[2 * centres[0] - middle[0]], middle, [2 * centres[-1] - middle[-1]]])


def _bifurcation(frame: Any, x: str, title: str, color: str | None) -> Any:
    from lagsolve.render.picture import Picture as Figure

    figure = Figure(figsize=(5.2, 3.8), dpi=100, layout="constrained")
    axes = figure.add_subplot()
    states = [c.removeprefix("final_") for c in frame.columns if c.startswith("final_")]
    crossing = "poincare_t" in frame.columns and color is None
    if crossing:
        shown = next((s for s in states if s != frame.attrs.get("section")), states[0])
        points = [(xv, v) for xv, vs in zip(frame[x], frame[f"poincare_{shown}"], strict=True) for v in vs]
        px = np.array([p[0] for p in points], dtype=float)
        py = np.array([p[1] for p in points], dtype=float)
        axes.scatter(px, py, s=2, color="#0072B2", linewidths=0)
        axes.set_ylabel(f"{shown} at the section crossings")
    else:
        shown = color or f"final_{states[0]}"
        outcome_colors = frame["outcome"].map(OUTCOMES).fillna("#999999")
        axes.scatter(frame[x], frame[shown], s=6, c=list(outcome_colors), linewidths=0)
        axes.set_ylabel(shown)
    axes.set_xlabel(x)
    axes.set_title(f"{title}: {len(frame)} runs", fontsize=10)
    return figure


def png(figure: Any) -> bytes:
    """The figure as PNG bytes (fixed metadata, so the same figure gives the same bytes)."""
    import io

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", metadata={"Software": None})
    return buffer.getvalue()
