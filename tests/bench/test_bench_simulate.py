"""The simulation benchmark runs and reports its figures as JSON (speed itself is not tested)."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "simulate.py"


def _bench_module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_simulate", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _run(*args: str) -> dict[str, Any]:
    done = subprocess.run([sys.executable, str(SCRIPT), *args, "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.mark.slow
def test_bench_simulate_json_for_one_problem() -> None:
    result = _run("--repeat", "1", "--only", "pendulum2")

    assert result["repeat"] == 1
    assert result["t_end"] == 10.0
    [row] = result["problems"]
    assert row["name"] == "pendulum2"
    assert row["errors"] == []
    assert row["n"] == 2
    assert row["constraints"] == 0
    for key in ("build_s", "load_s", "form_s", "bind_s", "import_s", "rhs_per_s", "python_rhs_per_s",
                "python_bind_s", "integrate_s", "rhs_share", "lm_build_s", "lm_eqs_s", "lm_rhs_s",
                "lm_lambdify_s", "lm_import_s", "lm_rhs_per_s", "ratio"):
        assert isinstance(row[key], float), key
        assert row[key] > 0, key
    assert isinstance(row["steps"], int) and row["steps"] > 0
    assert isinstance(row["evaluations"], int) and row["evaluations"] >= row["steps"]
    assert row["runs"] == row["lm_runs"] == 1
    assert row["lm_timed_out"] is None
    assert row["agree"] is True, row["check"]
    # the targets are for the 6-link pendulum, which this run leaves out
    assert result["targets"]["problem"] == "pendulum6"
    assert "ratio_pass" not in result["targets"]
    assert result["total_s"] > 0

    text = _bench_module().report(result)
    assert "pendulum2" in text and "exit status is always 0" in text


@pytest.mark.slow
def test_bench_simulate_reports_a_baseline_timeout() -> None:
    result = _run("--repeat", "2", "--only", "pendulum3", "--baseline-timeout", "0.1")

    [row] = result["problems"]
    assert row["n"] == 3
    assert row["runs"] == 2
    assert row["lm_runs"] == 1  # a baseline that timed out is not run again
    assert row["lm_timed_out"]["timeout_s"] == 0.1
    assert row["lm_rhs_per_s"] is None and row["ratio"] is None
    assert row["rhs_per_s"] > 0
    assert row["check"] == "baseline timed out"
    assert "baseline timed out" in _bench_module().report(result)
