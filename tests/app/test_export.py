"""lagsolve export --to python: the generated module reproduces lagsolve.simulate (issue 32)."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lagsolve
from lagsolve.errors import SpecError

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"


def _load(path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"exported_{path.stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", ["bead", "rotating_tube", "atwood", "pendulum_cartesian", "rough_incline",
                                  "moving_support"])
def test_module_matches_simulate(name: str, tmp_path: Path) -> None:
    written = lagsolve.export(PROBLEMS / f"{name}.yaml", to="python", output=tmp_path)
    assert written == tmp_path / f"{name}.py"
    module = _load(written)
    run = lagsolve.simulate(PROBLEMS / f"{name}.yaml", t_end=2.0, samples=5, rtol=1e-12, atol=1e-13,
                            coordinates="full")
    assert not run.events  # the module carries the kinetic law: compare while every contact slides
    n = len(run.coordinates)
    assert (*run.coordinates, *(f"{c}_dot" for c in run.coordinates)) == module.STATE
    y0 = np.concatenate((run.q[0], run.qd[0]))
    solution = solve_ivp(module.rhs, (0.0, 2.0), y0, method="DOP853", t_eval=run.t, rtol=1e-11, atol=1e-13)
    assert solution.success
    scale = max(1.0, float(np.max(np.abs(solution.y))))
    np.testing.assert_allclose(solution.y[:n].T, run.q, rtol=1e-8, atol=1e-8 * scale)
    np.testing.assert_allclose(solution.y[n:].T, run.qd, rtol=1e-8, atol=1e-8 * scale)
    columns = run.columns()
    assert any(key.startswith("N_") for key in columns) == (name in ("rotating_tube", "rough_incline"))
    for i, t in enumerate(run.t):
        out = module.outputs(t, solution.y[:, i])
        for j, c in enumerate(run.constraints):
            lam = float(run.multipliers[i, j])
            assert out[f"lambda_{c}"] == pytest.approx(lam, rel=1e-8, abs=1e-8 * max(1.0, abs(lam)))
            assert out[f"F_{c}"] == pytest.approx(float(columns[f"F_{c}"][i]), rel=1e-8, abs=1e-8)
            vector = [out[f"F_{c}_{axis}"] for axis in "xyz" if f"F_{c}_{axis}" in out]
            assert len(vector) >= 2 and np.hypot.reduce(vector) == pytest.approx(out[f"F_{c}"], rel=1e-12, abs=1e-12)
            assert abs(out[f"velocity_{c}"]) < 1e-7
        for key in columns:
            if key.startswith(("N_", "friction_")):
                assert out[key] == pytest.approx(float(columns[key][i]), rel=1e-8, abs=1e-8)
        assert out["energy"] == pytest.approx(float(columns["energy"][i]), rel=1e-8, abs=1e-8)


def test_unknown_target_is_refused_with_exit_2(tmp_path: Path) -> None:
    result = subprocess.run([sys.executable, "-m", "lagsolve", "export", str(PROBLEMS / "bead.yaml"),
                             "--to", "fortran", "-o", str(tmp_path)], capture_output=True, text=True, check=False)
    assert result.returncode == 2
    assert not list(tmp_path.iterdir())
    with pytest.raises(SpecError):
        lagsolve.export(PROBLEMS / "bead.yaml", to="fortran", output=tmp_path)


def test_output_is_byte_identical_across_hash_seeds(tmp_path: Path) -> None:
    texts = []
    for seed in ("1", "2"):
        folder = tmp_path / seed
        subprocess.run([sys.executable, "-m", "lagsolve", "export", str(PROBLEMS / "atwood.yaml"), "-o", str(folder)],
                       check=True, env={**os.environ, "PYTHONHASHSEED": seed}, capture_output=True)
        texts.append((folder / "atwood.py").read_bytes())
    assert texts[0] == texts[1]


HOSTILE = """\
name: "Hostile'); import os; os.system('echo pwned') #"
parameters:
  np: {description: the generated module's NumPy alias}
  numpy: {description: its module name}
  out: {description: a local of outputs}
coordinates:
  y: {}
  p: {}
particles:
  rhs: {mass: np, position: [y, p]}
gravity: [0, -numpy]
constraints:
  PARAMETERS: {holonomic: y**2 + p**2 - out**2, on: rhs}
simulation:
  values: {np: 2.0, numpy: 9.81, out: 1.0}
  initial: {y: 1.0, y_dot: 0.0}
  t_end: 1.0
"""


def test_hostile_names_stay_string_literals(tmp_path: Path) -> None:
    source = tmp_path / "hostile.yaml"
    source.write_text(HOSTILE)
    written = lagsolve.export(source, output=tmp_path / "out")
    text = written.read_text()
    lines = text.splitlines()
    assert lines[0].startswith("# Hostile") and not any("os.system" in line for line in lines[1:])
    module = _load(written)
    assert module.PARAMETERS == {"np": 2.0, "numpy": 9.81, "out": 1.0}
    assert module.STATE == ("y", "p", "y_dot", "p_dot")
    out = module.outputs(0.0, [1.0, 0.0, 0.0, 0.0])
    assert out["psi_PARAMETERS"] == pytest.approx(0.0)
    assert out["lambda_PARAMETERS"] == pytest.approx(0.0, abs=1e-12)
    assert module.rhs(0.0, [1.0, 0.0, 0.0, 0.0]) == pytest.approx([0.0, 0.0, 0.0, -9.81])
    assert module.rhs(0.0, [0.0, 1.0, 1.0, 0.0], {"np": 1.0, "numpy": 0.0, "out": 1.0}) == pytest.approx(
        [1.0, 0.0, 0.0, -1.0])


def test_a_parameter_without_value_is_nan_in_the_module(tmp_path: Path) -> None:
    from lagsolve.render.python_module import _number

    assert _number(float("nan")) == "float('nan')" and _number(2.5) == "2.5"


def test_an_output_file_that_is_a_link_is_refused_as_a_write_error(tmp_path: Path) -> None:
    """-o naming a symbolic link: refused (exit 2 through the command), the link's target untouched, and the
    message is the writer's (the path, "cannot write"), not "the equations cannot be exported ... simulate it
    instead", which it used to be wrapped in."""
    target = tmp_path / "target.txt"
    target.write_text("keep\n")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "bead.py").symlink_to(target)
    with pytest.raises(SpecError) as caught:
        lagsolve.export(PROBLEMS / "bead.yaml", to="python", output=tmp_path / "out" / "bead.py")
    message = str(caught.value)
    assert "bead.py" in message and "cannot write" in message
    assert "cannot be exported" not in message and "simulate" not in message
    assert target.read_text() == "keep\n"
