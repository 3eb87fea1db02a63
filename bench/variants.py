#!/usr/bin/env python3
"""Benchmark: ``lagsolve variants``, generation time per verified variant (issue 34; target ≤ 1 s per variant).

``lagsolve.variants(problems/rotating_tube.yaml, count=N, vary=mu, Omega, require=slip)`` in this process,
timed from the call to the returned set, files written: the per-variant figure is total / N, the one derivation
included (so it is conservative for small N), by wall clock and by CPU time. The reference, in the same run:
what a variant costs done the obvious way, file by file — ``derive`` (a fresh derivation, as ``lagsolve
check`` of each file does) plus ``simulate`` of the variant's file — timed on a sample of S variants. PASS/MISS
is information only: the script always exits 0. On a machine shared with other work the wall clock depends on
the load; the CPU time less so.

    .venv/bin/python bench/variants.py                  # 30 variants, a sample of 2 (about a minute)
    .venv/bin/python bench/variants.py --count 5 --sample 1 --json
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

ROOT = Path(__file__).resolve().parent.parent
PROBLEM = ROOT / "problems" / "rotating_tube.yaml"
VARY = ("mu=0.1:0.6", "Omega=1:4")
TARGET = 1.0  # seconds per variant


def _clocks() -> tuple[float, float]:
    return time.perf_counter(), time.process_time()


def generation(count: int, seed: int) -> dict[str, Any]:
    """The variants command in process (the first derivation of this process): total, per variant, rejections."""
    import lagsolve

    with tempfile.TemporaryDirectory() as folder:
        wall, cpu = _clocks()
        made = lagsolve.variants(PROBLEM, count=count, vary=list(VARY), seed=seed, require="slip", output=folder)
        total = (time.perf_counter() - wall, time.process_time() - cpu)
        texts = [v.text for v in made.variants]
    return {"count": count, "attempts": made.attempts, "rejections": made.rejections,
            "total_s": {"wall": total[0], "cpu": total[1]},
            "per_variant_s": {"wall": total[0] / count, "cpu": total[1] / count},
            "texts": texts}


def reference(texts: list[str], sample: int) -> dict[str, Any]:
    """Per variant, the obvious way: a fresh derivation of the variant's file and a simulation of it."""
    import sympy

    import lagsolve

    walls, cpus = [], []
    for text in texts[:sample]:
        sympy.core.cache.clear_cache()
        wall, cpu = _clocks()
        derivation = lagsolve.derive(text)
        lagsolve.simulate(derivation, samples=2001)
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return {"sample": len(walls), "per_variant_s": {"wall": sum(walls) / len(walls), "cpu": sum(cpus) / len(cpus)}}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=30, help="variants to generate (default 30)")
    parser.add_argument("--sample", type=int, default=2, help="variants done the obvious way (default 2)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args(argv)
    importlib.import_module("lagsolve.api")
    made = generation(args.count, args.seed)
    texts = made.pop("texts")
    ref = reference(texts, max(1, args.sample))
    per = made["per_variant_s"]
    result = {**made, "reference": ref,
              "speed_up": {k: ref["per_variant_s"][k] / per[k] if per[k] > 0 else None for k in ("wall", "cpu")},
              "target_s": TARGET, "pass": per["cpu"] <= TARGET}
    if args.json:
        print(json.dumps(result, indent=2))
        return 0
    print(f"lagsolve variants {PROBLEM.relative_to(ROOT)} --count {args.count} --vary {' --vary '.join(VARY)} "
          f"--require slip --seed {args.seed}")
    print(f"  attempts {made['attempts']}, rejected per rule: "
          + (", ".join(f"{k} {v}" for k, v in made["rejections"].items() if v) or "none"))
    print(f"  {'':28}{'wall s':>10}{'CPU s':>10}")
    rows = [("total (one derivation)", made["total_s"]), ("per variant", per),
            (f"reference per variant (S={ref['sample']})", ref["per_variant_s"])]
    for label, figures in rows:
        print(f"  {label:28}{figures['wall']:10.3f}{figures['cpu']:10.3f}")
    speed = result["speed_up"]
    print(f"  speed-up over the reference: {speed['wall']:.1f}x wall, {speed['cpu']:.1f}x CPU")
    print(f"  target <= {TARGET:g} s per variant (CPU): {'PASS' if result['pass'] else 'MISS'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
