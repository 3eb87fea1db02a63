"""Every problem in problems/ end to end: load → derive → render, golden files, expected answers."""

from __future__ import annotations

import json
import random
from collections.abc import Callable
from pathlib import Path

import pytest
import sympy

from lagsolve.app.pipeline import Reports, golden_differences
from lagsolve.mechanics.derivation import Derivation
from lagsolve.problem.load import load_problem
from mechanics_support import shipped

ROOT = Path(__file__).resolve().parents[1]
ALL_PROBLEMS = sorted((ROOT / "problems").glob("*.yaml"))
PROBLEMS = [ROOT / "problems" / f"{name}.yaml" for name in shipped()]  # derived (see AWAITING_DERIVATION)
REVIEWED = [ROOT / "problems" / f"{name}.yaml" for name in shipped(golden=True)]  # with golden reports
GOLDEN = ROOT / "tests" / "golden"

# concrete smooth functions that stand in for declared functions in numeric checks
CONCRETE = [lambda u: sympy.sin(u) + u**2 / 3, lambda u: sympy.exp(u / 2) - u, lambda u: u**3 / 5 + sympy.cos(u)]


@pytest.fixture(scope="module", params=REVIEWED, ids=[p.stem for p in REVIEWED])
def reports(request: pytest.FixtureRequest, shipped_reports: Callable[[str], Reports]) -> Reports:
    return shipped_reports(request.param.stem)


@pytest.fixture(scope="module")
def derivations(shipped_derivation: Callable[[str], Derivation]) -> dict[str, Derivation]:
    return {p.stem: shipped_derivation(p.stem) for p in PROBLEMS}


@pytest.mark.slow
def test_reports_match_golden_files(reports: Reports) -> None:
    """Markdown, LaTeX and JSON of every problem equal the reviewed golden files (`make golden` rewrites them)."""
    assert golden_differences(reports, GOLDEN) == []


@pytest.mark.slow
def test_json_has_the_contract_keys(reports: Reports) -> None:
    """The JSON result carries every key of the format's section 2, with one equation per coordinate."""
    data = json.loads(reports.outputs["json"])
    for key in ("name", "coordinates", "lagrangian", "equations", "accelerations", "multipliers",
                "constraint_forces", "reduced", "conserved", "effective_potential"):
        assert key in data
    assert len(data["equations"]) == len(data["coordinates"])
    assert list(data["accelerations"]) == data["coordinates"]


def _numeric_points(derivation: Derivation, count: int, seed: int) -> list[tuple[dict, dict]]:
    """Random states on the constraint surface: position constraints solved numerically for one
    coordinate, velocity-level constraints for one velocity (states with no real solution are redrawn)."""
    rng = random.Random(seed)
    points: list[tuple[dict, dict]] = []
    while len(points) < count:
        point = _try_point(derivation, rng, len(points))
        if point is not None:
            points.append(point)
    return points


def _try_point(derivation: Derivation, rng: random.Random, k: int) -> tuple[dict, dict] | None:
    problem, model = derivation.problem, derivation.model
    values: dict = {problem.time: sympy.Rational(rng.randint(0, 30), 10)}
    for p in problem.parameters:
        values[p.symbol] = sympy.Rational(rng.randint(5, 40), 10)
    for c in problem.coordinates:
        low = 1 if c.symbol.is_positive else -25
        values[c.symbol] = sympy.Rational(rng.randint(low, 25), 10)
        values[c.velocity] = sympy.Rational(rng.randint(-25, 25), 10)
    concrete = {f.function: CONCRETE[(k + i) % len(CONCRETE)] for i, f in enumerate(problem.functions)}
    explicit = set(derivation.elimination.sources.values())
    for c in derivation.constraints:
        if c.kind != "holonomic" or c.name in explicit:
            continue
        target = [q for q in model.coordinates if q in c.expression.free_symbols][-1]
        others = {s: v for s, v in values.items() if s != target}
        try:
            root = sympy.nsolve(_evaluate(c.expression, (others, concrete), numeric=False), target, values[target])
        except (ValueError, ZeroDivisionError):
            return None
        values[target] = root
    for c in derivation.constraints:
        form = sum((a * v for a, v in zip(c.coefficients, model.velocities, strict=True)), c.offset)
        form = _evaluate(form, ({s: v for s, v in values.items() if s not in model.velocities}, concrete),
                         numeric=False)
        free = [v for v in model.velocities if form.coeff(v) != 0]
        if not free:
            continue
        target = free[-1]
        values[target] = sympy.solve(form.xreplace({s: v for s, v in values.items() if s != target}), target)[0]
    return values, concrete


def _evaluate(expr: sympy.Expr, point: tuple[dict, dict], numeric: bool = True) -> complex | sympy.Expr:
    values, concrete = point
    for fn, body in concrete.items():
        u = sympy.Dummy("u")
        expr = expr.replace(fn, sympy.Lambda(u, body(u)))
    expr = expr.doit().xreplace(values)
    return complex(sympy.N(expr, 30)) if numeric else expr


def _agree(derivation: Derivation, got: sympy.Expr, want: sympy.Expr, points: list[tuple[dict, dict]]) -> None:
    got, want = derivation.elimination.apply(got), derivation.elimination.apply(want)
    for point in points:
        a, b = _evaluate(got, point), _evaluate(want, point)
        assert abs(a - b) <= 1e-9 * max(1.0, abs(b)), (got, want, point[0])


@pytest.mark.slow
@pytest.mark.parametrize("name", [p.stem for p in PROBLEMS])
def test_expected_answers_hold(derivations: dict[str, Derivation], name: str) -> None:
    """Every `expected:` answer in a problem file agrees with the derivation at many random states."""
    derivation = derivations[name]
    expected = derivation.problem.expected
    pairs = [(derivation.accelerations[q], want) for q, want in expected.accelerations.items()]
    pairs += [(derivation.multipliers[c], want) for c, want in expected.multipliers.items()]
    pairs += [(derivation.constraint_forces[c].magnitude, want["magnitude"])
              for c, want in expected.constraint_forces.items() if "magnitude" in want]
    points = _numeric_points(derivation, 12, seed=7) if pairs else []  # the same states for every answer
    for got, want in pairs:
        _agree(derivation, got, want, points)


def test_every_problem_states_expected_answers_or_simulation() -> None:
    """Each shipped problem documents itself: a description, and answers or simulation defaults."""
    for path in ALL_PROBLEMS:
        problem = load_problem(path)
        assert problem.description, path
        assert problem.simulation is not None, path
