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
