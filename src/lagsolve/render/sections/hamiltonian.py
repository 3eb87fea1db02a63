"""The Hamiltonian section of a report, as data: momenta, H, Hamilton's equations, the Routhian and the
Poisson brackets of the conserved quantities, or why there is no Hamiltonian.

Built once by :func:`hamiltonian_section`, which gives one of three records (None without an analysis):
:class:`HamiltonianSection` (the formulation), :class:`NotApplicable` (none by the physics) or
:class:`NotDerived` (its stage did not finish). Each format is :func:`lagsolve.render.model.present` of that
one value: the JSON key ``hamiltonian`` (``docs/format.md``, *Output*: the formulation,
``{"not_applicable": reason}`` or null), the templates' context (``templates/*/_hamiltonian.*.j2``) and the
terminal lines (``templates/text/_hamiltonian.txt.j2``). The builder makes both shapes where they differ: the
JSON's maps keyed by name, in full and with the constants of integration written back as the integrals they
stand for, and the templates' rows, with what a compact (matrix form) report does not show left blank, never
printed. Nothing here simplifies.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, cast

import sympy

from lagsolve.mechanics.hamiltonian import T2_T0_V0
from lagsolve.render.model import Expr, Printer, Rows, shown

if TYPE_CHECKING:
    from lagsolve.mechanics.hamiltonian import Hamiltonian
    from lagsolve.mechanics.results import Derivation

#: how H relates to T and V (:attr:`lagsolve.mechanics.hamiltonian.Hamiltonian.form`; None: none of these)
Form = Literal["T + V", "T2 - T0 + V", "T2 - T0 + V0"]
#: how a conserved quantity's rate was found 0 (or not)
Verified = Literal["symbolic", "numeric", "differ"]

#: what a compact report leaves out of the templates: not printed at all (with a long inverse, printing q̇(q, p),
#: H and Hamilton's equations cost more than the whole derivation); the JSON has them in full
BLANK = ""


@dataclass(frozen=True)
class DottedMomentum:
    r""":math:`\dot p_q`, the rate of the momentum ``p_<q>``: printed as the momentum with a dot on the p
    (LaTeX ``\dot{p}_{q}``, MathML an accented ``p``, text ``ṗ_q``); the JSON's name ``p_<q>_dot``."""

    momentum: Any

    def present(self, printer: Printer) -> str:
        printed = printer.expr(self.momentum)
        if printer.kind == "mathml":
            return printed.replace("<mi>p</mi>", '<mover accent="true"><mi>p</mi><mo>&#729;</mo></mover>', 1)
        if printer.kind == "latex":
            return "\\dot{p}" + printed[1:]
        if printer.kind == "text":
            return "ṗ" + printed[1:]
        return f"{self.momentum.name}_dot"


@dataclass(frozen=True)
class Canonical:
    """One minimal coordinate's row in the reports: q, q̇, p = ∂L/∂q̇, q̇(q, p), and Hamilton's equations
    q̇ = ∂H/∂p, ṗ = −∂H/∂q + Q − ∂R/∂q̇ (``momentum_rate`` in full; ``force``, ``dissipation`` its parts, "" when
    0). ``inverse``, ``rate`` and ``momentum_rate`` are blank in a compact report."""

    coordinate: Expr = shown()
    velocity: Expr = shown(terminal=True)
    momentum: Expr = shown()
    rate_symbol: DottedMomentum = shown(terminal=True)
    momentum_value: Expr = shown()
    inverse: Expr = shown()
    rate: Expr = shown(terminal=True)
    momentum_rate: Expr = shown(terminal=True)
    force: Expr = shown(blank_zero=True)
    dissipation: Expr = shown(blank_zero=True)


@dataclass(frozen=True)
class CyclicMomentum:
    """A cyclic coordinate of Routh's reduction in the reports: its constant momentum, q̇_c(q, q̇, p_c) and
    −∂R/∂p_c."""

    coordinate: Expr = shown()
    momentum: Expr = shown()
    velocity: Expr = shown()  # the symbol q_c_dot
    value: Expr = shown()
    rate: Expr = shown()


@dataclass(frozen=True)
class Reduced:
    """An equation of a coordinate left by Routh's reduction, in the reports."""

    coordinate: Expr = shown()
    lhs: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class Equation:
    """An equation of the JSON: its two sides."""

    lhs: Expr = shown()
    rhs: Expr = shown()


@dataclass(frozen=True)
class Routhian:
    """Routh's reduction by the cyclic coordinates: the JSON's names, R, q̇_c and the reduced equations by name;
    the reports' rows (``single``: one coordinate is left)."""

    cyclic: tuple[CyclicMomentum, ...] = shown(json=None)
    cyclic_names: tuple[str, ...] = shown(json="cyclic", template=False)
    expression: Expr = shown(json=None, terminal=True)
    R: Expr = shown(json="expression", template=False)
    velocities: Mapping[str, Expr] = shown(template=False, doc="<q>_dot of each cyclic coordinate")
    equations: tuple[Reduced, ...] = shown(json=None)
    reduced: Mapping[str, Equation] = shown(json="equations", template=False,
                                            doc="the equation of each coordinate left")
    coordinates: tuple[Expr, ...] = shown(json=None)
    single: bool = shown(json=None)


@dataclass(frozen=True)
class Bracket:
    """A conserved quantity's rate {C, H} + ∂C/∂t + Σ ∂C/∂p Q in the reports; ``same`` says when C is H itself
    ("H") or a momentum ("momentum"), which a report writes briefly (``quantity`` is then blank)."""

    name: str = shown()
    symbol: Expr = shown()
    quantity: Expr = shown()
    bracket: Expr = shown()
    partial_t: Expr = shown()
    forces: Expr = shown(blank_zero=True)
    rate: Expr = shown()
    status: str = shown()
    same: str = shown()


@dataclass(frozen=True)
class BracketCheck:
    """A conserved quantity's rate in the JSON: C, its parts and their sum, and how the sum was found 0."""

    quantity: Expr = shown()
    bracket: Expr = shown()
    partial_t: Expr = shown()
    forces: Expr = shown()
    rate: Expr = shown()
    verified: Verified = shown()


@dataclass(frozen=True)
class HamiltonianSection:
    """The Hamiltonian formulation. The JSON's values (in order of its keys) are in full, with the constants of
    integration written back; the reports' are the rows ``coordinates``, A, b (None when 0), H (blank when
    ``compact``: H and the equations are too long to write out, the matrix form instead), U = −L at q̇ = 0, how H
    relates to T and V (``form``, ``kinetic_*``: T₂, T₁, T₀, "" when 0), whether forces or dissipation enter the
    equations, the Routhian and the Poisson brackets."""

    coordinates: tuple[Canonical, ...] = shown(json=None, terminal=True)
    names: tuple[str, ...] = shown(json="coordinates", template=False)
    momenta: Mapping[str, Expr] = shown(template=False, doc="p_<q> = dL/d<q>_dot, in the coordinates and velocities")
    inverse: Mapping[str, Expr] = shown(json="velocities", template=False,
                                        doc="<q>_dot in the coordinates and momenta")
    H: Expr = shown(template=False, doc="the Hamiltonian in the coordinates and momenta (and t)")
    form: Form | None = shown(terminal=True)
    equations: Mapping[str, Expr] = shown(template=False, doc="<q>_dot and p_<q>_dot, Hamilton's equations")
    routhian: Routhian | None = shown(terminal=True)
    poisson_brackets: Mapping[str, BracketCheck] = shown(template=False)
    lagrangian: Expr = shown(json=None)
    mass: Rows = shown(json=None)
    offset: Rows | None = shown(json=None, terminal=True)
    velocities: Rows = shown(json=None)
    momenta_vector: Rows = shown(json=None)
    diagonal: bool = shown(json=None)
    expression: Expr = shown(json=None, terminal=True)
    remainder: Expr = shown(json=None, terminal=True)
    compact: bool = shown(json=None, terminal=True)
    magnetic: bool = shown(json=None)
    kinetic_two: Expr = shown(json=None)
    kinetic_one: Expr = shown(json=None, blank_zero=True)
    kinetic_zero: Expr = shown(json=None, blank_zero=True)
    time_dependent: bool = shown(json=None)
    forces: bool = shown(json=None)
    dissipation: bool = shown(json=None)
    routhian_note: str = shown(json=None)
    brackets: tuple[Bracket, ...] = shown(json=None)


@dataclass(frozen=True)
class NotApplicable:
    """No Hamiltonian by the physics, and why (the JSON's ``{"not_applicable": reason}``)."""

    reason: str = shown(json="not_applicable", terminal=True)


@dataclass(frozen=True)
class NotDerived:
    """No Hamiltonian because its stage did not finish: the reports say why; the JSON writes null and the
    terminal nothing (the notes say why)."""

    reason: str = shown(json=None)


#: what :func:`hamiltonian_section` gives (None: the derivation has no analysis, so no section at all)
HamiltonianPart = HamiltonianSection | NotApplicable | NotDerived | None


def hamiltonian_section(derivation: Derivation) -> HamiltonianPart:
    """The Hamiltonian section of ``derivation``, built once."""
    analysis = derivation.analysis
    if analysis is None:
        return None
    h = derivation.hamiltonian
    note = derivation.hamiltonian_note
    if h is None:
        stopped = any(n.stage == "hamiltonian" for n in derivation.notes)
        return NotDerived(note or "not derived") if stopped or not note else NotApplicable(note)
    back = {k.constant: k.integral for k in analysis.classification if k.constant is not None}
    return _formulation(h, back)


def _written_back(back: Mapping[Any, Any]) -> Callable[[Any], Any]:
    """How an expression is written in the JSON: with the constants of integration written back as the integrals
    they stand for (as :func:`lagsolve.mechanics.analysis.analyse.contract_forms` writes them)."""
    return lambda expr: expr.xreplace(back) if isinstance(expr, sympy.Basic) else expr


def _formulation(h: Hamiltonian, back: Mapping[Any, Any]) -> HamiltonianSection:
    js = _written_back(back)
    full = (lambda expr: BLANK) if h.compact else (lambda expr: expr)
    n = range(len(h.coordinates))
    rates = tuple(sympy.Add(h.momentum_rates[i], h.forces[i], h.dissipation[i]) for i in n)
    canonical = tuple(
        Canonical(q, h.velocities[i], h.momentum_symbols[i], DottedMomentum(h.momentum_symbols[i]), h.momenta[i],
                  full(h.inverse[i]), full(h.rates[i]), full(rates[i]), h.forces[i], h.dissipation[i])
        for i, q in enumerate(h.coordinates))
    equations = {f"{q.name}_dot": js(h.rates[i]) for i, q in enumerate(h.coordinates)}
    equations.update({f"{p.name}_dot": js(rates[i]) for i, p in enumerate(h.momentum_symbols)})
    T2, T1, T0 = h.kinetic_parts
    return HamiltonianSection(
        coordinates=canonical, names=tuple(q.name for q in h.coordinates),
        momenta={p.name: js(h.momenta[i]) for i, p in enumerate(h.momentum_symbols)},
        inverse={f"{q.name}_dot": js(h.inverse[i]) for i, q in enumerate(h.coordinates)},
        H=js(h.expression), form=cast(Form | None, h.form or None), equations=equations, routhian=_routhian(h, js),
        poisson_brackets={b.name: BracketCheck(js(b.quantity), js(b.bracket), js(b.partial_t), js(b.forces),
                                               js(b.rate), cast(Verified, b.status)) for b in h.brackets},
        lagrangian=h.lagrangian, mass=h.mass, offset=h.offset if any(not b.is_zero for b in h.offset) else None,
        velocities=sympy.ImmutableMatrix(h.velocities), momenta_vector=sympy.ImmutableMatrix(h.momentum_symbols),
        diagonal=h.mass.is_diagonal(), expression=full(h.expression), remainder=h.remainder, compact=h.compact,
        magnetic=h.form == T2_T0_V0, kinetic_two=T2, kinetic_one=T1, kinetic_zero=T0,
        time_dependent=h.time_dependent, forces=any(f != 0 for f in h.forces),
        dissipation=any(d != 0 for d in h.dissipation), routhian_note=h.routhian_note,
        brackets=tuple(_bracket(h, b) for b in h.brackets))


def _routhian(h: Hamiltonian, js: Callable[[Any], Any]) -> Routhian | None:
    r = h.routhian
    if r is None:
        return None
    cyclic = tuple(CyclicMomentum(c, p, sympy.Symbol(f"{c.name}_dot"), v, w)
                   for c, p, v, w in zip(r.cyclic, r.momenta, r.velocities, r.cyclic_rates, strict=True))
    return Routhian(
        cyclic=cyclic, cyclic_names=tuple(c.name for c in r.cyclic), expression=r.expression, R=js(r.expression),
        velocities={f"{c.name}_dot": js(v) for c, v in zip(r.cyclic, r.velocities, strict=True)},
        equations=tuple(Reduced(q, lhs, rhs) for q, (lhs, rhs) in zip(r.coordinates, r.equations, strict=True)),
        reduced={q.name: Equation(js(lhs), js(rhs)) for q, (lhs, rhs) in zip(r.coordinates, r.equations,
                                                                             strict=True)},
        coordinates=tuple(r.coordinates), single=len(r.coordinates) == 1)


def _bracket(h: Hamiltonian, b: Any) -> Bracket:
    """A bracket in the reports: a quantity that is H or a momentum is shown by that name alone."""
    if b.quantity == h.expression:
        same = "H"
    elif b.quantity in h.momentum_symbols and b.name == b.quantity.name:
        same = "momentum"
    else:
        same = ""
    symbol = sympy.Symbol(b.name) if b.name != "energy" else sympy.Symbol("h")
    return Bracket(b.name, symbol, BLANK if same else b.quantity, b.bracket, b.partial_t, b.forces, b.rate,
                   b.status, same)
