#!/usr/bin/env python3
"""Benchmark: ``lagsolve sweep`` against a loop of single runs, for the double pendulum.

Three ways to run N initial conditions (θ1, θ2 on a grid over [0.1, 1.5]², at rest) of
``problems/double_pendulum.yaml`` to t = 5 s, all with the same integrator and tolerances
(DOP853, rtol 1e-10, atol 1e-12: lagsolve's defaults):

* **sweep**: ``lagsolve.sweep(...)`` in this process (W = 0) and on a local Dask cluster of W worker
  processes (W = 1, 2), started beforehand (its start-up is reported apart) and passed as
  ``scheduler``; the sweep is timed from the call to the returned DataFrame (compilation in each
  worker included), and the CPU time of each worker is taken around it;
* **simulate loop**: ``lagsolve.simulate(derivation, t_end=5, initial=...)`` run after run, the
  derivation made once beforehand (the loop a user writes); a sample of S runs from the same
  inputs is timed and the rate extrapolated per run;
* **solve_ivp loop**: plain ``scipy.integrate.solve_ivp`` per run with a right-hand side made by
  ``sympy.lambdify(cse=True)`` of the mass matrix and forcing of SymPy's ``LagrangesMethod``
  (``np.linalg.solve`` per evaluation), the same S runs; building the function is not timed.

The sample runs are also checked against the sweep's rows (final states within 1e-7). The sweep
takes its default engine: in process, 1000 runs or more run on the compiled path (Numba; see
bench/sweep_fast.py), fewer on the batched NumPy path; on the Dask workers the same rule applies.
Targets (issue 18): sweep ≥ 20× the simulate loop, ≥ 5× the solve_ivp loop (per run), and a
near-linear speed-up from 1 to 2 workers (≥ 1.6×). Each ratio is given by wall clock and by CPU
time (runs per CPU second; for the workers, the 1-worker CPU over the busiest worker's CPU with
2, the speed-up the split allows on two free cores): on a machine shared with other work the wall
clock, and the worker speed-up above all, depends on the load. PASS/MISS (either clock) is
information only: the script always exits 0.

    .venv/bin/python bench/sweep.py                        # 10⁴ runs (a few minutes)
    .venv/bin/python bench/sweep.py --runs 400 --sample 5 --workers 1 --json
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Any

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
PROBLEM = ROOT / "problems" / "double_pendulum.yaml"
METHOD, RTOL, ATOL = "DOP853", 1e-10, 1e-12
TARGETS = {"simulate": 20.0, "solve_ivp": 5.0, "workers": 1.6}
VALUES = {"m": 1.0, "g": 9.81, "l": 1.0}


def grid(runs: int) -> tuple[np.ndarray, np.ndarray]:
    """About ``runs`` points on a square grid over [0.1, 1.5]² (exactly side² points)."""
    side = max(1, round(math.sqrt(runs)))
    a, b = np.meshgrid(np.linspace(0.1, 1.5, side), np.linspace(0.1, 1.5, side), indexing="ij")
    return a.ravel(), b.ravel()


def lagranges_rhs() -> Any:
    """The double pendulum written for SymPy's LagrangesMethod; rhs(t, y) with y = (θ1, θ2, θ̇1, θ̇2)."""
    import sympy
    from sympy.physics import mechanics as me

    q1, q2 = me.dynamicsymbols("q1 q2")
    u1, u2 = me.dynamicsymbols("q1 q2", 1)
    m, g, l = sympy.symbols("m g l", positive=True)  # noqa: E741 - the rod length, as in the problem file
    frame = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(frame, 0)
    upper = origin.locatenew("P1", l * sympy.sin(q1) * frame.x - l * sympy.cos(q1) * frame.y)
    lower = upper.locatenew("P2", l * sympy.sin(q2) * frame.x - l * sympy.cos(q2) * frame.y)
    upper.set_vel(frame, upper.pos_from(origin).dt(frame))
    lower.set_vel(frame, lower.pos_from(origin).dt(frame))
    particles = [me.Particle("A", upper, m), me.Particle("B", lower, m)]
    for p in particles:
        p.potential_energy = m * g * p.point.pos_from(origin).dot(frame.y)
    method = me.LagrangesMethod(me.Lagrangian(frame, *particles), [q1, q2])
    method.form_lagranges_equations()
    symbols = sympy.symbols("y0:4")
    states = dict(zip([q1, q2, u1, u2], symbols, strict=True))
    mass = method.mass_matrix_full.subs(states).subs({m: VALUES["m"], g: VALUES["g"], l: VALUES["l"]})
    forcing = method.forcing_full.subs(states).subs({m: VALUES["m"], g: VALUES["g"], l: VALUES["l"]})
    evaluate = sympy.lambdify([symbols], [mass, forcing], cse=True, modules="numpy")

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        matrix, force = evaluate(y)
        return np.linalg.solve(np.asarray(matrix, dtype=float), np.asarray(force, dtype=float).ravel())

    return rhs


def time_simulate(theta1: np.ndarray, theta2: np.ndarray, t_end: float) -> tuple[dict[str, float], np.ndarray]:
    import lagsolve

    derivation = lagsolve.derive(PROBLEM)
    finals = []
    start, cpu = time.perf_counter(), time.process_time()
    for a, b in zip(theta1, theta2, strict=True):
        run = lagsolve.simulate(derivation, t_end=t_end, initial={"theta1": a, "theta2": b, "theta1_dot": 0,
                                                                  "theta2_dot": 0}, method=METHOD, rtol=RTOL,
                                atol=ATOL)
        finals.append(np.concatenate([run.q[-1], run.qd[-1]]))
    return _loop(len(theta1), time.perf_counter() - start, time.process_time() - cpu), np.array(finals)


def time_solve_ivp(theta1: np.ndarray, theta2: np.ndarray, t_end: float) -> tuple[dict[str, float], np.ndarray]:
    from scipy.integrate import solve_ivp

    rhs = lagranges_rhs()
    finals = []
    start, cpu = time.perf_counter(), time.process_time()
    for a, b in zip(theta1, theta2, strict=True):
        done = solve_ivp(rhs, (0.0, t_end), [a, b, 0.0, 0.0], method=METHOD, rtol=RTOL, atol=ATOL)
        finals.append(done.y[:, -1])
    return _loop(len(theta1), time.perf_counter() - start, time.process_time() - cpu), np.array(finals)


def _loop(runs: int, wall: float, cpu: float) -> dict[str, float]:
    return {"runs_per_s": runs / wall, "runs_per_cpu_s": runs / cpu}


def time_sweep(theta1: np.ndarray, theta2: np.ndarray, t_end: float, workers: int) -> tuple[dict[str, Any], Any]:
    """The sweep in this process (0) or on a local cluster of ``workers`` processes started beforehand
    (its start-up timed apart); CPU time is measured in each worker, around the sweep."""
    from lagsolve.sweep.api import sweep

    runs = len(theta1)
    options = {"t_end": t_end, "method": METHOD, "rtol": RTOL, "atol": ATOL, **_inputs(theta1, theta2)}
    if workers == 0:
        start, cpu = time.perf_counter(), time.process_time()
        frame = sweep(PROBLEM, **options)
        wall, used = time.perf_counter() - start, time.process_time() - cpu
        return {"seconds": wall, "runs_per_s": runs / wall, "runs_per_cpu_s": runs / used,
                "failed": int((frame["status"] == "failed").sum())}, frame
    import logging

    from distributed import Client, LocalCluster

    start = time.perf_counter()
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        startup = time.perf_counter() - start
        before = client.run(time.process_time)
        start = time.perf_counter()
        frame = sweep(PROBLEM, workers=workers, scheduler=cluster.scheduler_address, **options)
        wall = time.perf_counter() - start
        after = client.run(time.process_time)
    cpu = [after[key] - before[key] for key in before]
    return {"seconds": wall, "startup_seconds": startup, "runs_per_s": runs / wall,
            "runs_per_cpu_s": runs / sum(cpu), "worker_cpu_seconds": sorted(cpu),
            "failed": int((frame["status"] == "failed").sum())}, frame


def _inputs(theta1: np.ndarray, theta2: np.ndarray) -> dict[str, Any]:
    """The grid as the API's grid argument (the product of the two axes, in the same order)."""
    return {"grid": {"theta1": np.unique(theta1), "theta2": np.unique(theta2)}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=10_000, help="runs of the sweep (rounded to a square grid)")
    parser.add_argument("--sample", type=int, default=50, help="runs timed in each single-run loop")
    parser.add_argument("--t-end", type=float, default=5.0)
    parser.add_argument("--workers", default="1,2", help="worker counts, comma-separated (0: in process)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    theta1, theta2 = grid(args.runs)
    runs = len(theta1)
    pick = np.linspace(0, runs - 1, min(args.sample, runs)).round().astype(int)
    result: dict[str, Any] = {"problem": "double_pendulum", "runs": runs, "sample": len(pick), "t_end": args.t_end,
                              "method": METHOD, "rtol": RTOL, "atol": ATOL, "cpus": os.cpu_count(),
                              "load": list(os.getloadavg()), "sweep": {}}
    reference = None
    for workers in [int(w) for w in args.workers.split(",")]:
        figures, frame = time_sweep(theta1, theta2, args.t_end, workers)
        result["sweep"][str(workers)] = figures
        reference = frame
    assert reference is not None
    ours = reference[["final_theta1", "final_theta2", "final_theta1_dot", "final_theta2_dot"]].to_numpy()[pick]
    for key, timer in (("simulate", time_simulate), ("solve_ivp", time_solve_ivp)):
        figures, finals = timer(theta1[pick], theta2[pick], args.t_end)
        result[key] = {**figures, "max_difference": float(np.max(np.abs(finals - ours)))}
    sweeps = result["sweep"]
    best = max(v["runs_per_s"] for v in sweeps.values())
    best_cpu = max(v["runs_per_cpu_s"] for v in sweeps.values())
    result["ratios"] = {key: best / result[key]["runs_per_s"] for key in ("simulate", "solve_ivp")}
    result["cpu_ratios"] = {key: best_cpu / result[key]["runs_per_cpu_s"] for key in ("simulate", "solve_ivp")}
    if "1" in sweeps and "2" in sweeps:
        result["ratios"]["workers"] = sweeps["2"]["runs_per_s"] / sweeps["1"]["runs_per_s"]
        # on two free cores the sweep lasts as long as its busiest worker: the speed-up the split allows
        one, two = sweeps["1"]["worker_cpu_seconds"], sweeps["2"]["worker_cpu_seconds"]
        result["cpu_ratios"]["workers"] = sum(one) / max(two)
    result["targets"] = {key: {"target": TARGETS[key], "ratio": ratio, "cpu_ratio": result["cpu_ratios"][key],
                               "met": max(ratio, result["cpu_ratios"][key]) >= TARGETS[key]}
                         for key, ratio in result["ratios"].items()}
    if args.json:
        print(json.dumps(result, indent=2))
        return
    print(f"double pendulum, {runs} runs to t = {args.t_end:g} s, {METHOD} rtol {RTOL:g} atol {ATOL:g}; "
          f"{result['cpus']} CPUs, load {result['load'][0]:.1f}")
    print(f"{'route':<28}{'runs/s (wall)':>14}{'runs per CPU s':>16}")
    for workers, figures in result["sweep"].items():
        label = "sweep, in process" if workers == "0" else f"sweep, {workers} worker{'s' if workers != '1' else ''}"
        extra = f"{figures['seconds']:.1f} s"
        if "startup_seconds" in figures:
            extra += f"; cluster start {figures['startup_seconds']:.1f} s; worker CPU " + ", ".join(
                f"{c:.1f}" for c in figures["worker_cpu_seconds"]) + " s"
        print(f"{label:<28}{figures['runs_per_s']:>14.1f}{figures['runs_per_cpu_s']:>16.1f}   ({extra})")
    for key, label in (("simulate", "simulate loop"), ("solve_ivp", "solve_ivp loop (lambdify)")):
        figures = result[key]
        print(f"{label:<28}{figures['runs_per_s']:>14.2f}{figures['runs_per_cpu_s']:>16.2f}   ({len(pick)} runs "
              f"timed; final states within {figures['max_difference']:.1e} of the sweep's)")
    for key, target in result["targets"].items():
        verdict = "PASS" if target["met"] else "MISS"
        what = {"simulate": "sweep / simulate loop", "solve_ivp": "sweep / solve_ivp loop",
                "workers": "2 workers / 1 worker"}[key]
        print(f"{what:<28}{target['ratio']:>13.1f}x{target['cpu_ratio']:>15.1f}x  target >= {target['target']:g}x"
              f"  {verdict}")

if __name__ == "__main__":
    sys.exit(main())
