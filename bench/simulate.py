#!/usr/bin/env python3
"""Benchmark: lagsolve's compiled right-hand side against SymPy's LagrangesMethod + lambdify.

For the seed problems and a planar n-link pendulum (n = 2, 4, 6) this measures the time
to build the numeric callables (``load`` + ``matrix_form(display=False)`` + ``bind``, as
``lagsolve simulate`` does), the right-hand-side evaluations per second of ``system.solve``
at a fixed state (SymEngine's LLVM backend, the
default, and the plain ``lambdify`` backend), and the wall time of a 10 s integration; next
to them the same system written by hand for ``sympy.physics.mechanics.LagrangesMethod``,
``rhs = LM.rhs()`` and ``f = lambdify((t, q..., qd..., params...), rhs, cse=True)``: its
build time and the evaluations per second of ``f`` at the same state. Targets (issue 4) at
n = 6: at least 4x the baseline's evaluations per second, and building in under 1 s.

Every build is timed in a fresh Python process, so SymPy's cache never helps; times are
taken inside that process with ``time.perf_counter`` and leave out interpreter start-up
and imports. The report prints PASS/MISS against each target but the exit status is
always 0: this is a benchmark, not a test.

    .venv/bin/python bench/simulate.py                  # the table (about two minutes on 2 idle cores)
    .venv/bin/python bench/simulate.py --repeat 1 --only pendulum2 --json
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import json
import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
from pendulum import pendulum_yaml as shared_pendulum  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SEEDS = ("bead", "rotating_tube", "knife_edge", "hole_table")
PENDULUMS = (2, 4, 6)
NAMES = (*SEEDS, *(f"pendulum{n}" for n in PENDULUMS))
TARGET_PROBLEM = "pendulum6"
RATIO_TARGET = 4.0  # lagsolve's evaluations per second over the baseline's, at n = 6
BUILD_TARGET = 1.0  # seconds for load + matrix_form + bind, at n = 6
T_END = 10.0  # seconds of simulated time for the integration column
SAMPLES = 1001
RATE_BUDGET = 0.3  # seconds spent measuring one evaluation rate (best of ~20 ms batches)
BASELINE_TIMEOUT = 60.0  # seconds for the whole baseline build in its child
SLOW_RUN = 15.0  # a child run longer than this is not repeated (its figures are from one run)
CHILD_TIMEOUT = 300.0  # backstop for a lagsolve child
CHECK_TOLERANCE = 1e-8
# a fixed hash seed makes SymPy's term order, and so its run time, repeatable between runs
CHILD_ENV = {**os.environ, "PYTHONHASHSEED": "0"}
# the baseline leaves out what LagrangesMethod cannot express; the check sets these values in lagsolve too
BASELINE_OVERRIDES: dict[str, dict[str, float]] = {"rotating_tube": {"mu": 0.0}}
BASELINE_NOTES = {
    "bead": "f(x) = x**2/2 substituted before forming the equations",
    "rotating_tube": "no friction in the baseline (the check sets mu = 0 in lagsolve)",
    "knife_edge": "the skate as nonhol_coneqs",
    "hole_table": "the string as hol_coneqs",
}

COLUMNS = """\
Columns (best of {repeat} run(s); builds each in a fresh Python process with a cold SymPy cache,
times leave out interpreter start-up and imports):
  build        lagsolve: load (YAML -> Problem) + matrix_form(display=False) + bind (compiling every
               callable the integrator needs, not only the right-hand side); (load form bind) split it
  rhs/s        evaluations per second of system.solve(t, q, qd) at the problem's initial state:
               compiled M, F, A, beta (SymEngine LLVM) + the LAPACK solve of the augmented system
  (python)     the same with compile_state_function(..., backend="python") (sympy.lambdify with
               cse=True and the math module), bound in the same process after the LLVM build
  LM build     sympy.physics.mechanics.LagrangesMethod written by hand: building L +
               form_lagranges_equations() + rhs() + lambdify((t, q, qd, params), rhs, cse=True)
  LM rhs/s     evaluations per second of that lambdified function at the same state
  ratio        rhs/s over LM rhs/s
  10 s run     wall time of integrate_motion(system, q0, qd0, 10.0) at default tolerances
               (DOP853, rtol 1e-10, atol 1e-12, 1001 samples, projection onto the constraints)
  steps/evals  accepted steps and right-hand-side evaluations of that run; (in rhs) is the share
               of the run those evaluations account for at the measured rhs/s
  check        lagsolve's and the baseline's accelerations agree at the state (relative {tol:.0e})"""


# --------------------------------------------------------------------------- problems


def pendulum_yaml(n: int) -> str:
    """A planar n-link pendulum (:func:`pendulum.pendulum_yaml`)."""
    return shared_pendulum(n, T_END, "bench/simulate.py")


def _pendulum_size(name: str) -> int | None:
    found = re.fullmatch(r"pendulum([1-9]\d*)", name)
    return int(found.group(1)) if found else None


def _problem_name(value: str) -> str:
    """argparse type for --only: a seed problem or pendulumN."""
    if value in SEEDS or _pendulum_size(value) is not None:
        return value
    raise argparse.ArgumentTypeError(f"unknown problem {value!r} (choose from {', '.join(NAMES)} or pendulumN)")


# --------------------------------------------------------------------------- children


def _rate(call: Callable[[], Any], budget: float = RATE_BUDGET) -> float:
    """Calls per second: the best of batches of about 20 ms each, for ``budget`` seconds."""
    call()
    batch = 1
    while True:
        start = time.perf_counter()
        for _ in range(batch):
            call()
        spent = time.perf_counter() - start
        if spent >= 0.02:
            break
        batch *= 2
    best = batch / spent
    end = time.perf_counter() + budget
    while time.perf_counter() < end:
        start = time.perf_counter()
        for _ in range(batch):
            call()
        best = max(best, batch / (time.perf_counter() - start))
    return best


def child_lagsolve(name: str) -> dict[str, Any]:
    begin = time.perf_counter()

    import lagsolve.numeric.system as system_module
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.numeric.compile import compile_state_function
    from lagsolve.numeric.initial import complete_initial
    from lagsolve.numeric.integrate import integrate_motion
    from lagsolve.problem.load import load_problem, load_text

    with contextlib.suppress(ImportError):  # the LLVM backend imports SymEngine on first use: not building
        import symengine  # noqa: F401
    imported = time.perf_counter()

    size = _pendulum_size(name)
    start = time.perf_counter()
    problem = load_text(pendulum_yaml(size), f"<{name}>") if size else load_problem(ROOT / "problems" / f"{name}.yaml")
    loaded = time.perf_counter()
    form = matrix_form(problem, display=False)
    formed = time.perf_counter()
    system = system_module.bind(form)
    bound = time.perf_counter()

    given = problem.simulation.initial if problem.simulation else {}
    q, qd = complete_initial(system, given, problem.source)
    rate = _rate(lambda: system.solve(0.0, q, qd))

    # the accelerations for the check, with the values the baseline assumes
    saved = system.parameters.copy()
    for key, value in BASELINE_OVERRIDES.get(name, {}).items():
        system.parameters[system.parameter_names.index(key)] = value
    check_qdd = system.solve(0.0, q, qd)[0]
    system.parameters[:] = saved

    figures: dict[str, Any] = {
        "seconds": bound - start, "load": loaded - start, "form": formed - loaded, "bind": bound - formed,
        "import": imported - begin, "rate": rate,
        "n": system.n, "m": system.m,
        "state": {"q": q.tolist(), "qd": qd.tolist(),
                  "values": {**dict(zip(system.parameter_names, saved.tolist(), strict=True)),
                             **BASELINE_OVERRIDES.get(name, {})}},
        "qdd": check_qdd.tolist(),
    }

    system.evaluations[0] = 0
    start = time.perf_counter()
    try:
        run = integrate_motion(system, q, qd, T_END, samples=SAMPLES)
    except Exception as error:  # noqa: BLE001 - a benchmark reports every failure and goes on
        figures["integrate_error"] = f"{type(error).__name__}: {error}"
    else:
        figures["integrate"] = time.perf_counter() - start
        figures["steps"] = run.stats["steps"]
        figures["evaluations"] = run.stats["evaluations"]

    # the plain-Python backend, in this process after the LLVM build (so with a warm SymPy cache)
    system_module.compile_state_function = functools.partial(compile_state_function, backend="python")
    start = time.perf_counter()
    plain = system_module.bind(form)
    figures["python_bind"] = time.perf_counter() - start
    figures["python_rate"] = _rate(lambda: plain.solve(0.0, q, qd))
    return figures


def _lm_pendulum(sp: Any, me: Any, n: int) -> dict[str, Any]:
    q = [me.dynamicsymbols(f"th{i}") for i in range(1, n + 1)]
    m, l, g = sp.symbols("m l g")  # noqa: E741 - the problem's name for the rod length
    t = me.dynamicsymbols._t
    x = y = sp.Integer(0)
    lagrangian = sp.Integer(0)
    for th in q:
        x, y = x + l * sp.sin(th), y - l * sp.cos(th)
        lagrangian += m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y
    return {"lm": me.LagrangesMethod(lagrangian, q), "parameters": [m, l, g]}


def _lm_bead(sp: Any, me: Any) -> dict[str, Any]:
    """Bead on the wire y = f(x) with f(x) = x**2/2: a holonomic constraint."""
    x, y = me.dynamicsymbols("x y")
    m, g = sp.symbols("m g")
    t = me.dynamicsymbols._t
    lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y
    return {"lm": me.LagrangesMethod(lagrangian, [x, y], hol_coneqs=[y - x**2 / 2]), "parameters": [m, g]}


def _lm_rotating_tube(sp: Any, me: Any) -> dict[str, Any]:
    """Particle in a tube turning at rate Omega, spherical coordinates, nonholonomic constraints
    theta_dot = 0 and phi_dot - Omega = 0; no friction (LagrangesMethod cannot couple it to N)."""
    r, th, ph = me.dynamicsymbols("r theta phi")
    m, g, om, mu = sp.symbols("m g Omega mu")
    t = me.dynamicsymbols._t
    rd, thd, phd = r.diff(t), th.diff(t), ph.diff(t)
    kinetic = m * (rd**2 + r**2 * thd**2 + r**2 * sp.sin(th) ** 2 * phd**2) / 2
    lagrangian = kinetic - m * g * r * sp.cos(th)
    lm = me.LagrangesMethod(lagrangian, [r, th, ph], nonhol_coneqs=[thd, phd - om])
    return {"lm": lm, "parameters": [m, g, om, mu]}


def _lm_knife_edge(sp: Any, me: Any) -> dict[str, Any]:
    """Dumbbell with a knife edge under particle 1: one nonholonomic constraint."""
    x, y, th = me.dynamicsymbols("x y theta")
    m, l = sp.symbols("m l")  # noqa: E741
    t = me.dynamicsymbols._t
    x2, y2 = x + l * sp.cos(th), y + l * sp.sin(th)
    kinetic = m * (x.diff(t) ** 2 + y.diff(t) ** 2 + x2.diff(t) ** 2 + y2.diff(t) ** 2) / 2
    skate = -sp.sin(th) * x.diff(t) + sp.cos(th) * y.diff(t)
    return {"lm": me.LagrangesMethod(kinetic, [x, y, th], nonhol_coneqs=[skate]), "parameters": [m, l]}


def _lm_hole_table(sp: Any, me: Any) -> dict[str, Any]:
    """Two masses joined through a hole: the string is the holonomic constraint r - z - l."""
    r, th, z = me.dynamicsymbols("r theta z")
    m1, m2, g, l = sp.symbols("m1 m2 g l")  # noqa: E741
    t = me.dynamicsymbols._t
    kinetic = m1 * (r.diff(t) ** 2 + r**2 * th.diff(t) ** 2) / 2 + m2 * z.diff(t) ** 2 / 2
    lm = me.LagrangesMethod(kinetic - m2 * g * z, [r, th, z], hol_coneqs=[r - z - l])
    return {"lm": lm, "parameters": [m1, m2, g, l]}


LM_BUILDERS: dict[str, Callable[[Any, Any], dict[str, Any]]] = {
    "bead": _lm_bead,
    "rotating_tube": _lm_rotating_tube,
    "knife_edge": _lm_knife_edge,
    "hole_table": _lm_hole_table,
}


class _Timeout(Exception):
    pass


def _on_alarm(signum: int, frame: Any) -> None:
    raise _Timeout


def child_lm(name: str, state_text: str, timeout: float) -> dict[str, Any]:
    begin = time.perf_counter()
    import numpy as np
    import sympy as sp
    import sympy.physics.mechanics as me

    imported = time.perf_counter()
    size = _pendulum_size(name)
    stage = "building L"
    signal.signal(signal.SIGALRM, _on_alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    start = time.perf_counter()
    marks: dict[str, float] = {}
    try:
        built = _lm_pendulum(sp, me, size) if size else LM_BUILDERS[name](sp, me)
        lm = built["lm"]
        stage = "form_lagranges_equations"
        lm.form_lagranges_equations()
        marks["eqs"] = time.perf_counter() - start
        stage = "rhs"
        rhs = lm.rhs()
        marks["rhs"] = time.perf_counter() - start - marks["eqs"]
        stage = "lambdify"
        t = me.dynamicsymbols._t
        q = list(lm.q)
        qd = [c.diff(t) for c in q]
        f = sp.lambdify((t, *q, *qd, *built["parameters"]), rhs, cse=True)
        end = time.perf_counter()
        marks["lambdify"] = end - start - marks["eqs"] - marks["rhs"]
    except _Timeout:
        return {"timed_out": True, "stage": stage, "elapsed": time.perf_counter() - start, **marks,
                "import": imported - begin}
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)

    n = len(q)
    state = json.loads(state_text) if state_text else {}
    q0 = state.get("q", [0.5] * n)
    qd0 = state.get("qd", [0.1] * n)
    values = state.get("values", {})
    arguments = (0.0, *q0, *qd0, *(values.get(str(p), 1.0) for p in built["parameters"]))
    rate = _rate(lambda: f(*arguments))
    out = np.asarray(f(*arguments), dtype=float).ravel()
    return {"seconds": end - start, **marks, "import": imported - begin, "rate": rate,
            "qdd": out[n: 2 * n].tolist()}


# --------------------------------------------------------------------------- parent


def _child(args: list[str], timeout: float) -> dict[str, Any]:
    """One run in a fresh interpreter; the child prints its figures as JSON on its last line."""
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", *args]
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=CHILD_ENV,
                              timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return {"error": f"killed after {timeout:.0f} s", "wall": time.perf_counter() - start}
    wall = time.perf_counter() - start
    if done.returncode != 0:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"error": f"exit {done.returncode}: {tail}", "wall": wall}
    return {**json.loads(done.stdout.strip().splitlines()[-1]), "wall": wall}


def _runs(args: list[str], repeat: int, timeout: float, label: str,
          progress: Callable[[str], None]) -> list[dict[str, Any]]:
    """Up to ``repeat`` runs; a run that fails, times out or is slower than SLOW_RUN is not repeated."""
    runs: list[dict[str, Any]] = []
    for i in range(repeat):
        progress(f"{label}: run {i + 1}/{repeat}")
        run = _child(args, timeout)
        runs.append(run)
        if "error" in run or run.get("timed_out") or run["wall"] > SLOW_RUN:
            break
    return runs


def _best(runs: list[dict[str, Any]], key: str, better: Callable[..., Any]) -> Any:
    values = [r[key] for r in runs if isinstance(r.get(key), (int, float))]
    return better(values) if values else None


def _check(ours: list[float] | None, theirs: list[float] | None) -> tuple[bool | None, str]:
    if ours is None or theirs is None:
        return None, "not compared"
    if len(ours) != len(theirs):
        return False, f"sizes differ ({len(ours)} vs {len(theirs)})"
    worst = max((abs(a - b) / (1.0 + abs(a)) for a, b in zip(ours, theirs, strict=True)), default=0.0)
    if worst != worst or worst > CHECK_TOLERANCE:  # NaN or too far
        return False, f"differ (relative {worst:.1e})"
    return True, "agree"


def bench(only: list[str] | None, repeat: int, baseline_timeout: float,
          progress: Callable[[str], None]) -> dict[str, Any]:
    begin = time.perf_counter()
    rows: list[dict[str, Any]] = []
    for name in only or NAMES:
        ours_runs = _runs(["lagsolve", name], repeat, CHILD_TIMEOUT, f"{name} lagsolve", progress)
        good = [r for r in ours_runs if "error" not in r]
        state = json.dumps(good[0]["state"]) if good else ""
        lm_runs = _runs(["lm", name, state, str(baseline_timeout)], repeat, baseline_timeout + 60.0,
                        f"{name} baseline", progress)
        lm_good = [r for r in lm_runs if "error" not in r and not r.get("timed_out")]
        rate = _best(ours_runs, "rate", max)
        lm_rate = _best(lm_good, "rate", max)
        integrate = _best(ours_runs, "integrate", min)
        fastest = min((r for r in good if "integrate" in r), key=lambda r: r["integrate"], default=None)
        timed_out = next((r for r in lm_runs if r.get("timed_out")), None)
        row: dict[str, Any] = {
            "name": name,
            "n": good[0]["n"] if good else None,
            "constraints": good[0]["m"] if good else None,
            "build_s": _best(ours_runs, "seconds", min),
            "load_s": _best(ours_runs, "load", min),
            "form_s": _best(ours_runs, "form", min),
            "bind_s": _best(ours_runs, "bind", min),
            "import_s": _best(ours_runs, "import", min),
            "rhs_per_s": rate,
            "python_rhs_per_s": _best(ours_runs, "python_rate", max),
            "python_bind_s": _best(ours_runs, "python_bind", min),
            "integrate_s": integrate,
            "steps": fastest["steps"] if fastest else None,
            "evaluations": fastest["evaluations"] if fastest else None,
            "rhs_share": (fastest["evaluations"] / rate / integrate) if fastest and rate else None,
            "lm_build_s": _best(lm_good, "seconds", min),
            "lm_eqs_s": _best(lm_good, "eqs", min),
            "lm_rhs_s": _best(lm_good, "rhs", min),
            "lm_lambdify_s": _best(lm_good, "lambdify", min),
            "lm_import_s": _best(lm_runs, "import", min),
            "lm_rhs_per_s": lm_rate,
            "lm_timed_out": None if timed_out is None else {
                "stage": timed_out["stage"], "after_s": timed_out["elapsed"], "timeout_s": baseline_timeout},
            "ratio": rate / lm_rate if rate and lm_rate else None,
            "baseline_note": BASELINE_NOTES.get(name, ""),
            "runs": len(ours_runs),
            "lm_runs": len(lm_runs),
            "errors": sorted({r["error"] for r in ours_runs + lm_runs if "error" in r}
                             | {r["integrate_error"] for r in ours_runs if "integrate_error" in r}),
        }
        row["agree"], row["check"] = _check(good[0]["qdd"] if good else None,
                                            lm_good[0]["qdd"] if lm_good else None)
        if timed_out is not None:
            row["check"] = "baseline timed out"
        rows.append(row)

    targets: dict[str, Any] = {"problem": TARGET_PROBLEM, "ratio_target": RATIO_TARGET,
                               "build_target_s": BUILD_TARGET}
    target_row = next((r for r in rows if r["name"] == TARGET_PROBLEM), None)
    if target_row is not None:
        ratio, build = target_row["ratio"], target_row["build_s"]
        targets["ratio"] = ratio
        targets["ratio_pass"] = None if ratio is None else ratio >= RATIO_TARGET
        targets["build_s"] = build
        targets["build_pass"] = None if build is None else build < BUILD_TARGET
    return {
        "repeat": repeat,
        "python": sys.version.split()[0],
        "versions": _versions(),
        "t_end": T_END,
        "samples": SAMPLES,
        "baseline_timeout_s": baseline_timeout,
        "problems": rows,
        "targets": targets,
        "total_s": time.perf_counter() - begin,
    }


def _versions() -> dict[str, str]:
    code = ("import importlib.metadata as m\nfor p in ('sympy', 'symengine', 'numpy', 'scipy'):\n"
            "    try: print(p, m.version(p))\n    except m.PackageNotFoundError: print(p, '-')")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    return dict(line.split(" ", 1) for line in done.stdout.splitlines())


def _s(value: float | None, width: int = 7) -> str:
    return f"{'-':>{width}}" if value is None else f"{value:{width - 1}.2f}s"


def _r(value: float | None, width: int = 8) -> str:
    return f"{'-':>{width}}" if value is None else f"{value:{width},.0f}"


def _verdict(passed: bool | None) -> str:
    return "n/a" if passed is None else ("PASS" if passed else "MISS")


def report(result: dict[str, Any]) -> str:
    versions = result["versions"]
    lines = [
        f"lagsolve simulation benchmark (Python {result['python']}, SymPy {versions.get('sympy', '?')}, "
        f"SymEngine {versions.get('symengine', '?')}, NumPy {versions.get('numpy', '?')}, "
        f"SciPy {versions.get('scipy', '?')})",
        "",
        f"{'problem':<14} {'n':>2} {'build':>7} {'(load':>7} {'form':>6} {'bind)':>6} {'rhs/s':>8} "
        f"{'(python)':>8} {'LM build':>8} {'LM rhs/s':>8} {'ratio':>6} {'10 s run':>8} "
        f"{'steps/evals':>12} {'(in rhs)':>8}  check",
    ]
    for row in result["problems"]:
        ratio = "-" if row["ratio"] is None else f"{row['ratio']:.1f}x"
        lm_build = _s(row["lm_build_s"], 8)
        if row["lm_timed_out"]:
            lm_build = f"{'>' + format(row['lm_timed_out']['timeout_s'], '.0f') + 's':>8}"
        steps = "-" if row["steps"] is None else f"{row['steps']}/{row['evaluations']}"
        share = "-" if row["rhs_share"] is None else f"{100 * row['rhs_share']:.0f}%"
        n = "-" if row["n"] is None else str(row["n"])
        lines.append(
            f"{row['name']:<14} {n:>2} {_s(row['build_s'])} {_s(row['load_s'])} {_s(row['form_s'], 6)} "
            f"{_s(row['bind_s'], 6)} {_r(row['rhs_per_s'])} {_r(row['python_rhs_per_s'])} {lm_build} "
            f"{_r(row['lm_rhs_per_s'])} {ratio:>6} {_s(row['integrate_s'], 8)} {steps:>12} {share:>8}  "
            f"{row['check']}"
        )
        if row["lm_timed_out"]:
            lost = row["lm_timed_out"]
            lines.append(f"{'':<14} baseline timed out after {lost['after_s']:.0f} s (in {lost['stage']})")
        for error in row["errors"]:
            lines.append(f"{'':<14} error: {error}")
    lines += ["", COLUMNS.format(repeat=result["repeat"], tol=CHECK_TOLERANCE), ""]
    notes = [(row["name"], row["baseline_note"]) for row in result["problems"] if row["baseline_note"]]
    if notes:
        lines.append("Baseline notes:")
        lines += [f"  {name:<14} {note}" for name, note in notes]
        lines.append("")
    split = [row for row in result["problems"] if row["lm_build_s"] is not None]
    if split:
        lines.append("Baseline build split (form_lagranges_equations / rhs / lambdify):")
        lines += [f"  {row['name']:<14} {_s(row['lm_eqs_s'])} {_s(row['lm_rhs_s'])} {_s(row['lm_lambdify_s'])}"
                  for row in split]
        lines.append("")
    targets = result["targets"]
    if "ratio" in targets:
        ratio = "-" if targets["ratio"] is None else f"{targets['ratio']:.1f}x"
        lines += [
            f"Targets ({targets['problem']}):",
            f"  evaluations per second over the baseline  {ratio:>7}  target >= {targets['ratio_target']:.0f}x  "
            f"{_verdict(targets['ratio_pass'])}",
            f"  building the callables                    {_s(targets['build_s'])}  target < "
            f"{targets['build_target_s']:.0f} s  {_verdict(targets['build_pass'])}",
            "",
        ]
    lines.append(f"Benchmark wall time {result['total_s']:.1f}s. PASS/MISS is information only: "
                 "the exit status is always 0.")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3, metavar="N",
                        help="runs per problem and method; the best is reported (default 3)")
    parser.add_argument("--only", action="append", type=_problem_name, metavar="NAME",
                        help=f"only this problem (repeatable): {', '.join(NAMES)} or pendulumN")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    parser.add_argument("--baseline-timeout", type=float, default=BASELINE_TIMEOUT, metavar="S",
                        help=f"give up on a baseline build after S seconds (default {BASELINE_TIMEOUT:.0f})")
    parser.add_argument("--child", nargs="+", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)

    if args.child:
        kind, name, *rest = args.child
        figures = child_lagsolve(name) if kind == "lagsolve" else child_lm(name, rest[0], float(rest[1]))
        print(json.dumps(figures))
        return 0
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    if args.baseline_timeout <= 0:
        parser.error("--baseline-timeout must be positive")

    quiet = args.json or not sys.stderr.isatty()

    def progress(message: str) -> None:
        if not quiet:
            print(f"  ... {message}", file=sys.stderr, flush=True)

    result = bench(args.only, args.repeat, args.baseline_timeout, progress)
    print(json.dumps(result, indent=2) if args.json else report(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
