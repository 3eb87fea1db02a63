"""The integrator's view of the equations (:mod:`lagsolve.numeric.integrate`): which constraints hold, which friction
contacts stick and which way each slides, in which coordinates the integrator's state is, and what follows from that
at a state: the accelerations, the constraint residual, the projection onto the constraints, a stuck contact's
holding margin, whether a contact sliding in a plane that comes to rest only turns."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lagsolve.errors import SimulationError
from lagsolve.numeric.minimal_state import NumericChart
from lagsolve.numeric.system import NumericSystem


@dataclass
class ActiveSystem:
    """The integrator's view of the equations: which constraints hold and which contacts stick."""

    system: NumericSystem
    active: np.ndarray
    stuck: np.ndarray
    direction: np.ndarray
    project: bool
    chart: NumericChart | None = None  # set while the integrator's state is in minimal coordinates
    extended: np.ndarray = field(default_factory=lambda: np.zeros(0))  # parameters, then the chart's constants
    #: per holonomic constraint, the residual below which a state is not projected: PROJECTED, scaled down for a
    #: constraint whose scale (NumericSystem.surface_scales, at the start) is below 1 (a problem in micrometres)
    floor: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: per released unilateral holonomic constraint j: how far below zero its ψ must go to count as reached again
    returning: dict[int, float] = field(default_factory=dict)
    #: per contact that slides in a plane: the speed (a fraction REST of the one at the start) that counts as at rest
    resting: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: per contact that slides in a plane: its velocity turned (:meth:`turns`) and its speed has not yet risen
    #: past twice ``resting``: it is not watched for rest until then (it would be found at once again)
    turning: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))

    def solve(self, t: float, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        n = self.system.n
        try:
            return self.system.solve_all(t, y[:n], y[n:], self.active, self.stuck, self.direction)
        except np.linalg.LinAlgError:
            raise SimulationError(f"the augmented system is singular at t = {t:.6g}") from None

    def full(self, t: float, y: np.ndarray) -> np.ndarray:
        """The whole state (q, q̇) from the integrator's state."""
        return y if self.chart is None else self.chart.full(t, y, self.system.n, self.extended)

    def local(self, y: np.ndarray) -> np.ndarray:
        """The integrator's state from a whole one."""
        return y if self.chart is None else self.chart.local(y, self.system.n)

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        if self.chart is None:
            return np.concatenate([y[self.system.n:], self.solve(t, y)[0]])
        return np.concatenate([y[self.chart.size:], self.solve(t, self.full(t, y))[0][self.chart.independent]])

    def _velocity_rows(self, t: float, q: np.ndarray, qd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        system, p, n = self.system, self.system.parameters, self.system.n
        a = system.velocity_jacobian(t, q, qd, p).reshape(system.m, n)[self.active] if system.m else np.zeros((0, n))
        b = system.velocity_offset(t, q, qd, p)[self.active] if system.m else np.zeros(0)
        held = []  # the sliding parts are evaluated only when a contact is stuck: nothing else uses them here
        if self.stuck.any():
            held = [w for c, (w, _, _) in system.sliding_parts(t, q, qd).items() if self.stuck[c]]
        if held:
            a, b = np.vstack([a, *held]), np.concatenate([b, np.zeros(len(held))])
        return a, b

    def residual(self, t: float, q: np.ndarray, qd: np.ndarray) -> float:
        system, p = self.system, self.system.parameters
        worst = 0.0
        rows = [i for i, j in enumerate(system.holonomic) if self.active[j]]
        if rows:
            worst = float(np.max(np.abs(system.position_residual(t, q, qd, p)[rows])))
        a, b = self._velocity_rows(t, q, qd)
        if a.shape[0]:
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
                if np.all(np.abs(psi) < self.floor[rows]):
                    break
                jac = system.position_jacobian(t, q, qd, p).reshape(len(system.holonomic), n)[rows]
                q -= jac.T @ np.linalg.solve(jac @ jac.T, psi)
        a, b = self._velocity_rows(t, q, qd)
        if a.shape[0]:
            qd -= a.T @ np.linalg.solve(a @ a.T, a @ qd + b)
        return q, qd

    def holding_margin(self, t: float, y: np.ndarray, c: int) -> tuple[float, float]:
        """For a stuck contact: (μ_s N − |Φ|, Φ), Φ the tangential force needed to hold it."""
        _, _, normal, sticking = self.solve(t, y)
        mu_s = self.system.contact_values(t, y[: self.system.n], y[self.system.n:], self.system.parameters)[2 * c]
        return float(mu_s * normal[c] - abs(sticking[c])), float(sticking[c])

    def rate(self, t: float, y: np.ndarray, c: int) -> float:
        """The sliding rate σ of contact ``c``."""
        return self.system.sliding_rate(t, y[: self.system.n], y[self.system.n:], c)

    def turns(self, t: float, y: np.ndarray, index: int) -> bool:
        """Whether the contact that slides in a plane (``index`` among those) and whose speed falls to zero at
        ``(t, y)`` only turns there: the tangential force of everything but friction exceeds μ_s N, as a spring that
        pulls a puck back along the line it came on does; then it slides on (the other way) and the run goes on.

        The accelerations at the state and at its reversed velocity are the applied part plus and minus the
        friction's (the velocity is about 0, so the terms in q̇ are negligible), and the sliding velocity is linear
        in q̇: the two parts' sliding rates are those of the applied force and of μ N along the contact. Exact for a
        particle; a file whose velocity constraints have an offset (a motor's ψ = φ − Ω t) cannot reverse its
        velocity: it stops, as at rest."""
        system, n, p = self.system, self.system.n, self.system.parameters
        q, qd = y[:n], y[n:]
        if system.m and np.any(system.velocity_offset(t, q, qd, p)[self.active] != 0):
            return False
        ahead = self.solve(t, y)[0]
        back = self.solve(t, np.concatenate([q, -qd]))[0]
        applied = float(system.speeds(t, q, (ahead + back) / 2, p)[index])
        friction = float(system.speeds(t, q, (ahead - back) / 2, p)[index])
        contact = system.planar[index]
        mu_s, mu = system.contact_values(t, q, qd, p)[2 * contact: 2 * contact + 2]
        return bool(mu > 0 and applied * mu > (1 + 1e-9) * mu_s * friction)
