"""Stick–slip: contacts that come to rest stick while friction can hold them and slip again beyond μ_s N."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from lagsolve.mechanics.matrix_form import matrix_form
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
