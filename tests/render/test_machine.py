"""`lagsolve.render.machine`: JSON streams keep every result, check results become JSON and JUnit from plain rows."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

from lagsolve.app.pipeline import Checked
from lagsolve.render.machine import Unchecked, checks_json, checks_junit, json_stream

ROW = {"quantity": "accelerations", "name": "x", "status": "warning", "reason": "holds only where",
       "label": "ẍ", "description": "holds only where x > 0", "expected": "x", "derived": "Abs(x)"}


def test_json_stream_as_array_and_as_lines() -> None:
    """The same results come out as one indented array or as one compact line each."""
    texts = ['{\n  "name": "a"\n}\n', '{"name": "b", "n": [1, 2]}\n']
    assert json.loads(json_stream(texts, lines=False)) == [{"name": "a"}, {"name": "b", "n": [1, 2]}]
    assert json_stream(texts, lines=True) == '{"name":"a"}\n{"name":"b","n":[1,2]}\n'


def test_warning_passes_in_junit_with_its_diagnosis() -> None:
    """A warning is a passing testcase whose system-out holds the diagnosis; counts are summed up the tree."""
    checked = Checked("p/a.yaml", "A", "", {"ok": 0, "warning": 1, "mismatch": 0, "unchecked": 0}, (ROW,))
    root = ET.fromstring(checks_junit([checked, Unchecked("p/b.yaml", "p/b.yaml: file not found", 2)]))
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("2", "0", "1")
    case = root.find("./testsuite/testcase")
    assert case.get("classname") == "a" and case.find("failure") is None
    assert "holds only where x > 0" in case.find("system-out").text


def test_unchecked_file_in_json() -> None:
    """A file that was not checked is an entry with its error and exit status."""
    data = json.loads(checks_json([Unchecked("b.yaml", "b.yaml: file not found", 2)]))
    assert data == [{"source": "b.yaml", "passed": False, "error": "b.yaml: file not found", "exit_status": 2}]


def test_junit_escapes_what_xml_forbids() -> None:
    """Every character XML 1.0 forbids, in any attribute or text (names, paths, messages, diagnoses), comes out
    escaped; the rest of the text is kept as it is."""
    bad = "".join(chr(c) for c in (*range(0, 9), 11, 12, *range(14, 32), 0xFFFE, 0xFFFF, 0xD800))
    row = {**ROW, "name": f"x{bad}", "description": f"d{bad}", "label": "ẍ\ufffe"}
    checked = Checked(f"p/{bad}.yaml", f"A{bad}", "", {"ok": 0, "warning": 1, "mismatch": 0, "unchecked": 0}, (row,))
    text = checks_junit([checked, Unchecked(f"p/{bad}b.yaml", f"message{bad}", 2)])
    root = ET.fromstring(text)
    assert root.find("testsuite").get("name") == "A" + bad.encode("unicode_escape").decode("ascii")
    assert "\\x00\\x01" in root.find("./testsuite/testcase").get("name")
    assert root.find("./testsuite/testcase/system-out").text.startswith("label: ẍ\\ufffe\ndescription: d\\x00")
    assert root.findall("testsuite")[1].find("./testcase/error").text.endswith("\\ufffe\\uffff\\ud800")
