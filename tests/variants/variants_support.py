"""What the variants tests share: the level tube with static friction, its closed forms, and a checker that runs
``lagsolve check`` on a variant's problem text against one shared derivation (the variants differ only in their
numbers, which a derivation does not read)."""

from __future__ import annotations

import dataclasses
import importlib
from pathlib import Path
from typing import Any

from lagsolve.check.compare import CheckReport, check
from lagsolve.mechanics.derivation import Derivation
from lagsolve.problem.load import load_text

TUBE = Path(__file__).resolve().parents[1] / "data" / "variants" / "rough_level_tube.yaml"
TUBE_VARY = ("mu_s=0.1:0.6", "Omega=1:4", "r=0.5:1.5")

#: the package's modules (``lagsolve.variants`` itself is the library function)
run = importlib.import_module("lagsolve.variants.run")
layout = importlib.import_module("lagsolve.variants.layout")
spec = importlib.import_module("lagsolve.variants.spec")


def tube_sticks(values: dict[str, float], initial: dict[str, float]) -> bool:
    """The closed form: at rest relative to the tube, the particle is held while mu_s*g >= Omega**2*r."""
    return values["mu_s"] * values["g"] >= values["Omega"] ** 2 * initial["r"]


def check_text(derivation: Derivation, text: str) -> CheckReport:
    """``lagsolve check`` of a variant's problem text, with the shared derivation."""
    problem = load_text(text, derivation.problem.source)
    assert dataclasses.replace(problem, expected=derivation.problem.expected,
                               simulation=derivation.problem.simulation, lines=derivation.problem.lines,
                               texts=derivation.problem.texts) == derivation.problem, "only numbers may change"
    form = dataclasses.replace(derivation.form, problem=problem)
    return check(dataclasses.replace(derivation, form=form))


def answers(variant: Any) -> dict[str, float]:
    return {a.name: a.value for a in variant.key.answers}
