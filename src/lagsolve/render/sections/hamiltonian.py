"""The Hamiltonian section of a report, as data: momenta, H, Hamilton's equations, the Routhian and the
Poisson brackets of the conserved quantities, or why there is no Hamiltonian.

Built once by :func:`hamiltonian_section`; :mod:`lagsolve.render.hamiltonian_report` projects it onto the
templates, the JSON key ``hamiltonian`` and the terminal. Nothing here simplifies.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.hamiltonian import T2_T0_V0

if TYPE_CHECKING:
    from lagsolve.mechanics.hamiltonian import Hamiltonian
    from lagsolve.mechanics.results import Derivation

Expr = Any


@dataclass(frozen=True)
class Canonical:
    """One minimal coordinate's pair: q, q̇, p = ∂L/∂q̇, q̇(q, p), and Hamilton's equations
    q̇ = ∂H/∂p, ṗ = −∂H/∂q + Q − ∂R/∂q̇ (``momentum_rate`` in full; ``force``, ``dissipation`` its parts)."""

    coordinate: Expr
    velocity: Expr
    momentum: Expr  # the symbol p_q
    momentum_value: Expr
    inverse: Expr
    rate: Expr
    momentum_rate: Expr
    force: Expr
    dissipation: Expr


@dataclass(frozen=True)
class CyclicMomentum:
    """A cyclic coordinate of Routh's reduction: its constant momentum, q̇_c(q, q̇, p_c) and −∂R/∂p_c."""

    coordinate: Expr
    momentum: Expr
    velocity: Expr  # the symbol q_c_dot
    value: Expr
    rate: Expr


@dataclass(frozen=True)
class Reduced:
    """An equation of a coordinate left by Routh's reduction."""

    coordinate: Expr
    lhs: Expr
    rhs: Expr


@dataclass(frozen=True)
class Routhian:
    cyclic: tuple[CyclicMomentum, ...]
    expression: Expr
    equations: tuple[Reduced, ...]
    coordinates: tuple[Expr, ...]


@dataclass(frozen=True)
class Bracket:
    """A conserved quantity's rate {C, H} + ∂C/∂t + Σ ∂C/∂p Q; ``same`` says when C is H itself ("H") or a
    momentum ("momentum"), which a report writes briefly."""

    name: str
    symbol: Expr
    quantity: Expr
    bracket: Expr
    partial_t: Expr
    forces: Expr
    rate: Expr
    status: str
    same: str


@dataclass(frozen=True)
class HamiltonianParts:
    """H and everything shown with it."""

    canonical: tuple[Canonical, ...]
    lagrangian: Expr
    mass: Expr
    offset: Expr | None  # b of p = A q̇ + b, None when zero
    expression: Expr
    form: str
    magnetic: bool
    kinetic_parts: tuple[Expr, Expr, Expr]
    time_dependent: bool
    remainder: Expr
    compact: bool  # H and the equations are too long to write out: the matrix form instead
    routhian: Routhian | None
    routhian_note: str
    brackets: tuple[Bracket, ...]


@dataclass(frozen=True)
class HamiltonianSection:
    """The Hamiltonian of a derivation (``parts``), or why there is none (``note``; ``stopped`` when its stage
    ran out of budget). ``analysed`` False: the derivation has no analysis, so no section at all.
    ``constants``: constants of integration and the integrals they stand for (the JSON writes them back)."""

    analysed: bool
    parts: HamiltonianParts | None
    note: str
    stopped: bool
    constants: tuple[tuple[Expr, Expr], ...]


def hamiltonian_section(derivation: Derivation) -> HamiltonianSection:
    """The Hamiltonian section of ``derivation``, built once."""
    analysis = derivation.analysis
    constants = () if analysis is None else tuple(
        (k.constant, k.integral) for k in analysis.classification if k.constant is not None)
    h = derivation.hamiltonian
    return HamiltonianSection(
        analysed=analysis is not None, parts=None if h is None else _parts(h),
        note=derivation.hamiltonian_note, stopped=any(n.stage == "hamiltonian" for n in derivation.notes),
        constants=constants)


def _parts(h: Hamiltonian) -> HamiltonianParts:
    rates = tuple(sympy.Add(h.momentum_rates[i], h.forces[i], h.dissipation[i]) for i in range(len(h.coordinates)))
    canonical = tuple(
        Canonical(q, h.velocities[i], h.momentum_symbols[i], h.momenta[i], h.inverse[i], h.rates[i], rates[i],
                  h.forces[i], h.dissipation[i])
        for i, q in enumerate(h.coordinates))
    r = h.routhian
    routhian = None if r is None else Routhian(
        cyclic=tuple(CyclicMomentum(c, p, sympy.Symbol(f"{c.name}_dot"), v, w)
                     for c, p, v, w in zip(r.cyclic, r.momenta, r.velocities, r.cyclic_rates, strict=True)),
        expression=r.expression,
        equations=tuple(Reduced(q, lhs, rhs) for q, (lhs, rhs) in zip(r.coordinates, r.equations, strict=True)),
        coordinates=tuple(r.coordinates))
    brackets = tuple(
        Bracket(b.name, sympy.Symbol(b.name) if b.name != "energy" else sympy.Symbol("h"), b.quantity, b.bracket,
                b.partial_t, b.forces, b.rate, b.status,
                "H" if b.quantity == h.expression else ("momentum" if b.quantity in h.momentum_symbols
                                                        and b.name == b.quantity.name else ""))
        for b in h.brackets)
    return HamiltonianParts(
        canonical=canonical, lagrangian=h.lagrangian, mass=h.mass,
        offset=h.offset if any(not b.is_zero for b in h.offset) else None,
        expression=h.expression, form=h.form, magnetic=h.form == T2_T0_V0, kinetic_parts=h.kinetic_parts,
        time_dependent=h.time_dependent, remainder=h.remainder, compact=h.compact, routhian=routhian,
        routhian_note=h.routhian_note, brackets=brackets)
