"""Reports from a :class:`~lagsolve.mechanics.derivation.Derivation`: the sections, presented.

:func:`lagsolve.render.sections.build` walks the derivation once; each output here is
:func:`~lagsolve.render.model.present` of those records with one printer: :func:`sections_context`
(:func:`context`) gives the templates plain strings (LaTeX or MathML), which the Jinja2 templates of each
format in :mod:`lagsolve.render.formats` lay out as a worked solution (the Markdown and LaTeX pages include
one partial per section, :func:`page_parts`); :func:`sections_json` (:func:`result_dict`,
:func:`result_json`) is the contract of the format's section 2; :func:`sections_summary` (:func:`summary`)
is the short text shown in a terminal, from the partials of ``templates/text/``. The analysis and
Hamiltonian sections still have their own projections, called in one marked place. Nothing here
simplifies: every expression arrives in display form.
"""
from __future__ import annotations

import base64
import dataclasses
import functools
import json
import typing
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
from jinja2.sandbox import ImmutableSandboxedEnvironment

from lagsolve.errors import RenderError
from lagsolve.mechanics.derivation import Derivation
from lagsolve.render.formats import FORMATS
from lagsolve.render.mathml import typeset
from lagsolve.render.model import JsonPrinter, NotationPrinter, metadata, present
from lagsolve.render.notation import FILTERS, Notation, symbol_table
from lagsolve.render.sections import Sections, build

# -- context ------------------------------------------------------------------------------------


def context(derivation: Derivation, math: str = "latex") -> dict[str, Any]:
    """Everything a template needs, as plain strings, lists and dicts; expressions in LaTeX, or in presentation
    MathML when ``math`` is "mathml" (the HTML report; the keys keep their names)."""
    return sections_context(build(derivation), math)


def sections_context(sections: Sections, math: str = "latex") -> dict[str, Any]:
    """:func:`context` of sections already built: the sections :func:`present`-ed with the format's printer
    (``core``, ``units``: each record's fields by name), and what only the page needs: the problem's
    ``symbols`` (for the prose of notes and descriptions) and ``math``."""
    note = Notation([c.name for c in sections.core.coordinates])
    return {**present(sections, NotationPrinter(math, note)),
            "symbols": symbol_table(dict(sections.core.symbols), note), "math": math}


#: the figures a page shows, which are not sections (they come with the call): each one's partial and the
#: section partial it follows (None: the end of the page)
FIGURES: tuple[tuple[str, str | None], ...] = (("_potential", "_analysis"), ("_simulation", None))
#: where a format whose figures float places them instead, by extension: the first of the partials given that the
#: page has. In LaTeX the simulation (its summary and half-page figures) follows the results, so that the analysis
#: after it fills the pages around the figures; at the end of the page nothing would, and the page where the
#: summary ends would stay empty below it.
FLOATING: dict[str, dict[str, tuple[str, ...]]] = {".tex": {"_simulation": ("_units", "_core")}}


def page_parts(sections: Sections, extension: str) -> list[str]:
    """The partials a Markdown or LaTeX page includes, in reading order: one per section (the order of the fields
    of :class:`~lagsolve.render.sections.Sections`; a section that is None has none), each figure's after its
    section's (:data:`FIGURES`, or for a format whose figures float :data:`FLOATING`); ``extension`` is the
    format's (``.md``: ``_core.md.j2`` ...)."""
    names = [meta.partial for field in dataclasses.fields(sections)
             if (meta := metadata(field, Sections)).partial is not None and getattr(sections, field.name) is not None]
    floating = FLOATING.get(extension, {})
    for figure, after in FIGURES:
        after = next((a for a in floating.get(figure, ()) if a in names), after)
        names.insert(names.index(after) + 1 if after in names else len(names), figure)
    return [f"{name}{extension}.j2" for name in names]


# -- templates ----------------------------------------------------------------------------------


def template_dirs(kind: str, extra: Path | None = None) -> list[Path]:
    """Where templates of ``kind`` are looked for: ``--templates`` dir, the installed package, the checkout."""
    dirs = []
    if extra is not None:
        dirs.append(Path(extra) / kind)
    packaged = resources.files("lagsolve").joinpath("templates", kind)
    dirs.append(Path(str(packaged)))
    dirs.append(Path(__file__).resolve().parents[3] / "templates" / kind)
    return dirs


#: every template, packaged or from ``--templates``, is rendered in Jinja2's immutable sandbox: a template is data,
#: and one from a folder the user gave (a pull request's, in CI) cannot reach Python (``__globals__``, ``os``),
#: call unsafe methods or change the context; what it tries is a RenderError (exit 1)
ENVIRONMENT: type[jinja2.Environment] = ImmutableSandboxedEnvironment


def environment(kind: str, extra: Path | None = None) -> jinja2.Environment:
    """A sandboxed Jinja2 environment for ``kind`` ("markdown", "latex", "html" or "text", the terminal summary's);
    LaTeX uses ``((* *))``-style delimiters. One per kind and templates folder in a process, so that each template
    is compiled once (Jinja2 reloads one whose file changed); compiled templates are read from the install's
    bytecode cache where ``make`` built one (:mod:`lagsolve.render.template_cache`)."""
    dirs = tuple(str(d) for d in template_dirs(kind, extra) if d.is_dir())
    return _environment(ENVIRONMENT, kind, dirs)  # type: ignore[arg-type]  # a class is hashable


@functools.lru_cache(maxsize=32)
def _environment(sandbox: type[jinja2.Environment], kind: str, dirs: tuple[str, ...]) -> jinja2.Environment:
    from lagsolve.render.template_cache import CACHE, InstalledCache

    options: dict[str, Any] = {
        "loader": jinja2.FileSystemLoader(list(dirs)),
        # the code Jinja2 compiles differs by environment class (the sandbox's calls are checked): its own folder
        "bytecode_cache": InstalledCache(CACHE / sandbox.__name__) if (CACHE / sandbox.__name__).is_dir() else None,
        "autoescape": kind == "html",
        "undefined": jinja2.StrictUndefined,
        "keep_trailing_newline": True,
        "trim_blocks": True,
        "lstrip_blocks": True,
    }
    if kind == "latex":
        options.update(block_start_string="((*", block_end_string="*))", variable_start_string="(((",
                       variable_end_string=")))", comment_start_string="((=", comment_end_string="=))")
    env = sandbox(**options)  # noqa: S701 - Markdown/TeX are escaped by filters, HTML autoescaped
    env.filters.update(FILTERS)
    return env


def render(derivation: Derivation, fmt: str, templates: Path | None = None,
           simulation: dict[str, Any] | None = None, potential: dict[str, Any] | None = None,
           files: dict[str, bytes] | None = None) -> str:
    """The report of ``derivation`` in ``fmt`` ("md", "tex", "html" or "json").

    ``files`` are the figures the report shows (name → PNG bytes): Markdown and LaTeX refer to them by
    name, the HTML page carries them as ``data:`` URIs so that it is one self-contained file.
    """
    if fmt not in FORMATS:
        raise RenderError(f"unknown format {fmt!r}; use {', '.join(FORMATS)}")
    return render_sections(build(derivation), fmt, templates, simulation, potential, files)


def render_sections(sections: Sections, fmt: str, templates: Path | None = None,
                    simulation: dict[str, Any] | None = None, potential: dict[str, Any] | None = None,
                    files: dict[str, bytes] | None = None) -> str:
    """:func:`render` of sections already built."""
    if fmt not in FORMATS:
        raise RenderError(f"unknown format {fmt!r}; use {', '.join(FORMATS)}")
    spec = FORMATS[fmt]
    if spec.templates is None or spec.template is None:
        return TEXT_PROJECTIONS[fmt](sections)
    kind, name = spec.templates, spec.template
    env = environment(kind, templates)
    try:
        template = env.get_template(name)
    except jinja2.TemplateNotFound:
        searched = ", ".join(str(d) for d in template_dirs(kind, templates))
        raise RenderError(f"template {kind}/{name} not found; searched: {searched}") from None
    if spec.figures == "inline":
        simulation, potential = _inlined(simulation, files or {}), _inlined(potential, files or {})
    try:
        page = template.render(**sections_context(sections, spec.math), parts=page_parts(sections, spec.extension),
                               simulation=simulation, potential_plot=potential)
    except jinja2.TemplateError as exc:
        raise RenderError(f"template {kind}/{name} failed: {exc}") from None
    return typeset(page) if spec.math == "mathml" else page


def text_lines(partial: str, data: dict[str, Any], templates: Path | None = None) -> list[str]:
    """The terminal lines of ``templates/text/<partial>`` over ``data`` (sections :func:`present`-ed with the text
    printer: only the fields marked ``terminal``)."""
    env = environment("text", templates)
    try:
        page = env.get_template(partial).render(**data)
    except jinja2.TemplateError as exc:
        raise RenderError(f"template text/{partial} failed: {exc}") from None
    return page.splitlines()


def _inlined(figures: dict[str, Any] | None, files: dict[str, bytes]) -> dict[str, Any] | None:
    """``figures`` (a simulation's or the potential plot's) with each PNG as a ``data:`` URI under ``data``."""
    if figures is None:
        return None

    def uri(name: str) -> str:
        return "data:image/png;base64," + base64.b64encode(files[name]).decode("ascii") if name in files else ""

    out = dict(figures)
    if "file" in out:
        out["data"] = uri(out["file"])
    if "figures" in out:
        out["figures"] = [{**f, "data": uri(f["file"])} for f in out["figures"]]
    return out


# -- JSON and terminal summary --------------------------------------------------------------------


def result_dict(derivation: Derivation) -> dict[str, Any]:
    """The result contract (format section 2) as a dict of strings."""
    return sections_json(build(derivation))


def sections_json(sections: Sections) -> dict[str, Any]:
    """:func:`result_dict` of sections already built (the JSON projection)."""
    return typing.cast(dict[str, Any], present(sections, JsonPrinter()))


def result_json(derivation: Derivation) -> str:
    """:func:`result_dict` as indented JSON text (stable key order, ASCII only)."""
    return _json_text(result_dict(derivation))


def _json_text(data: dict[str, Any]) -> str:
    return json.dumps(data, indent=2, ensure_ascii=True) + "\n"


#: the formats of :mod:`lagsolve.render.formats` that are not templates: each one's projection of the sections
TEXT_PROJECTIONS: dict[str, Callable[[Sections], str]] = {"json": lambda sections: _json_text(sections_json(sections))}


def summary(derivation: Derivation) -> str:
    """The key results, readable in a terminal."""
    return sections_summary(build(derivation))


def sections_summary(sections: Sections) -> str:
    """:func:`summary` of sections already built: the terminal partials (``templates/text/``) over the sections
    :func:`present`-ed with the text printer (the fields marked ``terminal``)."""
    note = Notation([c.name for c in sections.core.coordinates])
    data = present(sections, NotationPrinter("text", note))
    return "\n".join(text_lines("summary.txt.j2", data)) + "\n"
