r"""Conserved quantities: cyclic momenta and the Jacobi integral, each verified along the motion.

For a system :math:`L(q, \dot q, t)` with generalized forces :math:`Q` and (possibly)
velocity constraints :math:`\sum_i a_{ji}\dot q_i + b_j = 0` left over:

* a coordinate :math:`q_k` is **cyclic** when :math:`\partial L/\partial q_k = 0`,
  :math:`Q_k = 0` and every constraint has :math:`a_{jk} = 0` (none involves :math:`\dot q_k`);
  then :math:`p_k = \partial L/\partial\dot q_k` is constant, since
  :math:`\dot p_k = \partial L/\partial q_k + Q_k + \sum_j\lambda_j a_{jk} = 0`. The coordinate
  itself may appear in the other velocities' coefficients: the upright rolling coin's heading
  :math:`\phi` enters :math:`\dot x - R\dot\theta\cos\phi = 0`, yet :math:`p_\phi` is conserved;
* the **Jacobi integral** :math:`h = \sum_i \dot q_i\,\partial L/\partial\dot q_i - L` obeys

  .. math:: \frac{dh}{dt} = -\frac{\partial L}{\partial t} + \sum_i Q_i\dot q_i - \sum_j \lambda_j b_j,

  so it is conserved when L has no explicit t, the forces do no work and every
  constraint has :math:`b_j = 0`. It equals T + V when T is a quadratic form in the
  velocities (:math:`h = T_2 - T_0 + V` in general).

Every candidate is then **verified**: its total time derivative, with the accelerations
of the equations of motion substituted (and the state put on the constraint surface), must
simplify to zero exactly. A candidate that fails is dropped, never claimed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy

from lagsolve.enums import TextEnum
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.energy import jacobi_integral
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.surface import on_surface
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.partials import partial
from lagsolve.mechanics.symbolic.simplify import display_forms, tidy
from lagsolve.problem.names import momentum_name


@dataclass(frozen=True)
class MotionSystem:
    """Equations of motion to check conservation against.

    ``accelerations`` maps each acceleration symbol to its expression; ``constraints`` are
    the velocity constraints still in force (none for a reduced system) and ``surface``
    substitutes one velocity per constraint so that a state satisfies them. ``kind`` is
    ``"reduced"`` or ``"full"``.
    """

    model: Model
    generalized_forces: tuple[Any, ...]
    accelerations: dict[Any, Any]
    constraints: tuple[ConstraintTerms, ...] = ()
    surface: dict[Any, Any] = field(default_factory=dict)
    kind: str = "reduced"

    def rate(self, expr: Any) -> Any:
        """Total time derivative of ``expr`` along the motion, on the constraint surface."""
        rate = self.model.time_derivative(expr, second_order=True).xreplace(self.accelerations)
        return on_surface(rate, self.surface)

    def constant(self, expr: Any) -> bool:
        """``expr`` is constant along the motion: its :meth:`rate` is proved identically zero.

        A cheap proof comes first. The rate is linear in the accelerations, so over their common
        denominator D (non-zero: the solve divided by it) it is zero exactly when its numerator is,
        and a numerator that expands to 0 is zero. When that does not settle it (a constraint surface,
        or an identity that needs sin² + cos² = 1), :func:`proved_zero` decides.
        """
        if not self.surface and _numerator_vanishes(self.model, expr, self.accelerations):
            return True
        return proved_zero(self.rate(expr))


def _numerator_vanishes(model: Model, expr: Any, accelerations: dict[Any, Any]) -> bool:
    """The numerator of ``d expr/dt`` with ``accelerations`` put in, over their common denominator, expands to 0."""
    if expr.has(*model.accelerations):
        return False  # the rate is linear in the accelerations only when expr has none
    fast = _numerator_vanishes_symengine(model, expr, accelerations)
    if fast is not None:
        return fast
    rate = model.time_derivative(expr, second_order=True)
    parts = {a: sympy.fraction(v) for a, v in accelerations.items() if rate.has(a)}
    if any(rate.has(a) for a in model.accelerations if a not in accelerations):
        return False
    denominators = list(dict.fromkeys(d for _, d in parts.values()))
    common = sympy.Mul(*denominators)
    others = {a: sympy.Mul(*[d for d in denominators if d != den]) for a, (_, den) in parts.items()}
    numerator = rate.xreplace(dict.fromkeys(parts, sympy.Integer(0))) * common
    for a, (num, _) in parts.items():
        numerator += sympy.diff(rate, a) * num * others[a]
    try:
        return sympy.expand(numerator) == 0
    except (TypeError, ValueError):
        return False


def _numerator_vanishes_symengine(model: Model, expr: Any, accelerations: dict[Any, Any]) -> bool | None:
    """:func:`_numerator_vanishes` with the derivatives and the expansion in SymEngine (an expansion that
    gives 0 is a proof in any engine); None where SymEngine cannot take the expressions."""
    accelerations = {a: v if isinstance(v, sympy.Basic) else sympy.Integer(v) for a, v in accelerations.items()}
    pieces = (expr, *accelerations.values())
    if not isinstance(expr, sympy.Basic) or any(
            e.atoms(sympy.core.function.AppliedUndef) or e.has(sympy.Derivative) for e in pieces):
        return None
    try:
        import symengine
        from symengine.lib.symengine_wrapper import sympy2symengine
    except ImportError:
        return None
    try:
        engine = sympy2symengine(expr)
        rate = engine.diff(sympy2symengine(model.time))
        for q, v in zip(model.coordinates, model.velocities, strict=True):
            rate += engine.diff(sympy2symengine(q)) * sympy2symengine(v)
        coefficients = {a: engine.diff(sympy2symengine(v)) for v, a in zip(model.velocities, model.accelerations,
                                                                            strict=True)}
        coefficients = {a: c for a, c in coefficients.items() if c != 0}
        if any(a not in accelerations for a in coefficients):
            return False
        parts = {a: tuple(sympy2symengine(x) for x in sympy.fraction(accelerations[a])) for a in coefficients}
        denominators = list(dict.fromkeys(d for _, d in parts.values()))
        numerator = rate * symengine.Mul(*denominators) if denominators else rate
        for a, (num, den) in parts.items():
            others = [d for d in denominators if d != den]
            numerator += coefficients[a] * num * (symengine.Mul(*others) if others else 1)
        return bool(symengine.expand(numerator) == 0)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return None


@dataclass(frozen=True)
class Conserved:
    r"""One verified constant of the motion.

    ``name`` is ``p_<q>``, ``energy`` or the name of a symmetry's momentum (``L_z``, ``P_x``);
    ``kind`` is ``"momentum"``, ``"jacobi"`` or ``"noether"``;
    ``expression`` its display form; ``reason`` a sentence in plain text. For the Jacobi
    integral ``equals_energy`` says whether :math:`h = T + V`, ``moving`` whether T has a
    part :math:`T_0` free of the velocities (a moving constraint), and ``flags`` which
    conditions held (``"no_time"``, ``"no_work"``, ``"eliminated"``/``"workless"``).
    ``symmetry`` names the translation or rotation whose momentum it is (``"rotation about z"``;
    :mod:`~lagsolve.mechanics.analysis.symmetry`) and ``generator`` its flow ξ, one entry per coordinate.
    """

    name: str
    kind: str
    expression: Any
    coordinate: Any = None
    reason: str = ""
    equals_energy: bool | None = None
    moving: bool = False
    flags: tuple[str, ...] = ()
    symmetry: str = ""
    generator: tuple[Any, ...] = ()


class Energy(TextEnum):
    """What the analysis decided about the energy function h (the Jacobi integral)."""

    CONSERVED = "conserved"
    TIME = "L depends on the time"
    WORK = "forces do work"
    MOVING = "a constraint moves"
    NOT_PROVED = "not proved"
    UNDECIDED = "undecided"  # the conservation stage gave no answer


@dataclass(frozen=True)
class EnergyDecision:
    """The energy decision as data: its ``kind``, whether the work is friction's (``WORK``), and the
    constraints with b != 0 (``MOVING``). :meth:`note` and :meth:`reason` write it as sentences."""

    kind: Energy = Energy.UNDECIDED
    friction: bool = False
    moving: tuple[str, ...] = ()

    def why(self) -> str:
        """Why h is not claimed, as the analysis notes write it ("" when conserved or undecided)."""
        if self.kind == Energy.TIME:
            return "not conserved, L depends explicitly on the time"
        if self.kind == Energy.WORK:
            what = "friction does" if self.friction else "the non-conservative forces do"
            return f"not conserved, {what} work (sum of Q_i q_i_dot is not 0)"
        if self.kind == Energy.MOVING:
            return f"not conserved, constraint {', '.join(self.moving)} has b != 0, so its force does work"
        if self.kind == Energy.NOT_PROVED:
            return "the conditions hold but dh/dt did not simplify to 0; not claimed"
        return ""

    def note(self) -> str:
        """The line of ``Conservation.notes`` ("energy: ..."); "" when there is nothing to note."""
        return f"energy: {self.why()}" if self.why() else ""

    def reason(self) -> str:
        """Why the energy is not conserved, for a simulation's summary ("" when it is)."""
        if self.kind == Energy.CONSERVED:
            return ""
        return self.why().removeprefix("not conserved, ") or "the analysis finds no conserved energy"


@dataclass(frozen=True)
class Conservation:
    """The verified quantities, the cyclic coordinates, notes on what is not conserved, and the energy
    decision (``energy``, whose note is among ``notes`` when there is one)."""

    quantities: tuple[Conserved, ...]
    cyclic: tuple[Any, ...]
    notes: tuple[str, ...]
    energy: EnergyDecision = EnergyDecision()


def conserved_quantities(system: MotionSystem, *, friction: bool = False) -> Conservation:
    """Cyclic momenta and the Jacobi integral of ``system``, each verified (module docstring)."""
    model = system.model
    L = model.lagrangian
    quantities: list[Conserved] = []
    notes: list[str] = []
    cyclic = []
    for i, q in enumerate(model.coordinates):
        # only a_jk matters: dp_k/dt = dL/dq_k + Q_k + sum_j lambda_j a_jk (q_k may sit in other coefficients)
        involved = any(not proved_zero(c.coefficients[i]) for c in system.constraints)
        if involved or not proved_zero(partial(L, q)) or not proved_zero(system.generalized_forces[i]):
            continue
        momentum = partial(L, model.velocities[i])
        if momentum == 0:
            continue
        cyclic.append(q)
        if system.accelerations and not system.constant(momentum):
            notes.append(f"{momentum_name(q)}: {q.name} is cyclic but dp/dt did not simplify to 0; not claimed")
            continue
        quantities.append(Conserved(
            momentum_name(q), "momentum", tidy(momentum), q,
            f"{q.name} is cyclic: dL/d{q.name} = 0, Q_{q.name} = 0"
            + (f" and no constraint involves {q.name}_dot" if system.constraints else "") + unverified_caveat(system),
        ))
    decision, energy = _jacobi(system, friction)
    if energy is not None:
        quantities.append(energy)
    if decision.note():
        notes.append(decision.note())
    return Conservation(tuple(quantities), tuple(cyclic), tuple(notes), decision)


def unverified_caveat(system: MotionSystem) -> str:
    """The caveat of a quantity claimed by its criteria alone (no explicit accelerations to verify it with)."""
    if system.accelerations:
        return ""
    return " (by these conditions alone: the explicit accelerations are not available to verify it)"


def _jacobi(system: MotionSystem, friction: bool) -> tuple[EnergyDecision, Conserved | None]:
    """The energy decision, and the Jacobi integral when it is conserved."""
    model = system.model
    L = model.lagrangian
    if not proved_zero(partial(L, model.time)):
        return EnergyDecision(Energy.TIME), None
    power = on_surface(sum((f * v for f, v in zip(system.generalized_forces, model.velocities, strict=True)),
                    sympy.Integer(0)), system.surface)
    if friction or not proved_zero(power):
        return EnergyDecision(Energy.WORK, friction=friction), None
    moving = tuple(c.name for c in system.constraints if not proved_zero(c.offset))
    if moving:
        return EnergyDecision(Energy.MOVING, moving=moving), None
    h = jacobi_integral(model)
    if system.accelerations and not system.constant(h):
        return EnergyDecision(Energy.NOT_PROVED), None
    return EnergyDecision(Energy.CONSERVED), _jacobi_integral(system, h)


def _jacobi_integral(system: MotionSystem, h: Any) -> Conserved:
    """The conserved Jacobi integral ``h`` with the conditions that held and its reason."""
    model = system.model
    forces_zero = all(proved_zero(f) for f in system.generalized_forces)
    flags = ["no_time", "no_work" if not forces_zero else "no_forces",
             "eliminated" if system.kind == "reduced" else "workless"]
    if not system.constraints and system.kind == "full":
        flags[-1] = "unconstrained"
    T0 = model.kinetic.xreplace({v: 0 for v in model.velocities})
    equals = proved_zero(h - model.kinetic - model.potential)
    moving_t0 = not proved_zero(T0)
    reason = "L has no explicit t" + (", no force does work" if flags[1] == "no_work" else ", Q = 0")
    reason += {"eliminated": ", the constraints are built into the coordinates",
               "workless": ", every constraint has b = 0 (workless)", "unconstrained": ""}[flags[2]]
    reason += "; h = T + V" if equals else "; h = T2 - T0 + V, not T + V (a constraint moves)"
    reason += unverified_caveat(system)
    _, show_sum = display_forms(len(model.coordinates))  # a large system's h: one rewriting, angles contracted
    return Conserved("energy", "jacobi", show_sum(h), None, reason, equals, moving_t0, tuple(flags))
