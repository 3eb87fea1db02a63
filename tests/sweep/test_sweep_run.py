"""Sweeps (lagsolve.sweep): each run equals a single simulate run, numbers do not depend on chunking,
and events and outcomes agree with closed forms and with independent routes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pandas = pytest.importorskip("pandas")

import lagsolve  # noqa: E402
from lagsolve.sweep.api import sweep  # noqa: E402
from simulation_support import CARTESIAN_PENDULUM as CARTESIAN  # noqa: E402
from simulation_support import PUCK  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
DOUBLE = ROOT / "problems" / "double_pendulum.yaml"
SPRING = ROOT / "problems" / "spring_on_rough_floor.yaml"
INCLINE = ROOT / "problems" / "rough_incline.yaml"


def test_batched_runs_equal_single_simulate_runs() -> None:
    """At several random points the batched final state equals lagsolve.simulate's to the tolerance."""
    frame = sweep(DOUBLE, random={"theta1": (-2.0, 2.0), "theta2": (-2.0, 2.0), "theta2_dot": (-1.0, 1.0)},
                  runs=5, seed=3, t_end=3.0)
    assert (frame["path"] == "batched").all()
    for _, row in frame.iterrows():
        run = lagsolve.simulate(DOUBLE, t_end=3.0, initial={"theta1": row.theta1, "theta2": row.theta2,
                                                            "theta2_dot": row.theta2_dot})
        final = np.concatenate([run.q[-1], run.qd[-1]])
        ours = row[["final_theta1", "final_theta2", "final_theta1_dot", "final_theta2_dot"]].to_numpy(float)
        assert np.max(np.abs(final - ours)) < 1e-8
        assert row.steps == run.motion.stats["steps"]  # the same steps: SciPy's step control per run


def test_constrained_runs_are_projected_and_equal_simulate() -> None:
    """A Cartesian pendulum (a holonomic constraint) runs batched with projection and matches simulate
    (which integrates it in minimal coordinates): a second route to the same motion."""
    frame = sweep(CARTESIAN, grid={"x": [0.2, 0.5, 0.8]}, t_end=2.0)
    assert (frame["path"] == "batched").all()
    assert frame["max_residual"].max() < 1e-8
    for _, row in frame.iterrows():
        run = lagsolve.simulate(CARTESIAN, t_end=2.0, initial={"x": row.x})
        assert abs(run.q[-1, 0] - row.final_x) < 1e-7 and abs(run.q[-1, 1] - row.final_y) < 1e-7
    assert frame["drift_energy"].max() < 1e-8


def test_a_micro_pendulum_is_projected_at_its_own_scale() -> None:
    """The Cartesian pendulum 100 nm long for 30 periods, batched with projection: each run's final state equals
    simulate's (in minimal coordinates, a second route) to 1e-6 of l, and the rod holds to 1e-12 of l² (the
    projection's threshold is scaled to the constraint, as simulate's is; with an absolute 1e-15 m² it never
    projected here, and the rod drifted by 1.3e-8 of l²)."""
    length = 1e-7
    text = CARTESIAN.replace("l: 1.0}", f"l: {length!r}}}").encode()
    t_end = 30 * 2 * math.pi * math.sqrt(length / 9.81)
    frame = sweep(text, grid={"x": [0.2 * length, 0.5 * length, 0.8 * length]}, t_end=t_end)
    assert (frame["path"] == "batched").all()
    for _, row in frame.iterrows():
        run = lagsolve.simulate(text, t_end=t_end, initial={"x": row.x})
        assert abs(run.q[-1, 0] - row.final_x) < 1e-6 * length and abs(run.q[-1, 1] - row.final_y) < 1e-6 * length
        assert abs(row.final_x**2 + row.final_y**2 - length**2) < 1e-12 * length**2


def test_results_do_not_depend_on_chunking() -> None:
    """One chunk, chunks of one run and chunks of three give identical tables."""
    options = {"grid": {"theta1": "-2:2:4", "theta2": "0.5:2.5:3"}, "t_end": 2.0, "poincare": "theta2=0"}
    whole = sweep(DOUBLE, **options)
    for size in (1, 3):
        pandas.testing.assert_frame_equal(whole, sweep(DOUBLE, chunk_size=size, **options), check_exact=True)


def test_flips_only_where_the_energy_allows() -> None:
    """The lower rod can pass upright only if 2 cos θ1 + cos θ2 <= 1 (energy conservation); some runs do."""
    frame = sweep(DOUBLE, grid={"theta1": "-3:3:9", "theta2": "-3:3:9"}, t_end=5.0, rtol=1e-8, atol=1e-10)
    bound = 2 * np.cos(frame["theta1"]) + np.cos(frame["theta2"]) > 1
    assert not frame.loc[bound, "flipped"].any()
    assert frame["flipped"].any()
    assert set(frame["outcome"]) == {"flipped", "no flip"}
    flips = frame[frame["flipped"]]
    assert ((flips["flip_time"] >= 0) & (flips["flip_time"] <= 5)).all()
    assert frame.loc[~frame["flipped"], "flip_time"].isna().all()


def test_poincare_crossings_match_solve_ivp_events() -> None:
    """Section crossings lie on the section, meet its condition, and agree with SciPy's event location
    on an independent right-hand side (the textbook equations of the double pendulum)."""
    from scipy.integrate import solve_ivp

    frame = sweep(DOUBLE, grid={"theta1": [0.4, 1.0]}, t_end=6.0, poincare="theta2=0, theta2_dot>0")
    g = 9.81

    def rhs(t: float, y: np.ndarray) -> list[float]:  # Taylor 11.4 with m = l = 1: M(θ) θ̈ = f
        a, b, ad, bd = y
        c, s = math.cos(a - b), math.sin(a - b)
        mass = np.array([[2.0, c], [c, 1.0]])
        force = np.array([-s * bd**2 - 2 * g * math.sin(a), s * ad**2 - g * math.sin(b)])
        return [ad, bd, *np.linalg.solve(mass, force)]

    def event(t: float, y: np.ndarray) -> float:
        return y[1]

    event.direction = 1  # type: ignore[attr-defined]
    for _, row in frame.iterrows():
        reference = solve_ivp(rhs, (0, 6.0), [row.theta1, 0.3, 0, 0], method="DOP853", rtol=1e-11, atol=1e-12,
                              events=event)
        times = reference.t_events[0]
        assert row.poincare_count == len(times) > 0
        assert np.max(np.abs(np.array(row.poincare_t) - times)) < 1e-7
        assert np.all(np.array(row.poincare_theta2) == 0.0)
        assert np.all(np.array(row.poincare_theta2_dot) > 0)
        assert np.max(np.abs(np.array(row.poincare_theta1) - reference.y_events[0][:, 0])) < 1e-7


def _spring_rest(x0: float) -> tuple[float, float]:
    """Closed form of the spring block (m = 1, k = 10, g = 9.81, μ = 0.1, μ_s = 0.15): each half swing is a
    half oscillation about ±μmg/k; it sticks at the first turning point with k|x| <= μ_s m g."""
    m, k, g, mu, mu_s = 1.0, 10.0, 9.81, 0.1, 0.15
    a, x, t = mu * m * g / k, x0, 0.0
    while k * abs(x) > mu_s * m * g:
        x = -(x - 2 * a * np.sign(x))
        t += math.pi * math.sqrt(m / k)
    return x, t


def test_spring_block_sticks_where_the_closed_form_says() -> None:
    """Stick time and resting place of the spring block on a rough floor, over a grid of starting points,
    equal the closed form, and a run that starts inside the band |x| <= μ_s m g / k never moves."""
    frame = sweep(SPRING, grid={"x": "-1.2:1.2:13"}, t_end=8.0)
    assert frame["path"].str.startswith("per run").all()
    for _, row in frame.iterrows():
        rest, when = _spring_rest(row.x)
        assert row.outcome == "stick" and row.stuck_at_end
        assert abs(row.final_x - rest) < 1e-6
        assert abs(row.stick_times[-1] - when) < 1e-6
        assert (row.stick_times[-1] == 0.0) == (10.0 * abs(row.x) <= 0.15 * 9.81)


def test_spring_block_equals_single_runs() -> None:
    """The per-run path is simulate's integrator: the same final state and events."""
    frame = sweep(SPRING, grid={"x": [0.7], "mu_s": [0.12, 0.3]}, t_end=8.0)
    for _, row in frame.iterrows():
        run = lagsolve.simulate(SPRING, t_end=8.0, initial={"x": 0.7}, values={"mu_s": row.mu_s})
        assert abs(run.q[-1, 0] - row.final_x) < 1e-12
        assert [e.time for e in run.events if e.kind == "stick"] == row.stick_times


def test_incline_sticks_iff_tan_alpha_at_most_mu() -> None:
    """A block at rest on a rough incline (μ_s = μ = 0.3) stays iff tan α <= μ."""
    frame = sweep(INCLINE, grid={"alpha": "0.05:0.6:12", "s_dot": [0.0]}, t_end=1.0)
    for _, row in frame.iterrows():
        sticks = math.tan(row.alpha) <= 0.3
        assert (row.outcome == "stick") == sticks
        assert (abs(row.final_s) < 1e-12) == sticks


def test_a_failed_run_says_why_and_the_others_go_on() -> None:
    """A start off the constraint (x = 2 on a rod of length 1) fails with its reason; the other run is ok."""
    frame = sweep(CARTESIAN, grid={"x": [0.5, 2.0]}, t_end=0.5)
    assert list(frame["status"]) == ["ok", "failed"]
    assert "violate the constraints" in frame["reason"][1]
    assert frame["outcome"][1] == "failed"


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


def _finite_where_ok(frame: object) -> None:
    """Every run reported ok or released has every value it measured finite."""
    measured = [c for c in frame.columns if c.startswith(("final_", "drift_"))]  # type: ignore[attr-defined]
    measured += ["t_final", "max_residual", "energy_drift"]
    good = frame[frame["status"] != "failed"]  # type: ignore[index]
    assert np.isfinite(good[measured].to_numpy(float)).all()


@pytest.mark.parametrize("method", ["DOP853", "Radau"])
def test_a_run_that_leaves_the_domain_fails_as_simulate_does(method: str) -> None:
    """A bead on y = log(x) reaches x = 0 at t ≈ 2.6, where simulate stops ("no longer finite"): the sweep
    reports that run failed, with when and why, never ok with an empty residual (batched and per run)."""
    with pytest.raises(lagsolve.errors.SimulationError, match="no longer finite at t = 2.6"):
        lagsolve.simulate(LOG_WIRE, t_end=5.0)
    frame = sweep(LOG_WIRE, grid={"m": [1.0, 2.0]}, t_end=5.0, method=method)
    assert list(frame["status"]) == ["failed", "failed"] and list(frame["outcome"]) == ["failed", "failed"]
    for reason in frame["reason"]:
        assert "no longer finite at t = " in reason
    if method == "DOP853":  # batched: stopped at the step where it happened, as simulate does
        assert all("no longer finite at t = 2.6" in reason for reason in frame["reason"])
        assert (frame["t_final"] < 2.7).all()
    _finite_where_ok(frame)
    short = sweep(LOG_WIRE, grid={"m": [1.0]}, t_end=1.0, method=method)  # before x reaches 0: ok
    assert list(short["status"]) == ["ok"]
    _finite_where_ok(short)


def test_a_row_with_a_value_that_is_not_finite_is_not_ok() -> None:
    """The status rule: an ok or released row with any measured value NaN (the residual, a drift, the release
    state) is failed, and the reason names those columns."""
    from lagsolve.sweep.run import _settle

    base = {"status": "ok", "reason": "", "t_final": 1.0, "final_x": 0.5, "final_x_dot": 0.1,
            "max_residual": math.nan, "energy_drift": 0.0, "drift_energy": math.inf, "flipped": False,
            "flip_time": math.nan, "stuck_at_end": False, "release_time": math.nan, "release_x": math.nan}
    row = dict(base)
    _settle(row, False, False)
    assert row["status"] == "failed" and row["outcome"] == "failed"
    assert row["reason"].startswith("max_residual, drift_energy are not finite")
    released = {**base, "status": "released", "max_residual": 0.0, "drift_energy": 0.0, "release_time": 0.5}
    _settle(released, False, False)
    assert released["status"] == "failed" and released["reason"].startswith("release_x is not finite")
    fine = {**base, "max_residual": 0.0, "drift_energy": 0.0}
    _settle(fine, False, False)
    assert fine["status"] == "ok" and fine["outcome"] == "ok"  # flip_time and release_* may be NaN: no event


def test_random_inputs_repeat_with_the_seed() -> None:
    """The same seed gives the same inputs and results; another seed other inputs."""
    one = sweep(DOUBLE, random=["theta1=0:1", "l=0.5:2"], runs=4, seed=7, t_end=0.5)
    assert one.equals(sweep(DOUBLE, random=["theta1=0:1", "l=0.5:2"], runs=4, seed=7, t_end=0.5))
    assert not np.array_equal(one["theta1"], sweep(DOUBLE, random=["theta1=0:1"], runs=4, seed=8, t_end=0.5)["theta1"])
    assert one["l"].between(0.5, 2).all()


def test_release_from_a_sphere_where_the_closed_form_says() -> None:
    """A particle launched along the top of a smooth sphere with speed v₀ leaves it where
    cos θ = (v₀²/(g R) + 2 cos θ₀)/3 (energy and the radial equation with N = 0); the rows say
    released, when, and where."""
    sphere = ROOT / "problems" / "sliding_off_sphere.yaml"
    frame = sweep(sphere, grid={"x_dot": "0.2:2.8:6"}, t_end=5.0)
    g, radius = 9.81, 1.0
    x0, y0 = 0.001, 0.9999995
    for _, row in frame.iterrows():
        assert row.status == "released" and row.outcome == "released"
        assert row.release_constraint == "surface" and 0 < row.release_time == row.t_final
        speed2 = row.x_dot**2 + (x0 * row.x_dot / y0) ** 2  # y_dot from x x_dot + y y_dot = 0
        cos_release = (speed2 / (g * radius) + 2 * y0 / radius) / 3
        assert abs(row.release_y - radius * cos_release) < 1e-6
        assert row.path.startswith("per run: unilateral constraints")


@pytest.mark.slow
@pytest.mark.parametrize("path", sorted((ROOT / "problems").glob("*.yaml")), ids=lambda p: p.stem)
def test_every_shipped_problem_matches_simulate(path: Path) -> None:
    """Each shipped problem with a simulation block, swept over one point (its first parameter's file value),
    ends where lagsolve.simulate ends (batched with projection, or per run), at the same time."""
    problem = lagsolve.load_problem(path)
    values = dict(problem.simulation.values) if problem.simulation is not None else {}
    if problem.simulation is None or problem.simulation.t_end is None or problem.parameters[0].name not in values:
        pytest.skip("no simulation block with values")
    name = problem.parameters[0].name
    t_end = min(problem.simulation.t_end, 2.0)
    row = sweep(path, grid={name: [values[name]]}, t_end=t_end).iloc[0]
    run = lagsolve.simulate(path, t_end=t_end)
    assert row.status in ("ok", "released"), row.reason
    assert row.t_final == pytest.approx(run.t[-1], abs=1e-12)
    ours = np.array([row[f"final_{c}"] for c in run.coordinates])
    assert np.max(np.abs(ours - run.q[-1])) < 1e-8
    assert row.max_residual < 1e-8


def test_a_puck_that_comes_to_rest_stops_its_run_with_a_note() -> None:
    """Friction in a plane is modelled only while the contact slides: each run stops where the puck comes to rest,
    at |v0|/(mu g) (closed form), and its note says so (the per-run path: a friction contact)."""
    frame = sweep(PUCK.encode(), grid={"x_dot": [0.5, 1.0]}, t_end=3.0)
    for _, row in frame.iterrows():
        speed = math.hypot(row.x_dot, 0.5)
        assert row.status == "ok" and row.t_final == pytest.approx(speed / (0.1 * 9.81), rel=1e-8)
        assert "contact 'rub' comes to rest" in row.note
