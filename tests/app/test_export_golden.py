"""The exported bead and rotating tube (Python and C) equal the reviewed copies in tests/golden/export, byte for
byte, whatever PYTHONHASHSEED (``make golden`` rewrites them)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import lagsolve

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "golden" / "export"
FILES = {"python": (".py",), "c": (".h", ".c")}


@pytest.mark.parametrize("name", ["bead", "rotating_tube"])
@pytest.mark.parametrize("to", ["python", "c"])
def test_export_equals_the_golden_copy(name: str, to: str, tmp_path: Path) -> None:
    lagsolve.export(ROOT / "problems" / f"{name}.yaml", to=to, output=tmp_path)
    for suffix in FILES[to]:
        assert (tmp_path / f"{name}{suffix}").read_bytes() == (GOLDEN / f"{name}{suffix}").read_bytes(), suffix


@pytest.mark.parametrize("seed", ["0", "12345"])
def test_export_is_byte_identical_under_any_hash_seed(seed: str, tmp_path: Path) -> None:
    for to in ("python", "c"):
        subprocess.run([sys.executable, "-m", "lagsolve", "export", str(ROOT / "problems" / "rotating_tube.yaml"),
                        "--to", to, "-o", str(tmp_path)], check=True, capture_output=True,
                       env={**os.environ, "PYTHONHASHSEED": seed})
    for suffix in (".py", ".h", ".c"):
        assert (tmp_path / f"rotating_tube{suffix}").read_bytes() == (GOLDEN / f"rotating_tube{suffix}").read_bytes()
