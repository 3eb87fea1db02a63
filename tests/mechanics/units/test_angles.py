"""Angles typed in degrees where radians are read (lagsolve.mechanics.units.angles): a warning with the value to
write, on the quantities used only as angles; none on the shipped problems, rates or lengths."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from lagsolve.cli import main
from lagsolve.mechanics.units.angles import angle_warnings
from lagsolve.problem.load import load_problem, load_text

ROOT = Path(__file__).resolve().parents[3]

INCLINE = """name: block on an incline
parameters:
  m: {description: mass}
  g: {description: gravity}
  alpha: {description: incline angle}
  Omega: {description: drive rate}
  k: {description: wave number}
coordinates:
  s: {description: along the slope}
  theta: {description: a wheel's angle}
particles:
  block: {mass: m, position: [s*cos(alpha), -s*sin(alpha) + sin(k*s)/k]}
kinetic: m*theta_dot**2/2
potential: -m*g*cos(theta + Omega*t)
simulation:
  values: {m: 1, g: 9.81, alpha: ALPHA, Omega: 20, k: 30}
  initial: {s: 40, s_dot: 0, theta: THETA}
  t_end: 1
"""


def _warnings(alpha: float, theta: float) -> tuple[str, ...]:
    return angle_warnings(load_text(INCLINE.replace("ALPHA", str(alpha)).replace("THETA", str(theta)), "p.yaml"))


def test_a_value_of_more_than_a_turn_on_an_angle_is_a_warning_with_the_radians() -> None:
    """alpha = 30 inside sin and cos, theta = 60 added to Omega*t: both read as radians (4.8 and 9.5 turns);
    the warning names the line, the field and the value in radians. Omega (in sin(Omega*t), a rate), k and s
    (in sin(k*s), lengths) are no angles, however large."""
    found = _warnings(30, 60)
    assert found == (
        "p.yaml:16: simulation.values.alpha: alpha = 30 is an angle in radians, 4.77 turns; if you meant 30°, "
        "write 0.523599",
        "p.yaml:17: simulation.initial.theta: theta = 60 is an angle in radians, 9.55 turns; if you meant 60°, "
        f"write {math.radians(60):.6g}")
    assert _warnings(0.5, -6.2) == ()  # within a turn either way
    assert len(_warnings(0.5, -7)) == 1  # (theta: negative)


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "problems").glob("*.yaml")))
def test_no_shipped_problem_gets_the_warning(name: str) -> None:
    assert angle_warnings(load_problem(ROOT / "problems" / f"{name}.yaml")) == ()


def test_simulate_prints_it_once_and_goes_on(tmp_path: Path) -> None:
    """The run is made (a winding angle such as 7.5 rad can be meant), exit 0, the warning on stderr once."""
    path = tmp_path / "p.yaml"
    path.write_text(INCLINE.replace("ALPHA", "30").replace("THETA", "0.1"), encoding="utf-8")
    result = CliRunner().invoke(main, ["simulate", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert result.stderr.count("alpha = 30 is an angle in radians") == 1
    assert f"warning: {path}:16: simulation.values.alpha" in result.stderr


def test_the_command_lines_values_replace_the_files(tmp_path: Path) -> None:
    """--set and --initial replace the file's values: the file's 30 they override is not warned about (the run does
    not use it), and theirs are checked (simulate --initial theta=60 started 9.5 turns round without a word)."""
    path = tmp_path / "p.yaml"
    path.write_text(INCLINE.replace("ALPHA", "30").replace("THETA", "0.1"), encoding="utf-8")
    found = angle_warnings(load_problem(path), {"alpha": 0.5}, {"theta": 60.0})
    assert found == (f"{path}: --initial theta: theta = 60 is an angle in radians, 9.55 turns; if you meant 60°, "
                     f"write {math.radians(60):.6g}",)
    result = CliRunner().invoke(main, ["simulate", str(path), "--set", "alpha=0.5", "--initial", "theta=60",
                                       "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "alpha = 30" not in result.stderr
    assert f"warning: {path}: --initial theta: theta = 60 is an angle in radians" in result.stderr


def test_a_sweep_over_an_angle_in_degrees_is_warned_of(tmp_path: Path) -> None:
    """--grid alpha=0:45:4 sweeps the incline 7 turns round (it was silent); the file's alpha, replaced by the
    sweep, gets no warning, its theta (not swept) does; a sweep of a rate (Omega) does not."""
    path = tmp_path / "p.yaml"
    path.write_text(INCLINE.replace("ALPHA", "30").replace("THETA", "60"), encoding="utf-8")
    result = CliRunner().invoke(main, ["sweep", str(path), "--grid", "alpha=0:45:4", "--t-end", "0.1",
                                       "-o", str(tmp_path / "s.csv")])
    assert result.exit_code == 0, result.output
    assert f"warning: {path}: the swept alpha reaches 45, an angle in radians, 7.16 turns" in result.stderr
    assert "alpha = 30" not in result.stderr and "theta = 60" in result.stderr
    assert angle_warnings(load_text(INCLINE.replace("ALPHA", "0.5").replace("THETA", "0.1"), "p.yaml"),
                          swept={"Omega": [10.0, 40.0]}) == ()
