"""Reports from a :class:`~lagsolve.mechanics.derivation.Derivation`: projections of its sections.

:func:`lagsolve.render.sections.build` walks the derivation once; each output here prints those records:
:func:`sections_context` (:func:`context`) gives the templates plain strings (LaTeX or MathML, text,
JSON syntax), which the Jinja2 templates of each format in :mod:`lagsolve.render.formats` lay out as a
worked solution; :func:`sections_json` (:func:`result_dict`, :func:`result_json`) is the contract of the
format's section 2; :func:`sections_summary` (:func:`summary`) is the short text shown in a terminal.
Nothing here simplifies: every expression arrives in display form.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
from jinja2.sandbox import ImmutableSandboxedEnvironment

from lagsolve.errors import RenderError
from lagsolve.mechanics.derivation import Derivation
from lagsolve.render.analysis_report import analysis_context, analysis_json, analysis_summary
from lagsolve.render.formats import FORMATS
from lagsolve.render.hamiltonian_report import hamiltonian_context, hamiltonian_json, hamiltonian_summary
from lagsolve.render.mathml import typeset
from lagsolve.render.model import JsonPrinter, NotationPrinter, present
from lagsolve.render.notation import FILTERS, Notation, symbol_table, to_json
from lagsolve.render.sections import Sections, build
from lagsolve.render.sections.core import ConstraintForce

#: above this many coordinates the matrix form is written one equation per row instead of as matrices
LARGE = 3


# -- context ------------------------------------------------------------------------------------


def context(derivation: Derivation, math: str = "latex") -> dict[str, Any]:
    """Everything a template needs, as plain strings, lists and dicts; expressions in LaTeX, or in presentation
    MathML when ``math`` is "mathml" (the HTML report; the keys keep their names)."""
    return sections_context(build(derivation), math)


def sections_context(sections: Sections, math: str = "latex") -> dict[str, Any]:
    """:func:`context` of sections already built (the templates' projection)."""
    core = sections.core
    note = Notation([c.name for c in core.coordinates])
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text

    def both(expr: Any) -> dict[str, str]:
        return {"tex": tex(expr), "text": text(expr), "json": to_json(expr)}

    def by_coordinate(values: Any) -> list[dict[str, Any]]:
        return [{"coordinate": tex(v.coordinate), "value": tex(v.value)} for v in values if v.value != 0]

    coords = [{"name": c.name, "tex": tex(c.symbol), "velocity": tex(c.velocity),
               "acceleration": tex(c.acceleration), "description": c.description} for c in core.coordinates]
    constraints = [{
        "name": c.name, "kind": c.kind, "multiplier": tex(c.multiplier), "expression": tex(c.expression),
        "velocity_form": tex(c.velocity_form),
        "coefficients": [{"coordinate": tex(a.coordinate), "value": tex(a.value)} for a in c.coefficients],
        "offset": tex(c.offset), "acceleration_rhs": tex(c.acceleration_rhs), "on": list(c.on),
        "unilateral": c.unilateral,
    } for c in core.constraints]
    equations = [{
        "coordinate": tex(e.coordinate.symbol), "velocity": tex(e.coordinate.velocity), "momentum": tex(e.momentum),
        "rate": tex(e.rate), "gradient": tex(e.gradient), "force": tex(e.force) if e.force != 0 else "",
        "lhs": tex(e.lhs), "rhs": tex(e.rhs),
    } for e in core.equations]
    substitutions = [{"symbol": tex(s.symbol), "value": tex(s.value), "source": s.source} for s in core.substitutions]
    solved = {key: None if rows is None else [
        {"name" if key == "multipliers" else "coordinate": r.name, "symbol": tex(r.symbol),
         "symbol_text": text(r.symbol), **both(r.value)} for r in rows]
        for key, rows in (("accelerations", core.accelerations), ("multipliers", core.multipliers))}
    forces = None if core.forces is None else [{
        "name": f.name,
        "vector": [tex(v) for v in f.vector] if f.vector is not None else None,
        "magnitude": both(f.magnitude) if f.magnitude is not None else None,
        "particles": [{"name": p.name, "vector": [tex(v) for v in p.vector], "magnitude": both(p.magnitude)}
                      for p in f.particles],
        "note": f.note,
        "generalized": [{"coordinate": tex(g.coordinate), "coordinate_text": g.name, "value": both(g.value)}
                        for g in f.generalized_shown],
    } for f in core.forces]
    friction = [
        {"name": f.name, "particle": f.particle, "against": f.against or "",
         "point": [tex(c) for c in f.point] if f.point is not None else None,
         "rate": tex(f.rate) if f.rate is not None else "",
         "tangent": [tex(c) for c in f.tangent] if f.tangent is not None else None,
         "coefficient": tex(f.coefficient),
         "normal": tex(f.normal), "normal_text": text(f.normal), "constraints": list(f.constraints),
         "force": [tex(v) for v in f.term_force], "generalized": by_coordinate(f.term_generalized),
         "valid_while": tex(f.valid_while), "normal_force": both(f.normal_shown),
         "case": f.case, "condition": tex(f.condition) if f.condition is not None else "", "static": tex(f.static),
         "members": [{"name": m.name, "normal": [tex(v) for v in m.normal], "friction": [tex(v) for v in m.friction],
                      "total": [tex(v) for v in m.total], "magnitude": both(m.magnitude)} for m in f.members],
         "held": None if f.held is None else {"force": tex(f.held.force), "normal": tex(f.held.normal),
                                               "ratio": tex(f.held.ratio) if f.held.ratio is not None else ""}}
        for f in core.friction
    ]
    matrix = core.matrix
    return {
        "name": core.name,
        "description": core.description,
        "slug": core.slug,
        "time": tex(core.time),
        "coordinates": coords,
        "parameters": [{"name": p.name, "tex": tex(p.symbol), "description": p.description,
                        "assumption": p.assumption} for p in core.parameters],
        "functions": [{"name": f.name, "tex": tex(f.symbol), "description": f.description} for f in core.functions],
        "particles": [{"name": p.name, "mass": tex(p.mass), "position": [tex(r) for r in p.position]}
                      for p in core.particles],
        "bodies": [{"name": b.name, "mass": tex(b.mass), "position": [tex(r) for r in b.position],
                    "inertia": [tex(i) for i in b.inertia], "angular_velocity": [tex(w) for w in b.angular_velocity],
                    "planar": b.planar} for b in core.bodies],
        "gravity": [tex(g) for g in core.gravity] if core.gravity is not None else None,
        "kinetic": tex(core.kinetic),
        "potential": tex(core.potential),
        "lagrangian": tex(core.lagrangian),
        "loads": [{"label": t.label, "values": by_coordinate(t.generalized)} for t in core.loads],
        "constraints": constraints,
        "equations": equations,
        "substitutions": substitutions,
        "constrained": [{"coordinate": tex(s.coordinate.symbol), "lhs": tex(s.lhs), "rhs": tex(s.rhs)}
                        for s in core.constrained] if substitutions else [],
        "matrices": {
            "mass": tex(matrix.mass_shown),
            "forcing": tex(matrix.forcing_shown),
            "jacobian": tex(matrix.jacobian) if matrix.jacobian is not None else "",
            "rhs": tex(matrix.rhs_shown) if matrix.rhs_shown is not None else "",
            "unknowns": tex(matrix.unknowns),
        },
        "matrix_equations": [{"coordinate": tex(r.coordinate.symbol), "lhs": tex(r.lhs),
                              "rhs": tex(r.forcing + r.constraint_part)}
                             for r in matrix.rows] if len(coords) > LARGE else [],
        **solved,
        "unilateral": [{"name": c.name, "multiplier": tex(c.multiplier)} for c in core.constraints if c.unilateral],
        "forces": forces,
        "friction": friction,
        "analysis": analysis_context(sections.analysis, note, math),
        "hamiltonian": hamiltonian_context(sections.hamiltonian, note, math),
        "notes": [n.sentence for n in core.notes],
        "symbols": symbol_table(dict(core.symbols), note),
        "math": math,
        "stage_notes": {n.stage: n.reason for n in core.notes},
        "units": present(sections.units, NotationPrinter(math, note)),
    }


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
    LaTeX uses ``((* *))``-style delimiters."""
    dirs = [str(d) for d in template_dirs(kind, extra) if d.is_dir()]
    options: dict[str, Any] = {
        "loader": jinja2.FileSystemLoader(dirs),
        "autoescape": kind == "html",
        "undefined": jinja2.StrictUndefined,
        "keep_trailing_newline": True,
        "trim_blocks": True,
        "lstrip_blocks": True,
    }
    if kind == "latex":
        options.update(block_start_string="((*", block_end_string="*))", variable_start_string="(((",
                       variable_end_string=")))", comment_start_string="((=", comment_end_string="=))")
    env = ENVIRONMENT(**options)  # noqa: S701 - Markdown/TeX are escaped by filters, HTML autoescaped
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
        page = template.render(**sections_context(sections, spec.math), simulation=simulation,
                               potential_plot=potential)
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
    return _unmigrated_json(present(sections, JsonPrinter()), sections)


# -- not yet migrated (issue 30) -----------------------------------------------------------------
# The analysis and Hamiltonian sections are not yet records with `shown` fields: their own projections print
# them, here only. Their JSON keys go where Sections.JSON_LAST puts them.


def _unmigrated_json(data: dict[str, Any], sections: Sections) -> dict[str, Any]:
    data = {**data, "analysis": analysis_json(sections.analysis), "hamiltonian": hamiltonian_json(sections.hamiltonian)}
    last = [key for key in Sections.JSON_LAST if key in data]
    return {**{k: v for k, v in data.items() if k not in last}, **{k: data[k] for k in last}}


# ------------------------------------------------------------------------------------------------


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
    """:func:`summary` of sections already built (the terminal projection)."""
    core = sections.core
    note = Notation([c.name for c in core.coordinates])
    text = note.text
    lines = [f"{core.name}"]
    if core.accelerations is not None:
        lines.append("  accelerations:")
        lines += [f"    {text(a.symbol)} = {text(a.value)}" for a in core.accelerations]
    else:
        lines.append("  equations of motion in matrix form M q̈ = F + Aᵀλ (the explicit accelerations are not given; "
                     "see the report):")
        extra = " + Σ λ a" if core.constraints else ""
        lines += [f"    ({i + 1}) {text(r.lhs)} = {text(r.forcing)}{extra}" for i, r in enumerate(core.matrix.rows)]
    if core.multipliers:
        lines.append("  multipliers:")
        lines += [f"    {text(m.symbol)} = {text(m.value)}" for m in core.multipliers]
    if core.forces:
        lines.append("  forces of constraint (magnitude):")
        lines += [line for f in core.forces for line in _force_lines(f, text)]
    for f in core.friction:
        lines.append(f"  friction {f.name}: normal force {text(f.normal)} = {text(f.normal_shown)}")
        lines += [f"    |F| on {m.name} (normal force and friction) = {text(m.magnitude)}" for m in f.members]
        if f.held is not None and f.held.ratio is not None:
            lines.append(f"    sticks while mu_s >= {text(f.held.ratio)} (holding force {text(f.held.force)})")
    lines += analysis_summary(sections.analysis, note)
    lines += hamiltonian_summary(sections.hamiltonian, note)
    if core.notes:
        lines.append("  not completed:")
        lines += [f"    {n.sentence}" for n in core.notes]
    return "\n".join(lines) + "\n"


def _force_lines(f: ConstraintForce, text: Callable[[Any], str]) -> list[str]:
    """A force of constraint in the terminal: its magnitude, each particle's, or its generalized forces."""
    generalized = f.generalized_shown
    if generalized:
        parts = ", ".join(f"Q_{g.name} = {text(g.value)}" for g in generalized)
        return [f"    {f.name}: generalized forces of constraint (no point named): {parts}"]
    if f.magnitude is None and f.particles:
        return [f"    |F_{f.name}| on {p.name} = {text(p.magnitude)}" for p in f.particles]
    value = text(f.magnitude) if f.magnitude is not None else "— " + f.note
    return [f"    |F_{f.name}| = {value}"]
