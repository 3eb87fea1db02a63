"""A Moodle XML quiz for a variant set: one category per answer, holding one numerical question per variant
(a quiz's "random question from category" then gives each student a different variant); each answer with an
absolute tolerance of :data:`~lagsolve.variants.prairielearn.RTOL` of its value.

Built with :mod:`xml.etree.ElementTree`, which escapes every text; no published XSD of the format is available
offline, so the tests parse the file and check its structure (``docs/variants.md``).
"""

from __future__ import annotations

import html
import xml.etree.ElementTree as ET

from lagsolve.variants.prairielearn import RTOL
from lagsolve.variants.run import Variant, VariantSet


def _text(parent: ET.Element, tag: str, text: str, **attributes: str) -> ET.Element:
    element = ET.SubElement(parent, tag, attributes)
    ET.SubElement(element, "text").text = text
    return element


def _question_text(variants: VariantSet, variant: Variant, name: str) -> str:
    problem = variants.problem
    given = {**variant.values, **variant.initial}
    items = "".join(f"<li>{html.escape(k)} = {v:g}</li>" for k, v in given.items())
    what = html.escape(variants.answer(variant, name).what)
    return (f"<p>{html.escape(problem.name)}</p><p>{html.escape(problem.description.strip())}</p>"
            f"<p>Numbers (one consistent system of units):</p><ul>{items}</ul>"
            f"<p>Give {what} ({html.escape(name)}).</p>")


def _question(quiz: ET.Element, variants: VariantSet, variant: Variant, name: str) -> None:
    value = variants.answer(variant, name).value
    question = ET.SubElement(quiz, "question", {"type": "numerical"})
    _text(question, "name", f"{variants.slug} variant {variant.index}: {name}")
    _text(question, "questiontext", _question_text(variants, variant, name), format="html")
    _text(question, "generalfeedback", "", format="html")
    ET.SubElement(question, "defaultgrade").text = "1"
    ET.SubElement(question, "penalty").text = "0.3333333"
    ET.SubElement(question, "hidden").text = "0"
    answer = _text(question, "answer", f"{value:.6g}", fraction="100", format="moodle_auto_format")
    ET.SubElement(answer, "tolerance").text = f"{RTOL * max(abs(value), 1e-12):.3g}"
    _text(answer, "feedback", "", format="html")
    ET.SubElement(question, "unitgradingtype").text = "0"
    ET.SubElement(question, "unitpenalty").text = "0.1"
    ET.SubElement(question, "showunits").text = "3"
    ET.SubElement(question, "unitsleft").text = "0"


def quiz_xml(variants: VariantSet) -> str:
    quiz = ET.Element("quiz")
    for name in variants.exported():
        category = ET.SubElement(quiz, "question", {"type": "category"})
        _text(category, "category", f"$course$/top/lagsolve/{variants.slug}/{name}")
        for variant in variants.variants:
            _question(quiz, variants, variant, name)
    ET.indent(quiz)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(quiz, encoding="unicode") + "\n"
