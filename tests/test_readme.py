"""The README's excerpts of the analysis are what the tool produces: the heavy top's steady precession."""

from __future__ import annotations

import re
from pathlib import Path

from lagsolve.render.report import summary
from mechanics_support import derived_file

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
SECTION = README[README.index("### The analysis, on the heavy symmetric top"):README.index("### The reports")]


def test_readme_shows_the_tops_steady_precession_as_reported() -> None:
    """The quoted report section is the golden report's Steady motions section (itself the fresh report), word for
    word."""
    quoted = "\n".join(re.sub(r"^> ?", "", line) for line in SECTION.splitlines() if line.startswith(">"))
    golden = (ROOT / "tests" / "golden" / "heavy_top.md").read_text(encoding="utf-8")
    assert "every steady motion is **stable**" in quoted
    assert quoted in golden


def test_readme_terminal_excerpt_is_the_summary() -> None:
    """The terminal lines quoted for the top are lines of its summary, in order."""
    block = SECTION.split("```\n")[1]
    lines = summary(derived_file("heavy_top")).splitlines()
    start = lines.index(block.splitlines()[0])
    assert lines[start:start + len(block.splitlines())] == block.splitlines()
