"""The grading benchmark runs and reports its figures as JSON (speed itself is not tested)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "grade.py"


@pytest.mark.slow
def test_bench_grade_json_shape() -> None:
    done = subprocess.run([sys.executable, str(SCRIPT), "--count", "4", "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["count"] == 4
    for key in ("grade_s", "grade_wall_s", "per_submission_s", "reference_s", "target_s"):
        assert isinstance(result[key], int | float) and result[key] >= 0
    assert result["result"] in ("PASS", "MISS")
    assert "LagrangesMethod" in result["reference"]
    assert result["correct"] + result["wrong"] == 4
    assert 0 <= result["mistakes_found"] <= result["wrong"]
    assert 0 <= result["correct_full_marks"] <= result["correct"]
