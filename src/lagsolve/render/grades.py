"""The grades of a class (:class:`lagsolve.app.grading.ClassGrades`) as text, JSON, a CSV gradebook, JUnit XML
and Gradescope's autograder ``results.json`` (``lagsolve grade --format``). Plain functions of the grades."""

from __future__ import annotations

import csv
import io
import json
from typing import Any
from xml.sax.saxutils import quoteattr

from lagsolve.grade.grader import ClassGrades, SubmissionGrade

FORMATS = ("text", "json", "csv", "junit", "gradescope")
#: the file each format is written to with ``-o DIR`` (gradescope: one folder per student)
FILES = {"text": "grades.txt", "json": "grades.json", "csv": "grades.csv", "junit": "grades.xml",
         "gradescope": "results.json"}
MARKS = {"correct": "✓", "follows": "→", "incorrect": "✗", "missing": "–", "unreadable": "?"}


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
        writer.writerow([_safe(g.student), g.source, _number(g.points), _number(g.max_points),
                         *(_number(by[s].points) for s in steps), *(str(by[s].status) for s in steps)])
    return out.getvalue()


def _safe(text: str) -> str:
    """A cell a spreadsheet will not run as a formula."""
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def grades_junit(grades: ClassGrades) -> str:
    """One test suite per student, one test per step (incorrect, missing, unreadable: a failure)."""
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', f"<testsuites name={quoteattr('lagsolve grade')}>"]
    for g in grades.grades:
        failures = sum(1 for s in g.steps if s.status not in ("correct", "follows"))
        lines.append(f"  <testsuite name={quoteattr(g.student)} tests=\"{len(g.steps)}\" failures=\"{failures}\">")
        for s in g.steps:
            lines.append(f"    <testcase classname={quoteattr(g.student)} name={quoteattr(s.step)}>")
            if s.status not in ("correct", "follows"):
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
