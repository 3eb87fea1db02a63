"""lagsolve export --to fmu: an FMI 2.0 Model Exchange FMU that FMPy validates and simulates to the same
states, multipliers and normal forces as lagsolve.simulate (issue 32)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

import lagsolve
from lagsolve.errors import SpecError

fmpy = pytest.importorskip("fmpy")

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
needs_cc = pytest.mark.skipif(shutil.which("cc") is None and shutil.which("gcc") is None, reason="no C compiler")


@needs_cc
@pytest.mark.parametrize("name", ["rotating_tube", "bead"])
def test_fmu_validates_and_matches_simulate(name: str, tmp_path: Path) -> None:
    from fmpy.validation import validate_fmu

    fmu = lagsolve.export(PROBLEMS / f"{name}.yaml", to="fmu", output=tmp_path)
    assert fmu == tmp_path / f"{name}.fmu"
    assert validate_fmu(str(fmu)) == []
    run = lagsolve.simulate(PROBLEMS / f"{name}.yaml", t_end=1.0, samples=11, rtol=1e-12, atol=1e-13,
                            coordinates="full")
    columns = run.columns()
    states = [*run.coordinates, *(f"{c}_dot" for c in run.coordinates)]
    compared = [*states, *(k for k in columns if k.startswith(("lambda_", "N_", "F_", "friction_"))), "energy"]
    result = fmpy.simulate_fmu(str(fmu), stop_time=1.0, output_interval=0.1, relative_tolerance=1e-11,
                               output=compared)
    times = result["time"]
    for i, t in enumerate(run.t):
        row = int(np.argmin(np.abs(times - t)))
        assert times[row] == pytest.approx(t, abs=1e-12)
        for key in compared:
            expected = float(columns[key][i])
            assert float(result[key][row]) == pytest.approx(expected, rel=1e-6, abs=1e-6), (key, t)


@needs_cc
def test_fmu_declares_event_indicators_and_parameters(tmp_path: Path) -> None:
    from fmpy import read_model_description

    fmu = lagsolve.export(PROBLEMS / "rotating_tube.yaml", to="fmu", output=tmp_path)
    description = read_model_description(str(fmu))
    assert description.numberOfEventIndicators == 1 and "sliding_wall" in description.description
    variables = {v.name: v for v in description.modelVariables}
    assert variables["mu"].causality == "parameter" and float(variables["mu"].start) == 0.2
    assert variables["N_wall"].causality == "output" and variables["der(r)"].derivative is variables["r"]
    with zipfile.ZipFile(fmu) as archive:
        names = archive.namelist()
    assert "binaries/linux64/rotating_tube.so" in names or sys.platform != "linux"
    assert {"sources/rotating_tube.c", "sources/fmi2_rotating_tube.c", "sources/fmi2Functions.h",
            "documentation/licenses/fmi2-headers.txt"} <= set(names)


def test_without_a_compiler_fmu_exits_2_with_the_fix(tmp_path: Path) -> None:
    env = {**os.environ, "PATH": str(tmp_path / "empty"), "CC": ""}
    result = subprocess.run([sys.executable, "-m", "lagsolve", "export", str(PROBLEMS / "bead.yaml"), "--to", "fmu",
                             "-o", str(tmp_path / "out")], capture_output=True, text=True, check=False, env=env)
    assert result.returncode == 2, result.stderr
    assert "C compiler" in result.stderr and "install" in result.stderr
    assert not (tmp_path / "out").exists()


def test_xml_names_are_escaped_and_control_characters_refused() -> None:
    from lagsolve.render.c_module import Layout
    from lagsolve.render.fmu import attribute, variable_names

    assert attribute('a<b>&"c\'') == "a&lt;b&gt;&amp;&quot;c'"
    with pytest.raises(ValueError):
        attribute("bell\x07")
    with pytest.raises(ValueError, match="two variables"):
        variable_names(Layout(("x", "x_dot"), ("energy",), (1.0,), ("energy",), ()))
    with pytest.raises(SpecError):
        lagsolve.export(PROBLEMS / "bead.yaml", to="fmi", output="unused")


@needs_cc
def test_a_problem_name_with_xml_characters_is_escaped(tmp_path: Path) -> None:
    from fmpy import read_model_description
    from fmpy.validation import validate_fmu

    text = (PROBLEMS / "bead.yaml").read_text()
    lines = [line if not line.startswith("name:") else "name: 'A \"bead\" <on> & wire ]]> */'"
             for line in text.splitlines()]
    source = tmp_path / "odd-name.yaml"
    source.write_text("\n".join(lines) + "\n")
    fmu = lagsolve.export(source, to="fmu", output=tmp_path / "out")
    assert fmu.name == "odd_name.fmu"
    assert validate_fmu(str(fmu)) == []
    assert read_model_description(str(fmu)).modelName == 'A "bead" <on> & wire ]]> */'
