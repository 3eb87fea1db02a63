"""Issue 34: the files of a variant set — the problem files keep the original's comments and change only numbers
and the key, PrairieLearn's info.json validates against PrairieLearn's published schema (vendored in
tests/data/prairielearn, with its licence), server.py serves the verified table, and the Moodle XML parses (lxml)
and has the structure of a numerical-question quiz (no XSD of the format is published for offline use)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import jsonschema
import pytest
from lxml import etree
from variants_support import TUBE, TUBE_VARY, answers, layout, run, spec

from lagsolve.problem.load import load_problem

SCHEMA = Path(__file__).resolve().parents[1] / "data" / "prairielearn" / "infoQuestion.json"


def _made(to: str, count: int = 4):
    request = spec.build_request(load_problem(TUBE), count=count, vary=TUBE_VARY, seed=5, to=to)
    return run.generate(TUBE, request)


@pytest.fixture(scope="module")
def prairielearn() -> tuple[object, dict[str, str]]:
    made = _made("prairielearn")
    return made, layout.files(made)


def test_variant_files_keep_the_comments_and_change_only_numbers_and_key(prairielearn):
    made, files = prairielearn
    original = TUBE.read_text(encoding="utf-8")
    text = files["variant-01/rough_level_tube.yaml"]
    assert "# at rest relative to the tube" in text and "static: mu_s" in text
    before = original.split("simulation:")[0]
    assert text.startswith(before.rstrip("\n"))  # everything above is untouched; expected: and numbers follow
    assert "expected:" in text and "lagsolve variants: variant 1 of 4 (seed 5)" in text
    v = made.variants[0]
    assert f"Omega: {v.varied['Omega']}" in text and f"r: {v.varied['r']}" in text
    assert all(x == float(f"{x:.3g}") for x in v.varied.values())  # three significant figures
    assert {"variants.csv", "summary.json", "variant-04/solution.md", "variant-04/key.json"} <= set(files)
    assert "## Key" in files["variant-01/solution.md"] and "Lagrangian" in files["variant-01/solution.md"]


def test_prairielearn_info_json_validates_against_the_published_schema(prairielearn):
    made, files = prairielearn
    info = json.loads(files["prairielearn/rough_level_tube/info.json"])
    jsonschema.validate(info, json.loads(SCHEMA.read_text(encoding="utf-8")))
    assert re.fullmatch(r"[0-9a-f]{8}-[0-9a-f]{4}-4[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}", info["uuid"])
    other = _made("prairielearn", count=1)
    assert json.loads(layout.files(other)["prairielearn/rough_level_tube/info.json"])["uuid"] != info["uuid"]


def test_prairielearn_server_serves_the_verified_table(prairielearn):
    made, files = prairielearn
    namespace: dict[str, object] = {}
    exec(compile(files["prairielearn/rough_level_tube/server.py"], "server.py", "exec"), namespace)  # noqa: S102 - our own output
    table = namespace["VARIANTS"]
    assert len(table) == len(made.variants)
    for row, v in zip(table, made.variants, strict=True):
        assert row["params"]["Omega"] == v.values["Omega"] and row["params"]["r"] == v.initial["r"]
        assert all(answers(v)[k] == x for k, x in row["correct_answers"].items())
    data = {"params": {}, "correct_answers": {}}
    namespace["generate"](data)
    assert data in [{"params": r["params"], "correct_answers": r["correct_answers"]} for r in table]
    html = files["prairielearn/rough_level_tube/question.html"]
    names = re.findall(r'<pl-number-input answers-name="([^"]+)"', html)
    assert names and set(names) == set(table[0]["correct_answers"]) and "{{params.mu_s}}" in html


def test_moodle_xml_parses_and_is_a_quiz_of_numerical_questions():
    made = _made("moodle-xml")
    text = layout.files(made)["moodle/rough_level_tube.xml"]
    root = etree.fromstring(text.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))
    assert root.tag == "quiz"
    questions = root.findall("question")
    assert {q.get("type") for q in questions} == {"category", "numerical"}
    numerical = [q for q in questions if q.get("type") == "numerical"]
    categories = [q for q in questions if q.get("type") == "category"]
    assert len(numerical) == len(categories) * len(made.variants)
    for q in numerical:
        assert q.findtext("name/text") and q.findtext("questiontext/text")
        assert q.find("questiontext").get("format") == "html"
        (answer,) = q.findall("answer")
        assert answer.get("fraction") == "100"
        value, tolerance = float(answer.findtext("text")), float(answer.findtext("tolerance"))
        assert math.isfinite(value) and 0 < tolerance <= 0.011 * max(abs(value), 1e-12)
    first = numerical[0]
    index, name = re.fullmatch(r"rough_level_tube variant (\d+): (\w+)", first.findtext("name/text")).groups()
    assert float(first.findtext("answer/text")) == answers(made.variants[int(index) - 1])[name]


def test_text_from_the_file_is_inert_in_the_prairielearn_page():
    import importlib

    page = importlib.import_module("lagsolve.variants.prairielearn")
    assert page._text("<b>{{params.x}}</b>") == "&lt;b&gt;&#123;&#123;params.x&#125;&#125;&lt;/b&gt;"
