"""The variants benchmark runs in a tiny configuration and reports its figures as JSON (speed is not tested)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "variants.py"


@pytest.mark.slow
def test_bench_variants_json() -> None:
    done = subprocess.run([sys.executable, str(SCRIPT), "--count", "2", "--sample", "1", "--json"], cwd=ROOT,
                          capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["count"] == 2 and result["reference"]["sample"] == 1
    assert result["per_variant_s"]["cpu"] > 0 and result["speed_up"]["cpu"] > 0
    assert result["target_s"] == 1.0 and isinstance(result["pass"], bool)
