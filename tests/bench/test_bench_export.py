"""The export benchmark runs and reports its figures as JSON (speed itself is not tested)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "export.py"


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("cc") is None and shutil.which("gcc") is None, reason="no C compiler")
def test_bench_export_json_shape() -> None:
    done = subprocess.run([sys.executable, str(SCRIPT), "--n", "2", "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["n"] == 2
    for key in ("export_c_s", "export_python_s", "reference_s", "compile_s", "reference_compile_s", "total_s"):
        assert isinstance(result[key], int | float) and result[key] >= 0
    assert result["result"] in ("PASS", "MISS") and result["agree"] is True
    assert "LagrangesMethod" in result["reference"]
