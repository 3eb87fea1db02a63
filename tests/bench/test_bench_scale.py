"""The scaling benchmark runs and reports its figures as JSON (speed itself is not tested)."""

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
SCRIPT = ROOT / "bench" / "scale.py"
CELLS = ("cli_derive", "lib_derive", "core", "build", "sim_run", "lm_total", "kane_core", "kane_total")


def _bench_module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_scale", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the class is made
    spec.loader.exec_module(module)
    return module


def _run(*args: str) -> dict[str, Any]:
    done = subprocess.run([sys.executable, str(SCRIPT), *args, "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.mark.slow
def test_bench_scale_json_for_the_2_link_pendulum() -> None:
    """One run at n = 2 fills every cell and ratio with a positive figure and lists the four targets."""
    result = _run("--only-n", "2", "--repeat", "1", "--cap", "60", "--skip-problems")

    assert result["sizes"] == [2]
    assert result["repeat"] == 1
    assert result["cap_s"] == 60.0
    assert result["t_end"] == 10.0
    assert set(result["columns"]) == set(CELLS)
    assert {column["clock"] for column in result["columns"].values()} == {"cpu", "wall"}
    [row] = result["rows"]
    assert row["n"] == 2
    assert set(row["cells"]) == set(CELLS)
    for key, cell in row["cells"].items():
        assert cell["error"] is None, (key, cell["error"])
        assert cell["capped"] is False, key
        assert isinstance(cell["seconds"], float) and cell["seconds"] > 0, key
        assert cell["runs"] == 1, key
    for key in ("derive", "core"):
        assert row["ratios"][key]["bound"] == "exact"
        assert row["ratios"][key]["value"] > 0
    assert result["problems"] is None
    targets = {t["name"]: t for t in result["targets"]}
    assert set(targets) == {"problems", "derive_vs_lm", "core_vs_kane", "simulate", "issue33_derive_20",
                            "issue33_derive_50", "issue33_simulate"}
    assert all(t["verdict"] in ("PASS", "MISS", "n/a") for t in targets.values())
    # the targets at n = 6 and n = 12, and the problems/ sweep, were not measured
    assert targets["problems"]["verdict"] == "n/a"
    assert targets["core_vs_kane"]["verdict"] == "n/a"
    assert targets["simulate"]["verdict"] == "n/a"
    for name in ("issue33_derive_20", "issue33_derive_50", "issue33_simulate"):  # n = 20 and 50 not measured
        assert targets[name]["verdict"] == "n/a", name
    assert result["total_s"] > 0

    text = _bench_module().report(result)
    assert "derive ratio" in text and "exit status is always 0" in text


@pytest.mark.slow
def test_bench_scale_shows_a_capped_measurement() -> None:
    """A cap shorter than any measurement turns every cell into "> cap" and the script still exits 0."""
    result = _run("--only-n", "2", "--repeat", "2", "--cap", "0.05", "--skip-problems")

    [row] = result["rows"]
    for key, cell in row["cells"].items():
        assert cell["capped"] is True, key
        assert cell["seconds"] is None, key
        assert cell["runs"] == 1, key  # a capped measurement is not repeated
        assert cell["at_least"] is None or cell["at_least"] >= 0, key
    assert row["cells"]["cli_derive"]["at_least"] >= 0.05  # a wall column: the time until it was stopped
    assert row["ratios"]["derive"] == {"value": None, "bound": None}
    assert "> cap" in _bench_module().report(result)


def test_ratio_bounds() -> None:
    """A capped side turns the ratio into a bound, from the time it had run when it was stopped."""
    ratio = _bench_module()._ratio
    done = {"seconds": 2.0, "capped": False, "at_least": None}
    capped = {"seconds": None, "capped": True, "at_least": 50.0}
    unknown = {"seconds": None, "capped": True, "at_least": None}
    assert ratio(done, {"seconds": 1.0, "capped": False, "at_least": None}) == {"value": 2.0, "bound": "exact"}
    assert ratio(capped, done) == {"value": 25.0, "bound": "lower"}
    assert ratio(done, capped) == {"value": 2.0 / 50.0, "bound": "upper"}
    assert ratio(capped, capped) == {"value": None, "bound": None}
    assert ratio(unknown, done) == {"value": None, "bound": None}
