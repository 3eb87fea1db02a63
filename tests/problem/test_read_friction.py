"""problem/readers/friction.py: a friction contact is a pair, with its point; its normal constraints become
contacts between the same pair at the same point."""

from __future__ import annotations

import pytest

from lagsolve.errors import SpecError
from lagsolve.problem.load import load_text

WEDGE = """
name: block on a wedge
parameters: {m: mass, M: mass, g: gravity, mu: friction}
coordinates: [X, x, y]
particles:
  wedge: {mass: M, position: [X, 0]}
  block: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  face: {holonomic: y - x + X, on: FACE}
friction:
  rub: {coefficient: mu, RUB normal: [face]}
"""


def _load(face: str, rub: str):  # type: ignore[no-untyped-def]
    return load_text(WEDGE.replace("FACE", face).replace("RUB ", rub))


@pytest.mark.parametrize(("face", "rub"), [
    ("[block, wedge]", ""),                      # from the normal constraint
    ("block", "on: [block, wedge], "),           # named on the friction
    ("[block, wedge]", "on: block, "),           # the friction names what slides, the constraint the pair
    ("[block, wedge]", "on: [block, wedge], "),  # both
])
def test_the_pair_comes_from_the_friction_or_its_normal_constraint(face: str, rub: str) -> None:
    """However the pair is given, the friction acts between block and wedge at the block's position, and the
    face is a contact between the same two at the same point."""
    problem = _load(face, rub)
    (friction,) = problem.friction
    (constraint,) = problem.constraints
    block = problem.particle("block").position
    assert (friction.on, friction.against, friction.at) == ("block", "wedge", block)
    assert (constraint.on, constraint.at) == (("block", "wedge"), block)


def test_a_contact_with_the_ground_has_no_second_member() -> None:
    problem = _load("block", "")
    assert (problem.friction[0].on, problem.friction[0].against) == ("block", None)


@pytest.mark.parametrize(("face", "rub", "field", "words"), [
    ("[block, wedge]", "on: [block, other], ", "friction.rub.on", "cannot carry the surface"),
    ("[wedge, block]", "on: block, ", "friction.rub.normal", "a normal force acts between the two members"),
    ("[block, wedge]", "on: [block, wedge, wedge], ", "friction.rub.on", "expected the name of what slides"),
    ("[block, wedge]", "at: [x, y + 1], ", "friction.rub.at", "is a particle, a point"),
    ("[block, wedge]", "on: 3, ", "friction.rub.on", "expected the name of what slides"),
])
def test_a_pair_that_does_not_fit_is_refused(face: str, rub: str, field: str, words: str) -> None:
    """An unknown second member, a normal constraint on another member, three names, a point away from the
    particle: exit 2 with the field and a fix."""
    with pytest.raises(SpecError) as caught:
        _load(face, rub)
    assert any(i.where == field and words in i.message and i.hint for i in caught.value.issues), caught.value.issues


def test_a_particle_contact_may_name_its_point() -> None:
    """A smooth contact between two particles is declared with 'at:', the first particle's position: its force
    then acts on both, opposite (without 'at:' and without friction, 'on:' lists particles a constraint acts on)."""
    text = WEDGE.replace("on: FACE}", "on: [block, wedge], at: [x, y]}").split("friction:")[0]
    (constraint,) = load_text(text).constraints
    assert constraint.at is not None and constraint.on == ("block", "wedge")


def test_friction_on_a_body_takes_the_point_of_its_normal_constraint() -> None:
    text = """
name: disc
parameters: {m: mass, R: radius, g: gravity, mu: friction}
coordinates: [x, y, phi]
bodies:
  disc: {mass: m, position: [x, y], inertia: m*R**2/2, angular_velocity: -phi_dot}
gravity: [0, -g]
constraints:
  floor: {holonomic: y - R, on: disc, at: [x, y - R]}
friction:
  grip: {coefficient: mu, normal: [floor]}
"""
    problem = load_text(text)
    (friction,) = problem.friction
    assert friction.on == "disc" and friction.at == problem.constraints[0].at
    with pytest.raises(SpecError) as caught:
        load_text(text.replace("on: disc, at: [x, y - R]}", "on: disc, at: [x, y - R]}").replace(
            "normal: [floor]}", "at: [x, y], normal: [floor]}"))
    assert any(i.where == "friction.grip.at" and "at one point" in i.message for i in caught.value.issues)


@pytest.mark.parametrize("field", ["coefficient", "static"])
def test_a_negative_coefficient_is_refused(field: str) -> None:
    text = WEDGE.replace("FACE", "[block, wedge]").replace("RUB ", f"{'static: -0.2, ' if field == 'static' else ''}")
    if field == "coefficient":
        text = text.replace("coefficient: mu", "coefficient: -1/2")
    with pytest.raises(SpecError) as caught:
        load_text(text)
    assert any(i.where == f"friction.rub.{field}" and "negative" in i.message for i in caught.value.issues)
