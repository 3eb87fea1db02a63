"""The batched Runge–Kutta takes, for every run, the steps SciPy's solver takes for that run alone."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from lagsolve.sweep.rk import Step, Tableau, integrate_batch


def _pendulum(t: np.ndarray, y: np.ndarray, rows: np.ndarray) -> np.ndarray:
    return np.column_stack([y[:, 1], -np.sin(y[:, 0]) - 0.1 * y[:, 1] + 0.2 * np.cos(t)])


@pytest.mark.parametrize("method", ["RK45", "DOP853", "RK23"])
def test_each_run_takes_scipys_steps(method: str) -> None:
    """Final states and step counts of a batch equal solve_ivp run by run (same method and tolerances)."""
    starts = np.array([[0.1, 0.0], [1.0, 0.5], [3.0, 0.0], [-2.0, 1.5]])
    t, y, steps, failed = integrate_batch(_pendulum, starts, 7.0, Tableau.of(method), 1e-8, 1e-10)
    assert failed == [""] * 4 and np.all(t == 7.0)
    for r, start in enumerate(starts):
        single = integrate.solve_ivp(lambda tt, yy: _pendulum(np.array([tt]), yy[None, :], np.array([0]))[0],
                                     (0, 7.0), start, method=method, rtol=1e-8, atol=1e-10)
        assert steps[r] == len(single.t) - 1
        assert np.max(np.abs(y[r] - single.y[:, -1])) < 1e-12


@pytest.mark.parametrize("method", ["RK45", "DOP853", "RK23"])
def test_dense_output_is_scipys(method: str) -> None:
    """Each accepted step's dense output equals SciPy's interpolant of the same step."""
    solver = getattr(integrate, method)(lambda tt, yy: _pendulum(np.array([tt]), yy[None, :], np.array([0]))[0],
                                        0.0, np.array([1.0, 0.5]), 3.0, rtol=1e-6, atol=1e-9)
    checked = []

    def accepted(step: Step) -> None:
        if checked:
            return
        solver.step()
        assert solver.t == pytest.approx(step.t_new[0], abs=1e-15)
        times = np.linspace(step.t_old[0], step.t_new[0], 5)
        ours = np.array([step.dense(np.array([0]))(np.array([tau]))[0] for tau in times])
        assert np.max(np.abs(ours - solver.dense_output()(times).T)) < 1e-14
        checked.append(True)

    integrate_batch(_pendulum, np.array([[1.0, 0.5]]), 3.0, Tableau.of(method), 1e-6, 1e-9, accepted)
    assert checked


def test_a_diverging_run_fails_alone() -> None:
    """A run whose state stops being finite fails with its reason; the others finish."""

    def blow_up(t: np.ndarray, y: np.ndarray, rows: np.ndarray) -> np.ndarray:
        return np.where(rows[:, None] == 1, y * y, -y)

    t, y, steps, failed = integrate_batch(blow_up, np.array([[1.0], [1.0]]), 2.0, Tableau.of("RK45"), 1e-8, 1e-10)
    assert failed[0] == "" and abs(y[0, 0] - np.exp(-2.0)) < 1e-7
    assert "step size fell below" in failed[1] and abs(t[1] - 1.0) < 1e-6  # y = 1/(1 - t) blows up at t = 1


def test_a_step_the_callback_refuses_stops_that_run_alone() -> None:
    """A run the callback stops with Step.fail (a monitored value that is not finite) ends at that step with the
    reason; the others go on to the end."""

    def refuse_past_one(step: Step) -> None:
        late = np.flatnonzero((step.rows == 1) & (step.t_new > 1.0))
        if len(late):
            step.fail(late, "the energy is no longer finite")

    t, _, _, failed = integrate_batch(_pendulum, np.array([[0.1, 0.0], [1.0, 0.5]]), 3.0, Tableau.of("RK45"),
                                      1e-8, 1e-10, refuse_past_one)
    assert failed == ["", "the energy is no longer finite"]
    assert t[0] == 3.0 and 1.0 < t[1] < 3.0
