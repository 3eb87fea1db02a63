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


def test_bench_margins_takes_a_name_or_a_path() -> None:
    """``bead`` is the shipped problem; a path (an unshipped problem's) is taken as it is, not looked up in
    problems/ (it was read as problems/problems/bead.yaml.yaml, a traceback)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_margins", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module._problem_file("bead") == ROOT / "problems" / "bead.yaml"
    assert module._problem_file("/tmp/elsewhere/rod.yaml") == Path("/tmp/elsewhere/rod.yaml")
    assert module._problem_file("problems/bead.yml") == Path("problems/bead.yml")
