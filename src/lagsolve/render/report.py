"""Reports from a :class:`~lagsolve.mechanics.derivation.Derivation`.

:func:`context` turns a derivation into plain strings (LaTeX, text, JSON syntax);
the Jinja2 templates in ``templates/markdown`` and ``templates/latex`` lay them
out as a worked solution; :func:`result_json` is the contract of the format's
section 2; :func:`summary` is the short text shown in a terminal.
Nothing here simplifies: every expression arrives in display form.
"""

from __future__ import annotations

import base64
import json
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
import sympy

from lagsolve.errors import RenderError
from lagsolve.mechanics.derivation import Derivation
from lagsolve.render.analysis_report import analysis_context, analysis_json, analysis_summary, contract_json
from lagsolve.render.hamiltonian_report import hamiltonian_context, hamiltonian_json, hamiltonian_summary
from lagsolve.render.notation import FILTERS, Notation, symbol_table, to_json
from lagsolve.render.units import units_context, units_json

FORMAT_VERSION = 1
#: above this many coordinates the matrix form is written one equation per row instead of as matrices
LARGE = 3
FORMATS = {"md": ("markdown", "report.md.j2"), "tex": ("latex", "report.tex.j2"), "html": ("html", "report.html.j2"),
           "json": (None, None)}


# -- context ------------------------------------------------------------------------------------


def context(derivation: Derivation, math: str = "latex") -> dict[str, Any]:
    """Everything a template needs, as plain strings, lists and dicts; expressions in LaTeX, or in presentation
    MathML when ``math`` is "mathml" (the HTML report; the keys keep their names)."""
    problem = derivation.problem
    model = derivation.model
    names = [c.name for c in problem.coordinates]
    note = Notation(names)
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text

    def both(expr: Any) -> dict[str, str]:
        return {"tex": tex(expr), "text": text(expr), "json": to_json(expr)}

    coords = [
        {"name": c.name, "tex": tex(c.symbol), "velocity": tex(c.velocity), "acceleration": tex(c.acceleration),
         "description": c.description}
        for c in problem.coordinates
    ]
    unilateral = {c.name for c in problem.constraints if c.unilateral}
    constraints = []
    for c in derivation.constraints:
        velocity = sum((a * v for a, v in zip(c.coefficients, model.velocities, strict=True)), c.offset)
        constraints.append({
            "name": c.name,
            "kind": c.kind,
            "multiplier": tex(c.multiplier),
            "expression": tex(c.expression),
            "velocity_form": tex(velocity),
            "coefficients": [{"coordinate": coords[i]["tex"], "value": tex(a)} for i, a in enumerate(c.coefficients)],
            "offset": tex(c.offset),
            "acceleration_rhs": tex(c.acceleration_rhs),
            "on": list(c.on),
            "unilateral": c.name in unilateral,
        })
    equations = []
    for i, (lhs, rhs) in enumerate(derivation.equation_sides):
        equations.append({
            "coordinate": coords[i]["tex"],
            "velocity": coords[i]["velocity"],
            "momentum": tex(derivation.momenta[i]),
            "rate": tex(derivation.momenta_rates[i]),
            "gradient": tex(derivation.gradients[i]),
            "force": tex(derivation.generalized_forces[i]) if derivation.generalized_forces[i] != 0 else "",
            "lhs": tex(lhs),
            "rhs": tex(rhs),
        })
    elimination = derivation.elimination
    substitutions = [
        {"symbol": tex(sym), "value": tex(val), "source": elimination.sources.get(sym, "")}
        for sym, val in [*elimination.positions.items(), *elimination.velocities.items()]
    ]
    substitutions += [{"symbol": tex(sym), "value": tex(val), "source": ""}
                      for sym, val in derivation.eliminated_accelerations.items()]
    constrained = [
        {"coordinate": coords[i]["tex"], "lhs": tex(lhs), "rhs": tex(rhs)}
        for i, (lhs, rhs) in enumerate(derivation.constrained_sides)
    ]
    lagrange = derivation.lagrange
    accelerations = None if derivation.accelerations is None else [
        {"coordinate": c.name, "symbol": tex(c.acceleration), "symbol_text": text(c.acceleration),
         **both(derivation.accelerations[c.name])}
        for c in problem.coordinates
    ]
    multipliers = None if derivation.multipliers is None else [
        {"name": c.name, "symbol": tex(c.multiplier), "symbol_text": text(c.multiplier),
         **both(derivation.multipliers[c.name])}
        for c in derivation.constraints
    ]
    forces: list[dict[str, Any]] | None = None if derivation.constraint_forces is None else []
    for c in derivation.constraints if forces is not None else ():
        result = derivation.constraint_forces[c.name]  # type: ignore[index]
        forces.append({  # type: ignore[union-attr]
            "name": c.name,
            "vector": [tex(v) for v in result.vector] if result.vector is not None else None,
            "magnitude": both(result.magnitude) if result.magnitude is not None else None,
            "particles": [{"name": p, "vector": [tex(v) for v in vec], "magnitude": both(mag)}
                          for p, vec, mag in result.particles] if len(result.particles) > 1 else [],
            "note": result.note,
            "generalized": [{"coordinate": coords[i]["tex"], "coordinate_text": coords[i]["name"],
                             "value": both(v)} for i, v in enumerate(result.generalized) if v != 0],
        })
    friction = [
        {"name": f.term.name, "particle": f.term.particle, "coefficient": tex(f.term.coefficient),
         "normal": tex(f.term.normal), "normal_text": text(f.term.normal), "constraints": list(f.term.constraints),
         "force": [tex(v) for v in f.term.force],
         "generalized": [{"coordinate": coords[i]["tex"], "value": tex(v)}
                         for i, v in enumerate(f.term.generalized) if v != 0],
         "valid_while": tex(f.term.valid_while),
         # an implicit N is shown by the equation it solves, N = |a + B N|, not as "N = N"
         "normal_force": both(f.system.rhs if f.normal_force == f.term.normal and f.system is not None
                              else f.normal_force),
         "case": f.case, "condition": tex(f.valid_while) if f.valid_while is not None else "",
         "static": tex(f.term.static)}
        for f in derivation.friction
    ]
    return {
        "name": problem.name,
        "description": problem.description,
        "slug": problem.slug,
        "time": tex(problem.time),
        "coordinates": coords,
        "parameters": [{"name": p.name, "tex": tex(p.symbol), "description": p.description,
                        "assumption": "positive" if p.positive else ("real" if p.real else "")}
                       for p in problem.parameters],
        "functions": [{"name": f.name, "tex": tex(sympy.Symbol(f.name)), "description": f.description}
                      for f in problem.functions],
        "particles": [{"name": p.name, "mass": tex(p.mass), "position": [tex(r) for r in p.position]}
                      for p in problem.particles],
        "bodies": [{"name": b.name, "mass": tex(b.mass), "position": [tex(r) for r in b.position],
                    "inertia": [tex(i) for i in b.inertia], "angular_velocity": [tex(w) for w in b.angular_velocity],
                    "planar": b.planar} for b in problem.bodies],
        "gravity": [tex(g) for g in problem.gravity] if problem.gravity is not None else None,
        "kinetic": tex(derivation.kinetic),
        "potential": tex(derivation.potential),
        "lagrangian": tex(derivation.lagrangian),
        "loads": [{"label": t.label, "values": [{"coordinate": coords[i]["tex"], "value": tex(v)}
                                                 for i, v in enumerate(t.generalized) if v != 0]}
                  for t in derivation.force_terms],
        "constraints": constraints,
        "equations": equations,
        "substitutions": substitutions,
        "constrained": constrained if substitutions else [],
        "matrices": {
            "mass": tex(derivation.mass_matrix.applyfunc(sympy.factor_terms)),
            "forcing": tex(derivation.forcing.applyfunc(sympy.factor_terms)),
            "jacobian": tex(lagrange.constraint_jacobian) if derivation.constraints else "",
            "rhs": tex(lagrange.constraint_rhs.applyfunc(sympy.factor_terms)) if derivation.constraints else "",
            "unknowns": tex(sympy.Matrix(list(model.accelerations) + list(derivation.multiplier_symbols))),
        },
        "matrix_equations": [
            {"coordinate": coords[i]["tex"],
             "lhs": tex(sum((derivation.mass_matrix[i, k] * a for k, a in enumerate(model.accelerations)),
                            sympy.Integer(0))),
             "rhs": tex(derivation.forcing[i] + lagrange.constraint_forces[i])}
            for i in range(len(coords))] if len(coords) > LARGE else [],
        "accelerations": accelerations,
        "multipliers": multipliers,
        "unilateral": [{"name": c.name, "multiplier": tex(c.multiplier)} for c in derivation.constraints
                       if c.name in unilateral],
        "forces": forces,
        "friction": friction,
        "analysis": analysis_context(derivation, note, math),
        "hamiltonian": hamiltonian_context(derivation, note, math),
        "notes": [n.sentence() for n in derivation.notes],
        "symbols": symbol_table(dict(problem.symbols), note),
        "math": math,
        "stage_notes": {n.stage: n.reason for n in derivation.notes},
        "units": units_context(derivation, tex),
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


def environment(kind: str, extra: Path | None = None) -> jinja2.Environment:
    """A Jinja2 environment for ``kind`` ("markdown" or "latex"); LaTeX uses ``((* *))``-style delimiters."""
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
    env = jinja2.Environment(**options)  # noqa: S701 - Markdown/TeX are escaped by filters, HTML autoescaped
    env.filters.update(FILTERS)
    return env


def render(derivation: Derivation, fmt: str, templates: Path | None = None,
           simulation: dict[str, Any] | None = None, potential: dict[str, Any] | None = None,
           files: dict[str, bytes] | None = None) -> str:
    """The report of ``derivation`` in ``fmt`` ("md", "tex", "html" or "json").

    ``files`` are the figures the report shows (name → PNG bytes): Markdown and LaTeX refer to them by
    name, the HTML page carries them as ``data:`` URIs so that it is one self-contained file.
    """
    if fmt == "json":
        return result_json(derivation)
    if fmt not in FORMATS:
        raise RenderError(f"unknown format {fmt!r}; use {', '.join(FORMATS)}")
    kind, name = FORMATS[fmt]
    env = environment(kind or "", templates)
    try:
        template = env.get_template(name or "")
    except jinja2.TemplateNotFound:
        searched = ", ".join(str(d) for d in template_dirs(kind or "", templates))
        raise RenderError(f"template {kind}/{name} not found; searched: {searched}") from None
    if fmt == "html":
        simulation, potential = _inlined(simulation, files or {}), _inlined(potential, files or {})
    try:
        return template.render(**context(derivation, "mathml" if fmt == "html" else "latex"), simulation=simulation,
                               potential_plot=potential)
    except jinja2.TemplateError as exc:
        raise RenderError(f"template {kind}/{name} failed: {exc}") from None


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
    problem = derivation.problem
    unilateral = {c.name for c in problem.constraints if c.unilateral}
    forces: dict[str, Any] | None = None if derivation.constraint_forces is None else {}
    for name, result in (derivation.constraint_forces or {}).items():
        entry: dict[str, Any] = {}
        if result.vector is not None:
            entry["vector"] = [to_json(v) for v in result.vector]
        entry["magnitude"] = to_json(result.magnitude) if result.magnitude is not None else None
        if len(result.particles) > 1:
            entry["particles"] = {p: {"vector": [to_json(v) for v in vec], "magnitude": to_json(mag)}
                                  for p, vec, mag in result.particles}
        if result.generalized:
            entry["generalized"] = {q.name: to_json(v)
                                    for q, v in zip(problem.coordinates, result.generalized, strict=True)}
        if result.note:
            entry["note"] = result.note
        forces[name] = entry  # type: ignore[index]
    return {
        "format_version": FORMAT_VERSION,
        "name": problem.name,
        "coordinates": [c.name for c in problem.coordinates],
        "parameters": [p.name for p in problem.parameters],
        "kinetic": to_json(derivation.kinetic),
        "potential": to_json(derivation.potential),
        "lagrangian": to_json(derivation.lagrangian),
        "constraints": {
            c.name: {
                "kind": c.kind,
                "expression": to_json(c.expression),
                "coefficients": {q.name: to_json(a) for q, a in zip(problem.coordinates, c.coefficients, strict=True)},
                "offset": to_json(c.offset),
                **({"unilateral": True} if c.name in unilateral else {}),
            }
            for c in derivation.constraints
        },
        "equations": [to_json(e) for e in derivation.equations],
        "mass_matrix": [[to_json(e) for e in row] for row in derivation.mass_matrix.tolist()],
        "forcing": [to_json(e) for e in derivation.forcing],
        "accelerations": (None if derivation.accelerations is None
                          else {k: to_json(v) for k, v in derivation.accelerations.items()}),
        "multipliers": (None if derivation.multipliers is None
                        else {k: to_json(v) for k, v in derivation.multipliers.items()}),
        "constraint_forces": forces,
        "friction": {
            f.term.name: {
                "normal_force": to_json(f.normal_force),
                "force": [to_json(v) for v in (f.force or f.term.force)],
                "generalized": {q.name: to_json(v)
                                for q, v in zip(problem.coordinates, f.generalized or f.term.generalized, strict=True)},
                "valid_while": to_json(f.term.valid_while),
                "case": f.case,
                "normal_force_valid_while": to_json(f.valid_while) if f.valid_while is not None else None,
                "normal_force_equation": to_json(f.system) if f.system is not None else None,
            }
            for f in derivation.friction
        },
        **contract_json(derivation),
        "analysis": analysis_json(derivation),
        "hamiltonian": hamiltonian_json(derivation),
        "notes": [{"stage": n.stage, "kind": n.kind, "reason": n.reason} for n in derivation.notes],
        **({"units": units} if (units := units_json(derivation)) is not None else {}),
    }


def result_json(derivation: Derivation) -> str:
    """:func:`result_dict` as indented JSON text (stable key order, ASCII only)."""
    return json.dumps(result_dict(derivation), indent=2, ensure_ascii=True) + "\n"


def summary(derivation: Derivation) -> str:
    """The key results, readable in a terminal."""
    ctx = context(derivation)
    lines = [f"{derivation.problem.name}"]
    if ctx["accelerations"] is not None:
        lines.append("  accelerations:")
        lines += [f"    {a['symbol_text']} = {a['text']}" for a in ctx["accelerations"]]
    else:
        lines.append("  equations of motion in matrix form M q̈ = F + Aᵀλ (the explicit accelerations are not given; "
                     "see the report):")
        note = Notation([c.name for c in derivation.problem.coordinates])
        extra = " + Σ λ a" if derivation.constraints else ""
        for i in range(derivation.mass_matrix.rows):
            lhs = sum((derivation.mass_matrix[i, k] * a for k, a in enumerate(derivation.model.accelerations)),
                      sympy.Integer(0))
            lines.append(f"    ({i + 1}) {note.text(lhs)} = {note.text(derivation.forcing[i])}{extra}")
    if ctx["multipliers"]:
        lines.append("  multipliers:")
        lines += [f"    {m['symbol_text']} = {m['text']}" for m in ctx["multipliers"]]
    if ctx["forces"]:
        lines.append("  forces of constraint (magnitude):")
        for f in ctx["forces"]:
            if f["generalized"]:
                parts = ", ".join(f"Q_{g['coordinate_text']} = {g['value']['text']}" for g in f["generalized"])
                lines.append(f"    {f['name']}: generalized forces of constraint (no point named): {parts}")
                continue
            if f["magnitude"] is None and f["particles"]:
                lines += [f"    |F_{f['name']}| on {p['name']} = {p['magnitude']['text']}" for p in f["particles"]]
                continue
            value = f["magnitude"]["text"] if f["magnitude"] else "— " + f["note"]
            lines.append(f"    |F_{f['name']}| = {value}")
    for f in ctx["friction"]:
        lines.append(f"  friction {f['name']}: normal force {f['normal_text']} = {f['normal_force']['text']}")
    lines += analysis_summary(derivation, Notation([c.name for c in derivation.problem.coordinates]))
    lines += hamiltonian_summary(derivation, Notation([c.name for c in derivation.problem.coordinates]))
    if ctx["notes"]:
        lines.append("  not completed:")
        lines += [f"    {n}" for n in ctx["notes"]]
    return "\n".join(lines) + "\n"
