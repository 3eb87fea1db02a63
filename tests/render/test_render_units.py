"""Units in the outputs (render/units.py, the CSV header, figure axes): present with units, absent without."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from lagsolve.cli import main
from lagsolve.mechanics.derivation import derive
from lagsolve.mechanics.units.result_units import column_units
from lagsolve.numeric.integrate import Trajectory
from lagsolve.problem.load import load_problem
from lagsolve.render import plots
from lagsolve.render.report import render, result_dict
from lagsolve.render.trajectory import to_csv
from lagsolve.render.units import unit_tex

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"


@pytest.fixture(scope="module")
def pendulum() -> object:
    return derive(load_problem(PROBLEMS / "pendulum_cartesian.yaml"), budget=60)


def test_json_gives_the_unit_of_each_result(pendulum: object) -> None:
    """The JSON result's units: accelerations, each multiplier with its constraint's unit, forces in N."""
    units = result_dict(pendulum)["units"]  # type: ignore[arg-type]
    assert units["time"] == "s" and units["energy"] == "J"
    assert units["accelerations"] == {"x": "m/s^2", "y": "m/s^2"}
    assert units["multipliers"] == {"rod": {"unit": "N/m", "constraint": "m^2"}}
    assert units["constraint_forces"] == {"rod": "N"}
    assert "missing" not in units


def test_reports_have_a_units_section(pendulum: object) -> None:
    """Markdown and LaTeX list the declared units and each result's unit."""
    md = render(pendulum, "md")  # type: ignore[arg-type]
    assert "## Units" in md
    assert r"| $`\lambda_{\mathrm{rod}}`$ | $`\mathrm{N/m}`$ | its constraint is written in m^2 |" in md
    tex = render(pendulum, "tex")  # type: ignore[arg-type]
    assert r"$\ddot{x}$ & $\mathrm{m/s^{2}}$" in tex
    html = render(pendulum, "html")  # type: ignore[arg-type]
    assert '<h2 id="units">Units</h2>' in html and "<td>N/m</td>" in html


def test_a_problem_without_units_has_none_in_its_outputs() -> None:
    """No units, no change: no 'units' key, no Units section (the golden files of such problems are unchanged)."""
    for name in ("two_masses_spring", "wedge", "cone"):
        assert "units" not in json.loads((ROOT / "tests" / "golden" / f"{name}.json").read_text())
        assert "## Units" not in (ROOT / "tests" / "golden" / f"{name}.md").read_text()


def test_unit_tex() -> None:
    """Units in LaTeX math: upright, powers braced, products thin-spaced, unknown as ?."""
    assert unit_tex("kg*m^2/s^2") == r"\mathrm{kg\,m^{2}/s^{2}}"
    assert unit_tex("µm") == r"\mathrm{\mu m}"
    assert unit_tex(None) == r"\text{?}"


def _trajectory(coordinates: tuple[str, ...], constraints: tuple[str, ...]) -> Trajectory:
    t = np.linspace(0.0, 1.0, 5)
    n, m = len(coordinates), len(constraints)
    q = np.column_stack([np.sin(t + k) for k in range(n)])
    return Trajectory(t=t, coordinates=coordinates, constraints=constraints, q=q, qd=np.cos(q),
                      multipliers=np.ones((5, m)), magnitudes=np.ones((5, m)), contacts=(),
                      normal_forces=np.zeros((5, 0)), stuck=np.zeros((5, 0), dtype=bool), energy=np.ones(5),
                      conserved={}, residual=np.zeros(5), positions=q[:, :2], particles=(("bob", 2),),
                      events=(), stats={"energy_conserved": True})


def test_csv_header_carries_units() -> None:
    """The CSV header names each column with its unit, `x [m]`; without units it is as before."""
    problem = load_problem(PROBLEMS / "pendulum_cartesian.yaml")
    units = column_units(problem, derive_kinetic(problem))
    trajectory = _trajectory(("x", "y"), ("rod",))
    header = to_csv(trajectory, units).splitlines()[0]
    assert header == ("t [s],x [m],y [m],x_dot [m/s],y_dot [m/s],lambda_rod [N/m],F_rod [N],energy [J],"
                      "residual")
    assert to_csv(trajectory).splitlines()[0] == "t,x,y,x_dot,y_dot,lambda_rod,F_rod,energy,residual"


def derive_kinetic(problem: object) -> object:
    from lagsolve.mechanics.equations.model import build_model

    return build_model(problem).kinetic  # type: ignore[arg-type]


def test_csv_of_a_simulation_with_units(tmp_path: Path) -> None:
    """`lagsolve simulate --format csv` writes the units in the header for a problem that declares them."""
    out = tmp_path / "s.csv"
    result = CliRunner().invoke(main, ["simulate", str(PROBLEMS / "spring_damper.yaml"), "--format", "csv",
                                       "--t-end", "0.1", "--samples", "3", "-o", str(out)])
    assert result.exit_code == 0, result.output
    header = out.read_text().splitlines()[0].split(",")
    assert header[:5] == ["t [s]", "x [m]", "y [m]", "x_dot [m/s]", "y_dot [m/s]"]
    assert "lambda_floor [N]" in header and "F_floor [N]" in header and "energy [J]" in header


def test_figure_axes_carry_units() -> None:
    """Axis labels read `$x$ [m]`, `$t$ [s]`, the rates `[m/s]`, legends `[N/m]`; without units, no brackets."""
    problem = load_problem(PROBLEMS / "pendulum_cartesian.yaml")
    units = column_units(problem, derive_kinetic(problem))
    trajectory = _trajectory(("x", "y"), ("rod",))
    labels = {"x": "x", "y": "y"}
    figures = plots.figures(trajectory, "pendulum", labels, units=units)
    coordinates = figures["coordinates"].axes
    assert coordinates[0].get_ylabel() == "$x$ [m]"
    assert coordinates[-1].get_xlabel() == "$t$ [s]"
    assert figures["phase"].axes[0].get_ylabel() == r"$\dot{x}$ [m/s]"
    assert figures["path"].axes[0].get_xlabel() == "x [m]"
    legend = [t.get_text() for t in figures["forces"].axes[0].get_legend().get_texts()]
    assert legend == [r"$\lambda_{rod}$ [N/m]"]
    bare = plots.figures(trajectory, "pendulum", labels)
    assert bare["coordinates"].axes[0].get_ylabel() == "$x$"
    assert bare["path"].axes[0].get_xlabel() == "x"


def test_effective_potential_axes_carry_units() -> None:
    """The V_eff figure labels its axes `$r$ [m]` and `V_eff [J]` when the file declares units."""
    from lagsolve.render.potential_plot import potential_figure

    figure = potential_figure([1.0, 2.0, 3.0], [1.0, 0.0, 1.0], coordinate="r", units=("m", "J"))
    assert figure.axes[0].get_xlabel() == "$r$ [m]"
    assert figure.axes[0].get_ylabel() == r"$V_{\mathrm{eff}}$ [J]"
    bare = potential_figure([1.0, 2.0, 3.0], [1.0, 0.0, 1.0], coordinate="r")
    assert bare.axes[0].get_xlabel() == "$r$"
