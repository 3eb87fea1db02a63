"""Degrees of freedom (``lagsolve.mechanics.analysis.freedom``), against textbook counts and an independent route:
the free velocities are n less the rank of the constraint matrix A (evaluated at a random state), and the
coordinates a configuration needs are n less the holonomic constraints, counted from the file's own kinds and the
velocity constraints a textbook integrates."""

from __future__ import annotations

import random
from collections.abc import Callable
from typing import Any

import pytest
import sympy
from sympy.core.function import AppliedUndef

#: (problem, coordinates a configuration needs, free velocities): the textbook counts
TEXTBOOK = [
    ("bead", 1, 1),                    # x, y on the wire y = f(x)
    ("pendulum_cartesian", 1, 1),      # x, y with x² + y² = l²
    ("double_pendulum", 2, 2),
    ("atwood", 1, 1),
    ("knife_edge", 3, 2),              # x, y, θ; no sideways slip (nonholonomic)
    ("rolling_coin", 4, 2),            # vertical coin: x, y, θ, φ; rolling without slipping
    ("rolling_disc", 5, 3),            # inclined disc: x, y and three Euler angles
    ("rolling_incline", 1, 1),         # rolling along a line: the velocity constraint integrates
    ("two_masses_spring", 2, 2),
    ("differential_drive", 5, 2),
]


@pytest.mark.parametrize(("name", "configuration", "velocities"), TEXTBOOK, ids=[t[0] for t in TEXTBOOK])
def test_textbook_counts(name: str, configuration: int, velocities: int,
                         shipped_derivation: Callable[[str], Any]) -> None:
    """The two degrees of freedom of shipped problems, as textbooks count them."""
    f = shipped_derivation(name).analysis.freedom
    assert (f.configuration, f.velocities) == (configuration, velocities)


@pytest.mark.parametrize("name", [t[0] for t in TEXTBOOK])
def test_free_velocities_are_n_less_the_rank_of_the_constraint_matrix(
        name: str, shipped_derivation: Callable[[str], Any]) -> None:
    """Independent route: n − rank A(q, t) at a random state (A from the constraints' coefficients)."""
    d = shipped_derivation(name)
    rng = random.Random(3)
    A = sympy.Matrix([list(c.coefficients) for c in d.constraints]) if d.constraints else sympy.zeros(0, 1)
    # unspecified functions and their derivatives first (f'(x) is a number at a state), then the symbols
    functions = A.atoms(sympy.Derivative) | A.atoms(AppliedUndef)
    A = A.xreplace({a: sympy.Rational(rng.randint(11, 97), 37) for a in functions})
    at_state = A.xreplace({s: sympy.Rational(rng.randint(11, 97), 37) for s in A.free_symbols})
    rank = at_state.rank() if d.constraints else 0
    assert d.analysis.freedom.velocities == len(d.problem.coordinates) - rank


def test_the_sentence_says_both_counts_for_a_nonholonomic_system(shipped_derivation: Callable[[str], Any]) -> None:
    """The knife edge's report, JSON and terminal give 3 coordinates and 2 free velocities."""
    from lagsolve.render.report import result_dict, summary

    d = shipped_derivation("knife_edge")
    assert result_dict(d)["analysis"]["degrees_of_freedom"] == {
        "coordinates": 3, "holonomic": 0, "nonholonomic": 1, "unresolved": 0, "configuration": 3, "velocities": 2}
    assert "  degrees of freedom: 2 (3 coordinates fix a configuration: nonholonomic)" in summary(d).splitlines()
    from lagsolve.render.report import render

    page = render(d, "md")
    assert "### Degrees of freedom" in page and "so 2 velocities are free" in page


def test_an_unsettled_velocity_constraint_leaves_the_configuration_count_unknown() -> None:
    """A velocity constraint whose integrability is not settled: the free velocities are still known."""
    from lagsolve.mechanics.analysis.freedom import freedom
    from lagsolve.mechanics.analysis.integrability import Classification, Integrability
    from lagsolve.problem.load import load_text

    problem = load_text("name: p\ncoordinates: [x, y]\nparameters: [m]\nkinetic: m*(x_dot**2 + y_dot**2)/2\n"
                        "constraints:\n  c: {nonholonomic: x_dot - y*y_dot}\n", "p.yaml")
    unsettled = Classification("c", Integrability.UNRESOLVED)
    f = freedom(problem, [unsettled])
    assert (f.configuration, f.velocities) == (None, 1)
    assert freedom(problem, []).unresolved == 1  # not classified (its stage did not finish): not settled either
