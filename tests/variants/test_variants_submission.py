"""The model submission of a variant set (``variants/submission.py``) is read by ``lagsolve grade`` and earns full
marks on every step the key answers, the Hamiltonian included."""

from __future__ import annotations

from pathlib import Path

from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading, default_weights
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem
from lagsolve.variants.submission import model_submission

ROOT = Path(__file__).resolve().parents[2]


def test_the_hamiltonian_of_a_fixed_angle_uses_only_the_key_names() -> None:
    # the tube's theta is held by a velocity constraint: H was written with its integration constant theta0,
    # a name the submission reader does not know (the step was unreadable)
    problem = load_problem(ROOT / "problems" / "rotating_tube.yaml")
    derivation = derive(problem)
    text = model_submission(derivation)
    assert "theta0" not in text
    normals = {f.term.normal.name: f.term.normal for f in derivation.friction}
    submission = read_text(text, problem, "model_submission.yaml", normals=normals)
    grading = Grading({**default_weights(problem), "hamiltonian": 1.0})
    result = grade(derivation, grading, submission)
    assert {s.step: s.status for s in result.steps if s.status != "correct"} == {}
    assert result.points == result.max_points
