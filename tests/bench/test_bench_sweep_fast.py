"""The compiled-sweep benchmark runs in a tiny configuration and reports its figures as JSON (speed is not
tested: only that every route ran, agreed, and each target has a verdict)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pandas")
pytest.importorskip("numba")

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "sweep_fast.py"


@pytest.mark.slow
def test_bench_sweep_fast_json() -> None:
    """Sixteen runs, two solve_ivp runs: the compiled sweep ran with 0, 1 and 2 workers and no run failed; the
    sample agrees with it; both targets carry a figure and a verdict."""
    done = subprocess.run([sys.executable, str(SCRIPT), "--runs", "16", "--sample", "2", "--json"], cwd=ROOT,
                          capture_output=True, text=True, timeout=900, check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["runs"] == 16
    assert {figures["path"] for figures in result["sweep"].values()} == {"compiled"}
    assert all(figures["failed"] == 0 for figures in result["sweep"].values())
    assert result["solve_ivp"]["max_difference"] < 1e-3  # rtol 1e-6 over 10 s of a pendulum at these angles
    assert result["rk4"]["seconds"] > 0
    for target in result["targets"].values():
        assert target["value"] > 0 and isinstance(target["met"], bool)


def test_bench_sweep_fast_shows_a_ratio_it_could_not_measure(capsys: pytest.CaptureFixture[str]) -> None:
    """A sweep too short for the threads' clock (10 ms ticks) has no CPU ratio: the table says "not measured"
    where it would divide by zero (a 16-run sweep once did, failing the test above)."""
    import importlib.util

    loaded = importlib.util.spec_from_file_location("sweep_fast_bench", SCRIPT)
    assert loaded is not None and loaded.loader is not None
    bench = importlib.util.module_from_spec(loaded)
    loaded.loader.exec_module(bench)
    figures = {"seconds": 0.1, "cpu_seconds": 0.0, "failed": 0, "path": "compiled"}
    bench.show({"runs": 16, "t_end": 10.0, "cpus": 2, "load_before": 0.1, "load_after": 0.1, "loaded": False,
                "first_call": {"seconds": 1.0, "cpu_seconds": 1.0}, "sweep": {"0": figures, "1": figures, "2": figures},
                "rk4": {"seconds": 0.1, "cpu_seconds": 0.1},
                "solve_ivp": {"seconds": 1.0, "cpu_seconds": 1.0, "max_difference": 1e-9},
                "targets": {"seconds": {"target": 1.5, "value": 0.1, "cpu_value": 0.0, "met": True},
                            "workers": {"target": 1.7, "value": 1.0, "cpu_value": None, "met": False}}})
    assert "one worker's CPU over that) not measured" in capsys.readouterr().out
