"""The grades of a class (:class:`lagsolve.app.grading.ClassGrades`) as text, JSON, a CSV gradebook, JUnit XML
and Gradescope's autograder ``results.json`` (``lagsolve grade --format``), and the class summary in Markdown
and HTML (``--summary``). Plain functions of the grades.

The summary is anonymous (no student id, no file name) and its examples are student text, hostile: in Markdown
a code span on one line (:func:`~lagsolve.render.notation.md_code_span`), in HTML escaped."""

from __future__ import annotations

import csv
import io
import json
import re
from collections import Counter
from dataclasses import dataclass
from typing import Any
from xml.sax.saxutils import quoteattr

from markupsafe import escape

from lagsolve.grade.grader import ClassGrades, StepGrade, SubmissionGrade
from lagsolve.render.notation import md_code_span

FORMATS = ("text", "json", "csv", "junit", "gradescope")
#: the file each format is written to with ``-o DIR`` (gradescope: one folder per student)
FILES = {"text": "grades.txt", "json": "grades.json", "csv": "grades.csv", "junit": "grades.xml",
         "gradescope": "results.json"}
MARKS = {"correct": "✓", "follows": "→", "incorrect": "✗", "missing": "–", "unreadable": "?", "ungraded": "…"}


def _number(value: float) -> float | int:
    return int(value) if float(value).is_integer() else round(value, 4)


def grades_text(grades: ClassGrades) -> str:
    lines = [f"{grades.key} ({grades.source})"]
    for g in grades.grades:
        lines.append(f"{g.student} ({g.source}): {_number(g.points)}/{_number(g.max_points)}")
        if g.error:
            lines.append(f"  ? unreadable: {g.error}")
            continue
        for s in g.steps:
            mistake = f" [{s.mistake}]" if s.mistake else ""
            message = f": {s.message}" if s.message and s.status != "correct" else ""
            lines.append(f"  {MARKS[s.status]} {s.step:<19} {_number(s.points)}/{_number(s.max_points)} "
                         f"{s.status}{mistake}{message}")
    return "\n".join(lines) + "\n"


def submission_json(g: SubmissionGrade) -> dict[str, Any]:
    return {"student": g.student, "source": g.source, "points": _number(g.points), "max_points": _number(g.max_points),
            "error": g.error or None,
            "steps": [{"step": s.step, "status": str(s.status), "mistake": s.mistake, "points": _number(s.points),
                       "max_points": _number(s.max_points), "message": s.message} for s in g.steps]}


def grades_json(grades: ClassGrades) -> str:
    data = {"key": grades.key, "source": grades.source, "submissions": [submission_json(g) for g in grades.grades]}
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def grades_csv(grades: ClassGrades) -> str:
    """One row per student: the total, then each step's points and status."""
    steps = [s.step for s in grades.grades[0].steps] if grades.grades else []
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["student", "source", "points", "max_points", *steps, *(f"{s}_status" for s in steps)])
    for g in grades.grades:
        by = {s.step: s for s in g.steps}
        writer.writerow([_safe(g.student), _safe(g.source), _number(g.points), _number(g.max_points),
                         *(_number(by[s].points) for s in steps), *(str(by[s].status) for s in steps)])
    return out.getvalue()


def _safe(text: str) -> str:
    """A cell a spreadsheet will not run as a formula."""
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def grades_junit(grades: ClassGrades) -> str:
    """One test suite per student, one test per step (incorrect, missing, unreadable: a failure; ungraded:
    skipped, to be graded by hand)."""
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', f"<testsuites name={quoteattr('lagsolve grade')}>"]
    for g in grades.grades:
        failures = sum(1 for s in g.steps if s.status not in ("correct", "follows", "ungraded"))
        lines.append(f"  <testsuite name={quoteattr(g.student)} tests=\"{len(g.steps)}\" failures=\"{failures}\">")
        for s in g.steps:
            lines.append(f"    <testcase classname={quoteattr(g.student)} name={quoteattr(s.step)}>")
            if s.status == "ungraded":
                lines.append(f"      <skipped message={quoteattr(s.message)}/>")
            elif s.status not in ("correct", "follows"):
                what = f"{s.status}" + (f" ({s.mistake})" if s.mistake else "")
                lines.append(f"      <failure message={quoteattr(what)}>{_escape(s.message)}</failure>")
            lines.append("    </testcase>")
        lines.append("  </testsuite>")
    lines.append("</testsuites>")
    return "\n".join(lines) + "\n"


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def gradescope_result(g: SubmissionGrade) -> dict[str, Any]:
    """Gradescope's autograder ``results.json`` for one submission: one test per step."""
    tests = []
    for s in g.steps:
        mistake = f" [{s.mistake}]" if s.mistake else ""
        tests.append({"name": s.step, "score": _number(s.points), "max_score": _number(s.max_points),
                      "status": "passed" if s.status in ("correct", "follows") else "failed",
                      "output": f"{s.status}{mistake}: {s.message}" if s.message else str(s.status)})
    summary = f"{g.student}: {_number(g.points)}/{_number(g.max_points)}"
    return {"score": _number(g.points), "output": g.error or summary, "tests": tests}


def grades_gradescope(grades: ClassGrades) -> str:
    """``results.json`` for one submission; a list of them for several."""
    results = [gradescope_result(g) for g in grades.grades]
    data: Any = results[0] if len(results) == 1 else results
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


RENDER = {"text": grades_text, "json": grades_json, "csv": grades_csv, "junit": grades_junit,
          "gradescope": grades_gradescope}


# -- the class summary -----------------------------------------------------------------------------------

SUMMARIES = ("md", "html")
#: the file each summary is written to with ``-o DIR``
SUMMARY_FILES = {"md": "summary.md", "html": "summary.html"}
STATUSES = ("correct", "follows", "incorrect", "missing", "unreadable")
#: a comparison that used up its CPU budget: a column of the summary only when some step is ungraded
UNGRADED = "ungraded"
#: most mistakes listed per step, and longest example shown (characters)
MAX_MISTAKES = 5
MAX_EXAMPLE = 160
UNNAMED = "no named mistake"


@dataclass(frozen=True)
class MistakeSummary:
    """One mistake at one step: how many made it, and one example (the text and the grader's evidence)."""

    mistake: str | None
    count: int
    example: str
    message: str


@dataclass(frozen=True)
class StepSummary:
    """One step over the class: the count of each status, the mean points, the most common mistakes."""

    step: str
    counts: dict[str, int]
    points: float
    max_points: float
    mistakes: tuple[MistakeSummary, ...]


def class_summary(grades: ClassGrades) -> list[StepSummary]:
    """Per step (in the order of the grades), the statuses counted and the incorrect answers grouped by mistake,
    most common first (ties: named before unnamed, then by name); the example is the first in submission order."""
    by_step: dict[str, list[StepGrade]] = {}
    for g in grades.grades:
        for s in g.steps:
            by_step.setdefault(s.step, []).append(s)
    out = []
    for step, graded in by_step.items():
        counts = Counter(str(s.status) for s in graded)
        wrong = [s for s in graded if str(s.status) == "incorrect"]
        groups = Counter(s.mistake for s in wrong)
        order = sorted(groups, key=lambda m: (-groups[m], m is None, m or ""))[:MAX_MISTAKES]
        mistakes = []
        for mistake in order:
            same = [s for s in wrong if s.mistake == mistake]
            first = next((s for s in same if s.answer), same[0])
            mistakes.append(MistakeSummary(mistake, groups[mistake], _one_line(first.answer), _one_line(first.message)))
        mean = sum(s.points for s in graded) / len(graded)
        out.append(StepSummary(step, {k: counts.get(k, 0) for k in (*STATUSES, UNGRADED)}, mean,
                               max(s.max_points for s in graded), tuple(mistakes)))
    return out


def _one_line(text: str) -> str:
    """Whitespace (line breaks included) as single spaces, control characters dropped, cut at MAX_EXAMPLE."""
    text = re.sub(r"[\x00-\x08\x0b-\x1f\x7f]", "", re.sub(r"\s+", " ", text)).strip()
    return text if len(text) <= MAX_EXAMPLE else text[:MAX_EXAMPLE - 1] + "…"


def _md_example(text: str) -> str:
    """A student's answer as one Markdown code span; a run of backticks in it is shown spaced out (`` ` ` ``), so
    the span's own fence is at most two backticks (never one a reader or checker could take for a code fence)."""
    return md_code_span(re.sub(r"``+", lambda m: " ".join(m.group()), text))


def _md_literal(text: str) -> str:
    """Text shown as written in Markdown: on one line, every ASCII punctuation character backslash-escaped (no
    emphasis, link, HTML, code, table cell or heading can come from it)."""
    return re.sub(r"([!-/:-@\[-`{-~])", r"\\\1", _one_line(text))


def _totals(grades: ClassGrades) -> tuple[int, float, float]:
    n = len(grades.grades)
    mean = sum(g.points for g in grades.grades) / n if n else 0.0
    top = max((g.max_points for g in grades.grades), default=0.0)
    return n, mean, top


def _columns(steps: list[StepSummary]) -> tuple[str, ...]:
    """The statuses counted in the summary's table: ``ungraded`` only when some step is."""
    return (*STATUSES, UNGRADED) if any(s.counts.get(UNGRADED) for s in steps) else STATUSES


def summary_markdown(grades: ClassGrades) -> str:
    """The class summary as GitHub Markdown: a table of the steps, then each step's most common mistakes."""
    n, mean, top = _totals(grades)
    steps = class_summary(grades)
    columns = _columns(steps)
    lines = [f"# Class summary: {_md_literal(grades.key)}", "",
             f"{n} submissions graded against {md_code_span(_one_line(grades.source))}; mean "
             f"{_number(round(mean, 2))}/{_number(top)} points; {grades.unreadable} files could not be read.", "",
             "| step | mean points | " + " | ".join(columns) + " |", "|---|---:|" + "---:|" * len(columns)]
    for s in steps:
        lines.append(f"| {s.step} | {_number(round(s.points, 2))}/{_number(s.max_points)} | "
                     + " | ".join(str(s.counts[k]) for k in columns) + " |")
    lines += ["", "## Most common mistakes", ""]
    wrong = [s for s in steps if s.mistakes]
    if not wrong:
        lines += ["No incorrect step.", ""]
    for s in wrong:
        lines += [f"### {s.step}", ""]
        for m in s.mistakes:
            name = md_code_span(m.mistake) if m.mistake else UNNAMED
            example = f"; for example {_md_example(m.example)}" if m.example else ""
            evidence = f" ({_md_literal(m.message)})" if m.message else ""
            lines.append(f"- {name}: {m.count}{example}{evidence}")
        lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


_STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}"
          "table{border-collapse:collapse}th,td{border:1px solid #ccc;padding:.2em .6em}td.n{text-align:right}"
          "code{background:#f4f4f4;padding:0 .2em}")


def summary_html(grades: ClassGrades) -> str:
    """The class summary as one HTML page (well-formed XML too); every piece of text escaped."""
    n, mean, top = _totals(grades)
    steps = class_summary(grades)
    columns = _columns(steps)
    title = escape(f"Class summary: {grades.key}")
    out = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8"/>', f"<title>{title}</title>",
           f"<style>{_STYLE}</style>", "</head>", "<body>", f"<h1>{title}</h1>",
           f"<p>{n} submissions graded against <code>{escape(grades.source)}</code>; mean "
           f"{_number(round(mean, 2))}/{_number(top)} points; {grades.unreadable} files could not be read.</p>",
           "<table>", "<tr><th>step</th><th>mean points</th>" + "".join(f"<th>{k}</th>" for k in columns) + "</tr>"]
    for s in steps:
        cells = "".join(f'<td class="n">{s.counts[k]}</td>' for k in columns)
        out.append(f'<tr><th>{escape(s.step)}</th><td class="n">{_number(round(s.points, 2))}/'
                   f"{_number(s.max_points)}</td>{cells}</tr>")
    out += ["</table>", "<h2>Most common mistakes</h2>"]
    wrong = [s for s in steps if s.mistakes]
    if not wrong:
        out.append("<p>No incorrect step.</p>")
    for s in wrong:
        out += [f"<h3>{escape(s.step)}</h3>", "<ul>"]
        for m in s.mistakes:
            name = f"<code>{escape(m.mistake)}</code>" if m.mistake else UNNAMED
            example = f"; for example <code>{escape(m.example)}</code>" if m.example else ""
            evidence = f" ({escape(m.message)})" if m.message else ""
            out.append(f"<li>{name}: {m.count}{example}{evidence}</li>")
        out.append("</ul>")
    out += ["</body>", "</html>"]
    return "\n".join(out) + "\n"


SUMMARY = {"md": summary_markdown, "html": summary_html}
