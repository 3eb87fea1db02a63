"""A variant's key: the symbolic answers (the ``expected:`` section ``lagsolve check`` reads) and the numbers at
the variant's values, each number found twice — from the derivation's closed forms and from the compiled
equations or the simulation — and kept only when both agree.

Numbers at t = 0: accelerations, multipliers, magnitudes of the forces of constraint, per friction contact the
normal force, the friction force and (at rest) the least static coefficient that holds it, the conserved
quantities. Numbers read from the simulation: the first time (and place) a unilateral constraint lets go, a
contact sticks or slips after the start; each checked at its state against the closed form (λ = 0, σ = 0,
|Φ|/N = μ_s).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.results import Derivation
from lagsolve.numeric.compile import substitute_functions
from lagsolve.numeric.integrate import EventKind, Trajectory
from lagsolve.numeric.system import NumericSystem

#: relative agreement two routes to the same number must reach
AGREEMENT = 1e-6
#: relative agreement of a finite difference (accelerations starting from rest) and of an event's condition
LOOSE = 1e-4


@dataclass(frozen=True)
class Answer:
    """One number of the key: its name (``r_ddot``, ``lambda_tilt``, ``N_wall``), value, what it is, how checked."""

    name: str
    value: float
    what: str
    checked: str


@dataclass(frozen=True)
class Key:
    """The numbers of one variant and the regime of each friction contact at t = 0 (``stick``/``slip``)."""

    answers: tuple[Answer, ...]
    regime: Mapping[str, str] = field(default_factory=dict)
    released: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {"regime": dict(self.regime), "released": self.released,
                "answers": {a.name: {"value": a.value, "what": a.what, "checked": a.checked} for a in self.answers}}


def expected_section(derivation: Derivation) -> dict[str, dict[str, str]]:
    """The derivation's answers as the text of an ``expected:`` section (accelerations, multipliers, magnitudes
    of the forces of constraint, conserved quantities), each printed by SymPy and read back by ``lagsolve check``."""
    section: dict[str, dict[str, str]] = {}
    if derivation.accelerations:
        section["accelerations"] = {k: sympy.sstr(v) for k, v in derivation.accelerations.items()}
    if derivation.multipliers:
        section["multipliers"] = {k: sympy.sstr(v) for k, v in derivation.multipliers.items()}
    forces = {k: sympy.sstr(f.magnitude) for k, f in (derivation.constraint_forces or {}).items()
              if f.magnitude is not None}
    if forces:
        section["constraint_forces"] = forces
    if derivation.conserved:
        section["conserved"] = {k: sympy.sstr(v) for k, v in derivation.conserved.items()}
    return section


class StateNumbers:
    """Evaluates the derivation's expressions at one state and the variant's values."""

    def __init__(self, derivation: Derivation, values: Mapping[str, float], q: np.ndarray, qd: np.ndarray,
                 coordinates: tuple[str, ...], t: float = 0.0, signs: Mapping[Any, float] | None = None) -> None:
        self.signs = {k: sympy.Integer(int(v)) for k, v in (signs or {}).items()}
        symbols = derivation.problem.symbols
        numbers: dict[str, float] = {**values, str(derivation.problem.time): t}
        numbers.update(zip(coordinates, map(float, q), strict=True))
        numbers.update({f"{c}_dot": float(v) for c, v in zip(coordinates, qd, strict=True)})
        self.map = {symbols[k]: sympy.Float(v, 17) for k, v in numbers.items() if k in symbols}
        simulation = derivation.problem.simulation
        given = simulation.functions if simulation is not None else {}
        #: each declared function's concrete form (simulation.functions), as the simulation uses it
        self.functions = {f.function: (given[f.name].arguments, given[f.name].expression)
                          for f in derivation.problem.functions if f.name in given}

    def __call__(self, expr: Any) -> float:
        try:
            concrete = substitute_functions(sympy.sympify(expr, strict=True), self.functions)
            value = complex(concrete.xreplace(self.signs).xreplace(self.map).evalf(17))
        except TypeError:  # a symbol without a value (a conserved momentum p_phi): no number
            return math.nan
        return value.real if abs(value.imag) <= 1e-12 * (1 + abs(value.real)) else math.nan


def _agree(a: float, b: float, tolerance: float = AGREEMENT, scale: float = 1.0) -> bool:
    return math.isfinite(a) and math.isfinite(b) and abs(a - b) <= tolerance * max(abs(a), abs(b), scale)


class KeyBuilder:
    """Builds one variant's key; ``faults`` collects every disagreement between the two routes."""

    def __init__(self, derivation: Derivation, system: NumericSystem, values: Mapping[str, float],
                 trajectory: Trajectory) -> None:
        self.derivation, self.system, self.values, self.run = derivation, system, values, trajectory
        self.answers: list[Answer] = []
        self.faults: list[str] = []
        self.scale = 1.0

    def add(self, name: str, symbolic: float, numeric: float, what: str, checked: str,
            tolerance: float = AGREEMENT, scale: float | None = None) -> None:
        if _agree(symbolic, numeric, tolerance, self.scale if scale is None else scale):
            self.answers.append(Answer(name, float(f"{symbolic:.6g}"), what, checked))
        else:
            self.faults.append(f"{name}: closed form {symbolic:.6g}, {checked} {numeric:.6g}")

    def build(self) -> Key:
        run = self.run
        q0, qd0 = run.q[0], run.qd[0]
        at_rest, regime, signs = self.contacts_at_start(q0, qd0)
        numbers = StateNumbers(self.derivation, self.values, q0, qd0, run.coordinates, signs=signs)
        self.scale = max([1.0, *(abs(v) for v in run.multipliers[0]), *(abs(v) for v in run.normal_forces[0])])
        self.accelerations(numbers, q0, qd0, at_rest, regime)
        self.multipliers(numbers)
        self.friction(numbers, at_rest, regime)
        for name, expr in (self.derivation.conserved or {}).items():
            if name in run.conserved:
                self.add(name, numbers(expr), float(run.conserved[name][0]), f"conserved {name} at t = 0",
                         "simulation at t = 0")
        from lagsolve.variants.equilibria import equilibrium_answers

        parameters = [abs(v) for v in self.values.values()]
        equilibrium_answers(self.derivation, self.system, numbers, self.add, max([1.0, *parameters]))
        self.events()
        released = any(e.kind == EventKind.RELEASE for e in run.events)
        return Key(tuple(self.answers), regime, released)

    def contacts_at_start(self, q0: np.ndarray, qd0: np.ndarray) -> tuple[dict[str, bool], dict[str, str],
                                                                         dict[Any, float]]:
        """Per contact: whether it is at rest at t = 0, its regime (the closed form, checked against the run),
        and for a contact at rest that slips, sign(σ) as the way it starts to slide (against the holding force)."""
        at_rest: dict[str, bool] = {}
        regime: dict[str, str] = {}
        signs: dict[Any, float] = {}
        numbers = StateNumbers(self.derivation, self.values, q0, qd0, self.run.coordinates)
        for result in self.derivation.friction:
            name, term = result.term.name, result.term
            if result.sticking is None or not term.rate or name not in self.run.contacts:
                continue
            c = self.run.contacts.index(name)
            sigma = numbers(term.sliding_rate)
            at_rest[name] = abs(sigma) <= 1e-12
            closed = "slip"
            if at_rest[name]:
                ratio, static = numbers(result.sticking.ratio), numbers(term.static)
                closed = "stick" if ratio <= static else "slip"
                signs[sympy.sign(term.sliding_rate)] = math.copysign(1.0, -numbers(result.sticking.force))
            simulated = "stick" if self.run.stuck[0, c] > 0.5 else "slip"
            if closed != simulated:
                self.faults.append(f"contact {name} at t = 0: closed form says {closed}, simulation {simulated}")
            regime[name] = simulated
        return at_rest, regime, signs

    def accelerations(self, numbers: StateNumbers, q0: np.ndarray, qd0: np.ndarray, at_rest: Mapping[str, bool],
                      regime: Mapping[str, str]) -> None:
        run, coordinates = self.run, self.run.coordinates
        stuck = any(regime.get(k) == "stick" for k in at_rest)
        if any(at_rest.values()):
            t, v = run.t, run.qd
            dt = float(t[1] - t[0])
            numeric = (-3 * v[0] + 4 * v[1] - v[2]) / (2 * dt)
            checked, tolerance = "finite difference of the simulated velocities", LOOSE
        else:
            numeric, _ = self.system.solve(0.0, q0, qd0)
            checked, tolerance = "compiled equations at t = 0", AGREEMENT
        sliding = {i for r in self.derivation.friction for i, w in enumerate(r.term.rate or ()) if w != 0}
        for i, name in enumerate(coordinates):
            expr = (self.derivation.accelerations or {}).get(name)
            if expr is None or (stuck and i in sliding):
                continue
            self.add(f"{name}_ddot", numbers(expr), float(numeric[i]), f"acceleration of {name} at t = 0", checked,
                     tolerance, max(1.0, float(np.max(np.abs(numeric)))))

    def multipliers(self, numbers: StateNumbers) -> None:
        run = self.run
        for j, name in enumerate(run.constraints):
            expr = (self.derivation.multipliers or {}).get(name)
            if expr is not None:
                self.add(f"lambda_{name}", numbers(expr), float(run.multipliers[0, j]),
                         f"multiplier of {name} at t = 0", "simulation at t = 0")
            force = (self.derivation.constraint_forces or {}).get(name)
            if force is not None and force.magnitude is not None and not force.generalized:
                self.add(f"F_{name}", numbers(force.magnitude), float(run.magnitudes[0, j]),
                         f"magnitude of the force of constraint {name} at t = 0", "simulation at t = 0")

    def friction(self, numbers: StateNumbers, at_rest: Mapping[str, bool], regime: Mapping[str, str]) -> None:
        run = self.run
        for result in self.derivation.friction:
            name = result.term.name
            if name not in run.contacts:
                continue
            c = run.contacts.index(name)
            normal = numbers(result.normal_force)
            self.add(f"N_{name}", normal, float(run.normal_forces[0, c]), f"normal force of contact {name} at t = 0",
                     "simulation at t = 0")
            if name not in regime or c >= run.friction.shape[1]:
                continue
            if regime[name] == "stick" and result.sticking is not None:
                self.add(f"friction_{name}", numbers(result.sticking.force), float(run.friction[0, c]),
                         f"friction force that holds contact {name} at t = 0", "simulation at t = 0")
            if at_rest.get(name) and result.sticking is not None:
                ratio = numbers(result.sticking.ratio)
                self.add(f"least_static_{name}", ratio, ratio, f"least static coefficient that holds {name} at t = 0",
                         "closed form (the regime is checked against the simulation)")

    def events(self) -> None:
        """The first release, and the first stick and slip after the start, each checked at its state."""
        seen: set[tuple[str, str]] = set()
        constraints = self.run.constraints
        friction = {r.term.name: r for r in self.derivation.friction}
        for event in self.run.events:
            key = (str(event.kind), event.name)
            if event.time <= 0 or key in seen:
                continue
            seen.add(key)
            coordinates = self.run.coordinates
            state = event.state
            numbers = StateNumbers(self.derivation, self.values, np.array([state[c] for c in coordinates]),
                               np.array([state[f"{c}_dot"] for c in coordinates]), coordinates, event.time)
            what = f"time contact {event.name} {event.kind}s" if event.name in friction else \
                f"time constraint {event.name} lets go"
            self.answers.append(Answer(f"{event.kind}_time_{event.name}", float(f"{event.time:.6g}"), what,
                                       "simulation (event located on the dense output)"))
            if event.kind == EventKind.RELEASE:
                self.answers += [Answer(f"{c}_at_release_{event.name}", float(f"{state[c]:.6g}"),
                                        f"{c} where constraint {event.name} lets go",
                                        "simulation (event located on the dense output)") for c in coordinates]
            self.event_condition(event, numbers, friction, constraints)

    def event_condition(self, event: Any, numbers: StateNumbers, friction: Mapping[str, Any],
                        constraints: tuple[str, ...]) -> None:
        if event.kind == EventKind.RELEASE and event.name in constraints:
            value = numbers((self.derivation.multipliers or {}).get(event.name, sympy.nan))
            scale = max(1.0, *(abs(x) for x in self.run.multipliers[0]))
            if not abs(value) <= LOOSE * scale:
                self.faults.append(f"release of {event.name} at t = {event.time:.6g}: λ = {value:.3g}, not 0")
        elif event.kind == EventKind.STICK and event.name in friction:
            sigma = numbers(friction[event.name].term.sliding_rate)
            if not abs(sigma) <= LOOSE * max(1.0, float(np.max(np.abs(self.run.qd)))):
                self.faults.append(f"{event.name} sticks at t = {event.time:.6g} with sliding rate {sigma:.3g}")
        elif event.kind == EventKind.SLIP and event.name in friction and friction[event.name].sticking is not None:
            result = friction[event.name]
            ratio, static = numbers(result.sticking.ratio), numbers(result.term.static)
            if not _agree(ratio, static, LOOSE):
                self.faults.append(f"{event.name} slips at t = {event.time:.6g} needing |Φ|/N = {ratio:.6g}, "
                                   f"not mu_s = {static:.6g}")
