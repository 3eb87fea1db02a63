r"""Explicit embedded Runge–Kutta over a batch of runs, each with its own step size and error control.

The methods are SciPy's (``RK45``: Dormand–Prince 5(4); ``DOP853``: Dormand–Prince 8(5,3);
``RK23``: Bogacki–Shampine), with their Butcher tableaux read from the public classes of
:mod:`scipy.integrate`, and the step control is the one :func:`scipy.integrate.solve_ivp` uses,
applied to every run separately: the initial step of Hairer, Nørsett and Wanner (II.4), the
error norm

.. math:: \|e\| = \sqrt{\tfrac1d \sum_i \bigl(e_i / (a + r \max(|y_i|, |y_i^{new}|))\bigr)^2},

acceptance when it is below 1, and the factor :math:`0.9\,\|e\|^{-1/(p+1)}` clipped to [0.2, 10]
(at most 1 right after a rejection). So a run takes the steps a single ``solve_ivp`` run would
take; only the right-hand side is evaluated for all the unfinished runs together.

Each accepted step's dense output (the method's own interpolant) is available to a callback, which
locates events (Poincaré sections) inside the step.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import integrate

from lagsolve.problem.methods import EXPLICIT

SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
METHODS = EXPLICIT  # the batched methods: the explicit ones of the registry

Rhs = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]  # (t (N,), y (N, d), rows (N,)) -> (N, d)


@dataclass(frozen=True)
class Tableau:
    """A method's coefficients (from SciPy's solver class of that name)."""

    name: str
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    e: np.ndarray  # error weights (E5 for DOP853)
    e3: np.ndarray | None  # DOP853's third-order error weights
    order: int  # of the error estimator: the exponent of the step factor is -1/(order+1)
    stages: int

    @classmethod
    def of(cls, name: str) -> Tableau:
        if name not in METHODS:
            raise ValueError(f"unknown batched method {name!r} (one of {', '.join(METHODS)})")
        solver = getattr(integrate, name)
        s = solver.n_stages
        if name == "DOP853":
            return cls(name, np.asarray(solver.A)[:s, :s], np.asarray(solver.B), np.asarray(solver.C)[:s],
                       np.asarray(solver.E5), np.asarray(solver.E3), solver.error_estimator_order, s)
        return cls(name, np.asarray(solver.A), np.asarray(solver.B), np.asarray(solver.C), np.asarray(solver.E),
                   None, solver.error_estimator_order, s)


def _combine(k: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Σ_s w_s K_s over the stage axis, term by term (the same operations for every row)."""
    out = np.zeros(k.shape[::2])
    for s, w in enumerate(weights):
        if w != 0.0:
            out += w * k[:, s]
    return out


def _norm(x: np.ndarray) -> np.ndarray:
    """SciPy's RMS norm of each row."""
    return np.sqrt(np.sum(x * x, axis=1) / x.shape[1])


@dataclass
class Step:
    """The accepted steps of one iteration: their rows, the interval, the states and the stages
    (for the dense output)."""

    rows: np.ndarray
    t_old: np.ndarray
    t_new: np.ndarray
    y_old: np.ndarray
    y_new: np.ndarray
    f_old: np.ndarray
    f_new: np.ndarray
    k: np.ndarray
    tableau: Tableau
    rhs: Rhs
    failures: dict[int, str] = field(default_factory=dict)  # batch row -> why it stops here (set by a callback)

    def fail(self, subset: np.ndarray, reason: str) -> None:
        """Stop the runs of the steps ``subset`` (indices into ``rows``) at this step, for ``reason``: a
        callback found a value it monitors that is not finite, although the state is."""
        for i in subset:
            self.failures.setdefault(int(self.rows[i]), reason)

    def dense(self, subset: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """The dense output of the steps ``subset`` (indices into ``rows``): a function of times,
        one per step, giving the states (shape (len(subset), d))."""
        tab = self.tableau
        t_old, h = self.t_old[subset], (self.t_new - self.t_old)[subset]
        y_old, k = self.y_old[subset], self.k[subset]
        if tab.name == "DOP853":
            solver = integrate.DOP853
            ext = np.concatenate([k, np.zeros((len(subset), 3, k.shape[2]))], axis=1)
            a_extra, c_extra = np.asarray(solver.A_EXTRA), np.asarray(solver.C_EXTRA)
            rows = self.rows[subset]
            for i, (a, c) in enumerate(zip(a_extra, c_extra, strict=True)):
                s = tab.stages + 1 + i
                dy = _combine(ext[:, :s], a[:s]) * h[:, None]
                ext[:, s] = self.rhs(t_old + c * h, y_old + dy, rows)
            delta = self.y_new[subset] - y_old
            f_old, f_new = self.f_old[subset], self.f_new[subset]
            coefficients = [delta, h[:, None] * f_old - delta, 2 * delta - h[:, None] * (f_new + f_old)]
            coefficients += [h[:, None] * _combine(ext, d) for d in np.asarray(solver.D)]

            def dop853(t: np.ndarray) -> np.ndarray:
                x = ((t - t_old) / h)[:, None]
                y = np.zeros_like(y_old)
                for i, f in enumerate(reversed(coefficients)):
                    y += f
                    y *= x if i % 2 == 0 else 1 - x
                return y + y_old

            return dop853
        solver = getattr(integrate, tab.name)
        powers = np.asarray(solver.P)  # (stages + 1, order of the interpolant)
        q = np.stack([_combine(k, powers[:, j]) for j in range(powers.shape[1])], axis=2)

        def polynomial(t: np.ndarray) -> np.ndarray:
            x = (t - t_old) / h
            p = np.cumprod(np.repeat(x[:, None], powers.shape[1], axis=1), axis=1)
            return y_old + h[:, None] * np.einsum("rdj,rj->rd", q, p)

        return polynomial


@dataclass
class _Runs:
    """Every run of a batch between iterations: its time, state, derivative, next step size and step count,
    whether it still runs (or why it stopped), and where its step control stands."""

    t: np.ndarray
    y: np.ndarray
    f: np.ndarray
    h_abs: np.ndarray
    steps: np.ndarray
    failure: list[str]
    live: np.ndarray
    fresh: np.ndarray  # at the start of a step (not retrying after a rejection)
    rejected: np.ndarray

    def stop(self, row: int, reason: str) -> None:
        """End the run ``row`` for ``reason``."""
        self.failure[row] = reason
        self.live[row] = False


def integrate_batch(rhs: Rhs, y0: np.ndarray, t_end: float, tableau: Tableau, rtol: float, atol: float,
                    accepted: Callable[[Step], np.ndarray | None] | None = None,
                    max_steps: int = 1_000_000) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[str]]:
    """Integrate every row of ``y0`` (shape (N, d)) from t = 0 to ``t_end``.

    ``rhs(t, y, rows)`` evaluates the rows ``rows`` (indices into the batch). ``accepted(step)``
    is called after each iteration's accepted steps; it may return replacement states for them
    (a projection onto the constraints), after which their derivative is evaluated again.

    Returns the final times, states, step counts and, per run, "" or the reason it failed
    (a step below the smallest step SciPy allows, a state that is not finite, too many steps, or
    what ``accepted`` found wrong with a step through :meth:`Step.fail`).
    """
    runs = _start(rhs, y0, t_end, tableau, rtol, atol)
    exponent = -1.0 / (tableau.order + 1)
    while runs.live.any():
        rows, h = _step_sizes(runs)
        if not len(rows):
            continue
        tr, yr, fr = runs.t[rows], runs.y[rows], runs.f[rows]
        t_new = np.minimum(tr + h, t_end)
        h = t_new - tr
        y_new, f_new, k = _stages(rhs, tableau, tr, yr, fr, t_new, h, rows)
        error = _error(tableau, k, h, yr, y_new, rtol, atol)
        ok = _control(runs, rows, h, error, exponent)
        if ok.any():
            take = np.flatnonzero(ok)
            step = Step(rows[take], tr[take], t_new[take], yr[take], y_new[take], fr[take], f_new[take], k[take],
                        tableau, rhs)
            _advance(runs, step, accepted, t_end, max_steps)
    return runs.t, runs.y, runs.steps, runs.failure


def _start(rhs: Rhs, y0: np.ndarray, t_end: float, tableau: Tableau, rtol: float, atol: float) -> _Runs:
    """Every run at t = 0 with its derivative and initial step size; a run whose initial state or derivative
    is not finite fails there."""
    runs = len(y0)
    t = np.zeros(runs)
    y = y0.astype(float).copy()
    everyone = np.arange(runs)
    f = rhs(t, y, everyone)
    h_abs = _initial_step(rhs, t, y, f, t_end, tableau.order, rtol, atol, everyone)
    bad = ~np.all(np.isfinite(f), axis=1) | ~np.all(np.isfinite(y), axis=1)
    failure = [""] * runs
    for r in np.flatnonzero(bad):
        failure[r] = "the initial state or its accelerations are not finite"
    return _Runs(t, y, f, h_abs, np.zeros(runs, dtype=int), failure, live=~bad, fresh=np.ones(runs, dtype=bool),
                 rejected=np.zeros(runs, dtype=bool))


def _step_sizes(runs: _Runs) -> tuple[np.ndarray, np.ndarray]:
    """The runs still running and the step each tries now; a run whose step fell below the smallest one SciPy
    allows (10 units in the last place of its time) fails and is left out."""
    rows = np.flatnonzero(runs.live)
    tr = runs.t[rows]
    min_step = 10 * np.abs(np.nextafter(tr, np.inf) - tr)
    h = runs.h_abs[rows]
    h = np.where(runs.fresh[rows], np.maximum(h, min_step), h)
    small = h < min_step
    for r in rows[small]:
        runs.stop(r, f"the step size fell below the smallest allowed at t = {runs.t[r]:.6g}")
    if small.any():
        keep = ~small
        rows, h = rows[keep], h[keep]
    return rows, h


def _stages(rhs: Rhs, tableau: Tableau, tr: np.ndarray, yr: np.ndarray, fr: np.ndarray, t_new: np.ndarray,
            h: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One step of the method from (``tr``, ``yr``) to ``t_new`` for every row: the new state, its derivative
    and the stages (the last one that derivative, for the error estimate and the dense output)."""
    k = np.empty((len(rows), tableau.stages + 1, yr.shape[1]))
    k[:, 0] = fr
    for s in range(1, tableau.stages):
        dy = _combine(k[:, :s], tableau.a[s, :s]) * h[:, None]
        k[:, s] = rhs(tr + tableau.c[s] * h, yr + dy, rows)
    y_new = yr + h[:, None] * _combine(k[:, :-1], tableau.b)
    f_new = rhs(t_new, y_new, rows)
    k[:, -1] = f_new
    return y_new, f_new, k


def _error(tableau: Tableau, k: np.ndarray, h: np.ndarray, yr: np.ndarray, y_new: np.ndarray, rtol: float,
           atol: float) -> np.ndarray:
    """SciPy's error norm of each row's step (DOP853's combines its fifth- and third-order estimates)."""
    scale = atol + np.maximum(np.abs(yr), np.abs(y_new)) * rtol
    with np.errstate(all="ignore"):
        if tableau.e3 is None:
            return _norm(_combine(k, tableau.e) * h[:, None] / scale)
        e5 = np.sum((_combine(k, tableau.e) / scale) ** 2, axis=1)
        e3 = np.sum((_combine(k, tableau.e3) / scale) ** 2, axis=1)
        return np.where((e5 == 0) & (e3 == 0), 0.0, h * e5 / np.sqrt((e5 + 0.01 * e3) * yr.shape[1]))


def _control(runs: _Runs, rows: np.ndarray, h: np.ndarray, error: np.ndarray, exponent: float) -> np.ndarray:
    """Which steps are accepted (error norm below 1), and each row's next step size: grown by at most
    MAX_FACTOR (not at all right after a rejection) or shrunk by at most MIN_FACTOR."""
    with np.errstate(all="ignore"):
        growth = SAFETY * error ** exponent
    finite = np.isfinite(error)
    ok = finite & (error < 1)
    factor = np.where(error == 0, MAX_FACTOR, np.minimum(MAX_FACTOR, growth))
    factor = np.where(runs.rejected[rows], np.minimum(1.0, factor), factor)
    runs.h_abs[rows] = np.where(ok, h * factor, h * np.maximum(MIN_FACTOR, np.where(finite, growth, MIN_FACTOR)))
    runs.rejected[rows] = ~ok
    runs.fresh[rows] = ok
    return ok


def _advance(runs: _Runs, step: Step, accepted: Callable[[Step], np.ndarray | None] | None, t_end: float,
             max_steps: int) -> None:
    """Move the runs of the accepted ``step`` to its end (or to the states ``accepted`` returns instead), and
    stop those that reached ``t_end``, are no longer finite, failed in ``accepted`` or took too many steps."""
    done = step.rows
    replaced = accepted(step) if accepted is not None else None
    y_done, f_done = step.y_new, step.f_new
    if replaced is not None:
        y_done = replaced
        f_done = step.rhs(step.t_new, y_done, done)
    runs.t[done], runs.y[done], runs.f[done] = step.t_new, y_done, f_done
    runs.steps[done] += 1
    broken = ~np.all(np.isfinite(y_done), axis=1) | ~np.all(np.isfinite(f_done), axis=1)
    for r in done[broken]:
        runs.stop(r, f"the state is no longer finite at t = {runs.t[r]:.6g} (the motion diverged or left the "
                     "domain of an expression)")
    for stopped, reason in step.failures.items():
        if runs.live[stopped]:
            runs.stop(stopped, reason)
    finished = runs.t[done] >= t_end
    runs.live[done[finished]] = False
    for r in done[runs.steps[done] >= max_steps]:
        if runs.live[r]:
            runs.stop(r, f"more than {max_steps} steps before t_end")


def _initial_step(rhs: Rhs, t0: np.ndarray, y0: np.ndarray, f0: np.ndarray, t_end: float, order: int,
                  rtol: float, atol: float, rows: np.ndarray) -> np.ndarray:
    """SciPy's ``select_initial_step`` for every row."""
    scale = atol + np.abs(y0) * rtol
    with np.errstate(all="ignore"):
        d0, d1 = _norm(y0 / scale), _norm(f0 / scale)
        h0 = np.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / d1)
        h0 = np.minimum(h0, t_end)
        f1 = rhs(t0 + h0, y0 + h0[:, None] * f0, rows)
        d2 = _norm((f1 - f0) / scale) / h0
        h1 = np.where((d1 <= 1e-15) & (d2 <= 1e-15), np.maximum(1e-6, h0 * 1e-3),
                      (0.01 / np.maximum(d1, d2)) ** (1.0 / (order + 1)))
    return np.minimum(np.minimum(100 * h0, h1), t_end)
