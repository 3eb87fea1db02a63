"""Binding a derivation to numbers: values, concrete functions, the numeric augmented solve."""

from __future__ import annotations

import numpy as np
import pytest

from lagsolve.errors import SpecError
from lagsolve.mechanics.derivation import derive
from lagsolve.numeric.system import bind
from lagsolve.problem.load import load_text
from simulation_support import CARTESIAN_PENDULUM

BEAD = """
name: Bead
parameters: {m: mass, g: gravity}
functions: {f: wire}
coordinates: [x, y]
particles: {bead: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints: {wire: {holonomic: y - f(x)}}
simulation:
  values: {m: 2.0, g: 9.81}
  functions: {"f(u)": "u**2/2"}
"""


def test_numeric_solve_matches_the_closed_form() -> None:
    """The per-step augmented solve gives the bead's ẍ and λ of the textbook closed form."""
    system = bind(derive(load_text(BEAD)))
    rng = np.random.default_rng(1)
    for _ in range(20):
        x, xd = rng.uniform(-2, 2, 2)
        q, qd = np.array([x, x**2 / 2]), np.array([xd, x * xd])
        qdd, lam = system.solve(0.0, q, qd)
        assert qdd[0] == pytest.approx(-x * (xd**2 + 9.81) / (1 + x**2))
        assert lam[0] == pytest.approx(2.0 * (xd**2 + 9.81) / (1 + x**2))


def test_overrides_replace_file_values() -> None:
    """--set values take precedence over simulation.values."""
    system = bind(derive(load_text(BEAD)), {"g": 1.62})
    assert dict(zip(system.parameter_names, system.parameters, strict=True)) == {"m": 2.0, "g": 1.62}


def test_missing_parameter_value_is_named() -> None:
    """A parameter the equations need but nobody gave a value is an error that names it."""
    text = BEAD.replace("values: {m: 2.0, g: 9.81}", "values: {m: 2.0}")
    with pytest.raises(SpecError, match="no value for parameter g; give it under simulation.values or with --set"):
        bind(derive(load_text(text)))


def test_missing_concrete_function_is_named() -> None:
    """A declared function without a concrete form cannot be simulated; the error says how to add one."""
    text = BEAD.replace('  functions: {"f(u)": "u**2/2"}\n', "")
    with pytest.raises(SpecError, match="function 'f' has no concrete form"):
        bind(derive(load_text(text)))


def test_unknown_override_is_refused() -> None:
    """--set of a name that is not a parameter is an error listing the known ones."""
    with pytest.raises(SpecError, match="unknown parameter 'h'.*known: g, m"):
        bind(derive(load_text(BEAD)), {"h": 1.0})


def test_energy_conservation_is_decided_from_the_equations() -> None:
    """Energy counts as conserved for a workless, time-independent system."""
    system = bind(derive(load_text(CARTESIAN_PENDULUM)))
    assert system.energy_conserved and "workless" in system.energy_note
    assert system.holonomic == (0,)
