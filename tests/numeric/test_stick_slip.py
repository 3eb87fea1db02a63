"""Stick–slip: contacts that come to rest stick while friction can hold them and slip again beyond μ_s N."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.integrate import integrate_motion
from lagsolve.numeric.system import bind
from lagsolve.problem.load import load_problem, load_text

ROOT = Path(__file__).resolve().parents[2]
M, K, G, MU, MU_S = 1.0, 10.0, 9.81, 0.1, 0.15

BELT = """
name: Mass on a spring on a moving belt
parameters: {m: mass, k: stiffness, g: gravity, V: belt speed, mu: kinetic, mu_s: static}
coordinates:
  s: position of the block relative to the belt
  y: height
particles: {block: {mass: m, position: [V*t + s, y]}}
gravity: [0, -g]
potential: k*(V*t + s)**2/2
constraints: {belt: {holonomic: y, on: block}}
friction: {rough: {coefficient: mu, static: mu_s, on: block, normal: [belt], sliding: [s]}}
simulation:
  values: {m: 1.0, k: 10.0, g: 9.81, V: 0.5, mu: 0.1, mu_s: 0.15}
  initial: {s: 0, s_dot: 0}
  t_end: 2
"""


def _run(problem, t_end: float, samples: int):  # type: ignore[no-untyped-def]
    system = bind(matrix_form(problem))
    q0, qd0 = complete_initial(system, dict(problem.simulation.initial))
    return integrate_motion(system, q0, qd0, t_end, samples=samples)


def test_damped_spring_turning_points_match_the_analytic_decay() -> None:
    """Each half swing lasts π√(m/k) and the turning points lose 2μmg/k, to 1e-6; the block sticks in the band."""
    half = math.pi * math.sqrt(M / K)
    trajectory = _run(load_problem(ROOT / "problems" / "spring_on_rough_floor.yaml"), 7 * half, 7 * 200 + 1)
    drop = 2 * MU * M * G / K
    for n in range(5):
        i = 200 * n
        assert trajectory.t[i] == pytest.approx(n * half, abs=1e-12)
        assert trajectory.q[i, 0] == pytest.approx((-1) ** n * (1.0 - n * drop), abs=1e-6)
    stick = [e for e in trajectory.events if e.kind == "stick"]
    assert len(stick) == 1
    assert stick[0].time == pytest.approx(5 * half, abs=1e-6)
    final = -(1.0 - 5 * drop)
    assert abs(final) <= MU_S * M * G / K
    after = trajectory.t > stick[0].time + 1e-9
    assert np.allclose(trajectory.q[after, 0], final, atol=1e-6)
    assert np.all(trajectory.qd[after, 0] == 0.0)
    assert trajectory.stuck[after, 0].all() and not trajectory.stuck[0, 0]


def test_no_chattering_at_rest() -> None:
    """Once stuck the run takes large steps: no tiny steps at v = 0."""
    trajectory = _run(load_problem(ROOT / "problems" / "spring_on_rough_floor.yaml"), 100.0, 101)
    assert trajectory.stats["steps"] < 400


def test_belt_drags_the_block_until_the_spring_beats_static_friction() -> None:
    """On a moving belt the block first sticks, then slips when k x reaches μ_s m g, at t = μ_s m g/(k V)."""
    trajectory = _run(load_text(BELT), 2.0, 401)
    kinds = [(e.kind, e.name) for e in trajectory.events]
    assert kinds[:2] == [("stick", "rough"), ("slip", "rough")]
    assert trajectory.events[1].time == pytest.approx(MU_S * M * G / (K * 0.5), rel=1e-9)
    # while stuck the block moves with the belt: s stays 0
    stuck = trajectory.t < trajectory.events[1].time
    assert np.allclose(trajectory.q[stuck, 0], 0.0, atol=1e-12)


def test_kinetic_friction_opposes_sliding_and_normal_force_is_weight() -> None:
    """While sliding, N = m g and the friction decelerates the block by μ g beyond the spring."""
    problem = load_problem(ROOT / "problems" / "spring_on_rough_floor.yaml")
    system = bind(matrix_form(problem))
    qdd, lam, normal, _ = system.solve_all(0.0, np.array([0.3, 0.0]), np.array([2.0, 0.0]))
    assert normal[0] == pytest.approx(M * G)
    assert qdd[0] == pytest.approx(-K * 0.3 / M - MU * G)
    assert lam[0] == pytest.approx(M * G)


def _shipped(name: str, values: dict[str, float] | None = None):  # type: ignore[no-untyped-def]
    """problems/<name>.yaml bound (with ``values`` over the file's) and run to its t_end."""
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    system = bind(matrix_form(problem), values or {})
    q0, qd0 = complete_initial(system, dict(problem.simulation.initial))
    return system, integrate_motion(system, q0, qd0, problem.simulation.t_end, samples=2001)


def test_a_block_on_a_rough_wedge_conserves_the_horizontal_momentum() -> None:
    """On a smooth floor nothing outside pushes horizontally: M X_dot + m x_dot stays 0 (to 1e-8) while the block
    slides down the rough face, and the energy lost is the friction's work, the integral of f sigma (1e-6)."""
    system, run = _shipped("rough_wedge")
    values = dict(zip(system.parameter_names, system.parameters, strict=True))
    X, x, y = (system.coordinates.index(c) for c in ("X", "x", "y"))
    momentum = values["M"] * run.qd[:, X] + values["m"] * run.qd[:, x]
    assert np.max(np.abs(momentum - momentum[0])) < 1e-8
    alpha = values["alpha"]
    sigma = (run.qd[:, x] - run.qd[:, X]) * np.cos(alpha) + run.qd[:, y] * np.sin(alpha)
    assert np.all(sigma[1:] < 0)  # it slides down the face
    power = run.friction[:, 0] * sigma  # the friction's component along the tangent times the sliding rate
    work = np.concatenate([[0.0], np.cumsum((power[1:] + power[:-1]) / 2 * np.diff(run.t))])
    assert run.energy - run.energy[0] == pytest.approx(work, rel=1e-6, abs=1e-9)
    assert np.all(run.friction[1:, 0] > 0)  # up the face, against the sliding
    assert run.friction[:, 0] == pytest.approx(values["mu"] * run.normal_forces[:, 0])


@pytest.mark.parametrize("above", [True, False])
def test_a_disc_on_a_rough_incline_rolls_or_slips_at_the_textbook_threshold(above: bool) -> None:
    """Started at rest, the disc rolls while mu_s >= tan(alpha)/3, with x_ddot = 2 g sin(alpha)/3 and the friction
    m g sin(alpha)/3 up the slope; just below the threshold it slips from the start, x_ddot = g (sin - mu cos)."""
    m, g, alpha, mu, R = 1.0, 9.81, 0.5, 0.1, 0.3
    threshold = math.tan(alpha) / 3
    mu_s = threshold * (1.02 if above else 0.98)
    system, run = _shipped("rough_disc_incline", {"mu_s": mu_s, "mu": mu})
    x, phi = system.coordinates.index("x"), system.coordinates.index("phi")
    if above:
        assert run.stuck[:, 0].all()
        assert run.friction[:, 0] == pytest.approx(-m * g * math.sin(alpha) / 3, rel=1e-9)
        assert run.qd[:, x] == pytest.approx(2 * g * math.sin(alpha) / 3 * run.t, abs=1e-9)
        assert run.qd[:, x] == pytest.approx(R * run.qd[:, phi], abs=1e-9)
    else:
        assert not run.stuck[:, 0].any()
        assert run.qd[:, x] == pytest.approx(g * (math.sin(alpha) - mu * math.cos(alpha)) * run.t, abs=1e-9)
        assert run.qd[:, phi] == pytest.approx(2 * mu * g * math.cos(alpha) / R * run.t, abs=1e-8)
        assert run.friction[:, 0] == pytest.approx(-mu * m * g * math.cos(alpha), rel=1e-9)


@pytest.mark.parametrize("pull", [8.0, 20.0])
def test_stacked_blocks_ride_together_or_the_upper_one_slips(pull: float) -> None:
    """The lower block is pulled across a rough floor. The upper one rides along while the common acceleration
    a = F/(m1 + m2) - mu1 g is at most mu2_s g (its friction then m2 a); beyond it slips, x2_ddot = mu2 g and
    m1 x1_ddot = F - mu1 (m1 + m2) g - mu2 m2 g."""
    m1, m2, g, mu1, mu2 = 2.0, 1.0, 9.81, 0.2, 0.25
    system, run = _shipped("stacked_blocks", {"F": pull})
    x1, x2 = system.coordinates.index("x1"), system.coordinates.index("x2")
    ground, between = system.contact_names.index("ground"), system.contact_names.index("between")
    assert run.normal_forces[:, ground] == pytest.approx((m1 + m2) * g)
    assert run.normal_forces[:, between] == pytest.approx(m2 * g)
    common = pull / (m1 + m2) - mu1 * g
    if pull == 8.0:
        assert run.stuck[:, between].all() and not run.stuck[:, ground].any()
        assert run.qd[:, x1] == pytest.approx(common * run.t, abs=1e-9)
        assert run.qd[:, x2] == pytest.approx(run.qd[:, x1], abs=1e-9)
        assert run.friction[:, between] == pytest.approx(m2 * common, rel=1e-9)
    else:
        assert common > 0.3 * g and not run.stuck[:, between].any()
        assert run.qd[:, x2] == pytest.approx(mu2 * g * run.t, abs=1e-9)
        assert run.qd[:, x1] == pytest.approx((pull - mu1 * (m1 + m2) * g - mu2 * m2 * g) / m1 * run.t, abs=1e-8)


def test_a_disc_rolling_on_a_cylinder_leaves_it_at_four_sevenths() -> None:
    """Rolling from rest at theta0, the disc leaves the cylinder where cos(theta) = 4 cos(theta0)/7 (energy with
    the rolling constraint, and the normal force m g cos(theta) - m (R + a) theta_dot^2 = 0); the friction at the
    contact is m g sin(theta)/3 all the way."""
    system, run = _shipped("disc_on_cylinder")
    (release,) = [e for e in run.events if e.kind == "release"]
    assert math.cos(release.state["theta"]) == pytest.approx(4 * math.cos(0.1) / 7, rel=1e-8)
    theta = run.q[:, system.coordinates.index("theta")]
    roll = system.constraints.index("roll")
    assert run.magnitudes[:, roll] == pytest.approx(9.81 * np.abs(np.sin(theta)) / 3, rel=1e-8)


CYLINDER_ON_ROUGH_WEDGE = """
name: cylinder on a rough sliding wedge
parameters: {M: mass, m: mass, R: radius, g: gravity, alpha: angle, mu: friction, mu_s: static}
coordinates: [X, s, h, phi]
particles:
  wedge: {mass: M, position: [X, 0]}
bodies:
  cyl: {mass: m, position: [X + s*cos(alpha) + h*sin(alpha), -s*sin(alpha) + h*cos(alpha)], inertia: m*R**2/2,
        angular_velocity: -phi_dot}
gravity: [0, -g]
constraints:
  face: {holonomic: h - R, on: [cyl, wedge], at: [X + s*cos(alpha) + (h - R)*sin(alpha),
                                                  -s*sin(alpha) + (h - R)*cos(alpha)]}
friction:
  grip: {coefficient: mu, static: mu_s, normal: [face]}
simulation:
  values: {M: 3, m: 1, R: 0.2, g: 9.81, alpha: 0.4, mu: 0.05, mu_s: MUS}
  initial: {X: 0, s: 0, phi: 0, X_dot: 0, s_dot: 0, phi_dot: 0}
  t_end: 1
"""


@pytest.mark.parametrize("mu_s", [0.06, 0.3])
def test_a_cylinder_on_a_rough_sliding_wedge_keeps_the_momentum_rolling_or_slipping(mu_s: float) -> None:
    """Friction between a turning body and a sliding wedge: the contact point's velocity relative to the face,
    rotation included. Rolling (enough static friction) it is wedge_cylinder.yaml's s_ddot; slipping it is
    not; either way the horizontal momentum (M + m) X_dot + m cos(alpha) s_dot stays 0."""
    problem = load_text(CYLINDER_ON_ROUGH_WEDGE.replace("MUS", str(mu_s)))
    system = bind(matrix_form(problem))
    q0, qd0 = complete_initial(system, dict(problem.simulation.initial))
    run = integrate_motion(system, q0, qd0, 1.0, samples=201)
    M, m, g, alpha = 3.0, 1.0, 9.81, 0.4
    X, s, phi = (system.coordinates.index(c) for c in ("X", "s", "phi"))
    momentum = (M + m) * run.qd[:, X] + m * math.cos(alpha) * run.qd[:, s]
    assert np.max(np.abs(momentum)) < 1e-9
    rolling = g * math.sin(alpha) * (M + m) / (1.5 * (M + m) - m * math.cos(alpha) ** 2)
    if mu_s == 0.3:
        assert run.stuck[:, 0].all()
        assert run.qd[:, s] == pytest.approx(rolling * run.t, abs=1e-9)
        assert run.qd[:, s] == pytest.approx(0.2 * run.qd[:, phi], abs=1e-9)
    else:
        assert not run.stuck[1:, 0].any()
        assert run.qd[-1, s] > rolling * run.t[-1] * 1.05  # slipping, it slides faster than it would roll


SPRING_ON_INCLINE = """
name: Block on a rough incline held by a spring along the slope (written here, not shipped)
parameters: {m: mass, k: stiffness, g: gravity, a: angle, mu: kinetic, mu_s: static}
coordinates: {s: distance down the slope from the spring's rest point, n: distance off the slope}
particles:
  block: {mass: m, position: [s*cos(a) - n*sin(a), -s*sin(a) - n*cos(a)]}
gravity: [0, -g]
potential: k*s**2/2
constraints:
  slope: {holonomic: n, on: block}
friction:
  rough: {coefficient: mu, static: mu_s, on: block, normal: [slope], sliding: [s]}
simulation:
  values: {m: 2.0, k: 30.0, g: 9.81, a: 0.4, mu: 0.12, mu_s: 0.2}
  initial: {s: 1.5, n: 0.0, s_dot: 0.0}
  t_end: 10.0
"""


def test_a_spring_on_a_rough_incline_turns_and_sticks_where_the_closed_form_says() -> None:
    """Each half swing is a harmonic half-oscillation of period π√(m/k) about s_g ± μ m g cos a / k (s_g = m g
    sin a / k, the sign against the motion), so the turning points follow by reflection; the block sticks at the
    first turning point within μ_s m g cos a / k of s_g. The rate reaches zero at each reversal and crosses it
    (friction holds its direction up to the event), seven times here, then sticks at t = 8 π√(m/k)."""
    from lagsolve.api import simulate

    m, k, g, a, mu, mu_s = 2.0, 30.0, 9.81, 0.4, 0.12, 0.2
    centre, shift, band = m * g * math.sin(a) / k, mu * m * g * math.cos(a) / k, mu_s * m * g * math.cos(a) / k
    s, turns = 1.5, []
    while abs(s - centre) > band:
        s = 2 * (centre + shift if s > centre else centre - shift) - s
        turns.append(s)
    run = simulate(SPRING_ON_INCLINE.encode(), samples=4001)
    (stick,) = run.events
    assert stick.kind == "stick" and stick.state["s"] == pytest.approx(turns[-1], abs=1e-9)
    assert stick.time == pytest.approx(len(turns) * math.pi * math.sqrt(m / k), rel=1e-9)
    frame = run.to_dataframe()
    rate, position = frame["s_dot"].to_numpy(), frame["s"].to_numpy()
    reversals = [position[i] for i in range(1, len(rate)) if rate[i - 1] * rate[i] < 0]
    assert reversals == pytest.approx(turns[:-1], abs=2e-3)  # sampled every 2.5 ms, near the turning point
