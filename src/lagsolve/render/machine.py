"""Output for machines: check verdicts as JSON and JUnit XML, several JSON results as one array or as lines.

A check result is given as plain rows (:func:`verdict_rows`, made where the check ran) so that it
crosses the process boundary of :mod:`lagsolve.app.budget`; a file that could not be checked is an
:class:`Unchecked` (its error message and exit code).

JUnit: one ``<testsuite>`` per problem file, one ``<testcase>`` per expected answer (``classname``
the file's slug, ``name`` the quantity, e.g. ``accelerations.x``). A mismatch is a ``<failure>``,
an answer that could not be checked is ``<skipped>``, a warning passes with its diagnosis in
``<system-out>``, and a file that could not be loaded or derived is a single testcase with an
``<error>``. A character XML 1.0 does not allow (a control character other than tab and line breaks,
U+FFFE, U+FFFF, a lone surrogate from a file name that is not UTF-8) is written as its escape ``\\uFFFE``,
so the document always parses.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from lagsolve.check.status import Status

if TYPE_CHECKING:
    from lagsolve.check.compare import CheckReport


@dataclass(frozen=True)
class Unchecked:
    """A problem file whose check did not run: what went wrong, and the exit code it means."""

    source: str
    message: str
    status: int


def verdict_rows(report: CheckReport) -> tuple[dict[str, str], ...]:
    """One row per verdict: quantity, name, status, reason, label (ẍ, λ_wire) and the diagnosis in words."""
    from lagsolve.render.checks import describe, label
    from lagsolve.render.notation import Notation

    note = Notation(report.coordinates)
    rows = []
    for v in report.verdicts:
        row = {"quantity": v.quantity, "name": v.name, "status": v.status, "reason": v.reason,
               "label": label(v, note, report.coordinates), "description": describe(v, note)}
        if v.status in (Status.WARNING, Status.MISMATCH):
            row["expected"] = ", ".join(note.text(e) for e in v.expected)
            row["derived"] = ", ".join(note.text(d) for d in v.derived) if v.derived is not None else ""
        rows.append(row)
    return tuple(rows)


def checks_json(results: list[Any]) -> str:
    """Check results (:class:`lagsolve.app.pipeline.Checked` or :class:`Unchecked`) as one JSON array."""
    out: list[dict[str, Any]] = []
    for r in results:
        if isinstance(r, Unchecked):
            out.append({"source": r.source, "passed": False, "error": r.message, "exit_status": r.status})
        else:
            out.append({"source": r.source, "name": r.name, "passed": r.passed, "counts": dict(r.counts),
                        "verdicts": [dict(row) for row in r.rows]})
    return json.dumps(out, indent=2, ensure_ascii=True) + "\n"


#: the characters XML 1.0 forbids (its ``Char`` production: tab, LF, CR, U+0020 to U+D7FF, U+E000 to U+FFFD, U+10000 up)
_NOT_XML = re.compile("[^\t\n\r\u0020-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def xml_safe(text: str) -> str:
    r"""``text`` with every character XML 1.0 forbids written as its Python escape (``\x01``, ``\ufffe``).

    >>> xml_safe("a\ufffeb\x01c\ud800")
    'a\\ufffeb\\x01c\\ud800'
    """
    return _NOT_XML.sub(lambda m: m.group(0).encode("unicode_escape", "backslashreplace").decode("ascii"), text)


def checks_junit(results: list[Any]) -> str:
    """Check results as JUnit XML: ``testsuites`` / ``testsuite`` per file / ``testcase`` per answer."""
    from lagsolve.files import safe_slug

    root = ET.Element("testsuites", name="lagsolve check")
    totals = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    for r in results:
        slug = safe_slug(r.source)
        suite = ET.SubElement(root, "testsuite", name=getattr(r, "name", slug), file=r.source)
        counts = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
        if isinstance(r, Unchecked):
            case = ET.SubElement(suite, "testcase", classname=slug, name="derivation", file=r.source)
            ET.SubElement(case, "error", message=r.message.splitlines()[0] if r.message else "error",
                          type="spec" if r.status == 2 else "derivation").text = r.message
            counts["tests"], counts["errors"] = 1, 1
        for row in () if isinstance(r, Unchecked) else r.rows:
            case = ET.SubElement(suite, "testcase", classname=slug, name=f"{row['quantity']}.{row['name']}",
                                 file=r.source)
            counts["tests"] += 1
            detail = "\n".join(f"{k}: {row[k]}" for k in ("label", "description", "expected", "derived") if k in row)
            if row["status"] == Status.MISMATCH:
                ET.SubElement(case, "failure", message=f"{row['label']}: {row['description']}",
                              type=row["reason"]).text = detail
                counts["failures"] += 1
            elif row["status"] == Status.UNCHECKED:
                ET.SubElement(case, "skipped", message=f"{row['label']}: {row['description']}")
                counts["skipped"] += 1
            elif row["status"] == Status.WARNING:
                ET.SubElement(case, "system-out").text = detail
        for key, n in counts.items():
            suite.set(key, str(n))
            totals[key] += n
    for key, n in totals.items():
        root.set(key, str(n))
    ET.indent(root)
    # the markup itself is ASCII: only text from files (names, paths, messages) can hold a forbidden character
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + xml_safe(ET.tostring(root, encoding="unicode")) + "\n"


def json_stream(texts: list[str], *, lines: bool) -> str:
    """JSON results (one text each) as one JSON array, or (``lines``) one compact object per line."""
    documents = [json.loads(t) for t in texts]
    if lines:
        return "".join(json.dumps(d, ensure_ascii=True, separators=(",", ":")) + "\n" for d in documents)
    return json.dumps(documents, indent=2, ensure_ascii=True) + "\n"
