"""A derivation bound to numbers: the callables the integrator needs.

The equations come from the derivation's *matrix form* (``M q̈ = F + Aᵀλ``,
``A q̈ = β``), not from the display-simplified results; the augmented linear
system is solved numerically at each evaluation. Parameters are passed as an
array, so ``--set g=1.62`` needs no recompilation.

State order: ``q`` and ``qd`` follow the problem's coordinates; multipliers
follow its constraints.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy

from lagsolve.errors import Issue, SimulationError, SpecError
from lagsolve.mechanics.derivation import Derivation
from lagsolve.numeric.compile import StateFunction, compile_state_function, substitute_functions


@dataclass(frozen=True)
class NumericSystem:
    """Numeric callables of one problem, each ``f(t, q, qd, p) -> ndarray``.

    ``parameters`` holds the parameter values in the order of ``parameter_names``;
    ``holonomic`` indexes the constraints given at position level (projected onto).
    """

    coordinates: tuple[str, ...]
    constraints: tuple[str, ...]
    holonomic: tuple[int, ...]
    unilateral: tuple[int, ...]
    parameter_names: tuple[str, ...]
    parameters: np.ndarray
    matrices: StateFunction
    position_residual: StateFunction
    position_jacobian: StateFunction
    velocity_jacobian: StateFunction
    velocity_offset: StateFunction
    energy: StateFunction
    magnitudes: StateFunction
    positions: StateFunction
    particles: tuple[tuple[str, int], ...]
    conserved_names: tuple[str, ...]
    conserved: StateFunction
    curve_coordinate: int | None
    curve: StateFunction | None
    energy_conserved: bool
    energy_note: str
    evaluations: list[int] = field(default_factory=lambda: [0])

    @property
    def n(self) -> int:
        return len(self.coordinates)

    @property
    def m(self) -> int:
        return len(self.constraints)

    def solve(self, t: float, q: np.ndarray, qd: np.ndarray,
              active: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Accelerations and multipliers at a state (inactive constraints get λ = 0).

        Solves :math:`\\begin{pmatrix}M & -A^T\\\\ A & 0\\end{pmatrix}
        \\begin{pmatrix}\\ddot q\\\\ \\lambda\\end{pmatrix} = \\begin{pmatrix}F\\\\ \\beta\\end{pmatrix}`
        with the rows of inactive constraints removed.
        """
        self.evaluations[0] += 1
        n, m = self.n, self.m
        flat = self.matrices(t, q, qd, self.parameters)
        M = flat[: n * n].reshape(n, n)
        F = flat[n * n: n * n + n]
        A = flat[n * n + n: n * n + n + m * n].reshape(m, n)
        beta = flat[n * n + n + m * n:]
        lam = np.zeros(m)
        if active is not None and not active.all():
            A, beta = A[active], beta[active]
        k = A.shape[0]
        if k == 0:
            return np.linalg.solve(M, F), lam
        system = np.zeros((n + k, n + k))
        system[:n, :n] = M
        system[:n, n:] = -A.T
        system[n:, :n] = A
        solution = np.linalg.solve(system, np.concatenate([F, beta]))
        if active is not None and not active.all():
            lam[active] = solution[n:]
        else:
            lam = solution[n:]
        return solution[:n], lam


def _values(derivation: Derivation, overrides: Mapping[str, float]) -> dict[str, float]:
    problem = derivation.problem
    values: dict[str, float] = {}
    for p in problem.parameters:
        if p.value is not None:
            values[p.name] = p.value
    if problem.simulation is not None:
        values.update(problem.simulation.values)
    values.update(overrides)
    return values


def bind(derivation: Derivation, overrides: Mapping[str, float] | None = None) -> NumericSystem:
    """Bind ``derivation`` to the parameter values of its file (and ``overrides``) and
    its concrete functions, and compile everything the integrator needs.

    Raises
    ------
    SpecError
        A parameter used by the equations has no value, a declared function has no
        concrete form, or an override names an unknown parameter.
    """
    problem = derivation.problem
    model = derivation.model
    source = problem.source
    overrides = dict(overrides or {})
    issues: list[Issue] = []
    known = {p.name for p in problem.parameters}
    for name in overrides:
        if name not in known:
            issues.append(Issue(source, 0, "--set", f"unknown parameter {name!r}",
                                "known: " + ", ".join(sorted(known)) if known else "the problem has no parameters"))
    values = _values(derivation, overrides)
    for name, value in values.items():
        if not np.isfinite(value):
            issues.append(Issue(source, 0, f"parameter {name}", f"value {value} is not a finite number"))

    concrete = {}
    simulation = problem.simulation
    for fn in problem.functions:
        given = simulation.functions.get(fn.name) if simulation is not None else None
        if given is None:
            issues.append(Issue(source, problem.lines.get("functions", 0), "simulation.functions",
                                f"function {fn.name!r} has no concrete form",
                                f'add e.g. "{fn.name}(u)": "u**2/2" under simulation.functions'))
        else:
            concrete[fn.function] = (given.arguments, given.expression)

    normals = {f.term.normal: f.normal_force for f in derivation.friction}
    lagrange = derivation.lagrange

    def prepare(expr: Any) -> Any:
        expr = sympy.Integer(expr) if isinstance(expr, int) else expr
        return substitute_functions(expr.xreplace(normals), concrete)

    matrices = [*lagrange.mass_matrix, *lagrange.forcing, *lagrange.constraint_jacobian, *lagrange.constraint_rhs]
    holonomic = tuple(j for j, c in enumerate(derivation.constraints) if c.kind == "holonomic")
    psi = [derivation.constraints[j].expression for j in holonomic]
    psi_jacobian = [sympy.diff(e, q) for e in psi for q in model.coordinates]
    velocity_jacobian = list(lagrange.constraint_jacobian)
    offsets = [c.offset for c in derivation.constraints]
    energy = sum((v * sympy.diff(model.lagrangian, v) for v in model.velocities), sympy.Integer(0)) - model.lagrangian
    magnitudes = [f.magnitude if f.magnitude is not None else sympy.nan for f in derivation.constraint_forces.values()]
    positions = [r for p in problem.particles for r in p.position]
    conserved_names, conserved = [], []
    for name, expr in (derivation.conserved or {}).items():
        conserved_names.append(name)
        conserved.append(expr)

    prepared = {key: [prepare(e) for e in group] for key, group in {
        "matrices": matrices, "psi": psi, "psi_jacobian": psi_jacobian, "velocity_jacobian": velocity_jacobian,
        "offsets": offsets, "energy": [energy], "magnitudes": magnitudes, "positions": positions,
        "conserved": conserved}.items()}
    needed = set().union(*(e.free_symbols for group in ("matrices", "psi", "offsets")
                           for e in prepared[group] if hasattr(e, "free_symbols")))
    missing = sorted(p.name for p in problem.parameters if p.symbol in needed and p.name not in values)
    if missing:
        issues.append(Issue(source, problem.lines.get("simulation", 0), "simulation.values",
                            "no value for parameter" + ("s " if len(missing) > 1 else " ") + ", ".join(missing),
                            "give it under simulation.values or with --set NAME=VALUE"))
    if issues:
        raise SpecError(issues)

    # symbols the optional diagnostics need but that have no value (integration constants, say)
    parameter_symbols = [p.symbol for p in problem.parameters]
    parameter_values = np.array([values.get(p.name, np.nan) for p in problem.parameters], dtype=float)
    arguments = {"time": model.time, "coordinates": model.coordinates, "velocities": model.velocities,
                 "parameters": parameter_symbols}
    allowed = {model.time, *model.coordinates, *model.velocities, *parameter_symbols}

    def compile_group(group: str) -> StateFunction:
        exprs = [e if isinstance(e, sympy.Basic) and e.free_symbols <= allowed else sympy.nan
                 for e in prepared[group]]
        return compile_state_function(exprs, **arguments)

    usable_conserved = [i for i, e in enumerate(prepared["conserved"]) if e.free_symbols <= allowed]
    curve_coordinate, curve = _constraint_curve(derivation, prepare, arguments)
    energy_conserved, note = _energy_conserved(derivation)
    names = [c.name for c in derivation.constraints]
    try:
        return NumericSystem(
            coordinates=tuple(c.name for c in problem.coordinates),
            constraints=tuple(names),
            holonomic=holonomic,
            unilateral=tuple(j for j, c in enumerate(problem.constraints) if c.unilateral),
            parameter_names=tuple(p.name for p in problem.parameters),
            parameters=parameter_values,
            matrices=compile_group("matrices"),
            position_residual=compile_group("psi"),
            position_jacobian=compile_group("psi_jacobian"),
            velocity_jacobian=compile_group("velocity_jacobian"),
            velocity_offset=compile_group("offsets"),
            energy=compile_group("energy"),
            magnitudes=compile_group("magnitudes"),
            positions=compile_group("positions"),
            particles=tuple((p.name, len(p.position)) for p in problem.particles),
            conserved_names=tuple(conserved_names[i] for i in usable_conserved),
            conserved=compile_state_function([prepared["conserved"][i] for i in usable_conserved], **arguments),
            curve_coordinate=curve_coordinate,
            curve=curve,
            energy_conserved=energy_conserved,
            energy_note=note,
        )
    except (ValueError, TypeError, NameError) as exc:  # pragma: no cover - lambdify of a derived expression
        raise SimulationError(f"could not compile the equations of {source}: {exc}") from None


def _constraint_curve(derivation: Derivation, prepare: Any,
                      arguments: dict[str, Any]) -> tuple[int | None, StateFunction | None]:
    """For one degree of freedom left by explicit position constraints (a bead on a wire), the first
    particle's position as a function of the independent coordinate: the curve the constraint draws."""
    problem, model = derivation.problem, derivation.model
    positions = derivation.elimination.positions
    if not problem.particles or not positions or any(c.kind != "holonomic" for c in derivation.constraints):
        return None, None
    free = [i for i, q in enumerate(model.coordinates) if q not in positions]
    if len(free) != 1:
        return None, None
    shape = [prepare(derivation.elimination.apply(r)) for r in problem.particles[0].position]
    if any(model.time in e.free_symbols for e in shape):
        return None, None
    return free[0], compile_state_function(shape, **arguments)


def _energy_conserved(derivation: Derivation) -> tuple[bool, str]:
    """Whether the Jacobi integral h = Σ q̇ ∂L/∂q̇ − L of the full system is conserved, and why (not)."""
    model = derivation.model
    if sympy.diff(model.lagrangian, model.time) != 0:
        return False, "L depends explicitly on time"
    if any(g != 0 for g in derivation.lagrange.generalized_forces):
        return False, "non-conservative forces (or dissipation, or friction) do work"
    for c in derivation.constraints:
        if c.offset != 0 or any(sympy.diff(a, model.time) != 0 for a in c.coefficients):
            return False, f"constraint {c.name!r} depends on time, so its force can do work"
    return True, "L has no explicit time, the constraints are workless and no other force does work"
