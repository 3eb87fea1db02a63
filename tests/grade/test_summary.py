"""The class summary of ``lagsolve grade`` (issue 31): per step the statuses counted and the most common mistakes
with one anonymous example each, in Markdown (parsed as GitHub does) and HTML (well-formed, hostile text escaped);
the same bytes whatever PYTHONHASHSEED."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner

from lagsolve.app.grading import grade_files
from lagsolve.cli import main
from lagsolve.grade.grader import ClassGrades, GradeStatus, StepGrade, SubmissionGrade
from lagsolve.render.grades import STATUSES, class_summary, summary_html, summary_markdown

markdown_it = pytest.importorskip("markdown_it")
from test_markdown_valid import markdown_problems  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
KEY = ROOT / "problems" / "bead.yaml"
EXAMPLES = sorted((ROOT / "examples" / "grading").glob("*.yaml"))
STUDENTS = ("ada", "bob", "carol", "dan")
HOSTILE = "<script>alert(1)</script> `x` | y ** z\n# forged [link](javascript:x) &amp; $\\input{a}$"
HOSTILE_NAME = "<script>steal()</script>|`who`"

#: (correct, follows, incorrect, missing, unreadable) per step for examples/grading/*.yaml against the bead
COUNTS = {
    "kinetic": (3, 0, 1, 0, 0), "potential": (2, 0, 1, 1, 0), "lagrangian": (2, 1, 1, 0, 0),
    "constraints": (2, 0, 0, 2, 0), "momenta": (3, 0, 0, 1, 0), "generalized_forces": (2, 1, 0, 1, 0),
    "equations": (2, 1, 1, 0, 0), "accelerations": (2, 1, 1, 0, 0), "multipliers": (2, 1, 0, 1, 0),
    "constraint_forces": (2, 0, 1, 1, 0),
}
MISTAKES = {
    "kinetic": ("missing_kinetic_term", "m*x_dot**2/2"), "potential": ("wrong_potential_sign", "-m*g*y"),
    "lagrangian": ("missing_factor", "m*x_dot**2*(1 + Derivative(f(x), x)**2) - m*g*f(x)"),
    "equations": ("lambda_sign_convention", "x: m*x_ddot = lambda_wire*Derivative(f(x), x)"),
    "accelerations": ("missing_velocity_squared_terms", "x: -Derivative(f(x), x)*g/(1 + Derivative(f(x), x)**2)"),
    "constraint_forces": ("missing_abs",
                          "wire: m*(Derivative(f(x), (x, 2))*x_dot**2 + g)/sqrt(1 + Derivative(f(x), x)**2)"),
}


@pytest.fixture(scope="module")
def grades() -> ClassGrades:
    return grade_files(KEY, EXAMPLES)


def _names(text: str) -> list[str]:
    return re.findall(r"\b(?:" + "|".join(STUDENTS) + r")\b", text)


def _parser() -> object:
    return markdown_it.MarkdownIt("commonmark").enable("table")


def _hostile() -> ClassGrades:
    """Two submissions by a hostile student: the same wrong answer twice, and an unnamed one."""
    step = StepGrade("kinetic", GradeStatus.INCORRECT, "sign_error", 0.0, 1.0, "x: *bad* | <img src=x> `q`", HOSTILE)
    other = StepGrade("potential", GradeStatus.INCORRECT, None, 0.0, 1.0, "not <b>equivalent</b>", "V | `` ` ``")
    fine = StepGrade("potential", GradeStatus.CORRECT, None, 1.0, 1.0, "")
    one = SubmissionGrade(HOSTILE_NAME, f"/tmp/{HOSTILE_NAME}.yaml", (step, other))
    two = SubmissionGrade(HOSTILE_NAME + "2", "b.yaml", (step, fine))
    return ClassGrades("Key <i>x</i> | `k`", "key.yaml", (one, two))


def test_counts_and_mistakes_on_the_examples(grades: ClassGrades) -> None:
    """Each step's statuses counted over the four examples; each mistake with its first example, as written."""
    summary = {s.step: s for s in class_summary(grades)}
    assert list(summary) == list(COUNTS)
    for step, counts in COUNTS.items():
        assert tuple(summary[step].counts[k] for k in STATUSES) == counts, step
        assert sum(counts) == len(STUDENTS)
    for step, (mistake, example) in MISTAKES.items():
        assert [(m.mistake, m.count, m.example) for m in summary[step].mistakes] == [(mistake, 1, example)], step
    assert {s for s, v in summary.items() if v.mistakes} == set(MISTAKES)
    assert summary["equations"].points == 1.5 and summary["equations"].max_points == 2


def test_markdown_parses_as_github_does(grades: ClassGrades) -> None:
    """One table with a row per step, a heading per step with mistakes, each example one code span; anonymous."""
    text = summary_markdown(grades)
    assert markdown_problems(text) == []
    tokens = _parser().parse(text)
    assert sum(1 for t in tokens if t.type == "table_open") == 1
    assert sum(1 for t in tokens if t.type == "tr_open") == 1 + len(COUNTS)
    headings = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open" and t.tag == "h3"]
    assert headings == list(MISTAKES)
    spans = [c.content for t in tokens if t.type == "inline" for c in t.children or () if c.type == "code_inline"]
    assert all(example in spans for _, example in MISTAKES.values())
    assert "| kinetic | 0.75/1 | 3 | 0 | 1 | 0 | 0 |" in text
    assert not _names(text) and "examples/grading" not in text


def test_html_is_well_formed_and_anonymous(grades: ClassGrades) -> None:
    root = ET.fromstring(summary_html(grades).split("\n", 1)[1])
    rows = root.findall(".//table/tr")
    assert len(rows) == 1 + len(COUNTS)
    cells = {r[0].text: tuple(int(c.text or "") for c in r[2:]) for r in rows[1:]}
    assert cells == COUNTS
    codes = [c.text for c in root.iter("code")]
    assert all(example in codes for _, example in MISTAKES.values())
    assert not _names(summary_html(grades))


def test_hostile_text_is_inert_in_markdown() -> None:
    """A hostile example is one literal code span; the evidence and the key's name make no HTML, emphasis,
    link, code or table cell; the student's name and file are nowhere."""
    text = summary_markdown(_hostile())
    assert markdown_problems(text) == []
    tokens = _parser().parse(text)
    kinds = {c.type for t in tokens if t.type == "inline" for c in t.children or ()}
    assert not kinds & {"html_inline", "em_open", "strong_open", "link_open", "image"}
    assert not any(t.type in ("html_block", "hr") for t in tokens)
    spans = [c.content for t in tokens if t.type == "inline" for c in t.children or () if c.type == "code_inline"]
    assert " ".join(HOSTILE.split()) in spans and "V | ` ` ` ` `" in spans  # backtick runs spaced out
    assert sum(1 for t in tokens if t.type == "tr_open") == 3  # header, kinetic, potential: no forged cell or row
    assert [t.tag for t in tokens if t.type == "heading_open"] == ["h1", "h2", "h3", "h3"]
    assert "steal" not in text and "who" not in text and "/tmp" not in text
    assert "- `sign_error`: 2;" in text and "- no named mistake: 1;" in text


def test_hostile_text_is_escaped_in_html() -> None:
    page = summary_html(_hostile())
    root = ET.fromstring(page.split("\n", 1)[1])  # well-formed
    assert "<script" not in page and "<img" not in page and "<b>" not in page and "<i>x" not in page
    assert " ".join(HOSTILE.split()) in [c.text for c in root.iter("code")]
    assert "steal" not in page and "/tmp" not in page
    assert [e.tag for e in root.iter() if e.tag in ("script", "img", "b", "i", "a")] == []


def test_command_prints_or_writes_the_summary(tmp_path: Path) -> None:
    runner = CliRunner()
    printed = runner.invoke(main, ["grade", str(KEY), *map(str, EXAMPLES), "--summary", "md"])
    assert printed.exit_code == 0 and printed.stdout.startswith("# Class summary: Bead on a wire\n")
    written = runner.invoke(main, ["grade", str(KEY), *map(str, EXAMPLES), "--format", "csv", "--summary", "html",
                                   "-o", str(tmp_path)])
    assert written.exit_code == 0, written.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["grades.csv", "summary.html"]
    ET.fromstring((tmp_path / "summary.html").read_text(encoding="utf-8").split("\n", 1)[1])


def test_summary_does_not_depend_on_hash_seed() -> None:
    """Two runs under different PYTHONHASHSEED print the same summary, byte for byte."""
    command = [sys.executable, "-m", "lagsolve", "grade", str(KEY), *map(str, EXAMPLES), "--summary", "md"]
    runs = [subprocess.Popen(command, env={**os.environ, "PYTHONHASHSEED": seed}, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE) for seed in ("0", "4242")]
    outputs = [run.communicate() for run in runs]
    assert all(run.returncode == 0 for run in runs), [err for _, err in outputs]
    assert outputs[0][0] == outputs[1][0] and outputs[0][0].startswith(b"# Class summary")
