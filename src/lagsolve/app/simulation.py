"""One simulation run, from a problem's matrix form to summary, tables and figures.

Shared by ``lagsolve simulate`` and ``lagsolve derive --simulate``; nothing here
prints, exits or writes files.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from lagsolve.enums import TextEnum
from lagsolve.problem.methods import DEFAULT as DEFAULT_METHOD

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.matrix_form import MatrixForm
    from lagsolve.mechanics.results import Derivation
    from lagsolve.numeric.integrate import Trajectory
    from lagsolve.numeric.scene import Scene

#: a progress report: called with t_end in the process that integrates, it gives the callable that takes
#: each time reached (the command line's progress bar)
Progress = Callable[[float], Callable[[float], None]]


class Coordinates(TextEnum):
    """Which state a run integrates (``--coordinates``)."""

    MINIMAL = "minimal"  # the independent coordinates, where the constraints are solved in closed form
    FULL = "full"  # every coordinate, the constraints held by their multipliers and projection


@dataclass(frozen=True)
class SimulationOptions:
    """What ``lagsolve simulate`` may change; ``None`` means "from the file, else the default"."""

    values: dict[str, float]
    initial: dict[str, float]
    t_end: float | None = None
    samples: int | None = None
    method: str | None = None
    rtol: float | None = None
    atol: float | None = None
    max_step: float | None = None
    after_release: str = "stop"  # an AfterRelease
    coordinates: str = Coordinates.MINIMAL  # MINIMAL where the constraints are solved in closed form, else FULL
    tables: tuple[str, ...] = ()  # "csv", "npz"
    plots: bool = False
    animate: bool = False
    analysis_timeout: float = 60.0  # budget of the derivation that finds the conserved quantities
    scene: bool = False  # also evaluate the sketch's geometry without figures (for Trajectory.plot())
    units: dict[str, str] | None = None  # unit of a coordinate, "t", "length", "force", "energy" for the axes


@dataclass(frozen=True)
class SimulationResult:
    """A finished run: the text summary, the requested tables and figures (PNG/GIF bytes)."""

    source: str
    slug: str
    name: str
    summary: str
    tables: dict[str, str | bytes]
    figures: dict[str, bytes]
    trajectory: Trajectory
    warnings: tuple[str, ...] = ()  # about the file (units missing), for the command line to show
    scene: Scene | None = None  # the numeric.scene.Scene of the run's rods, surfaces and wires (None without particles)


def _scene(form: Any, parameters: Any, trajectory: Any) -> Any:
    """What the sketch draws (``mechanics/geometry/shapes.py``: rods, surfaces, wires, strings, springs, bodies and the
    forces as arrows) along the trajectory."""
    from lagsolve.mechanics.geometry.shapes import sketch
    from lagsolve.numeric.scene_shapes import evaluate

    return evaluate(sketch(form), form.problem, parameters, trajectory)


def run_simulation(form: Any, conserved: Any, options: SimulationOptions, progress: Progress | None = None,
                   note: str = "", chart: Any = None, chart_note: str = "", energy_note: str = "") -> SimulationResult:
    """Bind ``form`` (a :class:`~lagsolve.mechanics.equations.matrix_form.MatrixForm`) to numbers, integrate,
    and build the requested tables and figures. ``conserved`` maps names to expressions whose
    drift is reported (the energy is conserved exactly when it has an ``energy``; ``energy_note`` says
    why not); ``note`` is appended to the summary. ``chart`` (a
    :class:`~lagsolve.mechanics.analysis.minimal_chart.MinimalChart`) lets the run integrate in minimal
    coordinates; ``chart_note`` says why there is none.

    Raises
    ------
    SpecError
        Missing values, an end time, or initial values that violate the constraints.
    SimulationError
        The integration failed.
    """
    from lagsolve.files import safe_slug
    from lagsolve.numeric.system import bind
    from lagsolve.render import trajectory as table

    problem = form.problem
    if options.coordinates not in tuple(Coordinates):
        raise ValueError(f"unknown coordinates option {options.coordinates!r}")
    minimal = options.coordinates == Coordinates.MINIMAL
    system = bind(form, options.values, conserved, chart if minimal else None, energy_note)
    if minimal and chart is None and chart_note and form.constraints:
        note = f"  not in minimal coordinates: {chart_note}\n" + note
    trajectory = _integrate(system, problem, options, minimal, progress)
    units = _column_units(form)
    tables: dict[str, str | bytes] = {}
    if "csv" in options.tables:
        tables["csv"] = table.to_csv(trajectory, units)
    if "npz" in options.tables:
        tables["npz"] = table.to_npz(trajectory)
    # what the sketch draws (a classification and a few compiled shapes), for figures or on request
    wanted = options.plots or options.animate or options.scene
    scene = _scene(form, system.parameters, trajectory) if wanted else None
    axis_units = {**(options.units or {}), **units}  # the file's units win over options.units
    figures = _figures(problem, trajectory, options, scene, axis_units)
    return SimulationResult(problem.source, safe_slug(problem.source), problem.name,
                            table.summary(trajectory, problem.name) + note, tables, figures, trajectory, scene=scene)


def _t_end(problem: Any, options: SimulationOptions) -> float:
    """The end time: the option's, else the file's."""
    from lagsolve.errors import Issue, SpecError

    spec = problem.simulation
    t_end = options.t_end if options.t_end is not None else (spec.t_end if spec else None)
    if t_end is None:
        raise SpecError([Issue(problem.source, 0, "simulation.t_end", "no end time",
                               "give simulation.t_end in the file or --t-end")])
    return t_end


def _initial_state(system: Any, problem: Any, options: SimulationOptions) -> tuple[Any, Any]:
    """q and q̇ at the start: the file's initial values, then the options', completed onto the constraints."""
    from lagsolve.numeric.initial import complete_initial

    spec = problem.simulation
    given = {**(spec.initial if spec else {}), **options.initial}
    from_file = "simulation.initial" if spec and spec.initial else ""
    field = " and ".join(f for f in (from_file, "--initial" if options.initial else "") if f) or "simulation.initial"
    line = problem.lines.get("simulation.initial", problem.lines.get("simulation", 0)) if from_file else 0
    return complete_initial(system, given, problem.source, line=line, field=field)


def _integrate(system: Any, problem: Any, options: SimulationOptions, minimal: bool,
               progress: Progress | None) -> Trajectory:
    """The run, each setting from the options, else the file, else its default."""
    import numpy as np

    from lagsolve.numeric.integrate import integrate_motion

    t_end = _t_end(problem, options)
    q0, qd0 = _initial_state(system, problem, options)
    spec = problem.simulation
    return integrate_motion(
        system, q0, qd0, t_end,
        samples=options.samples or (spec.samples if spec and spec.samples else 1001),
        method=options.method or (spec.method if spec and spec.method else DEFAULT_METHOD),
        rtol=options.rtol or (spec.rtol if spec and spec.rtol else 1e-10),
        atol=options.atol or (spec.atol if spec and spec.atol else 1e-12),
        max_step=options.max_step or np.inf,
        after_release=options.after_release,
        minimal=minimal,
        progress=progress(t_end) if progress is not None else None,
    )


def _column_units(form: Any) -> dict[str, str]:
    """The unit of each table column (none when the file declares no units)."""
    problem = form.problem
    if not problem.has_units:
        return {}
    from lagsolve.mechanics.units.result_units import column_units

    units: dict[str, str] = column_units(problem, form.model.kinetic)
    force = next((u for k, u in units.items() if k.startswith(("F_", "N_"))), None)
    units.update({f"friction_{f.name}": force for f in problem.friction if force})
    return units


def _figures(problem: Any, trajectory: Any, options: SimulationOptions, scene: Any,
             axis_units: dict[str, str]) -> dict[str, bytes]:
    """The requested figures and animation, as PNG and GIF bytes by name."""
    figures: dict[str, bytes] = {}
    if not (options.plots or options.animate):
        return figures
    from lagsolve.render import plots
    from lagsolve.render.notation import Notation

    notation = Notation([c.name for c in problem.coordinates])
    labels = {c.name: notation.latex(c.symbol) for c in problem.coordinates}
    if options.plots:
        for key, figure in plots.figures(trajectory, problem.name, labels, scene=scene, units=axis_units).items():
            figures[key] = plots.png_bytes(figure)
    if options.animate and (trajectory.particles or scene):
        figures["animation"] = plots.animation_gif(trajectory, problem.name, scene=scene, units=axis_units)
    return figures


def simulate_form(form: MatrixForm, options: SimulationOptions, progress: Progress | None = None) -> SimulationResult:
    """A run from the matrix form alone: the conserved quantities to monitor and the minimal coordinates come
    from cheap criteria on the matrix form (:func:`lagsolve.mechanics.analysis.analyse.monitored`, the functions
    derive uses), never from the symbolic solve or the analysis of equilibria."""
    from lagsolve.mechanics.analysis.analyse import monitored

    conserved, chart, chart_note, energy_note = monitored(form, options.analysis_timeout)
    return run_simulation(form, conserved, options, progress, "", chart, chart_note, energy_note)


def simulate_derivation(derivation: Derivation, options: SimulationOptions,
                        progress: Progress | None = None) -> SimulationResult:
    """A run from a finished derivation: it monitors what the derivation's analysis found (without an analysis,
    as :func:`simulate_form`).

    Raises
    ------
    SpecError
        The derivation has no matrix form (and the errors of :func:`run_simulation`).
    """
    from lagsolve.errors import Issue, SpecError
    from lagsolve.mechanics.analysis.minimal_chart import minimal_chart

    if derivation.form is None:
        raise SpecError([Issue(derivation.problem.source, 0, "", "this derivation has no matrix form to simulate")])
    if derivation.analysis is None:
        return simulate_form(derivation.form, options, progress)
    chart, chart_note = minimal_chart(derivation.analysis, derivation.model)
    return run_simulation(derivation.form, derivation.conserved or {}, options, progress, chart=chart,
                          chart_note=chart_note, energy_note=derivation.analysis.conservation.energy.reason())
