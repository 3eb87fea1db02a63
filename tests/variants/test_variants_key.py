"""The key of a variant (``variants/key.py``) on a problem with a declared function: its closed forms are evaluated
with the function's concrete form (``simulation.functions``), as the simulation is."""

from __future__ import annotations

from pathlib import Path

import lagsolve

ROOT = Path(__file__).resolve().parents[2]


def test_a_problem_with_a_declared_function_gets_its_key() -> None:
    # the bead on y = f(x), f(u) = u**2/2, at rest at x = -1.5: evaluating Derivative(f(x), x) at x = -1.5 raised
    # "Can't calculate derivative wrt -1.5" (a traceback, exit 1) for every variant
    made = lagsolve.variants(ROOT / "problems" / "bead.yaml", count=1, vary={"g": "2:2"})
    (variant,) = made.variants
    answers = {a.name: a.value for a in variant.key.answers}
    g, slope = 2.0, -1.5  # f'(x) = x, f''(x) = 1, x_dot = 0
    assert abs(answers["x_ddot"] - (-slope * g / (1 + slope**2))) < 1e-5
    assert abs(answers["lambda_wire"] - g / (1 + slope**2)) < 1e-5
    assert abs(answers["F_wire"] - g / (1 + slope**2) ** 0.5) < 1e-5
