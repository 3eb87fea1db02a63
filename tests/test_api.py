"""`lagsolve.api`: load, derive, simulate and check in process, with SymPy and NumPy results and exceptions."""

from __future__ import annotations

import doctest
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy

import lagsolve
from lagsolve import api
from lagsolve.errors import LagsolveError, SpecError

ROOT = Path(__file__).resolve().parents[1]
BEAD = ROOT / "problems" / "bead.yaml"
FALLING = api.FALLING


def test_docstring_examples_run() -> None:
    """Every example in the API's docstrings gives the output shown."""
    result = doctest.testmod(api, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0
    assert result.failed == 0


def test_import_is_cheap() -> None:
    """Importing lagsolve and its command line loads neither SymPy, NumPy nor matplotlib."""
    code = ("import sys, lagsolve, lagsolve.cli; "
            "print(sorted(m for m in ('sympy', 'numpy', 'matplotlib', 'symengine') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_check_stays_the_function_after_the_module_is_imported() -> None:
    """`lagsolve.check` is the public function even once the submodule `lagsolve.check` is loaded."""
    import lagsolve.check  # noqa: F401 - the import under test
    from lagsolve.check.compare import CheckReport

    assert callable(lagsolve.check)
    assert lagsolve.check is api.check
    assert lagsolve.CheckReport is CheckReport


def test_unknown_attribute_is_an_attribute_error() -> None:
    """A name the package does not export raises AttributeError naming it."""
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        _ = lagsolve.nothing  # type: ignore[attr-defined]


def test_load_problem_reads_a_path_or_text() -> None:
    """A path (str or Path) is read as a file; a string with a line break, or bytes, is YAML text."""
    assert lagsolve.load_problem(BEAD).name == "Bead on a wire"
    assert lagsolve.load_problem(str(BEAD)).name == "Bead on a wire"
    assert lagsolve.load_problem(FALLING).name == "falling mass"
    assert lagsolve.load_problem(FALLING.encode()).source == "<text>"


def test_load_problem_reports_a_missing_file() -> None:
    """A path that does not exist is a SpecError naming the file."""
    with pytest.raises(SpecError, match="nowhere.yaml: file not found"):
        lagsolve.load_problem("nowhere.yaml")


def test_load_problem_rejects_other_types() -> None:
    """Anything but a path or text is a SpecError saying what was found."""
    with pytest.raises(SpecError, match="expected a path or YAML text, found int"):
        lagsolve.load_problem(3)  # type: ignore[arg-type]


def test_derive_gives_sympy_results() -> None:
    """Accelerations and multipliers are SymPy expressions; the mass matrix and forcing are matrices."""
    derivation = lagsolve.derive(BEAD)
    assert isinstance(derivation, lagsolve.Derivation)
    x = sympy.Symbol("x", real=True)
    assert all(isinstance(e, sympy.Expr) for e in derivation.accelerations.values())
    assert isinstance(derivation.multipliers["wire"], sympy.Expr)
    assert isinstance(derivation.constraint_forces["wire"].magnitude, sympy.Expr)
    assert isinstance(derivation.mass_matrix, sympy.MatrixBase) and derivation.mass_matrix.shape == (2, 2)
    assert isinstance(derivation.forcing, sympy.MatrixBase) and derivation.forcing.shape == (2, 1)
    assert x.name in {s.name for s in derivation.accelerations["x"].free_symbols}


def test_derive_accepts_a_loaded_problem() -> None:
    """A Problem from load_problem is derived as it is."""
    derivation = lagsolve.derive(lagsolve.load_problem(FALLING))
    assert str(derivation.accelerations["y"]) == "-g"


def test_derive_rejects_a_non_positive_budget() -> None:
    """A budget of zero seconds is a SpecError naming the budget."""
    with pytest.raises(SpecError, match="budget: expected a finite number > 0 and <= 1e.06, found 0"):
        lagsolve.derive(FALLING, budget=0)


def test_derive_reports_an_invalid_problem_as_spec_error() -> None:
    """Invalid YAML text raises the loader's SpecError, which is a LagsolveError and a ValueError."""
    with pytest.raises(SpecError) as caught:
        lagsolve.derive("name: x\ncoordinates: [q]\nparticles: {p: {mass: m, position: [q]}}\n")
    assert isinstance(caught.value, LagsolveError) and isinstance(caught.value, ValueError)
    assert "<text>:3: particles.p.mass: unknown name 'm'" in str(caught.value)


def test_simulate_free_fall_matches_the_closed_form() -> None:
    """A falling mass follows y = -g t²/2 (cross-check of the numeric route with the exact one)."""
    run = lagsolve.simulate(FALLING, t_end=2.0, values={"m": 1.0, "g": 9.81}, initial={"y": 0.0, "y_dot": 0.0},
                            samples=21)
    assert isinstance(run, lagsolve.Trajectory)
    np.testing.assert_allclose(run.q[:, 0], -9.81 * run.t**2 / 2, atol=1e-9)
    assert run.coordinates == ("y",)


def test_simulate_from_a_path_and_from_a_derivation_agree() -> None:
    """A file and its derivation give the same motion (the file's values and initial state)."""
    from_path = lagsolve.simulate(BEAD, t_end=1.0, samples=11)
    from_derivation = lagsolve.simulate(lagsolve.derive(BEAD), t_end=1.0, samples=11)
    np.testing.assert_allclose(from_path.q, from_derivation.q, rtol=1e-7, atol=1e-9)
    assert from_path.constraints == ("wire",) and from_path.multipliers.shape == (11, 1)


def test_simulate_values_override_the_file() -> None:
    """`values` and `initial` take precedence over the file's simulation block."""
    moon = lagsolve.simulate(BEAD, t_end=0.5, samples=3, values={"g": 1.62}, initial={"x": 0.0, "x_dot": 1.0})
    assert moon.q[0, 0] == 0.0
    assert moon.qd[0, 0] == 1.0


def test_simulate_rejects_unknown_options() -> None:
    """An unknown integrator or coordinates choice is a SpecError listing the choices."""
    with pytest.raises(SpecError) as caught:
        lagsolve.simulate(FALLING, t_end=1.0, method="Euler", coordinates="polar")
    message = str(caught.value)
    assert "method: expected one of DOP853, RK45, RK23, Radau, BDF, LSODA, found 'Euler'" in message
    assert "coordinates: expected one of minimal, full, found 'polar'" in message


def test_simulate_needs_values() -> None:
    """A parameter without a value is a SpecError, not a silent default."""
    with pytest.raises(SpecError, match="g"):
        lagsolve.simulate(FALLING, t_end=1.0, values={"m": 1.0}, initial={"y": 0.0, "y_dot": 0.0})


def test_trajectory_converts_to_numpy() -> None:
    """`columns()` names every column; `to_numpy()` stacks them, shape (samples, columns)."""
    run = lagsolve.simulate(BEAD, t_end=1.0, samples=5)
    columns = run.columns()
    assert list(columns)[:7] == ["t", "x", "y", "x_dot", "y_dot", "lambda_wire", "F_wire"]
    table = run.to_numpy()
    assert table.shape == (5, len(columns))
    np.testing.assert_array_equal(table[:, 1], run.q[:, 0])


def test_trajectory_converts_to_a_dataframe() -> None:
    """`to_dataframe()` has the same columns and rows as `columns()`."""
    pandas = pytest.importorskip("pandas")
    run = lagsolve.simulate(BEAD, t_end=1.0, samples=5)
    frame = run.to_dataframe()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(run.columns())
    assert frame.shape == (5, len(run.columns()))


def test_trajectory_plot_returns_figures() -> None:
    """`plot()` returns matplotlib Figures by name, never bytes; the sketch draws the bead's wire."""
    from matplotlib.figure import Figure

    run = lagsolve.simulate(BEAD, t_end=1.0, samples=11)
    figures = run.plot()
    try:
        assert set(figures) == {"sketch", "path", "coordinates", "phase", "forces", "conservation"}
        assert all(isinstance(f, Figure) for f in figures.values())
        assert "wire" in [line.get_label() for line in figures["sketch"].axes[0].get_lines()]
    finally:
        import matplotlib.pyplot as plt

        for figure in figures.values():
            plt.close(figure)


def test_check_reports_a_wrong_sign() -> None:
    """`check` on text with a wrong answer gives a report that did not pass, with the diagnosis."""
    report = lagsolve.check(FALLING + 'expected: {accelerations: {y: "g"}}')
    assert isinstance(report, lagsolve.CheckReport)
    assert not report.passed
    assert [(v.status, v.reason) for v in report.verdicts] == [("mismatch", "opposite sign")]


def test_check_accepts_a_derivation() -> None:
    """`check` reuses a finished derivation; the shipped bead problem passes."""
    report = lagsolve.check(lagsolve.derive(BEAD))
    assert report.passed
    assert report.count("ok") == 3


@pytest.mark.parametrize(("option", "value", "message"), [
    ("t_end", -1.0, "t_end: expected a finite number > 0, found -1"),
    ("t_end", float("nan"), "t_end: expected a finite number > 0, found nan"),
    ("t_end", float("inf"), "t_end: expected a finite number > 0, found inf"),
    ("rtol", 0.0, "rtol: expected a finite number from 1e-13 to 1, found 0"),
    ("rtol", float("nan"), "rtol: expected a finite number from 1e-13 to 1, found nan"),
    ("atol", float("inf"), "atol: expected a finite number > 0, found inf"),
    ("max_step", float("nan"), "max_step: expected a finite number > 0, found nan"),
    ("budget", float("nan"), "budget: expected a finite number > 0 and <= 1e+06, found nan"),
    ("samples", 1, "samples: expected a whole number from 2 to 1000000, found 1"),
])
def test_simulate_rejects_bad_numbers(option: str, value: float, message: str) -> None:
    """A non-positive or non-finite end time or tolerance, or too few samples, is a SpecError naming it."""
    options = {"t_end": 1.0, "values": {"m": 1.0, "g": 1.0}, "initial": {"y": 0.0, "y_dot": 0.0}, option: value}
    with pytest.raises(SpecError, match=re.escape(message)):
        lagsolve.simulate(FALLING, **options)


def test_simulate_a_derivation_without_analysis() -> None:
    """A derivation made with analysis=False is simulated with the cheap analysis of its matrix form."""
    derivation = lagsolve.derive(BEAD, analysis=False)
    assert derivation.analysis is None
    run = lagsolve.simulate(derivation, t_end=1.0, samples=11)
    reference = lagsolve.simulate(BEAD, t_end=1.0, samples=11)
    np.testing.assert_allclose(run.q, reference.q, rtol=1e-7, atol=1e-9)


def test_every_result_has_a_short_one_line_repr() -> None:
    """repr() of a problem, a derivation, a trajectory (and its motion), a check report, a verdict and a figure is
    one line of at most 160 characters, not a page-long dump."""
    problem = lagsolve.load_problem(ROOT / "problems" / "bead.yaml")
    derivation = lagsolve.derive(problem)
    run = lagsolve.simulate(derivation, t_end=0.5)
    report = lagsolve.check(derivation)
    figure = run.plot()["coordinates"]
    for result in (problem, derivation, run, run.motion, report, report.verdicts[0], figure):
        text = repr(result)
        assert "\n" not in text and len(text) <= 160, text
    assert repr(derivation) == "<Derivation of 'Bead on a wire': 2 coordinates, 1 constraint; complete>"
    assert repr(report) == "<CheckReport of 'Bead on a wire': 3 ok>"


def test_a_check_report_shows_as_a_table_in_a_notebook() -> None:
    """CheckReport's rich display: an HTML table and a Markdown table, one row per expected answer."""
    from markdown_it import MarkdownIt

    report = lagsolve.check(ROOT / "problems" / "bead.yaml")
    html_text = report._repr_html_()
    assert html_text.count("<tr>") == 1 + len(report.verdicts) and "λ_wire" in html_text
    tokens = MarkdownIt("commonmark").enable("table").parse(report._repr_markdown_())
    rows = [t for t in tokens if t.type == "tr_open"]
    assert len(rows) == 1 + len(report.verdicts)


def test_figures_show_themselves_in_a_notebook_without_a_backend_chosen() -> None:
    """lagsolve never calls matplotlib.use: its figures carry their own Agg canvas and a PNG for IPython."""
    import matplotlib

    before = matplotlib.get_backend()
    figure = lagsolve.simulate(ROOT / "problems" / "bead.yaml", t_end=0.5).plot()["coordinates"]
    assert figure._repr_png_().startswith(b"\x89PNG")
    assert matplotlib.get_backend() == before
