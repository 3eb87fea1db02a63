"""Shared helpers for the mechanics tests: cached derivations and numeric spot checks.

Derivations are cached for the whole session (``derive`` of a seed problem takes
seconds), so every test module can ask for the same problem without paying twice.
Numeric checks substitute random values for every free symbol (positive symbols get
positive values) and concrete functions for declared ones.
"""

from __future__ import annotations

import functools
import random
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import sympy

from lagsolve.mechanics.derivation import Derivation, derive
from lagsolve.problem.load import load_problem, load_text
from lagsolve.problem.schema import Problem

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"

#: problems the derive-everything tests leave out (none: since the staged derivation, every shipped problem
#: derives in seconds, and each has reviewed golden reports)
AWAITING_DERIVATION: frozenset[str] = frozenset()
AWAITING_GOLDEN: frozenset[str] = frozenset()


def shipped(*, golden: bool = False) -> list[str]:
    """Stems of ``problems/*.yaml`` that the derive-everything tests cover, sorted; with ``golden``, only those with
    reviewed golden reports."""
    left_out = AWAITING_GOLDEN if golden else AWAITING_DERIVATION
    return sorted(p.stem for p in PROBLEMS.glob("*.yaml") if p.stem not in left_out)

#: the particle in a frictionless rotating tube (ESM 3124 HW6, problem 2, with mu = 0)
TUBE = """
name: Particle in a smooth rotating tube
parameters: {m: mass, g: gravitational acceleration, Omega: rate of turn}
coordinates: [r, theta, phi]
particles:
  bead: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), r*cos(theta)]}
gravity: [0, 0, -g]
constraints:
  tilt: {nonholonomic: theta_dot}
  spin: {nonholonomic: phi_dot - Omega}
"""


@functools.cache
def problem_file(name: str) -> Problem:
    """``problems/<name>.yaml``, loaded once."""
    return load_problem(PROBLEMS / f"{name}.yaml")


def unpickled(blob: bytes) -> Any:
    """A pickled derivation, read back as it was: without evaluation, since pickle rebuilds each expression with
    its class's constructor, which would rewrite a display form such as (a + b)/2 as a/2 + b/2."""
    import pickle

    from sympy.core.parameters import evaluate

    with evaluate(False):
        return pickle.loads(blob)


#: a folder the test processes of one session share (pytest-xdist's workers; set by conftest.py), or None
SHARED: list[Path] = []


@functools.cache
def derived_file(name: str) -> Derivation:
    """``derive`` of ``problems/<name>.yaml``, computed once per session: by this process, or under pytest-xdist by
    whichever worker asks first (the others wait for it and read its pickle from :data:`SHARED`)."""
    if not SHARED:
        return derive(problem_file(name))
    import fcntl
    import pickle

    path = SHARED[0] / f"{name}.pickle"
    with open(SHARED[0] / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if path.exists():
            return unpickled(path.read_bytes())
        derivation = derive(problem_file(name))
        partial = path.with_suffix(".partial")
        partial.write_bytes(pickle.dumps(derivation))
        partial.replace(path)
        return derivation


@functools.cache
def problem_text(text: str) -> Problem:
    """A problem given inline as YAML, loaded once."""
    return load_text(text)


@functools.cache
def derived_text(text: str) -> Derivation:
    """``derive`` of an inline YAML problem, computed once per session."""
    return derive(problem_text(text))


def names(problem: Problem) -> dict[str, Any]:
    """Every declared name (time, parameters, coordinates, velocities, accelerations,
    functions) mapped to its SymPy object."""
    out = dict(problem.symbols)
    for c in problem.coordinates:
        out[c.acceleration.name] = c.acceleration
    for f in problem.functions:
        out[f.name] = f.function
    return out


def concrete(expr: Any, functions: Mapping[Any, Callable[[Any], Any]] | None = None) -> Any:
    """``expr`` with each declared function replaced by a concrete one, derivatives done."""
    expr = sympy.sympify(expr)
    for fn, body in (functions or {}).items():
        expr = expr.replace(fn, body)
    return expr.doit()


def random_point(symbols: Iterable[Any], rng: random.Random,
                 ranges: Mapping[Any, tuple[float, float]] | None = None) -> dict[Any, Any]:
    """A random value for each symbol: in ``ranges`` when given, positive symbols in
    [0.5, 2], all others in [-2, 2]."""
    ranges = ranges or {}
    point = {}
    for s in sorted(symbols, key=sympy.default_sort_key):
        low, high = ranges.get(s, (0.5, 2.0) if s.is_positive else (-2.0, 2.0))
        point[s] = sympy.Float(rng.uniform(low, high), 30)
    return point


def value(expr: Any, point: Mapping[Any, Any]) -> complex:
    """Numeric value of ``expr`` at ``point``; every free symbol must be given."""
    result = sympy.sympify(expr).xreplace(dict(point)).evalf(30)
    missing = result.free_symbols
    if missing:
        raise AssertionError(f"no value for {sorted(map(str, missing))} in {expr}")
    return complex(result)


def assert_same(actual: Any, expected: Any, *, functions: Mapping[Any, Any] | None = None,
                complete: Callable[[dict[Any, Any]], dict[Any, Any]] | None = None,
                ranges: Mapping[Any, tuple[float, float]] | None = None,
                also: Iterable[Any] = (), samples: int = 25, seed: int = 1,
                tol: float = 1e-9) -> None:
    """``actual`` equals ``expected`` at ``samples`` random points.

    ``functions`` makes declared functions concrete first; ``complete`` fills in
    dependent variables (for points on a constraint surface) from the random ones,
    which include the symbols in ``also`` even when the expressions lack them.
    """
    a, b = concrete(actual, functions), concrete(expected, functions)
    free = sympy.sympify(a).free_symbols | sympy.sympify(b).free_symbols | set(also)
    rng = random.Random(seed)
    for _ in range(samples):
        point = random_point(free, rng, ranges)
        if complete is not None:
            point.update(complete(dict(point)))
        va, vb = value(a, point), value(b, point)
        assert abs(va - vb) <= tol * (1 + abs(va) + abs(vb)), (
            f"{actual} != {expected} at {point}: {va} vs {vb}"
        )


def assert_zero(expr: Any, **kwargs: Any) -> None:
    """``expr`` vanishes at random points (same options as :func:`assert_same`)."""
    assert_same(expr, 0, **kwargs)


def exactly_equal(a: Any, b: Any) -> bool:
    """Symbolic equality: ``simplify(a - b) == 0`` (entry by entry for matrices)."""
    difference = sympy.sympify(a) - sympy.sympify(b)
    if isinstance(difference, sympy.MatrixBase):
        return all(sympy.simplify(e) == 0 for e in difference)
    return sympy.simplify(difference) == 0
