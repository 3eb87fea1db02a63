"""Integration in minimal coordinates (``lagsolve.numeric.minimal_state``): the independent coordinates alone are
integrated and the dependent ones follow from the constraints' closed forms.

Checked against independent routes: the reduced Lagrangian's own accelerations (symbolic, from the
analysis), the run in all coordinates with projection, textbook motions, and energy conservation.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
import sympy

from lagsolve.app.simulation import SimulationOptions, run_simulation
from lagsolve.mechanics.analysis.minimal_chart import minimal_chart
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.integrate import integrate_motion
from lagsolve.numeric.system import bind
from mechanics_support import derived_file, derived_text, shipped


def minimal_system(derivation, values=None):
    chart, note = minimal_chart(derivation.analysis, derivation.model)
    assert chart is not None, note
    return bind(derivation.form, values or {}, derivation.conserved, chart)


def start(derivation, system, given=None):
    spec = derivation.problem.simulation
    return complete_initial(system, {**spec.initial, **(given or {})}, derivation.problem.source)


@pytest.mark.parametrize("name", ["bead", "hole_table", "wedge", "rotating_tube", "moving_support", "cone"])
def test_accelerations_are_the_reduced_lagrangians(name):
    """At random states, the accelerations the integrator uses in minimal coordinates equal those of the
    reduced Lagrangian L(q_I, phi(q_I, t), ...) that the analysis derived symbolically."""
    derivation = derived_file(name)
    system = minimal_system(derivation)
    chart, reduced = system.chart, derivation.analysis.reduced
    problem, model = derivation.problem, derivation.model
    concrete = {}
    for fn in problem.functions:
        given = problem.simulation.functions[fn.name]
        concrete[fn.function] = sympy.Lambda(given.arguments, given.expression)
    rng = random.Random(7)
    n = system.n
    q0, qd0 = start(derivation, system)
    for _ in range(12):
        t = rng.uniform(0, 3)
        local = np.array([rng.uniform(0.3, 1.5) for _ in range(2 * chart.size)])
        extended = chart.extended(0.0, q0, qd0, system.parameters)
        y = chart.full(t, local, n, extended)
        qdd = system.solve(t, y[:n], y[n:])[0][chart.independent]
        point = {model.time: t, **dict(zip([p.symbol for p in problem.parameters], system.parameters, strict=True))}
        point.update({c: v for c, v in zip(reduced.constants, extended[len(system.parameters):], strict=True)})
        for k, i in enumerate(chart.independent):
            point[model.coordinates[i]] = local[k]
            point[model.velocities[i]] = local[chart.size + k]
        for k, expected in enumerate(reduced.raw_accelerations):
            for fn, body in concrete.items():
                expected = expected.replace(fn, body)
            value = float(expected.doit().xreplace(point).evalf(20))
            assert qdd[k] == pytest.approx(value, rel=1e-10, abs=1e-10)


def _simulated():
    # cart_two_wheels (coordinates x1, x2) once ran wrong with the LLVM backend: SymEngine's CSE temporaries are
    # named x0, x1, ... and took the coordinates' places; compile.py now renames the arguments
    return list(shipped())


@pytest.mark.slow
@pytest.mark.parametrize("name", _simulated())
def test_minimal_and_full_coordinates_give_the_same_motion(name):
    """Every shipped problem simulates from its file's defaults in both modes; where a chart exists the
    minimal run keeps the constraints to rounding error and ends where the projected full run does."""
    derivation = derived_file(name)
    chart, note = minimal_chart(derivation.analysis, derivation.model)
    runs = {}
    for mode in ("minimal", "full"):
        options = SimulationOptions(values={}, initial={}, samples=101, coordinates=mode)
        runs[mode] = run_simulation(derivation.form, derivation.conserved, options, chart=chart, chart_note=note)
    small, full = runs["minimal"].trajectory, runs["full"].trajectory
    if chart is None:
        assert not small.stats["coordinates"].startswith("minimal")
        if derivation.constraints:
            assert "not in minimal coordinates" in runs["minimal"].summary
        return
    assert small.stats["coordinates"].startswith("minimal")
    assert small.stats["max_residual"] < 1e-12
    assert small.t[-1] == pytest.approx(full.t[-1], rel=1e-9)
    scale = 1 + np.max(np.abs(full.q)) + np.max(np.abs(full.qd))
    assert np.max(np.abs(small.q - full.q)) < 1e-6 * scale
    assert np.max(np.abs(small.qd - full.qd)) < 1e-6 * scale
    assert np.max(np.abs(small.multipliers - full.multipliers)) < 1e-5 * (1 + np.max(np.abs(full.multipliers)))


@pytest.mark.slow
def test_frictionless_bead_in_minimal_coordinates_conserves_energy_for_100_periods():
    """The bead integrated in x alone keeps its energy to 1e-8 over 100 oscillations, y on the wire exactly."""
    derivation = derived_file("bead")
    system = minimal_system(derivation)
    q0, qd0 = start(derivation, system)
    trajectory = integrate_motion(system, q0, qd0, 100 * 2.6, samples=5001)
    x, y = trajectory.q[:, 0], trajectory.q[:, 1]
    assert np.array_equal(y, x**2 / 2)
    assert trajectory.stats["energy_drift"] < 1e-8
    crossings = np.count_nonzero((x[:-1] < 0) & (x[1:] >= 0))
    assert crossings >= 90


def test_rotating_tube_constants_come_from_the_initial_state():
    """theta = theta0 and phi = Omega t + phi0, with theta0, phi0 taken from the initial state."""
    derivation = derived_file("rotating_tube")
    system = minimal_system(derivation)
    q0, qd0 = start(derivation, system, {"phi": 0.3, "theta": 0.7})
    trajectory = integrate_motion(system, q0, qd0, 1.0, samples=51)
    omega = system.parameters[system.parameter_names.index("Omega")]
    theta, phi = trajectory.q[:, 1], trajectory.q[:, 2]
    assert np.all(theta == 0.7)
    assert np.max(np.abs(phi - (0.3 + omega * trajectory.t))) < 1e-14
    assert np.all(trajectory.qd[:, 2] == omega)


POLAR_SPHERE = """
name: Particle sliding off a sphere, polar coordinates
parameters: {m: mass, g: gravity, R: radius}
coordinates: [r, theta]
particles: {p: {mass: m, position: [r*sin(theta), r*cos(theta)]}}
gravity: [0, -g]
constraints:
  surface: {holonomic: r - R, unilateral: true}
simulation:
  values: {m: 1.0, g: 9.81, R: 1.0}
  initial: {theta: 1.0e-6, theta_dot: 0.0}
  t_end: 6.0
"""


def test_release_switches_to_all_coordinates():
    """In polar coordinates the chart removes r = R; the particle leaves at cos(theta) = 2/3 and then flies
    freely in (r, theta), integrated in all coordinates: a parabola from the release state."""
    derivation = derived_text(POLAR_SPHERE)
    system = minimal_system(derivation)
    q0, qd0 = start(derivation, system)
    trajectory = integrate_motion(system, q0, qd0, 6.0, samples=601, after_release="continue")
    assert trajectory.stats["coordinates"].startswith("minimal: theta, with r from the constraints")
    assert "once a constraint was released" in trajectory.stats["coordinates"]
    (event,) = trajectory.events
    assert math.cos(event.state["theta"]) == pytest.approx(2 / 3, abs=1e-6)
    assert event.state["r"] == 1.0
    before = trajectory.t < event.time
    assert np.all(trajectory.q[before, 0] == 1.0)
    # free flight from the release state, in Cartesian coordinates
    g, r0, th0 = 9.81, event.state["r"], event.state["theta"]
    k = np.searchsorted(trajectory.t, event.time)
    x0, y0 = r0 * math.sin(th0), r0 * math.cos(th0)
    v = math.sqrt(2 * g * (1 - math.cos(th0)))  # speed from energy at release
    vx, vy = v * math.cos(th0), -v * math.sin(th0)
    tau = trajectory.t[k:] - event.time
    r, th = trajectory.q[k:, 0], trajectory.q[k:, 1]
    assert np.max(np.abs(r * np.sin(th) - (x0 + vx * tau))) < 1e-7
    assert np.max(np.abs(r * np.cos(th) - (y0 + vy * tau - g * tau**2 / 2))) < 1e-7
    assert trajectory.stats["energy_drift"] < 1e-8
