"""The analysis part of the reports: plain context for the templates, the JSON forms, the terminal lines.

:func:`analysis_context` turns :class:`~lagsolve.mechanics.analysis.Analysis` into strings
for ``templates/*/_analysis.*.j2``; :func:`contract_json` prints the format's ``reduced``,
``conserved`` and ``effective_potential``; :func:`analysis_json` the extra ``analysis`` key;
:func:`analysis_summary` the lines shown in a terminal. Nothing here simplifies.
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.integrability import Integrability
from lagsolve.render.notation import Notation, to_json

KINDS = {
    Integrability.HOLONOMIC: "holonomic (as given)",
    Integrability.INTEGRABLE: "integrable: holonomic in disguise",
    Integrability.NONHOLONOMIC: "nonholonomic",
    Integrability.UNRESOLVED: "velocity constraint (integrability not settled)",
}


def _at(q: Any, taken: Any = ()) -> Any:
    """The display symbol of an equilibrium value: ``r`` → ``r_0`` (``r_eq`` when the problem
    already uses ``r0`` or ``r_0``, which print alike)."""
    if f"{q.name}0" in taken or f"{q.name}_0" in taken:
        return sympy.Symbol(f"{q.name}_eq")
    return sympy.Symbol(f"{q.name}_0")


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


def _contact(checks: Any, tex: Any) -> dict[str, Any]:
    """A unilateral constraint's force at an equilibrium, for the templates: ``admissible`` False when one
    would pull, None when a sign depends on the parameters, True when all push, and the multipliers there."""
    if not checks:
        return {"admissible": True, "contact": []}
    verdicts = [c.admissible for c in checks]
    admissible = False if False in verdicts else (None if None in verdicts else True)
    return {"admissible": admissible,
            "contact": [{"constraint": c.constraint, "multiplier": tex(sympy.Symbol(f"lambda_{c.constraint}")),
                         "value": tex(c.multiplier), "admissible": c.admissible} for c in checks]}


def _contact_json(checks: Any) -> dict[str, Any]:
    if not checks:
        return {}
    verdicts = [c.admissible for c in checks]
    return {"admissible": False if False in verdicts else (None if None in verdicts else True),
            "contact": {c.constraint: to_json(c.multiplier) for c in checks}}


def analysis_context(derivation: Derivation, note: Notation, math: str = "latex") -> dict[str, Any] | None:
    """Strings for the analysis sections (None when the derivation carries no analysis); expressions in LaTeX,
    or in presentation MathML when ``math`` is "mathml"."""
    analysis = derivation.analysis
    if analysis is None:
        return None
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text
    constraints = []
    for k in analysis.classification:
        entry: dict[str, Any] = {"name": k.name, "kind": k.kind, "kind_text": KINDS[k.kind], "note": k.note}
        if k.kind != Integrability.HOLONOMIC:
            entry["form"] = (_pfaffian(k.form, k.variables, tex) if math == "latex" else
                             tex(sum((w * sympy.Symbol(f"d{x.name}") for w, x in zip(k.form, k.variables,
                                                                                    strict=True)), sympy.Integer(0))))
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
        constraints.append(entry)

    reduced = None
    r = analysis.reduced
    if r is not None:
        problem_coords = [c.symbol for c in derivation.problem.coordinates]
        reduced = {
            "trivial": not r.substitution.positions,
            "independent": [tex(q) for q in r.independent],
            "dependent": [{"symbol": tex(q), "value": tex(v), "source": r.substitution.sources.get(q, "")}
                          for q, v in r.substitution.positions.items()],
            "velocities": [{"symbol": tex(v), "value": tex(e)} for v, e in r.substitution.velocities.items()],
            "constants": [tex(c) for c in r.constants],
            "kinetic": tex(r.kinetic),
            "potential": tex(r.potential),
            "lagrangian": tex(r.lagrangian),
            "forces": [{"coordinate": tex(q), "value": tex(f)} for q, f in zip(r.independent, r.generalized_forces,
                                                                                strict=True) if f != 0],
            "equations": [{"coordinate": tex(q), "lhs": tex(lhs), "rhs": tex(rhs)}
                          for q, (lhs, rhs) in zip(r.independent, r.equation_sides, strict=True)]
            if r.equation_sides else [],
            "accelerations": [{"symbol": tex(c.acceleration), "tex": tex(r.accelerations[c.name])}
                              for c in derivation.problem.coordinates if c.name in r.accelerations],
            "agreement": r.agreement,
            "all_coordinates": len(r.independent) == len(problem_coords),
        }

    conservation = analysis.conservation
    conserved = []
    for c in conservation.quantities:
        symbol = tex(sympy.Symbol(c.name)) if c.kind == "momentum" else tex(sympy.Symbol("h"))
        conserved.append({
            "name": c.name, "kind": c.kind, "symbol": symbol, "tex": tex(c.expression), "text": text(c.expression),
            "coordinate": tex(c.coordinate) if c.coordinate is not None else "",
            "reason": c.reason, "equals_energy": bool(c.equals_energy), "moving": c.moving, "flags": list(c.flags),
        })

    effective = None
    v = analysis.effective_potential
    if v is not None:
        q = v.coordinate
        q0 = _at(q, derivation.problem.symbols)
        equilibria = []
        checks = analysis.effective_contact or ((),) * len(v.equilibria)
        for e, check in zip(v.equilibria, checks, strict=True):
            power = e.condition.lhs == q or (isinstance(e.condition.lhs, sympy.Pow) and e.condition.lhs.base == q)
            equilibria.append({
                "value": tex(e.value) if e.value is not None and not power else "",
                "condition": tex(e.condition.xreplace({q: q0})),
                "exists_if": tex(e.exists_if.xreplace({q: q0})) if e.exists_if is not None else "",
                "curvature": (tex((e.curvature_at if e.curvature_at is not None else e.curvature).xreplace({q: q0}))
                              if e.curvature is not None else ""),
                "stable": e.stable,
                "stability_condition": (tex(e.stability_condition.xreplace({q: q0}))
                                        if e.stability_condition is not None else ""),
                "frequency": tex(e.frequency.xreplace({q: q0})) if e.frequency is not None else "",
                "frequency_squared": (tex((e.frequency_squared_at if e.frequency_squared_at is not None
                                           else e.frequency_squared).xreplace({q: q0}))
                                      if e.frequency_squared is not None else ""),
                **_contact(check, tex),
            })
        effective = {
            "coordinate": tex(q), "at": tex(q0), "velocity": tex(derivation.model.velocities[
                derivation.model.coordinates.index(q)]),
            "cyclic": [{"coordinate": tex(c), "momentum": tex(p), "velocity": tex(sympy.Symbol(f"{c.name}_dot")),
                        "value": tex(w)} for c, p, w in v.cyclic],
            "routhian": tex(v.routhian), "mass": tex(v.mass), "expression": tex(v.expression),
            "expression_text": text(v.expression),
            "lhs": tex(v.equation[0]), "rhs": tex(v.equation[1]), "damped": v.damped,
            "equilibria": equilibria,
        }

    modes: dict[str, Any] | None = None
    lin = analysis.linearization
    if lin is not None:
        modes = {"coordinates": [tex(q) for q in lin.coordinates], "equilibria": []}
        checks = analysis.modes_contact or ((),) * len(lin.modes)
        for m, check in zip(lin.modes, checks, strict=True):
            has_g, has_d = any(x != 0 for x in m.gyroscopic), any(x != 0 for x in m.damping)
            modes["equilibria"].append({
                "point": [{"coordinate": tex(q), "value": tex(x)} for q, x in m.point],
                "free": [tex(q) for q in m.free],
                "mass": tex(m.mass), "stiffness": tex(m.stiffness),
                "gyroscopic": tex(m.gyroscopic) if has_g else "", "damping": tex(m.damping) if has_d else "",
                "squares": [tex(s) for s in m.squared_frequencies] if m.squared_frequencies is not None else [],
                "frequencies": [tex(f) if f is not None else "" for f in m.frequencies] if m.frequencies else [],
                "stable": m.stable, "note": m.note, **_contact(check, tex),
            })
    return {
        "constraints": constraints,
        "velocity_constraints": any(k.kind != Integrability.HOLONOMIC for k in analysis.classification),
        "reduced": reduced,
        "reduced_note": analysis.reduced_note,
        "system": analysis.system.kind,
        "conserved": conserved,
        "conserved_notes": list(conservation.notes),
        "cyclic": [tex(q) for q in conservation.cyclic],
        "effective": effective,
        "effective_note": analysis.effective_note,
        "modes": modes,
        "equilibria_note": (analysis.linearization_note if "coordinates are left" in analysis.effective_note
                            else analysis.effective_note),
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


def contract_json(derivation: Derivation) -> dict[str, Any]:
    """``reduced``, ``conserved``, ``effective_potential`` of format section 2, as JSON values."""
    return {
        "reduced": _json(derivation.reduced),
        "conserved": _json(derivation.conserved),
        "effective_potential": _json(derivation.effective_potential),
    }


def analysis_json(derivation: Derivation) -> dict[str, Any] | None:
    """The extra ``analysis`` key: classification, reduction steps, reasons, equilibria, normal modes."""
    analysis = derivation.analysis
    if analysis is None:
        return None
    constraints = {}
    for k in analysis.classification:
        entry: dict[str, Any] = {"class": k.kind}
        if k.kind == Integrability.INTEGRABLE:
            entry.update({"factor": to_json(k.factor), "integral": to_json(k.integral),
                          "constant": to_json(k.constant)})
            if k.solved:
                entry["solved"] = {k.solved[0].name: to_json(k.solved[1])}
        if k.witness is not None:
            entry["frobenius"] = {"variables": [to_json(x) for x in k.witness[0]], "value": to_json(k.witness[1])}
        if k.note:
            entry["note"] = k.note
        constraints[k.name] = entry
    out: dict[str, Any] = {"constraints": constraints}
    r = analysis.reduced
    if r is None:
        out["reduced"] = {"note": analysis.reduced_note}
    else:
        out["reduced"] = {
            "dependent": {q.name: to_json(v) for q, v in r.substitution.positions.items()},
            "constants": [to_json(c) for c in r.constants],
            "lagrangian": to_json(r.lagrangian),
            "generalized_forces": {q.name: to_json(f) for q, f in zip(r.independent, r.generalized_forces,
                                                                       strict=True)},
            "agreement": r.agreement,
        }
    out["conserved"] = {c.name: {"reason": c.reason, **({"equals_total_energy": c.equals_energy}
                                                        if c.kind == "jacobi" else {})}
                        for c in analysis.conservation.quantities}
    out["conserved_notes"] = list(analysis.conservation.notes)
    v = analysis.effective_potential
    if v is None:
        out["effective_potential"] = {"note": analysis.effective_note}
    else:
        out["effective_potential"] = {
            "mass": to_json(v.mass), "routhian": to_json(v.routhian),
            "equilibria": [{"condition": to_json(e.condition),
                            "exists_if": to_json(e.exists_if) if e.exists_if is not None else None,
                            "stability_condition": (to_json(e.stability_condition)
                                                    if e.stability_condition is not None else None),
                            "frequency_squared_at": (to_json(e.frequency_squared_at)
                                                     if e.frequency_squared_at is not None else None),
                            **_contact_json(check)}
                           for e, check in zip(v.equilibria, analysis.effective_contact or ((),) * len(v.equilibria),
                                               strict=True)],
        }
    lin = analysis.linearization
    if lin is None:
        out["linearization"] = {"note": analysis.linearization_note}
    else:
        out["linearization"] = {
            "coordinates": [q.name for q in lin.coordinates],
            "equilibria": [{
                "point": {q.name: to_json(x) for q, x in m.point},
                "mass": [[to_json(x) for x in row] for row in m.mass.tolist()],
                "stiffness": [[to_json(x) for x in row] for row in m.stiffness.tolist()],
                "gyroscopic": [[to_json(x) for x in row] for row in m.gyroscopic.tolist()],
                "damping": [[to_json(x) for x in row] for row in m.damping.tolist()],
                "squared_frequencies": ([to_json(s) for s in m.squared_frequencies]
                                        if m.squared_frequencies is not None else None),
                "stable": m.stable,
                **({"free": [q.name for q in m.free]} if m.free else {}),
                **_contact_json(check),
            } for m, check in zip(lin.modes, analysis.modes_contact or ((),) * len(lin.modes), strict=True)],
        }
    return out


def analysis_summary(derivation: Derivation, note: Notation) -> list[str]:
    """Terminal lines: minimal coordinates, conserved quantities, effective potential and equilibria."""
    analysis = derivation.analysis
    if analysis is None:
        return []
    text = note.text
    lines = []
    for k in analysis.classification:
        if k.kind == Integrability.INTEGRABLE and k.solved:
            lines.append(f"  constraint {k.name}: integrable, {text(k.solved[0])} = {text(k.solved[1])}")
        elif k.kind in (Integrability.NONHOLONOMIC, Integrability.UNRESOLVED):
            lines.append(f"  constraint {k.name}: {k.kind}")
    r = analysis.reduced
    if r is not None and r.substitution.positions:
        agree = {"symbolic": "agrees with the multiplier route",
                 "numeric": "agrees with the multiplier route (numerically)",
                 "differ": "DIFFERS from the multiplier route"}[r.agreement]
        lines.append(f"  minimal coordinates: {', '.join(text(q) for q in r.independent)} ({agree})")
    if analysis.conservation.quantities:
        lines.append("  conserved:")
        for c in analysis.conservation.quantities:
            symbol = text(sympy.Symbol(c.name)) if c.kind == "momentum" else "h"
            extra = " (= T + V)" if c.equals_energy else (" (not T + V)" if c.kind == "jacobi" else "")
            lines.append(f"    {symbol} = {text(c.expression)}{extra}")
    v = analysis.effective_potential
    if v is not None:
        q, q0 = v.coordinate, _at(v.coordinate, derivation.problem.symbols)
        lines.append(f"  effective potential: V_eff({text(q)}) = {text(v.expression)}")
        for k, e in enumerate(v.equilibria):
            condition = e.condition.xreplace({q: q0})
            power = e.condition.lhs == q or (isinstance(e.condition.lhs, sympy.Pow) and e.condition.lhs.base == q)
            where = (f"{text(q0)} = {text(e.value)}" if e.value is not None and not power
                     else f"{text(condition.lhs)} = {text(condition.rhs)}")
            if e.stable is True:
                verdict = "stable"
            elif e.stable is False:
                verdict = "unstable"
            elif e.stability_condition is not None:
                verdict = f"stable if {text(e.stability_condition.xreplace({q: q0}))}"
            else:
                verdict = "stability not analysed (several momenta)"
            line = f"    equilibrium {where}: {verdict}"
            if e.frequency_squared is not None:
                square = e.frequency_squared_at if e.frequency_squared_at is not None else e.frequency_squared
                line += f", ω² = {text(square.xreplace({q: q0}))}"
            line += _contact_summary(analysis.effective_contact[k] if analysis.effective_contact else (), text)
            lines.append(line)
    lin = analysis.linearization
    if lin is not None:
        lines.append("  equilibria:")
        for k, m in enumerate(lin.modes):
            point = ", ".join([f"{text(q)} = {text(x)}" for q, x in m.point]
                              + ([f"any {', '.join(text(q) for q in m.free)}"] if m.free else []))
            verdict = {True: "stable", False: "unstable", None: "stability not decided"}[m.stable]
            squares = ""
            if m.squared_frequencies is not None and m.stable:
                squares = ", ω² = " + "; ".join(text(s) for s in m.squared_frequencies)
            contact = _contact_summary(analysis.modes_contact[k] if analysis.modes_contact else (), text)
            lines.append(f"    {point}: {verdict}{squares}{contact}")
    return lines


def _contact_summary(checks: Any, text: Any) -> str:
    """`` (not admissible: surface would pull, λ = -g m)`` for a terminal line; empty when every force pushes."""
    pulling = [c for c in checks if c.admissible is False]
    if pulling:
        return " (not admissible: " + "; ".join(f"{c.constraint} would pull, λ = {text(c.multiplier)}"
                                                for c in pulling) + ")"
    open_ = [c for c in checks if c.admissible is None]
    if open_:
        return " (only while " + "; ".join(f"{text(c.multiplier)} ≥ 0" for c in open_) + ")"
    return ""
