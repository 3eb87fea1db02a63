"""The trajectory table (CSV/NPZ) and the run summary."""

from __future__ import annotations

import io

import numpy as np
import pytest

from lagsolve.numeric.integrate import Trajectory
from lagsolve.render.trajectory import columns, summary, to_csv, to_npz
from simulation_support import CARTESIAN_PENDULUM, SPHERE, run


@pytest.fixture(scope="module")
def trajectory() -> Trajectory:
    return run(CARTESIAN_PENDULUM, 1.0, samples=11)


def test_csv_columns_follow_the_format(trajectory: Trajectory) -> None:
    """CSV header: t, coordinates, velocities, lambda_<c>, F_<c>, energy, then extras; one row per sample."""
    lines = to_csv(trajectory).splitlines()
    assert lines[0] == "t,x,y,x_dot,y_dot,lambda_rod,F_rod,energy,residual"
    assert len(lines) == 12
    first = [float(v) for v in lines[1].split(",")]
    assert first[0] == 0.0 and first[1] == pytest.approx(0.5)


def test_npz_holds_the_same_columns(trajectory: Trajectory) -> None:
    """The NPZ archive has every CSV column as an array."""
    archive = np.load(io.BytesIO(to_npz(trajectory)))
    assert list(archive.files) == list(columns(trajectory))
    assert np.array_equal(archive["x"], trajectory.q[:, 0])


def test_summary_reports_diagnostics(trajectory: Trajectory) -> None:
    """The summary gives the final state, steps, evaluations, residual and energy drift."""
    text = summary(trajectory, "Pendulum")
    assert text.startswith("Pendulum: simulated to t = 1 with DOP853")
    for phrase in ("final state: x = ", "steps: ", "right-hand-side evaluations: ",
                   "largest constraint residual (before projection): ", "energy (Jacobi integral) conserved"):
        assert phrase in text


def test_summary_lists_events() -> None:
    """A lost contact is listed with its time and where it happened."""
    text = summary(run(SPHERE, 6.0), "Sphere")
    assert "event: constraint 'sphere' released at t = 4.58" in text and "y = 0.666667" in text


def test_summary_says_contact_was_lost_at_the_start() -> None:
    """A run stopped at t = 0 because the contact would pull says so, and how to go on without it."""
    text = summary(run(SPHERE, 5.0, initial={"x": 0.8, "y": 0.6, "x_dot": 3.0}), "Sphere")
    assert "simulated to t = 0 " in text
    assert ("event: constraint 'sphere' would have to pull at the start, t = 0 (x = 0.8, y = 0.6), so contact is "
            "lost at once; stopped there (--after-release continue goes on without it)") in text
