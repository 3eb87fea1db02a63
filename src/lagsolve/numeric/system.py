"""A problem's matrix form bound to numbers: the callables the integrator needs.

The equations come from the *matrix form* (``M q̈ = F + Aᵀλ``, ``A q̈ = β``), not
from display-simplified results; the augmented linear system is solved
numerically at each evaluation. Parameters are an array, so ``--set g=1.62``
needs no recompilation.

Friction: the generalized forces are affine in the normal forces,
``F = F₀ + S N`` (``S`` holds −μ times the sliding direction), so one solve with
several right-hand sides gives ``q̈ = q̈₀ + Q N`` and ``λ = λ₀ + Λ N``. The normal
force of a contact is the length of the combined force of its constraints,
``N = |a + B N|`` with ``a = Σ λ₀ⱼ uⱼ`` and ``B = Σ Λⱼ uⱼ``: for one contact a
quadratic with a unique non-negative root when ``|B| < 1``, for several a
fixed-point iteration. This solves the coupling between friction and normal
force consistently at every step (and reports the Painlevé-type case where it
has no unique solution).

State order: ``q`` and ``qd`` follow the problem's coordinates; multipliers its
constraints; normal forces its friction contacts.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy
from scipy.linalg import lapack

from lagsolve.errors import Issue, SimulationError, SpecError
from lagsolve.mechanics.analysis.minimal_chart import MinimalChart
from lagsolve.mechanics.equations.energy import jacobi_integral
from lagsolve.mechanics.equations.friction import contact_directions, normal_forces_at
from lagsolve.mechanics.equations.matrix_form import MatrixForm
from lagsolve.mechanics.equations.reactions import force_direction, force_scale
from lagsolve.numeric.compile import StateFunction, compile_state_function, substitute_functions
from lagsolve.numeric.minimal_state import NumericChart, compile_chart
from lagsolve.problem.schema import ConstraintKind, Problem


def surface_scales(gradients: np.ndarray, q: np.ndarray) -> np.ndarray:
    """For each holonomic constraint (``gradients``: its ∇ψ in the last axis, one state or a batch of them), the
    size its residual ψ takes for a displacement of the state's own size: ‖∇ψ‖ · max|q| (1 where that is zero or
    not finite). Residuals are measured against it, so that a problem in micrometres is held to the same relative
    accuracy as one in metres (x² + y² − l² is 1e-14 m² off at l = 1e-7 m with the bob 40 % of l away from its
    circle)."""
    with np.errstate(all="ignore"):
        scales = np.linalg.norm(gradients, axis=-1) * np.max(np.abs(q), axis=-1, initial=0.0)[..., None]
    return np.where(np.isfinite(scales) & (scales > 0), scales, 1.0)


@dataclass(frozen=True)
class NumericSystem:
    """Numeric callables of one problem, each ``f(t, q, qd, p) -> ndarray``.

    ``holonomic`` indexes the constraints given at position level (projected onto);
    ``unilateral`` those that hold only while they push; ``contacts`` lists, per
    friction contact, the rows of ``directions`` holding each normal constraint's
    force direction on the member that slides.
    """

    coordinates: tuple[str, ...]
    constraints: tuple[str, ...]
    holonomic: tuple[int, ...]
    unilateral: tuple[int, ...]
    parameter_names: tuple[str, ...]
    parameters: np.ndarray
    matrices: StateFunction
    contacts: tuple[tuple[tuple[int, int, int], ...], ...]  # per contact: (constraint j, offset, dims)
    contact_names: tuple[str, ...]
    sticks: tuple[bool, ...]  # per contact: it slides along one line, so it can stick (stick–slip)
    contact_values: StateFunction  # per contact: the static and the kinetic coefficient
    # per contact that can stick: the sliding rate's coefficients w (n), the rate of change of w along the motion
    # times the velocities (ẇ·q̇, 1), and the generalized forces of a unit tangential force g (n)
    sliding: StateFunction
    directions: StateFunction
    scales: StateFunction
    position_residual: StateFunction
    position_jacobian: StateFunction
    velocity_jacobian: StateFunction
    velocity_offset: StateFunction
    # per contact that slides in a plane (not ``sticks``), in contact order: its sliding speed |v|; the friction
    # -mu N v/|v| holds only while it is not 0 (:mod:`lagsolve.numeric.integrate` stops the run where it comes to rest)
    speeds: StateFunction
    energy: StateFunction
    positions: StateFunction
    particles: tuple[tuple[str, int], ...]
    conserved_names: tuple[str, ...]
    conserved: StateFunction
    energy_conserved: bool
    energy_note: str
    # per constraint: how many components its force of constraint has (the force on its first particle is
    # λ times the rows of expressions["force_directions"]; 0 where no physical force is known)
    force_dims: tuple[int, ...] = ()
    chart: NumericChart | None = None  # minimal coordinates, when the constraints are solved in closed form
    evaluations: list[int] = field(default_factory=lambda: [0])
    # what was compiled, for batch compilers (lagsolve.sweep): each group's expressions (NaN where a symbol
    # has no value) and the ordered arguments (time, coordinates, velocities, parameters)
    expressions: Mapping[str, tuple[Any, ...]] = field(default_factory=dict)
    arguments: tuple[Any, ...] = ()

    @property
    def n(self) -> int:
        return len(self.coordinates)

    @property
    def m(self) -> int:
        return len(self.constraints)

    @property
    def planar(self) -> tuple[int, ...]:
        """The contacts that slide in a plane (not :attr:`sticks`), in the order of :attr:`speeds`."""
        return tuple(c for c, sticks in enumerate(self.sticks) if not sticks)

    def solve(self, t: float, q: np.ndarray, qd: np.ndarray,
              active: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Accelerations and multipliers at a state (inactive constraints get λ = 0)."""
        qdd, lam, _, _ = self.solve_all(t, q, qd, active)
        return qdd, lam

    def solve_all(self, t: float, q: np.ndarray, qd: np.ndarray, active: np.ndarray | None = None,
                  stuck: np.ndarray | None = None,
                  direction: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        r"""Accelerations, multipliers, friction normal forces and sticking forces at a state.

        Solves :math:`\begin{pmatrix}M & -A^T\\ A & 0\end{pmatrix}
        \begin{pmatrix}\ddot q\\ \lambda\end{pmatrix} = \begin{pmatrix}F\\ \beta\end{pmatrix}`
        with the rows of inactive constraints removed, and the normal forces consistently.
        A ``stuck`` contact holds its sliding rate σ = w·q̇ at zero (a row w·q̈ = −ẇ·q̇) with a
        tangential force Φ t at the contact (generalized forces Φ g) instead of kinetic friction;
        Φ is returned in the last array. ``direction`` gives the sliding direction (±1) where
        the sliding rate is zero (the start of a slip).
        """
        self.evaluations[0] += 1
        n, m, k = self.n, self.m, len(self.contacts)
        p = self.parameters
        flat = self.matrices(t, q, qd, p)
        M = flat[: n * n].reshape(n, n)
        if k == 0 and (active is None or active.all()):
            # the common cases without friction, kept lean: this runs at every step
            if m == 0:
                return _solve(M, flat[n * n: n * n + n]), _EMPTY, _EMPTY, _EMPTY
            at = n * n + n
            system = np.zeros((n + m, n + m))
            system[:n, :n] = M
            A = flat[at: at + m * n].reshape(m, n)
            system[:n, n:] = -A.T
            system[n:, :n] = A
            solution = _solve(system, np.concatenate((flat[n * n: at], flat[at + m * n:])))
            return solution[:n], solution[n:], _EMPTY, _EMPTY
        at = n * n
        F = flat[at: at + n * (k + 1)].reshape(n, k + 1).copy()
        at += n * (k + 1)
        A = flat[at: at + m * n].reshape(m, n)
        beta = flat[at + m * n:]
        mask = np.ones(m, dtype=bool) if active is None else active
        A, beta = A[mask], beta[mask]
        held = []
        for c, (w, drift, g) in self.sliding_parts(t, q, qd).items():
            if stuck is not None and stuck[c]:
                F[:, c + 1] = 0.0
                held.append((c, w, drift, g))
                continue
            F[:, c + 1] *= sliding_sign(w, qd, direction, c)
        kept = A.shape[0]
        rows = kept + len(held)
        if rows == 0:
            solution = _solve(M, F)
        else:
            system = np.zeros((n + rows, n + rows))
            system[:n, :n] = M
            system[:n, n: n + kept] = -A.T
            system[n: n + kept, :n] = A
            rhs = np.zeros((n + rows, k + 1))
            rhs[:n] = F
            rhs[n: n + kept, 0] = beta
            for r, (_, w, drift, g) in enumerate(held):
                system[:n, n + kept + r] = -g
                system[n + kept + r, :n] = w
                rhs[n + kept + r, 0] = -drift
            solution = _solve(system, rhs)
        lam_all = np.zeros((m, k + 1))
        lam_all[mask] = solution[n: n + kept]
        normal = self._normal_forces(t, q, qd, lam_all) if k else _EMPTY
        qdd = solution[:n, 0] + solution[:n, 1:] @ normal
        lam = lam_all[:, 0] + lam_all[:, 1:] @ normal
        sticking = np.zeros(k)
        for r, (c, *_) in enumerate(held):
            sticking[c] = solution[n + kept + r, 0] + solution[n + kept + r, 1:] @ normal
        return qdd, lam, normal, sticking

    def surface_scales(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """:func:`surface_scales` of each holonomic constraint at the state (t, q, q̇)."""
        if not self.holonomic:
            return _EMPTY
        gradients = self.position_jacobian(t, q, qd, self.parameters).reshape(len(self.holonomic), self.n)
        return surface_scales(gradients, q)

    def sliding_parts(self, t: float, q: np.ndarray, qd: np.ndarray) -> dict[int, tuple[np.ndarray, float, np.ndarray]]:
        """Per contact that can stick: its sliding rate's coefficients w, the drift ẇ·q̇ and the generalized
        forces g of a unit tangential force."""
        if not any(self.sticks):
            return {}
        n = self.n
        values = self.sliding(t, q, qd, self.parameters)
        out = {}
        at = 0
        for c, sticks in enumerate(self.sticks):
            if sticks:
                out[c] = (values[at: at + n], float(values[at + n]), values[at + n + 1: at + 2 * n + 1])
                at += 2 * n + 1
        return out

    def sliding_rate(self, t: float, q: np.ndarray, qd: np.ndarray, c: int) -> float:
        """σ = w·q̇ of contact ``c`` (which can stick)."""
        return float(self.sliding_parts(t, q, qd)[c][0] @ qd)

    def _normal_forces(self, t: float, q: np.ndarray, qd: np.ndarray, lam: np.ndarray) -> np.ndarray:
        return normal_forces_at(t, self.contacts, self.directions(t, q, qd, self.parameters), lam)

    def friction_forces(self, t: float, q: np.ndarray, qd: np.ndarray, normal: np.ndarray, stuck: np.ndarray,
                        sticking: np.ndarray, direction: np.ndarray) -> np.ndarray:
        r"""The friction force of each contact at a state, shape (contacts,).

        Where the contact slides along one line: the force's component along its unit tangent t (signed),
        :math:`-\mu N\,\mathrm{sign}(\sigma)` while it slides and the force Φ that holds it while it sticks.
        Where it slides in a plane: the magnitude μ N of the kinetic friction (it opposes the sliding
        velocity).
        """
        k = len(self.contacts)
        if k == 0:
            return _EMPTY
        values = self.contact_values(t, q, qd, self.parameters)
        parts = self.sliding_parts(t, q, qd)
        out = np.zeros(k)
        for c in range(k):
            kinetic = values[2 * c + 1]
            if c not in parts:
                out[c] = kinetic * normal[c]
            elif stuck[c]:
                out[c] = sticking[c]
            else:
                out[c] = -kinetic * normal[c] * sliding_sign(parts[c][0], qd, direction, c)
        return out

    def magnitudes(self, t: float, q: np.ndarray, qd: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """|force of constraint j| = |λ_j| · |direction_j| (NaN where no force can be claimed)."""
        return np.abs(lam) * self.scales(t, q, qd, self.parameters)


_EMPTY = np.zeros(0)

#: a sliding rate this small against |w|·|q̇| counts as zero (rounding after a projection onto σ = 0)
RATE_TOLERANCE = 1e-12


def sliding_sign(w: np.ndarray, qd: np.ndarray, direction: np.ndarray | None, c: int) -> float:
    """The sign kinetic friction opposes at contact ``c``: the direction the integrator holds between events
    (``direction[c]``, set where the contact starts to slide and flipped where its rate passes through zero,
    :mod:`lagsolve.numeric.integrate`), so that the right-hand side is smooth up to the event and the rate
    crosses zero there, not stalls at it with ever smaller steps; without one, the sign of the rate."""
    if direction is not None and direction[c] != 0:
        return float(np.sign(direction[c]))
    return rate_sign(w, qd, 0.0)


def rate_sign(w: np.ndarray, qd: np.ndarray, fallback: float) -> float:
    """The sign of the sliding rate w·q̇, or ``fallback`` (the direction a slip starts in) where it is zero."""
    rate = float(w @ qd)
    if abs(rate) <= RATE_TOLERANCE * float(np.abs(w) @ np.abs(qd)) or rate == 0.0:
        return float(fallback)
    return 1.0 if rate > 0 else -1.0


def _solve(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """LAPACK's dgesv directly: a small system costs about a microsecond, a fifth of ``np.linalg.solve``."""
    _, _, solution, info = lapack.dgesv(matrix, rhs)
    if info != 0:
        raise np.linalg.LinAlgError("singular matrix")
    return solution


def _values(form: MatrixForm, overrides: Mapping[str, float]) -> dict[str, float]:
    problem = form.problem
    values: dict[str, float] = {p.name: p.value for p in problem.parameters if p.value is not None}
    if problem.simulation is not None:
        values.update(problem.simulation.values)
    values.update(overrides)
    return values


def bind(form: MatrixForm, overrides: Mapping[str, float] | None = None,
         conserved: Mapping[str, Any] | None = None, chart: MinimalChart | None = None,
         energy_note: str = "") -> NumericSystem:
    """Bind a problem's matrix form to parameter values (the file's, then ``overrides``) and its
    concrete functions, and compile everything the integrator needs. ``conserved`` maps names to
    expressions whose drift should be reported (those with unknown symbols are skipped); with a
    ``chart`` the system can be integrated in minimal coordinates.

    Raises
    ------
    SpecError
        A parameter used by the equations has no value, a declared function has no
        concrete form, or an override names an unknown parameter.
    """
    overrides = dict(overrides or {})
    conserved = dict(conserved or {})
    issues = _override_issues(form.problem, overrides)
    concrete = _concrete_functions(form.problem, issues)

    def prepare(expr: Any) -> Any:
        return substitute_functions(sympy.Integer(expr) if isinstance(expr, int) else expr, concrete)

    contacts, groups = _expressions(form, conserved)
    prepared = {key: [prepare(e) for e in group] for key, group in groups.items()}
    values = _values(form, overrides)
    issues += _value_issues(form.problem, prepared, values)
    if issues:
        raise SpecError(issues)
    try:
        compiled_chart = None if chart is None else compile_chart(chart, prepare, **_arguments(form))
        return _compiled(form, prepared, values, contacts, conserved, compiled_chart, energy_note)
    except (ValueError, TypeError, NameError) as exc:  # pragma: no cover - lambdify of a derived expression
        raise SimulationError(f"could not compile the equations of {form.problem.source}: {exc}") from None


def _override_issues(problem: Problem, overrides: Mapping[str, float]) -> list[Issue]:
    """An override of an unknown parameter, or a negative value of a positive one."""
    source = problem.source
    issues: list[Issue] = []
    known = {p.name for p in problem.parameters}
    for name, value in overrides.items():
        if name not in known:
            issues.append(Issue(source, 0, "--set", f"unknown parameter {name!r}",
                                "known: " + ", ".join(sorted(known)) if known else "the problem has no parameters"))
        elif value < 0 and next(p for p in problem.parameters if p.name == name).positive:
            issues.append(Issue(source, 0, "--set", f"{name}={value:g} contradicts the assumption that parameter "
                                f"{name!r} is positive (parameters are, unless declared with positive: false), "
                                "which the derivation relies on",
                                f"give a value >= 0, or declare {name} with positive: false in {source}"))
    return issues


def _concrete_functions(problem: Problem, issues: list[Issue]) -> dict[Any, Any]:
    """Each declared function → (arguments, expression) of its concrete form; an issue for each without one."""
    concrete = {}
    simulation = problem.simulation
    for fn in problem.functions:
        given = simulation.functions.get(fn.name) if simulation is not None else None
        if given is None:
            issues.append(Issue(problem.source, problem.lines.get("functions", 0), "simulation.functions",
                                f"function {fn.name!r} has no concrete form",
                                f'add e.g. "{fn.name}(u)": "u**2/2" under simulation.functions'))
        else:
            concrete[fn.function] = (given.arguments, given.expression)
    return concrete


def _friction_columns(form: MatrixForm) -> tuple[list[Any], list[Any]]:
    """The forcing's columns (F at N = 0, then F's part per unit normal force of each contact) and the
    sliding rates, their drift and unit directions of the contacts that slide along one line."""
    model, forcing = form.model, form.lagrange.forcing
    columns = [forcing.xreplace({f.normal: 0 for f in form.frictions})]
    sliding: list[Any] = []
    for f in form.frictions:
        if f.unit_generalized is None:
            columns.append(forcing.diff(f.normal))
            continue
        # sliding along one line: -mu sign(sigma) g per unit N; the sign is applied at each state
        columns.append(sympy.Matrix([-f.coefficient * g for g in f.unit_generalized]))
        assert f.rate is not None
        rate_change = [model.time_derivative(w) for w in f.rate]
        drift = sum((c * v for c, v in zip(rate_change, model.velocities, strict=True)), sympy.Integer(0))
        sliding += [*f.rate, drift, *f.unit_generalized]
    return columns, sliding


def _holonomic(form: MatrixForm) -> tuple[int, ...]:
    return tuple(j for j, c in enumerate(form.constraints) if c.kind == ConstraintKind.HOLONOMIC)


def _expressions(form: MatrixForm, conserved: Mapping[str, Any]) -> tuple[list[Any], dict[str, list[Any]]]:
    """The contacts, and every group of expressions the system compiles, by name."""
    problem, model, lagrange = form.problem, form.model, form.lagrange
    columns, sliding = _friction_columns(form)
    forcing_columns = [columns[c][i] for i in range(len(model.coordinates)) for c in range(len(columns))]
    matrices = [*lagrange.mass_matrix, *forcing_columns, *lagrange.constraint_jacobian, *lagrange.constraint_rhs]
    contacts, directions = contact_directions(problem, form.frictions, form.constraints, form.reactions)
    psi = [form.constraints[j].expression for j in _holonomic(form)]
    return contacts, {
        "matrices": matrices, "directions": directions,
        "scales": [force_scale(form.reactions[c.name]) for c in form.constraints], "psi": psi,
        "force_directions": [e for c in form.constraints for e in force_direction(form.reactions[c.name])],
        "psi_jacobian": [sympy.diff(e, q) for e in psi for q in model.coordinates],
        "velocity_jacobian": list(lagrange.constraint_jacobian),
        "offsets": [c.offset for c in form.constraints], "energy": [jacobi_integral(model)],
        "positions": [r for p in problem.particles for r in p.position],
        "conserved": list(conserved.values()),
        "contact_values": [value for f in form.frictions for value in (f.static, f.coefficient)], "sliding": sliding,
        # per contact that slides in a plane (kinetic friction only, -mu N v/|v|): its sliding speed |v|
        "speeds": [sympy.sqrt(sum((v**2 for v in f.sliding_velocity), sympy.Integer(0)))
                   for f in form.frictions if f.rate is None],
    }


def _value_issues(problem: Problem, prepared: dict[str, list[Any]], values: dict[str, float]) -> list[Issue]:
    """A parameter the equations use without a value, and a value that is not finite."""
    issues = []
    needed = set().union(*(getattr(e, "free_symbols", set()) for group in ("matrices", "psi", "offsets", "directions")
                           for e in prepared[group]))
    missing = sorted(p.name for p in problem.parameters if p.symbol in needed and p.name not in values)
    lines = problem.lines
    if missing:
        # the values' line, else the simulation's, else (a file without one) where the first missing one is declared
        line = lines.get("simulation.values", lines.get("simulation", lines.get(f"parameters.{missing[0]}", 0)))
        issues.append(Issue(problem.source, line, "simulation.values",
                            "no value for parameter" + ("s " if len(missing) > 1 else " ") + ", ".join(missing),
                            "give it under simulation.values or with --set NAME=VALUE"))
    for name, value in values.items():
        if not np.isfinite(value):
            line = lines.get(f"simulation.values.{name}", lines.get(f"parameters.{name}", 0))
            issues.append(Issue(problem.source, line, f"parameter {name}", f"value {value} is not a finite number"))
    return issues


def _arguments(form: MatrixForm) -> dict[str, Any]:
    """The arguments of every compiled function: time, coordinates, velocities, parameters."""
    model = form.model
    return {"time": model.time, "coordinates": model.coordinates, "velocities": model.velocities,
            "parameters": [p.symbol for p in form.problem.parameters]}


def _compiled(form: MatrixForm, prepared: dict[str, list[Any]], values: dict[str, float], contacts: list[Any],
              conserved: Mapping[str, Any], chart: NumericChart | None, energy_note: str) -> NumericSystem:
    """The :class:`NumericSystem` of the prepared expressions (an expression with a symbol that is not an
    argument compiles to NaN; a conserved quantity with one is left out)."""
    problem, model = form.problem, form.model
    arguments = _arguments(form)
    parameter_symbols = arguments["parameters"]
    allowed = {model.time, *model.coordinates, *model.velocities, *parameter_symbols}

    def usable_group(group: str) -> list[Any]:
        return [e if isinstance(e, sympy.Basic) and e.free_symbols <= allowed else sympy.nan for e in prepared[group]]

    def compile_group(group: str) -> StateFunction:
        return compile_state_function(usable_group(group), **arguments)

    conserved_names = list(conserved)
    usable = [i for i, e in enumerate(prepared["conserved"]) if e.free_symbols <= allowed]
    # mechanics decides (mechanics.analysis.monitored, or the derivation's analysis); this only evaluates
    return NumericSystem(
        coordinates=tuple(c.name for c in problem.coordinates),
        constraints=tuple(c.name for c in form.constraints),
        holonomic=_holonomic(form),
        unilateral=tuple(j for j, c in enumerate(problem.constraints) if c.unilateral),
        parameter_names=tuple(p.name for p in problem.parameters),
        parameters=np.array([values.get(p.name, np.nan) for p in problem.parameters], dtype=float),
        matrices=compile_group("matrices"),
        contacts=tuple(contacts),
        contact_names=tuple(f.name for f in form.frictions),
        sticks=tuple(f.rate is not None for f in form.frictions),
        contact_values=compile_group("contact_values"),
        sliding=compile_group("sliding"),
        directions=compile_group("directions"),
        scales=compile_group("scales"),
        position_residual=compile_group("psi"),
        position_jacobian=compile_group("psi_jacobian"),
        velocity_jacobian=compile_group("velocity_jacobian"),
        velocity_offset=compile_group("offsets"),
        speeds=compile_group("speeds"),
        energy=compile_group("energy"),
        positions=compile_group("positions"),
        particles=tuple((p.name, len(p.position)) for p in problem.particles),
        conserved_names=tuple(conserved_names[i] for i in usable),
        conserved=compile_state_function([prepared["conserved"][i] for i in usable], **arguments),
        energy_conserved="energy" in conserved,
        force_dims=tuple(len(force_direction(form.reactions[c.name])) for c in form.constraints),
        energy_note=energy_note or "the analysis finds no conserved energy",
        chart=chart,
        expressions={**{group: tuple(usable_group(group)) for group in prepared if group != "conserved"},
                     "conserved": tuple(prepared["conserved"][i] for i in usable)},
        arguments=(model.time, tuple(model.coordinates), tuple(model.velocities), tuple(parameter_symbols)),
    )


