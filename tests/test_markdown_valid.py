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


HOSTILE = r'''
name: Falling mass
description: "Drops. [click me](javascript:alert(1)) and ![beacon](https://tracker.example/p.gif?u=1)
  <https://evil.example/a> https://evil.example/b www.evil.example/c mail a.b@evil.example
  [ref][r] [r]\n\n[r]: https://evil.example/ref\n\n<img src=x onerror=alert(1)>\n# Forged heading\nSetext\n===\n
  \\[x](https://evil.example/backslash) and a matrix [[m, 0], [0, m]]"
parameters:
  m: "mass\n## Forged | row [p](https://evil.example/param)"
  g: {description: "gravity ![i](https://tracker.example/g.gif)"}
coordinates:
  y: "height\n| forged | cells |"
functions: {}
particles: {p: {mass: m, position: [0, y]}}
gravity: [0, -g]
'''


def _tokens(text: str) -> list[Any]:
    md = markdown_it.MarkdownIt("commonmark").enable("table")
    md.use(dollarmath.dollarmath_plugin, allow_space=True, allow_digits=True, double_inline=True)
    out = []
    for token in md.parse(text):
        out.append(token)
        out += token.children or []
    return out


def test_descriptions_are_inert_text_in_markdown() -> None:
    """Links, images, autolinks, raw HTML and headings in descriptions stay text: the parsed report has no
    link or image token, no URL in a text node (where GitHub's autolinker looks), its own headings only, and one
    table row per parameter and coordinate whatever line breaks their descriptions hold."""
    import lagsolve

    text = render(lagsolve.derive(HOSTILE, analysis=False), "md")
    tokens = _tokens(text)
    assert [t.type for t in tokens if t.type in ("link_open", "image", "html_inline", "html_block")] == []
    urls = re.compile(r"https?://|www\.|@evil")
    assert [t.content for t in tokens if t.type == "text" and urls.search(t.content)] == []
    assert any(t.type == "code_inline" and t.content == "https://evil.example/b" for t in tokens)
    headings = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open"]
    assert not [h for h in headings if "Forged" in h or "Setext" in h], headings
    rows = [tokens[i + 2].content for i, t in enumerate(tokens) if t.type == "td_open" and i + 2 < len(tokens)]
    assert "height | forged | cells |" in rows and "mass ## Forged | row [p](`https://evil.example/param`)" not in rows
    assert sum(1 for t in tokens if t.type == "tr_open") == 2 + 3  # header rows, one coordinate, two parameters
    assert "[[m, 0], [0, m]]" in text and "Drops." in text


def test_descriptions_are_inert_in_html_and_latex() -> None:
    """The HTML report has no link, image or attribute from a description; LaTeX has no \\href, \\url or
    \\includegraphics from one (their backslashes are escaped)."""
    from html.parser import HTMLParser

    import lagsolve

    derivation = lagsolve.derive(HOSTILE, analysis=False)
    found: list[tuple[str, list[tuple[str, str | None]]]] = []

    class Collect(HTMLParser):
        def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
            found.append((tag, attrs))

    Collect().feed(render(derivation, "html"))
    links = [dict(attrs).get("href") or "" for tag, attrs in found if tag == "a"]
    assert links and all(href.startswith("#") for href in links)  # the page's own table of contents only
    assert not [tag for tag, _ in found if tag in ("img", "script", "iframe")]
    values = " ".join(v or "" for _, attrs in found for _, v in attrs)
    assert "evil" not in values and "tracker" not in values and "javascript" not in values
    tex = render(derivation, "tex")
    assert "\\href" not in tex and "\\url" not in tex and "\\includegraphics{https" not in tex
    assert "tracker.example" in tex  # shown, as text
