"""The documentation site (mkdocs + mkdocstrings) builds with --strict, and the API reference comes from docstrings."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_mkdocs_builds_strict(tmp_path: Path) -> None:
    """`mkdocs build --strict` succeeds and the API page holds the docstrings of derive and Trajectory."""
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings")
    site = tmp_path / "site"
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                            cwd=ROOT, capture_output=True, text=True, timeout=600, check=False)
    assert result.returncode == 0, result.stderr
    page = (site / "api" / "index.html").read_text(encoding="utf-8")
    assert "Derive the equations of motion, multipliers and forces of constraint of a problem." in page
    assert "A simulated motion, with one row per sample time." in page
