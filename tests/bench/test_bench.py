"""The benchmark script runs and reports its figures as JSON (speed itself is not tested)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "derive.py"


@pytest.mark.slow
def test_bench_json_for_one_problem() -> None:
    done = subprocess.run(
        [sys.executable, str(SCRIPT), "--repeat", "1", "--only", "bead", "--json"],
        cwd=ROOT, capture_output=True, text=True, timeout=300, check=False,
    )
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)

    assert result["repeat"] == 1
    assert result["skipped"] == []
    [row] = result["problems"]
    assert row["name"] == "bead"
    assert row["errors"] == []
    for key in ("lagsolve_s", "lagsolve_load_s", "lagsolve_derive_s", "lagsolve_tidy_s",
                "lm_s", "lm_build_s", "lm_solve_s", "lm_finish_s", "target_s"):
        assert isinstance(row[key], float), key
        assert row[key] > 0, key
    assert len(row["lagsolve_runs_s"]) == len(row["lm_runs_s"]) == 1
    assert isinstance(row["pass"], bool)
    assert isinstance(row["agree"], bool)
    assert isinstance(row["check"], str)

    startup = result["startup"]
    for key in ("help_s", "help_target_s", "import_cli_s", "python_s"):
        assert isinstance(startup[key], float), key
        assert startup[key] > 0, key
    assert len(startup["help_runs_s"]) == 5
    assert isinstance(startup["help_pass"], bool)
    assert result["total_s"] > 0
