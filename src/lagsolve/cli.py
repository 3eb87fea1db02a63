"""The ``lagsolve`` command: a thin shell over :mod:`lagsolve.pipeline`.

Parses options, calls one library function, shows or writes the result, and
maps errors to exit codes: 0 success, 1 the computation failed, 2 invalid input.
Heavy libraries (SymPy, matplotlib) are imported only inside commands, so
``lagsolve --help`` stays fast.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

import click

from lagsolve import __version__
from lagsolve.errors import LagsolveError, SpecError

if TYPE_CHECKING:
    from lagsolve.pipeline import Reports

EXTENSIONS = {"md": ".md", "tex": ".tex", "html": ".html", "json": ".json"}


def _fail(error: LagsolveError) -> int:
    if isinstance(error, SpecError):
        for issue in error.issues:
            click.echo(f"error: {issue}", err=True)
        return 2
    click.echo(f"error: {error}", err=True)
    return 1


def _golden(reports: Reports, folder: Path, update: bool) -> int:
    from lagsolve.pipeline import golden_differences

    if update:
        folder.mkdir(parents=True, exist_ok=True)
        for fmt, text in reports.outputs.items():
            target = folder / f"{reports.slug}.{fmt}"
            target.write_text(text, encoding="utf-8")
            click.echo(f"  wrote {target}")
        return 0
    diffs = golden_differences(reports, folder)
    for diff in diffs:
        click.echo(diff, nl=False)
    verdict = "differs from" if diffs else "matches"
    click.echo(f"{reports.source}: {verdict} the golden files in {folder}")
    return 1 if diffs else 0


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="lagsolve")
def main() -> None:
    """Lagrangian mechanics from a YAML problem file: equations of motion,
    multipliers, forces of constraint, and worked-solution reports."""


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--timeout", type=click.FloatRange(min=0.1), default=120.0, show_default=True,
              help="CPU seconds allowed for each derivation and check.")
def check(files: tuple[Path, ...], timeout: float) -> None:
    """Compare the expected answers in each problem FILE with the derivation.

    ✓ ok, ! holds only in part (warning), ✗ mismatch (exit 1), – not checked.

    \b
    lagsolve check problems/*.yaml
    """
    from lagsolve.pipeline import check_file

    status = 0
    for path in files:
        try:
            checked = check_file(path, timeout=timeout)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
        click.echo(checked.table, nl=False)
        if not checked.passed:
            status = max(status, 1)
    sys.exit(status)


@main.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("-o", "--output", type=click.Path(path_type=Path),
              help="Output folder (default out/), or a file name when one file and one --format are given.")
@click.option("--format", "fmt", type=click.Choice(["md", "tex", "html", "json"]),
              help="Only this format; printed to stdout unless -o is given.")
@click.option("--timeout", type=click.FloatRange(min=0.1), default=120.0, show_default=True,
              help="CPU seconds allowed for each derivation; a stage that runs out of its share is named "
                   "and the rest is still given.")
@click.option("--templates", type=click.Path(file_okay=False, exists=True, path_type=Path),
              help="Folder with markdown/ and latex/ templates that override the packaged ones.")
@click.option("--golden", type=click.Path(file_okay=False, path_type=Path),
              help="Compare the reports with DIR/<problem>.<ext>; exit 1 with a diff when any differs.")
@click.option("--update-golden", is_flag=True, help="With --golden: write the golden files instead.")
@click.option("--simulate", "with_simulation", is_flag=True,
              help="Also simulate (the file's simulation block) and embed the figures in the reports.")
def derive(files: tuple[Path, ...], output: Path | None, fmt: str | None, timeout: float,
           templates: Path | None, golden: Path | None, update_golden: bool, with_simulation: bool) -> None:
    """Derive the equations of motion of each problem FILE.

    \b
    lagsolve derive problems/bead.yaml                 # summary here, reports in out/bead/
    lagsolve derive problems/*.yaml -o reports/        # several problems at once
    lagsolve derive problems/bead.yaml --format json   # the result contract on stdout
    lagsolve derive problems/bead.yaml --format tex -o bead.tex
    lagsolve derive problems/bead.yaml --simulate      # the report with the simulation's figures
    """
    from lagsolve.pipeline import SimulationOptions, derive_file, safe_slug

    if update_golden and golden is None:
        raise click.UsageError("--update-golden needs --golden DIR")

    formats = (fmt,) if fmt else ("md", "tex", "json")
    slugs = [safe_slug(f) for f in files]
    if len(set(slugs)) != len(slugs):
        raise click.UsageError("two problem files have the same name; their reports would overwrite each other")
    if with_simulation and fmt and output is None:
        raise click.UsageError("--simulate writes figure files beside the report: give -o DIR (or no --format)")
    single_file = fmt is not None and output is not None and output.suffix == EXTENSIONS[fmt]
    if single_file and len(files) > 1:
        raise click.UsageError(f"-o {output} names one file, but {len(files)} problems were given; give a folder")
    status = 0
    for path in files:
        try:
            simulate = SimulationOptions(values={}, initial={}, plots=True) if with_simulation else None
            reports = derive_file(path, formats, templates=templates, timeout=timeout, simulate=simulate)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
        for warning in reports.warnings:
            click.echo(f"warning: {reports.source}: not completed: {warning}", err=True)
        if golden is not None:
            status = max(status, _golden(reports, golden, update_golden))
            continue
        if fmt and output is None:
            click.echo(reports.outputs[fmt], nl=False)
            continue
        if single_file:
            targets = {fmt: output}
        elif fmt:
            targets = {fmt: output / f"{reports.slug}{EXTENSIONS[fmt]}"}
        else:
            folder = (output or Path("out")) / reports.slug
            targets = {f: folder / f"{reports.slug}{EXTENSIONS[f]}" for f in formats}
            click.echo(reports.summary, nl=False)
        for f, target in targets.items():
            click.echo(f"  wrote {_write(target, reports.outputs[f])}")
        for name, data in reports.files.items():
            click.echo(f"  wrote {_write(next(iter(targets.values())).parent / name, data)}")
    sys.exit(status)


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


def _progress_bar(t_end: float) -> object:
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
@click.option("--t-end", type=click.FloatRange(min=0, min_open=True), help="End time (default: simulation.t_end).")
@click.option("--set", "values", multiple=True, metavar="NAME=VALUE", help="Parameter value (repeatable).")
@click.option("--initial", multiple=True, metavar="NAME=VALUE",
              help="Initial coordinate or velocity, e.g. x=0.5 or x_dot=0 (repeatable).")
@click.option("--samples", type=click.IntRange(min=2, max=1_000_000), help="Number of output times (default 1001).")
@click.option("--method", type=click.Choice(["DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA"]),
              help="Integrator (default DOP853; Radau/BDF/LSODA for stiff problems).")
@click.option("--rtol", type=click.FloatRange(min=0, min_open=True), help="Relative tolerance (default 1e-10).")
@click.option("--atol", type=click.FloatRange(min=0, min_open=True), help="Absolute tolerance (default 1e-12).")
@click.option("--max-step", type=click.FloatRange(min=0, min_open=True), help="Largest step size.")
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
@click.option("--timeout", type=click.FloatRange(min=0.1), default=600.0, show_default=True,
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
    from lagsolve.pipeline import SimulationOptions, safe_slug, simulate_file

    options = SimulationOptions(
        values=_assignments(values, "--set"), initial=_assignments(initial, "--initial"), t_end=t_end,
        samples=samples, method=method, rtol=rtol, atol=atol, max_step=max_step, after_release=after_release,
        coordinates=coordinates, tables=(fmt,) if fmt != "summary" else (), plots=plot or show, animate=animate)
    single = output is not None and output.suffix == f".{fmt}"
    if single and len(files) > 1:
        raise click.UsageError(f"-o {output} names one file, but {len(files)} problems were given; give a folder")
    status = 0
    for path in files:
        try:
            result = simulate_file(path, options, timeout=timeout, progress=_progress_bar)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
        folder = (output if output is not None and not single else Path("out")) / safe_slug(path)
        to_stdout = fmt == "csv" and output is None
        click.echo(result.summary, nl=False, err=to_stdout)
        written = []
        for kind, data in result.tables.items():
            if to_stdout:
                click.echo(data, nl=False)
                continue
            target = output if single and output is not None else folder / f"{result.slug}.{kind}"
            written.append(_write(target, data))
        for key, data in result.figures.items():
            written.append(_write(folder / f"{result.slug}_{key}.{'gif' if key == 'animation' else 'png'}", data))
        for target in written:
            click.echo(f"  wrote {target}", err=to_stdout)
        if show:
            for target in written:
                if target.suffix in (".png", ".gif"):
                    click.launch(str(target))
    sys.exit(status)


def _write(target: Path, data: str | bytes) -> Path:
    """Write one output file; a path that cannot be written is a command-line error (exit 2)."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(data, bytes):
            target.write_bytes(data)
        else:
            target.write_text(data, encoding="utf-8")
    except OSError as exc:
        raise click.BadParameter(f"cannot write {target}: {exc.strerror or exc}", param_hint="-o/--output") from None
    return target


if __name__ == "__main__":  # pragma: no cover
    main()
