"""Reading units (problem/units.py): pint's grammar behind a whitelist; a bad unit is exit 2 with file:line:field."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from lagsolve.cli import main
from lagsolve.errors import ExpressionError
from lagsolve.problem.load import load_text
from lagsolve.problem.units import canonical, unit_of

GOOD = """\
name: spring
time: {name: t, unit: s}
parameters:
  k: {description: stiffness, unit: N/m}
  m: {unit: kg}
functions:
  f: {description: a shape, unit: m}
coordinates:
  x: {description: extension, unit: m}
particles:
  a: {mass: m, position: [x, f(x)]}
potential: k*x**2/2
"""


@pytest.mark.parametrize(("text", "dimensionality"), [
    ("m/s^2", {"[length]": 1, "[time]": -2}),
    ("m/s**2", {"[length]": 1, "[time]": -2}),
    ("N*m", {"[mass]": 1, "[length]": 2, "[time]": -2}),
    ("kg*m^2", {"[mass]": 1, "[length]": 2}),
    ("kg·m²", {"[mass]": 1, "[length]": 2}),
    ("kg/(m*s^2)", {"[mass]": 1, "[length]": -1, "[time]": -2}),
    ("(m/s)^2", {"[length]": 2, "[time]": -2}),
    ("m^(1/2)", {"[length]": 0.5}),
    ("kg m**2 s**-2", {"[mass]": 1, "[length]": 2, "[time]": -2}),
    ("rad", {}),
    ("rad/s", {"[time]": -1}),
    ("1", {}),
    ("km", {"[length]": 1}),
    ("ms", {"[time]": 1}),
    ("N*s/m", {"[mass]": 1, "[time]": -1}),
    ("J", {"[mass]": 1, "[length]": 2, "[time]": -2}),
    ("W", {"[mass]": 1, "[length]": 2, "[time]": -3}),
    ("C", {"[current]": 1, "[time]": 1}),
])
def test_units_are_read(text: str, dimensionality: dict[str, int]) -> None:
    """SI and derived units, prefixes and powers are read to their dimension (angles are pure numbers)."""
    assert dict(unit_of(canonical(text)).dimensionality) == dimensionality


@pytest.mark.parametrize(("value", "phrase"), [
    ("kgg", "unknown unit 'kgg'"),
    ("2*m", "a unit has no number in front"),
    ("__import__('os').system('true')", "is not a unit"),
    ("m/(s", "is not a unit"),
    ("degC", "has an offset"),
    ("m^99", "out of range"),
    ("m" * 61, "the limit is 60"),
    ("", "the unit is empty"),
    ("m_s", "is not a unit"),
    ("m; rm -rf", "is not a unit"),
    ("$m$", "is not a unit"),
    (["m"], "a unit is text, found a list"),
    (2, "a unit is text"),
    (True, "a unit is text"),
    ("m^9^9^9", "raises a power to a power"),  # pint's own grammar would compute 9**387420489
    ("m^(9^9^9)", "fractional exponent"),
    ("m**99**99", "raises a power to a power"),
    ("m^9999", "not a small whole number"),
    ("m^1e3", "is not a unit"),
    ("(((((m)))))", "nests parentheses too deeply"),
    ("m/", "ends too early"),
    ("(m", "ends too early"),
])
def test_bad_units_are_refused(value: object, phrase: str) -> None:
    """Anything that is not a plain unit is refused with a fix, at once (pint never sees a huge exponent)."""
    import time

    start = time.process_time()
    with pytest.raises(ExpressionError) as caught:
        canonical(value)
    assert time.process_time() - start < 2.0  # a guard against hangs, not a benchmark
    assert phrase in str(caught.value)
    assert caught.value.hint  # always a fix


def test_units_are_kept_on_the_problem() -> None:
    """Parameters, functions, coordinates and the time carry the unit as written."""
    problem = load_text(GOOD)
    assert problem.time_unit == "s"
    assert problem.units == {"k": "N/m", "m": "kg", "f": "m", "x": "m"}
    assert problem.has_units


def test_no_units_no_change() -> None:
    """A file without units has no unit anywhere (and behaves as before: see the golden files)."""
    problem = load_text(GOOD.replace("time: {name: t, unit: s}\n", "").replace(", unit: N/m", "")
                        .replace("{unit: kg}", "mass").replace(", unit: m}", "}"))
    assert problem.time_unit is None
    assert set(problem.units.values()) == {None}
    assert not problem.has_units


@pytest.mark.parametrize(("old", "new", "line", "where", "phrase"), [
    ("unit: N/m", "unit: N/mx", 4, "parameters.k.unit", "unknown unit"),
    ("unit: kg}", "unit: kg, units: kg}", 5, "parameters.m.units", "unknown key 'units'"),
    ("{description: a shape, unit: m}", "{description: a shape, unit: 3*m}", 7, "functions.f.unit",
     "a unit has no number in front"),
    ("{description: extension, unit: m}", "{description: extension, unit: [m]}", 9, "coordinates.x.unit",
     "a unit is text, found a list"),
    ("time: {name: t, unit: s}", "time: {name: t, unit: secs and more}", 2, "time.unit", "unknown unit"),
])
def test_bad_unit_in_a_file_exits_2(tmp_path: Path, old: str, new: str, line: int, where: str,
                                    phrase: str) -> None:
    """`lagsolve derive` refuses a bad unit with exit 2, file:line: field: what and a fix, no traceback."""
    assert old in GOOD
    path = tmp_path / "p.yaml"
    path.write_text(GOOD.replace(old, new, 1), encoding="utf-8")
    result = CliRunner().invoke(main, ["derive", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert f"error: {path}:{line}: {where}: " in result.stderr, result.stderr
    assert phrase in result.stderr
    assert "Traceback" not in result.stderr


def test_time_unit_changes_the_units_of_rates() -> None:
    """With time in ms, a velocity is in m/ms and a damping c*x_dot**2/2 must be an energy per ms."""
    from lagsolve.mechanics.units.result_units import result_units
    from lagsolve.mechanics.units.unit_system import check_units

    # one system (kg, m, ms): the stiffness in kg/ms^2, not N/m (mechanics/units/unit_system.py refuses mixed scales)
    text = GOOD.replace("unit: s}", "unit: ms}").replace("unit: N/m", "unit: kg/ms^2") + "dissipation: k*x*x_dot\n"
    problem = load_text(text)
    check_units(problem)  # kg*m^2/ms^3 is a power, and every unit is of one system
    units = result_units(problem, problem.potential)
    assert units is not None
    assert units.time == "ms"
    assert units.accelerations["x"] == "m/ms^2"
