"""The report formats: the one registry the renderer, the pipeline and the command line read.

Plain data (nothing here imports Jinja2 or SymPy), so ``lagsolve --help`` can list the formats.
A new format is one :class:`Format` here, its templates in ``templates/<templates>/`` and, when it
is not a template, its projection in :mod:`lagsolve.render.report`.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Format:
    """One output format of ``lagsolve derive``.

    ``templates`` is the template folder (None: not a template, the JSON contract), ``template`` the
    entry template in it, ``math`` how its expressions are printed ("latex" or "mathml"), ``figures``
    how it shows figures ("files": by name, written beside it; "inline": inside it; "": none), and
    ``default`` whether ``lagsolve derive`` writes it when no ``--format`` is given.
    """

    name: str
    extension: str
    templates: str | None
    template: str | None
    math: str
    figures: str
    default: bool


REGISTRY: tuple[Format, ...] = (
    Format("md", ".md", "markdown", "report.md.j2", "latex", "files", True),
    Format("tex", ".tex", "latex", "report.tex.j2", "latex", "files", True),
    Format("html", ".html", "html", "report.html.j2", "mathml", "inline", False),
    Format("json", ".json", None, None, "", "", True),
)
#: name → format, in the registry's order
FORMATS: dict[str, Format] = {f.name: f for f in REGISTRY}
#: what ``lagsolve derive`` writes without ``--format``
DEFAULT_FORMATS: tuple[str, ...] = tuple(f.name for f in REGISTRY if f.default)


def extension(name: str) -> str:
    """The file extension of format ``name`` (``".md"``)."""
    return FORMATS[name].extension
