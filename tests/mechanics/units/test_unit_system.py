"""One system of units per file (mechanics/units/unit_system.py): mixed scales and degrees are refused, never used."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

import lagsolve
from lagsolve.cli import main
from lagsolve.errors import SpecError
from lagsolve.mechanics.units.unit_system import check_units, scale_issues
from lagsolve.problem.load import load_text

#: a mass falling from rest for 1000 ms: y = -g t^2/2 = -9.81 m/s^2 * (1 s)^2 / 2 = -4.905 m
FALL_MS = """\
name: falling mass
time: {name: t, unit: ms}
parameters:
  m: {unit: kg, value: 1}
  g: {unit: m/s^2, value: 9.81}
coordinates:
  y: {unit: m}
particles:
  a: {mass: m, position: [0, y]}
gravity: [0, -g]
simulation:
  initial: {y: 0, y_dot: 0}
  t_end: 1000
  samples: 11
"""

#: a mass in g on a spring in N/m (k/m is 1000 times too large unless converted)
SPRING_G = """\
name: spring
parameters:
  m: {unit: g, value: 500}
  k: {unit: N/m, value: 2}
coordinates:
  x: {unit: m}
particles:
  a: {mass: m, position: [x, 0]}
potential: k*x**2/2
simulation:
  initial: {x: 0.1, x_dot: 0}
  t_end: 1
"""

#: a coordinate in km next to a length in m
KM = """\
name: spring in km
parameters:
  m: {unit: kg, value: 1}
  k: {unit: N/m, value: 1}
  l0: {unit: m, value: 100}
coordinates:
  x: {unit: km}
particles:
  a: {mass: m, position: [x, 0]}
potential: k*(x - l0)**2/2
simulation:
  initial: {x: 1, x_dot: 0}
  t_end: 1
"""

#: a pendulum whose angle is declared in degrees, released at 90
PENDULUM_DEG = """\
name: pendulum in degrees
parameters:
  m: {unit: kg, value: 1}
  g: {unit: m/s^2, value: 9.81}
  l: {unit: m, value: 1}
coordinates:
  theta: {unit: deg}
particles:
  bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}
gravity: [0, -g]
simulation:
  initial: {theta: 90, theta_dot: 0}
  t_end: 0.25
  samples: 2
"""

#: a block sliding down an incline whose angle alpha is a parameter in degrees (sin(30) is not sin(30 deg))
INCLINE_DEG = """\
name: incline
parameters:
  m: {unit: kg, value: 1}
  g: {unit: m/s^2, value: 9.81}
  alpha: {unit: deg, value: 30}
coordinates:
  s: {unit: m}
particles:
  a: {mass: m, position: ["s*cos(alpha)", "-s*sin(alpha)"]}
gravity: [0, -g]
simulation:
  initial: {s: 0, s_dot: 0}
  t_end: 1
"""


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "p.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def _refused(tmp_path: Path, text: str, *args: str, command: str = "simulate") -> str:
    """Run ``lagsolve <command>`` on ``text``: it must exit 2 without a traceback or any file written; stderr."""
    path = _write(tmp_path, text)
    out = tmp_path / "out"
    extra = {"sweep": ["-o", str(out / "s.csv")], "check": []}.get(command, ["-o", str(out)])
    result = CliRunner().invoke(main, [command, str(path), *args, *extra])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.stderr
    assert not out.exists() or not any(out.rglob("*.*"))
    return result.stderr.replace(str(path), "p.yaml")


def _csv(tmp_path: Path, text: str) -> list[dict[str, str]]:
    path = _write(tmp_path, text)
    result = CliRunner().invoke(main, ["simulate", str(path), "--format", "csv", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    with next((tmp_path / "out").rglob("*.csv")).open(encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


# -- item 1: units of another scale -----------------------------------------------------------------------------


def test_time_in_ms_with_g_in_m_per_s2_is_refused(tmp_path: Path) -> None:
    """Time in ms and g in m/s^2 (which gave y = -4 905 000 m with exit 0) exits 2 naming g, its unit, the unit it
    needs (m/ms^2), the factor, the value to write and the other fix (time in s)."""
    stderr = _refused(tmp_path, FALL_MS)
    assert stderr.startswith("error: p.yaml:5: parameters.g.unit: g is declared in m/s^2, but with the time in ms "
                             "and the coordinate y in m, an acceleration is in m/ms^2 (1 m/s^2 = 1e-06 m/ms^2)")
    assert "parameters.g.value = 9.81 would be used as 9.81 m/ms^2" in stderr
    assert "declare g: {unit: m/ms^2, value: 9.81e-06}, or use SI units: the time in s" in stderr
    assert stderr.count("error:") == 1


def test_fall_in_one_ms_system_gives_the_right_numbers(tmp_path: Path) -> None:
    """Following the fix (g = 9.81e-6 m/ms^2) the mass is at y = -g t^2/2 = -4.905 m after 1000 ms, moving at
    -9.81 m/s = -9.81e-3 m/ms, and the CSV says so in its header."""
    fixed = FALL_MS.replace("{unit: m/s^2, value: 9.81}", "{unit: m/ms^2, value: 9.81e-6}")
    rows = _csv(tmp_path, fixed)
    last = rows[-1]
    assert float(last["t [ms]"]) == pytest.approx(1000.0)
    assert float(last["y [m]"]) == pytest.approx(-9.81 * 1.0 ** 2 / 2, rel=1e-8)
    assert float(last["y_dot [m/ms]"]) == pytest.approx(-9.81e-3, rel=1e-8)
    trajectory = lagsolve.simulate(fixed.encode())
    assert trajectory.q[-1, 0] == pytest.approx(-4.905, rel=1e-8)


def test_mass_in_grams_with_a_spring_in_newtons_per_metre_is_refused(tmp_path: Path) -> None:
    """A mass in g next to a spring in N/m exits 2: k must be in g/s^2 in that system (1 N/m = 1000 g/s^2)."""
    stderr = _refused(tmp_path, SPRING_G)
    assert stderr.startswith("error: p.yaml:4: parameters.k.unit: k is declared in N/m, but with the time in s and "
                             "the parameter m in g, a force per length is in g/s^2 (1 N/m = 1000 g/s^2)")
    assert "declare k: {unit: g/s^2, value: 2000}, or use SI units: the parameter m in kg" in stderr


def test_cgs_spring_gives_the_right_numbers(tmp_path: Path) -> None:
    """In one CGS system (g, cm, s, dyn/cm) the numbers are right: m = 500 g, k = 2000 dyn/cm = 2 N/m, so
    omega = sqrt(k/m) = 2 rad/s and x = 10 cos(2 t) cm from x0 = 10 cm; at t = 1 s, x = 10 cos 2 = -4.1615 cm."""
    cgs = (SPRING_G.replace("{unit: N/m, value: 2}", "{unit: dyn/cm, value: 2000}")
           .replace("x: {unit: m}", "x: {unit: cm}").replace("x: 0.1,", "x: 10,"))
    assert scale_issues(load_text(cgs)) == []
    last = _csv(tmp_path, cgs)[-1]
    assert float(last["t [s]"]) == pytest.approx(1.0)
    assert float(last["x [cm]"]) == pytest.approx(10 * math.cos(2.0), rel=1e-7)
    assert float(last["x_dot [cm/s]"]) == pytest.approx(-20 * math.sin(2.0), rel=1e-7)


def test_coordinate_in_km_with_a_length_in_m_is_refused(tmp_path: Path) -> None:
    """A coordinate in km next to a length (and a stiffness) in m exits 2, one line per unit out of the system."""
    stderr = _refused(tmp_path, KM)
    assert ("error: p.yaml:4: parameters.k.unit: k is declared in N/m, but with the time in s and the parameter "
            "m in kg, a force per length is in kg/s^2") not in stderr  # N/m is kg/s^2: k is fine
    assert ("error: p.yaml:5: parameters.l0.unit: l0 is declared in m, but with the coordinate x in km, a length "
            "is in km (1 m = 0.001 km)") in stderr
    assert "declare l0: {unit: km, value: 0.1}, or use SI units: the coordinate x in m" in stderr
    assert stderr.count("error:") == 1


# -- item 2: degrees -----------------------------------------------------------------------------------------------


def test_degrees_on_a_coordinate_are_refused(tmp_path: Path) -> None:
    """A coordinate in deg (integrated as radians: 89.72 after 0.25 s with exit 0) exits 2 with the values in rad."""
    stderr = _refused(tmp_path, PENDULUM_DEG)
    assert stderr.startswith("error: p.yaml:7: coordinates.theta.unit: theta is declared in deg, but angles are "
                             "computed in radians")
    assert "1 deg = 0.0174533 rad" in stderr
    assert "simulation.initial.theta = 90 would be used as 90 rad" in stderr
    assert "declare theta: {unit: rad} and give simulation.initial.theta: 1.5708, simulation.initial.theta_dot: 0" \
        in stderr


def test_pendulum_in_radians_gives_the_right_angle(tmp_path: Path) -> None:
    """Following the fix (rad, pi/2), the pendulum released at 90 deg is at about 72.5 deg after 0.25 s, as an
    independent integration of theta'' = -(g/l) sin(theta) says; the energy is in J (no deg^2)."""
    from scipy.integrate import solve_ivp

    fixed = PENDULUM_DEG.replace("{unit: deg}", "{unit: rad}").replace("theta: 90,", f"theta: {math.pi / 2!r},")
    last = _csv(tmp_path, fixed)[-1]
    reference = solve_ivp(lambda t, y: [y[1], -9.81 * math.sin(y[0])], (0, 0.25), [math.pi / 2, 0.0],
                          rtol=1e-12, atol=1e-12).y[0, -1]
    assert float(last["theta [rad]"]) == pytest.approx(reference, rel=1e-7)
    # to leading order theta = pi/2 - g t^2/2 (sin(theta) stays near 1): 90 - 17.57 = 72.43 deg; integrated 72.49
    assert math.degrees(float(last["theta [rad]"])) == pytest.approx(90 - math.degrees(9.81 * 0.25 ** 2 / 2),
                                                                     abs=0.1)
    assert "energy [J]" in last


def test_degrees_on_a_parameter_are_refused(tmp_path: Path) -> None:
    """alpha: {unit: deg, value: 30} inside sin(alpha) would be sin(30 rad): exit 2 with the value in rad."""
    stderr = _refused(tmp_path, INCLINE_DEG)
    assert stderr.startswith("error: p.yaml:5: parameters.alpha.unit: alpha is declared in deg, but angles are "
                             "computed in radians (sin(alpha) reads alpha in rad; 1 deg = 0.0174533 rad)")
    assert "declare alpha: {unit: rad, value: 0.523599}" in stderr


def test_incline_in_radians_gives_the_right_distance(tmp_path: Path) -> None:
    """With alpha = pi/6 rad the block slides s = g sin(alpha) t^2/2 = 9.81 * 0.5 / 2 = 2.4525 m in 1 s."""
    fixed = INCLINE_DEG.replace("{unit: deg, value: 30}", f"{{unit: rad, value: {math.pi / 6!r}}}")
    last = _csv(tmp_path, fixed)[-1]
    assert float(last["s [m]"]) == pytest.approx(9.81 * 0.5 / 2, rel=1e-8)


# -- every entry refuses ------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("command", "args"), [
    ("derive", ()), ("check", ()), ("simulate", ()), ("simulate", ("--set", "g=1")),
    ("sweep", ("--grid", "g=1:2:2", "--t-end", "1")),
])
@pytest.mark.parametrize("text", [FALL_MS, PENDULUM_DEG], ids=["ms", "deg"])
def test_every_command_refuses_mixed_units(tmp_path: Path, command: str, args: tuple[str, ...], text: str) -> None:
    """derive, check, simulate (with --set too) and sweep all exit 2 with the same file:line: field: message."""
    if command == "sweep":
        pytest.importorskip("pandas")
    if command == "check":
        text += "expected: {}\n"
    stderr = _refused(tmp_path, text, *args, command=command)
    assert "error: p.yaml:5: parameters.g.unit: " in stderr or "error: p.yaml:7: coordinates.theta.unit: " in stderr


@pytest.mark.parametrize("text", [FALL_MS, SPRING_G, KM, PENDULUM_DEG, INCLINE_DEG])
def test_library_refuses_mixed_units(text: str) -> None:
    """lagsolve.derive, lagsolve.simulate and lagsolve.check raise SpecError (a ValueError) with the message."""
    for call in (lagsolve.derive, lagsolve.simulate, lagsolve.check):
        with pytest.raises(SpecError) as caught:
            call(text.encode())
        assert "lagsolve never converts a unit" in str(caught.value)


def test_sweep_library_refuses_mixed_units() -> None:
    """lagsolve's sweep function refuses too, before any run."""
    pytest.importorskip("pandas")
    from lagsolve.sweep.api import sweep

    with pytest.raises(SpecError, match="parameters.g.unit: g is declared in m/s\\^2"):
        sweep(FALL_MS.encode(), grid={"m": "1:2:2"}, t_end=1.0)


# -- the rule -------------------------------------------------------------------------------------------------------


def _problem(time: str, parameters: dict[str, str], coordinates: dict[str, str]) -> str:
    return ("name: units\n" + f"time: {{name: t, unit: {time}}}\nparameters:{'' if parameters else ' {}'}\n"
            + "".join(f"  {k}: {{unit: {u}}}\n" for k, u in parameters.items()) + "coordinates:\n"
            + "".join(f"  {k}: {{unit: {u}}}\n" for k, u in coordinates.items())
            + "kinetic: 0\n")


@pytest.mark.parametrize(("time", "parameters", "coordinates"), [
    ("s", {"m": "kg", "k": "N/m", "c": "N*s/m", "g": "m/s^2", "En": "J", "P": "W"}, {"x": "m", "th": "rad"}),
    ("s", {"m": "g", "k": "dyn/cm", "En": "erg", "g": "cm/s^2"}, {"x": "cm"}),
    ("min", {"m": "kg", "g": "km/min^2", "k": "kg/min^2"}, {"x": "km"}),
    ("ms", {"m": "kg", "g": "m/ms^2", "w": "rad/ms"}, {"y": "m"}),
    ("s", {"w": "rad/s", "f": "Hz", "c": "N*m/rad", "n": "1"}, {"th": "rad"}),
    ("s", {"En": "erg", "V": "cm^3"}, {"th": "rad"}),  # erg and cm^3 fix the mass (g) and length (cm) together
])
def test_coherent_systems_are_accepted(time: str, parameters: dict[str, str], coordinates: dict[str, str]) -> None:
    """SI, CGS, (kg, km, min), (kg, m, ms) and radians are each one system: nothing to refuse."""
    problem = load_text(_problem(time, parameters, coordinates))
    assert scale_issues(problem) == []
    check_units(problem)


@pytest.mark.parametrize(("time", "parameters", "coordinates", "expected"), [
    ("s", {"m": "g", "k": "N/m", "c": "N*s/m"}, {"x": "m"},
     {"parameters.k.unit": "(1 N/m = 1000 g/s^2)", "parameters.c.unit": "(1 N*s/m = 1000 g/s)"}),
    ("s", {"m": "kg", "F": "kN"}, {"x": "m"}, {"parameters.F.unit": "a force is in kg*m/s^2 (1 kN = 1000 kg*m/s^2)"}),
    ("s", {"V": "L"}, {"x": "m"}, {"parameters.V.unit": "(1 L = 0.001 m^3)"}),
    ("s", {"w": "rpm"}, {"x": "m"}, {"parameters.w.unit": "a rate (per time) is in rad/s (1 rpm = 0.10472 rad/s)"}),
    ("s", {"w": "deg/s"}, {"x": "m"}, {"parameters.w.unit": "is in rad/s (1 deg/s = 0.0174533 rad/s)"}),
    ("s", {"p": "percent"}, {"x": "m"}, {"parameters.p.unit": "a pure number has no unit (1 percent = 0.01)"}),
    ("h", {"v": "km/s"}, {"x": "km"}, {"parameters.v.unit": "a velocity is in km/h (1 km/s = 3600 km/h)"}),
    ("s", {}, {"x": "m", "z": "cm"}, {"coordinates.z.unit": "a length is in m (1 cm = 0.01 m)"}),
])
def test_scaled_units_are_refused(time: str, parameters: dict[str, str], coordinates: dict[str, str],
                                  expected: dict[str, str]) -> None:
    """Each unit whose size disagrees with the system fixed before it gets one issue, saying the unit it needs."""
    issues = scale_issues(load_text(_problem(time, parameters, coordinates)))
    assert {i.where: i.message for i in issues}.keys() == expected.keys()
    for issue in issues:
        assert expected[issue.where] in issue.message
        assert issue.line > 0 and issue.hint.startswith("declare ")


def test_dimension_and_scale_mistakes_are_reported_together() -> None:
    """A wrong dimension and a unit of another scale in one file: both issues in one SpecError, by line."""
    text = FALL_MS.replace("gravity: [0, -g]", "gravity: [0, -g*m]")
    with pytest.raises(SpecError) as caught:
        check_units(load_text(text))
    assert [i.where for i in caught.value.issues] == ["parameters.g.unit", "gravity[1]"]


def test_a_file_without_units_is_not_checked() -> None:
    """Without units there is no system to check: a file without units behaves as before."""
    plain = ("name: plain\nparameters: {g: {value: 9.81}}\ncoordinates: [y]\n"
             "particles: {a: {mass: 1, position: [0, y]}}\nsimulation: {values: {g: 1000}}\n")
    problem = load_text(plain)
    assert not problem.has_units
    assert scale_issues(problem) == []
    check_units(problem)


@pytest.mark.parametrize(("name", "text"), [("fall.yaml", FALL_MS), ("spring.yaml", SPRING_G)])
def test_docs_show_the_messages_lagsolve_prints(tmp_path: Path, name: str, text: str, monkeypatch: pytest.MonkeyPatch
                                                ) -> None:
    """docs/format.md (Units) quotes the refusals of the ms and grams examples exactly as lagsolve prints them."""
    monkeypatch.chdir(tmp_path)
    Path(name).write_text(text, encoding="utf-8")
    result = CliRunner().invoke(main, ["derive", name, "-o", "out"])
    assert result.exit_code == 2
    docs = (Path(__file__).resolve().parents[3] / "docs" / "format.md").read_text(encoding="utf-8")
    assert result.stderr.strip() in docs


def test_units_checked_once_then_derived_without_pint(tmp_path: Path) -> None:
    """The command's process checks the units as it loads the file (units_checked) and marks the problem, so that
    the budgeted child that derives it needs no pint (it imported pint and its registry to check them again: about
    a tenth of a second of lagsolve derive). A derivation with pint made unimportable still completes, and gives
    the same equations as one that checked the units itself; a file with wrong units is refused by units_checked."""
    import subprocess
    import sys

    from lagsolve.mechanics.units.unit_system import units_checked

    path = Path(__file__).resolve().parents[3] / "problems" / "bead.yaml"
    problem = load_text(path.read_text(), "bead.yaml")
    assert not problem.units_checked and units_checked(problem).units_checked
    unitless = load_text("name: free\ncoordinates: {x: {}}\nkinetic: x_dot**2/2\n", "free.yaml")
    assert units_checked(unitless) is unitless
    with pytest.raises(SpecError, match="m/ms\\^2"):
        units_checked(load_text(FALL_MS, "fall.yaml"))
    script = f"""
import pickle, sys
from lagsolve.problem.load import load_problem
from lagsolve.mechanics.units.unit_system import units_checked
blob = pickle.dumps(units_checked(load_problem({str(path)!r})))
for name in [m for m in sys.modules if m == "pint" or m.startswith("pint.") or m == "lagsolve.pint_import"]:
    del sys.modules[name]
sys.modules["pint"] = None  # any import of pint now fails
from lagsolve.mechanics.derivation import derive
checked = derive(pickle.loads(blob))
assert checked.complete, checked
print(sorted(map(str, checked.accelerations.values())))
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    from lagsolve.mechanics.derivation import derive

    assert done.stdout.strip() == str(sorted(map(str, derive(problem).accelerations.values())))
