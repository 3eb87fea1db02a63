"""The staged derivation: the matrix form always comes out, checked against SymPy's LagrangesMethod;
a stage that cannot finish is named while the rest is still given; numeric equilibria and modes."""

from __future__ import annotations

import json
import random

import numpy as np
import pytest
import sympy
from click.testing import CliRunner

from lagsolve.cli import main
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_text
from lagsolve.render.report import result_json


def chain(n: int) -> str:
    """A planar n-link pendulum of equal masses m and rods l, as a problem file."""
    lines = [f"name: Planar {n}-link pendulum", "parameters: {m: mass, g: gravity, l: length}", "coordinates:"]
    lines += [f"  theta{i}: angle {i}" for i in range(1, n + 1)]
    lines.append("particles:")
    for i in range(1, n + 1):
        x = " + ".join(f"l*sin(theta{k})" for k in range(1, i + 1))
        y = " - ".join(f"l*cos(theta{k})" for k in range(1, i + 1))
        lines.append(f"  p{i}: {{mass: m, position: [{x}, -{y}]}}")
    lines.append("gravity: [0, -g]")
    lines.append("simulation:\n  values: {m: 1.0, g: 9.81, l: 1.0}\n  initial: {"
                 + ", ".join(f"theta{i}: 0.{i}" for i in range(1, n + 1)) + "}\n  t_end: 1.0")
    return "\n".join(lines) + "\n"


SPRING = """
name: Two pendulums joined by a spring
parameters: {m: mass, g: gravity, l: length, k: spring constant}
coordinates: [theta1, theta2]
kinetic: m*l**2*(theta1_dot**2 + theta2_dot**2)/2
potential: -m*g*l*(cos(theta1) + cos(theta2)) + k*l**2*(sin(theta2) - sin(theta1))**2/2
simulation:
  values: {m: 1.0, g: 9.81, l: 1.0, k: 2.0}
  initial: {theta1: 0.1, theta2: 0.0}
  t_end: 1.0
"""


def _lagranges_method(n: int) -> tuple[sympy.Matrix, sympy.Matrix, list, list]:
    """M and F of the n-link pendulum from SymPy's LagrangesMethod (an independent route)."""
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

    q = dynamicsymbols(f"q1:{n + 1}")
    t = dynamicsymbols._t
    m, g, length = sympy.symbols("m g l", positive=True)
    kinetic = potential = 0
    x = y = 0
    for i in range(n):
        x += length * sympy.sin(q[i])
        y -= length * sympy.cos(q[i])
        kinetic += m * (sympy.diff(x, t) ** 2 + sympy.diff(y, t) ** 2) / 2
        potential += m * g * y
    method = LagrangesMethod(kinetic - potential, q)
    method.form_lagranges_equations()
    return method.mass_matrix, method.forcing, q, [sympy.diff(c, t) for c in q]


@pytest.mark.slow
def test_five_link_pendulum_gives_the_matrix_form_of_lagranges_method() -> None:
    """The 5-link pendulum's explicit solve is too large (its numerators would have 545 terms: it is declined at
    once), so the result is M q̈ = F, equal to what SymPy's LagrangesMethod derives at random states; the note names
    the stage."""
    derivation = derive(load_text(chain(5), "chain5.yaml"))
    assert derivation.accelerations is None
    assert [n.stage for n in derivation.notes if n.kind == "size"][:1] == ["explicit solve"]
    M_lm, F_lm, q, u = _lagranges_method(5)
    model = derivation.model
    rng = random.Random(1)
    for _ in range(5):
        state = [rng.uniform(-3, 3) for _ in range(10)]
        values = {"m": rng.uniform(0.5, 2), "g": rng.uniform(5, 10), "l": rng.uniform(0.5, 2)}
        ours_at = {**dict(zip(model.coordinates, state[:5], strict=True)),
                   **dict(zip(model.velocities, state[5:], strict=True))}
        ours_at |= {s: values[s.name] for s in derivation.form.lagrange.mass_matrix.free_symbols
                    | derivation.form.lagrange.forcing.free_symbols if s.name in values}
        theirs_at = {**dict(zip(u, state[5:], strict=True)), **dict(zip(q, state[:5], strict=True))}
        # velocities first: xreplace of q(t) must not touch Derivative(q(t), t) before it is replaced
        theirs_at |= {sympy.Symbol(k, positive=True): v for k, v in values.items()}
        for ours, theirs in ((derivation.mass_matrix, M_lm), (derivation.forcing, F_lm)):
            a = np.array(sympy.Matrix(ours).xreplace(ours_at).evalf().tolist(), dtype=float)
            b = np.array(sympy.Matrix(theirs).subs(theirs_at).evalf().tolist(), dtype=float)
            assert np.allclose(a, b, rtol=1e-9, atol=1e-9)


def test_json_of_a_partial_result_keeps_its_keys_with_null_and_notes() -> None:
    """A stage without a result keeps its JSON key as null, M and F are given, and a note names the stage."""
    data = json.loads(result_json(derive(load_text(chain(5), "chain5.yaml"))))
    assert data["accelerations"] is None and data["multipliers"] is None
    assert len(data["mass_matrix"]) == 5 and len(data["forcing"]) == 5
    assert any(n["stage"] == "explicit solve" and n["kind"] == "size" for n in data["notes"])


@pytest.mark.budget
def test_a_small_budget_still_gives_the_accelerations() -> None:
    """Coupled pendulums under a budget of 6 s: whether or not the equilibria finish within their small share,
    the JSON has the accelerations (Newton: m l θ̈1 = -m g sin θ1 + k l cos θ1 (sin θ2 - sin θ1)), and either
    the equilibria or a note naming their stage."""
    derivation = derive(load_text(SPRING, "spring.yaml"), budget=6.0)
    data = json.loads(result_json(derivation))
    assert set(data["accelerations"]) == {"theta1", "theta2"}
    s = {x.name: x for x in derivation.model.coordinates} | {p.name: p.symbol for p in derivation.problem.parameters}
    t1, t2, m, g, rod, k = (s[n] for n in ("theta1", "theta2", "m", "g", "l", "k"))
    newton = -g / rod * sympy.sin(t1) + k / m * sympy.cos(t1) * (sympy.sin(t2) - sympy.sin(t1))
    assert sympy.simplify(derivation.accelerations["theta1"] - newton) == 0
    assert data["analysis"]["linearization"].get("equilibria") or any(
        n["stage"] == "equilibria and normal modes" for n in data["notes"])


def test_coupled_pendulums_modes_without_a_general_solve() -> None:
    """The symbolic solve of the coupled equations does not finish, yet with the default budget the equilibria
    come in closed form from the obvious values of θ1, each checked, and the modes hanging down are the
    textbook ω² = g/l and g/l + 2k/m (in phase and out of phase); no stage is left out, and the numeric search
    at the simulation values finds no other equilibrium."""
    derivation = derive(load_text(SPRING, "spring.yaml"))
    assert derivation.notes == ()
    linear = derivation.analysis.linearization
    down = linear.modes[0]
    assert all(v == 0 for _, v in down.point)
    s = {p.name: p.symbol for p in derivation.problem.parameters}
    g, rod, k, m = s["g"], s["l"], s["k"], s["m"]
    assert [sympy.simplify(w - e) for w, e in zip(down.squared_frequencies, (g / rod, g / rod + 2 * k / m),
                                                   strict=True)] == [0, 0]
    assert down.stable is True and down.note == ""
    points = {tuple(v for _, v in mode.point) for mode in linear.modes}
    assert points == {(0, 0), (0, sympy.pi), (sympy.pi, 0), (sympy.pi, sympy.pi)}
    assert "did not finish within 0.5 s" in linear.search and "finds no other" in linear.search


def test_triple_pendulum_frequencies_are_numeric_not_radicals() -> None:
    """The triple pendulum's characteristic cubic does not split: its ω² are given numerically at the
    simulation values (equal to the eigenvalues of M0⁻¹K built by hand), never as complex radicals."""
    derivation = derive(load_text(chain(3), "chain3.yaml"))
    down = derivation.analysis.linearization.modes[0]
    assert all(v == 0 for _, v in down.point)
    mass = np.array([[3, 2, 1], [2, 2, 1], [1, 1, 1]], dtype=float)
    stiffness = 9.81 * np.diag([3.0, 2.0, 1.0])
    expected = np.sort(np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real)
    assert [float(w) for w in down.squared_frequencies] == pytest.approx(list(expected), rel=1e-6)
    assert not any(w.has(sympy.I) for w in down.squared_frequencies)


def test_cli_partial_result_exits_zero_with_a_warning(tmp_path) -> None:  # noqa: ANN001
    """A derivation with a stage left out exits 0, names the stage on stderr, and writes every report."""
    path = tmp_path / "chain5.yaml"
    path.write_text(chain(5), encoding="utf-8")
    result = CliRunner().invoke(main, ["derive", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "warning:" in result.stderr and "Explicit solve: too large" in result.stderr
    report = (tmp_path / "out" / "chain5" / "chain5.md").read_text(encoding="utf-8")
    assert "The explicit solution is not written out" in report and "Not completed in this derivation" in report


def test_simulate_does_not_wait_for_the_analysis(tmp_path) -> None:  # noqa: ANN001
    """Simulating the 4-link pendulum compiles from the matrix form and monitors the energy, which
    stays conserved (an independent check of the equations: energy conservation)."""
    path = tmp_path / "chain4.yaml"
    path.write_text(chain(4), encoding="utf-8")
    result = CliRunner().invoke(main, ["simulate", str(path), "--t-end", "2"])
    assert result.exit_code == 0, result.output
    drift = float(result.output.split("relative drift ")[1].split()[0])
    assert drift < 1e-7


@pytest.mark.parametrize(("name", "named", "absent"), [
    ("bead", ["explicit solve", "forces of constraint", "display simplification", "constraint classification",
              "minimal coordinates", "conserved quantities", "effective potential", "equilibria and normal modes",
              "hamiltonian"], ["normal forces"]),
    ("double_pendulum", ["explicit solve", "display simplification", "conserved quantities", "hamiltonian"],
     ["forces of constraint", "constraint classification", "minimal coordinates", "normal forces"]),
    ("rough_incline", ["explicit solve", "normal forces", "forces of constraint"], ["effective potential"]),
], ids=["constrained", "unconstrained", "friction"])
def test_the_core_alone_names_each_stage_that_did_not_complete(name: str, named: list[str],
                                                                absent: list[str]) -> None:
    """A derivation stopped after its core has one note per stage that would have run (in the order they run),
    each with the reason; no anonymous "later stages", and none for a stage with nothing to do."""
    from pathlib import Path

    from lagsolve.mechanics.derivation import core
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.problem.load import load_problem

    form = matrix_form(load_problem(Path(__file__).resolve().parents[2] / "problems" / f"{name}.yaml"), display=False)
    stopped = core(form, "ran out of time")
    stages = [n.stage for n in stopped.notes]
    assert [s for s in stages if s in named] == named and not set(absent) & set(stages)
    assert "later stages" not in stages
    assert {(n.kind, n.reason) for n in stopped.notes} == {("budget", "ran out of time")}
    assert core(form).notes == ()
