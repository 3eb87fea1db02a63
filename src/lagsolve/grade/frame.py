r"""A submission in other coordinates (``coordinates_map:``): the point transformation and what it does to each step.

The submission gives each of its own coordinates q' as an expression of the key's coordinates q (and the time),
q'_s = f_s(q, t); a key coordinate that no expression uses is kept as it is. The student's text is then read with
their names (``phi``, ``phi_dot``, ``phi_ddot``, ``p_phi``) and mapped into the key's by the chain rule:

- q' → f(q, t), q̇' → ḟ = ∂f/∂q q̇ + ∂f/∂t, q̈' → f̈ (the total derivative again, with q̈), and in the Hamiltonian
  p'_s → Σ_k p_k M[k][s], where M = J⁻¹ = ∂q/∂q' (J[s][k] = ∂f_s/∂q_k) is written in the key's coordinates;
- scalars (T, V, L, conserved quantities, V_eff) are compared as they are, mapped; H as K − Σ_s p'_s ∂f_s/∂t
  (a time-dependent map changes the Hamiltonian by the generating function's rate);
- the key's per-coordinate answers are carried into the student's coordinates: momenta and equations are
  covectors, p'_s = Σ_k p_k M[k][s]; ∂L'/∂q'_s = Σ_k (∂L/∂q_k M[k][s] + p_k Ṁ[k][s]) (∂q̇/∂q' = d/dt ∂q/∂q');
  accelerations are f̈_s with the key's q̈ put in; an equilibrium is f(q*) (for a map without t);
- multipliers, forces of constraint, normal forces and frequencies do not depend on the coordinates.

Nothing here reads text: the map's expressions come through the expression gateway (:mod:`.submission`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.grade.numeric_lists import Condition
from lagsolve.problem.names import momentum_symbol

#: CPU seconds to invert a map in closed form (for the terms of the key's T in the student's coordinates)
INVERT_BUDGET = 2.0


class MapError(ValueError):
    """The map is not a change of coordinates (the message says why)."""


@dataclass(frozen=True)
class StudentCoordinate:
    """One of the student's coordinates: its name and symbols."""

    name: str
    symbol: Any
    velocity: Any
    acceleration: Any
    momentum: Any


def student_coordinate(name: str, existing: Any = None) -> StudentCoordinate:
    """The symbols of the student's coordinate ``name`` (a key coordinate's own symbol when it is one)."""
    symbol = existing if existing is not None else sympy.Symbol(name, real=True)
    return StudentCoordinate(name, symbol, sympy.Symbol(f"{name}_dot", real=True),
                             sympy.Symbol(f"{name}_ddot", real=True), momentum_symbol(name))


class Frame:
    """The map q' = f(q, t) between a submission's coordinates and the key's.

    ``coordinates`` are the student's, in the key's order (each at the place of the first key coordinate it
    uses); ``q``, ``qd``, ``qdd``, ``p`` the key's coordinates, velocities, accelerations and momentum symbols."""

    def __init__(self, coordinates: tuple[StudentCoordinate, ...], expressions: tuple[Any, ...], time: Any,
                 key_coordinates: tuple[Any, ...], key_velocities: tuple[Any, ...],
                 key_accelerations: tuple[Any, ...]) -> None:
        if len(coordinates) != len(key_coordinates):
            raise MapError(f"the map gives {len(coordinates)} coordinates for the key's {len(key_coordinates)}")
        self.coordinates, self.expressions, self.time = coordinates, expressions, time
        self.q, self.qd, self.qdd = key_coordinates, key_velocities, key_accelerations
        self.p = tuple(momentum_symbol(q.name) for q in key_coordinates)
        self.names = tuple(c.name for c in coordinates)
        jacobian = sympy.Matrix([[sympy.diff(f, q) for q in self.q] for f in expressions])
        if sympy.cancel(jacobian.det()) == 0:
            raise MapError("the map's Jacobian ∂q'/∂q is singular: it is not a change of coordinates")
        self.jacobian = jacobian
        self.inverse = jacobian.inv(method="LU")  # M[k][s] = ∂q_k/∂q'_s
        self.velocities = tuple(self.rate(f) for f in expressions)
        self.accelerations = tuple(self.rate(v, second_order=True) for v in self.velocities)
        self.inverse_rate = self.inverse.applyfunc(self.rate)
        self.momenta = tuple(sum((self.p[k] * self.inverse[k, s] for k in range(len(self.q))), sympy.Integer(0))
                             for s in range(len(coordinates)))
        self.depends_on_time = any(f.has(time) for f in expressions)
        self._inverse: dict[Any, Any] | None = None
        self.substitution: dict[Any, Any] = {}
        for c, f, v, a, p in zip(coordinates, expressions, self.velocities, self.accelerations, self.momenta,
                                 strict=True):
            self.substitution.update({c.symbol: f, c.velocity: v, c.acceleration: a, c.momentum: p})

    def rate(self, expr: Any, *, second_order: bool = False) -> Any:
        """The total time derivative along the key's coordinates (with the accelerations when ``second_order``)."""
        out = sympy.diff(expr, self.time)
        for q, qd in zip(self.q, self.qd, strict=True):
            out += sympy.diff(expr, q) * qd
        if second_order:
            for qd, qdd in zip(self.qd, self.qdd, strict=True):
                out += sympy.diff(expr, qd) * qdd
        return out

    # -- the student's expressions in the key's coordinates

    def entry(self, expr: Any) -> Any:
        """A student's expression with their coordinates, velocities, accelerations and momenta put in."""
        return expr.xreplace(self.substitution)

    def hamiltonian(self, expr: Any) -> Any:
        """The student's K(q', p') as the key's H: K − Σ_s p'_s ∂f_s/∂t, mapped; the sum over the coordinates whose
        momentum K has (H is written in the minimal coordinates: a coordinate its constraint fixes has none)."""
        used = expr.free_symbols
        shift = sum((p * sympy.diff(f, self.time) for c, p, f in zip(self.coordinates, self.momenta, self.expressions,
                                                                     strict=True) if c.momentum in used),
                    sympy.Integer(0))
        return self.entry(expr) - shift

    def key_equations(self, equations: dict[str, Any]) -> dict[str, Any] | None:
        """The student's equations (by their coordinates, mapped) as the key's: E_k = Σ_s J[s][k] E'_s."""
        if set(equations) != set(self.names):
            return None
        return {q.name: sum((self.jacobian[s, k] * equations[name] for s, name in enumerate(self.names)),
                            sympy.Integer(0)) for k, q in enumerate(self.q)}

    # -- the key's answers in the student's coordinates

    def covector(self, values: dict[str, Any]) -> dict[str, Any]:
        """Σ_k v_k M[k][s] for each student coordinate s (momenta, equations); {} when a key entry is absent."""
        if any(q.name not in values for q in self.q):
            return {}
        return {name: sum((values[q.name] * self.inverse[k, s] for k, q in enumerate(self.q)), sympy.Integer(0))
                for s, name in enumerate(self.names)}

    def gradients(self, gradients: dict[str, Any], momenta: dict[str, Any]) -> dict[str, Any]:
        """∂L'/∂q'_s = Σ_k (∂L/∂q_k M[k][s] + p_k Ṁ[k][s])."""
        if any(q.name not in gradients or q.name not in momenta for q in self.q):
            return {}
        return {name: sum((gradients[q.name] * self.inverse[k, s] + momenta[q.name] * self.inverse_rate[k, s]
                           for k, q in enumerate(self.q)), sympy.Integer(0))
                for s, name in enumerate(self.names)}

    def key_accelerations(self, accelerations: dict[str, Any]) -> dict[str, Any]:
        """q̈'_s = f̈_s with the key's q̈ put in."""
        if any(q.name not in accelerations for q in self.q):
            return {}
        values = {qdd: accelerations[q.name] for q, qdd in zip(self.q, self.qdd, strict=True)}
        return {name: a.xreplace(values) for name, a in zip(self.names, self.accelerations, strict=True)}

    def point(self, point: dict[str, Any]) -> dict[str, Any] | None:
        """An equilibrium of the key's, f(q*), over the student's coordinates that depend only on the point's;
        None for a map with t."""
        if self.depends_on_time:
            return None
        conditions = [v for v in point.values() if isinstance(v, Condition)]
        if conditions:
            return self.condition(conditions[0]) if len(point) == 1 else None
        given = {q: point[q.name] for q in self.q if q.name in point}
        out = {}
        for name, f in zip(self.names, self.expressions, strict=True):
            if f.free_symbols & set(self.q) <= set(given):
                out[name] = f.xreplace(given)
        return out or None

    @property
    def scalable(self) -> bool:
        """The student's velocities are linear in the key's (a map without t)."""
        return not self.depends_on_time

    def scaling(self, k: int) -> dict[Any, Any]:
        r"""The student's velocities times ``k`` and their accelerations held, in the key's variables (a map
        without t): q̇ → k q̇ and q̈ → q̈ + (k² − 1) Ṁ J q̇ (q̈ = M q̈' + Ṁ q̇', q̇' = J q̇)."""
        quadratic = self.inverse_rate * self.jacobian * sympy.Matrix(self.qd)
        out: dict[Any, Any] = {v: k * v for v in self.qd}
        out.update({a: a + (k**2 - 1) * quadratic[i] for i, a in enumerate(self.qdd)})
        return out

    def condition(self, condition: Condition) -> dict[str, Any] | None:
        """An equilibrium known by its condition, written in the one student coordinate it then depends on (the map
        inverted in closed form); None otherwise."""
        residual = self.in_student(condition.residual)
        if residual is None:
            return None
        own = [c for c in self.coordinates if c.symbol in residual.free_symbols]
        if len(own) != 1:
            return None
        return {own[0].name: Condition(own[0].symbol, residual)}

    def in_student(self, expr: Any) -> Any:
        """``expr`` (in the key's coordinates and velocities) written in the student's, when the map can be inverted
        in closed form within :data:`INVERT_BUDGET` s of CPU (one solution, checked at a point); else None."""
        if self._inverse is None:
            self._inverse = self._invert() or {}
        if not self._inverse:
            return None
        try:
            return expr.xreplace(self._inverse)
        except (TypeError, ValueError, AttributeError):  # a derivative with respect to a replaced coordinate
            return None

    def _invert(self) -> dict[Any, Any] | None:
        from lagsolve.mechanics.stages import StageTimeout, cpu_limit

        kept = {c.symbol for c, f in zip(self.coordinates, self.expressions, strict=True) if f == c.symbol}
        equations = [f - c.symbol for c, f in zip(self.coordinates, self.expressions, strict=True)
                     if c.symbol not in kept]
        unknowns = [q for q in self.q if q not in kept]
        try:
            with cpu_limit(INVERT_BUDGET):
                solutions = sympy.solve(equations, unknowns, dict=True)
        except StageTimeout:
            return None
        except (TypeError, ValueError, NotImplementedError, AttributeError, sympy.PolynomialError):
            return None
        if len(solutions) != 1 or set(solutions[0]) != set(unknowns):
            return None
        positions = {**solutions[0], **{q: q for q in kept}}
        velocities = {}
        for q, qd in zip(self.q, self.qd, strict=True):
            g = positions[q]
            velocities[qd] = sympy.diff(g, self.time) + sum((sympy.diff(g, c.symbol) * c.velocity
                                                             for c in self.coordinates), sympy.Integer(0))
        return {**positions, **velocities}

    def signature(self) -> tuple:
        return tuple(zip(self.names, self.expressions, strict=True))


def build_frame(spec: dict[str, Any], key_symbols: dict[str, Any], time: Any, key_coordinates: tuple[Any, ...],
                key_velocities: tuple[Any, ...], key_accelerations: tuple[Any, ...]) -> Frame:
    """The frame of a read map ``spec`` (student coordinate name → SymPy expression of the key's coordinates).

    Raises
    ------
    MapError
        An expression uses a velocity, uses no key coordinate, or the map is not invertible.
    """
    allowed = {*key_coordinates, time}
    parameters = {s for name, s in key_symbols.items() if s not in key_velocities}
    coordinates, expressions = [], []
    used: set[Any] = set()
    by_name = {q.name: q for q in key_coordinates}
    for name, expr in spec.items():
        symbols = expr.free_symbols
        if symbols & set(key_velocities):
            raise MapError(f"{name}: a coordinate is a function of the key's coordinates and t, not of velocities")
        if not symbols & set(key_coordinates):
            raise MapError(f"{name}: the expression uses none of the key's coordinates "
                           f"({', '.join(q.name for q in key_coordinates)})")
        if symbols - allowed - parameters:
            raise MapError(f"{name}: unknown names {sorted(str(s) for s in symbols - allowed - parameters)}")
        used |= symbols & set(key_coordinates)
        coordinates.append(student_coordinate(name, by_name.get(name)))
        expressions.append(expr)
    for q in key_coordinates:
        if q not in used and q.name not in spec:
            coordinates.append(student_coordinate(q.name, q))
            expressions.append(q)
    # in the key's order: each at the place of the first key coordinate it uses (ties in the map's order)
    place = {q: i for i, q in enumerate(key_coordinates)}
    order = sorted(range(len(coordinates)), key=lambda i: (min(place[q] for q in expressions[i].free_symbols
                                                               if q in place), i))
    return Frame(tuple(coordinates[i] for i in order), tuple(expressions[i] for i in order), time, key_coordinates,
                 key_velocities, key_accelerations)


#: per-coordinate steps carried into the student's coordinates; the other steps keep the key's answers
CARRIED = ("momenta", "generalized_forces", "equations", "accelerations", "equilibria")


def answers_in_frame(answers: dict[str, dict[str, Any]], frame: Frame) -> dict[str, dict[str, Any]]:
    """The key's answers (or what follows from a student's steps) with the per-coordinate steps in the student's
    coordinates; a step that cannot be carried over is left out."""
    out = {step: values for step, values in answers.items() if step not in CARRIED}
    if "momenta" in answers:
        out["momenta"] = frame.covector(answers["momenta"])
    if "equations" in answers:
        out["equations"] = frame.covector(answers["equations"])
    if "generalized_forces" in answers and "momenta" in answers:
        out["generalized_forces"] = frame.gradients(answers["generalized_forces"], answers["momenta"])
    if "accelerations" in answers:
        out["accelerations"] = frame.key_accelerations(answers["accelerations"])
    if "equilibria" in answers:
        points = [frame.point(p) for p in answers["equilibria"].values()]
        if points and all(p is not None for p in points):
            out["equilibria"] = {str(i + 1): p for i, p in enumerate(points)}
    if "effective_potential" in answers:
        [(coordinate, value)] = answers["effective_potential"].items()
        out["effective_potential"] = {name: value for name, f in frame.signature()
                                      if {str(q) for q in f.free_symbols} & {coordinate}}
    return {step: values for step, values in out.items() if values}


def own_in_key(own: dict[str, dict[str, Any]], frame: Frame) -> dict[str, dict[str, Any]]:
    """A submission's own steps as the key's coordinates see them (for follow-through): its equations as the
    key's covectors; the other steps are already mapped (their per-coordinate names are the student's, unused)."""
    out = {step: values for step, values in own.items() if step in ("kinetic", "potential", "lagrangian",
                                                                   "multipliers", "hamiltonian", "conserved")}
    if "equations" in own:
        equations = frame.key_equations(own["equations"])
        if equations is not None:
            out["equations"] = equations
    return out
