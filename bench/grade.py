#!/usr/bin/env python3
"""Benchmark: grading a class of 200 submissions of the bead on a wire (issue 31, target: under 60 s).

The submissions are generated: every student writes each step in a form of their own (the equations
multiplied by a student's own integer, the potential with a student's own constant, the kinetic energy
with its terms in another order), so that no two students share an expression and nothing is cached
between them; every other student makes one known mistake (the potential's sign, L = T + V, a missing
factor 2 in T, λ in the other convention, no centripetal term, no Abs) at a known step.

Reported beside it, in the same run, as a reference: SymPy's own ``LagrangesMethod`` deriving the
equations of each student's Lagrangian (the work an instructor's script would do to follow a student's
L through), for the same number of students. Both are CPU time (``time.process_time``) after imports; the
target is judged on the wall time of the grading (the key's derivation included).

    .venv/bin/python bench/grade.py                 # 200 submissions
    .venv/bin/python bench/grade.py --count 20 --json
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
KEY = ROOT / "problems" / "bead.yaml"
TARGET = 60.0  # seconds for 200 submissions
COUNT = 200

FP, FPP = "Derivative(f(x), x)", "Derivative(f(x), (x, 2))"
#: one mistake per wrong submission: (name of the step it is made at, the mistake's name, the steps changed)
MISTAKES: list[tuple[str, str, dict[str, Any]]] = [
    ("potential", "wrong_potential_sign", {"potential": "-m*g*f(x) + {c}"}),
    ("lagrangian", "wrong_potential_sign", {"lagrangian": "m*(x_dot**2 + y_dot**2)/2 + m*g*y + {c}"}),
    ("kinetic", "missing_factor", {"kinetic": "{k}*m*x_dot**2*(1 + {fp}**2)".replace("{fp}", FP)}),
    ("multipliers", "lambda_sign_convention",
     {"multipliers": {"wire": f"-{{k}}*m*({FPP}*x_dot**2 + g)/({{k}} + {{k}}*{FP}**2)"}}),
    ("accelerations", "missing_velocity_squared_terms",
     {"accelerations": {"x": f"-{{k}}*{FP}*g/({{k}}*(1 + {FP}**2))", "y": f"-g*{FP}**2/(1 + {FP}**2)"}}),
    ("constraint_forces", "missing_abs",
     {"constraint_forces": {"wire": f"{{k}}*m*({FPP}*x_dot**2 + g)/({{k}}*sqrt(1 + {FP}**2))"}}),
]


def correct_steps(k: int, c: int) -> dict[str, Any]:
    """The bead's answers written with the student's own integer ``k`` and constant ``c``."""
    return {
        "kinetic": f"m*x_dot**2/2 + m*{FP}**2*x_dot**2/2 + {c} - {c}",
        "potential": f"m*g*f(x) + {c}",
        "lagrangian": f"m*(y_dot**2 + x_dot**2)/2 - m*g*y - {c}",
        "constraints": {"wire": f"{k}*y = {k}*f(x)"},
        "momenta": {"x": f"{k}*m*x_dot/{k}", "y": f"m*y_dot*{k}/{k}"},
        "generalized_forces": {"x": f"{c} - {c}", "y": f"-{k}*m*g/{k}"},
        "equations": {"x": f"{k}*m*x_ddot = -{k}*lambda_wire*{FP}",
                      "y": f"{k}*m*y_ddot + {k}*m*g - {k}*lambda_wire"},
        "accelerations": {"x": f"-{k}*{FP}*({FPP}*x_dot**2 + g)/({k} + {k}*{FP}**2)",
                          "y": f"({k}*{FPP}*x_dot**2 - {k}*g*{FP}**2)/({k}*(1 + {FP}**2))"},
        "multipliers": {"wire": f"{k}*m*({FPP}*x_dot**2 + g)/({k} + {k}*{FP}**2)"},
        "constraint_forces": {"wire": f"{k}*m*Abs({FPP}*x_dot**2 + g)/({k}*sqrt(1 + {FP}**2))"},
    }


def _fill(value: Any, k: int, c: int) -> Any:
    if isinstance(value, dict):
        return {n: _fill(v, k, c) for n, v in value.items()}
    return value.replace("{k}", str(k)).replace("{c}", str(c))


def submissions(count: int) -> list[tuple[str, dict[str, Any], tuple[str, str] | None]]:
    """``count`` (student, steps, (step, mistake) or None): even students correct, odd ones one mistake."""
    out = []
    for i in range(count):
        k, c = 2 + i, 3 + 2 * i
        steps = correct_steps(k, c)
        seeded = None
        if i % 2:
            step, mistake, changed = MISTAKES[(i // 2) % len(MISTAKES)]
            steps.update(_fill(changed, k, c))
            seeded = (step, mistake)
        out.append((f"student{i:03d}", steps, seeded))
    return out


def write(folder: Path, count: int) -> list[Path]:
    paths = []
    for student, steps, _ in submissions(count):
        path = folder / f"{student}.yaml"
        path.write_text(json.dumps({"student": student, "steps": steps}), encoding="utf-8")  # JSON is YAML
        paths.append(path)
    return paths


def reference_lagranges_method(count: int) -> float:
    """CPU seconds for SymPy's LagrangesMethod to derive each student's (distinct) Lagrangian's equations."""
    import sympy
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

    m, g = sympy.symbols("m g", positive=True)
    f = sympy.Function("f")
    x, y = dynamicsymbols("x y")
    t = dynamicsymbols._t
    start = time.process_time()
    for i in range(count):
        c = 3 + 2 * i
        lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y - c
        method = LagrangesMethod(lagrangian, [x, y], hol_coneqs=[y - f(x)])
        method.form_lagranges_equations()
    return time.process_time() - start


def run(count: int) -> dict[str, Any]:
    from lagsolve.app.grading import grade_files

    generated = submissions(count)
    with tempfile.TemporaryDirectory() as tmp:
        paths = write(Path(tmp), count)
        start, wall = time.process_time(), time.perf_counter()
        grades = grade_files(KEY, paths)
        seconds, wall = time.process_time() - start, time.perf_counter() - wall
    found = 0
    wrong = 0
    for (_, _, seeded), g in zip(generated, grades.grades, strict=True):
        if seeded is None:
            continue
        wrong += 1
        by = {s.step: s for s in g.steps}
        found += by[seeded[0]].mistake == seeded[1]
    full = sum(1 for (_, _, seeded), g in zip(generated, grades.grades, strict=True)
               if seeded is None and g.points == g.max_points)
    reference = reference_lagranges_method(count)
    target = TARGET * count / COUNT
    return {"count": count, "grade_s": round(seconds, 3), "grade_wall_s": round(wall, 3),
            "per_submission_s": round(seconds / max(count, 1), 4),
            "reference_s": round(reference, 3),
            "reference": "sympy.physics.mechanics.LagrangesMethod: form_lagranges_equations() of each student's L",
            "target_s": target, "result": "PASS" if wall < target else "MISS",
            "correct_full_marks": full, "correct": count - wrong, "mistakes_found": found, "wrong": wrong}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=COUNT, help="how many submissions (target scaled: 60 s per 200)")
    parser.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    args = parser.parse_args(argv)
    result = run(args.count)
    if args.json:
        print(json.dumps(result))
        return 0
    print(f"lagsolve grade, {result['count']} submissions of the bead: {result['grade_wall_s']:.1f} s wall, "
          f"{result['grade_s']:.1f} s CPU ({result['per_submission_s']:.3f} s CPU each); target < "
          f"{result['target_s']:g} s wall: {result['result']}")
    print(f"reference, {result['reference']}: {result['reference_s']:.1f} s CPU")
    print(f"correct submissions with full marks: {result['correct_full_marks']}/{result['correct']}; "
          f"seeded mistakes found at their step: {result['mistakes_found']}/{result['wrong']}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    sys.exit(main())
