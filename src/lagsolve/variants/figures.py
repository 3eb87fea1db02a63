"""A variant's figures (``--figures``): its coordinates and its forces of constraint (with the friction forces and
the sticking phases shaded) against time, as PNG bytes, drawn by :mod:`lagsolve.render.plots`."""

from __future__ import annotations

import sympy

from lagsolve.numeric.integrate import Trajectory
from lagsolve.render import plots
from lagsolve.render.notation import Notation


def variant_figures(run: Trajectory, title: str) -> dict[str, bytes]:
    """``{"coordinates": PNG, "forces": PNG}`` (forces only with constraints)."""
    notation = Notation(list(run.coordinates))
    labels = {name: notation.latex(sympy.Symbol(name)) for name in run.coordinates}
    out = {"coordinates": plots.png_bytes(plots.coordinates_figure(run, title, labels))}
    if run.constraints:
        out["forces"] = plots.png_bytes(plots.forces_figure(run, title))
    return out
