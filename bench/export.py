#!/usr/bin/env python3
"""Benchmark: exporting the 12-link pendulum to C and compiling it (issue 32, target: under 10 s together).

The planar n-link pendulum of ``bench/pendulum.py`` (default n = 12) is written to a temporary folder, then,
each in a fresh Python process (cold SymPy cache, ``PYTHONHASHSEED=0``; CPU time after imports):

* ``lagsolve.export(FILE, to="c")``: load, matrix form, bind, and the C text (header and source);
* ``lagsolve.export(FILE, to="python")``: the same equations as a NumPy module, for comparison;
* as the reference, in the same run: SymPy's own route to C, ``LagrangesMethod`` (``form_lagranges_equations``)
  and ``sympy.utilities.codegen.codegen`` of ``mass_matrix_full`` and ``forcing_full`` (C99) — which leaves the
  solve for q̈ to the caller, so it is less work than lagsolve's export;

then both C files are compiled (wall time) with ``cc -std=c99 -O2 -shared -fPIC`` (lagsolve's also with
``-Wall -Wextra -Werror``), and the compiled ``rhs`` is compared with the exported Python module's at a random
state (``agree``). The target is judged on lagsolve's export (CPU) plus its compilation (wall). The exit status
is always 0: this is a benchmark, not a test.

    .venv/bin/python bench/export.py              # n = 12
    .venv/bin/python bench/export.py --n 6 --json
"""

from __future__ import annotations

import argparse
import ctypes
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pendulum import pendulum_yaml  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
TARGET = 10.0  # seconds: export to C and compile, 12-link pendulum
CHILD_ENV = {**os.environ, "PYTHONHASHSEED": "0"}
FLAGS = ["-std=c99", "-O2", "-shared", "-fPIC"]
STRICT = ["-Wall", "-Wextra", "-Werror"]


def child_export(path: str, to: str, folder: str) -> None:
    """Print the CPU seconds of ``lagsolve.export`` (imports first, not counted)."""
    import lagsolve
    from lagsolve.app import export  # noqa: F401 - imported before the clock starts
    from lagsolve.mechanics.equations import matrix_form  # noqa: F401
    from lagsolve.numeric import system  # noqa: F401
    from lagsolve.problem import load  # noqa: F401
    from lagsolve.render import c_module, python_module  # noqa: F401

    start = time.process_time()
    lagsolve.export(path, to=to, output=folder)
    print(json.dumps({"cpu": time.process_time() - start}))


def child_sympy(n: int, folder: str) -> None:
    """SymPy's route to C: LagrangesMethod, then codegen of the mass matrix and forcing (no solve)."""
    import sympy as sp
    import sympy.physics.mechanics as me
    from sympy.utilities.codegen import codegen

    start = time.process_time()
    q = [me.dynamicsymbols(f"th{i}") for i in range(1, n + 1)]
    m, l, g = sp.symbols("m l g")  # noqa: E741 - the problem's name for the rod length
    t = me.dynamicsymbols._t
    x = y = sp.Integer(0)
    lagrangian = sp.Integer(0)
    for th in q:
        x, y = x + l * sp.sin(th), y - l * sp.cos(th)
        lagrangian += m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y
    lm = me.LagrangesMethod(lagrangian, q)
    lm.form_lagranges_equations()
    plain = {**{qd.diff(t): sp.Symbol(f"w{i}") for i, qd in enumerate(q)},
             **{th: sp.Symbol(f"q{i}") for i, th in enumerate(q)}}
    mass = lm.mass_matrix_full.xreplace(plain)
    forcing = lm.forcing_full.xreplace(plain)
    [(c_name, c_code), (h_name, h_code)] = codegen([("mass", mass), ("forcing", forcing)], "C99", "lm_pendulum",
                                                   header=False, empty=False)
    Path(folder, c_name).write_text(c_code)
    Path(folder, h_name).write_text(h_code)
    print(json.dumps({"cpu": time.process_time() - start}))


def _child(*args: str) -> float:
    done = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--child", *args], capture_output=True,
                          text=True, env=CHILD_ENV, timeout=600, check=True)
    return float(json.loads(done.stdout.strip().splitlines()[-1])["cpu"])


def _compile(compiler: str, source: Path, target: Path, strict: bool) -> float:
    start = time.perf_counter()
    subprocess.run([compiler, *FLAGS, *(STRICT if strict else []), "-o", str(target), str(source), "-lm"],
                   check=True, capture_output=True, timeout=600)
    return time.perf_counter() - start


def _agree(folder: Path, name: str, n: int) -> bool:
    """The compiled C rhs equals the exported Python module's at a random state (to 1e-12)."""
    import numpy as np

    spec = importlib.util.spec_from_file_location("bench_export_module", folder / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    lib = ctypes.CDLL(str(folder / f"{name}.so"))
    y = np.random.default_rng(32).uniform(-1.0, 1.0, 2 * n)
    p = np.array(list(module.PARAMETERS.values()), dtype=float)
    dy = np.zeros(2 * n)
    doubles = ctypes.POINTER(ctypes.c_double)
    status = getattr(lib, f"{name}_rhs")(ctypes.c_double(0.3), y.ctypes.data_as(doubles),
                                          p.ctypes.data_as(doubles), dy.ctypes.data_as(doubles))
    expected = module.rhs(0.3, y)
    return bool(status == 0 and np.allclose(dy, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.max(abs(expected)))))


def run(n: int) -> dict[str, Any]:
    compiler = shutil.which("cc") or shutil.which("gcc")
    with tempfile.TemporaryDirectory(prefix="lagsolve-bench-export-") as scratch:
        folder = Path(scratch)
        name = f"pendulum{n}"
        path = folder / f"{name}.yaml"
        path.write_text(pendulum_yaml(n, 10.0, "bench/export.py"))
        export_c = _child("export", str(path), "c", str(folder))
        export_python = _child("export", str(path), "python", str(folder))
        reference = _child("sympy", str(n), str(folder))
        result: dict[str, Any] = {
            "n": n, "export_c_s": export_c, "export_python_s": export_python, "reference_s": reference,
            "reference": "SymPy LagrangesMethod + codegen(C99) of mass_matrix_full, forcing_full (no solve)",
            "c_lines": len((folder / f"{name}.c").read_text().splitlines()), "target_s": TARGET,
        }
        if compiler is None:
            result.update(compile_s=None, reference_compile_s=None, total_s=None, result="MISS", agree=None,
                          note="no C compiler")
            return result
        result["compile_s"] = _compile(compiler, folder / f"{name}.c", folder / f"{name}.so", strict=True)
        result["reference_compile_s"] = _compile(compiler, folder / "lm_pendulum.c", folder / "lm.so", strict=False)
        result["total_s"] = export_c + result["compile_s"]
        result["result"] = "PASS" if result["total_s"] < TARGET else "MISS"
        result["agree"] = _agree(folder, name, n)
        return result


def report(result: dict[str, Any]) -> str:
    def seconds(value: float | None) -> str:
        return "-" if value is None else f"{value:7.2f} s"

    return "\n".join([
        f"Export of the planar {result['n']}-link pendulum (fresh processes, PYTHONHASHSEED=0; CPU after imports, "
        "compile wall time)",
        f"  lagsolve export --to c      {seconds(result['export_c_s'])}   ({result['c_lines']} lines of C)",
        f"  cc -Wall -Wextra -Werror    {seconds(result['compile_s'])}",
        f"  export + compile            {seconds(result['total_s'])}   target {TARGET:g} s: {result['result']}",
        f"  lagsolve export --to python {seconds(result['export_python_s'])}",
        f"  reference: {result['reference']}",
        f"    codegen                   {seconds(result['reference_s'])}",
        f"    cc                        {seconds(result['reference_compile_s'])}",
        f"  C rhs equals the Python export's at a random state: {result['agree']}",
    ])


def main() -> None:
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        kind, *args = sys.argv[2:]
        if kind == "export":
            child_export(*args)
        else:
            child_sympy(int(args[0]), args[1])
        return
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=12, help="links of the pendulum (default 12)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    options = parser.parse_args()
    result = run(options.n)
    print(json.dumps(result, indent=2) if options.json else report(result))


if __name__ == "__main__":
    main()
