"""The ``lagsolve`` command: a thin shell over :mod:`lagsolve.app.pipeline`.

Parses options, calls one library function, shows or writes the result, and
maps errors to exit codes: 0 success, 1 the computation failed, 2 invalid input.
Heavy libraries (SymPy, matplotlib) are imported only inside commands, so
``lagsolve --help`` stays fast.
"""

from __future__ import annotations

import codecs
import gc
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import click

from lagsolve import __version__
from lagsolve.errors import LagsolveError, SpecError
from lagsolve.problem.methods import DEFAULT as DEFAULT_METHOD
from lagsolve.problem.methods import EXPLICIT, METHODS
from lagsolve.ranges import RANGES
from lagsolve.render.formats import DEFAULT_FORMATS, REGISTRY

# numeric libraries run single-threaded: the budgets count the process's CPU time, which idle-spinning BLAS
# threads would otherwise inflate (and the arrays here are small); set before NumPy is first imported
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")
# SymPy's own caches (each function's LRU, ``sort_key`` among them) hold 1000 entries by default; a large system's
# report sorts the terms and factors of thousands of expressions, which a larger cache sorts once (read by SymPy
# when it is first imported, after this)
os.environ.setdefault("SYMPY_CACHE_SIZE", "50000")

if TYPE_CHECKING:
    from lagsolve.app.pipeline import Reports

_F = TypeVar("_F", bound=Callable[..., Any])

#: each format's file extension (the registry: :mod:`lagsolve.render.formats`)
EXTENSIONS = {f.name: f.extension for f in REGISTRY}

#: the collector's thresholds in the program (:func:`run`): a young collection every 10 000 allocations, not 700;
#: deriving takes 5-10 % less CPU (the bead 0.50 → 0.45 s; 20 shipped problems in one process 12.9 → 11.9 s; the
#: tests run with the same, tests/conftest.py)
COLLECTOR = (10_000, 10, 10)


class Number(click.ParamType):
    """Every numeric option's type: a finite number in the option's range (:data:`lagsolve.ranges.RANGES`),
    else a usage error (exit 2) that gives the range. NaN and infinity are never accepted."""

    def __init__(self, key: str) -> None:
        self.key = key
        self.range = RANGES[key]
        self.name = "integer" if self.range.integer else "float"

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> int | float:
        number: object = value
        if isinstance(value, str):
            try:
                number = int(value.strip(), 10) if self.range.integer else float(value)
            except ValueError:
                self.fail(f"expected {self.range.describe()}, found {value!r}", param, ctx)
        fault = self.range.fault(number)
        if fault is not None:
            self.fail(fault, param, ctx)
        return number  # type: ignore[return-value]  # fault() is None only for an int or a float


def _number(*names: str, key: str, help: str = "", **kwargs: Any) -> Callable[[_F], _F]:
    """``click.option(*names)`` of the :class:`Number` ``key``, its range said at the end of its help."""
    accepted = f"[{RANGES[key].describe()}]"
    return click.option(*names, type=Number(key), help=f"{help} {accepted}" if help else accepted, **kwargs)


def _fail(error: LagsolveError) -> int:
    if isinstance(error, SpecError):
        for issue in error.issues:
            click.echo(f"error: {issue}", err=True)
        return 2
    click.echo(f"error: {error}", err=True)
    return 1


def _sweep_warnings(file: Path, frame: Any) -> tuple[str, ...]:
    """A sweep's angle warnings: its swept values of an angle, and the file's values it does not sweep
    (:func:`lagsolve.mechanics.units.angles.angle_warnings`)."""
    from lagsolve.mechanics.units.angles import angle_warnings
    from lagsolve.problem.load import load_problem

    swept = {name: frame[name].tolist() for name in frame.attrs.get("swept", ()) if name in frame}
    return angle_warnings(load_problem(file), swept=swept)


def _warn(source: str, warning: str) -> None:
    """A warning about the file ``source`` on stderr, prefixed with the file unless it names it (with its line)."""
    _note(f"warning: {warning}" if warning.startswith(f"{source}:") else f"warning: {source}: {warning}", err=True)


def _note(text: str, *, err: bool = False, level: int = 1, nl: bool = True) -> None:
    """Show ``text`` unless --quiet (level 1), or only with --verbose (level 2)."""
    context = click.get_current_context(silent=True)
    root = context.find_root() if context is not None else None
    verbosity = root.obj.get("verbosity", 1) if root is not None and isinstance(root.obj, dict) else 1
    if verbosity >= level:
        click.echo(text, err=err, nl=nl)


def _golden(reports: Reports, folder: Path, update: bool) -> int:
    from lagsolve.app.pipeline import golden_differences
    from lagsolve.files import write_file

    if update:
        for fmt, text in reports.outputs.items():
            _note(f"  wrote {write_file(folder, f'{reports.slug}.{fmt}', text, option='--update-golden')}")
        return 0
    diffs = golden_differences(reports, folder)
    for diff in diffs:
        click.echo(diff, nl=False)
    verdict = "differs from" if diffs else "matches"
    _note(f"{reports.source}: {verdict} the golden files in {folder}")
    return 1 if diffs else 0


def _ascii_fallback(error: UnicodeError) -> tuple[str, int]:
    from lagsolve.render.notation import ascii_fallback  # imported only when needed: it loads SymPy

    return ascii_fallback(error)


def _ascii_where_needed() -> None:
    """A terminal whose encoding cannot show ẍ, λ or ✓ (cp1252, ASCII) gets x_ddot, lambda and +
    instead of a UnicodeEncodeError."""
    codecs.register_error("lagsolve-ascii", _ascii_fallback)
    for stream in (sys.stdout, sys.stderr):
        encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
        if encoding != "utf8" and hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="lagsolve-ascii")


class _Commands(click.Group):
    """The command group: Ctrl-C (SIGINT) during any command ends it with one line and exit 130 (128 + SIGINT),
    after the command's own clean-up (child processes, workers) has run, instead of click's "Aborted!"."""

    def invoke(self, ctx: click.Context) -> object:
        try:
            return super().invoke(ctx)
        except KeyboardInterrupt:
            click.echo("interrupted", err=True)
            ctx.exit(130)


@click.group(cls=_Commands, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="lagsolve")
@click.option("-q", "--quiet", is_flag=True, help="Show only errors and the output asked for (no summaries, "
                                                  "'wrote' lines or warnings).")
@click.option("-v", "--verbose", is_flag=True, help="Also say on stderr what is done, file by file.")
@click.pass_context
def main(context: click.Context, quiet: bool, verbose: bool) -> None:
    """Lagrangian mechanics from a YAML problem file: equations of motion,
    multipliers, forces of constraint, and worked-solution reports."""
    if quiet and verbose:
        raise click.UsageError("--quiet and --verbose exclude each other")
    context.obj = {"verbosity": 0 if quiet else 2 if verbose else 1}
    _ascii_where_needed()


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@_number("--timeout", key="timeout", default=120.0, show_default=True,
         help="CPU seconds allowed for each derivation and check.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "junit"]), default="text", show_default=True,
              help="json: one array of verdicts per file; junit: JUnit XML for CI (a mismatch is a failure).")
def check(files: tuple[Path, ...], timeout: float, fmt: str) -> None:
    """Compare the expected answers in each problem FILE with the derivation.

    ✓ ok, ! holds only in part (warning), ✗ mismatch (exit 1), – not checked.

    \b
    lagsolve check problems/*.yaml
    lagsolve check problems/*.yaml --format junit > check.xml
    """
    from lagsolve.app.pipeline import check_file
    from lagsolve.render.machine import Unchecked, checks_json, checks_junit

    status = 0
    results: list[object] = []
    for path in files:
        _note(f"lagsolve: checking {path}", err=True, level=2)
        try:
            checked = check_file(path, timeout=timeout)
        except LagsolveError as error:
            code = _fail(error)
            status = max(status, code)
            results.append(Unchecked(str(path), str(error), code))
            continue
        results.append(checked)
        for warning in checked.warnings:
            _warn(checked.source, warning)
        if fmt == "text":
            click.echo(checked.table, nl=False)
        if not checked.passed:
            status = max(status, 1)
    if fmt != "text":
        click.echo((checks_json if fmt == "json" else checks_junit)(results), nl=False)
    sys.exit(status)


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("-o", "--output", type=click.Path(path_type=Path),
              help="Output folder (default out/), or a file name when one file and one --format are given.")
@click.option("--format", "fmts", type=click.Choice([*EXTENSIONS, "jsonl"]), multiple=True,
              help="Only this format; printed to stdout unless -o is given. json with several files prints one "
                   "array; jsonl prints one result per line. Repeat it for several formats (with -o DIR, as "
                   "without --format: DIR/<problem>/).")
@_number("--timeout", key="timeout", default=120.0, show_default=True,
         help="CPU seconds allowed for each derivation; a stage that runs out of its share is named "
              "and the rest is still given.")
@click.option("--templates", type=click.Path(file_okay=False, exists=True, path_type=Path),
              help="Folder with markdown/ and latex/ templates that override the packaged ones.")
@click.option("--golden", type=click.Path(file_okay=False, path_type=Path),
              help="Compare the reports with DIR/<problem>.<ext>; exit 1 with a diff when any differs.")
@click.option("--update-golden", is_flag=True, help="With --golden: write the golden files instead.")
@click.option("--simulate", "with_simulation", is_flag=True,
              help="Also simulate (the file's simulation block) and embed the figures in the reports.")
def derive(files: tuple[Path, ...], output: Path | None, fmts: tuple[str, ...], timeout: float,
           templates: Path | None, golden: Path | None, update_golden: bool, with_simulation: bool) -> None:
    """Derive the equations of motion of each problem FILE.

    \b
    lagsolve derive problems/bead.yaml                 # summary here, reports in out/bead/
    lagsolve derive problems/*.yaml -o reports/        # several problems at once
    lagsolve derive problems/bead.yaml --format json   # the result contract on stdout
    lagsolve derive problems/*.yaml --format jsonl     # one JSON result per line
    lagsolve derive problems/bead.yaml --format tex -o bead.tex
    lagsolve derive problems/bead.yaml --format md --format html -o reports/
    lagsolve derive problems/bead.yaml --simulate      # the report with the simulation's figures
    """
    from lagsolve.app.pipeline import SimulationOptions, derive_file

    plan = _derive_plan(files, output, fmts, golden, update_golden, with_simulation)
    texts: list[str] = []
    status = 0
    for path in files:
        _note(f"lagsolve: deriving {path}", err=True, level=2)
        try:
            simulate = SimulationOptions(values={}, initial={}, plots=True) if with_simulation else None
            reports = derive_file(path, plan.formats, templates=templates, timeout=timeout, simulate=simulate)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
        for warning in reports.warnings:
            _warn(reports.source, warning)
        status = max(status, _deliver(reports, plan, output, golden, update_golden, texts))
    if plan.stream:
        from lagsolve.render.machine import json_stream

        click.echo(json_stream(texts, lines=plan.fmt == "jsonl"), nl=False)
    sys.exit(status)


@dataclass(frozen=True)
class _DerivePlan:
    """Where ``derive``'s reports go: ``fmt`` the one format asked for (None for none or several), ``formats``
    those rendered, ``stream`` JSON to stdout (jsonl, or json of several files), ``single_file`` -o names a file."""

    fmt: str | None
    formats: tuple[str, ...]
    stream: bool
    single_file: bool


def _derive_plan(files: tuple[Path, ...], output: Path | None, fmts: tuple[str, ...], golden: Path | None,
                 update_golden: bool, with_simulation: bool) -> _DerivePlan:
    """The options of ``derive`` read together; a combination that cannot be honoured is a usage error."""
    if update_golden and golden is None:
        raise click.UsageError("--update-golden needs --golden DIR")
    chosen = tuple(dict.fromkeys(fmts))
    fmt = _one_format(chosen, output, golden)
    formats = ("json",) if fmt == "jsonl" else (fmt,) if fmt else chosen or DEFAULT_FORMATS
    stream = fmt == "jsonl" or (fmt == "json" and output is None and golden is None and len(files) > 1)
    return _DerivePlan(fmt, formats, stream, _single_file(files, output, fmt, with_simulation))


def _one_format(chosen: tuple[str, ...], output: Path | None, golden: Path | None) -> str | None:
    """The one format asked for (None for none or several), when the formats can go where they are sent."""
    if len(chosen) > 1 and "jsonl" in chosen:
        raise click.UsageError("--format jsonl prints to stdout alone; give it without other formats")
    if len(chosen) > 1 and output is None and golden is None:
        raise click.UsageError(f"several formats ({', '.join(chosen)}) are written as files: give -o DIR")
    fmt = chosen[0] if len(chosen) == 1 else None
    if fmt == "jsonl" and (output is not None or golden is not None):
        raise click.UsageError("--format jsonl prints to stdout; redirect it, or use --format json with -o")
    return fmt


def _single_file(files: tuple[Path, ...], output: Path | None, fmt: str | None, with_simulation: bool) -> bool:
    """Whether -o names the one file to write; a usage error when the files' reports cannot all be written."""
    from lagsolve.files import safe_slug

    slugs = [safe_slug(f) for f in files]
    if len(set(slugs)) != len(slugs):
        raise click.UsageError("two problem files have the same name; their reports would overwrite each other")
    if with_simulation and fmt and output is None:
        raise click.UsageError("--simulate writes figure files beside the report: give -o DIR (or no --format)")
    single_file = fmt is not None and output is not None and output.suffix == EXTENSIONS[fmt]
    if single_file and len(files) > 1:
        raise click.UsageError(f"-o {output} names one file, but {len(files)} problems were given; give a folder")
    return single_file


def _deliver(reports: Any, plan: _DerivePlan, output: Path | None, golden: Path | None, update_golden: bool,
             texts: list[str]) -> int:
    """One problem's reports to where ``plan`` sends them (the JSON stream, stdout, the golden files, the output
    folder); the exit status it asks for."""
    if plan.stream and golden is None:
        texts.append(reports.outputs["json"])
        return 0
    if plan.fmt and output is None and golden is None:
        click.echo(reports.outputs[plan.fmt], nl=False)
        return 0
    try:
        if golden is not None:
            return _golden(reports, golden, update_golden)
        _write_reports(reports, plan, output)
    except LagsolveError as error:
        return _fail(error)
    return 0


def _write_reports(reports: Any, plan: _DerivePlan, output: Path | None) -> None:
    """The reports and their figures written: to the file -o names, else to out/<problem>/ (or -o DIR)."""
    from lagsolve.files import write_file

    fmt = plan.fmt
    if plan.single_file and output is not None and fmt is not None:
        root, place = output.parent, Path()
        names = {fmt: output.name}
    else:
        root, place = output or Path("out"), Path() if fmt else Path(reports.slug)
        names = {f: str(place / f"{reports.slug}{EXTENSIONS[f]}") for f in plan.formats}
    if not fmt:
        _note(reports.summary, nl=False)
    for f, name in names.items():
        _note(f"  wrote {write_file(root, name, reports.outputs[f])}")
    for name, data in reports.files.items():
        _note(f"  wrote {write_file(root, place / name, data)}")


@main.command()
@click.argument("file", type=click.Path(path_type=Path))
@click.option("--to", "to", type=click.Choice(["python", "c", "fmu"]), default="python", show_default=True,
              help="Target: python (one NumPy module <slug>.py), c (C99 <name>.h and <name>.c, needing only libm), "
                   "fmu (an FMI 2.0 Model Exchange <name>.fmu, built with the system C compiler).")
@click.option("-o", "--output", type=click.Path(path_type=Path), default=Path("out"), show_default=True,
              help="Output folder.")
def export(file: Path, to: str, output: Path) -> None:
    """Write the equations of problem FILE as code (rhs for solve_ivp, outputs with the multipliers).

    \b
    lagsolve export problems/bead.yaml --to python -o out/
    lagsolve export problems/bead.yaml --to c -o out/
    lagsolve export problems/rotating_tube.yaml --to fmu -o out/
    """
    from lagsolve.app.export import export_file

    try:
        written = export_file(file, to, output)
    except LagsolveError as error:
        sys.exit(_fail(error))
    _note(f"lagsolve: wrote {written}", err=True)


def _assignments(pairs: tuple[str, ...], option: str) -> dict[str, float]:
    """``("g=1.62", "m=2")`` → ``{"g": 1.62, "m": 2.0}``; a bad pair is a usage error (exit 2)."""
    import math

    out: dict[str, float] = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        name = name.strip()
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not sep or not name.isidentifier() or not math.isfinite(value):
            raise click.BadParameter(f"{pair!r}: expected NAME=NUMBER with a finite number, e.g. g=9.81",
                                     param_hint=option)
        out[name] = value
    return out


def _progress_bar(t_end: float) -> Callable[[float], None]:
    """A progress bar on stderr for runs longer than about a second; silent when stderr is not a terminal."""
    from tqdm import tqdm

    bar = tqdm(total=t_end, unit="t", delay=1.0, disable=not sys.stderr.isatty(), leave=False,
               bar_format="{l_bar}{bar}| t = {n:.3g}/{total:.3g} [{elapsed}<{remaining}]")

    def update(t: float) -> None:
        bar.update(t - bar.n)
        if t >= t_end:
            bar.close()

    return update


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@_number("--t-end", key="t_end", help="End time (default: simulation.t_end).")
@click.option("--set", "values", multiple=True, metavar="NAME=VALUE", help="Parameter value (repeatable).")
@click.option("--initial", multiple=True, metavar="NAME=VALUE",
              help="Initial coordinate or velocity, e.g. x=0.5 or x_dot=0 (repeatable).")
@_number("--samples", key="samples", help="Number of output times (default 1001).")
@click.option("--method", type=click.Choice(METHODS),
              help=f"Integrator (default {DEFAULT_METHOD}; {'/'.join(m for m in METHODS if m not in EXPLICIT)} "
                   "for stiff problems).")
@_number("--rtol", key="rtol", help="Relative tolerance (default 1e-10).")
@_number("--atol", key="atol", help="Absolute tolerance (default 1e-12).")
@_number("--max-step", key="max_step", help="Largest step size.")
@click.option("--after-release", type=click.Choice(["stop", "continue"]), default="stop", show_default=True,
              help="When a unilateral constraint's force reaches zero: stop there, or go on without it.")
@click.option("--coordinates", type=click.Choice(["minimal", "full"]), default="minimal", show_default=True,
              help="minimal: integrate the independent coordinates alone where the constraints are solved in "
                   "closed form; full: integrate every coordinate and project onto the constraints.")
@click.option("--format", "fmt", type=click.Choice(["summary", "csv", "npz"]), default="summary",
              show_default=True, help="csv: the trajectory table (stdout unless -o); npz: NumPy archive.")
@click.option("-o", "--output", type=click.Path(path_type=Path),
              help="Output folder (default out/), or a file name for one file with --format csv/npz.")
@click.option("--plot", is_flag=True, help="Write PNG figures to the output folder.")
@click.option("--show", is_flag=True, help="Also open the figures in the system's viewer.")
@click.option("--animate", is_flag=True, help="Write an animated GIF of the particles.")
@_number("--timeout", key="timeout", default=600.0, show_default=True,
         help="CPU seconds allowed for derivation and integration of each file.")
def simulate(files: tuple[Path, ...], t_end: float | None, values: tuple[str, ...], initial: tuple[str, ...],
             samples: int | None, method: str | None, rtol: float | None, atol: float | None,
             max_step: float | None, after_release: str, coordinates: str, fmt: str, output: Path | None,
             plot: bool, show: bool, animate: bool, timeout: float) -> None:
    """Integrate the equations of motion of each problem FILE.

    \b
    lagsolve simulate problems/bead.yaml                  # summary of the run
    lagsolve simulate problems/bead.yaml --plot           # PNG figures in out/bead/
    lagsolve simulate problems/bead.yaml --t-end 20 --set g=1.62 --initial x=0.5 --plot --show
    lagsolve simulate problems/bead.yaml --format csv -o bead.csv
    """
    from lagsolve.app.pipeline import SimulationOptions, simulate_file
    from lagsolve.files import safe_slug, write_file

    options = SimulationOptions(
        values=_assignments(values, "--set"), initial=_assignments(initial, "--initial"), t_end=t_end,
        samples=samples, method=method, rtol=rtol, atol=atol, max_step=max_step, after_release=after_release,
        coordinates=coordinates, tables=(fmt,) if fmt != "summary" else (), plots=plot or show, animate=animate)
    single = output is not None and output.suffix == f".{fmt}"
    if single and len(files) > 1:
        raise click.UsageError(f"-o {output} names one file, but {len(files)} problems were given; give a folder")
    status = 0
    for path in files:
        _note(f"lagsolve: simulating {path}", err=True, level=2)
        try:
            result = simulate_file(path, options, timeout=timeout, progress=_progress_bar)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
        root = output if output is not None and not single else Path("out")
        folder = Path(safe_slug(path))
        to_stdout = fmt == "csv" and output is None
        _note(result.summary, nl=False, err=to_stdout)
        for warning in result.warnings:
            _warn(result.source, warning)
        written = []
        try:
            for kind, data in result.tables.items():
                if to_stdout:
                    click.echo(data, nl=False)
                elif single and output is not None:
                    written.append(write_file(output.parent, output.name, data))
                else:
                    written.append(write_file(root, folder / f"{result.slug}.{kind}", data))
            for key, data in result.figures.items():
                extension = "gif" if key == "animation" else "png"
                written.append(write_file(root, folder / f"{result.slug}_{key}.{extension}", data))
        except LagsolveError as error:
            status = max(status, _fail(error))
        for target in written:
            _note(f"  wrote {target}", err=to_stdout)
        if show:
            for target in written:
                if target.suffix in (".png", ".gif"):
                    click.launch(str(target))
    sys.exit(status)


@main.command()
@click.argument("key", type=click.Path(path_type=Path))
@click.argument("submissions", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--format", "fmt", type=click.Choice(["text", "json", "csv", "junit", "gradescope"]), default="text",
              show_default=True, help="csv: a gradebook, one row per student; junit: one test per step; "
                                      "gradescope: the autograder's results.json.")
@click.option("-o", "--output", type=click.Path(path_type=Path), default=None,
              help="Write the grades into this folder (gradescope: one folder per student) instead of printing.")
@click.option("--summary", type=click.Choice(["md", "html"]), default=None,
              help="The class summary (per step: the statuses counted, the most common mistakes with one anonymous "
                   "example each): printed instead of the grades, or written as summary.md/summary.html with -o.")
@_number("--timeout", key="timeout", default=120.0, show_default=True, help="CPU seconds for the key's derivation.")
def grade(key: Path, submissions: tuple[Path, ...], fmt: str, output: Path | None, summary: str | None,
          timeout: float) -> None:
    """Grade each student SUBMISSION step by step against the problem file KEY (docs/grading.md).

    Exit 2 when KEY is invalid or a submission file cannot be read at all (the others are still graded).

    \b
    lagsolve grade problems/bead.yaml examples/grading/*.yaml --format csv
    lagsolve grade problems/bead.yaml examples/grading/*.yaml --summary md
    """
    from lagsolve.app.grading import grade_files
    from lagsolve.files import write_file
    from lagsolve.render.grades import FILES, RENDER, SUMMARY, SUMMARY_FILES, gradescope_result

    try:
        grades = grade_files(key, submissions, budget=timeout)
    except LagsolveError as error:
        sys.exit(_fail(error))
    for g in grades.grades:
        if g.error:
            click.echo(f"error: {g.error}", err=True)
    text = RENDER[fmt](grades) if summary is None or output is not None else SUMMARY[summary](grades)
    try:
        if output is None:
            click.echo(text, nl=False)
        elif fmt == "gradescope":
            import json

            from lagsolve.app.grading import gradescope_folders

            for folder, g in gradescope_folders(grades.grades).items():
                write_file(output, Path(folder) / FILES[fmt],
                           json.dumps(gradescope_result(g), indent=2, ensure_ascii=False) + "\n")
        else:
            write_file(output, FILES[fmt], text)
        if output is not None and summary is not None:
            write_file(output, SUMMARY_FILES[summary], SUMMARY[summary](grades))
    except LagsolveError as error:
        sys.exit(_fail(error))
    sys.exit(2 if grades.unreadable else 0)


@main.command()
@click.argument("kind", type=click.Choice(["input", "output", "grades"]))
def schema(kind: str) -> None:
    """Print the JSON Schema (draft 2020-12) of the problem file (input), of the JSON result (output) or of
    lagsolve grade's JSON grades (grades).

    \b
    lagsolve schema input > problem.schema.json
    """
    from lagsolve.schemas import schema_json

    click.echo(schema_json(kind), nl=False)


def _sweep_progress() -> Callable[[int, int], None]:
    """A progress bar over the runs of a sweep (made at the first report), on stderr when it is a terminal."""
    from tqdm import tqdm

    bars: list[tqdm] = []

    def update(done: int, total: int) -> None:
        if not bars:
            bars.append(tqdm(total=total, unit="run", delay=1.0, disable=not sys.stderr.isatty(), leave=False))
        bars[0].update(done - bars[0].n)
        if done >= total:
            bars[0].close()

    return update


@main.command()
@click.argument("file", type=click.Path(path_type=Path))
@click.option("--grid", multiple=True, metavar="NAME=START:STOP:COUNT",
              help="Swept parameter, coordinate (theta1) or velocity (theta1_dot); repeat for a Cartesian product.")
@click.option("--random", "random_", multiple=True, metavar="NAME=LOW:HIGH", help="Uniform random values (repeatable).")
@_number("--runs", key="runs", help="Random runs (per grid point).")
@_number("--seed", key="seed", default=0, show_default=True, help="Seed of the random values.")
@_number("--t-end", key="t_end", help="End time (default: simulation.t_end).")
@click.option("--method", type=click.Choice(METHODS), default=DEFAULT_METHOD,
              show_default=True, help=f"Integrator; {', '.join(EXPLICIT[:-1])} and {EXPLICIT[-1]} run batched.")
@_number("--rtol", key="rtol", default=1e-10, show_default=True)
@_number("--atol", key="atol", default=1e-12, show_default=True)
@click.option("--poincare", metavar="SECTION", help='Record section crossings, e.g. "theta2=0, theta2_dot>0".')
@_number("--workers", key="workers",
         help="Parallel workers: threads on the compiled path, else processes of a local Dask cluster "
              "(0: in this process; default: the fastest for the run count).")
@click.option("--engine", type=click.Choice(["auto", "compiled", "numpy"]), default="auto", show_default=True,
              help="compiled: machine code per run (Numba, in the sweep extra); numpy: the batched NumPy integrator; "
                   "auto: compiled for 1000 runs or more when Numba is installed.")
@click.option("--scheduler", metavar="ADDRESS", help="Run on an existing Dask cluster, e.g. tcp://10.0.0.1:8786.")
@_number("--chunk-size", key="chunk_size",
         help="Runs per chunk (default: about 4 chunks per worker process, 16 per thread).")
@click.option("-o", "--output", type=click.Path(path_type=Path), required=True,
              help="The table: FILE.parquet or FILE.csv (one row per run).")
@click.option("--plot", is_flag=True, help="Also write the regime map (two inputs) or bifurcation scatter (one).")
@click.option("--color", metavar="COLUMN", help="Colour the regime map by this column instead of the outcome.")
def sweep(file: Path, grid: tuple[str, ...], random_: tuple[str, ...], runs: int | None, seed: int,
          t_end: float | None, method: str, rtol: float, atol: float, poincare: str | None, workers: int | None,
          engine: str, scheduler: str | None, chunk_size: int | None, output: Path, plot: bool,
          color: str | None) -> None:
    """Run problem FILE many times over parameters and initial conditions; one table row per run.

    \b
    lagsolve sweep problems/double_pendulum.yaml --grid theta1=0.1:1.5:32 --grid theta2=0.1:1.5:32 \\
        --t-end 5 --workers 2 -o s.parquet --plot
    lagsolve sweep problems/spring_on_rough_floor.yaml --random mu_s=0.1:0.5 --runs 200 -o s.csv
    """
    from lagsolve.files import write_file
    from lagsolve.sweep.api import sweep as run_sweep
    from lagsolve.sweep.output import SUFFIXES, table_bytes

    if output.suffix not in SUFFIXES:
        raise click.BadParameter(f"{output}: name the table FILE.parquet or FILE.csv", param_hint="-o/--output")
    try:
        from lagsolve.sweep.figures import check_color

        frame = run_sweep(file, grid=grid, random=random_, runs=runs, seed=seed, t_end=t_end, method=method,
                          rtol=rtol, atol=atol, poincare=poincare, workers=workers, scheduler=scheduler,
                          chunk_size=chunk_size, progress=_sweep_progress(), engine=engine,
                          before=lambda numeric: check_color(color, numeric))
        written = [write_file(output.parent, output.name, table_bytes(frame, output.suffix))]
        warnings = _sweep_warnings(file, frame)
        if plot or color:
            from lagsolve.sweep.figures import figures, png

            for key, figure in figures(frame, frame.attrs["swept"], file.stem, color).items():
                written.append(write_file(output.parent, f"{output.stem}_{key}.png", png(figure)))
    except LagsolveError as error:
        sys.exit(_fail(error))
    except ImportError as error:
        click.echo(f"error: {error}", err=True)
        sys.exit(1)
    for warning in warnings:
        _warn(str(file), warning)
    counts = frame["outcome"].value_counts()
    _note(f"{file}: {len(frame)} runs (" + ", ".join(f"{k} {v}" for k, v in counts.items()) + ")")
    for target in written:
        _note(f"  wrote {target}")


@main.command()
@click.argument("file", type=click.Path(path_type=Path))
@_number("--count", key="count", required=True, help="Variants to write.")
@click.option("--vary", multiple=True, required=True, metavar="NAME=LOW:HIGH[:STEP]",
              help="A parameter, coordinate (r) or velocity (r_dot) to vary, uniform or on a grid (repeatable).")
@_number("--seed", key="seed", default=0, show_default=True, help="Seed of the draws (same seed, same files).")
@click.option("--require", type=click.Choice(["stick", "slip", "release", "no-release"]),
              help="The regime every variant must show (stick/slip: of the friction contacts at t = 0).")
@click.option("--to", "to", type=click.Choice(["yaml", "prairielearn", "moodle-xml"]), default="yaml",
              show_default=True, help="Also write a PrairieLearn question folder or a Moodle XML quiz.")
@_number("--sig-figs", key="sig_figs", default=3, show_default=True, help="Significant figures of the varied numbers.")
@_number("--attempts", key="attempts", default=0, show_default=True,
         help="Candidates drawn at most (0: 20 per variant, at least 50).")
@_number("--timeout", key="timeout", default=120.0, show_default=True, help="CPU seconds of the one derivation.")
@click.option("--figures", is_flag=True, help="Also draw each variant's coordinates and forces (PNG; slower).")
@click.option("-o", "--output", type=click.Path(path_type=Path), required=True, help="Output folder.")
def variants(file: Path, count: int, vary: tuple[str, ...], seed: int, require: str | None, to: str, sig_figs: int,
             attempts: int, timeout: float, figures: bool, output: Path) -> None:
    """Write COUNT homework variants of problem FILE, each with its problem file, worked solution and a key
    verified twice (closed form and simulation), every one physically sane (exit 2 if too few pass).

    \b
    lagsolve variants problems/rotating_tube.yaml --count 30 --vary mu=0.1:0.6 --vary Omega=1:4 \\
        --require slip -o hw/
    """
    from lagsolve.files import write_file
    from lagsolve.variants.layout import files
    from lagsolve.variants.run import generate
    from lagsolve.variants.spec import build_request

    try:
        from lagsolve.problem.load import load_problem

        request = build_request(load_problem(file), count=count, vary=vary, seed=seed, require=require,
                                sig_figs=sig_figs, to=to, attempts=attempts, figures=figures)
        made = generate(file, request, budget=timeout)
        written = [write_file(output, name, data) for name, data in files(made).items()]
    except LagsolveError as error:
        sys.exit(_fail(error))
    rejected = ", ".join(f"{rule} {n}" for rule, n in made.rejections.items() if n) or "none"
    _note(f"{file}: {len(made.variants)} variants in {made.attempts} attempts; rejected per rule: {rejected}")
    for note in made.notes:
        _note(f"  note: {note}")
    _note(f"  wrote {len(written)} files into {output}")


def run() -> None:
    """The ``lagsolve`` program (its console script, ``python -m lagsolve``): :func:`main`, then, once what it
    printed is flushed, the process ends at once (``os._exit``) with main's exit status.

    The interpreter's own shutdown would free every object and module one by one: about 0.2 s after a derivation,
    a sixth of ``lagsolve derive``, for nothing. By the time a command returns its files are written (atomically),
    its budgeted children and workers joined and its clusters closed; no command relies on an ``atexit`` hook.
    A status that is not a number (a message) and an error that escapes (a bug's traceback) take Python's usual
    way out.

    The collector runs less often (:data:`COLLECTOR`): a derivation makes and drops millions of small SymPy objects,
    and Python's default (a young collection every 700 allocations) spends a tenth of a small derivation
    re-examining them; they hold no reference cycles worth finding sooner."""
    gc.set_threshold(*COLLECTOR)
    try:
        main()
    except SystemExit as done:
        code = done.code
    else:  # pragma: no cover - click's main always exits
        code = 0
    if code is not None and not isinstance(code, int):
        raise SystemExit(code)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except OSError:  # the reader went away (a closed pipe): what Python's own exit would report as status 120
        code = code or 120
    os._exit(code or 0)


if __name__ == "__main__":  # pragma: no cover
    run()
