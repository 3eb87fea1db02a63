"""The files of a variant set, by path relative to the output folder (written by the caller, through
:func:`lagsolve.files.write_file`):

``variant-NN/<slug>.yaml``   the problem file with the variant's numbers and the ``expected:`` key
``variant-NN/solution.md``   its worked solution
``variant-NN/key.json``      its numbers (value, what, how verified) and regime
``variant-NN/*.png``         with ``--figures``: its coordinates and forces against time
``variants.csv``             one row per variant: the varied values, the regime, every answer
``summary.json``             the request, attempts and rejections per rule, notes
``model_submission.yaml``    the key in ``lagsolve grade``'s submission format (full marks on every variant)
and, with ``--to``, ``prairielearn/<slug>/`` or ``moodle/<slug>.xml``.
"""

from __future__ import annotations

import csv
import io
import json
from typing import Any

from lagsolve.variants.run import VariantSet
from lagsolve.variants.solution import variant_markdown
from lagsolve.variants.spec import Export


def folder(variants: VariantSet, index: int) -> str:
    width = max(2, len(str(len(variants.variants))))
    return f"variant-{index:0{width}d}"


def summary(variants: VariantSet) -> dict[str, Any]:
    request = variants.request
    return {
        "source": variants.problem.source,
        "count": request.count,
        "seed": request.seed,
        "vary": [{"name": v.name, "low": v.low, "high": v.high, "step": v.step} for v in request.vary],
        "require": str(request.require) if request.require else None,
        "sig_figs": request.sig_figs,
        "attempts": variants.attempts,
        "rejections": variants.rejections,
        "notes": list(variants.notes),
    }


def table(variants: VariantSet) -> str:
    names = variants.answer_names()
    varied = [v.name for v in variants.request.vary]
    contacts = sorted({c for v in variants.variants for c in v.key.regime})
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["variant", *varied, *(f"regime_{c}" for c in contacts), *names])
    for v in variants.variants:
        answers = {a.name: a.value for a in v.key.answers}
        writer.writerow([v.index, *(repr(v.varied[n]) for n in varied), *(v.key.regime.get(c, "") for c in contacts),
                         *(repr(answers[n]) if n in answers else "" for n in names)])
    return out.getvalue()


def files(variants: VariantSet) -> dict[str, str | bytes]:
    """Every file of the set, by relative path, in a fixed order."""
    out: dict[str, str | bytes] = {}
    slug, count = variants.slug, len(variants.variants)
    for v in variants.variants:
        place = folder(variants, v.index)
        out[f"{place}/{slug}.yaml"] = v.text
        out[f"{place}/solution.md"] = variant_markdown(variants.problem.name, v.index, count, v.values, v.initial,
                                                       v.key, v.summary, variants.report, tuple(v.figures))
        out[f"{place}/key.json"] = json.dumps(v.key.as_dict(), indent=2) + "\n"
        out.update({f"{place}/{name}.png": png for name, png in v.figures.items()})
    out["model_submission.yaml"] = variants.submission
    out["variants.csv"] = table(variants)
    out["summary.json"] = json.dumps(summary(variants), indent=2) + "\n"
    if variants.request.to == Export.PRAIRIELEARN:
        from lagsolve.variants.prairielearn import question_files

        out.update({f"prairielearn/{slug}/{k}": t for k, t in question_files(variants).items()})
    elif variants.request.to == Export.MOODLE:
        from lagsolve.variants.moodle import quiz_xml

        out[f"moodle/{slug}.xml"] = quiz_xml(variants)
    return out
