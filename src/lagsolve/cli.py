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

EXTENSIONS = {"md": ".md", "tex": ".tex", "json": ".json"}


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
@click.option("-o", "--output", type=click.Path(path_type=Path),
              help="Output folder (default out/), or a file name when one file and one --format are given.")
@click.option("--format", "fmt", type=click.Choice(["md", "tex", "json"]),
              help="Only this format; printed to stdout unless -o is given.")
@click.option("--timeout", type=click.FloatRange(min=0.1), default=120.0, show_default=True,
              help="Seconds allowed for each derivation.")
@click.option("--templates", type=click.Path(file_okay=False, exists=True, path_type=Path),
              help="Folder with markdown/ and latex/ templates that override the packaged ones.")
@click.option("--golden", type=click.Path(file_okay=False, path_type=Path),
              help="Compare the reports with DIR/<problem>.<ext>; exit 1 with a diff when any differs.")
@click.option("--update-golden", is_flag=True, help="With --golden: write the golden files instead.")
def derive(files: tuple[Path, ...], output: Path | None, fmt: str | None, timeout: float,
           templates: Path | None, golden: Path | None, update_golden: bool) -> None:
    """Derive the equations of motion of each problem FILE.

    \b
    lagsolve derive problems/bead.yaml                 # summary here, reports in out/bead/
    lagsolve derive problems/*.yaml -o reports/        # several problems at once
    lagsolve derive problems/bead.yaml --format json   # the result contract on stdout
    lagsolve derive problems/bead.yaml --format tex -o bead.tex
    """
    from lagsolve.pipeline import derive_file, safe_slug

    if update_golden and golden is None:
        raise click.UsageError("--update-golden needs --golden DIR")

    formats = (fmt,) if fmt else ("md", "tex", "json")
    slugs = [safe_slug(f) for f in files]
    if len(set(slugs)) != len(slugs):
        raise click.UsageError("two problem files have the same name; their reports would overwrite each other")
    single_file = fmt is not None and output is not None and len(files) == 1 and output.suffix == EXTENSIONS[fmt]
    status = 0
    for path in files:
        try:
            reports = derive_file(path, formats, templates=templates, timeout=timeout)
        except LagsolveError as error:
            status = max(status, _fail(error))
            continue
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
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(reports.outputs[f], encoding="utf-8")
            click.echo(f"  wrote {target}")
    sys.exit(status)


if __name__ == "__main__":  # pragma: no cover
    main()
