"""Library entry points the command line calls: one function per command.

Nothing here prints, exits or writes files; results come back as data.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lagsolve import ranges
from lagsolve.app.simulation import Progress, SimulationOptions, SimulationResult, simulate_derivation, simulate_form
from lagsolve.check.status import Status
from lagsolve.files import safe_slug
from lagsolve.render.formats import DEFAULT_FORMATS, FORMATS

if TYPE_CHECKING:
    from lagsolve.mechanics.derivation import Derivation
    from lagsolve.problem.schema import Problem

DEFAULT_TIMEOUT = 120.0


@dataclass(frozen=True)
class Reports:
    """Rendered output of one problem: ``outputs`` maps a format ("md", "tex", "json") to text;
    ``files`` holds figures the reports refer to (file name → PNG bytes), to be written beside them."""

    source: str
    slug: str
    name: str
    summary: str
    outputs: dict[str, str]
    files: dict[str, bytes] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()  # each a sentence: missing units, "not completed: <stage note>"


FIGURE_CAPTIONS = {
    "sketch": "The system at the start, drawn from the problem, with its forces of constraint and friction as arrows",
    "path": "Paths in space, with the constraint curve where there is one",
    "coordinates": "Coordinates against time",
    "phase": "Phase portraits",
    "forces": "Multipliers and magnitudes of the forces of constraint",
    "conservation": "Drift of the conserved quantities and the constraint residual",
}


#: the share of a derivation's CPU budget its stages get; the rest is left for rendering the reports
STAGE_SHARE = 0.8

#: a derivation whose pickle is at most this many bytes comes back from its child to be rendered by the command's
#: own process, which imports the renderers while the child derives (the start-up of one command: 0.08 s off the
#: longer path). Its reports are quick (the largest shipped derivation, 44 kB, renders in 0.27 s); a larger one,
#: and one with a simulation, is rendered in the child, under the budget.
RENDER_HERE = 64 * 1024


@dataclass(frozen=True)
class _Derived:
    """A derivation sent back from its child, pickled (:func:`lagsolve.app.budget.pickled_within`), to be rendered
    by the parent."""

    blob: bytes


def _derive_and_render(problem: Problem, formats: tuple[str, ...], templates: Path | None,
                       simulate: SimulationOptions | None = None,
                       budget: float = DEFAULT_TIMEOUT) -> tuple[str, dict[str, str], dict[str, bytes]] | _Derived:
    """The reports of ``problem`` (in the budgeted child), or, for a small derivation without a simulation, the
    derivation itself to be rendered by the parent (:data:`RENDER_HERE`)."""
    from lagsolve.app.budget import pickled_within, report_partial
    from lagsolve.mechanics.derivation import derive

    derivation = derive(problem, budget=budget * STAGE_SHARE, on_core=report_partial)
    blob = pickled_within(derivation, RENDER_HERE) if simulate is None else None
    if blob is not None:
        return _Derived(blob)
    return _render(derivation, formats, templates, simulate)


def _render_core(formats: tuple[str, ...], templates: Path | None, timeout: float) -> Callable[[Any, str], tuple]:
    """What the parent answers with when a derivation is stopped at its CPU limit: the core it sent, with a note
    for each later stage, which did not complete."""

    def answer(core: Any, reason: str) -> tuple[str, dict[str, str], dict[str, bytes]]:
        from lagsolve.mechanics.derivation import core as core_of

        note = (f"did not finish within the derivation's {timeout:g} s CPU budget (raise it with --timeout); "
                "the matrix form above is what was derived")
        return _render(core_of(core.form, note), formats, templates, None)

    return answer


def _render(derivation: Any, formats: tuple[str, ...], templates: Path | None,
            simulate: SimulationOptions | None) -> tuple[str, dict[str, str], dict[str, bytes]]:
    from lagsolve.render.report import render_sections, sections_summary
    from lagsolve.render.sections import build

    sections = build(derivation)  # one walk of the derivation; every output projects it

    files: dict[str, bytes] = {}
    simulation = None
    # figures are made only for a format that shows them (JSON does not)
    shown = [FORMATS[f].figures for f in formats if f in FORMATS]  # render() refuses an unknown one
    figures_shown, figures_written = any(shown), "files" in shown
    potential = _potential_figure(derivation) if figures_shown else None
    if potential is not None:
        files[potential["file"]] = potential.pop("png")
    text = sections_summary(sections)
    if simulate is not None:
        from dataclasses import replace

        run = simulate_derivation(derivation, replace(simulate, scene=True))  # the slider and the sketch draw it
        slug = safe_slug(derivation.problem.source)
        figures = []
        for key, data in run.figures.items():
            name = f"{slug}_{key}.png"
            files[name] = data
            figures.append({"file": name, "caption": FIGURE_CAPTIONS.get(key, key)})
        from lagsolve.render.trajectory import animation
        from lagsolve.render.trajectory import summary as run_summary

        simulation = {"summary": run_summary(run.trajectory, run.name, timing=False), "figures": figures,
                      "animation": animation(run.trajectory, scene=run.scene)}
        text += run.summary
    outputs = {fmt: render_sections(sections, fmt, templates, simulation, potential, files) for fmt in formats}
    if not figures_written:
        files = {}  # an HTML page carries its figures inside; JSON has none
    return text, outputs, files


def _warnings(outputs: dict[str, str], summary_text: str) -> tuple[str, ...]:
    """The stages a derivation did not complete, as read from its terminal summary (one per line)."""
    lines = summary_text.splitlines()
    if "  not completed:" not in lines:
        return ()
    return tuple("not completed: " + line.strip() for line in lines[lines.index("  not completed:") + 1:]
                 if line.startswith("    "))


def _unit_warnings(problem: Problem, options: SimulationOptions | None = None) -> tuple[str, ...]:
    """A file that declares some units but not all: the names without one (their dimensions go unchecked); and
    a value of more than a whole turn on an angle (likely degrees: :func:`~lagsolve.mechanics.units.angles.
    angle_warnings`), with a simulation's ``options`` (``--set``, ``--initial``) in place of the file's values."""
    from lagsolve.mechanics.units.angles import angle_warnings
    from lagsolve.mechanics.units.result_units import missing_units

    angles = angle_warnings(problem) if options is None else angle_warnings(problem, options.values, options.initial)
    missing = missing_units(problem)
    if not missing:
        return angles
    return (f"units: no unit declared for {', '.join(missing)}, so dimensions involving "
            f"{'it' if len(missing) == 1 else 'them'} are not checked; add 'unit:' to each (1 for a pure number)",
            *angles)


def _potential_figure(derivation: Derivation) -> dict | None:
    """The V_eff plot with its equilibria, for a problem that has an effective potential and numbers
    (simulation values and initial state) to draw it with; None otherwise."""
    problem = derivation.problem
    spec = problem.simulation
    analysis = getattr(derivation, "analysis", None)
    if spec is None or analysis is None or getattr(analysis, "effective_potential", None) is None:
        return None
    if problem.functions:  # drawing V_eff with declared functions would need their concrete forms
        return None
    from lagsolve.numeric.potential import potential_curve  # matplotlib only when there is a curve to draw
    from lagsolve.render.plots import png_bytes
    from lagsolve.render.potential_plot import potential_figure

    try:
        curve = potential_curve(derivation, dict(spec.values), initial=dict(spec.initial))
    except (ValueError, KeyError, TypeError, ZeroDivisionError, StopIteration, NameError, OverflowError):
        return None
    from lagsolve.mechanics.units.result_units import result_units

    units = result_units(problem, derivation.kinetic)
    coordinate = str(getattr(analysis.effective_potential, "coordinate", ""))
    axis_units = (None, None) if units is None else (units.coordinates.get(coordinate), units.energy)
    figure = potential_figure(curve.q, curve.v, curve.equilibria, coordinate=curve.coordinate,
                              title=f"{problem.name}: effective potential", units=axis_units)
    return {"file": f"{safe_slug(problem.source)}_effective_potential.png", "png": png_bytes(figure),
            "caption": "Effective potential with its equilibria, for the simulation's values"}


def derive_file(path: str | Path, formats: tuple[str, ...] = DEFAULT_FORMATS, *,
                templates: Path | None = None, timeout: float = DEFAULT_TIMEOUT,
                simulate: SimulationOptions | None = None) -> Reports:
    """Load, derive and render one problem file.

    Loading (validation) runs here; derivation and rendering run in a child
    process under ``timeout`` seconds (see :mod:`lagsolve.app.budget`).

    Raises
    ------
    SpecError
        The file is invalid (every problem listed), or ``timeout`` is outside its range (:mod:`lagsolve.ranges`).
    DerivationError
        The derivation failed or ran out of time.
    """
    from lagsolve.app.budget import rebuilt, run_with_budget

    ranges.check(timeout=timeout)
    loaded = _Loading(path)
    rendered = run_with_budget(_derive_and_render, (formats, templates, simulate, timeout), timeout,
                               f"the derivation of {path}", on_partial=_render_core(formats, templates, timeout),
                               first=loaded.problem_loaded, warm=_warm_once(_warm_derive), meanwhile=_warm_render)
    if isinstance(rendered, _Derived):
        rendered = _render(rebuilt(rendered.blob), formats, templates, None)
    return _reports(path, loaded.problem, rendered)


def reports_of(derivation: Derivation, path: str | Path, formats: tuple[str, ...] = DEFAULT_FORMATS, *,
               templates: Path | None = None) -> Reports:
    """The reports :func:`derive_file` gives for the file at ``path``, rendered here from its ``derivation`` made
    already (no budget, no second derivation)."""
    return _reports(path, derivation.problem, _render(derivation, formats, templates, None))


def _reports(path: str | Path, problem: Problem, rendered: tuple[str, dict[str, str], dict[str, bytes]]) -> Reports:
    text, outputs, files = rendered
    return Reports(str(path), safe_slug(path), problem.name, text, outputs, files,
                   _unit_warnings(problem) + _warnings(outputs, text))


@dataclass(frozen=True)
class Checked:
    """The check of one problem file: the verdict table and how many answers got each verdict."""

    source: str
    name: str
    table: str
    counts: dict[str, int]
    rows: tuple[dict[str, str], ...] = ()  # one per verdict (:func:`lagsolve.render.machine.verdict_rows`)
    warnings: tuple[str, ...] = ()  # about the file (units missing)

    @property
    def passed(self) -> bool:
        """True when no expected answer is a mismatch (warnings and unchecked answers pass)."""
        return self.counts.get(Status.MISMATCH, 0) == 0


def _derive_and_check(problem: Problem, budget: float = DEFAULT_TIMEOUT
                      ) -> tuple[str, dict[str, int], tuple[dict[str, str], ...]]:
    from lagsolve.check.compare import MISMATCH, OK, UNCHECKED, WARNING, check
    from lagsolve.mechanics.derivation import derive
    from lagsolve.render.checks import check_table
    from lagsolve.render.machine import verdict_rows

    report = check(derive(problem, budget=budget * STAGE_SHARE))
    return (check_table(report), {s: report.count(s) for s in (OK, WARNING, MISMATCH, UNCHECKED)},
            verdict_rows(report))


def check_file(path: str | Path, *, timeout: float = DEFAULT_TIMEOUT) -> Checked:
    """Load and derive one problem file and compare its ``expected:`` answers (:func:`lagsolve.check.compare.check`).

    Loading runs here; derivation and check run in a child process under ``timeout`` seconds.

    Raises
    ------
    SpecError
        The file is invalid (every problem listed), or ``timeout`` is outside its range (:mod:`lagsolve.ranges`).
    DerivationError
        The derivation failed or ran out of time.
    """
    from lagsolve.app.budget import run_with_budget

    ranges.check(timeout=timeout)
    loaded = _Loading(path)
    table, counts, rows = run_with_budget(_derive_and_check, (timeout,), timeout, f"the check of {path}",
                                          first=loaded.problem_loaded, warm=_warm_once(_warm_derive))
    return Checked(str(path), loaded.problem.name, table, counts, rows, _unit_warnings(loaded.problem))


#: the warm-ups this process has had a child run: the next file's warms up here instead (:func:`_warm_once`)
_WARMED: set[Callable[[], None]] = set()


class _Loading:
    """One problem file loaded *while* its budgeted child starts (:func:`lagsolve.app.budget.run_with_budget` with
    its first argument made later): the child imports what it needs (:func:`_warm_once`) as this process loads
    and validates the file, on the machine's second core. SymPy and the loader are imported here first, so that
    both processes share them."""

    def __init__(self, path: str | Path) -> None:
        from lagsolve.problem.load import load_problem

        self.path, self.load = path, load_problem
        self._problem: Problem | None = None

    @property
    def problem(self) -> Problem:
        """The problem, once :meth:`problem_loaded` has loaded it."""
        assert self._problem is not None, "problem_loaded() first"
        return self._problem

    def problem_loaded(self) -> Problem:
        """The file loaded and its units checked (raises :class:`SpecError` for an invalid one), kept for
        :attr:`problem`. The units are checked here, where pint is loaded anyway, so that the child needs none."""
        from lagsolve.mechanics.units.unit_system import units_checked

        self._problem = units_checked(self.load(self.path))
        return self._problem


def _warm_once(imports: Callable[[], None]) -> Callable[[], None] | None:
    """``imports`` for a budgeted child to run while the file is loaded, the first time; from a command's second
    file on, run here before the fork instead (None for the child), so that every later child inherits them."""
    if imports in _WARMED:
        imports()
        return None
    _WARMED.add(imports)
    return imports


def _warm_derive() -> None:
    """What a derivation's child needs besides SymPy: the mechanics and ``sympy.physics.units``, which SymPy's
    ``simplify`` imports at its first call (about 0.1 s). (The renderers are imported by the parent meanwhile,
    :func:`_warm_render`, or by the child once it has derived, for a large derivation.)"""
    import sympy.physics.units  # noqa: F401

    import lagsolve.mechanics.derivation  # noqa: F401


def _warm_render() -> None:
    """What rendering a derivation needs: imported by the command's process while the child derives."""
    import lagsolve.render.report  # noqa: F401
    import lagsolve.render.sections  # noqa: F401


def _warm_simulate() -> None:
    """What a simulation's child needs besides SymPy: the derivation and the numerical integration."""
    import lagsolve.app.simulation  # noqa: F401
    import lagsolve.mechanics.equations.matrix_form  # noqa: F401
    import lagsolve.numeric.integrate  # noqa: F401


def golden_differences(reports: Reports, folder: Path) -> list[str]:
    """Unified diffs between ``reports`` and the golden files ``folder/<slug>.<ext>``.

    A missing golden file counts as a difference (its diff says so).

    Raises
    ------
    SpecError
        A golden file is a symbolic link (not followed), a folder, unreadable or not UTF-8.
    """
    import difflib

    from lagsolve.files import read_text

    diffs = []
    for fmt, text in reports.outputs.items():
        path = Path(folder) / f"{reports.slug}.{fmt}"
        expected = read_text(path, option="--golden")
        if expected is None:
            diffs.append(f"--- {path} (missing; create it with --update-golden)\n")
            continue
        if expected != text:
            diffs.append("".join(difflib.unified_diff(
                expected.splitlines(keepends=True), text.splitlines(keepends=True),
                fromfile=str(path), tofile=f"{reports.source} ({fmt}, now)")))
    return diffs


def _simulate(problem: Problem, options: SimulationOptions, progress: Progress | None) -> SimulationResult:
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    return simulate_form(matrix_form(problem, display=False), options, progress)


def simulate_file(path: str | Path, options: SimulationOptions, *, timeout: float = 600.0,
                  progress: Progress | None = None) -> SimulationResult:
    """Load, derive and simulate one problem file (derivation and run in a budgeted child process).

    ``progress``, when given, is called with ``t_end`` in the child and returns a callable
    taking the current time (the command line shows a progress bar with it).

    Raises
    ------
    SpecError
        The file or an option is invalid (unknown parameter, missing value, bad initial state, ``timeout``
        outside its range).
    DerivationError, SimulationError
        The derivation or the integration failed, or ran out of time.
    """
    from dataclasses import replace

    from lagsolve.app.budget import run_with_budget

    ranges.check(timeout=timeout)
    loaded = _Loading(path)
    result = run_with_budget(_simulate, (options, progress), timeout, f"the simulation of {path}",
                             first=loaded.problem_loaded, warm=_warm_once(_warm_simulate))
    return replace(result, warnings=_unit_warnings(loaded.problem, options))
