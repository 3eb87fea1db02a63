#!/usr/bin/env python3
"""Benchmark: lagsolve's derivation against SymPy's LagrangesMethod, and CLI start-up time.

For each seed problem this times ``load_problem`` + ``derive`` (target 3 s) and the
same system written by hand for ``sympy.physics.mechanics.LagrangesMethod``; then the
start-up time of ``lagsolve --help`` (target 0.3 s) and of ``import lagsolve.cli``.

Every timed run happens in a fresh Python process, so SymPy's expression cache
(which makes a second derivation in the same process much faster) never helps; the
derivation times are taken inside that process with ``time.perf_counter`` and leave
out interpreter start-up and imports. Start-up times are wall times of whole
subprocess runs. The report prints PASS/MISS against each target but the exit status
is always 0: this is a benchmark, not a test.

    .venv/bin/python bench/derive.py                  # the table (about a minute)
    .venv/bin/python bench/derive.py --repeat 1 --only bead --json
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
PROBLEMS = ("bead", "knife_edge", "hole_table", "rotating_tube")
DERIVE_TARGET = 3.0  # seconds for load_problem + derive, per problem
HELP_TARGET = 0.3  # seconds for `lagsolve --help`, whole process
STARTUP_RUNS = 5
CHILD_TIMEOUT = 300.0
# a fixed hash seed makes SymPy's term order, and so its run time, repeatable between runs
CHILD_ENV = {**os.environ, "PYTHONHASHSEED": "0"}

COLUMNS = """\
Columns (best of {repeat} run(s), each in a fresh Python process with a cold SymPy cache;
the times leave out interpreter start-up and imports):
  lagsolve     load_problem(file) + derive(problem): the whole mechanics stage, including
               the display simplification of every shown result (T, V, momenta, equations,
               accelerations, multipliers, constraint and normal forces)
  (tidy)       the part of the lagsolve time spent in lagsolve.mechanics.symbolic.simplify
               (tidy, tidy_sum, norm, ...), timed in the same run
  LM total     sympy.physics.mechanics.LagrangesMethod on the same system written by hand:
               building L (and forces) + form_lagranges_equations() + rhs() (LU solve of
               mass_matrix_full for the accelerations and multipliers) + finishing
  LM eqs+solve form_lagranges_equations() + rhs() only
  LM finish    substituting the velocity constraints (and the normal force, for friction)
               + sympy.simplify() of each acceleration and multiplier; LagrangesMethod does
               no simplification of its own, lagsolve simplifies many more expressions
  target       the goal for the lagsolve column; PASS/MISS compares the two
  check        LM's accelerations and multipliers (up to sign) agree with lagsolve's,
               compared numerically at random points"""


# --------------------------------------------------------------------------- children


def _time_simplify_module() -> Callable[[], float]:
    """Wrap every function of lagsolve.mechanics.symbolic.simplify wherever it was imported; return
    a reader of the seconds spent inside them (outermost calls only)."""
    from lagsolve.mechanics.symbolic import simplify

    spent = [0.0]
    depth = [0]

    def timed(fn: Callable[..., Any]) -> Callable[..., Any]:
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            depth[0] += 1
            start = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                depth[0] -= 1
                if depth[0] == 0:
                    spent[0] += time.perf_counter() - start

        return wrapper

    originals = {
        name: fn
        for name, fn in vars(simplify).items()
        if callable(fn) and getattr(fn, "__module__", None) == simplify.__name__
        and not isinstance(fn, type)
    }
    wrapped = {id(fn): timed(fn) for fn in originals.values()}
    for name, module in list(sys.modules.items()):
        if not name.startswith("lagsolve") or module is None:
            continue
        for attr, value in list(vars(module).items()):
            if id(value) in wrapped:
                setattr(module, attr, wrapped[id(value)])
    return lambda: spent[0]


def child_lagsolve(path: str) -> dict[str, Any]:
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    tidy_seconds = _time_simplify_module()
    start = time.perf_counter()
    problem = load_problem(path)
    loaded = time.perf_counter()
    derivation = derive(problem)
    end = time.perf_counter()
    return {
        "seconds": end - start,
        "load": loaded - start,
        "derive": end - loaded,
        "tidy": tidy_seconds(),
        "accelerations": {k: str(v) for k, v in derivation.accelerations.items()},
        "multipliers": {k: str(v) for k, v in derivation.multipliers.items()},
    }


def _lm_bead(sp: Any, me: Any) -> dict[str, Any]:
    """Bead on the wire y = f(x): a holonomic constraint y - f(x)."""
    x, y = me.dynamicsymbols("x y", real=True)
    m, g = sp.symbols("m g", positive=True)
    f = sp.Function("f")
    t = me.dynamicsymbols._t
    lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y
    lm = me.LagrangesMethod(lagrangian, [x, y], hol_coneqs=[y - f(x)])
    return {"lm": lm, "names": ["x", "y"], "multipliers": ["wire"]}


def _lm_knife_edge(sp: Any, me: Any) -> dict[str, Any]:
    """Dumbbell with a knife edge under particle 1: one nonholonomic constraint."""
    x, y, th = me.dynamicsymbols("x y theta", real=True)
    m, l = sp.symbols("m l", positive=True)  # noqa: E741 - the problem's name for the rod length
    t = me.dynamicsymbols._t
    x2, y2 = x + l * sp.cos(th), y + l * sp.sin(th)
    kinetic = m * (x.diff(t) ** 2 + y.diff(t) ** 2 + x2.diff(t) ** 2 + y2.diff(t) ** 2) / 2
    skate = -sp.sin(th) * x.diff(t) + sp.cos(th) * y.diff(t)
    lm = me.LagrangesMethod(kinetic, [x, y, th], nonhol_coneqs=[skate])
    return {"lm": lm, "names": ["x", "y", "theta"], "multipliers": ["skate"]}


def _lm_hole_table(sp: Any, me: Any) -> dict[str, Any]:
    """Two masses joined through a hole: the string is the holonomic constraint r - z - l."""
    r, th, z = me.dynamicsymbols("r theta z", real=True)
    m1, m2, g, l = sp.symbols("m1 m2 g l", positive=True)  # noqa: E741
    t = me.dynamicsymbols._t
    px, py = r * sp.cos(th), r * sp.sin(th)
    kinetic = m1 * (px.diff(t) ** 2 + py.diff(t) ** 2) / 2 + m2 * z.diff(t) ** 2 / 2
    lm = me.LagrangesMethod(kinetic - m2 * g * z, [r, th, z], hol_coneqs=[r - z - l])
    return {"lm": lm, "names": ["r", "theta", "z"], "multipliers": ["string"]}


def _lm_rotating_tube(sp: Any, me: Any) -> dict[str, Any]:
    """Particle in a rough tube turning at rate Omega: spherical coordinates, nonholonomic
    constraints theta_dot = 0 and phi_dot - Omega = 0, Coulomb friction -mu N s along the
    tube, with N the magnitude of the combined constraint force and s = sign(r_dot) kept as
    a symbol until the end (simplify would turn sign() into a Piecewise)."""
    r, th, ph = me.dynamicsymbols("r theta phi", real=True)
    m, g, om, mu, normal = sp.symbols("m g Omega mu N", positive=True)
    slide = sp.Symbol("s")
    t = me.dynamicsymbols._t
    frame = me.ReferenceFrame("F")
    e_r = (sp.sin(th) * sp.cos(ph) * frame.x + sp.sin(th) * sp.sin(ph) * frame.y
           + sp.cos(th) * frame.z)
    bead = me.Point("P")
    bead.set_vel(frame, (r * e_r).dt(frame))
    kinetic = m * bead.vel(frame).dot(bead.vel(frame)) / 2
    lagrangian = kinetic - m * g * r * sp.cos(th)
    lm = me.LagrangesMethod(lagrangian, [r, th, ph], forcelist=[(bead, -mu * normal * slide * e_r)],
                            frame=frame, nonhol_coneqs=[th.diff(t), ph.diff(t) - om])
    velocities = {th.diff(t): 0, ph.diff(t): om}

    def finish(acc: list[Any], lam: list[Any]) -> tuple[list[Any], list[Any]]:
        lam = [sp.simplify(e.subs(velocities)) for e in lam]
        acc = [sp.simplify(e.subs(velocities)) for e in acc]
        # the constraint force on the bead is lambda_tilt e_theta / r + lambda_spin e_phi / (r sin)
        size = sp.sqrt(sp.simplify((lam[0] / r) ** 2 + (lam[1] / (r * sp.sin(th))) ** 2))
        acc = [e.subs({normal: size, slide: sp.sign(r.diff(t))}) for e in acc]
        return acc, lam

    return {"lm": lm, "names": ["r", "theta", "phi"], "multipliers": ["tilt", "spin"],
            "finish": finish}


LM_BUILDERS: dict[str, Callable[[Any, Any], dict[str, Any]]] = {
    "bead": _lm_bead,
    "knife_edge": _lm_knife_edge,
    "hole_table": _lm_hole_table,
    "rotating_tube": _lm_rotating_tube,
}


def _plain(sp: Any, expr: Any, coordinates: list[Any], names: list[str], t: Any) -> str:
    """The expression with q(t) -> q and q'(t) -> q_dot, printed (lagsolve's naming)."""
    rules: dict[Any, Any] = {}
    for q, name in zip(coordinates, names, strict=True):
        rules[q.diff(t)] = sp.Symbol(f"{name}_dot")
        rules[q] = sp.Symbol(name)
    return str(expr.xreplace(rules))


def child_lm(name: str) -> dict[str, Any]:
    import sympy as sp
    import sympy.physics.mechanics as me

    start = time.perf_counter()
    built = LM_BUILDERS[name](sp, me)
    lm = built["lm"]
    made = time.perf_counter()
    lm.form_lagranges_equations()
    rhs = lm.rhs()  # mass_matrix_full.LUsolve(forcing_full): [q_dot; q_ddot; lambda]
    solved = time.perf_counter()
    n = len(lm.q)
    acc, lam = list(rhs[n:2 * n]), list(rhs[2 * n:])
    if "finish" in built:
        acc, lam = built["finish"](acc, lam)
    else:
        acc = [sp.simplify(e) for e in acc]
        lam = [sp.simplify(e) for e in lam]
    end = time.perf_counter()
    t = me.dynamicsymbols._t
    names, q = built["names"], list(lm.q)
    return {
        "seconds": end - start,
        "build": made - start,
        "solve": solved - made,
        "finish": end - solved,
        "accelerations": {k: _plain(sp, e, q, names, t) for k, e in zip(names, acc, strict=True)},
        "multipliers": {k: _plain(sp, e, q, names, t)
                        for k, e in zip(built["multipliers"], lam, strict=True)},
    }


# --------------------------------------------------------------------------- parent


def _child(kind: str, arg: str) -> dict[str, Any]:
    """One timed run in a fresh interpreter; the child prints its figures as JSON."""
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", kind, arg]
    try:
        done = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=CHILD_ENV,
                              timeout=CHILD_TIMEOUT, check=False)
    except subprocess.TimeoutExpired:
        return {"error": f"timed out after {CHILD_TIMEOUT:.0f} s"}
    if done.returncode != 0:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"error": f"exit {done.returncode}: {tail}"}
    return json.loads(done.stdout.strip().splitlines()[-1])


def _best(runs: list[dict[str, Any]]) -> dict[str, Any] | None:
    good = [r for r in runs if "error" not in r]
    return min(good, key=lambda r: r["seconds"]) if good else None


def _agree(ours: dict[str, Any], theirs: dict[str, Any]) -> tuple[bool, str]:
    """Numerical comparison at random points: accelerations by coordinate, multipliers by
    name up to sign (conventions differ)."""
    import sympy as sp

    def parse(text: str) -> Any:
        # names SymPy would read as its own objects (N, S, E, I, gamma, ...) are symbols here
        names = {w for w in re.findall(r"[A-Za-z_]\w*(?!\w*\()", text)
                 if w != "pi" and not isinstance(getattr(sp, w, None), (type(None), type))}
        return sp.sympify(text, locals={w: sp.Symbol(w) for w in names})

    def same(a: Any, b: Any, signs: tuple[int, ...]) -> bool:
        atoms = sorted((a - b).atoms(sp.Symbol, sp.Derivative, sp.core.function.AppliedUndef)
                       | (a + b).atoms(sp.Symbol, sp.Derivative, sp.core.function.AppliedUndef),
                       key=sp.default_sort_key)
        rng = random.Random(1234)
        for sign in signs:
            ok = True
            for _ in range(3):
                point = {s: sp.Float(rng.uniform(0.3, 1.7)) for s in atoms}
                try:
                    diff = complex(sp.N((a - sign * b).xreplace(point)))
                    scale = 1.0 + abs(complex(sp.N(a.xreplace(point))))
                except (TypeError, ValueError):
                    ok = False
                    break
                if abs(diff) > 1e-9 * scale:
                    ok = False
                    break
            if ok:
                return True
        return False

    missing = [f"{k}" for k in theirs["accelerations"] if k not in ours["accelerations"]]
    missing += [f"{k}" for k in theirs["multipliers"] if k not in ours["multipliers"]]
    if missing:
        return False, f"names differ: {', '.join(missing)}"
    bad = [k for k, v in theirs["accelerations"].items()
           if not same(parse(ours["accelerations"][k]), parse(v), (1,))]
    bad += [k for k, v in theirs["multipliers"].items()
            if not same(parse(ours["multipliers"][k]), parse(v), (1, -1))]
    if bad:
        return False, f"differ: {', '.join(bad)}"
    return True, "agree"


def _startup(cmd: list[str], runs: int = STARTUP_RUNS) -> dict[str, Any]:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        done = subprocess.run(cmd, cwd=ROOT, capture_output=True, check=False)
        times.append(time.perf_counter() - start)
        if done.returncode != 0:
            return {"error": f"exit {done.returncode}", "runs": times}
    return {"seconds": min(times), "runs": times}


def _lagsolve_command() -> list[str]:
    script = Path(sys.executable).parent / "lagsolve"
    if script.exists():
        return [str(script)]
    found = shutil.which("lagsolve")
    return [found] if found else [sys.executable, "-m", "lagsolve"]


def bench(only: list[str] | None, repeat: int, progress: Callable[[str], None]) -> dict[str, Any]:
    begin = time.perf_counter()
    problems: list[dict[str, Any]] = []
    skipped: list[dict[str, str]] = []
    for name in only or PROBLEMS:
        path = Path("problems") / f"{name}.yaml"
        if not (ROOT / path).exists():
            skipped.append({"name": name, "reason": f"{path} does not exist yet"})
            progress(f"{name}: skipped ({path} does not exist yet)")
            continue
        ours_runs, lm_runs = [], []
        for i in range(repeat):
            progress(f"{name}: run {i + 1}/{repeat}")
            ours_runs.append(_child("lagsolve", str(path)))
            lm_runs.append(_child("lm", name))
        ours, lm = _best(ours_runs), _best(lm_runs)
        row: dict[str, Any] = {
            "name": name,
            "file": str(path),
            "lagsolve_s": ours["seconds"] if ours else None,
            "lagsolve_load_s": ours["load"] if ours else None,
            "lagsolve_derive_s": ours["derive"] if ours else None,
            "lagsolve_tidy_s": ours["tidy"] if ours else None,
            "lagsolve_runs_s": [r.get("seconds") for r in ours_runs],
            "lm_s": lm["seconds"] if lm else None,
            "lm_build_s": lm["build"] if lm else None,
            "lm_solve_s": lm["solve"] if lm else None,
            "lm_finish_s": lm["finish"] if lm else None,
            "lm_runs_s": [r.get("seconds") for r in lm_runs],
            "target_s": DERIVE_TARGET,
            "pass": bool(ours and ours["seconds"] <= DERIVE_TARGET),
            "errors": sorted({r["error"] for r in ours_runs + lm_runs if "error" in r}),
        }
        if ours and lm:
            row["agree"], row["check"] = _agree(ours, lm)
        else:
            row["agree"], row["check"] = None, "not compared (a run failed)"
        problems.append(row)

    progress("start-up times")
    python = [sys.executable]
    help_run = _startup([*_lagsolve_command(), "--help"])
    startup = {
        "help_s": help_run.get("seconds"),
        "help_runs_s": help_run["runs"],
        "help_target_s": HELP_TARGET,
        "help_pass": bool(help_run.get("seconds") is not None
                          and help_run["seconds"] <= HELP_TARGET),
        "import_cli_s": _startup([*python, "-c", "import lagsolve.cli"]).get("seconds"),
        "python_s": _startup([*python, "-c", "pass"]).get("seconds"),
    }
    return {
        "repeat": repeat,
        "python": sys.version.split()[0],
        "sympy": _sympy_version(),
        "problems": problems,
        "skipped": skipped,
        "startup": startup,
        "total_s": time.perf_counter() - begin,
    }


def _sympy_version() -> str:
    done = subprocess.run([sys.executable, "-c", "import sympy; print(sympy.__version__)"],
                          capture_output=True, text=True, check=False)
    return done.stdout.strip() or "?"


def _s(value: float | None) -> str:
    return "    -   " if value is None else f"{value:7.2f}s"


def report(result: dict[str, Any]) -> str:
    lines = [
        f"lagsolve derivation benchmark (Python {result['python']}, SymPy {result['sympy']})",
        "",
        f"{'problem':<14} {'lagsolve':>8} {'(tidy)':>8} {'LM total':>8} {'LM eqs+solve':>12} "
        f"{'LM finish':>9} {'target':>7}  result  check",
    ]
    for row in result["problems"]:
        verdict = "PASS" if row["pass"] else "MISS"
        lines.append(
            f"{row['name']:<14} {_s(row['lagsolve_s'])} {_s(row['lagsolve_tidy_s'])} "
            f"{_s(row['lm_s'])} {_s(row['lm_solve_s']):>12} {_s(row['lm_finish_s']):>9} "
            f"{row['target_s']:6.1f}s  {verdict:<6}  {row['check']}"
        )
        for error in row["errors"]:
            lines.append(f"{'':<14} error: {error}")
    for skip in result["skipped"]:
        lines.append(f"{skip['name']:<14} skipped: {skip['reason']}")
    lines += ["", COLUMNS.format(repeat=result["repeat"]), ""]
    startup = result["startup"]
    help_verdict = "PASS" if startup["help_pass"] else "MISS"
    lines += [
        f"Start-up (best of {STARTUP_RUNS} fresh processes, wall time including the interpreter):",
        f"  lagsolve --help                   {_s(startup['help_s'])}  "
        f"target {startup['help_target_s']:.1f}s  {help_verdict}",
        f"  python -c \"import lagsolve.cli\"   {_s(startup['import_cli_s'])}  (information)",
        f"  python -c \"pass\"                  {_s(startup['python_s'])}  (interpreter alone)",
        "",
        f"Benchmark wall time {result['total_s']:.1f}s. PASS/MISS is information only: "
        "the exit status is always 0.",
    ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3, metavar="N",
                        help="runs per problem and method; the best is reported (default 3)")
    parser.add_argument("--only", action="append", choices=PROBLEMS, metavar="NAME",
                        help=f"only this problem (repeatable): {', '.join(PROBLEMS)}")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)

    if args.child:
        kind, arg = args.child
        figures = child_lagsolve(arg) if kind == "lagsolve" else child_lm(arg)
        print(json.dumps(figures))
        return 0
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")

    quiet = args.json or not sys.stderr.isatty()

    def progress(message: str) -> None:
        if not quiet:
            print(f"  ... {message}", file=sys.stderr, flush=True)

    result = bench(args.only, args.repeat, progress)
    print(json.dumps(result, indent=2) if args.json else report(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
