"""The key's ``grading:`` section: the weight of each step, the credit of a step that follows from an
earlier mistake, and whether the opposite sign convention of λ is accepted.

.. code-block:: yaml

    grading:
      weights: {equations: 4, multipliers: 2}   # points per step; a step with no weight is not graded
      follow_through: 0.5                         # share of a step's points for `follows` (default 1)
      lambda_sign: either                         # strict (default): -λ is the mistake lambda_sign_convention
      frequency_form: squared                     # either (default): ω or ω²; squared: ω² only
      step_budget: 10                             # CPU seconds to grade one step of one submission (default 10)

Without ``weights`` the steps of the derivation's core are graded (:func:`default_weights`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lagsolve.errors import Issue, SpecError
from lagsolve.grade.submission import STEPS
from lagsolve.problem.schema import Problem
from lagsolve.problem.yamlread import dotted, kind_of, read_document

#: default weight of each step the core of a derivation answers
DEFAULT_WEIGHTS = {"kinetic": 1.0, "potential": 1.0, "lagrangian": 1.0, "constraints": 1.0, "momenta": 1.0,
                   "generalized_forces": 1.0, "equations": 2.0, "accelerations": 2.0, "multipliers": 1.0,
                   "constraint_forces": 1.0, "normal_force": 1.0}
LAMBDA_SIGN = ("strict", "either")
#: what a submission's frequencies may be: ω² or ω (either, the default), or ω² only (squared)
FREQUENCY_FORM = ("either", "squared")
#: CPU seconds one step of one submission may take to grade (then it is `ungraded`)
STEP_BUDGET = 10.0


@dataclass(frozen=True)
class Grading:
    """``weights`` by step (in :data:`~lagsolve.grade.submission.STEPS` order), ``follow_through`` in [0, 1],
    ``lambda_sign`` strict or either, ``frequency_form`` either (ω or ω²) or squared (ω² only), ``step_budget``
    the CPU seconds one step of one submission may take to grade."""

    weights: dict[str, float]
    follow_through: float = 1.0
    lambda_sign: str = "strict"
    frequency_form: str = "either"
    step_budget: float = STEP_BUDGET


def default_weights(problem: Problem) -> dict[str, float]:
    """The core steps that apply to ``problem`` (no constraint steps without constraints, no normal force
    without friction)."""
    skip = set()
    if not problem.constraints:
        skip |= {"constraints", "multipliers", "constraint_forces"}
    if not problem.friction:
        skip.add("normal_force")
    return {k: v for k, v in DEFAULT_WEIGHTS.items() if k not in skip}


def _weights(raw: Any, fail: Any) -> dict[str, float]:
    """The points of each step from ``grading.weights`` (a step with 0 is not graded); ``fail(where, message,
    hint)`` makes the error of a malformed entry."""
    if not isinstance(raw, dict) or not raw:
        raise fail(("grading", "weights"), f"expected a mapping of steps to points, found {kind_of(raw)}")
    weights = {}
    for step in STEPS:
        if step not in raw:
            continue
        value = raw[step]
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) \
                or not 0 <= value <= 1000:
            raise fail(("grading", "weights", step), f"expected a number of points from 0 to 1000, found {value!r}")
        if value:
            weights[step] = float(value)
    for step in raw:
        if step not in STEPS:
            raise fail(("grading", "weights", step), f"unknown step {step!r}", f"the steps are: {', '.join(STEPS)}")
    return weights


def read_grading(path: str | Path, problem: Problem) -> Grading:
    """The ``grading:`` section of the key file ``path`` (already loaded as ``problem``).

    Raises
    ------
    SpecError
        The section is malformed (unknown step, negative weight, follow_through outside [0, 1], ...).
    """
    source = str(path)
    document = read_document(Path(path).read_bytes(), source)
    spec = document.data.get("grading") if isinstance(document.data, dict) else None

    def fail(where: tuple, message: str, hint: str = "") -> SpecError:
        line = document.lines.get(where, document.lines.get(("grading",), 0))
        return SpecError([Issue(source, line, dotted(where), message, hint)])

    if spec is None:
        return Grading(default_weights(problem))
    if not isinstance(spec, dict):
        raise fail(("grading",), f"expected a mapping, found {kind_of(spec)}",
                   "write e.g. 'grading: {weights: {equations: 4}, follow_through: 0.5}'")
    for key in spec:
        if key not in ("weights", "follow_through", "lambda_sign", "frequency_form", "step_budget"):
            raise fail(("grading", key), f"unknown key {key!r}",
                       "use weights, follow_through, lambda_sign, frequency_form, step_budget")
    weights = _weights(spec["weights"], fail) if "weights" in spec else default_weights(problem)
    follow = spec.get("follow_through", 1.0)
    if isinstance(follow, bool) or not isinstance(follow, int | float) or not 0 <= follow <= 1:
        raise fail(("grading", "follow_through"), f"expected a number from 0 to 1, found {follow!r}")
    sign = spec.get("lambda_sign", "strict")
    if sign not in LAMBDA_SIGN:
        raise fail(("grading", "lambda_sign"), f"expected one of {', '.join(LAMBDA_SIGN)}, found {sign!r}")
    form = spec.get("frequency_form", "either")
    if form not in FREQUENCY_FORM:
        raise fail(("grading", "frequency_form"), f"expected one of {', '.join(FREQUENCY_FORM)}, found {form!r}")
    budget = spec.get("step_budget", STEP_BUDGET)
    if isinstance(budget, bool) or not isinstance(budget, int | float) or not 0.1 <= budget <= 3600:
        raise fail(("grading", "step_budget"), f"expected CPU seconds from 0.1 to 3600, found {budget!r}")
    return Grading(weights, float(follow), sign, form, float(budget))
