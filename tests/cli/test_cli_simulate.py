"""`lagsolve simulate` as a user runs it: every option, and bad values with exit code 2."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from lagsolve.cli import main

ROOT = Path(__file__).resolve().parents[2]
BEAD = str(ROOT / "problems" / "bead.yaml")
SPHERE = str(ROOT / "problems" / "sliding_off_sphere.yaml")


@pytest.fixture()
def runner() -> CliRunner:
    return CliRunner()


def test_summary_by_default(runner: CliRunner) -> None:
    """Without options the run uses the file's simulation block and prints a summary."""
    result = runner.invoke(main, ["simulate", BEAD])
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("Bead on a wire: simulated to t = 10 with DOP853")
    assert "energy (Jacobi integral) conserved: relative drift" in result.stdout


def test_coordinates_minimal_or_full(runner: CliRunner) -> None:
    """By default the bead is integrated in x alone (y = f(x) exactly); --coordinates full integrates x and y
    with projection; both end in the same state. A problem without a closed-form reduction says why."""
    minimal = runner.invoke(main, ["simulate", BEAD, "--t-end", "2", "--format", "csv"])
    full = runner.invoke(main, ["simulate", BEAD, "--t-end", "2", "--format", "csv", "--coordinates", "full"])
    assert minimal.exit_code == full.exit_code == 0, minimal.output + full.output
    assert "coordinates: minimal: x, with y from the constraints" in minimal.stderr
    assert "largest constraint residual: 0\n" in minimal.stderr
    assert "coordinates: all, projected onto the constraints after each step" in full.stderr
    a = np.loadtxt(io.StringIO(minimal.stdout), delimiter=",", skiprows=1)
    b = np.loadtxt(io.StringIO(full.stdout), delimiter=",", skiprows=1)
    assert np.array_equal(a[:, 2], a[:, 1] ** 2 / 2)  # y = f(x) = x^2/2 to the last bit
    assert np.max(np.abs(a[:, 1:5] - b[:, 1:5])) < 1e-8
    sphere = runner.invoke(main, ["simulate", SPHERE])
    assert "not in minimal coordinates: constraint 'surface'" in sphere.stdout


def test_plot_writes_figures(runner: CliRunner, tmp_path: Path) -> None:
    """--plot writes the PNG figures under the output folder with stable names."""
    result = runner.invoke(main, ["simulate", BEAD, "--plot", "-o", str(tmp_path), "--t-end", "2"])
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in (tmp_path / "bead").iterdir())
    assert names == ["bead_conservation.png", "bead_coordinates.png", "bead_forces.png", "bead_path.png",
                     "bead_phase.png", "bead_sketch.png"]
    assert all((tmp_path / "bead" / n).read_bytes().startswith(b"\x89PNG") for n in names)


def test_overrides_change_the_run(runner: CliRunner) -> None:
    """--t-end, --set, --initial, --samples change the run (CSV on stdout shows it)."""
    result = runner.invoke(main, ["simulate", BEAD, "--format", "csv", "--t-end", "1", "--set", "g=1.62",
                                  "--initial", "x=0.5", "--samples", "5"])
    assert result.exit_code == 0, result.output
    rows = [line.split(",") for line in result.stdout.splitlines()]
    # bead.yaml declares units, so the header carries them (docs/format.md, Units)
    assert rows[0][:5] == ["t [s]", "x [m]", "y [m]", "x_dot [m/s]", "y_dot [m/s]"] and len(rows) == 6
    assert float(rows[1][1]) == 0.5 and float(rows[1][2]) == pytest.approx(0.125)
    assert float(rows[-1][0]) == 1.0
    # with g = 1.62 the bead released at x = 0.5 is slower than on Earth
    earth = runner.invoke(main, ["simulate", BEAD, "--format", "csv", "--t-end", "1", "--initial", "x=0.5",
                                 "--samples", "5"])
    assert float(rows[-1][1]) > float(earth.stdout.splitlines()[-1].split(",")[1])
    assert "simulated to t = 1" in result.stderr


def test_method_and_tolerances(runner: CliRunner) -> None:
    """--method, --rtol, --atol and --max-step reach the integrator and show in the summary."""
    result = runner.invoke(main, ["simulate", BEAD, "--t-end", "1", "--method", "Radau", "--rtol", "1e-6",
                                  "--atol", "1e-9", "--max-step", "0.01"])
    assert result.exit_code == 0, result.output
    assert "with Radau (rtol 1e-06, atol 1e-09)" in result.stdout
    steps = int(result.stdout.split("steps: ")[1].split(",")[0])
    assert steps >= 100


def test_csv_and_npz_files(runner: CliRunner, tmp_path: Path) -> None:
    """-o FILE.csv writes that file; --format npz writes the archive in the output folder."""
    target = tmp_path / "bead.csv"
    assert runner.invoke(main, ["simulate", BEAD, "--t-end", "1", "--format", "csv", "-o", str(target)]).exit_code == 0
    assert target.read_text().startswith("t [s],x [m],y [m],x_dot [m/s],y_dot [m/s],lambda_wire [N],F_wire [N],"
                                         "energy [J],residual\n")
    npz = runner.invoke(main, ["simulate", BEAD, "--t-end", "1", "--format", "npz", "-o", str(tmp_path)])
    assert npz.exit_code == 0
    archive = np.load(io.BytesIO((tmp_path / "bead" / "bead.npz").read_bytes()))
    assert "lambda_wire" in archive.files


def test_after_release(runner: CliRunner) -> None:
    """The sphere run stops at lost contact, or continues with --after-release continue."""
    stop = runner.invoke(main, ["simulate", SPHERE])
    assert stop.exit_code == 0 and "released at t = 2.37" in stop.stdout and "stopped there" in stop.stdout
    go_on = runner.invoke(main, ["simulate", SPHERE, "--after-release", "continue", "--t-end", "3"])
    assert go_on.exit_code == 0 and "continued without it" in go_on.stdout
    assert "simulated to t = 3" in go_on.stdout


@pytest.mark.slow
def test_animate_and_show(runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """--animate writes a GIF; --show opens each written figure with the system viewer."""
    opened: list[str] = []
    monkeypatch.setattr("click.launch", lambda path: opened.append(path))
    result = runner.invoke(main, ["simulate", BEAD, "--t-end", "1", "--animate", "--show", "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "bead" / "bead_animation.gif").read_bytes().startswith(b"GIF8")
    assert len(opened) == 7 and any(p.endswith("bead_sketch.png") for p in opened)


@pytest.mark.parametrize(("args", "message"), [
    (["--t-end", "-1"], "Invalid value for '--t-end'"),
    (["--set", "h=1"], "unknown parameter 'h'"),
    (["--set", "g=nan"], "expected NAME=NUMBER with a finite number"),
    (["--set", "g"], "expected NAME=NUMBER"),
    (["--initial", "x=abc"], "expected NAME=NUMBER"),
    (["--initial", "zz=1"], "unknown coordinate or velocity 'zz'"),
    (["--initial", "x=0", "--initial", "y=5"], "initial positions violate the constraints"),
    (["--method", "Euler"], "Invalid value for '--method'"),
    (["--samples", "1"], "Invalid value for '--samples'"),
    (["--rtol", "0"], "Invalid value for '--rtol'"),
    (["--coordinates", "polar"], "Invalid value for '--coordinates'"),
], ids=["negative-t-end", "unknown-parameter", "nan", "no-value", "bad-number", "unknown-initial",
        "inconsistent-initial", "bad-method", "few-samples", "zero-rtol", "bad-coordinates"])
def test_bad_values_exit_2(runner: CliRunner, args: list[str], message: str) -> None:
    """Bad option values are reported clearly with exit code 2 and no traceback."""
    result = runner.invoke(main, ["simulate", BEAD, *args])
    assert result.exit_code == 2, result.output
    assert message in result.stderr and "Traceback" not in result.output


def test_missing_values_are_named(runner: CliRunner, tmp_path: Path) -> None:
    """A problem without values for its parameters says which ones are missing."""
    text = (ROOT / "problems" / "bead.yaml").read_text().replace("values: {m: 1.0, g: 9.81}", "values: {m: 1.0}")
    path = tmp_path / "bead.yaml"
    path.write_text(text)
    result = runner.invoke(main, ["simulate", str(path)])
    assert result.exit_code == 2 and "no value for parameter g" in result.stderr


def test_simulation_timeout(runner: CliRunner) -> None:
    """A run past its --timeout CPU budget stops with exit 1 and says how to raise it."""
    result = runner.invoke(main, ["simulate", BEAD, "--t-end", "100000", "--timeout", "1"])
    assert result.exit_code == 1 and "used up its 1 s CPU budget; raise it with --timeout" in result.stderr


@pytest.mark.slow
def test_tables_do_not_depend_on_hash_seed(tmp_path: Path) -> None:
    """The same run under two PYTHONHASHSEED values writes byte-identical CSV tables (minimal and full
    coordinates, friction, a chaotic system)."""
    import os
    import subprocess
    import sys

    names = ("double_pendulum", "hole_table", "ladder_rough_floor", "rotating_tube")
    problems = [str(ROOT / "problems" / f"{name}.yaml") for name in names]
    tables = []
    for seed in ("0", "4242"):
        target = tmp_path / seed
        run = subprocess.run([sys.executable, "-m", "lagsolve", "simulate", *problems, "--format", "csv", "-o",
                              str(target), "--samples", "201"],
                             env={**os.environ, "PYTHONHASHSEED": seed}, capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        tables.append({p.name: p.read_bytes() for p in sorted(target.rglob("*.csv"))})
    assert len(tables[0]) == len(names) and tables[0] == tables[1]


def test_initial_state_off_the_constraints_names_line_and_field(runner: CliRunner, tmp_path: Path) -> None:
    """Initial values that violate a constraint are reported at simulation.initial's line in the file,
    and as coming from --initial too when that option was used."""
    text = Path(SPHERE).read_text().replace("initial: {x: 0.001, y: 0.9999995, x_dot: 0.0}",
                                            "initial: {x: 0.8, y: 0.9, x_dot: 0.0}")
    line = next(i for i, row in enumerate(text.splitlines(), 1) if row.strip().startswith("initial:"))
    (tmp_path / "off.yaml").write_text(text)
    result = runner.invoke(main, ["simulate", str(tmp_path / "off.yaml")])
    assert result.exit_code == 2
    assert (f"off.yaml:{line}: simulation.initial: the initial positions violate the constraints (surface = 0.45); "
            "give fewer coordinates") in result.stderr
    both = runner.invoke(main, ["simulate", str(tmp_path / "off.yaml"), "--initial", "x=0.1"])
    assert both.exit_code == 2
    assert f"off.yaml:{line}: simulation.initial and --initial: the initial positions violate" in both.stderr
