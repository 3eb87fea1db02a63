"""A model submission for a variant set (``model_submission.yaml``): the derivation's answer to every step of
``lagsolve grade``'s format, printed by SymPy, so that ``lagsolve grade variant-NN/<slug>.yaml
model_submission.yaml`` shows the key earning full marks (the answers do not depend on the numbers: one file
serves every variant)."""

from __future__ import annotations

import io
from typing import Any

import sympy
from ruamel.yaml import YAML

from lagsolve.grade.analysis_steps import reduction_constants
from lagsolve.grade.grader import key_answers
from lagsolve.grade.submission import LISTS, SCALAR
from lagsolve.mechanics.results import Derivation


def model_submission(derivation: Derivation) -> str:
    """The key's answers as a submission; an integration constant of the minimal coordinates (θ0 of θ = θ0, in H) is
    written as the coordinate expression it stands for (θ), since a submission may use only the key's names."""
    steps: dict[str, Any] = {}
    constants = reduction_constants(derivation)

    def shown(value: Any) -> str:
        return sympy.sstr(value.xreplace(constants) if isinstance(value, sympy.Basic) else value)

    for step, entries in key_answers(derivation).items():
        if step in LISTS or not entries:
            continue  # equilibria and frequencies are graded as lists of points; not written here
        if step in SCALAR:
            steps[step] = shown(entries[""])
        else:
            steps[step] = {name: shown(value) for name, value in entries.items()}
    yaml = YAML(typ="safe", pure=True)
    yaml.default_flow_style = False
    yaml.width = 4096
    out = io.StringIO()
    yaml.dump({"student": "key", "steps": steps}, out)
    return "# the key's answers in lagsolve grade's submission format (written by lagsolve variants)\n" + out.getvalue()
