"""lagsolve export --to c: the C99 code compiles warning-free and reproduces lagsolve.simulate (issue 32)."""

from __future__ import annotations

import ctypes
import importlib.util
import shutil
import subprocess
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lagsolve
from lagsolve.errors import SpecError

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
CC = shutil.which("cc") or shutil.which("gcc")
needs_cc = pytest.mark.skipif(CC is None, reason="no C compiler")
DOUBLES = ctypes.POINTER(ctypes.c_double)


class Compiled:
    """The exported C of one problem, compiled and loaded through ctypes."""

    def __init__(self, name: str, folder: Path) -> None:
        source = lagsolve.export(PROBLEMS / f"{name}.yaml", to="c", output=folder)
        assert source == folder / f"{name}.c" and (folder / f"{name}.h").is_file()
        library = folder / f"{name}.so"
        assert CC is not None
        subprocess.run([CC, "-std=c99", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC", "-o", str(library),
                        str(source), "-lm"], check=True, capture_output=True, text=True)
        self.lib = ctypes.CDLL(str(library))
        self.prefix = name
        for function in ("rhs", "outputs", "event_indicators"):
            getattr(self.lib, f"{name}_{function}").restype = ctypes.c_int
        self.states = self._names("state_names")
        self.parameters = self._names("parameter_names")
        self.outputs_names = self._names("output_names")
        self.events = self._names("event_names")
        defaults = (ctypes.c_double * len(self.parameters)).in_dll(self.lib, f"{name}_parameter_defaults")
        self.p = np.array(defaults[:], dtype=float)

    def _names(self, label: str) -> list[str]:
        array = (ctypes.c_char_p * 200).in_dll(self.lib, f"{self.prefix}_{label}")
        out = []
        for item in array:
            if item is None:
                return out
            out.append(item.decode())
        raise AssertionError("no NULL at the end")

    def _call(self, function: str, t: float, y: np.ndarray, size: int) -> np.ndarray:
        y = np.ascontiguousarray(y, dtype=float)
        out = np.zeros(size)
        status = getattr(self.lib, f"{self.prefix}_{function}")(
            ctypes.c_double(t), y.ctypes.data_as(DOUBLES), self.p.ctypes.data_as(DOUBLES), out.ctypes.data_as(DOUBLES))
        assert status == 0
        return out

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        return self._call("rhs", t, y, len(self.states))

    def outputs(self, t: float, y: np.ndarray) -> dict[str, float]:
        return dict(zip(self.outputs_names, self._call("outputs", t, y, len(self.outputs_names)).tolist(),
                        strict=True))


def _python_module(name: str, folder: Path) -> ModuleType:
    path = lagsolve.export(PROBLEMS / f"{name}.yaml", to="python", output=folder)
    spec = importlib.util.spec_from_file_location(f"exported_c_{name}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@needs_cc
@pytest.mark.parametrize("name", ["bead", "rotating_tube", "rough_incline"])
def test_c_matches_simulate(name: str, tmp_path: Path) -> None:
    compiled = Compiled(name, tmp_path)
    run = lagsolve.simulate(PROBLEMS / f"{name}.yaml", t_end=1.0, samples=11, rtol=1e-13, atol=1e-14,
                            coordinates="full")
    assert not run.events
    n = len(run.coordinates)
    assert compiled.states == [*run.coordinates, *(f"{c}_dot" for c in run.coordinates)]
    y0 = np.concatenate((run.q[0], run.qd[0]))
    solution = solve_ivp(compiled.rhs, (0.0, 1.0), y0, method="DOP853", t_eval=run.t, rtol=1e-13, atol=1e-14)
    assert solution.success
    scale = max(1.0, float(np.max(np.abs(solution.y))))
    np.testing.assert_allclose(solution.y[:n].T, run.q, rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(solution.y[n:].T, run.qd, rtol=1e-9, atol=1e-9 * scale)
    columns = run.columns()
    for i, t in enumerate(run.t):
        out = compiled.outputs(t, solution.y[:, i])
        for j, c in enumerate(run.constraints):
            lam = float(run.multipliers[i, j])
            assert out[f"lambda_{c}"] == pytest.approx(lam, rel=1e-9, abs=1e-9 * max(1.0, abs(lam)))
        for key in columns:
            if key.startswith(("F_", "N_", "friction_")) or key == "energy":
                assert out[key] == pytest.approx(float(columns[key][i]), rel=1e-9, abs=1e-9)


@needs_cc
@pytest.mark.parametrize("name", ["bead", "rotating_tube", "rough_incline", "atwood", "pendulum_cartesian",
                                  "sliding_off_sphere", "stacked_blocks", "ladder_rough_floor", "rough_circular_wire",
                                  "moving_support", "disc_on_cylinder"])
def test_c_matches_the_python_export_at_random_states(name: str, tmp_path: Path) -> None:
    compiled = Compiled(name, tmp_path)
    module = _python_module(name, tmp_path)
    assert compiled.parameters == list(module.PARAMETERS)
    assert compiled.states == list(module.STATE)
    rng = np.random.default_rng(32)
    for _ in range(20):
        t = float(rng.uniform(0.0, 2.0))
        y = rng.uniform(0.3, 1.5, len(compiled.states))
        expected = module.rhs(t, y)
        np.testing.assert_allclose(compiled.rhs(t, y), expected, rtol=1e-12, atol=1e-12 * max(1.0, max(abs(expected))))
        out, reference = compiled.outputs(t, y), module.outputs(t, y)
        assert list(out) == list(reference)
        for key, value in reference.items():
            assert out[key] == pytest.approx(value, rel=1e-12, abs=1e-12 * max(1.0, abs(value))), key
        assert compiled.events == list(module.EVENTS)
        np.testing.assert_allclose(compiled._call("event_indicators", t, y, max(1, len(compiled.events)))[
            :len(compiled.events)], module.event_indicators(t, y), rtol=1e-12, atol=1e-12)


def test_a_file_name_without_identifier_is_refused(tmp_path: Path) -> None:
    source = tmp_path / "振子.yaml"
    source.write_text((PROBLEMS / "bead.yaml").read_text())
    with pytest.raises(SpecError, match="rename the file"):
        lagsolve.export(source, to="c", output=tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_names_are_escaped_in_strings_and_comments() -> None:
    from lagsolve.render.c_module import c_comment, c_prefix, c_string

    assert c_string('a"b\\c??/d\né') == '"a\\"b\\\\c\\?\\?/d\\012\\303\\251"'
    assert "*/" not in c_comment("x */ y /* z") and "?" not in c_comment("??/")
    assert c_prefix("2-link pendulum") == "m_2_link_pendulum"


HOSTILE = """\
name: "Hostile */ int main(void) { return 1; } /* ??/ \\\\"
parameters:
  out: {description: a local of the outputs}
  status: {description: another}
coordinates:
  y: {}
  p: {}
particles:
  t: {mass: out, position: [y, p]}
gravity: [0, -status]
constraints:
  NULL: {holonomic: y**2 + p**2 - 1, on: t}
simulation:
  values: {out: 2.0, status: 9.81}
  initial: {y: 1.0, y_dot: 0.0}
  t_end: 1.0
"""


@needs_cc
def test_hostile_names_compile_and_stay_strings(tmp_path: Path) -> None:
    (PROBLEMS_COPY := tmp_path / "problems").mkdir()
    (PROBLEMS_COPY / "hostile.yaml").write_text(HOSTILE)
    source = lagsolve.export(PROBLEMS_COPY / "hostile.yaml", to="c", output=tmp_path)
    text = source.read_text()
    assert "int main" in text.splitlines()[0] and text.index("*/") > text.index("Generated code")
    assert CC is not None
    subprocess.run([CC, "-std=c99", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC", "-o",
                    str(tmp_path / "hostile.so"), str(source), "-lm"], check=True, capture_output=True)
    lib = ctypes.CDLL(str(tmp_path / "hostile.so"))
    assert [n.decode() for n in (ctypes.c_char_p * 3).in_dll(lib, "hostile_parameter_names")[:2]] == ["out", "status"]
    y, p, dy = (np.array(v, dtype=float) for v in ([1.0, 0.0, 0.0, 0.0], [2.0, 9.81], [0.0] * 4))
    assert lib.hostile_rhs(ctypes.c_double(0.0), y.ctypes.data_as(DOUBLES), p.ctypes.data_as(DOUBLES),
                           dy.ctypes.data_as(DOUBLES)) == 0
    assert dy == pytest.approx([0.0, 0.0, 0.0, -9.81])
