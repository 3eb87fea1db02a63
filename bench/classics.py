#!/usr/bin/env python3
"""Benchmark: every stage finishes or declines at once on the classic problems (issue 28).

For each problem this runs ``load_problem`` + ``derive`` with the default budget in a fresh process and reports
its CPU time (target: under 5 s), whether every stage finished (no stage note of kind "budget": a stage that
spent its share and gave up), and what came out (explicit q̈, the multipliers, the forces of constraint, normal
modes, steady motions). Side by side, in the same run, SymPy's mechanics module builds the same system the way its
documentation does and solves it for q̈ (and λ): ``LagrangesMethod`` for the coupled pendulums and the two-wheeled
cart, ``KanesMethod`` for PyDy's three-coordinate system, each in its own fresh process, CPU time.

Before issue 28 the three classics each spent a stage's whole share: the coupled pendulums 15 s with no normal
modes, PyDy's system 20 s with no q̈, the cart 19 s with no λ.

    .venv/bin/python bench/classics.py                 # the classics (about a minute)
    .venv/bin/python bench/classics.py --all           # and every problems/*.yaml
    .venv/bin/python bench/classics.py --json

The exit status is always 0: this is a benchmark, not a test (``tests/conftest.py`` fails any test whose
derivation has a stage that ran out of its share).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
TARGET = 5.0  # CPU seconds for load_problem + derive
CLASSICS = ("coupled_pendulums", "multidof_holonomic", "differential_drive", "heavy_top",
            "spherical_pendulum_cartesian", "double_pendulum", "triple_pendulum")
CHILD_ENV = {**os.environ, "PYTHONHASHSEED": "0"}
CAP = 300.0  # wall seconds for one fresh process


def _lagsolve(name: str) -> dict[str, Any]:
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    start = time.process_time()
    derivation = derive(load_problem(ROOT / "problems" / f"{name}.yaml"))
    seconds = time.process_time() - start
    notes = derivation.notes
    analysis = derivation.analysis
    linear = analysis.linearization if analysis is not None else None
    return {
        "seconds": seconds,
        "spent": [f"{n.stage}: {n.reason}" for n in notes if n.kind == "budget"],
        "declined": [f"{n.stage}: {n.reason}" for n in notes if n.kind in ("size", "skipped")],
        "explicit": derivation.accelerations is not None,
        "multipliers": bool(derivation.multipliers) if derivation.multipliers is not None else False,
        "modes": bool(linear is not None and linear.modes),
        "steady": analysis is not None and analysis.steady is not None,
    }


def _sympy_coupled_pendulums() -> None:
    from sympy import cos, sin, symbols
    from sympy.physics import mechanics as me

    th1, th2 = me.dynamicsymbols("theta1 theta2")
    m, g, length, k, d = symbols("m g l k d")
    x1, y1 = length * sin(th1), -length * cos(th1)
    x2, y2 = d + length * sin(th2), -length * cos(th2)
    t = me.dynamicsymbols._t
    T = m * (x1.diff(t) ** 2 + y1.diff(t) ** 2 + x2.diff(t) ** 2 + y2.diff(t) ** 2) / 2
    V = m * g * (y1 + y2) + k * ((x2 - x1) - d) ** 2 / 2
    method = me.LagrangesMethod(T - V, [th1, th2])
    method.form_lagranges_equations()
    method.rhs()


def _sympy_pydy() -> None:
    sys.path.insert(0, str(ROOT / "tests"))
    import sympy

    from test_classics import pydy_kane  # PyDy's documented model, built as its documentation does

    _, (_, _, _, rates) = pydy_kane()
    sympy.count_ops(rates)


def _sympy_cart() -> None:
    sys.path.insert(0, str(ROOT / "tests"))
    from test_classics import cart_lagrange  # the cart with LagrangesMethod: frames, bodies, three constraints

    mass, forcing, _ = cart_lagrange()
    mass.LUsolve(forcing)


PEERS = {"coupled_pendulums": ("LagrangesMethod", _sympy_coupled_pendulums),
         "multidof_holonomic": ("KanesMethod", _sympy_pydy),
         "differential_drive": ("LagrangesMethod", _sympy_cart)}


def _child(kind: str, name: str) -> None:
    if kind == "lagsolve":
        print(json.dumps(_lagsolve(name)))
        return
    start = time.process_time()
    PEERS[name][1]()
    print(json.dumps({"seconds": time.process_time() - start}))


def _run(kind: str, name: str) -> dict[str, Any]:
    try:
        done = subprocess.run([sys.executable, __file__, "--child", kind, name], capture_output=True, text=True,
                              timeout=CAP, env=CHILD_ENV, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return {"error": f"over {CAP:g} s of wall time"}
    if done.returncode != 0:
        return {"error": (done.stderr.strip().splitlines() or ["failed"])[-1]}
    result: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--all", action="store_true", help="every problems/*.yaml, not only the classics")
    parser.add_argument("--json", action="store_true", help="the figures as JSON")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(*args.child)
        return
    names = list(CLASSICS)
    if args.all:
        names += sorted(p.stem for p in (ROOT / "problems").glob("*.yaml") if p.stem not in CLASSICS)
    rows = []
    for name in names:
        print(f"  {name} ...", file=sys.stderr, flush=True)
        row = {"name": name, "lagsolve": _run("lagsolve", name)}
        if name in PEERS:
            row["peer"] = {"method": PEERS[name][0], **_run("sympy", name)}
        rows.append(row)
    if args.json:
        print(json.dumps(rows, indent=2))
        return
    print(f"load_problem + derive, CPU s, default budget (target < {TARGET:g} s, no stage out of its share); "
          "SymPy's mechanics module beside it where it solves the same system")
    print(f"{'problem':30} {'lagsolve':>9} {'target':>6} {'complete':>9}  {'q̈':>3} {'λ':>3} {'modes':>5} "
          f"{'steady':>6}  {'SymPy (q̈, λ)':>22}")
    for row in rows:
        ours = row["lagsolve"]
        if "error" in ours:
            print(f"{row['name']:30} error: {ours['error']}")
            continue
        peer = row.get("peer")
        peer_text = ("" if peer is None else f"{peer['method']} error" if "error" in peer
                     else f"{peer['method']} {peer['seconds']:.2f}")
        flag = "PASS" if ours["seconds"] < TARGET else "MISS"
        complete = "yes" if not ours["spent"] else "NO"
        print(f"{row['name']:30} {ours['seconds']:9.2f} {flag:>6} {complete:>9}  "
              f"{'yes' if ours['explicit'] else '-':>3} {'yes' if ours['multipliers'] else '-':>3} "
              f"{'yes' if ours['modes'] else '-':>5} {'yes' if ours['steady'] else '-':>6}  {peer_text:>22}")
        for spent in ours["spent"]:
            print(f"    out of its share: {spent}")


if __name__ == "__main__":
    main()
