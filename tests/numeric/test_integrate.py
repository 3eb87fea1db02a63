"""Integration: conservation, projection, events and textbook motions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lagsolve.errors import SimulationError
from lagsolve.numeric.integrate import integrate_motion
from simulation_support import CARTESIAN_PENDULUM, FREE_FALL, PUCK, SPHERE, run, system_of

BEAD_SMOOTH = """
name: Bead on a parabola
parameters: {m: mass, g: gravity}
functions: {f: wire}
coordinates: [x, y]
particles: {bead: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints: {wire: {holonomic: y - f(x)}}
simulation:
  values: {m: 1.0, g: 9.81}
  functions: {"f(u)": "u**2/2"}
  initial: {x: -1.5, x_dot: 0.0}
  t_end: 10.0
"""


def _period(t: np.ndarray, x: np.ndarray) -> float:
    """Mean time between upward zero crossings of x (linear interpolation)."""
    up = np.where((x[:-1] < 0) & (x[1:] >= 0))[0]
    crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    return float(np.mean(np.diff(crossings)))


@pytest.mark.slow
def test_frictionless_bead_conserves_energy_for_100_periods() -> None:
    """A frictionless bead on a wire keeps its energy to 1e-8 over 100 oscillations at default tolerances."""
    first = run(BEAD_SMOOTH, 10.0)
    period = _period(first.t, first.q[:, 0])
    trajectory = run(BEAD_SMOOTH, 100 * period, samples=20001)
    assert trajectory.stats["energy_conserved"] is True
    assert trajectory.stats["energy_drift"] < 1e-8
    assert len(np.where((trajectory.q[:-1, 0] < 0) & (trajectory.q[1:, 0] >= 0))[0]) >= 99


@pytest.mark.slow
def test_cartesian_pendulum_stays_on_its_rod_for_1000_periods() -> None:
    """With projection after every step, a pendulum in x, y keeps x² + y² = l² to 1e-10 for 1000 periods."""
    period = 2 * math.pi * math.sqrt(1.0 / 9.81) * 1.02  # amplitude 30 degrees lengthens it a little
    trajectory = run(CARTESIAN_PENDULUM, 1000 * period, samples=5001)
    r = np.hypot(trajectory.q[:, 0], trajectory.q[:, 1])
    assert trajectory.stats["max_residual"] < 1e-10
    assert np.max(np.abs(r - 1.0)) < 1e-12
    assert trajectory.stats["energy_drift"] < 1e-8


@pytest.mark.slow
def test_without_projection_the_rod_drifts() -> None:
    """Projection is what keeps the constraint: an implicit method without per-step projection drifts more."""
    projected = run(CARTESIAN_PENDULUM, 200.0, rtol=1e-6, atol=1e-8)
    loose = run(CARTESIAN_PENDULUM, 200.0, rtol=1e-6, atol=1e-8, method="Radau")
    assert loose.stats["max_residual"] > 50 * projected.stats["max_residual"]
    assert np.max(np.abs(np.hypot(projected.q[:, 0], projected.q[:, 1]) - 1)) < 1e-12


@pytest.mark.slow
def test_small_pendulum_period() -> None:
    """A pendulum released at 0.01 rad swings with period 2π√(l/g) to 1e-6."""
    angle = 0.01
    trajectory = run(CARTESIAN_PENDULUM, 20.0, initial={"x": math.sin(angle)}, samples=40001)
    expected = 2 * math.pi * math.sqrt(1.0 / 9.81) * (1 + angle**2 / 16)
    assert _period(trajectory.t, trajectory.q[:, 0]) == pytest.approx(expected, rel=1e-6)


def test_free_fall_matches_closed_form() -> None:
    """Without constraints, z(t) = z0 + v0 t − g t²/2 and x(t) = x0 + u0 t."""
    trajectory = run(FREE_FALL, 2.0, samples=21)
    t = trajectory.t
    assert np.allclose(trajectory.q[:, 1], 10.0 + 3.0 * t - 9.81 * t**2 / 2, rtol=0, atol=1e-10)
    assert np.allclose(trajectory.q[:, 0], 1.5 * t, rtol=0, atol=1e-10)
    assert trajectory.multipliers.shape == (21, 0)


def test_particle_leaves_the_sphere_at_cos_two_thirds() -> None:
    """Sliding from rest at the top of a smooth sphere, contact is lost where cos θ = 2/3."""
    trajectory = run(SPHERE, 5.0)
    assert len(trajectory.events) == 1
    event = trajectory.events[0]
    assert event.constraint == "sphere" and event.action == "stopped"
    assert event.state["y"] / 1.0 == pytest.approx(2 / 3, abs=1e-6)
    assert trajectory.t[-1] == pytest.approx(event.time)
    assert trajectory.multipliers[-1, 0] == pytest.approx(0.0, abs=1e-8)


def test_after_release_the_particle_flies_freely() -> None:
    """With after_release='continue' the released particle follows a parabola off the sphere."""
    trajectory = run(SPHERE, 6.0, after_release="continue")
    event = trajectory.events[0]
    after = trajectory.t > event.time + 1e-9
    r = np.hypot(trajectory.q[after, 0], trajectory.q[after, 1])
    assert np.all(r > 1.0 - 1e-9) and r[-1] > 1.01
    assert np.all(trajectory.multipliers[after, 0] == 0.0)
    # in free flight the horizontal velocity is constant
    assert np.ptp(trajectory.qd[after, 0]) < 1e-8


def test_energy_drift_reported_only_when_conserved() -> None:
    """A time-dependent problem says why its energy is not conserved."""
    driven = """
name: Driven oscillator
parameters: {m: mass, k: stiffness, F0: amplitude, w: frequency}
coordinates: [x]
kinetic: m*x_dot**2/2
potential: k*x**2/2
forces: [{coordinate: x, value: F0*cos(w*t)}]
simulation: {values: {m: 1, k: 4, F0: 1, w: 1}, initial: {x: 0, x_dot: 0}, t_end: 1}
"""
    trajectory = run(driven, 3.0)
    assert trajectory.stats["energy_conserved"] is False
    assert "forces" in trajectory.stats["energy_note"]
    # x(t) = F0/(k - m w²) (cos w t − cos ω0 t), ω0 = 2
    t = trajectory.t
    assert np.allclose(trajectory.q[:, 0], (np.cos(t) - np.cos(2 * t)) / 3, atol=1e-9)


def test_bad_arguments_are_rejected() -> None:
    """Unknown methods and non-positive end times are errors, not silent defaults."""
    system, _ = system_of(FREE_FALL)
    q0, qd0 = np.zeros(2), np.zeros(2)
    with pytest.raises(ValueError, match="unknown method"):
        integrate_motion(system, q0, qd0, 1.0, method="Euler")
    with pytest.raises(ValueError, match="t_end must be a positive number"):
        integrate_motion(system, q0, qd0, -1.0)


def test_singular_state_is_a_simulation_error() -> None:
    """A state where the augmented system is singular stops the run with a clear error."""
    text = """
name: Inertia that vanishes at x = 0
parameters: {k: spring}
coordinates: [x]
kinetic: x**2*x_dot**2/2
potential: k*x
simulation: {values: {k: 1}, initial: {x: 0}, t_end: 1}
"""
    system, _ = system_of(text)
    with pytest.raises(SimulationError, match="singular at t = 0"):
        integrate_motion(system, np.array([0.0]), np.zeros(1), 1.0)


LOG_WIRE = """
name: Bead on y = log(x)
parameters: {m: mass, g: gravity}
coordinates: [x, y]
particles: {bead: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints: {wire: {holonomic: y - log(x)}}
simulation:
  values: {m: 1.0, g: 9.81}
  initial: {x: 0.5, x_dot: -1.0}
  t_end: 5.0
"""


@pytest.mark.parametrize("minimal", [True, False])
def test_a_state_that_stops_being_finite_stops_the_run(minimal: bool) -> None:
    """A bead on y = log(x) reaching x <= 0 stops with an error saying when, at which state and why, not NaN rows."""
    with pytest.raises(SimulationError) as caught:
        run(LOG_WIRE, 5.0, minimal=minimal)
    message = str(caught.value)
    assert "the state is no longer finite at t = 2.6" in message
    assert "is not a finite number" in message or "are not finite numbers" in message
    assert "the last finite state was at t = " in message
    assert "outside its domain (log or sqrt of a number <= 0" in message



def test_stop_after_release_holds_when_contact_pulls_at_the_start() -> None:
    """A unilateral constraint that would have to pull at t = 0 ends a run with after_release="stop" right there."""
    trajectory = run(SPHERE, 5.0, initial={"x": 0.8, "y": 0.6, "x_dot": 3.0})
    assert trajectory.t.tolist() == [0.0]
    assert [(e.time, e.kind, e.name, e.action) for e in trajectory.events] == [(0.0, "release", "sphere", "stopped")]
    going_on = run(SPHERE, 1.0, initial={"x": 0.8, "y": 0.6, "x_dot": 3.0}, after_release="continue")
    assert going_on.t[-1] == 1.0 and going_on.events[0].action == "released"


def test_accelerations_that_are_not_finite_at_the_start_stop_at_once() -> None:
    """V = k x log(x) at x = -1 has no finite force: the run stops at t = 0 with the reason (SciPy would
    otherwise loop for ever on a NaN step size)."""
    text = """
name: Bad start
parameters: {m: mass, k: stiffness}
coordinates: [x]
kinetic: m*x_dot**2/2
potential: k*x*log(x)
simulation: {values: {m: 1.0, k: 1.0}, initial: {x: -1.0, x_dot: 0}, t_end: 1}
"""
    with pytest.raises(SimulationError, match=r"no longer finite at t = 0 \(x = -1, x_dot = 0\): x_ddot is not a "
                                              r"finite number"):
        run(text, 1.0)


PLATE = b"""
name: Ball on a vibrating plate
parameters: {m: mass, g: gravity, A: amplitude, w: angular frequency}
coordinates: [y]
particles:
  ball: {mass: m, position: [0, y]}
gravity: [0, -g]
constraints:
  plate: {holonomic: y - A*sin(w*t), on: ball, unilateral: true}
simulation:
  values: {m: 0.1, g: 9.81, A: 0.01, w: 60.0}
  initial: {y: 0.0, y_dot: 0.6}
  t_end: 0.2
"""


def test_a_ball_on_a_vibrating_plate_leaves_it_where_newton_says() -> None:
    """No coordinate is left free (the plate prescribes y = A sin ωt): the derivation says so instead of failing
    (the symmetry search crashed on it), N = m(g − Aω² sin ωt) as Newton gives, and the ball leaves the plate
    where N first reaches zero, sin ωt = g/(Aω²), although the integrator takes the whole run in one step (its
    state is empty): the watched force is looked at inside the step, where it goes negative and back."""
    import sympy

    import lagsolve

    derivation = lagsolve.derive(PLATE)
    s = {x.name: x.symbol for x in derivation.problem.parameters}
    t = derivation.model.time
    newton = s["m"] * (s["g"] - s["A"] * s["w"] ** 2 * sympy.sin(s["w"] * t))
    assert sympy.simplify(derivation.multipliers["plate"] - newton) == 0
    analysis = derivation.analysis
    assert analysis.linearization is None and "no degrees of freedom" in analysis.linearization_note
    assert derivation.hamiltonian is None
    from lagsolve.render.report import render

    markdown, latex = render(derivation, "md"), render(derivation, "tex")
    assert "No coordinate is left free (no degrees of freedom)" in markdown and "$``$" not in markdown
    assert "No coordinate is left free" in latex and "\\begin{aligned}\n\\end{aligned}" not in markdown
    run = lagsolve.simulate(derivation)
    [event] = run.events
    assert event.kind == "release" and event.name == "plate"
    assert event.time == pytest.approx(math.asin(9.81 / (0.01 * 60.0**2)) / 60.0, rel=1e-9)


STRING = """
name: Stone whirled on a string in a vertical circle
parameters: {m: mass, g: gravity, l: length}
coordinates: {r: {positive: true}, theta: angle from the downward vertical}
particles: {stone: {mass: m, position: [r*sin(theta), -r*cos(theta)]}}
gravity: [0, -g]
constraints: {string: {holonomic: l - r, unilateral: true}}
simulation:
  values: {m: 0.5, g: 9.81, l: 1.2}
  initial: {r: 1.2, theta: 0, theta_dot: 5.0}
  t_end: 1.5
"""


def test_a_string_that_comes_taut_again_after_going_slack_stops_the_run() -> None:
    """Below the critical speed the string goes slack (tension m(l θ̇² + g cos θ) reaches 0) and the stone flies
    free; where its parabola reaches r = l again the string would jerk taut, an impact lagsolve does not model.
    The run stops there (it went on with the stone 2.3 m from the pivot on a 1.2 m string, exit 0)."""
    from scipy.optimize import brentq

    from lagsolve.render.trajectory import summary

    trajectory = run(STRING, 1.5, after_release="continue")
    release, back = trajectory.events
    assert (release.kind, release.action, back.kind, back.name, back.action) == (
        "release", "released", "contact", "string", "stopped")
    g, length, theta, rate = 9.81, 1.2, release.state["theta"], release.state["theta_dot"]
    assert length * rate**2 + g * math.cos(theta) == pytest.approx(0.0, abs=1e-7)  # the tension is zero there
    x0, y0 = length * math.sin(theta), -length * math.cos(theta)
    vx, vy = length * math.cos(theta) * rate, length * math.sin(theta) * rate

    def gap(s: float) -> float:  # r² − l² along the free flight after the release
        return (x0 + vx * s) ** 2 + (y0 + vy * s - g * s * s / 2) ** 2 - length * length

    flight = brentq(gap, 0.05, 1.0)
    assert back.time == pytest.approx(release.time + flight, abs=1e-8)
    assert trajectory.t[-1] == pytest.approx(back.time)
    assert np.all(trajectory.q[:, 0] <= length + 1e-8)
    assert "reached again at t = " in summary(trajectory, "stone", timing=False)


LAUNCH = """
name: Two blocks launched by a spring
parameters: {mA: mass, mB: mass, k: stiffness, L0: natural length, w: width}
coordinates: [xA, xB]
particles: {A: {mass: mA, position: [xA, 0]}, B: {mass: mB, position: [xB, 0]}}
potential: k*(xA - L0)**2/2
constraints: {touch: {holonomic: xB - xA - w, on: [B, A], at: [xB, 0], unilateral: true}}
simulation:
  values: {mA: 1.0, mB: 3.0, k: 100.0, L0: 1.0, w: 0.1}
  initial: {xA: 0.8, xA_dot: 0}
  t_end: 1.0
"""


def test_conserved_quantities_are_measured_up_to_a_release_the_run_went_on_from() -> None:
    """The blocks separate at t = (π/2)√((mA + mB)/k); after it the energy of the joined blocks, (mA + mB) ẋA²/2
    + V, is no longer the energy, which stays 2 J. The summary said 'energy conserved: relative drift 0.75'."""
    from lagsolve.render.trajectory import summary

    trajectory = run(LAUNCH, 1.0, after_release="continue")
    [release] = trajectory.events
    assert release.time == pytest.approx(math.pi / 2 * math.sqrt(4.0 / 100.0), rel=1e-9)
    assert trajectory.stats["conserved_until"] == release.time
    assert trajectory.stats["conserved_drift"]["energy"] < 1e-8
    assert np.allclose(trajectory.energy, 2.0, rtol=1e-8)  # the whole system's energy, throughout
    text = summary(trajectory, "launch", timing=False)
    assert f"relative drift {trajectory.stats['conserved_drift']['energy']:.3g} (up to the release at t = " in text


def test_a_contact_sliding_in_a_plane_stops_the_run_where_it_comes_to_rest() -> None:
    """Friction in a plane, -mu N v/|v|, holds only while the puck slides: the run stops where it comes to rest, at
    t = |v0|/(mu g), |v0|²/(2 mu g) along v0 (closed form; it spun until its 600 s budget ran out, then exit 1)."""
    from lagsolve.numeric.integrate import EventKind

    motion = run(PUCK, 3.0)
    (event,) = motion.events
    speed, deceleration = math.hypot(1.2, 0.5), 0.1 * 9.81
    assert (event.kind, event.name, event.action) == (EventKind.REST, "rub", "stopped")
    assert event.time == pytest.approx(speed / deceleration, rel=1e-8)
    assert motion.t[-1] == pytest.approx(event.time, rel=1e-12)
    distance = speed**2 / (2 * deceleration)
    assert motion.q[-1, 0] == pytest.approx(distance * 1.2 / speed, rel=1e-8)
    assert motion.q[-1, 1] == pytest.approx(distance * 0.5 / speed, rel=1e-8)
    assert np.all(np.isfinite(motion.friction)) and np.all(np.isfinite(motion.qd))


def test_a_contact_sliding_in_a_plane_at_rest_at_the_start_is_refused() -> None:
    """At rest at t = 0 its friction is undefined (it failed with 'evaluated outside its domain', exit 1): refused
    with the contact's name and the fix, exit 2."""
    from lagsolve.errors import SpecError
    from lagsolve.numeric.initial import complete_initial
    system, given = system_of(PUCK)
    with pytest.raises(SpecError, match="contact 'rub' does not slide at the start"):
        complete_initial(system, {**given, "x_dot": 0.0, "y_dot": 0.0})
    q, qd = complete_initial(system, {**given, "x_dot": 1e-6, "y_dot": 0.0})  # slow, but sliding
    assert qd[0] == 1e-6


SPRUNG_PUCK = PUCK.replace("gravity: [0, 0, -g]", "gravity: [0, 0, -g]\npotential: k*x**2/2").replace(
    "mu: kinetic coefficient}", "mu: kinetic coefficient, k: stiffness}").replace(
    "values: {m: 0.2, g: 9.81, mu: 0.1}", "values: {m: 1.0, g: 9.81, mu: 0.1, k: 10.0}").replace(
    "x_dot: 1.2, y_dot: 0.5}", "x_dot: 2.0, y_dot: 0.0}").replace("t_end: 3.0", "t_end: 5.0")


def test_a_contact_sliding_in_a_plane_whose_velocity_only_turns_slides_on() -> None:
    """A spring pulls the puck back along the line it came on: at its turning point (x = 0.542, k x = 5.4 > mu m g)
    it does not come to rest, it slides back (the run stopped there, 'comes to rest'). Closed form, half swings of
    pi/omega about -+mu g/omega^2 from the first turn: it stops at x = 0.04668 (k x < mu m g), t = 3.42844."""
    from lagsolve.numeric.integrate import EventKind

    motion = run(SPRUNG_PUCK, 5.0)
    omega, shift = math.sqrt(10.0), 0.1 * 9.81 / 10.0
    amplitude = math.hypot(shift, 2.0 / omega)
    t, x = (math.pi / 2 - math.asin(shift / amplitude)) / omega, amplitude - shift
    for _ in range(3):
        t, x = t + math.pi / omega, 2 * math.copysign(shift, x) - x
    (event,) = motion.events
    assert (event.kind, event.name) == (EventKind.REST, "rub")
    assert event.time == pytest.approx(t, rel=1e-7)
    assert motion.q[-1, 0] == pytest.approx(x, rel=1e-6)
