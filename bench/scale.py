#!/usr/bin/env python3
"""Benchmark: how lagsolve scales with the size of the system (issue 11 item 6).

For a planar n-link pendulum (n = 2, 3, 4, 6, 8, 12, 20, and 50 with ``--large``: n equal particles of mass m
on massless rods of length l, angles th1..thn from the downward vertical, gravity) this measures, each in a fresh
process with a cap on its time:

* the whole ``lagsolve derive FILE`` as a command (wall time, start-up included) and as a
  library call (``load_problem`` + ``derive``, CPU time);
* lagsolve's core, ``matrix_form(problem, display=False)``, and the ``simulate`` build
  (``load`` + ``matrix_form(display=False)`` + ``bind``), CPU time;
* ``lagsolve simulate FILE --t-end 10`` (wall time, start-up included);
* SymPy's ``LagrangesMethod`` (``form_lagranges_equations()`` + ``rhs()``) and
  ``KanesMethod`` (``kanes_equations()``, the core, then ``rhs()``), CPU time;

then the ratios and the targets (PASS/MISS), among them issue 33's (the whole ``lagsolve derive`` of the 20- and
50-link pendulum within 5 s and 60 s, the 20-link simulation within 5 s, beside KanesMethod and LagrangesMethod of
the same run), and the library derive CPU time of every problem in ``problems/`` (target: each under 5 s).

A measurement that has not finished after ``--cap`` seconds of wall time is stopped (its
whole process group is killed) and its cell shows "> cap"; a measurement stopped at one n
before it gave any figure is not tried at a larger n. The exit status is always 0: this is a benchmark, not a test.

    .venv/bin/python bench/scale.py                          # the whole table (up to ~40 min)
    .venv/bin/python bench/scale.py --only-n 2 --only-n 3 --repeat 1 --skip-problems
    .venv/bin/python bench/scale.py --cap 60 --json
    .venv/bin/python bench/scale.py --only-n 20 --large --repeat 1 --skip-problems   # issue 33's sizes alone
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pendulum import pendulum_yaml as shared_pendulum  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
LM_SIZES = (2, 3, 4, 6, 8, 12)  # the sizes of the target against LagrangesMethod
SIZES = (*LM_SIZES, 20)
LARGE_N = 50  # added with --large: its derive takes most of a minute, the references are capped
DEFAULT_CAP = 120.0  # seconds of wall time for one measurement (one fresh process)
DEFAULT_REPEAT = 3
SLOW_RUN = 15.0  # a measurement slower than this is not repeated (its figure is from one run)
STOP_GRACE = 5.0  # seconds a child stopped at the cap gets to report how far it got, before SIGKILL
T_END = 10.0  # seconds of simulated time for `lagsolve simulate`
PROBLEM_TARGET = 5.0  # CPU seconds for the library derive of each problems/*.yaml
SIMULATE_TARGET = 3.0  # wall seconds for `lagsolve simulate` of the 6-link pendulum, start-up included
SIMULATE_TARGET_N = 6
CORE_TARGET = 2.0  # KanesMethod core / lagsolve core, at n = 12
CORE_TARGET_N = 12
# issue 33, target 2: the whole `lagsolve derive` (wall, start-up included) at these n, and the simulation of the
# 20-link pendulum for 10 s; the reference is SymEngine-backed KanesMethod's published form-only time
ISSUE33_DERIVE = {20: 5.0, 50: 60.0}
ISSUE33_SIMULATE_N, ISSUE33_SIMULATE = 20, 5.0
PUBLISHED_KANE = {20: 0.95, 50: 14.0}
# a fixed hash seed makes SymPy's term order, and so its run time, repeatable between runs
CHILD_ENV = {**os.environ, "PYTHONHASHSEED": "0"}

# measurement key -> (column title, clock, what it is)
CELLS: dict[str, tuple[str, str, str]] = {
    "cli_derive": ("derive CLI", "wall", "`lagsolve derive FILE -o DIR` as a command, start-up included"),
    "lib_derive": ("derive lib", "cpu", "load_problem(file) + derive(problem)"),
    "core": ("core", "cpu", "matrix_form(problem, display=False)"),
    "build": ("sim build", "cpu", "load + matrix_form(display=False) + bind(form)"),
    "sim_run": ("sim 10 s", "wall", f"`lagsolve simulate FILE --t-end {T_END:g}`, start-up included"),
    "lm_total": ("LM", "cpu", "LagrangesMethod: form_lagranges_equations() + rhs()"),
    "kane_core": ("Kane core", "cpu", "KanesMethod: kinematics + kanes_equations()"),
    "kane_total": ("Kane", "cpu", "KanesMethod: kanes_equations() + rhs()"),
}

COLUMNS = """\
Columns (best of {repeat} run(s); each measurement in a fresh Python process with a cold SymPy
cache and PYTHONHASHSEED=0; "cpu" figures are time.process_time() inside that process and leave
out interpreter start-up and imports (also the ones a derivation makes on first use), "wall"
figures are whole commands, start-up included;
"> cap" means the measurement was stopped after {cap:g} s of wall time, or was not tried because it
was stopped at a smaller n before it gave any figure):
  derive CLI   wall: `lagsolve derive FILE -o DIR` (all three reports), FILE generated in a temp dir
  derive lib   cpu: load_problem(FILE) + derive(problem), the whole mechanics stage with the
               display simplification of every result
  core         cpu: matrix_form(problem, display=False): the equations in matrix form M, F, A, beta,
               no solve, no simplification (load_problem is not included)
  sim build    cpu: load + matrix_form(display=False) + bind(form), what `lagsolve simulate` builds
               before integrating (as bench/simulate.py's build column, but CPU time)
  sim 10 s     wall: `lagsolve simulate FILE --t-end 10` (DOP853, default tolerances), start-up included;
               this includes the derivation of the conserved quantities for the energy check, which
               `lagsolve simulate` gives up after its own 60 s budget (SimulationOptions.analysis_timeout)
  LM           cpu: sympy.physics.mechanics.LagrangesMethod written by hand: building L +
               form_lagranges_equations() + rhs() (LU solve for the accelerations): derive + solve
  Kane core    cpu: KanesMethod with u_i = th_i': frames, points (v2pt_theory), KanesMethod(...) +
               kanes_equations(particles, gravity loads), without solving
  Kane         cpu: Kane core + rhs() (LU solve of mass_matrix_full, forcing_full)
  derive ratio LM / derive lib: how many times faster lagsolve's whole derivation is than
               LagrangesMethod's derive + solve (> 1: lagsolve is faster)
  core ratio   Kane core / core: how many times faster lagsolve's core is than KanesMethod's
  A ratio with a capped side is a bound, ">" (at least) or "<" (at most), from the time the capped side
  had run when it was stopped (CPU time for a cpu column); "?" when both are capped."""


# --------------------------------------------------------------------------- the problem


def pendulum_yaml(n: int) -> str:
    """A planar n-link pendulum (:func:`pendulum.pendulum_yaml`)."""
    return shared_pendulum(n, T_END, "bench/scale.py")


# --------------------------------------------------------------------------- children
# Each child prints one JSON line per finished stage (flushed), so that a child stopped at the
# cap still reports the stages it finished.


def _emit(**figures: Any) -> None:
    print(json.dumps(figures), flush=True)


class Stages:
    """The CPU clock of a child's stages. Each finished stage is printed at once; when the parent
    stops the child at the cap (SIGTERM), the CPU time each unfinished stage has run so far is
    printed as ``<stage>_at_least`` before the child exits."""

    def __init__(self) -> None:
        self.pending: dict[str, float] = {}
        signal.signal(signal.SIGTERM, self._stopped)

    def begin(self, *keys: str) -> None:
        now = time.process_time()
        self.pending.update(dict.fromkeys(keys, now))

    def done(self, key: str, **extra: float) -> None:
        _emit(**{key: time.process_time() - self.pending.pop(key)}, **extra)

    def _stopped(self, signum: int, frame: Any) -> None:
        now = time.process_time()
        _emit(**{f"{key}_at_least": now - start for key, start in self.pending.items()})
        os._exit(3)


#: modules a derivation imports on first use: lagsolve's own lazy imports (the YAML reader, SymEngine,
#: NumPy and SciPy's root finder for numeric equilibria) and SymPy's (``simplify`` imports units, tensors
#: and permutation groups on its first call). They are imported before the clock starts, as the
#: LagrangesMethod child imports sympy.physics.mechanics before its clock starts: the "cpu" columns
#: leave out imports on both sides (about 0.3 s of CPU here).
LAZY_IMPORTS = ("ruamel.yaml", "symengine", "numpy", "scipy.optimize", "sympy.physics.units",
                "sympy.tensor.tensor", "sympy.combinatorics")


def _preload() -> None:
    import importlib

    for name in LAZY_IMPORTS:
        with contextlib.suppress(ImportError):
            importlib.import_module(name)


def child_derive(path: str) -> None:
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    _preload()
    stages = Stages()
    stages.begin("lib_derive")
    derive(load_problem(path))
    stages.done("lib_derive")


def child_build(path: str) -> None:
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.numeric.system import bind
    from lagsolve.problem.load import load_problem

    with contextlib.suppress(ImportError):  # the LLVM backend imports SymEngine on first use: not building
        import symengine  # noqa: F401
    stages = Stages()
    stages.begin("build")
    start = time.process_time()
    problem = load_problem(path)
    stages.begin("core")
    form = matrix_form(problem, display=False)
    stages.done("core", load=stages.pending["core"] - start)
    bind(form)
    stages.done("build")


def child_lm(n: int) -> None:
    import sympy as sp
    import sympy.physics.mechanics as me

    stages = Stages()
    stages.begin("lm_eqs", "lm_total")
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
    stages.done("lm_eqs")
    lm.rhs()
    stages.done("lm_total")


def child_kane(n: int) -> None:
    import sympy as sp
    import sympy.physics.mechanics as me

    stages = Stages()
    stages.begin("kane_core", "kane_total")
    q = [me.dynamicsymbols(f"th{i}") for i in range(1, n + 1)]
    u = [me.dynamicsymbols(f"w{i}") for i in range(1, n + 1)]
    m, l, g = sp.symbols("m l g")  # noqa: E741
    frame = me.ReferenceFrame("N")
    pivot = me.Point("O")
    pivot.set_vel(frame, 0)
    previous = pivot
    particles, loads = [], []
    for i in range(n):
        rod = me.ReferenceFrame(f"A{i + 1}")
        rod.orient_axis(frame, frame.z, q[i])
        rod.set_ang_vel(frame, u[i] * frame.z)
        bob = previous.locatenew(f"P{i + 1}", -l * rod.y)
        bob.v2pt_theory(previous, frame, rod)
        particles.append(me.Particle(f"p{i + 1}", bob, m))
        loads.append((bob, -m * g * frame.y))
        previous = bob
    kinematics = [qi.diff() - ui for qi, ui in zip(q, u, strict=True)]
    kane = me.KanesMethod(frame, q_ind=q, u_ind=u, kd_eqs=kinematics)
    kane.kanes_equations(particles, loads)
    stages.done("kane_core")
    kane.rhs()
    stages.done("kane_total")


def run_child(kind: str, arg: str) -> None:
    if kind == "derive":
        child_derive(arg)
    elif kind == "build":
        child_build(arg)
    elif kind == "lm":
        child_lm(int(arg))
    elif kind == "kane":
        child_kane(int(arg))
    else:
        raise SystemExit(f"unknown child {kind!r}")


# --------------------------------------------------------------------------- parent


@dataclass
class Run:
    """One capped subprocess: its wall time, the JSON figures it printed, and how it ended."""

    wall: float
    figures: dict[str, float]
    capped: bool
    error: str | None


def run_capped(cmd: list[str], cap: float, cwd: Path) -> Run:
    """Run ``cmd`` in its own process group; stop the whole group after ``cap`` seconds of wall time
    (SIGTERM, so that a child can say how far it got, then SIGKILL after a grace period)."""
    start = time.perf_counter()
    process = subprocess.Popen(cmd, cwd=cwd, env=CHILD_ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, start_new_session=True)
    try:
        out, err = process.communicate(timeout=cap)
    except subprocess.TimeoutExpired:
        wall = time.perf_counter() - start
        _signal_group(process.pid, signal.SIGTERM)
        try:  # communicate() again loses no output
            out, err = process.communicate(timeout=STOP_GRACE)
        except subprocess.TimeoutExpired:
            _signal_group(process.pid, signal.SIGKILL)
            out, err = process.communicate()
        _signal_group(process.pid, signal.SIGKILL)  # anything the child left behind in its group
        return Run(wall, _figures(out), True, None)
    wall = time.perf_counter() - start
    error = None
    if process.returncode != 0:
        tail = (err.strip().splitlines() or ["no output"])[-1]
        error = f"exit {process.returncode}: {tail[:200]}"
    return Run(wall, _figures(out), False, error)


def _signal_group(pgid: int, signum: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, signum)


def _figures(out: str) -> dict[str, float]:
    """The JSON lines a child printed, merged."""
    figures: dict[str, float] = {}
    for line in out.splitlines():
        if line.startswith("{"):
            with contextlib.suppress(json.JSONDecodeError):
                figures.update(json.loads(line))
    return figures


def _lagsolve_command() -> list[str]:
    script = Path(sys.executable).parent / "lagsolve"
    return [str(script)] if script.exists() else [sys.executable, "-m", "lagsolve"]


def _child_command(kind: str, arg: str) -> list[str]:
    return [sys.executable, str(Path(__file__).resolve()), "--child", kind, arg]


@dataclass
class Measurement:
    """What one kind of child measures: its command, and the cells it fills (from JSON or wall time)."""

    name: str
    cells: tuple[str, ...]
    command: Callable[[int, Path, Path], list[str]]
    wall_cell: str | None = None  # the cell that is the child's wall time


MEASUREMENTS = (
    Measurement("cli_derive", ("cli_derive",),
                lambda n, path, tmp: [*_lagsolve_command(), "derive", str(path), "-o", str(tmp / "out"),
                                      "--timeout", "100000"], wall_cell="cli_derive"),
    Measurement("lib_derive", ("lib_derive",), lambda n, path, tmp: _child_command("derive", str(path))),
    Measurement("build", ("core", "build"), lambda n, path, tmp: _child_command("build", str(path))),
    Measurement("sim_run", ("sim_run",),
                lambda n, path, tmp: [*_lagsolve_command(), "simulate", str(path), "--t-end", f"{T_END:g}",
                                      "--timeout", "100000"], wall_cell="sim_run"),
    Measurement("lm", ("lm_total",), lambda n, path, tmp: _child_command("lm", str(n))),
    Measurement("kane", ("kane_core", "kane_total"), lambda n, path, tmp: _child_command("kane", str(n))),
)


def _empty_cell() -> dict[str, Any]:
    return {"seconds": None, "capped": False, "at_least": None, "skipped": False, "error": None, "runs": 0}


def measure(measurement: Measurement, n: int, path: Path, tmp: Path, repeat: int, cap: float,
            progress: Callable[[str], None], label: str) -> dict[str, dict[str, Any]]:
    """Up to ``repeat`` runs of one measurement; the best figure of each of its cells."""
    cells = {key: _empty_cell() for key in measurement.cells}
    for i in range(repeat):
        progress(f"{label}: {measurement.name} run {i + 1}/{repeat}")
        run = run_capped(measurement.command(n, path, tmp), cap, tmp)
        figures = dict(run.figures)
        if measurement.wall_cell and not run.capped and run.error is None:
            figures[measurement.wall_cell] = run.wall
        for key, cell in cells.items():
            cell["runs"] += 1
            value = figures.get(key)
            if isinstance(value, (int, float)):
                cell["seconds"] = value if cell["seconds"] is None else min(cell["seconds"], value)
            elif run.capped and cell["seconds"] is None:
                # how long it had run when stopped: the wall time, or the CPU time the child reported
                spent = run.wall if key == measurement.wall_cell else figures.get(f"{key}_at_least")
                cell["capped"] = True
                cell["at_least"] = spent if isinstance(spent, (int, float)) else None
            elif run.error and cell["seconds"] is None:
                cell["error"] = run.error
        if run.capped or run.error or run.wall > SLOW_RUN:
            break
    for cell in cells.values():
        if cell["seconds"] is not None:
            cell["capped"] = False
            cell["at_least"] = None
            cell["error"] = None
    return cells


def _ratio(slow: dict[str, Any], fast: dict[str, Any]) -> dict[str, Any]:
    """slow / fast; a bound when one side was capped, from the time it had run when it was stopped."""
    a, b = slow["seconds"], fast["seconds"]
    if a is not None and b is not None:
        return {"value": a / b, "bound": "exact"}
    if slow["capped"] and slow["at_least"] and b is not None:
        return {"value": slow["at_least"] / b, "bound": "lower"}
    if fast["capped"] and fast["at_least"] and a is not None:
        return {"value": a / fast["at_least"], "bound": "upper"}
    return {"value": None, "bound": None}


def bench_sizes(sizes: list[int], repeat: int, cap: float, tmp: Path,
                progress: Callable[[str], None]) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = []
    given_up: dict[str, tuple[int, dict[str, dict[str, Any]]]] = {}  # measurement -> n and cells when capped
    for n in sizes:
        path = tmp / f"pendulum{n}.yaml"
        path.write_text(pendulum_yaml(n), encoding="utf-8")
        cells: dict[str, dict[str, Any]] = {}
        for measurement in MEASUREMENTS:
            if measurement.name in given_up:
                # a larger pendulum takes at least as long as the one that was stopped
                stopped_at, stopped = given_up[measurement.name]
                for key in measurement.cells:
                    cells[key] = {**_empty_cell(), "capped": True, "skipped": True,
                                  "at_least": stopped[key]["at_least"],
                                  "note": f"not tried: capped at n = {stopped_at}"}
                continue
            measured = measure(measurement, n, path, tmp, repeat, cap, progress, f"n = {n}")
            cells.update(measured)
            if all(cell["capped"] for cell in measured.values()):  # nothing left to learn at a larger n
                given_up[measurement.name] = (n, measured)
        rows.append({
            "n": n,
            "cells": cells,
            "ratios": {"derive": _ratio(cells["lm_total"], cells["lib_derive"]),
                       "core": _ratio(cells["kane_core"], cells["core"])},
        })
    return rows


def bench_problems(repeat: int, cap: float, tmp: Path, progress: Callable[[str], None]) -> list[dict[str, Any]]:
    measurement = Measurement("problem", ("lib_derive",), lambda n, path, _: _child_command("derive", str(path)))
    rows = []
    for path in sorted((ROOT / "problems").glob("*.yaml")):
        cell = measure(measurement, 0, path, tmp, repeat, cap, progress, path.name)["lib_derive"]
        seconds = cell["seconds"]
        rows.append({"name": path.stem, "file": str(path.relative_to(ROOT)), **cell,
                     "pass": None if seconds is None and not cell["capped"] else
                     (seconds is not None and seconds < PROBLEM_TARGET)})
    return rows


def _verdict(values: list[bool | None]) -> str:
    if any(v is False for v in values):
        return "MISS"
    if values and all(v is True for v in values):
        return "PASS"
    return "n/a"


def targets(rows: list[dict[str, Any]], problems: list[dict[str, Any]] | None, cap: float) -> list[dict[str, Any]]:
    by_n = {row["n"]: row for row in rows}
    found: list[dict[str, Any]] = []

    if problems is None:
        found.append({"name": "problems", "verdict": "n/a", "detail": "problems/ not measured (--skip-problems)",
                      "text": f"every problems/*.yaml derives in < {PROBLEM_TARGET:g} s CPU"})
    else:
        slow = [p["name"] for p in problems if p["pass"] is False]
        found.append({"name": "problems", "verdict": _verdict([p["pass"] for p in problems]),
                      "detail": f"{len(problems) - len(slow)}/{len(problems)} under {PROBLEM_TARGET:g} s"
                      + (f"; slower: {', '.join(slow)}" if slow else ""),
                      "text": f"every problems/*.yaml derives in < {PROBLEM_TARGET:g} s CPU"})

    # lagsolve's whole derive faster than LagrangesMethod at every n <= 12
    checks: list[bool | None] = []
    unmeasured = [n for n in LM_SIZES if n not in by_n]
    notes = [f"n = {', '.join(map(str, unmeasured))} not measured"] if unmeasured else []
    for n in LM_SIZES:
        if n not in by_n:
            checks.append(None)
            continue
        ratio = by_n[n]["ratios"]["derive"]
        if ratio["value"] is None:
            checks.append(None)
            notes.append(f"n = {n}: both capped")
        elif ratio["bound"] == "upper" and ratio["value"] <= 1.0:
            checks.append(False)
        elif ratio["bound"] == "lower" and ratio["value"] >= 1.0:
            checks.append(True)
        elif ratio["bound"] == "exact":
            checks.append(ratio["value"] > 1.0)
        else:
            checks.append(None)
            notes.append(f"n = {n}: undecided ({_ratio_text(ratio)})")
    misses = [n for n, ok in zip(LM_SIZES, checks, strict=True) if ok is False]
    found.append({"name": "derive_vs_lm", "verdict": _verdict(checks),
                  "detail": "; ".join(([f"slower at n = {', '.join(map(str, misses))}"] if misses else []) + notes),
                  "text": "whole n-link derive faster than LagrangesMethod derive+solve at every n <= 12"})

    row = by_n.get(CORE_TARGET_N)
    ok: bool | None = None
    detail = f"n = {CORE_TARGET_N} not measured"
    if row is not None:
        ratio = row["ratios"]["core"]
        detail = f"core ratio {_ratio_text(ratio)}"
        if ratio["value"] is not None:
            if ratio["bound"] == "exact":
                ok = ratio["value"] >= CORE_TARGET
            elif ratio["bound"] == "upper" and ratio["value"] < CORE_TARGET:
                ok = False
            elif ratio["bound"] == "lower" and ratio["value"] >= CORE_TARGET:
                ok = True
    found.append({"name": "core_vs_kane", "verdict": _verdict([ok]), "detail": detail,
                  "text": f"lagsolve core >= {CORE_TARGET:g}x faster than KanesMethod core at n = {CORE_TARGET_N}"})

    row = by_n.get(SIMULATE_TARGET_N)
    ok = None
    detail = f"n = {SIMULATE_TARGET_N} not measured"
    if row is not None:
        cell = row["cells"]["sim_run"]
        if cell["seconds"] is not None:
            ok = cell["seconds"] < SIMULATE_TARGET
            detail = f"{cell['seconds']:.2f} s"
        elif cell["capped"]:
            ok = False if cap >= SIMULATE_TARGET else None  # slower than the cap
            detail = f"> {cap:g} s"
        else:
            detail = cell["error"] or "no figure"
    found.append({"name": "simulate", "verdict": _verdict([ok]), "detail": detail,
                  "text": f"simulate of the {SIMULATE_TARGET_N}-link pendulum for {T_END:g} s < {SIMULATE_TARGET:g} s "
                          "including start-up"})
    return found + issue33_targets(by_n, cap)


def _seconds(cell: dict[str, Any] | None) -> str:
    """A cell as the targets' details write it: its figure, "> cap" with the time it had run, or why not."""
    if cell is None:
        return "not measured"
    if cell["seconds"] is not None:
        return f"{cell['seconds']:.2f} s"
    if cell["capped"]:
        return f"> {cell['at_least']:.0f} s (capped)" if cell.get("at_least") else "> cap"
    return cell["error"] or "no figure"


def _references(row: dict[str, Any], n: int) -> str:
    """SymPy's KanesMethod and LagrangesMethod in the same run, and the published SymEngine-backed KanesMethod."""
    cells = row["cells"]
    published = (f"; SymEngine KanesMethod, published: {PUBLISHED_KANE[n]:g} s (form only)" if n in PUBLISHED_KANE
                 else "")
    return (f"this run: KanesMethod core {_seconds(cells.get('kane_core'))}, LagrangesMethod derive + solve "
            f"{_seconds(cells.get('lm_total'))}{published}")


def _within(cell: dict[str, Any], limit: float, cap: float) -> bool | None:
    """The figure is within ``limit``; False when capped past it; None when not decided."""
    if cell["seconds"] is not None:
        return bool(cell["seconds"] <= limit)
    return False if cell["capped"] and cap >= limit else None


def issue33_targets(by_n: dict[int, dict[str, Any]], cap: float) -> list[dict[str, Any]]:
    """Issue 33, target 2: the whole `lagsolve derive` of the 20- and 50-link pendulum within 5 s and 60 s, and
    `lagsolve simulate` of the 20-link one for 10 s within 5 s (wall, start-up included), each beside the references
    of the same run."""
    found = []
    for n, limit in ISSUE33_DERIVE.items():
        row = by_n.get(n)
        ok = None if row is None else _within(row["cells"]["cli_derive"], limit, cap)
        detail = (f"n = {n} not measured" + (" (--large)" if n == LARGE_N else "") if row is None
                  else f"{_seconds(row['cells']['cli_derive'])}; {_references(row, n)}")
        found.append({"name": f"issue33_derive_{n}", "verdict": _verdict([ok]), "detail": detail,
                      "text": f"issue 33: the whole `lagsolve derive` of the {n}-link pendulum <= {limit:g} s"})
    row = by_n.get(ISSUE33_SIMULATE_N)
    ok = None if row is None else _within(row["cells"]["sim_run"], ISSUE33_SIMULATE, cap)
    detail = f"n = {ISSUE33_SIMULATE_N} not measured" if row is None else _seconds(row["cells"]["sim_run"])
    found.append({"name": "issue33_simulate", "verdict": _verdict([ok]), "detail": detail,
                  "text": f"issue 33: `lagsolve simulate` of the {ISSUE33_SIMULATE_N}-link pendulum for {T_END:g} s "
                          f"<= {ISSUE33_SIMULATE:g} s, start-up included"})
    return found


def _versions() -> dict[str, str]:
    code = ("import importlib.metadata as m\nfor p in ('lagsolve', 'sympy', 'symengine', 'numpy', 'scipy'):\n"
            "    try: print(p, m.version(p))\n    except m.PackageNotFoundError: print(p, '-')")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    return dict(line.split(" ", 1) for line in done.stdout.splitlines())


def bench(sizes: list[int], repeat: int, cap: float, with_problems: bool,
          progress: Callable[[str], None]) -> dict[str, Any]:
    begin = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="lagsolve-scale-") as folder:
        tmp = Path(folder)
        rows = bench_sizes(sizes, repeat, cap, tmp, progress)
        problems = bench_problems(repeat, cap, tmp, progress) if with_problems else None
    return {
        "python": sys.version.split()[0],
        "versions": _versions(),
        "repeat": repeat,
        "cap_s": cap,
        "t_end": T_END,
        "sizes": sizes,
        "columns": {key: {"title": title, "clock": clock, "what": what}
                    for key, (title, clock, what) in CELLS.items()},
        "rows": rows,
        "problems": problems,
        "targets": targets(rows, problems, cap),
        "total_s": time.perf_counter() - begin,
    }


# --------------------------------------------------------------------------- report


def _cell_text(cell: dict[str, Any], width: int) -> str:
    if cell["seconds"] is not None:
        return f"{cell['seconds']:{width - 1}.2f}s"
    if cell["capped"]:
        return f"{'> cap':>{width}}"
    return f"{'error':>{width}}" if cell["error"] else f"{'-':>{width}}"


def _ratio_text(ratio: dict[str, Any]) -> str:
    if ratio["value"] is None:
        return "?"
    sign = {"exact": "", "lower": ">", "upper": "<"}[ratio["bound"]]
    value = ratio["value"]
    return f"{sign}{value:.2g}x" if value < 1 else f"{sign}{value:.1f}x" if value < 100 else f"{sign}{value:.0f}x"


def report(result: dict[str, Any]) -> str:
    versions = result["versions"]
    lines = [
        f"lagsolve scaling benchmark: planar n-link pendulum (Python {result['python']}, "
        f"SymPy {versions.get('sympy', '?')}, SymEngine {versions.get('symengine', '?')}; "
        f"cap {result['cap_s']:g} s per measurement)",
        "",
    ]
    width = 11
    header = f"{'n':>3} " + " ".join(f"{CELLS[key][0]:>{width}}" for key in CELLS)
    header += f" {'derive ratio':>12} {'core ratio':>10}"
    clocks = f"{'':>3} " + " ".join(f"{'(' + CELLS[key][1] + ')':>{width}}" for key in CELLS)
    lines += [header, clocks]
    errors = []
    for row in result["rows"]:
        text = f"{row['n']:>3} " + " ".join(_cell_text(row["cells"][key], width) for key in CELLS)
        text += f" {_ratio_text(row['ratios']['derive']):>12} {_ratio_text(row['ratios']['core']):>10}"
        lines.append(text)
        errors += [f"  n = {row['n']}, {CELLS[key][0]}: {cell['error']}"
                   for key, cell in row["cells"].items() if cell["error"]]
    if errors:
        lines += ["", "Errors:", *errors]
    lines += ["", COLUMNS.format(repeat=result["repeat"], cap=result["cap_s"]), ""]

    problems = result["problems"]
    if problems is not None:
        lines.append(f"problems/*.yaml, load_problem + derive, CPU time (target < {PROBLEM_TARGET:g} s each):")
        for row in problems:
            verdict = {True: "PASS", False: "MISS", None: "n/a"}[row["pass"]]
            lines.append(f"  {row['name']:<24} {_cell_text(row, 8)}  {verdict}"
                         + (f"  {row['error']}" if row["error"] else ""))
        lines.append("")
    lines.append("Targets:")
    for target in result["targets"]:
        lines.append(f"  {target['verdict']:<4}  {target['text']}" + (f" ({target['detail']})" if target["detail"]
                                                                       else ""))
    lines += ["", f"Benchmark wall time {result['total_s']:.0f} s. PASS/MISS is information only: "
              "the exit status is always 0."]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only-n", action="append", type=int, metavar="N",
                        help=f"only this number of links (repeatable; default {', '.join(map(str, SIZES))})")
    parser.add_argument("--repeat", type=int, default=DEFAULT_REPEAT, metavar="K",
                        help=f"runs per measurement, the best is reported (default {DEFAULT_REPEAT}); a run "
                             f"slower than {SLOW_RUN:g} s is not repeated")
    parser.add_argument("--large", action="store_true",
                        help=f"also n = {LARGE_N} (issue 33's second size; about a minute per run, the references "
                             "capped)")
    parser.add_argument("--cap", type=float, default=DEFAULT_CAP, metavar="S",
                        help=f"stop a measurement after S seconds of wall time (default {DEFAULT_CAP:g})")
    parser.add_argument("--skip-problems", action="store_true",
                        help="leave out the library derive time of every problems/*.yaml")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)

    if args.child:
        run_child(*args.child)
        return 0
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    if args.cap <= 0:
        parser.error("--cap must be positive")
    if args.only_n and any(n < 1 for n in args.only_n):
        parser.error("--only-n must be at least 1")
    sizes = sorted(set(args.only_n)) if args.only_n else list(SIZES)
    if args.large:
        sizes = sorted({*sizes, LARGE_N})

    quiet = args.json or not sys.stderr.isatty()

    def progress(message: str) -> None:
        if not quiet:
            print(f"  ... {message}", file=sys.stderr, flush=True)

    result = bench(sizes, args.repeat, args.cap, not args.skip_problems, progress)
    print(json.dumps(result, indent=2) if args.json else report(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
