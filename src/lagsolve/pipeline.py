"""Library entry points the command line calls: one function per command.

Nothing here prints, exits or writes files; results come back as data.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

DEFAULT_TIMEOUT = 120.0


@dataclass(frozen=True)
class Reports:
    """Rendered output of one problem: ``outputs`` maps a format ("md", "tex", "json") to text."""

    source: str
    slug: str
    name: str
    summary: str
    outputs: dict[str, str]


def safe_slug(path: str | Path) -> str:
    """A file-name-safe stem for output names: ``problems/My bead.yaml`` → ``My_bead``."""
    stem = Path(path).name
    stem = stem.rsplit(".", 1)[0] if "." in stem else stem
    slug = re.sub(r"[^A-Za-z0-9_-]+", "_", stem).strip("_")
    return slug or "problem"


def _derive_and_render(problem: object, formats: tuple[str, ...], templates: Path | None) -> tuple[str, dict[str, str]]:
    from lagsolve.mechanics.derivation import derive
    from lagsolve.render.report import render, summary

    derivation = derive(problem)  # type: ignore[arg-type]
    return summary(derivation), {fmt: render(derivation, fmt, templates) for fmt in formats}


def derive_file(path: str | Path, formats: tuple[str, ...] = ("md", "tex", "json"), *,
                templates: Path | None = None, timeout: float = DEFAULT_TIMEOUT) -> Reports:
    """Load, derive and render one problem file.

    Loading (validation) runs here; derivation and rendering run in a child
    process under ``timeout`` seconds (see :mod:`lagsolve.budget`).

    Raises
    ------
    SpecError
        The file is invalid (every problem listed).
    DerivationError
        The derivation failed or ran out of time.
    """
    from lagsolve.budget import run_with_budget
    from lagsolve.problem.load import load_problem

    problem = load_problem(path)
    text, outputs = run_with_budget(_derive_and_render, (problem, formats, templates), timeout,
                                    f"the derivation of {path}")
    return Reports(str(path), safe_slug(path), problem.name, text, outputs)


@dataclass(frozen=True)
class Checked:
    """The check of one problem file: the verdict table and how many answers got each verdict."""

    source: str
    name: str
    table: str
    counts: dict[str, int]

    @property
    def passed(self) -> bool:
        """True when no expected answer is a mismatch (warnings and unchecked answers pass)."""
        return self.counts.get("mismatch", 0) == 0


def _derive_and_check(problem: object) -> tuple[str, dict[str, int]]:
    from lagsolve.check import MISMATCH, OK, UNCHECKED, WARNING, check
    from lagsolve.mechanics.derivation import derive
    from lagsolve.render.checks import check_table

    report = check(derive(problem))  # type: ignore[arg-type]
    return check_table(report), {s: report.count(s) for s in (OK, WARNING, MISMATCH, UNCHECKED)}


def check_file(path: str | Path, *, timeout: float = DEFAULT_TIMEOUT) -> Checked:
    """Load and derive one problem file and compare its ``expected:`` answers (:func:`lagsolve.check.check`).

    Loading runs here; derivation and check run in a child process under ``timeout`` seconds.

    Raises
    ------
    SpecError
        The file is invalid (every problem listed).
    DerivationError
        The derivation failed or ran out of time.
    """
    from lagsolve.budget import run_with_budget
    from lagsolve.problem.load import load_problem

    problem = load_problem(path)
    table, counts = run_with_budget(_derive_and_check, (problem,), timeout, f"the check of {path}")
    return Checked(str(path), problem.name, table, counts)


def golden_differences(reports: Reports, folder: Path) -> list[str]:
    """Unified diffs between ``reports`` and the golden files ``folder/<slug>.<ext>``.

    A missing golden file counts as a difference (its diff says so).
    """
    import difflib

    diffs = []
    for fmt, text in reports.outputs.items():
        path = Path(folder) / f"{reports.slug}.{fmt}"
        try:
            expected = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            diffs.append(f"--- {path} (missing; create it with --update-golden)\n")
            continue
        if expected != text:
            diffs.append("".join(difflib.unified_diff(
                expected.splitlines(keepends=True), text.splitlines(keepends=True),
                fromfile=str(path), tofile=f"{reports.source} ({fmt}, now)")))
    return diffs


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
    after_release: str = "stop"
    tables: tuple[str, ...] = ()  # "csv", "npz"
    plots: bool = False
    animate: bool = False
    analysis_timeout: float = 60.0  # budget of the derivation that finds the conserved quantities


@dataclass(frozen=True)
class SimulationResult:
    """A finished run: the text summary, the requested tables and figures (PNG/GIF bytes)."""

    source: str
    slug: str
    name: str
    summary: str
    tables: dict[str, str | bytes]
    figures: dict[str, bytes]
    trajectory: object


def _simulate(problem: object, options: SimulationOptions, progress: object) -> SimulationResult:
    import numpy as np

    from lagsolve.budget import run_with_budget
    from lagsolve.errors import Issue, LagsolveError, SpecError
    from lagsolve.mechanics.matrix_form import matrix_form
    from lagsolve.numeric.initial import complete_initial
    from lagsolve.numeric.integrate import integrate_motion
    from lagsolve.numeric.system import bind
    from lagsolve.render import trajectory as table

    form = matrix_form(problem)  # type: ignore[arg-type]
    problem = form.problem
    spec = problem.simulation
    source = problem.source
    # conserved quantities come from the full derivation (analysis); it gets a budget of its own,
    # so that a system too large to solve symbolically can still be simulated from its matrix form
    conserved, note = None, ""
    try:
        conserved = run_with_budget(_conserved, (problem,), options.analysis_timeout, "the analysis")
    except LagsolveError as error:
        note = f"  conserved quantities not checked: {error}\n"
    system = bind(form, options.values, conserved)
    t_end = options.t_end if options.t_end is not None else (spec.t_end if spec else None)
    if t_end is None:
        raise SpecError([Issue(source, 0, "simulation.t_end", "no end time",
                               "give simulation.t_end in the file or --t-end")])
    given = {**(spec.initial if spec else {}), **options.initial}
    q0, qd0 = complete_initial(system, given, source)
    trajectory = integrate_motion(
        system, q0, qd0, t_end,
        samples=options.samples or (spec.samples if spec and spec.samples else 1001),
        method=options.method or (spec.method if spec and spec.method else "DOP853"),
        rtol=options.rtol or (spec.rtol if spec and spec.rtol else 1e-10),
        atol=options.atol or (spec.atol if spec and spec.atol else 1e-12),
        max_step=options.max_step or np.inf,
        after_release=options.after_release,
        progress=progress(t_end) if callable(progress) else None,
    )
    name = problem.name
    tables: dict[str, str | bytes] = {}
    if "csv" in options.tables:
        tables["csv"] = table.to_csv(trajectory)
    if "npz" in options.tables:
        tables["npz"] = table.to_npz(trajectory)
    figures: dict[str, bytes] = {}
    if options.plots or options.animate:
        from lagsolve.render import plots
        from lagsolve.render.notation import Notation

        notation = Notation([c.name for c in problem.coordinates])
        labels = {c.name: notation.latex(c.symbol) for c in problem.coordinates}
        curve = None
        if system.curve is not None and system.curve_coordinate is not None:
            k, fn = system.curve_coordinate, system.curve

            def shape(values: np.ndarray) -> np.ndarray:
                q = np.array(q0, dtype=float)
                rows = []
                for u in values:
                    q[k] = u
                    rows.append(fn(0.0, q, qd0, system.parameters))
                return np.array(rows)

            curve = (k, shape)
        if options.plots:
            for key, figure in plots.figures(trajectory, name, labels, curve).items():
                figures[key] = plots.png_bytes(figure)
        if options.animate and trajectory.particles:
            figures["animation"] = plots.animation_gif(trajectory, name)
    return SimulationResult(source, safe_slug(source), name, table.summary(trajectory, name) + note, tables,
                            figures, trajectory)


def _conserved(problem: object) -> dict | None:
    from lagsolve.mechanics.derivation import derive

    return derive(problem).conserved  # type: ignore[arg-type]


def simulate_file(path: str | Path, options: SimulationOptions, *, timeout: float = 600.0,
                  progress: object = None) -> SimulationResult:
    """Load, derive and simulate one problem file (derivation and run in a budgeted child process).

    ``progress``, when given, is called with ``t_end`` in the child and returns a callable
    taking the current time (the command line shows a progress bar with it).

    Raises
    ------
    SpecError
        The file or an option is invalid (unknown parameter, missing value, bad initial state).
    DerivationError, SimulationError
        The derivation or the integration failed, or ran out of time.
    """
    from lagsolve.budget import run_with_budget
    from lagsolve.problem.load import load_problem

    problem = load_problem(path)
    return run_with_budget(_simulate, (problem, options, progress), timeout, f"the simulation of {path}")
