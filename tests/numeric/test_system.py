"""Binding a derivation to numbers: values, concrete functions, the numeric augmented solve."""

from __future__ import annotations

import numpy as np
import pytest

from lagsolve.errors import SpecError
from lagsolve.mechanics.equations.matrix_form import matrix_form
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
    system = bind(matrix_form(load_text(BEAD)))
    rng = np.random.default_rng(1)
    for _ in range(20):
        x, xd = rng.uniform(-2, 2, 2)
        q, qd = np.array([x, x**2 / 2]), np.array([xd, x * xd])
        qdd, lam = system.solve(0.0, q, qd)
        assert qdd[0] == pytest.approx(-x * (xd**2 + 9.81) / (1 + x**2))
        assert lam[0] == pytest.approx(2.0 * (xd**2 + 9.81) / (1 + x**2))


def test_overrides_replace_file_values() -> None:
    """--set values take precedence over simulation.values."""
    system = bind(matrix_form(load_text(BEAD)), {"g": 1.62})
    assert dict(zip(system.parameter_names, system.parameters, strict=True)) == {"m": 2.0, "g": 1.62}


def test_missing_parameter_value_is_named() -> None:
    """A parameter the equations need but nobody gave a value is an error that names it."""
    text = BEAD.replace("values: {m: 2.0, g: 9.81}", "values: {m: 2.0}")
    with pytest.raises(SpecError, match="no value for parameter g; give it under simulation.values or with --set"):
        bind(matrix_form(load_text(text)))


def test_missing_parameter_value_names_a_line_without_a_simulation_section() -> None:
    """Without a simulation section (``lagsolve export`` of a file that only derives) the error names the line where
    the first missing parameter is declared (it named line 0); with one, the values' line."""
    head = BEAD.split("simulation:")[0]
    with pytest.raises(SpecError) as raised:
        bind(matrix_form(load_text(head, "nosim.yaml")))
    issue = next(i for i in raised.value.issues if i.where == "simulation.values")
    declared = next(n for n, line in enumerate(head.splitlines(), 1) if line.startswith("parameters:"))
    assert issue.line == declared > 0 and "no value for parameters g, m" in issue.message
    text = BEAD.replace("values: {m: 2.0, g: 9.81}", "values: {m: 2.0}")
    with pytest.raises(SpecError) as raised:
        bind(matrix_form(load_text(text)))
    line = next(n for n, row in enumerate(text.splitlines(), 1) if "values: {m: 2.0}" in row)
    assert raised.value.issues[0].line == line


def test_missing_concrete_function_is_named() -> None:
    """A declared function without a concrete form cannot be simulated; the error says how to add one."""
    text = BEAD.replace('  functions: {"f(u)": "u**2/2"}\n', "")
    with pytest.raises(SpecError, match="function 'f' has no concrete form"):
        bind(matrix_form(load_text(text)))


def test_unknown_override_is_refused() -> None:
    """--set of a name that is not a parameter is an error listing the known ones."""
    with pytest.raises(SpecError, match="unknown parameter 'h'.*known: g, m"):
        bind(matrix_form(load_text(BEAD)), {"h": 1.0})


def test_energy_conservation_is_taken_from_the_mechanics() -> None:
    """The numeric system does not decide energy conservation again: it is conserved exactly when the
    mechanics (mechanics.analysis.monitored) gives an 'energy', and otherwise it carries the mechanics' reason."""
    from lagsolve.mechanics.analysis.analyse import monitored

    form = matrix_form(load_text(CARTESIAN_PENDULUM))
    conserved, _, _, note = monitored(form)
    assert "energy" in conserved and note == ""
    system = bind(form, None, conserved, energy_note=note)
    assert system.energy_conserved and system.holonomic == (0,)
    unclaimed = bind(form, None, {}, energy_note="because")
    assert not unclaimed.energy_conserved and unclaimed.energy_note == "because"


ROUGH_TUBE_CLOSED_FORM = """r*Omega**2*sin(theta)**2 - g*cos(theta)
  - mu*sign(r_dot)*Abs(sin(theta))*sqrt(4*Omega**2*r_dot**2 + (r*Omega**2*cos(theta) + g)**2)"""


def test_friction_normal_force_matches_the_closed_form() -> None:
    """In the rough rotating tube the per-step normal force and r̈ equal the homework's closed forms."""
    from pathlib import Path

    from lagsolve.problem.load import load_problem

    problem = load_problem(Path(__file__).resolve().parents[2] / "problems" / "rotating_tube.yaml")
    system = bind(matrix_form(problem), {"mu": 0.3})
    rng = np.random.default_rng(3)
    g, omega, mu, m = 9.81, 2.0, 0.3, 1.0
    for _ in range(20):
        r, theta, rd = rng.uniform(0.2, 3), rng.uniform(0.1, 3.0), rng.uniform(-2, 2)
        qdd, lam, normal, _ = system.solve_all(0.0, np.array([r, theta, 0.4]), np.array([rd, 0.0, omega]))
        n_closed = m * abs(np.sin(theta)) * np.sqrt(4 * omega**2 * rd**2 + (r * omega**2 * np.cos(theta) + g) ** 2)
        assert normal[0] == pytest.approx(n_closed, rel=1e-12)
        assert qdd[0] == pytest.approx(r * omega**2 * np.sin(theta) ** 2 - g * np.cos(theta)
                                       - mu * np.sign(rd) * n_closed / m, rel=1e-10)
        assert lam[1] == pytest.approx(2 * m * r * rd * omega * np.sin(theta) ** 2, rel=1e-10)


LADDER = """
name: Two-mass ladder on a rough floor against a smooth wall
parameters: {m1: foot mass, m2: top mass, g: gravity, L: length, mu: floor friction}
coordinates: [x1, y1, x2, y2]
particles:
  foot: {mass: m1, position: [x1, y1]}
  top: {mass: m2, position: [x2, y2]}
gravity: [0, -g]
constraints:
  floor: {holonomic: y1, on: foot}
  wall: {holonomic: x2, on: top}
  rod: {holonomic: (x1 - x2)**2 + (y1 - y2)**2 - L**2, on: [foot, top]}
friction:
  rough: {coefficient: mu, on: foot, normal: [floor], sliding: [x1]}
simulation:
  values: {m1: 1.0, m2: 2.0, g: 9.81, L: 1.0, mu: 0.4}
"""


def test_coupled_friction_is_solved_consistently() -> None:
    """On a ladder the floor friction changes the floor's normal force; at random states the computed
    q̈, λ and N satisfy every equation, and N is the floor force the multipliers give."""
    import sympy

    form = matrix_form(load_text(LADDER))
    system = bind(form)
    frictionless = bind(form, {"mu": 0.0})
    lagrange = form.lagrange
    params = dict(zip(system.parameter_names, system.parameters, strict=True))
    rng = np.random.default_rng(5)
    for _ in range(20):
        angle, rate = rng.uniform(0.2, 1.3), rng.uniform(-3, 3)
        q = np.array([np.cos(angle), 0.0, 0.0, np.sin(angle)])
        qd = np.array([-np.sin(angle) * rate, 0.0, 0.0, np.cos(angle) * rate])
        qdd, lam, normal, _ = system.solve_all(0.0, q, qd)
        values = {s: v for s, v in zip(form.model.coordinates, q, strict=True)}
        values |= {s: v for s, v in zip(form.model.velocities, qd, strict=True)}
        values |= {p.symbol: params[p.name] for p in form.problem.parameters}
        values[form.frictions[0].normal] = normal[0]
        M = np.array(lagrange.mass_matrix.xreplace(values), dtype=float)
        F = np.array(lagrange.forcing.xreplace(values), dtype=float).ravel()
        A = np.array(lagrange.constraint_jacobian.xreplace(values), dtype=float)
        beta = np.array(lagrange.constraint_rhs.xreplace(values), dtype=float).ravel()
        assert np.allclose(M @ qdd, F + A.T @ lam, atol=1e-10)
        assert np.allclose(A @ qdd, beta, atol=1e-10)
        assert normal[0] == pytest.approx(abs(lam[0]), rel=1e-12)  # the floor pushes along (0, 1)
        if abs(rate) > 0.1:
            _, lam0, _, _ = frictionless.solve_all(0.0, q, qd)
            assert abs(lam[0] - lam0[0]) > 1e-6  # the coupling is real
    assert sympy.Symbol("N_rough", nonnegative=True) in lagrange.forcing.free_symbols


def test_set_contradicting_a_positive_parameter_is_refused() -> None:
    """--set g=-9.81 for a parameter assumed positive is refused with the fix, not simulated silently."""
    with pytest.raises(SpecError) as caught:
        bind(matrix_form(load_text(BEAD, "bead.yaml")), {"g": -9.81})
    assert [str(i) for i in caught.value.issues] == [
        "bead.yaml: --set: g=-9.81 contradicts the assumption that parameter 'g' is positive (parameters are, "
        "unless declared with positive: false), which the derivation relies on; give a value >= 0, or "
        "declare g with positive: false in bead.yaml"]
