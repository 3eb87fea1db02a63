"""The sweep's inputs and Poincaré sections are read by a strict grammar; bad text is refused with a fix."""

from __future__ import annotations

import numpy as np
import pytest

from lagsolve.errors import SpecError
from lagsolve.sweep.spec import Names, inputs, parse_grid, parse_random, parse_section

NAMES = Names(("m", "g", "k"), frozenset({"m", "g"}), ("theta1", "theta2"))


def test_grid_is_evenly_spaced_and_a_cartesian_product() -> None:
    """Two grids give every pair, the first name varying slowest."""
    a = parse_grid("theta1=0:1:3", NAMES)
    b = parse_grid(" theta2_dot = -1 : 1e0 : 2 ", NAMES)
    assert a[0] == "theta1" and np.allclose(a[1], [0, 0.5, 1])
    columns = inputs([a, b], [], None, 0)
    assert list(columns["theta1"]) == [0, 0, 0.5, 0.5, 1, 1]
    assert list(columns["theta2_dot"]) == [-1, 1, -1, 1, -1, 1]


def test_random_draws_repeat_per_grid_point() -> None:
    """--random with --runs draws that many values per grid point, reproducibly from the seed."""
    columns = inputs([parse_grid("k=1:2:2", NAMES)], [parse_random("theta1=0:pi", NAMES)], 3, 5)
    assert list(columns["k"]) == [1, 1, 1, 2, 2, 2]
    assert np.all((columns["theta1"] >= 0) & (columns["theta1"] < np.pi))
    assert np.array_equal(columns["theta1"], np.random.default_rng(5).uniform(0, np.pi, 6))


@pytest.mark.parametrize(("text", "message"), [
    ("theta1", "not of the form NAME=START:STOP:COUNT"),
    ("phi=0:1:3", "unknown name 'phi'"),
    ("theta1=0:1", "not of the form"),
    ("theta1=0:1:x", "COUNT 'x' is not a whole number"),
    ("theta1=0:nan:3", "STOP 'nan' is not a finite number"),
    ("theta1=__import__('os'):1:3", "START"),
    ("m=-1:1:3", "parameter 'm' is positive"),
    ("theta1=0:1:0", "COUNT '0'"),
])
def test_bad_grid_is_refused(text: str, message: str) -> None:
    """A malformed or unknown grid names what is wrong and how to write it."""
    with pytest.raises(SpecError) as caught:
        parse_grid(text, NAMES)
    assert message in str(caught.value)


def test_runs_and_random_go_together() -> None:
    """--random needs --runs, --runs needs --random, a name is swept once, and something is swept."""
    for grid, random, runs, message in (([], [("k", 0.0, 1.0)], None, "--random needs the number of runs"),
                                        ([parse_grid("k=0:1:2", NAMES)], [], 3, "--runs without --random"),
                                        ([parse_grid("k=0:1:2", NAMES)], [("k", 0.0, 1.0)], 2, "swept twice"),
                                        ([], [], None, "nothing to sweep")):
        with pytest.raises(SpecError, match=message):
            inputs(grid, random, runs, 0)


def test_section_grammar() -> None:
    """An equation, then conditions with <, <=, >, >=; numbers may be signed, exponents or ±pi."""
    section = parse_section("theta2 = 0, theta2_dot > 0, theta1 <= -pi, theta1_dot>=1.5e-3", NAMES)
    assert (section.name, section.index, section.value) == ("theta2", 1, 0.0)
    assert section.conditions == ((3, ">", 0.0), (0, "<=", -np.pi), (2, ">=", 1.5e-3))
    states = np.array([[-4.0, 0.0, 1.0, 1.0], [-4.0, 0.0, 1.0, -1.0]])
    assert list(section.holds(states)) == [True, False]


@pytest.mark.parametrize(("text", "message"), [
    ("theta2_dot>0", "the first part must be an equation"),
    ("theta2=0, theta1=1", "only the first part is an equation"),
    ("theta2==0", "is not a finite number"),
    ("theta2=0,", "cannot read ''"),
    ("phi=0", "'phi' is not a coordinate or velocity"),
    ("m=1", "'m' is not a coordinate or velocity"),
    ("theta2=__import__('os').system('true')", "is not a finite number"),
    ("theta2=0; theta2_dot>0", "is not a finite number"),
    ("theta2=0, theta2_dot>0 and theta1>0", "is not a finite number"),
    ("theta2=1/2", "is not a finite number"),
])
def test_bad_sections_are_refused_with_a_fix(text: str, message: str) -> None:
    """Anything outside the grammar is refused (never evaluated), with an example of the right form."""
    with pytest.raises(SpecError) as caught:
        parse_section(text, NAMES)
    assert message in str(caught.value)
    assert "--poincare" in str(caught.value)
