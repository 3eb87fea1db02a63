"""Degenerate and redundant constraints (lagsolve.mechanics.equations.regularity) are refused with a fix, before
anything is
solved; good constraints, singular points included, pass."""

from __future__ import annotations

import pytest

from lagsolve.errors import SpecError
from lagsolve.mechanics.derivation import derive
from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.model import build_model
from lagsolve.mechanics.equations.regularity import check_constraints
from lagsolve.problem.load import load_text
from mechanics_support import PROBLEMS

PENDULUM = """\
name: Pendulum in Cartesian coordinates
parameters: {m: mass, g: gravity, L: length}
coordinates: [x, y, z]
particles:
  bob: {mass: m, position: [x, y, z]}
gravity: [0, -g, 0]
constraints:
  plane: {holonomic: z}
  rod: {holonomic: CONSTRAINT}
"""


def issues(text: str) -> tuple:
    problem = load_text(text, "p.yaml")
    model = build_model(problem)
    with pytest.raises(SpecError) as caught:
        check_constraints(problem, model, tuple(constraint_terms(c, model) for c in problem.constraints))
    return caught.value.issues


def passes(text: str) -> None:
    problem = load_text(text, "p.yaml")
    model = build_model(problem)
    check_constraints(problem, model, tuple(constraint_terms(c, model) for c in problem.constraints))


def test_a_squared_constraint_is_refused_with_its_simple_form():
    """(x² + y² − L²)² = 0 has a zero gradient on its own surface: refused, with the constraint to write instead."""
    (issue,) = issues(PENDULUM.replace("CONSTRAINT", "(x**2 + y**2 - L**2)**2"))
    assert (issue.file, issue.line, issue.where) == ("p.yaml", 9, "constraints.rod.holonomic")
    assert issue.message == "the gradient of rod vanishes where rod = 0"
    assert issue.hint == "write it as x**2 + y**2 - L**2 = 0"


def test_a_cubed_factor_among_others_is_refused():
    """Any factor with a coordinate repeated is a multiple root: x³ (y − 1) becomes x (y − 1)."""
    (issue,) = issues(PENDULUM.replace("CONSTRAINT", "x**3*(y - 1)"))
    assert issue.hint.startswith("write it as ") and "**3" not in issue.hint


def test_a_double_zero_without_a_factor_is_found_numerically():
    """1 − cos(x − y) vanishes doubly on x = y + 2πk; no polynomial factor shows it, the random states do."""
    (issue,) = issues(PENDULUM.replace("CONSTRAINT", "1 - cos(x - y)"))
    assert issue.message == "the gradient of rod vanishes where rod = 0"
    assert "simple zero" in issue.hint


def test_redundant_constraints_are_named():
    """z = 0 given twice (once as 2 z): the Jacobian has rank 2 of 3 at every state; both are named."""
    text = PENDULUM.replace("CONSTRAINT", "x**2 + y**2 - L**2") + "  again: {holonomic: 2*z}\n"
    (issue,) = issues(text)
    assert issue.where == "constraints.again.holonomic"
    assert "the constraints plane, again are redundant" in issue.message
    assert issue.hint.startswith("remove again")


def test_redundant_velocity_constraint_is_named():
    """A velocity constraint that repeats the derivative of a holonomic one is redundant too."""
    text = PENDULUM.replace("CONSTRAINT", "x**2 + y**2 - L**2") + "  rate: {nonholonomic: x*x_dot + y*y_dot}\n"
    (issue,) = issues(text)
    assert "rod, rate" in issue.message and issue.where == "constraints.rate.nonholonomic"


def test_good_constraints_pass_even_with_singular_points():
    """x² + y² − L² has a zero gradient only at the origin, which is not on its surface; y − f(x) and a
    pendulum written through the pivot pass."""
    passes(PENDULUM.replace("CONSTRAINT", "x**2 + y**2 - L**2"))
    passes(PENDULUM.replace("CONSTRAINT", "x*y"))  # the two axes: the gradient vanishes only where they cross


@pytest.mark.parametrize("stem", sorted(p.stem for p in PROBLEMS.glob("*.yaml")))
def test_every_shipped_problem_passes(stem: str) -> None:
    problem = load_text((PROBLEMS / f"{stem}.yaml").read_text(), stem)
    model = build_model(problem, tidy=False)
    check_constraints(problem, model, tuple(constraint_terms(c, model) for c in problem.constraints))


def test_derive_refuses_a_degenerate_constraint():
    with pytest.raises(SpecError, match="the gradient of rod vanishes where rod = 0"):
        derive(load_text(PENDULUM.replace("CONSTRAINT", "(x**2 + y**2 - L**2)**2"), "p.yaml"))


@pytest.mark.parametrize("constraint", ["sqrt(x**2 + y**2 - 1) - L", "log(y) - x", "acos(x/L) - y",
                                        "sqrt(y - x**2)**2 - L"])
def test_constraints_outside_their_domain_at_some_states_still_pass(constraint: str) -> None:
    """Random states where a square root, logarithm or arccosine has no real value count as not a number (the
    checks evaluate with the math module, which raises there): a good constraint still passes."""
    passes(PENDULUM.replace("CONSTRAINT", constraint))


def test_a_squared_root_constraint_outside_its_domain_is_still_found_degenerate() -> None:
    """Where some states have no real value, the degenerate constraint is still found from the others."""
    (issue,) = issues(PENDULUM.replace("CONSTRAINT", "(sqrt(x**2 + y**2) - L)**2"))
    assert issue.message == "the gradient of rod vanishes where rod = 0"
