"""Integrate a :class:`~lagsolve.numeric.system.NumericSystem` into a :class:`Trajectory`.

The state is ``y = (q, q̇)``; accelerations and multipliers come from the
augmented system at each evaluation. SciPy's solvers are stepped one accepted
step at a time (the same solvers ``solve_ivp`` uses), which allows

* **projection** after each accepted step of an explicit Runge–Kutta method:
  positions onto ψ(q, t) = 0 (least-norm Newton), velocities onto A q̇ + b = 0,
  so holonomic constraints integrated at acceleration level do not drift;
* **events**: a unilateral constraint holds while its multiplier is ≥ 0 (its
  force pushes); the time it reaches zero is located on the step's dense output
  (Brent's method), and the run stops or continues with the constraint released.

Samples are taken from the dense output at evenly spaced times.
"""

from __future__ import annotations

import time as clock
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import integrate, optimize

from lagsolve.errors import SimulationError
from lagsolve.numeric.system import NumericSystem

EXPLICIT = ("DOP853", "RK45", "RK23")
METHODS = (*EXPLICIT, "Radau", "BDF", "LSODA")


@dataclass(frozen=True)
class Event:
    """A unilateral constraint's force reached zero at ``time``: contact was lost."""

    time: float
    constraint: str
    state: Mapping[str, float]
    action: str  # "stopped" | "released"


@dataclass(frozen=True)
class Trajectory:
    """A simulated motion. Arrays have one row per sample time.

    ``q``, ``qd`` shape (samples, n); ``multipliers`` and ``magnitudes`` shape
    (samples, m) in constraint order (λ = 0 and magnitude 0 after release);
    ``normal_forces`` shape (samples, contacts) for friction contacts;
    ``energy`` the Jacobi integral h = Σ q̇ ∂L/∂q̇ − L; ``residual`` the largest
    constraint violation of the integrated state before projection; ``positions``
    shape (samples, total particle components).
    """

    t: np.ndarray
    coordinates: tuple[str, ...]
    constraints: tuple[str, ...]
    q: np.ndarray
    qd: np.ndarray
    multipliers: np.ndarray
    magnitudes: np.ndarray
    contacts: tuple[str, ...]
    normal_forces: np.ndarray
    energy: np.ndarray
    conserved: Mapping[str, np.ndarray]
    residual: np.ndarray
    positions: np.ndarray
    particles: tuple[tuple[str, int], ...]
    events: tuple[Event, ...]
    stats: Mapping[str, Any] = field(default_factory=dict)


@dataclass
class _Run:
    system: NumericSystem
    active: np.ndarray
    project: bool
    residuals: list[float] = field(default_factory=list)

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        n = self.system.n
        try:
            qdd, _ = self.system.solve(t, y[:n], y[n:], self.active)
        except np.linalg.LinAlgError:
            raise SimulationError(f"the augmented system is singular at t = {t:.6g}") from None
        return np.concatenate([y[n:], qdd])

    def residual(self, t: float, q: np.ndarray, qd: np.ndarray) -> float:
        system, p = self.system, self.system.parameters
        worst = 0.0
        rows = [i for i, j in enumerate(system.holonomic) if self.active[j]]
        if rows:
            worst = float(np.max(np.abs(system.position_residual(t, q, qd, p)[rows])))
        if system.m and self.active.any():
            a = system.velocity_jacobian(t, q, qd, p).reshape(system.m, system.n)[self.active]
            b = system.velocity_offset(t, q, qd, p)[self.active]
            worst = max(worst, float(np.max(np.abs(a @ qd + b))))
        return worst

    def projected(self, t: float, q: np.ndarray, qd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The nearest state on the constraints (Euclidean, least-norm corrections)."""
        system, p = self.system, self.system.parameters
        n = system.n
        q, qd = q.copy(), qd.copy()
        rows = [i for i, j in enumerate(system.holonomic) if self.active[j]]
        if rows:
            for _ in range(4):
                psi = system.position_residual(t, q, qd, p)[rows]
                if np.max(np.abs(psi)) < 1e-15:
                    break
                jac = system.position_jacobian(t, q, qd, p).reshape(len(system.holonomic), n)[rows]
                q -= jac.T @ np.linalg.solve(jac @ jac.T, psi)
        if system.m and self.active.any():
            a = system.velocity_jacobian(t, q, qd, p).reshape(system.m, n)[self.active]
            b = system.velocity_offset(t, q, qd, p)[self.active]
            qd -= a.T @ np.linalg.solve(a @ a.T, a @ qd + b)
        return q, qd


def integrate_motion(system: NumericSystem, q0: np.ndarray, qd0: np.ndarray, t_end: float, *,
                     samples: int = 1001, method: str = "DOP853", rtol: float = 1e-10, atol: float = 1e-12,
                     max_step: float = np.inf, project: bool = True, after_release: str = "stop",
                     progress: Callable[[float], None] | None = None) -> Trajectory:
    """Integrate from ``(q0, qd0)`` at t = 0 to ``t_end``.

    Parameters
    ----------
    method : str
        One of DOP853 (default), RK45, RK23 (explicit; projected after every step),
        Radau, BDF, LSODA (implicit, for stiff problems; samples are projected).
    after_release : {"stop", "continue"}
        What to do when a unilateral constraint's force reaches zero.

    Raises
    ------
    SimulationError
        When the integrator fails or the system becomes singular.
    """
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}")
    if not (t_end > 0 and np.isfinite(t_end)):
        raise ValueError("t_end must be a positive number")
    n, m = system.n, system.m
    run = _Run(system, np.ones(m, dtype=bool), project)
    explicit = method in EXPLICIT
    times = np.linspace(0.0, t_end, samples)
    rows: list[tuple[float, np.ndarray, np.ndarray, float, np.ndarray]] = []
    events: list[Event] = []
    start = clock.perf_counter()
    steps = 0
    nfev = 0
    max_residual = run.residual(0.0, q0, qd0)
    t0, y0 = 0.0, np.concatenate([q0, qd0])
    next_sample = 0
    stop = stopped_by_event = False
    while not stop:
        solver = getattr(integrate, method)(run.rhs, t0, y0, t_end, rtol=rtol, atol=atol, max_step=max_step)
        lam_old = _multipliers(run, t0, y0)
        pulling = [j for j in system.unilateral if run.active[j] and lam_old[j] < 0]
        if pulling:
            # a unilateral constraint that would have to pull: contact is lost at once
            j = pulling[0]
            events.append(Event(float(t0), system.constraints[j], _state(system, y0), "released"))
            run.active[j] = False
            continue
        while solver.status == "running":
            message = solver.step()
            if solver.status == "failed":
                raise SimulationError(f"the integrator ({method}) failed at t = {solver.t:.6g}: {message}")
            steps += 1
            t_old, t_new = solver.t_old, solver.t
            dense = solver.dense_output()
            lam_new = _multipliers(run, t_new, solver.y)
            crossing = _release(run, dense, t_old, t_new, lam_old, lam_new)
            t_stop = crossing[0] if crossing is not None else t_new
            while next_sample < samples and times[next_sample] <= t_stop + 1e-12 * max(1.0, t_end):
                ts = times[next_sample]
                rows.append(_sample(run, ts, dense(ts)))
                next_sample += 1
            if crossing is not None:
                t_event, j = crossing
                y_event = dense(t_event)
                q_e, qd_e = run.projected(t_event, y_event[:n], y_event[n:])
                state = _state(system, np.concatenate([q_e, qd_e]))
                action = "stopped" if after_release == "stop" else "released"
                events.append(Event(float(t_event), system.constraints[j], state, action))
                if after_release == "stop":
                    rows.append(_sample(run, t_event, np.concatenate([q_e, qd_e])))
                    stop = stopped_by_event = True
                else:
                    run.active[j] = False
                    t0, y0 = t_event, np.concatenate([q_e, qd_e])
                break
            residual = run.residual(t_new, solver.y[:n], solver.y[n:])
            max_residual = max(max_residual, residual)
            if explicit and project and m and run.active.any():
                q, qd = run.projected(t_new, solver.y[:n], solver.y[n:])
                solver.y = np.concatenate([q, qd])
                solver.f = run.rhs(t_new, solver.y)
                lam_new = _multipliers(run, t_new, solver.y)
            lam_old = lam_new
            if progress is not None:
                progress(t_new)
        else:
            stop = True
        nfev += solver.nfev
    if next_sample < samples and not stopped_by_event:
        rows.append(_sample(run, t_end, solver.y))
    wall = clock.perf_counter() - start
    return _trajectory(system, rows, events, {
        "method": method, "rtol": rtol, "atol": atol, "steps": steps, "evaluations": system.evaluations[0],
        "solver_evaluations": nfev, "wall_time": wall, "max_residual": max_residual,
        "energy_conserved": system.energy_conserved, "energy_note": system.energy_note,
    })


def _state(system: NumericSystem, y: np.ndarray) -> dict[str, float]:
    n = system.n
    return {**{c: float(v) for c, v in zip(system.coordinates, y[:n], strict=True)},
            **{f"{c}_dot": float(v) for c, v in zip(system.coordinates, y[n:], strict=True)}}


def _multipliers(run: _Run, t: float, y: np.ndarray) -> np.ndarray:
    if not run.system.unilateral:
        return np.zeros(0)
    n = run.system.n
    return run.system.solve(t, y[:n], y[n:], run.active)[1]


def _release(run: _Run, dense: Any, t_old: float, t_new: float, lam_old: np.ndarray,
             lam_new: np.ndarray) -> tuple[float, int] | None:
    """The first unilateral constraint whose multiplier crosses from ≥ 0 to < 0 in the step."""
    first: tuple[float, int] | None = None
    for j in run.system.unilateral:
        if not run.active[j] or not (lam_old[j] >= 0 > lam_new[j]):
            continue

        def g(tau: float, j: int = j) -> float:
            y = dense(tau)
            return float(_multipliers(run, tau, y)[j])

        t_event = optimize.brentq(g, t_old, t_new, xtol=1e-14, rtol=4 * np.finfo(float).eps)
        if first is None or t_event < first[0]:
            first = (t_event, j)
    return first


def _sample(run: _Run, t: float, y: np.ndarray) -> tuple[float, np.ndarray, np.ndarray, float, np.ndarray]:
    n = run.system.n
    residual = run.residual(t, y[:n], y[n:])
    q, qd = run.projected(t, y[:n], y[n:]) if run.project else (y[:n].copy(), y[n:].copy())
    return (float(t), q, qd, residual, run.active.copy())


def _trajectory(system: NumericSystem, rows: list, events: list[Event], stats: dict) -> Trajectory:
    p = system.parameters
    t = np.array([r[0] for r in rows])
    q = np.array([r[1] for r in rows]).reshape(len(rows), system.n)
    qd = np.array([r[2] for r in rows]).reshape(len(rows), system.n)
    residual = np.array([r[3] for r in rows])
    lam = np.zeros((len(rows), system.m))
    mags = np.zeros((len(rows), system.m))
    normals = np.zeros((len(rows), len(system.contacts)))
    energy = np.zeros(len(rows))
    conserved = np.zeros((len(rows), len(system.conserved_names)))
    positions = np.zeros((len(rows), sum(d for _, d in system.particles)))
    for i, (ti, qi, qdi, _, active) in enumerate(rows):
        if system.m:
            _, lam[i], normals[i] = system.solve_all(ti, qi, qdi, active)
            mags[i] = np.where(active, system.magnitudes(ti, qi, qdi, lam[i]), 0.0)
        energy[i] = system.energy(ti, qi, qdi, p)[0]
        if system.conserved_names:
            conserved[i] = system.conserved(ti, qi, qdi, p)
        if positions.shape[1]:
            positions[i] = system.positions(ti, qi, qdi, p)
    drift = _relative_drift(energy)
    stats = {**stats, "energy_drift": drift,
             "conserved_drift": {name: _relative_drift(conserved[:, k])
                                 for k, name in enumerate(system.conserved_names)}}
    return Trajectory(t, system.coordinates, system.constraints, q, qd, lam, mags, system.contact_names, normals,
                      energy,
                      {name: conserved[:, k] for k, name in enumerate(system.conserved_names)},
                      residual, positions, system.particles, tuple(events), stats)


def _relative_drift(values: np.ndarray) -> float:
    """max |v − v₀| / |v₀| (absolute when v₀ is zero)."""
    if values.size == 0 or not np.all(np.isfinite(values)):
        return float("nan")
    scale = abs(values[0]) if abs(values[0]) > 1e-300 else 1.0
    return float(np.max(np.abs(values - values[0])) / scale)
