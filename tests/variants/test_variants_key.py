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


def test_frequencies_found_numerically_at_the_files_values_are_not_a_key() -> None:
    # the triple pendulum's ω² are numeric at the file's g = 9.81 (its characteristic polynomial does not split):
    # taken as closed forms at each variant's g they disagreed with the variant's own (2.0196 against 1.8442 at
    # g = 8.18), so every candidate failed the rule 'key' and no variant could be made (exit 2)
    made = lagsolve.variants(ROOT / "problems" / "triple_pendulum.yaml", count=1, vary={"g": "8.18:8.18"})
    names = {a.name for a in made.variants[0].key.answers}
    assert "equilibrium_1_theta1" in names and not any(n.startswith("omega_") for n in names)
    assert made.rejections.get("key", 0) == 0


def test_an_answer_too_long_for_the_reader_is_left_out_of_the_expected_section() -> None:
    # the differential drive's phiR_ddot prints to 2935 characters (the reader's limit is 2000): the whole command
    # stopped with exit 2 and "differential_drive.yaml:64: expected.accelerations.phiR: expression is 2935
    # characters long", a line of a file the user never wrote
    made = lagsolve.variants(ROOT / "problems" / "differential_drive.yaml", count=1, vary={"mc": "1.5:1.5"})
    assert "phiR" not in made.expected.get("accelerations", {}) and "theta" in made.expected["accelerations"]
    assert any(n.startswith("accelerations.phiR left out of the key") for n in made.notes)
    assert "phiR_ddot" in {a.name for a in made.variants[0].key.answers}  # still in the numeric key
