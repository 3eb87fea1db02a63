"""The stage-margin benchmark derives a problem and reports every stage it ran with its CPU use and slice (the
figures themselves are not tested)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "margins.py"


def test_bench_margins_json_for_one_problem() -> None:
    """The double pendulum: its equilibria stage and the others that ran are listed, each finished, with a
    positive slice, a use and their ratio, sorted by the ratio; the count of flagged stages matches the rows."""
    done = subprocess.run([sys.executable, str(SCRIPT), "double_pendulum", "--json"], cwd=ROOT,
                          capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["problems"] == ["double_pendulum"]
    rows = result["stages"]
    assert "equilibria and normal modes" in {r["stage"] for r in rows}
    assert all(r["problem"] == "double_pendulum" and r["finished"] for r in rows)
    assert all(r["slice_s"] > 0 and r["used_s"] >= 0 for r in rows)
    assert [r["ratio"] for r in rows] == sorted((r["ratio"] for r in rows), reverse=True)
    assert result["flagged"] == sum(r["flagged"] for r in rows)
