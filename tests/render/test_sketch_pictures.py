"""Pictures as a reader sees them (issue 29, items 5 and 7): PNG snapshots of a few sketches compared pixel by pixel
within a tolerance, and the LaTeX report with its simulation figures set with no line or figure over 1 pt past
the margin.

The snapshots are reviewed pictures (tests/render/snapshots/); after a deliberate change to the drawing, write them
again with ``LAGSOLVE_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest tests/render/test_sketch_pictures.py`` and look
at each one before committing.
"""

from __future__ import annotations

import io
import os
import re
from pathlib import Path

import numpy as np
import pytest
from test_report import compile_latex

from lagsolve.api import simulate
from lagsolve.app.pipeline import derive_file
from lagsolve.app.simulation import SimulationOptions
from lagsolve.render.plots import png_bytes
from lagsolve.render.sketch import sketch_figure

ROOT = Path(__file__).resolve().parents[2]
SNAPSHOTS = Path(__file__).parent / "snapshots"
#: a pixel differs when one of its channels differs by more than this (of 255): anti-aliasing and font hinting
PIXEL = 40
#: the share of pixels that may differ (a moved label or arrow changes far more)
SHARE = 0.004


def _pixels(data: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), dtype=np.int16)


@pytest.mark.parametrize("name", ["hole_table", "rough_wedge", "wedge_cylinder", "bead", "incline_pulley",
                                  "differential_drive"])
def test_sketch_matches_its_snapshot(name: str) -> None:
    """The sketch at the start (shapes, arrows, legend, views) looks as reviewed: same size, and fewer than 0.4 %
    of the pixels differ visibly."""
    run = simulate(ROOT / "problems" / f"{name}.yaml", samples=201)
    figure = sketch_figure(run.motion, run.scene, run.name)
    data = png_bytes(figure)
    path = SNAPSHOTS / f"{name}_sketch.png"
    if os.environ.get("LAGSOLVE_UPDATE_SNAPSHOTS") == "1":
        path.write_bytes(data)
    new, old = _pixels(data), _pixels(path.read_bytes())
    assert new.shape == old.shape
    differ = np.any(np.abs(new - old) > PIXEL, axis=2)
    assert differ.mean() < SHARE, f"{differ.mean():.2%} of the pixels of {name}'s sketch differ from {path.name}"


def test_snapshot_comparison_sees_a_moved_arrow() -> None:
    """The tolerance is not so loose that a changed drawing passes: the sketch without its arrows fails it."""
    run = simulate(ROOT / "problems" / "hole_table.yaml", samples=201)
    from dataclasses import replace

    figure = sketch_figure(run.motion, replace(run.scene, forces=()), run.name)
    new, old = _pixels(png_bytes(figure)), _pixels((SNAPSHOTS / "hole_table_sketch.png").read_bytes())
    assert new.shape != old.shape or np.any(np.abs(new - old) > PIXEL, axis=2).mean() >= SHARE


def test_report_with_figures_has_no_overfull_box(tmp_path: Path) -> None:
    """The hole table's LaTeX report with its simulation figures compiles with no box over 1 pt too wide, and the
    string's force is printed once (not again on each member)."""
    options = SimulationOptions(values={}, initial={}, samples=201, plots=True)
    reports = derive_file(ROOT / "problems" / "hole_table.yaml", ("tex",), simulate=options)
    tex = reports.outputs["tex"]
    run, log = compile_latex(tex, reports.files, tmp_path)
    assert run.returncode == 0, run.stdout[-2000:]
    assert r"\includegraphics[width=\linewidth]" in tex and len(reports.files) >= 3
    widths = [float(w) for w in re.findall(r"Overfull \\[hv]box \(([\d.]+)pt too", log)]
    assert all(w <= 1.0 for w in widths), widths
    assert len(re.findall(r"magnitude \$", tex)) == 1


def test_a_lone_bead_is_sketched_on_its_whole_wire() -> None:
    """A sketch at one sample zooms in on the system only where the system there has a size (a cart that rolls
    away); a lone bead is a point there, so its sketch shows the stretch of wire the run covers (x from −1.5 to
    1.5 on the parabola), not the bead and its arrow alone."""
    run = simulate(ROOT / "problems" / "bead.yaml", samples=201)
    figure = sketch_figure(run.motion, run.scene, run.name)
    low, high = figure.axes[0].get_xlim()
    assert low < -1.5 and high > 1.5
