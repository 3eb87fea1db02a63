"""The Hamiltonian part of the reports: projections of :class:`~lagsolve.render.sections.hamiltonian.HamiltonianSection`
onto the templates (``templates/*/_hamiltonian.*.j2``), the JSON key ``hamiltonian`` and the terminal lines.
Nothing here simplifies (every expression arrives in display form).
"""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.render.notation import Notation, to_json
from lagsolve.render.sections.hamiltonian import HamiltonianSection


def hamiltonian_context(section: HamiltonianSection, note: Notation, math: str = "latex") -> dict[str, Any] | None:
    """Strings for the Hamiltonian section (None without an analysis); expressions in LaTeX, or in presentation
    MathML when ``math`` is "mathml". ``applies`` False carries the ``reason``."""
    if not section.analysed:
        return None
    h = section.parts
    if h is None:
        return {"applies": False, "reason": section.note or "not derived"}
    tex, text = (note.mathml if math == "mathml" else note.latex), note.text
    # in matrix form (compact) the templates show neither q̇(q, p), H nor Hamilton's equations written out: they
    # are not printed at all (with a long inverse, printing them cost more than the whole derivation)
    full = (lambda e: "") if h.compact else tex
    full_text = (lambda e: "") if h.compact else text
    coordinates = [{
        "coordinate": tex(c.coordinate), "velocity": tex(c.velocity), "momentum": tex(c.momentum),
        "momentum_text": text(c.momentum), "rate_symbol": _dotted(tex(c.momentum), math),
        "momentum_value": tex(c.momentum_value), "inverse": full(c.inverse), "rate": full(c.rate),
        "momentum_rate": full(c.momentum_rate), "momentum_rate_text": full_text(c.momentum_rate),
        "rate_text": full_text(c.rate),
        "force": tex(c.force) if c.force != 0 else "",
        "dissipation": tex(c.dissipation) if c.dissipation != 0 else "",
    } for c in h.canonical]
    T2, T1, T0 = h.kinetic_parts
    r = h.routhian
    routhian = None if r is None else {
        "cyclic": [{"coordinate": tex(c.coordinate), "momentum": tex(c.momentum), "velocity": tex(c.velocity),
                    "value": tex(c.value), "rate": tex(c.rate)} for c in r.cyclic],
        "expression": tex(r.expression),
        "equations": [{"coordinate": tex(e.coordinate), "lhs": tex(e.lhs), "rhs": tex(e.rhs)} for e in r.equations],
        "coordinates": [tex(q) for q in r.coordinates],
        "single": len(r.coordinates) == 1,
    }
    # a quantity that is H or a momentum is shown by that name alone
    brackets = [{"name": b.name, "symbol": tex(b.symbol), "quantity": "" if b.same else tex(b.quantity),
                 "bracket": tex(b.bracket),
                 "partial_t": tex(b.partial_t), "forces": tex(b.forces) if b.forces != 0 else "", "rate": tex(b.rate),
                 "status": b.status, "same": b.same} for b in h.brackets]
    return {
        "applies": True,
        "compact": h.compact,
        "remainder": tex(h.remainder),
        "coordinates": coordinates,
        "lagrangian": tex(h.lagrangian),
        "mass": tex(h.mass),
        "offset": tex(h.offset) if h.offset is not None else "",
        "velocities": tex(sympy.Matrix([c.velocity for c in h.canonical])),
        "momenta_vector": tex(sympy.Matrix([c.momentum for c in h.canonical])),
        "diagonal": h.mass.is_diagonal(),
        "expression": full(h.expression),
        "expression_text": full_text(h.expression),
        "form": h.form,
        "magnetic": h.magnetic,
        "kinetic_two": tex(T2), "kinetic_one": tex(T1) if T1 != 0 else "", "kinetic_zero": tex(T0) if T0 != 0 else "",
        "time_dependent": h.time_dependent,
        "forces": any(c.force != 0 for c in h.canonical),
        "dissipation": any(c.dissipation != 0 for c in h.canonical),
        "routhian": routhian,
        "routhian_note": h.routhian_note,
        "brackets": brackets,
    }


def _dotted(momentum: str, math: str) -> str:
    r""":math:`\dot p_q` from the printed :math:`p_q` (LaTeX ``p_{q}`` or MathML ``<msub><mi>p</mi>...``)."""
    if math == "mathml":
        return momentum.replace("<mi>p</mi>", '<mover accent="true"><mi>p</mi><mo>&#729;</mo></mover>', 1)
    return "\\dot{p}" + momentum[1:]


def hamiltonian_json(section: HamiltonianSection) -> dict[str, Any] | None:
    """The ``hamiltonian`` key: ``coordinates``, ``momenta`` (``p_<q>`` in q and q_dot), ``H`` (in q and p),
    ``equations`` (``<q>_dot``, ``p_<q>_dot`` in q and p), ``form``, ``routhian`` (or null) and
    ``poisson_brackets``; ``{"not_applicable": reason}`` where there is none by the physics, null when its
    stage did not finish (the ``notes`` say why) or there is no analysis. Constants of integration are written
    back as the integrals they stand for (as ``contract_forms`` does)."""
    h = section.parts
    if h is None:
        if not section.analysed or section.stopped or not section.note:
            return None
        return {"not_applicable": section.note}
    back = dict(section.constants)

    def js(expr: Any) -> str:
        return to_json(expr.xreplace(back) if isinstance(expr, sympy.Basic) else expr)

    equations = {f"{c.coordinate.name}_dot": js(c.rate) for c in h.canonical}
    equations.update({f"{c.momentum.name}_dot": js(c.momentum_rate) for c in h.canonical})
    r = h.routhian
    routhian = None if r is None else {
        "cyclic": [c.coordinate.name for c in r.cyclic],
        "expression": js(r.expression),
        "velocities": {f"{c.coordinate.name}_dot": js(c.value) for c in r.cyclic},
        "equations": {e.coordinate.name: {"lhs": js(e.lhs), "rhs": js(e.rhs)} for e in r.equations},
    }
    return {
        "coordinates": [c.coordinate.name for c in h.canonical],
        "momenta": {c.momentum.name: js(c.momentum_value) for c in h.canonical},
        "velocities": {f"{c.coordinate.name}_dot": js(c.inverse) for c in h.canonical},
        "H": js(h.expression),
        "form": h.form or None,
        "equations": equations,
        "routhian": routhian,
        "poisson_brackets": {b.name: {"quantity": js(b.quantity), "bracket": js(b.bracket),
                                      "partial_t": js(b.partial_t), "forces": js(b.forces), "rate": js(b.rate),
                                      "verified": b.status}
                             for b in h.brackets},
    }


def hamiltonian_summary(section: HamiltonianSection, note: Notation) -> list[str]:
    """Terminal lines: H and Hamilton's equations, or why there is no Hamiltonian."""
    if not section.analysed:
        return []
    h = section.parts
    if h is None:
        return [] if section.stopped else [f"  Hamiltonian: not applicable: {section.note}"]
    text = note.text
    extra = {"T + V": " (= T + V)", "T2 - T0 + V": " (= T2 - T0 + V, not T + V)",
             "T2 - T0 + V0": " (= T2 - T0 + V0)"}.get(h.form, "")
    if h.compact:  # as the reports give it: the matrix form (the JSON has H and the equations in full)
        w = "(p - b)" if h.offset is not None else "p"
        lines = [f"  Hamiltonian: H = 1/2 {w}^T A^-1 {w} + U{extra}, U = {text(h.remainder)} (matrix form: the "
                 "inverse is long; the JSON has H and Hamilton's equations in full)"]
    else:
        lines = [f"  Hamiltonian: H = {text(h.expression)}{extra}"]
    for c in () if h.compact else h.canonical:
        lines.append(f"    {text(sympy.Symbol(c.coordinate.name + '_dot'))} = {text(c.rate)},  "
                     f"ṗ{text(c.momentum)[1:]} = {text(c.momentum_rate)}")
    if h.routhian is not None:
        lines.append(f"    Routhian R = {text(h.routhian.expression)}")
    return lines
