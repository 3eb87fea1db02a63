"""The compiled path of sweeps (lagsolve.sweep.native): the same table for every chunking and worker count,
single simulate runs to 1e-9, events (flips, Poincaré crossings) located as on the NumPy path, and the
problems it does not cover (constraints, stick–slip) left to the other paths with the reason."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pandas = pytest.importorskip("pandas")
pytest.importorskip("numba")

import lagsolve  # noqa: E402
from lagsolve.sweep.api import default_workers, sweep  # noqa: E402
from simulation_support import CARTESIAN_PENDULUM as CARTESIAN  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
DOUBLE = ROOT / "problems" / "double_pendulum.yaml"
SPRING = ROOT / "problems" / "spring_on_rough_floor.yaml"
FINALS = ["final_theta1", "final_theta2", "final_theta1_dot", "final_theta2_dot"]


def test_the_table_is_the_same_for_every_chunking_and_worker_count() -> None:
    """Chunks of 1, 7 and all runs, in this process and on 1 or 2 threads: identical tables, crossings and
    flips included (each run is integrated alone, whatever runs share its chunk)."""
    options = {"grid": {"theta1": "-3:3:5", "theta2": "0.5:2.5:3"}, "t_end": 3.0, "rtol": 1e-6,
               "poincare": "theta2=1, theta2_dot>0", "engine": "compiled"}
    whole = sweep(DOUBLE, workers=0, **options)
    assert (whole["path"] == "compiled").all() and whole["flipped"].any() and whole["poincare_count"].sum() > 0
    for workers in (0, 1, 2):
        for size in (1, 7, 15):
            frame = sweep(DOUBLE, workers=workers, chunk_size=size, **options)
            pandas.testing.assert_frame_equal(whole, frame, check_exact=True)


def test_runs_equal_single_simulate_runs_to_1e_9() -> None:
    """At tight tolerances each run's final state equals lagsolve.simulate's to 1e-9, with its steps."""
    frame = sweep(DOUBLE, random={"theta1": (-2.0, 2.0), "theta2": (-2.0, 2.0), "theta2_dot": (-1.0, 1.0)},
                  runs=4, seed=5, t_end=2.0, rtol=1e-12, atol=1e-12, engine="compiled")
    assert (frame["path"] == "compiled").all() and (frame["status"] == "ok").all()
    for _, row in frame.iterrows():
        run = lagsolve.simulate(DOUBLE, t_end=2.0, rtol=1e-12, atol=1e-12,
                                initial={"theta1": row.theta1, "theta2": row.theta2, "theta2_dot": row.theta2_dot})
        final = np.concatenate([run.q[-1], run.qd[-1]])
        assert np.max(np.abs(final - row[FINALS].to_numpy(float))) < 1e-9
        assert row.steps == run.motion.stats["steps"]


def test_events_and_measures_agree_with_the_numpy_path() -> None:
    """Flip times, Poincaré crossings, energy drift and outcomes: the compiled path and the NumPy batched path
    (two implementations of the same step control and event location) agree at tight tolerances."""
    options = {"grid": {"theta1": "-3:3:6", "theta2": "-3:3:5"}, "t_end": 4.0, "rtol": 1e-11, "atol": 1e-12,
               "poincare": "theta2=0, theta2_dot>0"}
    fast, slow = sweep(DOUBLE, engine="compiled", **options), sweep(DOUBLE, engine="numpy", **options)
    assert (slow["path"] == "batched").all() and (fast["path"] == "compiled").all()
    assert list(fast.columns) == list(slow.columns)
    assert fast["outcome"].tolist() == slow["outcome"].tolist() and fast["flipped"].any()
    np.testing.assert_allclose(fast["flip_time"], slow["flip_time"], atol=1e-8)
    np.testing.assert_allclose(fast[FINALS], slow[FINALS], atol=1e-7)
    assert fast["poincare_count"].tolist() == slow["poincare_count"].tolist() and fast["poincare_count"].sum() > 0
    for column in ("poincare_t", "poincare_theta1", "poincare_theta1_dot"):
        for ours, theirs in zip(fast[column], slow[column], strict=True):
            np.testing.assert_allclose(ours, theirs, atol=1e-7)
    np.testing.assert_allclose(fast["energy_drift"], slow["energy_drift"], rtol=0.2, atol=1e-9)


LOG_WIRE = """
name: Bead on y = log(x), in its own coordinate
parameters: {m: mass, g: gravity}
coordinates: [x]
particles: {bead: {mass: m, position: [x, log(x)]}}
gravity: [0, -g]
simulation:
  values: {m: 1.0, g: 9.81}
  initial: {x: 0.5, x_dot: -1.0}
  t_end: 5.0
"""


def test_a_run_that_leaves_the_domain_fails_alone_with_the_reason() -> None:
    """A bead on y = log(x) that reaches x = 0 fails, with the reason the NumPy path gives; a bead starting
    farther up the wire goes on."""
    options = {"grid": {"x": [0.5, 20.0]}, "t_end": 3.0}
    fast, slow = sweep(LOG_WIRE, engine="compiled", **options), sweep(LOG_WIRE, engine="numpy", **options)
    assert fast["path"].tolist() == ["compiled"] * 2
    assert fast["status"].tolist() == slow["status"].tolist() == ["failed", "ok"]
    assert fast["reason"][0].split(" at t = ")[0] == slow["reason"][0].split(" at t = ")[0]
    assert abs(fast["t_final"][0] - slow["t_final"][0]) < 1e-6


def test_problems_the_compiled_path_does_not_cover_take_the_others() -> None:
    """Constraints go to the batched NumPy path (it projects onto them), stick–slip to simulate's integrator:
    the path column says which; the table is the one the NumPy engine gives."""
    constrained = sweep(CARTESIAN, grid={"x": [0.2, 0.5]}, t_end=1.0, engine="compiled")
    assert (constrained["path"] == "batched").all()
    assert (constrained["note"] == "not compiled: constraints (the batched path projects onto them)").all()
    options = {"grid": {"x": [0.3, 0.5]}, "t_end": 2.0}
    friction = sweep(SPRING, engine="compiled", **options)
    assert friction["path"].str.startswith("per run: friction contacts").all()
    assert friction["stick_count"].sum() > 0
    pandas.testing.assert_frame_equal(friction, sweep(SPRING, engine="numpy", **options), check_exact=True)


def test_the_default_workers_follow_the_run_count() -> None:
    """In process for small sweeps and on the other paths; threads for large compiled sweeps."""
    assert default_workers(10, True) == 0 and default_workers(100_000, False) == 0
    assert default_workers(10_000, True) >= 1 and default_workers(100, False, batched=True) == 0


def test_a_run_that_starts_outside_the_domain_fails_and_the_chunk_goes_on() -> None:
    """x = 0 on y = log(x): the compiled code divides by zero there (NumPy's error model: an infinity, not an
    exception), so that run fails at its start with the NumPy path's reason and the others run."""
    options = {"grid": {"x": [0.0, 20.0]}, "t_end": 0.5}
    fast, slow = sweep(LOG_WIRE, engine="compiled", **options), sweep(LOG_WIRE, engine="numpy", **options)
    assert fast["path"].tolist() == ["compiled"] * 2
    assert fast["status"].tolist() == slow["status"].tolist() == ["failed", "ok"]
    assert fast["reason"][0] == slow["reason"][0]


def test_the_kernel_as_plain_python_gives_the_compiled_numbers() -> None:
    """The generated module run by the interpreter (no Numba) integrates two runs, with a section, to the
    numbers of its compiled form: the compiled path is the kernel's text, nothing else."""
    import importlib.util

    from lagsolve.sweep import native
    from lagsolve.sweep.run import compiled

    problem = compiled(DOUBLE.read_text(encoding="utf-8"), str(DOUBLE))
    text, why = native.source(problem.system)
    assert text is not None, why
    path = native._written(text, "lagsolve_sweep_plain_python_test")
    spec = importlib.util.spec_from_file_location("lagsolve_sweep_plain_python_test", path)
    assert spec is not None and spec.loader is not None
    plain = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plain)
    fast = problem.native()[0]
    y0 = np.array([[0.3, 0.2, 0.0, 0.0], [2.5, -1.0, 0.5, 0.0]])
    p = np.tile(np.asarray(problem.system.parameters, dtype=float), (2, 1))
    angular = np.array(problem.angular, dtype=bool)
    slow = native.NativeSystem(2, fast.n_conserved, plain).integrate(y0, p, 1.0, "DOP853", 1e-8, 1e-10, angular,
                                                                      (1, 0.0))
    ours = fast.integrate(y0, p, 1.0, "DOP853", 1e-8, 1e-10, angular, (1, 0.0))
    assert slow[2].tolist() == ours[2].tolist() and slow[3].tolist() == ours[3].tolist()  # steps, end codes
    for mine, theirs in zip(slow, ours, strict=True):
        np.testing.assert_allclose(np.asarray(mine, dtype=float), np.asarray(theirs, dtype=float), rtol=1e-12,
                                   atol=1e-12)


@pytest.mark.parametrize("method", ["RK45", "RK23"])
def test_the_other_explicit_methods_take_the_numpy_paths_steps(method: str) -> None:
    """RK45 and RK23 on the compiled path (their own dense output for the crossings): the steps, final states
    and crossings of the batched NumPy path."""
    options = {"grid": {"theta1": [0.4, 1.2], "theta2": [0.3, -0.8]}, "t_end": 2.0, "rtol": 1e-9, "atol": 1e-11,
               "method": method, "poincare": "theta2=0"}
    fast, slow = sweep(DOUBLE, engine="compiled", **options), sweep(DOUBLE, engine="numpy", **options)
    assert fast["steps"].tolist() == slow["steps"].tolist()
    np.testing.assert_allclose(fast[FINALS], slow[FINALS], atol=1e-9)
    assert fast["poincare_count"].tolist() == slow["poincare_count"].tolist() and fast["poincare_count"].sum() > 0
    for ours, theirs in zip(fast["poincare_t"], slow["poincare_t"], strict=True):
        np.testing.assert_allclose(ours, theirs, atol=1e-9)


def test_nothing_is_written_without_a_cache_folder_named(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """With $LAGSOLVE_CACHE unset, the compiled path keeps its module in memory (nothing in the home or temporary
    folder), and ``auto`` keeps sweeps on the NumPy path until the compilation in each process is won back; a
    symbolic link in the cache folder is not followed."""
    from lagsolve.sweep import api, native

    monkeypatch.delenv("LAGSOLVE_CACHE", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setattr(native.tempfile, "tempdir", str(tmp_path))
    assert native.cache_folder() is None and native._written("x = 1\n", "lagsolve_sweep_test") is None
    module = native._module("def f(a):\n    return 2 * a\n", "lagsolve_sweep_memory", None)
    assert module.f(3) == 6
    assert list(tmp_path.iterdir()) == []
    if native.numba_available():
        assert api._engine("auto", 10_000, "DOP853") == "numpy"
        assert api._engine("auto", api.UNCACHED_FROM, "DOP853") == "compiled"
    folder = tmp_path / "cache"
    monkeypatch.setenv("LAGSOLVE_CACHE", str(folder))
    assert native._written("x = 1\n", "lagsolve_sweep_a") == folder / "sweep" / "lagsolve_sweep_a.py"
    (folder / "sweep" / "lagsolve_sweep_b.py").symlink_to(tmp_path / "elsewhere.py")
    assert native._written("x = 1\n", "lagsolve_sweep_b") is None
    if native.numba_available():
        assert api._engine("auto", 10_000, "DOP853") == "compiled"
