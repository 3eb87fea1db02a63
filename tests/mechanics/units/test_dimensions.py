"""Dimensional checks (mechanics/units/dimensions.py): wrong physics refused before the derivation, units of results."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy
from click.testing import CliRunner

from lagsolve.cli import main
from lagsolve.errors import SpecError
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.mechanics.units.dimensions import algebra, check_dimensions
from lagsolve.mechanics.units.result_units import missing_units, result_units
from lagsolve.problem.load import load_problem, load_text
from lagsolve.problem.units import unit_of

PROBLEMS = Path(__file__).resolve().parents[3] / "problems"

SPRING = """\
name: spring
parameters:
  k: {description: stiffness, unit: N/m}
  m: {unit: kg}
  l0: {unit: m}
  F0: {unit: N}
  omega: {unit: 1/s}
  g: {unit: m/s^2}
coordinates:
  r: {unit: m}
  theta: {unit: rad}
particles:
  a: {mass: m, position: [r*cos(theta), r*sin(theta)]}
gravity: [0, -g]
potential: k*(r - l0)**2/2
"""

#: (id, text replaced, replacement, line, field, phrases in the message)
MISTAKES = [
    ("potential", "potential: k*(r - l0)**2/2", "potential: k*(r - l0)/2", 15, "potential",
     ["has dimension kg*m/s^2 (force), but it must be an energy (kg*m^2/s^2)", "did you forget a power?"]),
    ("constraint", "potential: k*(r - l0)**2/2", "constraints:\n  rod: {holonomic: r**2 - l0}", 16,
     "constraints.rod.holonomic", ["r**2 [m^2]", "-l0 [m (length)]", "have different dimensions",
                                   "every term of a sum must have the same dimension"]),
    ("velocity-constraint", "potential: k*(r - l0)**2/2", "constraints:\n  roll: {nonholonomic: r_dot - l0*theta}",
     16, "constraints.roll.nonholonomic", ["r_dot [m/s (velocity)]", "-l0*theta [m (length)]"]),
    ("force-on-angle", "potential: k*(r - l0)**2/2", "forces:\n  - {coordinate: theta, value: F0}", 16,
     "forces[0].value", ["F0 has dimension kg*m/s^2 (force), but it must be a torque (kg*m^2/s^2)",
                         "theta is an angle", "multiply the force by its lever arm"]),
    ("force-on-length", "potential: k*(r - l0)**2/2", "forces:\n  - {coordinate: r, value: F0*l0}", 16,
     "forces[0].value", ["F0*l0 has dimension kg*m^2/s^2 (energy), but it must be a force (kg*m/s^2)"]),
    ("trig-argument", "potential: k*(r - l0)**2/2", "forces:\n  - {coordinate: r, value: F0*cos(omega)}", 16,
     "forces[0].value", ["the argument of cos, omega, has dimension 1/s (rate), but it must be dimensionless"]),
    ("exp-argument", "potential: k*(r - l0)**2/2", "potential: k*l0**2*exp(r)", 15, "potential",
     ["the argument of exp, r, has dimension m (length), but it must be dimensionless"]),
    ("mass", "mass: m,", "mass: m*l0,", 13, "particles.a.mass",
     ["kg*m, but it must be a mass (kg)", "is there a factor of dimension m too many?"]),
    ("position", "position: [r*cos(theta), r*sin(theta)]", "position: [r*cos(theta), m*sin(theta)]", 13,
     "particles.a.position[1]", ["m*sin(theta) has dimension kg (mass), but it must be a length (m)"]),
    ("gravity", "gravity: [0, -g]", "gravity: [0, -g*m]", 14, "gravity[1]",
     ["but it must be an acceleration (m/s^2)"]),
    ("dissipation", "potential: k*(r - l0)**2/2", "dissipation: k*r_dot**2/2", 15, "dissipation",
     ["but it must be a power (kg*m^2/s^3)"]),
]


def run(tmp_path: Path, text: str, *args: str) -> tuple[int, str, Path]:
    path = tmp_path / "problem.yaml"
    path.write_text(text, encoding="utf-8")
    result = CliRunner().invoke(main, ["derive", str(path), "-o", str(tmp_path / "out"), *args])
    return result.exit_code, result.stderr, path


@pytest.mark.parametrize(("old", "new", "line", "where", "phrases"), [m[1:] for m in MISTAKES],
                         ids=[m[0] for m in MISTAKES])
def test_dimensional_mistake_is_refused(tmp_path: Path, old: str, new: str, line: int, where: str,
                                        phrases: list[str]) -> None:
    """Each kind of dimensional mistake exits 2 with file:line: field: the dimensions found and needed, a hint."""
    assert old in SPRING
    code, stderr, path = run(tmp_path, SPRING.replace(old, new, 1))
    assert code == 2, stderr
    assert f"error: {path}:{line}: {where}: " in stderr, stderr
    for phrase in phrases:
        assert phrase in stderr, stderr
    assert "Traceback" not in stderr
    assert not (tmp_path / "out").exists()


def test_every_mistake_is_listed_at_once() -> None:
    """Several wrong fields give one issue each, in line order."""
    text = SPRING.replace("potential: k*(r - l0)**2/2", "potential: k*r\ndissipation: m")
    with pytest.raises(SpecError) as caught:
        check_dimensions(load_text(text, "p.yaml"))
    assert [i.where for i in caught.value.issues] == ["potential", "dissipation"]


def test_the_right_file_passes_and_angles_are_pure_numbers() -> None:
    """The correct spring passes: sin and cos of an angle in rad, r*theta a length, a torque on theta."""
    text = SPRING.replace("potential: k*(r - l0)**2/2",
                          "potential: k*(r - l0)**2/2 + m*g*l0*cos(theta)\n"
                          "forces:\n  - {coordinate: theta, value: F0*r*sin(omega*t)}\n"
                          "constraints:\n  c: {holonomic: r*theta - l0*sin(theta)}")
    check_dimensions(load_text(text))


def test_fractional_powers_are_exact_enough() -> None:
    """Cube roots and other fractional powers combine to whole dimensions without rounding refusals."""
    text = SPRING.replace("  g: {unit: m/s^2}\n", "  g: {unit: m/s^2}\n  a: {unit: m^3}\n").replace(
        "potential: k*(r - l0)**2/2", "potential: k*r**2*(a/r**3)**(1/3)*(r**3/a)**(1/3)/2 + k*r*a**(1/3)")
    check_dimensions(load_text(text))


def test_without_units_nothing_is_checked() -> None:
    """A file without units is not checked at all (a "wrong" potential is accepted as before)."""
    problem = load_text("name: p\ncoordinates: [x]\nkinetic: x_dot**2/2\npotential: x\n")
    assert not problem.has_units
    check_dimensions(problem)
    assert result_units(problem, problem.kinetic) is None
    assert missing_units(problem) == []


def test_undeclared_symbols_are_not_checked_but_listed() -> None:
    """With some units missing, what involves them is unknown (never refused), and they are listed."""
    text = SPRING.replace("  omega: {unit: 1/s}\n", "  omega: angular frequency\n").replace(
        "potential: k*(r - l0)**2/2", "potential: k*(r - l0)**2/2 + omega")
    problem = load_text(text)
    check_dimensions(problem)
    assert missing_units(problem) == ["omega"]


def test_partial_units_warn_on_the_command_line(tmp_path: Path) -> None:
    """`lagsolve derive` warns on stderr about the names without a unit, and still derives (exit 0)."""
    text = SPRING.replace("  omega: {unit: 1/s}\n", "  omega: angular frequency\n").replace(
        "  F0: {unit: N}\n", "  F0: a force\n")
    code, stderr, path = run(tmp_path, text)
    assert code == 0, stderr
    assert f"warning: {path}: units: no unit declared for F0, omega" in stderr


def test_unit_algebra_of_derivatives_and_functions() -> None:
    """f(x) has f's unit, f'(x) f's over x's, f''(x) over x's squared; a symbolic power needs pure numbers."""
    problem = load_problem(PROBLEMS / "bead.yaml")
    units = algebra(problem)
    x = problem.symbols["x"]
    f = problem.functions[0].function
    assert units.of(sympy.Derivative(f(x), x)).dimensionality == unit_of("1").dimensionality
    assert units.of(sympy.Derivative(f(x), (x, 2))).dimensionality == unit_of("1/m").dimensionality
    assert units.of(f(x) * problem.symbols["m"]).dimensionality == unit_of("kg*m").dimensionality


SHIPPED_WITH_UNITS = sorted(p.name for p in PROBLEMS.glob("*.yaml") if "unit:" in p.read_text(encoding="utf-8"))


def test_several_shipped_problems_declare_units() -> None:
    """The shipped problems declare units where natural (at least the issue's list)."""
    assert {"bead.yaml", "double_pendulum.yaml", "hole_table.yaml", "rolling_incline.yaml",
            "spring_damper.yaml"} <= set(SHIPPED_WITH_UNITS)


@pytest.mark.parametrize("name", SHIPPED_WITH_UNITS)
def test_shipped_problem_with_units_passes_the_checks(name: str) -> None:
    """Every shipped problem with units declares all of them, passes the checks and gives a matrix form."""
    problem = load_problem(PROBLEMS / name)
    assert missing_units(problem) == []
    check_dimensions(problem)
    matrix_form(problem, display=False)


def test_named_dimensions_agree_with_pint() -> None:
    """The dimensions written out for the checks are pint's (energy J, power W, force N, ...)."""
    from lagsolve.mechanics.units import dimensions as d

    for dim, text in ((d.ENERGY, "J"), (d.POWER, "W"), (d.FORCE, "N"), (d.LENGTH, "m"), (d.MASS, "kg"),
                      (d.ACCELERATION, "m/s^2"), (d.INERTIA, "kg*m^2"), (d.RATE, "rad/s")):
        assert d.dimension(unit_of(text)) == dim, text


def test_a_file_without_units_never_loads_pint() -> None:
    """Deriving a problem without units does not import pint (its registry costs about 0.4 s)."""
    import subprocess
    import sys

    code = ("import sys; from lagsolve.problem.load import load_problem; "
            "from lagsolve.mechanics.equations.matrix_form import matrix_form; "
            f"matrix_form(load_problem({str(PROBLEMS / 'wedge.yaml')!r}), display=False); "
            "print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    assert out.stdout.strip() == "False"


def test_partial_units_warn_in_check_and_simulate(tmp_path: Path) -> None:
    """`lagsolve check` and `lagsolve simulate` warn about missing units too (stderr), and still run."""
    path = tmp_path / "p.yaml"
    path.write_text("name: p\nparameters:\n  m: {unit: kg}\n  k: stiffness\ncoordinates:\n  x: {unit: m}\n"
                    "particles:\n  a: {mass: m, position: [x, 0]}\npotential: k*x**2/2\n"
                    "expected:\n  accelerations: {x: '-k*x/m'}\n"
                    "simulation: {values: {m: 1, k: 1}, initial: {x: 1}, t_end: 0.1}\n", encoding="utf-8")
    warning = f"warning: {path}: units: no unit declared for k, so dimensions involving it are not checked"
    checked = CliRunner().invoke(main, ["check", str(path)])
    assert checked.exit_code == 0, checked.output
    assert warning in checked.stderr
    simulated = CliRunner().invoke(main, ["simulate", str(path), "-o", str(tmp_path / "out")])
    assert simulated.exit_code == 0, simulated.output
    assert warning in simulated.stderr


@pytest.mark.parametrize("command", ["check", "simulate"])
def test_check_and_simulate_refuse_wrong_dimensions_too(tmp_path: Path, command: str) -> None:
    """The checks run before any derivation, so `lagsolve check` and `lagsolve simulate` exit 2 the same way."""
    path = tmp_path / "p.yaml"
    path.write_text(SPRING.replace("potential: k*(r - l0)**2/2", "potential: k*(r - l0)/2")
                    + "simulation: {values: {k: 1, m: 1, l0: 1, F0: 1, omega: 1, g: 1}, initial: {r: 1}, t_end: 1}\n",
                    encoding="utf-8")
    result = CliRunner().invoke(main, [command, str(path)])
    assert result.exit_code == 2, result.output
    assert f"error: {path}:15: potential: k*(r - l0)/2 has dimension kg*m/s^2 (force)" in result.stderr
