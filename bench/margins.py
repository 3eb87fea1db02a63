#!/usr/bin/env python3
"""Benchmark: how far each stage of each derivation is from running out of its CPU slice.

A stage that runs out of its slice gives a note instead of its result, so a report is the same on every machine
only while every stage finishes well inside its slice: a slower or busier machine (CI) spends more CPU on the same
work. This derives each problem with the default budget and lists, for every stage that ran, the CPU it used and
the slice it had (``Stages.slice_for``, or the stage's cap), sorted by the ratio; a stage using more than
``1/MARGIN`` of its slice is flagged. The coupled pendulums' equilibria, at 0.95 s of a 2 s cap, once ran out
on CI: the stage's cap is now 6 s (``analyse.LINEARIZE_CAP``).

The stages are timed by wrapping :meth:`lagsolve.mechanics.stages.Stages.run` in this process (CPU time).

    .venv/bin/python bench/margins.py                   # every problems/*.yaml (about 30 s)
    .venv/bin/python bench/margins.py coupled_pendulums --json
    .venv/bin/python bench/margins.py /tmp/my_problem.yaml      # any problem file, by its path

The exit status is always 0: this is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
MARGIN = 5.0  # a stage should use under a fifth of its slice
SHOWN = 12  # rows printed (all are in the JSON)


def _measure(names: list[str]) -> list[dict[str, Any]]:
    from lagsolve.mechanics import stages as module
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    rows: list[dict[str, Any]] = []
    current = [""]
    original = module.Stages.run

    def timed(self: Any, stage: str, fn: Any, *args: Any, cap: float | None = None, **kwargs: Any) -> Any:
        given = self.slice_for(stage) if cap is None else min(self.slice_for(stage), cap)
        start = time.process_time()
        result = original(self, stage, fn, *args, cap=cap, **kwargs)
        used = time.process_time() - start
        rows.append({"problem": current[0], "stage": stage, "used_s": round(used, 3), "slice_s": round(given, 3),
                     "ratio": round(used / given, 3), "finished": result is not None,
                     "flagged": used * MARGIN > given})
        return result

    module.Stages.run = timed  # type: ignore[method-assign]
    try:
        for name in names:
            current[0] = name
            derive(load_problem(_problem_file(name)))
    finally:
        module.Stages.run = original  # type: ignore[method-assign]
    return sorted(rows, key=lambda r: (-r["ratio"], r["problem"], r["stage"]))


def _problem_file(name: str) -> Path:
    """A name in problems/ (``bead``) or the path of any problem file (``problems/bead.yaml``, an unshipped one)."""
    return Path(name) if name.endswith((".yaml", ".yml")) else ROOT / "problems" / f"{name}.yaml"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("problems", nargs="*", help="names in problems/ or problem files' paths (default: all shipped)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    options = parser.parse_args(argv)
    names = options.problems or sorted(p.stem for p in (ROOT / "problems").glob("*.yaml"))
    rows = _measure(names)
    flagged = [r for r in rows if r["flagged"]]
    if options.json:
        print(json.dumps({"margin": MARGIN, "problems": names, "stages": rows, "flagged": len(flagged)}, indent=1))
        return 0
    print(f"{'used/slice':>10}  {'used s':>7}  {'slice s':>7}  problem / stage")
    for r in rows[:SHOWN]:
        mark = f"  <- under a 1/{MARGIN:g} margin" if r["flagged"] else ""
        print(f"{r['ratio']:>10.3f}  {r['used_s']:>7.2f}  {r['slice_s']:>7.1f}  {r['problem']} / {r['stage']}{mark}")
    print(f"{len(flagged)} of {len(rows)} stages use more than 1/{MARGIN:g} of their slice")
    return 0


if __name__ == "__main__":
    sys.exit(main())
