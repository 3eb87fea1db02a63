"""A figure of the effective potential with its equilibria marked.

:func:`potential_figure` takes plain numbers (from :func:`lagsolve.numeric.potential.potential_curve`)
and returns a matplotlib ``Figure`` (Agg; it never shows itself). matplotlib is imported only when a
figure is made.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def potential_figure(q: Sequence[float], v: Sequence[float],
                     equilibria: Sequence[tuple[float, float, bool | None]] = (), *,
                     coordinate: str = "q", title: str = "", units: tuple[str | None, str | None] = (None, None)
                     ) -> Figure:
    """V_eff against the coordinate; stable equilibria as filled dots, unstable as open ones,
    undecided ones as crosses. ``units`` (the coordinate's, the energy's) label the axes ``r [m]``.

    >>> fig = potential_figure([1.0, 2.0, 3.0], [1.0, 0.0, 1.0], [(2.0, 0.0, True)], coordinate="r")
    >>> fig.axes[0].get_xlabel()
    '$r$'
    """
    from lagsolve.render.picture import Picture

    if len(q) != len(v):
        raise ValueError(f"q and v differ in length ({len(q)} and {len(v)})")
    figure = Picture(figsize=(6.0, 4.0), layout="constrained")
    axes = figure.add_subplot()
    axes.plot(list(q), list(v), color="C0", label=r"$V_{\mathrm{eff}}$")
    styles = {True: ("o", "C2", "stable"), False: ("o", "none", "unstable"), None: ("x", "C3", "not decided")}
    shown: set[Any] = set()
    for q0, v0, stable in equilibria:
        marker, face, label = styles[stable]
        axes.plot([q0], [v0], marker=marker, markersize=8, markerfacecolor=face, markeredgecolor="C3"
                  if stable is not True else "C2", linestyle="none", label=None if stable in shown else label)
        shown.add(stable)
    axes.set_xlabel(f"${coordinate}$" + (f" [{units[0]}]" if units[0] else ""))
    axes.set_ylabel(r"$V_{\mathrm{eff}}$" + (f" [{units[1]}]" if units[1] else ""))
    if title:
        axes.set_title(title, parse_math=False)  # user text: a "$" in a name is not mathtext
    axes.grid(True, alpha=0.3)
    axes.legend()
    return figure
