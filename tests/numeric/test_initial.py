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


@pytest.mark.parametrize("length", [1e-7, 1e-6, 1e-3, 1.0, 1e5])
def test_a_pendulum_of_any_size_starts_where_it_was_put(length: float) -> None:
    """The Cartesian pendulum with its rod l anywhere from 100 nm to 100 km, started at x = l/2 (30°): x is kept
    and y = -l·√3/2 to 1e-12 of l (at l = 1e-7 m the start y = 0 is only 7.5e-15 m² off the circle, which an
    absolute tolerance took for on it, and the bob swung from 90°); an x off the circle by 1e-6 of l is refused at
    every size, as it is at l = 1."""
    values = {"m": 1.0, "g": 9.81, "l": length}
    system, _ = system_of(CARTESIAN_PENDULUM, values)
    q, _ = complete_initial(system, {"x": length / 2, "x_dot": 0.0})
    assert q[0] == length / 2
    assert q[1] == pytest.approx(-length * np.sqrt(3) / 2, rel=1e-12)
    with pytest.raises(SpecError, match="initial positions violate the constraints"):
        complete_initial(system, {"x": length / 2, "y": -length * np.sqrt(3) / 2 * (1 + 1e-6)})


@pytest.mark.parametrize("length", [1e-7, 1e-6])
def test_a_micro_pendulum_swings_as_newton_says(length: float) -> None:
    """At l = 100 nm and 1 µm the simulated Cartesian pendulum follows θ'' = -(g/l) sin θ from 30° (SciPy's
    solve_ivp, independently): x/l and y/l within 1e-7 over about a period, and the rod stays on its circle to
    1e-9 of l² (projection held to the constraint's own scale)."""
    from scipy.integrate import solve_ivp

    from simulation_support import run

    text = CARTESIAN_PENDULUM.replace("l: 1.0}", f"l: {length!r}}}")
    period = 2 * np.pi * np.sqrt(length / 9.81)
    trajectory = run(text, period, initial={"x": length / 2, "x_dot": 0.0, "y_dot": 0.0}, samples=9)
    reference = solve_ivp(lambda t, s: [s[1], -9.81 / length * np.sin(s[0])], (0, period), [np.pi / 6, 0.0],
                          t_eval=trajectory.t, rtol=1e-12, atol=1e-14)
    theta = reference.y[0]
    assert trajectory.q[:, 0] / length == pytest.approx(np.sin(theta), abs=1e-7)
    assert trajectory.q[:, 1] / length == pytest.approx(-np.cos(theta), abs=1e-7)
    assert np.max(np.abs(np.sum(trajectory.q**2, axis=1) - length**2)) < 1e-9 * length**2
