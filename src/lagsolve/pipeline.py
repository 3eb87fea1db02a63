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
