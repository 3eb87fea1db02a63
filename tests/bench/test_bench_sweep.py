"""The sweep benchmark runs in a tiny configuration and reports its figures as JSON (speed is not tested)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pandas")

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "sweep.py"


@pytest.mark.slow
def test_bench_sweep_json() -> None:
    """Nine runs in process, two timed single runs per loop: every route agrees with the sweep's rows and
    each ratio is a positive number next to its target."""
    done = subprocess.run([sys.executable, str(SCRIPT), "--runs", "9", "--sample", "2", "--t-end", "0.5",
                           "--workers", "0", "--json"], cwd=ROOT, capture_output=True, text=True, timeout=600,
                          check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["runs"] == 9 and result["sample"] == 2
    assert result["sweep"]["0"]["failed"] == 0 and result["sweep"]["0"]["runs_per_s"] > 0
    for route in ("simulate", "solve_ivp"):
        assert result[route]["max_difference"] < 1e-7
        assert result["targets"][route]["ratio"] > 0
    assert set(result["targets"]) == {"simulate", "solve_ivp"}
