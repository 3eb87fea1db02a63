"""Figures of a run: the ones a person wants, labelled, and written as PNG/GIF."""

from __future__ import annotations

import numpy as np
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
    assert list(figs) == ["sketch", "path", "coordinates", "phase", "forces", "conservation"]


def test_axes_are_labelled(trajectory: Trajectory) -> None:
    """Each figure has a title and labelled axes with symbols."""
    figs = plots.figures(trajectory, "Pendulum", {"x": "x", "y": "y"})
    assert _labels(figs["path"]) == [("x", "y")]
    assert _labels(figs["sketch"])[0] == ("x", "y")
    assert _labels(figs["coordinates"]) == [("", "$x$"), ("$t$", "$y$")]
    assert ("$x$", "$\\dot{x}$") in _labels(figs["phase"])
    assert _labels(figs["forces"]) == [("", "multiplier $\\lambda$"), ("$t$", "magnitude $|F|$")]
    assert _labels(figs["conservation"])[-1] == ("$t$", "constraint residual\n(before projection)")
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
    """Integrated in minimal coordinates the residual is exactly zero: the figure says so in a line under it
    instead of drawing an empty panel, and the energy is drawn once."""
    from lagsolve.mechanics.analysis.minimal_chart import minimal_chart
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
    (drift,) = fig.axes  # no residual panel: it would be empty
    assert [line.get_label() for line in drift.get_lines()] == ["energy $h$", "p theta"]
    assert "exactly 0 at every sample" in fig.get_supxlabel()


def test_a_name_with_dollar_signs_is_drawn_as_text(trajectory: Trajectory) -> None:
    """A problem name such as 'bad $\\frac{ $' is a title, not mathtext: every figure and the animation draw."""
    title = "bad $\\frac{ $ x"
    for fig in plots.figures(trajectory, title, {"x": "x", "y": "y"}).values():
        assert plots.png_bytes(fig).startswith(b"\x89PNG")
    assert plots.animation_gif(trajectory, title, frames=3).startswith(b"GIF8")


# --- shipped problems: the sketch, friction, no empty panels, units, the time stamp ---------------------


def _shipped(name: str, **options: object) -> object:
    """``lagsolve simulate problems/<name>.yaml`` as the library runs it (tables and scene, no PNGs)."""
    from mechanics_support import problem_file

    return _scene(problem_file(name), **options)


def _scene(problem: object, **options: object) -> object:
    from lagsolve.app.simulation import SimulationOptions, run_simulation
    from lagsolve.mechanics.analysis.analyse import monitored
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    form = matrix_form(problem, display=False)
    conserved, _, _, note = monitored(form)
    settings = SimulationOptions(values={}, initial={}, tables=("csv",), scene=True, **options)  # type: ignore[arg-type]
    result = run_simulation(form, conserved, settings, energy_note=note)
    return result, result.scene


SHIPPED = ["bead", "double_pendulum", "pendulum_cartesian", "spring_on_rough_floor", "rough_incline", "wedge",
           "ladder_rough_floor", "rotating_tube", "bead_on_rotating_hoop", "hole_table"]


@pytest.mark.slow
@pytest.mark.parametrize("name", SHIPPED)
def test_no_figure_of_a_shipped_problem_has_an_empty_panel(name: str) -> None:
    """Every Axes of every figure holds data (lines, shading or the sketch), and each title fits its figure."""
    result, scene = _shipped(name)
    labels = {c: c for c in result.trajectory.coordinates}
    for key, fig in plots.figures(result.trajectory, result.name, labels, scene=scene).items():
        for ax in fig.axes:
            assert ax.has_data() or not ax.axison, f"{name}: an empty panel in the {key} figure"
        plots.png_bytes(fig)  # lays the figure out
        renderer = fig._get_renderer()  # noqa: SLF001
        box = fig._suptitle.get_window_extent(renderer)  # noqa: SLF001
        assert box.x0 >= 0 and box.x1 <= fig.bbox.x1, f"{name}: the {key} title is clipped"


def test_sketch_draws_rods_and_pivot_of_the_double_pendulum() -> None:
    """The sketch of the double pendulum draws two rods (pivot to upper, upper to lower) at t = 0."""
    import numpy as np

    result, scene = _shipped("double_pendulum")
    trajectory = result.trajectory
    fig = plots.sketch_figure(trajectory, scene, "Double pendulum")
    ax = fig.axes[0]
    upper, lower = trajectory.positions[0, :2], trajectory.positions[0, 2:4]
    segments = [np.column_stack(line.get_data()) for line in ax.get_lines() if len(line.get_xdata()) == 2]
    assert any(np.allclose(s, [[0, 0], upper]) for s in segments)
    assert any(np.allclose(s, [upper, lower]) for s in segments)
    assert [t.get_text() for t in ax.texts if t.get_text() in ("upper", "lower")] == ["upper", "lower"]


def test_animation_frames_carry_a_time_stamp() -> None:
    """Each frame of the animation shows 't = ...' with the sample's time; the first frame is the sketch at 0."""
    import numpy as np

    from lagsolve.render.sketch import Drawing

    result, scene = _shipped("pendulum_cartesian")
    trajectory = result.trajectory
    from lagsolve.render.picture import Picture

    fig = Picture()
    drawing = Drawing(fig.add_subplot(), trajectory, scene, trails=True, units={"t": "s"})
    assert drawing.show(0)[-1].get_text() == "t = 0.00 s"
    assert drawing.show(500)[-1].get_text() == f"t = {trajectory.t[500]:.2f} s"
    rod = drawing.rods[0]
    assert np.allclose(np.column_stack(rod.get_data())[1], trajectory.positions[500, :2])
    gif = plots.animation_gif(trajectory, "P", frames=4, scene=scene)
    assert gif.startswith(b"GIF8")


def test_friction_is_plotted_and_in_the_csv() -> None:
    """The spring on a rough floor: the CSV's friction column is -mu N sign(x_dot) while sliding and k x (what
    holds the spring) while stuck, stuck_rough marks the sticking phase, and the forces figure has a friction
    panel with that phase shaded."""
    import numpy as np

    result, scene = _shipped("spring_on_rough_floor")
    lines = result.tables["csv"].splitlines()
    header = lines[0].split(",")
    assert {"N_rough", "friction_rough", "stuck_rough"} <= set(header)
    table = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    col = {name: table[:, k] for k, name in enumerate(header)}
    trajectory = result.trajectory
    assert np.array_equal(col["friction_rough"], trajectory.friction[:, 0])
    m, k, g, mu = 1.0, 10.0, 9.81, 0.1
    stuck = col["stuck_rough"] == 1
    sliding = ~stuck & (col["x_dot"] != 0)
    assert stuck.any() and sliding.any()
    assert np.allclose(col["N_rough"], m * g, rtol=1e-12)
    assert np.allclose(col["friction_rough"][sliding], -mu * m * g * np.sign(col["x_dot"][sliding]), rtol=1e-10)
    assert np.allclose(col["friction_rough"][stuck], k * col["x"][stuck], rtol=1e-8, atol=1e-10)
    fig = plots.forces_figure(trajectory, result.name, units={"t": "s", "force": "N"})
    friction = fig.axes[-1]
    assert friction.get_ylabel() == "friction $f$ [N]" and friction.get_xlabel() == "$t$ [s]"
    assert [line.get_label() for line in friction.get_lines()][0] == "friction rough"
    assert friction.patches  # the sticking phase, shaded


def test_dissipative_run_shows_the_energy_dissipated() -> None:
    """Without a conserved energy, the conservation figure draws h - h0 and says how much was dissipated."""
    result, _ = _shipped("spring_on_rough_floor")
    fig = plots.conservation_figure(result.trajectory, result.name)
    (energy,) = fig.axes
    h = result.trajectory.energy
    assert energy.get_ylabel() == "$h - h_0$"
    assert energy.get_legend().get_title().get_text() == f"dissipated by t = 8: {h[0] - h[-1]:.4g}"
    assert "energy not conserved" in fig.get_supxlabel()


def test_constant_and_uniform_coordinates_get_no_panel() -> None:
    """The floor's y stays 0: no panel for it in the coordinates and phase figures, a note instead."""
    result, _ = _shipped("spring_on_rough_floor")
    fig = plots.coordinates_figure(result.trajectory, "S", {"x": "x", "y": "y"}, units={"x": "m", "t": "s"})
    assert _labels(fig) == [("$t$ [s]", "$x$ [m]")]
    assert fig.get_supxlabel() == "y = 0 throughout"
    phase = plots.phase_figure(result.trajectory, "S", {"x": "x", "y": "y"}, units={"x": "m", "t": "s"})
    assert _labels(phase) == [("$x$ [m]", "$\\dot{x}$ [m/s]")]


@pytest.mark.parametrize(("name", "contact", "rate"), [("rotating_tube", "wall", "r_dot"),
                                                       ("rough_circular_wire", "rub", "theta_dot"),
                                                       ("rough_incline", "contact", "s_dot")])
def test_friction_column_is_mu_n_against_the_sliding_rate(name: str, contact: str, rate: str) -> None:
    """While a contact slides, |friction_<c>| = mu N_<c> (Coulomb's law, from the CSV's own N) and the
    friction opposes the sliding rate: its power f * s_dot is never positive."""
    import numpy as np

    from mechanics_support import problem_file

    result, _ = _shipped(name)
    lines = result.tables["csv"].splitlines()
    header = lines[0].split(",")
    table = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    col = {key: table[:, k] for k, key in enumerate(header)}
    mu = problem_file(name).simulation.values["mu"]
    sliding = col[f"stuck_{contact}"] == 0
    assert sliding.all()
    assert np.allclose(np.abs(col[f"friction_{contact}"]), mu * col[f"N_{contact}"], rtol=1e-12, atol=1e-12)
    assert np.all(col[f"friction_{contact}"] * col[rate] <= 0)


def test_spring_legend_is_mathematics_not_python() -> None:
    """The legend names the spring and the damper with their terms as mathematics (mathtext), never in Python's
    syntax (`*`, `**`)."""
    result, scene = _shipped("spring_on_rough_floor")
    fig = plots.sketch_figure(result.trajectory, scene, result.name)
    texts = [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert "spring ($k x^{2} / 2$)" in texts and all("*" not in t for t in texts)


def test_the_table_has_a_gap_at_the_hole() -> None:
    """The hole table's table top is drawn in two pieces, with a gap wider than the hole's ring around the hole,
    so the string goes down through the table, not through a drawn top."""
    _, scene = _shipped("hole_table")
    (hole,) = [s.points[0] for s in scene.shapes if s.kind == "hole"]
    side = [s.points for s in scene.shapes if s.kind == "support" and s.views == (0, 2)]
    assert len(side) == 2
    assert all(not (band[:, 0].min() < hole[0] + 0.05 * scene.scale and band[:, 0].max() > hole[0] - 0.05
                    * scene.scale) for band in side)
    assert min(band[:, 0].min() for band in side) < hole[0] < max(band[:, 0].max() for band in side)


INCLINE_RISING_RIGHT = """
name: block on an incline rising to the right, pulling a weight over the pulley at the top
parameters: {m1: block, m2: weight, g: gravity, beta: angle}
coordinates: {x: across, y: height, h: the weight's height}
particles:
  block: {mass: m1, position: [x, y]}
  weight: {mass: m2, position: [6, h]}
gravity: [0, -g]
constraints:
  plane: {holonomic: y - x*tan(beta), on: block}
  string: {holonomic: x*cos(beta) + y*sin(beta) + h, on: [block, weight]}
simulation:
  values: {m1: 1.0, m2: 2.0, g: 9.81, beta: 0.5}
  initial: {x: 1.0, y: 0.5463024898437905, h: -1.1394939273245491}
  t_end: 0.6
"""


@pytest.mark.parametrize("source", ["incline_pulley", INCLINE_RISING_RIGHT])
def test_an_incline_ends_at_its_pulley(source: str) -> None:
    """A string from a block up an incline over a pulley to a hanging weight is drawn over one pulley, where the
    strand up the slope meets the weight's vertical strand (on the plane's line, at its top); the plane ends
    there and a face goes down from the corner (the weight hangs beside it, not inside the incline)."""
    from mechanics_support import problem_file, problem_text

    problem = problem_file(source) if source == "incline_pulley" else problem_text(source)
    _, scene = _scene(problem)
    pulleys = [s for s in scene.shapes if s.kind == "pulley"]
    assert len(pulleys) == 1
    (string,) = [s.points for s in scene.shapes if s.kind == "string"]
    corner = string[0, 1]
    assert all(np.allclose((p.points.min(axis=0) + p.points.max(axis=0)) / 2, corner, atol=1e-3) for p in pulleys)
    (label, stop, towards), = scene.ends
    assert label == "plane"
    grounds = [s.points for s in scene.shapes if s.kind == "ground"]
    assert len(grounds) == 2  # the slope and the face
    slope, face = grounds
    assert abs(float(face[0, 0] - face[1, 0])) < 1e-9 and face[0, 1] > face[1, 1]  # vertical, down from the top
    # the weight hangs on the side of the face away from the slope, and below the corner all the run
    weight = string[:, 2]
    assert np.all(np.sign(weight[:, 0] - face[0, 0]) == -np.sign(slope[0, 0] - face[0, 0]))
    assert np.all(weight[:, 1] < corner[1])
    # the corner is on the plane's line, the block's strand runs along it
    block = string[:, 0]
    along = (corner - block) / np.linalg.norm(corner - block, axis=1, keepdims=True)
    assert np.allclose(along, towards / np.linalg.norm(towards), atol=1e-9)
