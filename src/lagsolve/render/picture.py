"""Figures that show themselves in a notebook, and nowhere else.

lagsolve never chooses matplotlib's backend: its figures are :class:`Picture` objects, a
:class:`matplotlib.figure.Figure` drawn by the Agg canvas (so that ``savefig`` and the animation's frame
buffers work on a machine with no screen) whose ``_repr_png_`` lets IPython show it as a picture, inline,
whatever backend the notebook uses. Nothing here opens a window or changes global state.
"""

from __future__ import annotations

import io
from typing import Any

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure


class Picture(Figure):
    """A figure on its own Agg canvas, shown as a PNG in notebooks."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        FigureCanvasAgg(self)

    def _repr_png_(self) -> bytes:
        out = io.BytesIO()
        self.savefig(out, format="png", dpi=100)
        return out.getvalue()

    def __repr__(self) -> str:
        width, height = self.get_size_inches()
        return f"<lagsolve figure {width:g}x{height:g} in, {len(self.axes)} axes: {self.get_suptitle()[:60]!r}>"
