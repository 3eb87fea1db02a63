"""The accepted range of every numeric option: NaN, infinity and out-of-range numbers are refused with the range,
by the command line (one option type) and by the library alike."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

import lagsolve
from lagsolve.api import FALLING
from lagsolve.cli import Number, main
from lagsolve.errors import SpecError
from lagsolve.ranges import RANGES, Range, check

ROOT = Path(__file__).resolve().parents[1]
BEAD = str(ROOT / "problems" / "bead.yaml")
NAN, INF = math.nan, math.inf


@pytest.mark.parametrize("value", [NAN, INF, -INF, 0.0, -1.0, 2.0])
def test_a_range_refuses_what_is_outside_it(value: float) -> None:
    """NaN, ±infinity and numbers outside the bounds are faults that give the range and the value."""
    fault = Range(0.0, 1.0, low_open=True).fault(value)
    assert fault is not None and fault.startswith("expected a finite number > 0 and <= 1, found ")


def test_a_range_accepts_its_bounds_and_whole_numbers_only_where_asked() -> None:
    """A closed bound is accepted; an integer range refuses a float and a bool; a float range takes an int."""
    assert Range(0.1, 1e6).fault(0.1) is None and Range(0.1, 1e6).fault(1e6) is None
    assert Range(0.1, 1e6).fault(3) is None
    whole = Range(0, 256, integer=True)
    assert whole.fault(2) is None
    assert whole.fault(2.0) == "expected a whole number from 0 to 256, found 2.0"
    assert whole.fault(True) is not None


def test_check_lists_every_bad_value_and_skips_none() -> None:
    """check() raises one SpecError naming each bad option; None (the default applies) is not checked."""
    with pytest.raises(SpecError) as caught:
        check(t_end=NAN, rtol=INF, atol=None, workers=-1)
    assert [issue.where for issue in caught.value.issues] == ["t_end", "rtol", "workers"]


def _numeric(option: click.Option) -> bool:
    return isinstance(option.type, click.types.FloatParamType | click.types.IntParamType | Number)


def test_every_numeric_option_of_every_command_is_a_checked_number() -> None:
    """No command has a numeric option that bypasses the shared type (a plain float would take 'nan')."""
    options = [(name, p) for name, command in main.commands.items() for p in command.params
               if isinstance(p, click.Option) and _numeric(p)]
    assert {p.name for _, p in options} >= {"timeout", "t_end", "rtol", "atol", "max_step", "samples", "workers",
                                            "runs", "seed", "chunk_size"}
    loose = [f"{name} --{p.name}" for name, p in options if not isinstance(p.type, Number)]
    assert loose == []


CASES = [
    ("check", ["--timeout", "nan"], "--timeout", RANGES["timeout"]),
    ("derive", ["--timeout", "inf"], "--timeout", RANGES["timeout"]),
    ("simulate", ["--timeout", "nan"], "--timeout", RANGES["timeout"]),
    ("simulate", ["--timeout", "1e300"], "--timeout", RANGES["timeout"]),
    ("simulate", ["--t-end", "nan"], "--t-end", RANGES["t_end"]),
    ("simulate", ["--t-end", "inf"], "--t-end", RANGES["t_end"]),
    ("simulate", ["--rtol", "nan"], "--rtol", RANGES["rtol"]),
    ("simulate", ["--atol", "inf"], "--atol", RANGES["atol"]),
    ("simulate", ["--max-step", "nan"], "--max-step", RANGES["max_step"]),
    ("simulate", ["--samples", "1e3"], "--samples", RANGES["samples"]),
    ("sweep", ["--rtol", "nan"], "--rtol", RANGES["rtol"]),
    ("sweep", ["--t-end", "-inf"], "--t-end", RANGES["t_end"]),
    ("sweep", ["--workers", "100000"], "--workers", RANGES["workers"]),
    ("sweep", ["--seed", "-1"], "--seed", RANGES["seed"]),
    ("sweep", ["--chunk-size", "0"], "--chunk-size", RANGES["chunk_size"]),
]


@pytest.mark.parametrize(("command", "args", "option", "accepted"), CASES,
                         ids=[f"{c}{' '.join(a)}" for c, a, _, _ in CASES])
def test_bad_numbers_exit_2_with_the_range(command: str, args: list[str], option: str, accepted: Range) -> None:
    """Each command refuses a non-finite or out-of-range number before doing any work: exit 2, the option, the
    accepted range, no traceback."""
    extra = ["--grid", "m=1:2:2", "-o", "unused.csv"] if command == "sweep" else []
    result = CliRunner().invoke(main, [command, BEAD, *extra, *args])
    assert result.exit_code == 2, result.output
    assert f"Invalid value for '{option}'" in result.stderr
    assert f"expected {accepted.describe()}, found " in result.stderr
    assert "Traceback" not in result.output


def test_rtol_nan_does_not_hang_the_command() -> None:
    """`simulate --rtol nan` (which used to hang SciPy's step-size loop) exits 2 at once (a time-out of the
    subprocess would fail the test rather than hang it)."""
    result = subprocess.run([sys.executable, "-m", "lagsolve", "simulate", BEAD, "--rtol", "nan"],
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 2
    assert "expected a finite number from 1e-13 to 1, found nan" in result.stderr


def test_the_help_gives_each_range() -> None:
    """`--help` says what each numeric option accepts."""
    result = CliRunner().invoke(main, ["simulate", "--help"], terminal_width=200)
    assert "[a finite number from 0.1 to 1e+06]" in result.output
    assert "[a finite number from 1e-13 to 1]" in result.output


@pytest.mark.parametrize(("call", "message"), [
    (lambda: lagsolve.derive(FALLING, budget=NAN), "budget: expected a finite number > 0 and <= 1e+06, found nan"),
    (lambda: lagsolve.derive(FALLING, budget=INF), "budget: expected a finite number > 0 and <= 1e+06, found inf"),
    (lambda: lagsolve.check(FALLING, budget=INF), "budget: expected a finite number > 0 and <= 1e+06, found inf"),
    (lambda: lagsolve.simulate(FALLING, t_end=1.0, rtol=NAN), "rtol: expected a finite number from 1e-13 to 1"),
    (lambda: lagsolve.simulate(FALLING, t_end=NAN), "t_end: expected a finite number > 0, found nan"),
], ids=["derive-budget-nan", "derive-budget-inf", "check-budget-inf", "simulate-rtol-nan", "simulate-t-end-nan"])
def test_the_library_refuses_bad_numbers(call: object, message: str) -> None:
    """The Python API raises SpecError (a ValueError) naming the option and its range instead of hanging or
    overflowing."""
    with pytest.raises(SpecError, match=re.escape(message)):
        call()  # type: ignore[operator]


def test_the_pipeline_refuses_a_timeout_that_is_not_finite() -> None:
    """derive_file, check_file and simulate_file refuse an infinite time-out before starting a child."""
    from lagsolve.app.pipeline import SimulationOptions, check_file, derive_file, simulate_file

    for call in (lambda: derive_file(BEAD, timeout=INF), lambda: check_file(BEAD, timeout=NAN),
                 lambda: simulate_file(BEAD, SimulationOptions(values={}, initial={}), timeout=INF)):
        with pytest.raises(SpecError, match="timeout: expected a finite number from 0.1 to 1e.06"):
            call()


def test_sweep_refuses_bad_numbers() -> None:
    """lagsolve.sweep refuses an infinite end time and a NaN tolerance, naming both ranges."""
    pytest.importorskip("pandas")
    from lagsolve.sweep.api import sweep

    with pytest.raises(SpecError, match=r"t_end: expected a finite number > 0, found inf"):
        sweep(BEAD, grid={"m": "1:2:2"}, t_end=INF)
    with pytest.raises(SpecError, match=r"rtol: expected a finite number from 1e-13 to 1, found nan"):
        sweep(BEAD, grid={"m": "1:2:2"}, t_end=1.0, rtol=NAN)
