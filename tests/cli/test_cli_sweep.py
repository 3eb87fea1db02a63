"""`lagsolve sweep` as a user runs it: grid and random inputs, Parquet and CSV tables, pictures, bad input."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from lagsolve.cli import main

pandas = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

ROOT = Path(__file__).resolve().parents[2]
DOUBLE = str(ROOT / "problems" / "double_pendulum.yaml")
SPRING = str(ROOT / "problems" / "spring_on_rough_floor.yaml")
COLUMNS = {"run", "theta1", "theta2", "status", "reason", "outcome", "path", "t_final", "final_theta1",
           "final_theta2", "final_theta1_dot", "final_theta2_dot", "max_residual", "energy_conserved",
           "energy_drift", "drift_energy", "flipped", "flip_time", "stick_count", "slip_count", "stick_times",
           "slip_times", "stuck_at_end", "release_time", "release_constraint", "release_theta1", "release_theta2",
           "steps", "note"}


@pytest.fixture()
def runner() -> CliRunner:
    return CliRunner()


def test_grid_to_parquet_with_a_regime_map(runner: CliRunner, tmp_path: Path) -> None:
    """Two grids give their product, one row per run with the documented columns, and the regime map."""
    out = tmp_path / "s.parquet"
    result = runner.invoke(main, ["sweep", DOUBLE, "--grid", "theta1=0.1:1.5:4", "--grid", "theta2=0.1:3:3",
                                  "--t-end", "1", "-o", str(out), "--plot"])
    assert result.exit_code == 0, result.output
    assert "12 runs" in result.stdout
    frame = pandas.read_parquet(out)
    assert len(frame) == 12 and set(frame.columns) == COLUMNS
    assert list(frame["run"]) == list(range(12))
    assert (frame["status"] == "ok").all()
    assert (tmp_path / "s_regime.png").read_bytes().startswith(b"\x89PNG")


def test_random_to_csv_with_poincare_and_a_bifurcation_scatter(runner: CliRunner, tmp_path: Path) -> None:
    """Random draws for --runs, written as CSV with the crossings as JSON arrays; one input gives the scatter."""
    out = tmp_path / "r.csv"
    result = runner.invoke(main, ["sweep", DOUBLE, "--random", "theta1=0.2:1.2", "--runs", "5", "--seed", "2",
                                  "--t-end", "4", "--poincare", "theta2=0, theta2_dot>0", "--method", "RK45",
                                  "--rtol", "1e-8", "--atol", "1e-10", "-o", str(out), "--plot"])
    assert result.exit_code == 0, result.output
    frame = pandas.read_csv(out)
    assert len(frame) == 5
    assert {"poincare_count", "poincare_t", "poincare_theta1", "poincare_theta2_dot"} <= set(frame.columns)
    for count, times in zip(frame["poincare_count"], frame["poincare_t"], strict=True):
        assert len(json.loads(times)) == count
    assert np.array_equal(frame["theta1"], np.random.default_rng(2).uniform(0.2, 1.2, 5))
    assert (tmp_path / "r_bifurcation.png").exists()


def test_friction_problem_runs_per_run_with_events(runner: CliRunner, tmp_path: Path) -> None:
    """A stick–slip problem runs on simulate's integrator, says so, and gives its stick times."""
    out = tmp_path / "f.csv"
    result = runner.invoke(main, ["sweep", SPRING, "--grid", "x=0.1:1:3", "-o", str(out), "--color", "final_x"])
    assert result.exit_code == 0, result.output
    frame = pandas.read_csv(out)
    assert frame["path"].str.startswith("per run: friction contacts").all()
    assert (frame["outcome"] == "stick").all()
    assert json.loads(frame["stick_times"][0]) == [0.0]
    assert (tmp_path / "f_bifurcation.png").exists()


@pytest.mark.parametrize(("args", "message"), [
    (["--grid", "theta9=0:1:3"], "unknown name 'theta9'"),
    (["--grid", "theta1=0:1"], "NAME=START:STOP:COUNT"),
    (["--grid", "theta1=0:1:2", "--poincare", "theta2>0"], "the first part must be an equation"),
    (["--grid", "theta1=0:1:2", "--poincare", "theta2=exec('1')"], "is not a finite number"),
    (["--random", "theta1=0:1"], "--random needs the number of runs"),
    (["--grid", "theta1=0:1:2", "--color", "nope"], "no column 'nope'"),
])
def test_bad_input_exits_2_with_a_fix(runner: CliRunner, tmp_path: Path, args: list[str], message: str) -> None:
    """Bad options are refused with exit code 2 and a message, never a traceback."""
    result = runner.invoke(main, ["sweep", DOUBLE, "--t-end", "0.1", "-o", str(tmp_path / "s.csv"), *args])
    assert result.exit_code == 2, result.output
    assert message in result.output
    assert "Traceback" not in result.output


def test_output_must_be_parquet_or_csv(runner: CliRunner, tmp_path: Path) -> None:
    """-o names the table; another extension is a usage error."""
    result = runner.invoke(main, ["sweep", DOUBLE, "--grid", "theta1=0:1:2", "-o", str(tmp_path / "s.json")])
    assert result.exit_code == 2
    assert "FILE.parquet or FILE.csv" in result.output


@pytest.mark.parametrize(("color", "message"), [("nope", "no column 'nope'"),
                                               ("status", "column 'status' is not numeric")])
def test_a_bad_color_is_refused_before_any_run(runner: CliRunner, tmp_path: Path, color: str, message: str,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    """--color is checked against the table's columns once the input is read, before the first run: exit 2 with the
    columns it could be, and no run is made (run_chunk is never called)."""
    import importlib

    runs = importlib.import_module("lagsolve.sweep.run")

    def no_run(*args: object, **kwargs: object) -> None:
        raise AssertionError("a run started before --color was checked")

    monkeypatch.setattr(runs, "run_chunk", no_run)
    result = runner.invoke(main, ["sweep", str(ROOT / "problems" / "double_pendulum.yaml"), "--grid",
                                  "theta1=0.1:0.5:2", "--t-end", "0.5", "--color", color, "-o",
                                  str(tmp_path / "s.csv")])
    assert result.exit_code == 2, result.output
    assert f"--color: {message}" in result.stderr and "Traceback" not in result.output
    assert not (tmp_path / "s.csv").exists()


def test_the_columns_known_before_the_runs_are_the_table_s() -> None:
    """The columns given to ``before`` (and checked by --color) are exactly the table's, numeric where it is."""
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    from lagsolve.sweep.api import sweep

    for path, options in ((ROOT / "problems" / "double_pendulum.yaml", {"grid": ["theta1=0.1:0.5:2"], "t_end": 0.5,
                                                                        "poincare": "theta2=0, theta2_dot>0"}),
                          (ROOT / "problems" / "spring_on_rough_floor.yaml", {"random": ["mu_s=0.1:0.5"], "runs": 2})):
        seen: dict[str, bool] = {}
        frame = sweep(path, before=seen.update, **options)  # type: ignore[arg-type]
        assert list(seen) == [str(c) for c in frame.columns]
        assert seen == {str(c): bool(is_numeric_dtype(frame[c]) or is_bool_dtype(frame[c])) for c in frame.columns}
