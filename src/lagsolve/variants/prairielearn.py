"""A PrairieLearn question folder for a variant set: ``info.json``, ``question.html`` and ``server.py``.

``server.py`` does not randomise anything itself: it holds the table of the verified variants (as JSON text)
and picks one with PrairieLearn's per-variant seeded ``random``, putting its numbers in ``data["params"]`` and
its key in ``data["correct_answers"]``. The ``uuid`` is derived from the file's name, the seed and the varied
ranges, so the same command writes the same folder and another seed a new question.
"""

from __future__ import annotations

import hashlib
import html
import json
import uuid

from lagsolve.variants.run import VariantSet

#: relative tolerance of every numeric answer (also the Moodle export's)
RTOL = 0.01


def question_uuid(variants: VariantSet) -> str:
    """A version-4 UUID, the same for the same file, seed, count and ranges."""
    request = variants.request
    text = json.dumps([variants.slug, request.seed, request.count,
                       [[v.name, v.low, v.high, v.step] for v in request.vary],
                       str(request.require) if request.require else None])
    return str(uuid.UUID(bytes=hashlib.sha256(text.encode("utf-8")).digest()[:16], version=4))


def info_json(variants: VariantSet) -> str:
    info = {"uuid": question_uuid(variants), "title": f"{variants.problem.name} (lagsolve variants)",
            "topic": "Lagrangian mechanics", "tags": ["lagsolve", "variants", variants.slug], "type": "v3"}
    return json.dumps(info, indent=2) + "\n"


def _table(variants: VariantSet) -> list[dict[str, dict[str, float]]]:
    names = variants.exported()
    return [{"params": {**v.values, **v.initial},
             "correct_answers": {n: variants.answer(v, n).value for n in names}} for v in variants.variants]


def server_py(variants: VariantSet) -> str:
    table = json.dumps(_table(variants), indent=1, sort_keys=False)
    return (
        '"""PrairieLearn server for the verified variants written by lagsolve variants (do not edit by hand).\n\n'
        'Each variant below was simulated and its key checked twice; generate() picks one with the per-variant\n'
        'seeded random module and copies its numbers and key."""\n\n'
        "import json\nimport random\n\n"
        f"VARIANTS = json.loads({table!r})\n\n\n"
        "def generate(data):\n"
        "    variant = VARIANTS[random.randrange(len(VARIANTS))]\n"
        '    data["params"].update(variant["params"])\n'
        '    data["correct_answers"].update(variant["correct_answers"])\n'
    )


def _text(value: str) -> str:
    """Text from the file, inert in the page: HTML-escaped, and braces as entities (PrairieLearn renders
    question.html as a Mustache template, so ``{{...}}`` in a description must not become a tag)."""
    return html.escape(value).replace("{", "&#123;").replace("}", "&#125;")


def question_html(variants: VariantSet) -> str:
    problem = variants.problem
    first = variants.variants[0]
    given = [*first.values, *first.initial]
    rows = "\n".join(f"    <li><code>{html.escape(n)}</code> = {{{{params.{n}}}}}</li>" for n in given)
    inputs = "\n".join(
        f'<pl-number-input answers-name="{html.escape(n)}" label="{html.escape(n)} ="'
        f' rtol="{RTOL}" comparison="relabs"></pl-number-input>'
        f"\n<p><small>{_text(variants.answer(first, n).what)}</small></p>"
        for n in variants.exported())
    return (
        "<pl-question-panel>\n"
        f"  <p>{_text(problem.name)}</p>\n"
        f"  <p>{_text(problem.description.strip())}</p>\n"
        "  <p>The numbers of your variant (simulation values and initial state, one consistent system of units):</p>\n"
        f"  <ul>\n{rows}\n  </ul>\n"
        "</pl-question-panel>\n\n"
        f"{inputs}\n"
    )


def question_files(variants: VariantSet) -> dict[str, str]:
    return {"info.json": info_json(variants), "question.html": question_html(variants),
            "server.py": server_py(variants)}
