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
    from lagsolve.mechanics.matrix_form import MatrixForm
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


def _scene(problem: Any, parameters: Any, trajectory: Any) -> Any:
    """The problem's rods, surfaces and wires (``mechanics/geometry.py``) along the trajectory."""
    from lagsolve.mechanics.geometry import geometry
    from lagsolve.numeric.scene import evaluate

    return evaluate(geometry(problem), problem, parameters, trajectory.t, trajectory.q, trajectory.qd,
                    trajectory.positions)


def run_simulation(form: Any, conserved: Any, options: SimulationOptions, progress: Progress | None = None,
                   note: str = "", chart: Any = None, chart_note: str = "", energy_note: str = "") -> SimulationResult:
    """Bind ``form`` (a :class:`~lagsolve.mechanics.matrix_form.MatrixForm`) to numbers, integrate,
    and build the requested tables and figures. ``conserved`` maps names to expressions whose
    drift is reported (the energy is conserved exactly when it has an ``energy``; ``energy_note`` says
    why not); ``note`` is appended to the summary. ``chart`` (a
    :class:`~lagsolve.mechanics.minimal_chart.MinimalChart`) lets the run integrate in minimal
    coordinates; ``chart_note`` says why there is none.

    Raises
    ------
    SpecError
        Missing values, an end time, or initial values that violate the constraints.
    SimulationError
        The integration failed.
    """
    import numpy as np

    from lagsolve.errors import Issue, SpecError
    from lagsolve.numeric.initial import complete_initial
    from lagsolve.numeric.integrate import integrate_motion
    from lagsolve.numeric.system import bind
    from lagsolve.render import trajectory as table

    problem = form.problem
    spec = problem.simulation
    source = problem.source
    if options.coordinates not in tuple(Coordinates):
        raise ValueError(f"unknown coordinates option {options.coordinates!r}")
    minimal = options.coordinates == Coordinates.MINIMAL
    system = bind(form, options.values, conserved, chart if minimal else None, energy_note)
    if minimal and chart is None and chart_note and form.constraints:
        note = f"  not in minimal coordinates: {chart_note}\n" + note
    t_end = options.t_end if options.t_end is not None else (spec.t_end if spec else None)
    if t_end is None:
        raise SpecError([Issue(source, 0, "simulation.t_end", "no end time",
                               "give simulation.t_end in the file or --t-end")])
    given = {**(spec.initial if spec else {}), **options.initial}
    from_file = "simulation.initial" if spec and spec.initial else ""
    field = " and ".join(f for f in (from_file, "--initial" if options.initial else "") if f) or "simulation.initial"
    line = problem.lines.get("simulation.initial", problem.lines.get("simulation", 0)) if from_file else 0
    q0, qd0 = complete_initial(system, given, source, line=line, field=field)
    trajectory = integrate_motion(
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
    name = problem.name
    tables: dict[str, str | bytes] = {}
    units: dict[str, str] = {}
    if problem.has_units:
        from lagsolve.mechanics.result_units import column_units

        units = column_units(problem, form.model.kinetic)
        force = next((u for k, u in units.items() if k.startswith(("F_", "N_"))), None)
        units.update({f"friction_{f.name}": force for f in problem.friction if force})
    axis_units = {**(options.units or {}), **units}  # the file's units win over options.units
    if "csv" in options.tables:
        tables["csv"] = table.to_csv(trajectory, units)
    if "npz" in options.tables:
        tables["npz"] = table.to_npz(trajectory)
    figures: dict[str, bytes] = {}
    # what the sketch draws (a classification and a few compiled shapes), for figures or on request
    wanted = options.plots or options.animate or options.scene
    scene = _scene(problem, system.parameters, trajectory) if trajectory.particles and wanted else None
    if options.plots or options.animate:
        from lagsolve.render import plots
        from lagsolve.render.notation import Notation

        notation = Notation([c.name for c in problem.coordinates])
        labels = {c.name: notation.latex(c.symbol) for c in problem.coordinates}
        if options.plots:
            for key, figure in plots.figures(trajectory, name, labels, scene=scene, units=axis_units).items():
                figures[key] = plots.png_bytes(figure)
        if options.animate and trajectory.particles:
            figures["animation"] = plots.animation_gif(trajectory, name, scene=scene, units=axis_units)
    from lagsolve.files import safe_slug

    return SimulationResult(source, safe_slug(source), name, table.summary(trajectory, name) + note, tables,
                            figures, trajectory, scene=scene)


def simulate_form(form: MatrixForm, options: SimulationOptions, progress: Progress | None = None) -> SimulationResult:
    """A run from the matrix form alone: the conserved quantities to monitor and the minimal coordinates come
    from cheap criteria on the matrix form (:func:`lagsolve.mechanics.analysis.monitored`, the functions
    derive uses), never from the symbolic solve or the analysis of equilibria."""
    from lagsolve.mechanics.analysis import monitored

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
    from lagsolve.mechanics.minimal_chart import minimal_chart

    if derivation.form is None:
        raise SpecError([Issue(derivation.problem.source, 0, "", "this derivation has no matrix form to simulate")])
    if derivation.analysis is None:
        return simulate_form(derivation.form, options, progress)
    chart, chart_note = minimal_chart(derivation.analysis, derivation.model)
    return run_simulation(derivation.form, derivation.conserved or {}, options, progress, chart=chart,
                          chart_note=chart_note, energy_note=derivation.analysis.conservation.energy.reason())
