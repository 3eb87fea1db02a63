"""The Markdown reports parse as GitHub renders them: every heading is a heading and every fence closes.

GitHub's Markdown is CommonMark plus inline maths written $`...`$ (or $...$) and display maths in
```` ```math ```` fences. A glued closing fence (``…\\right]```​``) is not a fence at all in
CommonMark, so the block runs on and swallows the headings after it; these tests parse each report
with markdown-it-py (CommonMark with the dollar-math plugin) and check the block structure.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

markdown_it = pytest.importorskip("markdown_it")
dollarmath = pytest.importorskip("mdit_py_plugins.dollarmath")

from lagsolve.render.report import render  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = sorted((ROOT / "tests" / "golden").glob("*.md"))
HEADING = re.compile(r"#{1,2} \S")
FENCE_LINE = re.compile(r"\s*(```|~~~)")


def _parser() -> object:
    md = markdown_it.MarkdownIt("commonmark")
    return md.use(dollarmath.dollarmath_plugin, allow_space=True, allow_digits=True, double_inline=True)


def markdown_problems(text: str) -> list[str]:
    """What would not render as meant: headings that are not heading tokens, fences that do not close,
    and fence markers glued to the end of a line of content."""
    tokens = _parser().parse(text)
    lines = text.splitlines()
    headings = {token.map[0] for token in tokens if token.type == "heading_open" and token.map}
    blocks = [token for token in tokens if token.type == "fence" and token.map]
    # the content lines of a fence that does close may hold anything ("# comment" in a text block)
    verbatim = {number for token in blocks for number in range(token.map[0] + 1, token.map[1] - 1)
                if token.map[1] <= len(lines) and FENCE_LINE.match(lines[token.map[1] - 1])}
    found = []
    for number, line in enumerate(lines):
        if HEADING.match(line) and number not in headings and number not in verbatim:
            found.append(f"line {number + 1}: {line[:40]!r} is not a heading")
        if "```" in line and not FENCE_LINE.match(line):
            found.append(f"line {number + 1}: a fence marker glued to content: ...{line[-40:]!r}")
    for token in blocks:
        start, end = token.map
        closed = end <= len(lines) and FENCE_LINE.match(lines[end - 1]) is not None and end - 1 > start
        if not closed:
            found.append(f"line {start + 1}: the fence opened here does not close (runs to line {end})")
    fenced = sum(1 for line in lines if FENCE_LINE.match(line))
    if fenced != 2 * len(blocks):
        found.append(f"{fenced} fence lines for {len(blocks)} fenced blocks")
    return found


def test_checker_finds_a_glued_fence() -> None:
    """The checker reports a closing fence glued to the content line and the heading it swallows."""
    text = "# Title\n\n```math\nM = 1```\n\n## Results\n\nx\n"
    found = markdown_problems(text)
    assert any("glued" in item for item in found), found
    assert any("'## Results' is not a heading" in item for item in found), found
    assert any("does not close" in item for item in found), found


def test_checker_accepts_closed_fences_and_math() -> None:
    """Closed ```math fences, $`...`$ inline maths and headings after them pass the checker."""
    text = "# Title\n\nWith $`x^2`$ and $a_1$:\n\n```math\nM = 1\n```\n\n## Results\n\n```text\n# ok\n```\n"
    assert markdown_problems(text) == []


@pytest.mark.parametrize("path", GOLDEN, ids=[p.stem for p in GOLDEN])
def test_golden_markdown_is_valid(path: Path) -> None:
    """Each reviewed golden Markdown report has its headings as headings and every fence closed."""
    assert markdown_problems(path.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("name", ["bead", "double_pendulum"])
def test_fresh_markdown_report_is_valid(name: str, shipped_reports: Callable[[str], Any]) -> None:
    """A freshly rendered report, with constraints (bead) and without (double pendulum), is valid Markdown."""
    reports = shipped_reports(name)
    assert markdown_problems(reports.outputs["md"]) == []


def test_simulation_section_fence_closes(shipped_derivation: Callable[[str], Any]) -> None:
    """The simulation summary's ```text fence closes on its own line, with or without a final newline."""
    derivation = shipped_derivation("bead")
    for summary in ("Bead on a wire: simulated to t = 10\n  steps: 3", "Bead: simulated\n  steps: 3\n"):
        text = render(derivation, "md", simulation={"summary": summary, "figures": []})
        assert "## Simulation" in text
        assert markdown_problems(text) == []
