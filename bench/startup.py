#!/usr/bin/env python3
"""Benchmark: ``lagsolve derive problems/bead.yaml`` as a whole process (issue 33, target 3: ≤ 1 s wall on the
idle 2-core machine), beside the references of the same run.

Each row is a fresh process, best of ``--repeat``, its wall time and its CPU time (user + system, the process and
the children it waited for, from ``resource.getrusage``):

* **lagsolve derive**: ``lagsolve derive problems/bead.yaml -o TMP`` (load, derive, reports in md/tex/json);
* **lagsolve --help**;
* **python + sympy**: ``python -c "import sympy"``, the floor any SymPy tool starts from;
* **python + sympy + pint**: the libraries lagsolve needs before it derives (a file with units);
* **SymPy LagrangesMethod**: the bead written by hand for ``sympy.physics.mechanics.LagrangesMethod``
  (``hol_coneqs=[y - f(x)]``), ``form_lagranges_equations()`` + ``rhs()`` and ``simplify`` of each result,
  printed: what a user of SymPy's mechanics module runs for the same answers, without reports;

then the target with PASS/MISS (information only: the script always exits 0). The machine's load average is
printed with the figures: on a shared machine the wall clock varies by a factor of up to 2, the CPU time less.
Where the time goes inside ``lagsolve derive`` (the in-process phases, CPU) is printed with ``--phases``.

    .venv/bin/python bench/startup.py
    .venv/bin/python bench/startup.py --repeat 3 --phases --json
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYTHON = sys.executable
LAGSOLVE = str(Path(PYTHON).with_name("lagsolve"))
TARGET = 1.0

LAGRANGES_METHOD = """
import sympy
from sympy.physics.mechanics import LagrangesMethod, Particle, Point, ReferenceFrame, dynamicsymbols
x, y = dynamicsymbols("x y")
xd, yd = dynamicsymbols("x y", 1)
m, g = sympy.symbols("m g", positive=True)
f = sympy.Function("f")
N = ReferenceFrame("N")
P = Point("P")
P.set_vel(N, xd * N.x + yd * N.y)
bead = Particle("bead", P, m)
bead.potential_energy = m * g * y
L = sympy.physics.mechanics.Lagrangian(N, bead)
lm = LagrangesMethod(L, [x, y], hol_coneqs=[y - f(x)], frame=N)
lm.form_lagranges_equations()
print([sympy.simplify(e) for e in lm.rhs()])
"""

PHASES = """
import time, sys
t0 = time.process_time()
out = []
def lap(label):
    global t0
    t = time.process_time(); out.append((label, t - t0)); t0 = t
import lagsolve.cli; lap("import the command line")
from lagsolve.problem.load import load_problem; lap("import SymPy and the loader")
problem = load_problem(sys.argv[1]); lap("parent: load the file (pint for its units)")
from lagsolve.app.pipeline import _warm_derive
_warm_derive(); lap("child: import the mechanics and renderers")
from lagsolve.mechanics.derivation import derive
derivation = derive(problem); lap("child: derive (every stage)")
from lagsolve.render.sections import build
from lagsolve.render.report import render_sections, sections_summary
sections = build(derivation); lap("child: build the sections")
sections_summary(sections); lap("child: terminal summary")
for fmt in ("md", "tex", "json"):
    render_sections(sections, fmt); lap(f"child: render {fmt}")
import json; print(json.dumps(out))
"""


def _run(argv: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds of one fresh process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=ROOT,
                   env={**os.environ, "PYTHONHASHSEED": "0"})
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _best(argv: list[str], repeat: int) -> tuple[float, float]:
    runs = [_run(argv) for _ in range(repeat)]
    return min(w for w, _ in runs), min(c for _, c in runs)


def measure(repeat: int) -> dict[str, tuple[float, float]]:
    with tempfile.TemporaryDirectory() as out:
        rows = {
            "lagsolve derive problems/bead.yaml": [LAGSOLVE, "derive", "problems/bead.yaml", "-o", out],
            "lagsolve --help": [LAGSOLVE, "--help"],
            "python + sympy": [PYTHON, "-c", "import sympy"],
            "python + sympy + pint": [PYTHON, "-c", "import sympy, pint; pint.UnitRegistry()"],
            "SymPy LagrangesMethod (bead, simplified)": [PYTHON, "-c", LAGRANGES_METHOD],
        }
        return {name: _best(argv, repeat) for name, argv in rows.items()}


def phases() -> list[tuple[str, float]]:
    done = subprocess.run([PYTHON, "-c", PHASES, "problems/bead.yaml"], check=True, capture_output=True, text=True,
                          cwd=ROOT, env={**os.environ, "PYTHONHASHSEED": "0"})
    return [tuple(row) for row in json.loads(done.stdout.strip().splitlines()[-1])]  # type: ignore[misc]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="fresh processes per row (the best is shown)")
    parser.add_argument("--phases", action="store_true", help="also the CPU time of each phase, in process")
    parser.add_argument("--json", action="store_true", help="the figures as JSON")
    args = parser.parse_args(argv)
    load = os.getloadavg()[0]
    rows = measure(max(1, args.repeat))
    wall = rows["lagsolve derive problems/bead.yaml"][0]
    verdict = "PASS" if wall <= TARGET else "MISS"
    detail = phases() if args.phases else []
    if args.json:
        print(json.dumps({"load_average": load, "rows": {k: {"wall": w, "cpu": c} for k, (w, c) in rows.items()},
                          "target": TARGET, "verdict": verdict, "phases": dict(detail)}, indent=2))
        return 0
    print(f"start-up, best of {args.repeat} fresh processes (load average {load:.2f} on {os.cpu_count()} cores)")
    print(f"{'':44s} {'wall s':>8s} {'CPU s':>8s}")
    for name, (w, c) in rows.items():
        print(f"{name:44s} {w:8.2f} {c:8.2f}")
    print(f"target: lagsolve derive problems/bead.yaml ≤ {TARGET:g} s wall: {verdict} ({wall:.2f} s)")
    if detail:
        print("\nwhere lagsolve derive's CPU goes (the phases run one after the other in one process here; in the "
              "command\nthe budgeted child imports the mechanics while the parent loads the file):")
        for name, seconds in detail:
            print(f"  {name:45s} {seconds:6.3f}")
        parts = dict(detail)
        path = sum(v for k, v in detail if not k.startswith(("parent:", "child: import")))
        path += max(parts.get("parent: load the file (pint for its units)", 0.0),
                    parts.get("child: import the mechanics and renderers", 0.0))
        print(f"  {'the longer path (what the wall clock sees)':45s} {path:6.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
