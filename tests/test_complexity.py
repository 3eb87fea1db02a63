"""Complexity is removed by splitting work into named steps, not hidden by packing it (issue 30).

No function has a cyclomatic complexity over 25 by radon's count (ruff's count, capped at 25 too, misses
conditions packed into one statement), and none is over 80 lines. There are no exemptions.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "lagsolve"
MAX_COMPLEXITY = 25
MAX_LINES = 80



def _modules() -> list[tuple[str, Path]]:
    out = []
    for path in sorted(SRC.rglob("*.py")):
        out.append((path.relative_to(SRC).as_posix(), path))
    return out


def _complexities(text: str) -> list[tuple[str, int]]:
    """(name, radon's cyclomatic complexity) of every function, method and closure."""
    from radon.complexity import cc_visit
    from radon.visitors import Function

    out: list[tuple[str, int]] = []

    def visit(block: Function) -> None:
        out.append((block.name, block.complexity))
        for inner in block.closures:
            visit(inner)

    for block in cc_visit(text):
        if isinstance(block, Function):
            visit(block)
    return out


def _lengths(text: str) -> list[tuple[str, int]]:
    """(name, lines from ``def`` to its last line) of every function, method and closure."""
    return [(node.name, (node.end_lineno or node.lineno) - node.lineno + 1) for node in ast.walk(ast.parse(text))
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)]


def _over_the_limits() -> dict[str, str]:
    over: dict[str, str] = {}
    for name, path in _modules():
        text = path.read_text(encoding="utf-8")
        for function, complexity in _complexities(text):
            if complexity > MAX_COMPLEXITY:
                over[f"{name}::{function}"] = f"complexity {complexity}"
        for function, lines in _lengths(text):
            if lines > MAX_LINES:
                key = f"{name}::{function}"
                over[key] = f"{over[key]}, " if key in over else ""
                over[key] += f"{lines} lines"
    return over


def test_no_function_over_the_limits():
    pytest.importorskip("radon", reason="radon counts the complexity (pip install -e '.[dev]')")
    over = _over_the_limits()
    assert over == {}, (f"functions over {MAX_COMPLEXITY} (radon) or {MAX_LINES} lines: split them into named "
                        f"steps: {over}")


def test_the_counts_see_a_packed_condition():
    """radon counts each boolean operator, so packing conditions into one statement does not hide them."""
    pytest.importorskip("radon", reason="radon counts the complexity (pip install -e '.[dev]')")
    packed = "def f(a, b, c, d):\n    return 1 if (a and b) or (c and d) else 0\n"
    assert _complexities(packed) == [("f", 5)]
    assert _lengths(packed) == [("f", 2)]
