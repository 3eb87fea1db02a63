"""Figures of a run: the ones a person wants, labelled, and written as PNG/GIF."""

from __future__ import annotations

import pytest

from lagsolve.numeric.integrate import Trajectory
from lagsolve.render import plots
from simulation_support import CARTESIAN_PENDULUM, run


@pytest.fixture(scope="module")
def trajectory() -> Trajectory:
    return run(CARTESIAN_PENDULUM, 3.0, samples=301)


def _labels(fig: object) -> list[tuple[str, str]]:
    return [(ax.get_xlabel(), ax.get_ylabel()) for ax in fig.axes if ax.get_visible()]  # type: ignore[attr-defined]


def test_all_figures_are_made_with_stable_names(trajectory: Trajectory) -> None:
    """A constrained particle problem gets path, coordinates, phase, forces and conservation figures."""
    figs = plots.figures(trajectory, "Pendulum", {"x": "x", "y": "y"})
    assert list(figs) == ["path", "coordinates", "phase", "forces", "conservation"]


def test_axes_are_labelled(trajectory: Trajectory) -> None:
    """Each figure has a title and labelled axes with symbols."""
    figs = plots.figures(trajectory, "Pendulum", {"x": "x", "y": "y"})
    assert _labels(figs["path"]) == [("x", "y")]
    assert _labels(figs["coordinates"]) == [("", "$x$"), ("$t$", "$y$")]
    assert ("$x$", "$\\dot{x}$") in _labels(figs["phase"])
    assert _labels(figs["forces"]) == [("", "multiplier $\\lambda$"), ("$t$", "magnitude $|F|$")]
    assert _labels(figs["conservation"])[1] == ("$t$", "constraint residual\n(before projection)")
    for fig in figs.values():
        assert fig._suptitle.get_text().startswith("Pendulum")  # noqa: SLF001


def test_constraint_curve_is_drawn_when_given(trajectory: Trajectory) -> None:
    """The path figure draws the constraint curve (dashed, labelled) when one is supplied."""
    import numpy as np

    circle = (0, lambda xs: np.column_stack([xs, -np.sqrt(np.clip(1 - xs**2, 0, None))]))
    fig = plots.path_figure(trajectory, "Pendulum", circle)
    labels = [line.get_label() for line in fig.axes[0].get_lines()]
    assert "constraint" in labels and "bob" in labels


def test_png_and_gif_bytes(trajectory: Trajectory) -> None:
    """Figures become non-empty PNG files; the animation a GIF."""
    png = plots.png_bytes(plots.coordinates_figure(trajectory, "P", {}))
    assert png.startswith(b"\x89PNG") and len(png) > 5000
    gif = plots.animation_gif(trajectory, "P", frames=10)
    assert gif.startswith(b"GIF8") and len(gif) > 1000


def test_minimal_coordinates_conservation_figure() -> None:
    """Integrated in minimal coordinates the residual is exactly zero: the figure says so in words instead of
    drawing a line at the log scale's floor, and the energy is drawn once."""
    from lagsolve.mechanics.minimal_chart import minimal_chart
    from lagsolve.numeric.initial import complete_initial
    from lagsolve.numeric.integrate import integrate_motion
    from lagsolve.numeric.system import bind
    from mechanics_support import derived_file

    hole = derived_file("hole_table")
    chart, _ = minimal_chart(hole.analysis, hole.model)
    system = bind(hole.form, {}, hole.conserved, chart)
    q0, qd0 = complete_initial(system, hole.problem.simulation.initial)
    trajectory = integrate_motion(system, q0, qd0, 1.0, samples=101)
    fig = plots.conservation_figure(trajectory, "Hole")
    drift, residual = fig.axes[0], fig.axes[1]
    assert [line.get_label() for line in drift.get_lines()] == ["energy $h$", "p theta"]
    assert residual.get_ylabel() == "constraint residual" and not residual.get_lines()
    assert "exactly 0 at every sample" in residual.texts[0].get_text()


def test_a_name_with_dollar_signs_is_drawn_as_text(trajectory: Trajectory) -> None:
    """A problem name such as 'bad $\\frac{ $' is a title, not mathtext: every figure and the animation draw."""
    title = "bad $\\frac{ $ x"
    for fig in plots.figures(trajectory, title, {"x": "x", "y": "y"}).values():
        assert plots.png_bytes(fig).startswith(b"\x89PNG")
    assert plots.animation_gif(trajectory, title, frames=3).startswith(b"GIF8")
