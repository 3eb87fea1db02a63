"""The analysis part of the reports: projections of :class:`~lagsolve.render.sections.analysis.AnalysisSection`.

:func:`analysis_context` gives the strings for ``templates/*/_analysis.*.j2``; :func:`contract_json` prints the
format's ``reduced``, ``conserved`` and ``effective_potential``; :func:`analysis_json` the extra ``analysis``
key; :func:`analysis_summary` the lines shown in a terminal. Nothing here simplifies.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.integrability import Integrability
from lagsolve.render.notation import Notation, to_json
from lagsolve.render.sections.analysis import (
    AnalysisSection,
    Classified,
    Contacts,
    Effective,
    Modes,
    Reduced,
    Steady,
)

KINDS = {
    Integrability.HOLONOMIC: "holonomic (as given)",
    Integrability.INTEGRABLE: "integrable: holonomic in disguise",
    Integrability.NONHOLONOMIC: "nonholonomic",
    Integrability.UNRESOLVED: "velocity constraint (integrability not settled)",
}


def _pfaffian(form: tuple[Any, ...], variables: tuple[Any, ...], tex: Any) -> str:
    """``a_1 dq_1 + ... + b dt`` in LaTeX (zero terms left out)."""
    out = ""
    for w, x in zip(form, variables, strict=True):
        if w == 0:
            continue
        negative = not isinstance(w, sympy.Add) and w.could_extract_minus_sign()
        size = -w if negative else w
        coefficient = "" if size == 1 else (r"\left(" + tex(size) + r"\right)\," if isinstance(size, sympy.Add)
                                            else tex(size) + r"\,")
        sign = ("-" if negative else "") if not out else (" - " if negative else " + ")
        out += f"{sign}{coefficient}d{tex(x)}"
    return out or "0"


def _contact(contacts: Contacts, tex: Any) -> dict[str, Any]:
    """A unilateral constraint's force at an equilibrium, for the templates: ``admissible`` False when one
    would pull, None when a sign depends on the parameters, True when all push, and the multipliers there."""
    return {"admissible": contacts.admissible,
            "contact": [{"constraint": c.constraint, "multiplier": tex(c.symbol), "value": tex(c.value),
                         "admissible": c.admissible} for c in contacts.checks]}


def _contact_json(contacts: Contacts) -> dict[str, Any]:
    if not contacts.checks:
        return {}
    return {"admissible": contacts.admissible, "contact": {c.constraint: to_json(c.value) for c in contacts.checks}}


def _classified_context(k: Classified, tex: Any, math: str) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": k.name, "kind": k.kind, "kind_text": KINDS[k.kind], "note": k.note}
    if k.kind != Integrability.HOLONOMIC:
        form, variables = tuple(w for w, _ in k.differential), tuple(x for _, x in k.differential)
        entry["form"] = (_pfaffian(form, variables, tex) if math == "latex" else
                         tex(sum((w * sympy.Symbol(f"d{x.name}") for w, x in k.differential), sympy.Integer(0))))
        entry["exact"] = k.exact
        entry["factor"] = tex(k.factor) if k.factor is not None and k.factor != 1 else ""
    if k.kind == Integrability.INTEGRABLE:
        entry["integral"] = tex(k.integral)
        entry["constant"] = tex(k.constant)
        entry["solved"] = ({"symbol": tex(k.solved[0]), "value": tex(k.solved[1])}
                           if k.solved and k.integral != k.solved[0] else None)
    if k.witness is not None:
        (a, b, c), value = k.witness
        entry["witness"] = {"indices": f"{tex(a)}{tex(b)}{tex(c)}" if all(len(tex(s)) == 1 for s in (a, b, c))
                            else f"{tex(a)},{tex(b)},{tex(c)}", "value": tex(value)}
    return entry


def _reduced_context(r: Reduced, tex: Any) -> dict[str, Any]:
    return {
        "trivial": r.trivial,
        "independent": [tex(q) for q in r.independent],
        "dependent": [{"symbol": tex(d.symbol), "value": tex(d.value), "source": d.source} for d in r.dependent],
        "velocities": [{"symbol": tex(v), "value": tex(e)} for v, e in r.velocities],
        "constants": [tex(c) for c in r.constants],
        "kinetic": tex(r.kinetic),
        "potential": tex(r.potential),
        "lagrangian": tex(r.lagrangian),
        "forces": [{"coordinate": tex(q), "value": tex(f)} for q, f in r.forces if f != 0],
        "equations": [{"coordinate": tex(q), "lhs": tex(lhs), "rhs": tex(rhs)} for q, lhs, rhs in r.equations],
        "accelerations": [{"symbol": tex(a), "tex": tex(value)} for a, value in r.accelerations],
        "agreement": r.agreement,
        "agreement_sentence": r.agreement_text[1],
        "agreement_warning": r.agreement_text[2],
        "all_coordinates": r.all_coordinates,
    }


def _effective_context(v: Effective, tex: Any, text: Any) -> dict[str, Any]:
    def shown(expr: Any) -> str:
        return tex(expr) if expr is not None else ""

    equilibria = [{
        "value": shown(e.value), "condition": tex(e.condition), "exists_if": shown(e.exists_if),
        "curvature": shown(e.curvature), "stable": e.stable, "stability_condition": shown(e.stability_condition),
        "frequency": shown(e.frequency), "frequency_squared": shown(e.frequency_squared), **_contact(e.contact, tex),
    } for e in v.equilibria]
    return {
        "coordinate": tex(v.coordinate), "at": tex(v.at), "velocity": tex(v.velocity),
        "cyclic": [{"coordinate": tex(c.coordinate), "momentum": tex(c.momentum), "velocity": tex(c.velocity),
                    "value": tex(c.value)} for c in v.cyclic],
        "routhian": tex(v.routhian), "mass": tex(v.mass), "expression": tex(v.expression),
        "expression_text": text(v.expression),
        "lhs": tex(v.equation[0]), "rhs": tex(v.equation[1]), "damped": v.damped,
        "equilibria": equilibria,
    }


def _vector(u: tuple[Any, ...], tex: Any, math: str) -> str:
    """A mode shape as a row, (1, -1)."""
    if math == "latex":
        return r"\left(" + ", ".join(tex(c) for c in u) + r"\right)"
    return tex(sympy.Tuple(*u))


def _steady_context(s: Steady, tex: Any) -> dict[str, Any]:
    def shown(expr: Any) -> str:
        return tex(expr) if expr is not None else ""

    return {
        "coordinate": tex(s.coordinate), "at": tex(s.at), "rate": tex(s.rate), "velocity": tex(s.velocity),
        "held": [{"coordinate": tex(c), "momentum": tex(p), "value": tex(v)} for c, p, v in s.held],
        "velocities": [{"symbol": tex(v), "value": tex(e)} for v, e in s.velocities],
        "momentum": {"symbol": tex(s.momentum[0]), "value": tex(s.momentum[1])},
        "condition": tex(s.condition), "condition_lhs": tex(s.condition.lhs),
        "qdot": tex(s.coordinate_velocity), "qddot": tex(s.coordinate_acceleration),
        "excluded": [tex(sympy.Eq(e, 0)) for e in s.excluded],
        "roots": [tex(r) for r in s.roots] if s.square is None else [],
        "square": shown(s.square), "exists_if": shown(s.exists_if),
        "limits": {"slow": tex(s.limits[0]), "fast": tex(s.limits[1])} if s.limits is not None else None,
        "mass": tex(s.mass), "frequency_squared": tex(s.frequency_squared),
        "frequency_squared_at": shown(s.frequency_squared_at),
        "eliminated": ({"symbol": tex(s.eliminated[0]), "value": tex(s.eliminated[1])}
                       if s.eliminated is not None else None),
        "stable": s.stable, "stability_condition": shown(s.stability_condition), "verified": s.verified,
    }


def _modes_context(modes: Modes, tex: Any, math: str = "latex") -> dict[str, Any]:
    equilibria = []
    for m in modes.equilibria:
        has_g, has_d = any(x != 0 for x in m.gyroscopic), any(x != 0 for x in m.damping)
        equilibria.append({
            "point": [{"coordinate": tex(q), "value": tex(x)} for q, x in m.point],
            "free": [tex(q) for q in m.free],
            "mass": tex(m.mass), "stiffness": tex(m.stiffness),
            "gyroscopic": tex(m.gyroscopic) if has_g else "", "damping": tex(m.damping) if has_d else "",
            "squares": [tex(s) for s in m.squared_frequencies] if m.squared_frequencies is not None else [],
            "frequencies": [tex(f) if f is not None else "" for f in m.frequencies] if m.frequencies else [],
            "stable": m.stable, "note": m.note, **_contact(m.contact, tex),
            "shapes": [_vector(u, tex, math) for u in m.shapes] if m.shapes and m.squared_frequencies else [],
        })
    return {"coordinates": [tex(q) for q in modes.coordinates], "equilibria": equilibria, "search": modes.search}


def analysis_context(section: AnalysisSection | None, note: Notation, math: str = "latex") -> dict[str, Any] | None:
    """Strings for the analysis sections (None when the derivation carries no analysis); expressions in LaTeX,
    or in presentation MathML when ``math`` is "mathml"."""
    if section is None:
        return None
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text
    conserved = [{
        "name": c.name, "kind": c.kind, "symbol": tex(c.symbol), "tex": tex(c.expression), "text": text(c.expression),
        "coordinate": tex(c.coordinate) if c.coordinate is not None else "",
        "reason": c.reason, "equals_energy": bool(c.equals_energy), "moving": c.moving, "flags": list(c.flags),
        "symmetry": c.symmetry,
        "generator": [{"coordinate": tex(q), "value": tex(x), "unit": x == 1} for q, x in c.generator],
    } for c in section.conserved]
    return {
        "constraints": [_classified_context(k, tex, math) for k in section.constraints],
        "velocity_constraints": section.velocity_constraints,
        "reduced": _reduced_context(section.reduced, tex) if section.reduced is not None else None,
        "reduced_note": section.reduced_note,
        "system": section.system,
        "conserved": conserved,
        "conserved_notes": list(section.conserved_notes),
        "verified": section.verified,
        "cyclic": [tex(q) for q in section.cyclic],
        "effective": _effective_context(section.effective, tex, text) if section.effective is not None else None,
        "effective_note": section.effective_note,
        "modes": _modes_context(section.modes, tex, math) if section.modes is not None else None,
        "equilibria_note": section.equilibria_note,
        "steady": _steady_context(section.steady, tex) if section.steady is not None else None,
    }


def _json(value: Any) -> Any:
    """Contract values: expressions as strings, containers walked, plain values kept."""
    if isinstance(value, dict):
        return {k: _json(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json(v) for v in value]
    if value is None or isinstance(value, bool | int | float | str):
        return value
    return to_json(value)


def contract_json(contract: tuple[tuple[str, Any], ...]) -> dict[str, Any]:
    """``reduced``, ``conserved``, ``effective_potential`` of format section 2 (the derivation's contract forms,
    :attr:`~lagsolve.render.sections.core.CoreSections.contract`), as JSON values."""
    return {key: _json(value) for key, value in contract}


def _classified_json(k: Classified) -> dict[str, Any]:
    entry: dict[str, Any] = {"class": k.kind}
    if k.kind == Integrability.INTEGRABLE:
        entry.update({"factor": to_json(k.factor), "integral": to_json(k.integral), "constant": to_json(k.constant)})
        if k.solved:
            entry["solved"] = {k.solved[0].name: to_json(k.solved[1])}
    if k.witness is not None:
        entry["frobenius"] = {"variables": [to_json(x) for x in k.witness[0]], "value": to_json(k.witness[1])}
    if k.note:
        entry["note"] = k.note
    return entry


def _matrix_json(m: Any) -> list[list[str]]:
    return [[to_json(x) for x in row] for row in m.tolist()]


def analysis_json(section: AnalysisSection | None) -> dict[str, Any] | None:
    """The extra ``analysis`` key: classification, reduction steps, reasons, equilibria, normal modes."""
    if section is None:
        return None
    out: dict[str, Any] = {"constraints": {k.name: _classified_json(k) for k in section.constraints}}
    r = section.reduced
    out["reduced"] = {"note": section.reduced_note} if r is None else {
        "dependent": {d.symbol.name: to_json(d.value) for d in r.dependent},
        "constants": [to_json(c) for c in r.constants],
        "lagrangian": to_json(r.lagrangian),
        "generalized_forces": {q.name: to_json(f) for q, f in r.forces},
        "agreement": r.agreement,
    }
    out["conserved"] = {c.name: {"reason": c.reason, **({"equals_total_energy": c.equals_energy}
                                                        if c.kind == "jacobi" else {}),
                                 **({"symmetry": c.symmetry, "generator": {q.name: to_json(x) for q, x in c.generator}}
                                    if c.symmetry else {})}
                        for c in section.conserved}
    out["conserved_notes"] = list(section.conserved_notes)
    v = section.effective

    def maybe(expr: Any) -> str | None:
        return to_json(expr) if expr is not None else None

    out["effective_potential"] = {"note": section.effective_note} if v is None else {
        "mass": to_json(v.mass), "routhian": to_json(v.routhian),
        "equilibria": [{"condition": to_json(e.derived.condition), "exists_if": maybe(e.derived.exists_if),
                        "stability_condition": maybe(e.derived.stability_condition),
                        "frequency_squared_at": maybe(e.derived.frequency_squared_at), **_contact_json(e.contact)}
                       for e in v.equilibria],
    }
    out["steady_motions"] = _steady_json(section.steady) if section.steady is not None else {
        "note": section.steady_note}
    modes = section.modes
    out["linearization"] = {"note": section.linearization_note} if modes is None else {
        "coordinates": [q.name for q in modes.coordinates],
        "equilibria": [{
            "point": {q.name: to_json(x) for q, x in m.point},
            "mass": _matrix_json(m.mass), "stiffness": _matrix_json(m.stiffness),
            "gyroscopic": _matrix_json(m.gyroscopic), "damping": _matrix_json(m.damping),
            "squared_frequencies": ([to_json(s) for s in m.squared_frequencies]
                                    if m.squared_frequencies is not None else None),
            "mode_shapes": ([{q.name: to_json(x) for q, x in zip(modes.coordinates, u, strict=True)} for u in m.shapes]
                            if m.shapes is not None else None),
            "stable": m.stable,
            **({"free": [q.name for q in m.free]} if m.free else {}),
            **({"note": m.note} if m.note else {}),
            **_contact_json(m.contact),
        } for m in modes.equilibria],
        **({"search": modes.search} if modes.search else {}),
    }
    return out


def _steady_json(s: Steady) -> dict[str, Any]:
    """The steady motions in the JSON, in the coordinate's own name (standing for its steady value)."""
    d = s.derived

    def maybe(expr: Any) -> str | None:
        return to_json(expr) if expr is not None else None

    return {
        "coordinate": d.coordinate.name, "rate": d.rate.name,
        "held": {p.name: to_json(value) for _, p, value in d.held},
        "velocities": {v.name: to_json(value) for v, value in d.velocities},
        "momentum": {d.momentum[0].name: to_json(d.momentum[1])},
        "condition": to_json(d.condition.lhs), "coefficients": [to_json(c) for c in d.coefficients],
        "excluded": [to_json(e) for e in d.excluded], "values": [to_json(r) for r in d.roots],
        "exists_if": maybe(d.exists_if),
        "slow_fast": [to_json(x) for x in d.limits] if d.limits is not None else None,
        "mass": to_json(d.mass), "curvature": to_json(d.curvature),
        "frequency_squared": to_json(d.frequency_squared), "frequency_squared_at": maybe(d.frequency_squared_at),
        "eliminated": {d.eliminated[0].name: to_json(d.eliminated[1])} if d.eliminated is not None else None,
        "stable": d.stable, "stability_condition": maybe(d.stability_condition), "verified": d.verified,
    }


def analysis_summary(section: AnalysisSection | None, note: Notation) -> list[str]:
    """Terminal lines: minimal coordinates, conserved quantities, effective potential and equilibria."""
    if section is None:
        return []
    text = note.text
    lines = []
    for k in section.constraints:
        if k.kind == Integrability.INTEGRABLE and k.solved:
            lines.append(f"  constraint {k.name}: integrable, {text(k.solved[0])} = {text(k.solved[1])}")
        elif k.kind in (Integrability.NONHOLONOMIC, Integrability.UNRESOLVED):
            lines.append(f"  constraint {k.name}: {k.kind}")
    r = section.reduced
    if r is not None and not r.trivial:
        lines.append(f"  minimal coordinates: {', '.join(text(q) for q in r.independent)} ({r.agreement_text[0]})")
    if section.conserved:
        lines.append("  conserved:")
        for c in section.conserved:
            extra = " (= T + V)" if c.equals_energy else (" (not T + V)" if c.kind == "jacobi" else "")
            extra += f" ({c.symmetry})" if c.kind == "noether" else ""
            lines.append(f"    {text(c.symbol)} = {text(c.expression)}{extra}")
    if section.effective is not None:
        lines += _effective_summary(section.effective, text)
    if section.steady is not None:
        lines += _steady_summary(section.steady, text)
    if section.modes is not None:
        lines.append("  equilibria:")
        for m in section.modes.equilibria:
            point = ", ".join([f"{text(q)} = {text(x)}" for q, x in m.point]
                              + ([f"any {', '.join(text(q) for q in m.free)}"] if m.free else []))
            verdict = {True: "stable", False: "unstable", None: "stability not decided"}[m.stable]
            squares = ""
            if m.squared_frequencies is not None and m.stable and not m.shapes:
                squares = ", ω² = " + "; ".join(text(s) for s in m.squared_frequencies)
            lines.append(f"    {point}: {verdict}{squares}{_contact_summary(m.contact, text)}")
            if m.squared_frequencies is not None and m.stable and m.shapes:
                lines += [f"      ω² = {text(s)}, mode shape {text(sympy.Tuple(*u))}"
                          for s, u in zip(m.squared_frequencies, m.shapes, strict=True)]
    return lines


def _effective_summary(v: Effective, text: Any) -> list[str]:
    lines = [f"  effective potential: V_eff({text(v.coordinate)}) = {text(v.expression)}"]
    for e in v.equilibria:
        where = (f"{text(v.at)} = {text(e.value)}" if e.value is not None
                 else f"{text(e.condition.lhs)} = {text(e.condition.rhs)}")
        if e.stable is True:
            verdict = "stable"
        elif e.stable is False:
            verdict = "unstable"
        elif e.stability_condition is not None:
            verdict = f"stable if {text(e.stability_condition)}"
        else:
            verdict = "stability not analysed (several momenta)"
        line = f"    equilibrium {where}: {verdict}"
        if e.frequency_squared is not None:
            line += f", ω² = {text(e.frequency_squared)}"
        lines.append(line + _contact_summary(e.contact, text))
    return lines


def _steady_summary(s: Steady, text: Any) -> list[str]:
    held = "".join(f", {text(p)} held" for _, p, _ in s.held)
    lines = [f"  steady motions ({text(s.at)} fixed, {text(s.velocity)} constant{held}): "
             f"{text(s.condition.lhs)} = {text(s.condition.rhs)}"]
    if s.square is not None:
        lines.append(f"    {text(s.velocity)}² = {text(s.square)}")
    else:
        lines += [f"    {text(s.velocity)} = {text(r)}" for r in s.roots]
    if s.exists_if is not None:
        lines.append(f"    real when {text(s.exists_if)}")
    verdict = {True: "stable", False: "unstable"}.get(s.stable) if s.stable is not None else (
        f"stable if {text(s.stability_condition)}" if s.stability_condition is not None else "stability not decided")
    at = f" = {text(s.frequency_squared_at)}" if s.frequency_squared_at is not None else ""
    lines.append(f"    {verdict}, ω² = {text(s.frequency_squared)}{at}")
    return lines


def _contact_summary(contacts: Contacts, text: Any) -> str:
    """`` (not admissible: surface would pull, λ = -g m)`` for a terminal line; empty when every force pushes."""
    pulling = [c for c in contacts.checks if c.admissible is False]
    if pulling:
        return " (not admissible: " + "; ".join(f"{c.constraint} would pull, λ = {text(c.value)}"
                                                for c in pulling) + ")"
    open_ = [c for c in contacts.checks if c.admissible is None]
    if open_:
        return " (only while " + "; ".join(f"{text(c.value)} ≥ 0" for c in open_) + ")"
    return ""
