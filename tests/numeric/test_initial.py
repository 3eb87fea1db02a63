"""Initial conditions completed from the constraints."""

from __future__ import annotations

import numpy as np
import pytest

from lagsolve.errors import SpecError
from lagsolve.numeric.initial import complete_initial
from simulation_support import CARTESIAN_PENDULUM, system_of


def test_dependent_coordinate_and_velocity_are_completed() -> None:
    """Given x and both velocities free, y solves x² + y² = l² and the velocities satisfy the rod."""
    system, _ = system_of(CARTESIAN_PENDULUM)
    q, qd = complete_initial(system, {"x": 0.6, "x_dot": 0.8})
    assert q == pytest.approx([0.6, -0.8])
    assert float(q @ qd) == pytest.approx(0.0, abs=1e-12)
    assert qd[0] == pytest.approx(0.8)


def test_given_values_are_kept() -> None:
    """A consistent full state is returned unchanged."""
    system, _ = system_of(CARTESIAN_PENDULUM)
    q, qd = complete_initial(system, {"x": 0.0, "y": 1.0, "x_dot": 2.0, "y_dot": 0.0})
    assert np.array_equal(q, [0.0, 1.0]) and np.array_equal(qd, [2.0, 0.0])


def test_inconsistent_positions_show_the_residual() -> None:
    """Positions off the constraint are rejected with the residual named."""
    system, _ = system_of(CARTESIAN_PENDULUM)
    with pytest.raises(SpecError, match=r"initial positions violate the constraints \(rod = 1\)"):
        complete_initial(system, {"x": 1.0, "y": 1.0})


def test_inconsistent_velocities_show_the_residual() -> None:
    """Velocities that break the velocity-level constraint are rejected."""
    system, _ = system_of(CARTESIAN_PENDULUM)
    with pytest.raises(SpecError, match="initial velocities violate the constraints"):
        complete_initial(system, {"x": 0.0, "y": -1.0, "x_dot": 0.0, "y_dot": 1.0})


def test_unknown_names_are_refused() -> None:
    """A name that is neither a coordinate nor a velocity is an error listing the known ones."""
    system, _ = system_of(CARTESIAN_PENDULUM)
    with pytest.raises(SpecError, match="unknown coordinate or velocity 'z'"):
        complete_initial(system, {"z": 1.0})
