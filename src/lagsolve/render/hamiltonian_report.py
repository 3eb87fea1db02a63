"""The Hamiltonian part of the reports: plain context for ``templates/*/_hamiltonian.*.j2``, the JSON key
``hamiltonian`` and the terminal lines. Nothing here simplifies (every expression arrives in display form).
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.hamiltonian import T2_T0_V0, Hamiltonian
from lagsolve.render.notation import Notation, to_json


def _back(derivation: Derivation) -> dict[Any, Any]:
    """Constants of integration written back as the integrals they stand for (as ``contract_forms`` does)."""
    analysis = derivation.analysis
    if analysis is None:
        return {}
    return {k.constant: k.integral for k in analysis.classification if k.constant is not None}


def hamiltonian_context(derivation: Derivation, note: Notation, math: str = "latex") -> dict[str, Any] | None:
    """Strings for the Hamiltonian section (None without an analysis); expressions in LaTeX, or in presentation
    MathML when ``math`` is "mathml". ``applies`` False carries the ``reason``."""
    if derivation.analysis is None:
        return None
    h = derivation.hamiltonian
    if h is None:
        return {"applies": False, "reason": derivation.hamiltonian_note or "not derived"}
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text
    coordinates = []
    for i, q in enumerate(h.coordinates):
        coordinates.append({
            "coordinate": tex(q), "velocity": tex(h.velocities[i]), "momentum": tex(h.momentum_symbols[i]),
            "momentum_text": text(h.momentum_symbols[i]), "rate_symbol": _dotted(tex(h.momentum_symbols[i]), math),
            "momentum_value": tex(h.momenta[i]), "inverse": tex(h.inverse[i]), "rate": tex(h.rates[i]),
            "momentum_rate": tex(_momentum_rate(h, i)), "momentum_rate_text": text(_momentum_rate(h, i)),
            "rate_text": text(h.rates[i]),
            "force": tex(h.forces[i]) if h.forces[i] != 0 else "",
            "dissipation": tex(h.dissipation[i]) if h.dissipation[i] != 0 else "",
        })
    T2, T1, T0 = h.kinetic_parts
    linear = any(not b.is_zero for b in h.offset)
    routhian = None
    r = h.routhian
    if r is not None:
        routhian = {
            "cyclic": [{"coordinate": tex(c), "momentum": tex(p), "velocity": tex(sympy.Symbol(f"{c.name}_dot")),
                        "value": tex(v), "rate": tex(w)}
                       for c, p, v, w in zip(r.cyclic, r.momenta, r.velocities, r.cyclic_rates, strict=True)],
            "expression": tex(r.expression),
            "equations": [{"coordinate": tex(q), "lhs": tex(lhs), "rhs": tex(rhs)}
                          for q, (lhs, rhs) in zip(r.coordinates, r.equations, strict=True)],
            "coordinates": [tex(q) for q in r.coordinates],
            "single": len(r.coordinates) == 1,
        }
    brackets = [{"name": b.name, "symbol": tex(sympy.Symbol(b.name)) if b.name != "energy" else tex(sympy.Symbol("h")),
                 "quantity": tex(b.quantity), "bracket": tex(b.bracket), "partial_t": tex(b.partial_t),
                 "forces": tex(b.forces) if b.forces != 0 else "", "rate": tex(b.rate), "status": b.status,
                 "same": "H" if b.quantity == h.expression else ("momentum" if b.quantity in h.momentum_symbols
                                                                 and b.name == b.quantity.name else "")}
                for b in h.brackets]
    sizes = [sympy.count_ops(e) for e in (h.expression, *h.inverse, *h.rates)]
    compact = max(sizes) > COMPACT_LIMIT or max(sympy.count_ops(e) for e in h.momentum_rates) > 2 * COMPACT_LIMIT
    return {
        "applies": True,
        "compact": compact,
        "remainder": tex(h.remainder),
        "coordinates": coordinates,
        "lagrangian": tex(h.lagrangian),
        "mass": tex(h.mass),
        "offset": tex(h.offset) if linear else "",
        "velocities": tex(sympy.Matrix(h.velocities)),
        "momenta_vector": tex(sympy.Matrix(h.momentum_symbols)),
        "diagonal": h.mass.is_diagonal(),
        "expression": tex(h.expression),
        "expression_text": text(h.expression),
        "form": h.form,
        "magnetic": h.form == T2_T0_V0,
        "kinetic_two": tex(T2), "kinetic_one": tex(T1) if T1 != 0 else "", "kinetic_zero": tex(T0) if T0 != 0 else "",
        "time_dependent": h.time_dependent,
        "forces": any(f != 0 for f in h.forces),
        "dissipation": any(d != 0 for d in h.dissipation),
        "routhian": routhian,
        "routhian_note": h.routhian_note,
        "brackets": brackets,
    }


#: past this many operations H, q̇(q, p) and Hamilton's equations are shown in matrix form (in full in the JSON)
COMPACT_LIMIT = 45


def _dotted(momentum: str, math: str) -> str:
    r""":math:`\dot p_q` from the printed :math:`p_q` (LaTeX ``p_{q}`` or MathML ``<msub><mi>p</mi>...``)."""
    if math == "mathml":
        return momentum.replace("<mi>p</mi>", '<mover accent="true"><mi>p</mi><mo>&#729;</mo></mover>', 1)
    return "\\dot{p}" + momentum[1:]


def _momentum_rate(h: Hamiltonian, i: int) -> Any:
    r""":math:`\dot p_i` in full: :math:`-\partial H/\partial q_i + Q_i - \partial\mathcal R/\partial\dot q_i`."""
    return sympy.Add(h.momentum_rates[i], h.forces[i], h.dissipation[i])


def hamiltonian_json(derivation: Derivation) -> dict[str, Any] | None:
    """The ``hamiltonian`` key: ``coordinates``, ``momenta`` (``p_<q>`` in q and q_dot), ``H`` (in q and p),
    ``equations`` (``<q>_dot``, ``p_<q>_dot`` in q and p), ``form``, ``routhian`` (or null) and
    ``poisson_brackets``; ``{"not_applicable": reason}`` where there is none by the physics, null when its
    stage did not finish (the ``notes`` say why) or there is no analysis."""
    h = derivation.hamiltonian
    if h is None:
        analysis = derivation.analysis
        stopped = any(n.stage == "hamiltonian" for n in derivation.notes)
        if analysis is None or stopped or not derivation.hamiltonian_note:
            return None
        return {"not_applicable": derivation.hamiltonian_note}
    back = _back(derivation)

    def js(expr: Any) -> str:
        return to_json(expr.xreplace(back) if isinstance(expr, sympy.Basic) else expr)

    equations: dict[str, str] = {}
    for i, q in enumerate(h.coordinates):
        equations[f"{q.name}_dot"] = js(h.rates[i])
    for i, p in enumerate(h.momentum_symbols):
        equations[f"{p.name}_dot"] = js(_momentum_rate(h, i))
    r = h.routhian
    routhian = None if r is None else {
        "cyclic": [c.name for c in r.cyclic],
        "expression": js(r.expression),
        "velocities": {f"{c.name}_dot": js(v) for c, v in zip(r.cyclic, r.velocities, strict=True)},
        "equations": {q.name: {"lhs": js(lhs), "rhs": js(rhs)} for q, (lhs, rhs) in zip(r.coordinates, r.equations,
                                                                                      strict=True)},
    }
    return {
        "coordinates": [q.name for q in h.coordinates],
        "momenta": {p.name: js(v) for p, v in zip(h.momentum_symbols, h.momenta, strict=True)},
        "velocities": {f"{q.name}_dot": js(v) for q, v in zip(h.coordinates, h.inverse, strict=True)},
        "H": js(h.expression),
        "form": h.form or None,
        "equations": equations,
        "routhian": routhian,
        "poisson_brackets": {b.name: {"quantity": js(b.quantity), "bracket": js(b.bracket),
                                      "partial_t": js(b.partial_t), "forces": js(b.forces), "rate": js(b.rate),
                                      "verified": b.status}
                             for b in h.brackets},
    }


def hamiltonian_summary(derivation: Derivation, note: Notation) -> list[str]:
    """Terminal lines: H and Hamilton's equations, or why there is no Hamiltonian."""
    if derivation.analysis is None:
        return []
    h = derivation.hamiltonian
    if h is None:
        stopped = any(n.stage == "hamiltonian" for n in derivation.notes)
        return [] if stopped else [f"  Hamiltonian: not applicable: {derivation.hamiltonian_note}"]
    text = note.text
    extra = {"T + V": " (= T + V)", "T2 - T0 + V": " (= T2 - T0 + V, not T + V)",
             "T2 - T0 + V0": " (= T2 - T0 + V0)"}.get(h.form, "")
    lines = [f"  Hamiltonian: H = {text(h.expression)}{extra}"]
    for i, (q, p) in enumerate(zip(h.coordinates, h.momentum_symbols, strict=True)):
        lines.append(f"    {text(sympy.Symbol(q.name + '_dot'))} = {text(h.rates[i])},  "
                     f"ṗ{text(p)[1:]} = {text(_momentum_rate(h, i))}")
    if h.routhian is not None:
        lines.append(f"    Routhian R = {text(h.routhian.expression)}")
    return lines
