# ruff: noqa: E501 - the seeded answers are long formulas, one a line
"""Seeded submissions over the four seed problems (issue 31): correct answers written in other forms (and
the other λ convention where the key accepts it) earn every point; each known mistake, made at a known step,
is found at that step and named; after one seeded mistake the later steps that follow from it get
follow-through credit. The correct answers are checked against SymPy's LagrangesMethod, never lagsolve."""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.grade.grader import GradingKey, grade
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
F1, F2 = "Derivative(f(x), x)", "Derivative(f(x), (x, 2))"

#: per problem: the answers as a student writes them, the steps graded, and mistakes (step, name, changes)
SEEDS: dict[str, dict[str, Any]] = {
    "bead": {
        "steps": {
            "kinetic": f"m*x_dot**2*(1 + {F1}**2)/2", "potential": "m*g*f(x)",
            "lagrangian": "m*(x_dot**2 + y_dot**2)/2 - m*g*y",
            "momenta": {"x": "m*x_dot", "y": "m*y_dot"}, "generalized_forces": {"x": "0", "y": "-m*g"},
            "equations": {"x": f"m*x_ddot = -lambda_wire*{F1}", "y": "m*y_ddot + m*g = lambda_wire"},
            "accelerations": {"x": f"-{F1}*({F2}*x_dot**2 + g)/(1 + {F1}**2)",
                              "y": f"({F2}*x_dot**2 - g*{F1}**2)/(1 + {F1}**2)"},
            "multipliers": {"wire": f"m*({F2}*x_dot**2 + g)/(1 + {F1}**2)"},
        },
        "mistakes": [
            ("potential", "wrong_potential_sign", {"potential": "-m*g*f(x)"}),
            ("lagrangian", "wrong_potential_sign", {"lagrangian": "m*(x_dot**2 + y_dot**2)/2 + m*g*y"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m*x_dot**2/2"}),
            ("kinetic", "missing_factor", {"kinetic": f"m*x_dot**2*(1 + {F1}**2)"}),
            ("multipliers", "lambda_sign_convention", {"multipliers": {"wire": f"-m*({F2}*x_dot**2 + g)/(1 + {F1}**2)"}}),
            ("accelerations", "missing_velocity_squared_terms",
             {"accelerations": {"x": f"-{F1}*g/(1 + {F1}**2)", "y": f"-g*{F1}**2/(1 + {F1}**2)"}}),
            ("accelerations", "dropped_constraint", {"accelerations": {"x": "0", "y": "-g"}}),
            ("equations", "lambda_sign_convention",
             {"equations": {"x": f"m*x_ddot = lambda_wire*{F1}", "y": "m*y_ddot + m*g = -lambda_wire"}}),
        ],
    },
    "knife_edge": {
        "steps": {
            "kinetic": "m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2/2 + m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))",
            "potential": "0",
            "momenta": {"x": "2*m*x_dot - m*l*theta_dot*sin(theta)", "y": "2*m*y_dot + m*l*theta_dot*cos(theta)",
                        "theta": "m*l**2*theta_dot + m*l*(y_dot*cos(theta) - x_dot*sin(theta))"},
            "equations": {"x": "2*m*x_ddot - m*l*(theta_ddot*sin(theta) + theta_dot**2*cos(theta)) = -lambda_skate*sin(theta)",
                          "y": "2*m*y_ddot + m*l*(theta_ddot*cos(theta) - theta_dot**2*sin(theta)) = lambda_skate*cos(theta)",
                          "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"},
            "multipliers": {"skate": "m*theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))"},
        },
        "weights": {"kinetic": 1, "potential": 1, "momenta": 1, "equations": 2, "multipliers": 1},
        "mistakes": [
            ("kinetic", "missing_kinetic_term",
             {"kinetic": "m*(x_dot**2 + y_dot**2) + m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"}),
            ("kinetic", "missing_factor", {"kinetic": "2*m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2 + 2*m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"}),
            ("multipliers", "lambda_sign_convention",
             {"multipliers": {"skate": "-m*theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))"}}),
            ("multipliers", "sign_error", {"multipliers": {"skate": "m*theta_dot*(x_dot*cos(theta) - y_dot*sin(theta))"}}),
            ("momenta", "sign_error", {"momenta": {"x": "-2*m*x_dot + m*l*theta_dot*sin(theta)",
                                                   "y": "2*m*y_dot + m*l*theta_dot*cos(theta)",
                                                   "theta": "m*l**2*theta_dot + m*l*(y_dot*cos(theta) - x_dot*sin(theta))"}}),
            ("equations", "lambda_sign_convention",
             {"equations": {"x": "2*m*x_ddot - m*l*(theta_ddot*sin(theta) + theta_dot**2*cos(theta)) = lambda_skate*sin(theta)",
                            "y": "2*m*y_ddot + m*l*(theta_ddot*cos(theta) - theta_dot**2*sin(theta)) = -lambda_skate*cos(theta)",
                            "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"}}),
            ("equations", "missing_velocity_squared_terms",
             {"equations": {"x": "2*m*x_ddot - m*l*theta_ddot*sin(theta) = -lambda_skate*sin(theta)",
                            "y": "2*m*y_ddot + m*l*theta_ddot*cos(theta) = lambda_skate*cos(theta)",
                            "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"}}),
            ("momenta", "missing_factor", {"momenta": {"x": "4*m*x_dot - 2*m*l*theta_dot*sin(theta)", "y": "4*m*y_dot + 2*m*l*theta_dot*cos(theta)",
                          "theta": "2*m*l**2*theta_dot + 2*m*l*(y_dot*cos(theta) - x_dot*sin(theta))"}}),
        ],
    },
    "hole_table": {
        "steps": {
            "kinetic": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2", "potential": "m2*g*z",
            "lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 - m2*g*z",
            "momenta": {"r": "m1*r_dot", "theta": "m1*r**2*theta_dot", "z": "m2*z_dot"},
            "generalized_forces": {"r": "m1*r*theta_dot**2", "theta": "0", "z": "-m2*g"},
            "equations": {"r": "m1*r_ddot - m1*r*theta_dot**2 = lambda_string", "theta": "m1*r**2*theta_ddot + 2*m1*r*r_dot*theta_dot",
                          "z": "m2*z_ddot + m2*g = -lambda_string"},
            "accelerations": {"r": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r",
                              "z": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)"},
            "multipliers": {"string": "-m1*m2*(g + r*theta_dot**2)/(m1 + m2)"},
            "constraint_forces": {"string": "m1*m2*(g + r*theta_dot**2)/(m1 + m2)"},
        },
        "weights": {"kinetic": 1, "potential": 1, "lagrangian": 1, "momenta": 1, "generalized_forces": 1,
                    "equations": 2, "accelerations": 2, "multipliers": 1, "constraint_forces": 1},
        "mistakes": [
            ("potential", "wrong_potential_sign", {"potential": "-m2*g*z"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m1*r_dot**2/2 + m2*z_dot**2/2"}),
            ("generalized_forces", "sign_error", {"generalized_forces": {"r": "-m1*r*theta_dot**2", "theta": "0", "z": "-m2*g"}}),
            ("accelerations", "missing_velocity_squared_terms",
             {"accelerations": {"r": "-m2*g/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r", "z": "-m2*g/(m1 + m2)"}}),
            ("multipliers", "lambda_sign_convention", {"multipliers": {"string": "m1*m2*(g + r*theta_dot**2)/(m1 + m2)"}}),
            ("constraint_forces", "missing_factor", {"constraint_forces": {"string": "m1*(g + r*theta_dot**2)/(m1 + m2)"}}),
            ("lagrangian", "wrong_potential_sign",
             {"lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 + m2*g*z"}),
            ("momenta", "missing_factor", {"momenta": {"r": "m1*r_dot", "theta": "m1*r**2*theta_dot/2", "z": "m2*z_dot"}}),
        ],
    },
    "rotating_tube": {
        "steps": {
            "kinetic": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2",
            "potential": "m*g*r*cos(theta)",
            "lagrangian": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2 - m*g*r*cos(theta)",
            "momenta": {"r": "m*r_dot", "theta": "m*r**2*theta_dot", "phi": "m*r**2*sin(theta)**2*phi_dot"},
            "accelerations": {"r": "r*Omega**2*sin(theta)**2 - g*cos(theta) - mu*sign(r_dot)*Abs(sin(theta))"
                                   "*sqrt(4*Omega**2*r_dot**2 + (r*Omega**2*cos(theta) + g)**2)", "theta": "0", "phi": "0"},
            "multipliers": {"tilt": "-m*r**2*sin(theta)*cos(theta)*Omega**2 - m*g*r*sin(theta)",
                            "spin": "2*m*r*r_dot*sin(theta)**2*Omega"},
        },
        "weights": {"kinetic": 1, "potential": 1, "lagrangian": 1, "momenta": 1, "accelerations": 2, "multipliers": 1},
        "mistakes": [
            ("potential", "wrong_potential_sign", {"potential": "-m*g*r*cos(theta)"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m*(r_dot**2 + r**2*theta_dot**2)/2"}),
            ("lagrangian", "wrong_potential_sign",
             {"lagrangian": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2 + m*g*r*cos(theta)"}),
            ("multipliers", "lambda_sign_convention",
             {"multipliers": {"tilt": "m*r**2*sin(theta)*cos(theta)*Omega**2 + m*g*r*sin(theta)",
                              "spin": "-2*m*r*r_dot*sin(theta)**2*Omega"}}),
            ("momenta", "missing_factor",
             {"momenta": {"r": "m*r_dot", "theta": "m*r**2*theta_dot", "phi": "m*r**2*sin(theta)**2*phi_dot/2"}}),
            ("multipliers", "sign_error",
             {"multipliers": {"tilt": "-m*r**2*sin(theta)*cos(theta)*Omega**2 + m*g*r*sin(theta)",
                              "spin": "2*m*r*r_dot*sin(theta)**2*Omega"}}),
            ("kinetic", "missing_factor", {"kinetic": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)"}),
            ("potential", "missing_factor", {"potential": "2*m*g*r*cos(theta)"}),
        ],
    },
}


def _variant(steps: dict[str, Any], k: int, c: int) -> dict[str, Any]:
    """The same answers written differently: equations times k, the energies shifted by c, sums reordered."""
    out: dict[str, Any] = {}
    for name, value in steps.items():
        if name == "equations":
            out[name] = {q: " = ".join(f"{k}*({side})" for side in e.split("=")) for q, e in value.items()}
        elif name in ("potential", "lagrangian"):
            out[name] = f"{value} + {c}" if name == "potential" else f"{c} + ({value})"
        elif name == "kinetic":
            out[name] = f"({value})*{k}/{k}"
        elif isinstance(value, dict):
            out[name] = {q: f"{k}*({e})/{k}" for q, e in value.items()}
        else:
            out[name] = value
    return out


def _flip_lambda(steps: dict[str, Any], problem: Any) -> dict[str, Any]:
    """The other λ convention: the multipliers negated, and λ → −λ in the equations."""
    out = dict(steps)
    names = [c.name for c in problem.constraints]
    if "multipliers" in steps:
        out["multipliers"] = {n: f"-({e})" for n, e in steps["multipliers"].items()}
    if "equations" in steps:
        flipped = {}
        for q, e in steps["equations"].items():
            for n in names:
                e = e.replace(f"lambda_{n}", f"(-LAMBDA_{n})")
            flipped[q] = e.replace("LAMBDA_", "lambda_")
        out["equations"] = flipped
    return out


@pytest.fixture(scope="module")
def keys() -> dict[str, tuple]:
    out = {}
    for name, seed in SEEDS.items():
        problem = load_problem(ROOT / "problems" / f"{name}.yaml")
        derivation = derive(problem)
        weights = {k: float(v) for k, v in seed.get("weights", dict.fromkeys(seed["steps"], 1)).items()}
        out[name] = (problem, derivation, weights)
    return out


def _grade(keys: dict[str, tuple], name: str, steps: dict[str, Any], sign: str = "strict") -> dict[str, Any]:
    problem, derivation, weights = keys[name]
    grading = Grading(weights, 1.0, sign)
    text = json.dumps({"student": "s", "steps": steps})
    context = GradingKey(derivation, grading)
    result = grade(derivation, grading, read_text(text, problem, "s.yaml"), key=context)
    return {s.step: s for s in result.steps}


def _seeded() -> list[tuple[str, str, Any]]:
    """(problem, kind, data): 8 correct variants and 8 mistakes per problem: 64 submissions."""
    out: list[tuple[str, str, Any]] = []
    for name, seed in SEEDS.items():
        rng = random.Random(name)
        for i in range(8):
            out.append((name, "correct", (rng.randint(2, 9) * (-1) ** i, rng.randint(1, 50), i % 4 == 3)))
        for mistake in seed["mistakes"]:
            out.append((name, "mistake", mistake))
    return out


SEEDED = _seeded()


def test_at_least_sixty_seeded_submissions_half_correct() -> None:
    assert len(SEEDED) >= 60
    assert sum(kind == "correct" for _, kind, _ in SEEDED) * 2 == len(SEEDED)


@pytest.mark.parametrize(("name", "kind", "data"), SEEDED, ids=[f"{n}-{k}-{i}" for i, (n, k, _) in enumerate(SEEDED)])
def test_seeded_submission(keys: dict[str, tuple], name: str, kind: str, data: Any) -> None:
    problem = keys[name][0]
    steps = SEEDS[name]["steps"]
    if kind == "correct":
        k, c, other_convention = data
        written = _variant(steps, k, c)
        sign = "strict"
        if other_convention and problem.constraints:
            written, sign = _flip_lambda(written, problem), "either"
        graded = _grade(keys, name, written, sign)
        lost = {s: (g.status, g.message) for s, g in graded.items() if g.points != g.max_points}
        assert not lost
        return
    step, mistake, changed = data
    graded = _grade(keys, name, {**steps, **changed})
    assert graded[step].status == "incorrect"
    assert graded[step].mistake == mistake, graded[step].message
    for other, g in graded.items():
        if other not in changed:
            assert g.status in ("correct", "follows"), (other, g.message)


def test_follow_through_after_a_wrong_potential(keys: dict[str, tuple]) -> None:
    """hole_table with V = −m2 g z (the key's is +m2 g z: z is the height, gravity −g along it): L, the
    z equation and the accelerations that follow get credit. The z equation m2 z̈ − m2 g + λ is not the key's
    m2 z̈ + m2 g + λ up to a constant factor: the accelerations and λ are drawn anew at each state, so a ratio
    that depends on them is no constant (with them drawn per group of states it was, and this step was
    graded correct)."""
    steps = dict(SEEDS["hole_table"]["steps"])
    steps.update({"potential": "-m2*g*z", "lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 + m2*g*z",
                  "generalized_forces": {"r": "m1*r*theta_dot**2", "theta": "0", "z": "m2*g"},
                  "equations": {"r": "m1*r_ddot - m1*r*theta_dot**2 = lambda_string",
                                "theta": "m1*r**2*theta_ddot + 2*m1*r*r_dot*theta_dot",
                                "z": "m2*z_ddot - m2*g = -lambda_string"},
                  "accelerations": {"r": "(m1*r*theta_dot**2 + m2*g)/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r",
                                    "z": "(m1*r*theta_dot**2 + m2*g)/(m1 + m2)"},
                  "multipliers": {"string": "-m1*m2*(r*theta_dot**2 - g)/(m1 + m2)"},
                  "constraint_forces": {"string": "m1*m2*Abs(r*theta_dot**2 - g)/(m1 + m2)"}})
    graded = _grade(keys, "hole_table", steps)
    assert graded["potential"].mistake == "wrong_potential_sign"
    for step in ("lagrangian", "generalized_forces", "equations", "accelerations", "multipliers",
                 "constraint_forces"):
        assert graded[step].status == "follows", (step, graded[step].message)
        assert graded[step].points == graded[step].max_points
    assert graded["kinetic"].status == graded["momenta"].status == "correct"


# -- the correct answers, against SymPy's LagrangesMethod -----------------------------------------------


def _numeric_equal(a: Any, b: Any, symbols: list[Any], *, up_to_sign: bool = False) -> bool:
    rng = random.Random(1)
    for _ in range(5):
        point = {s: sympy.Float(rng.uniform(0.4, 1.6)) for s in symbols}
        x, y = complex(a.xreplace(point).evalf()), complex(b.xreplace(point).evalf())
        if abs(x - y) > 1e-9 * max(1, abs(y)) and not (up_to_sign and abs(x + y) <= 1e-9 * max(1, abs(y))):
            return False
    return True


@pytest.mark.parametrize("name", ["hole_table"])
def test_seeded_answers_agree_with_lagranges_method(keys: dict[str, tuple], name: str) -> None:
    problem = keys[name][0]
    parsed = read_text(json.dumps({"steps": SEEDS[name]["steps"]}), problem, "s.yaml")
    t = dynamicsymbols._t
    names = [q.name for q in problem.coordinates]
    q = dynamicsymbols(" ".join(names))
    syms = problem.symbols
    plain = {**{qi: syms[n] for qi, n in zip(q, names, strict=True)},
             **{qi.diff(t): syms[f"{n}_dot"] for qi, n in zip(q, names, strict=True)}}
    lagrangian = parsed.steps["kinetic"].entries[""] - parsed.steps["potential"].entries[""]
    back = {v: k for k, v in plain.items()}
    lagrangian = lagrangian.xreplace({s: back[s] for s in back if isinstance(s, sympy.Symbol)})
    if name == "knife_edge":
        x, y, th = q
        method = LagrangesMethod(lagrangian, q, nonhol_coneqs=[-sympy.sin(th) * x.diff(t) + sympy.cos(th) * y.diff(t)])
    else:
        r, _, z = q
        method = LagrangesMethod(lagrangian, q, hol_coneqs=[r - z - syms["l"]])
    method.form_lagranges_equations()
    rhs = method.rhs()
    n = len(q)
    accelerations = {nm: rhs[n + i].xreplace({qi.diff(t): plain[qi.diff(t)] for qi in q}).xreplace(plain)
                     for i, nm in enumerate(names)}
    multiplier = rhs[2 * n].xreplace({qi.diff(t): plain[qi.diff(t)] for qi in q}).xreplace(plain)
    symbols = sorted(set().union(*(e.free_symbols for e in accelerations.values())) | multiplier.free_symbols,
                     key=str)
    for coordinate, expr in parsed.steps["accelerations"].entries.items():
        assert _numeric_equal(expr, accelerations[coordinate], symbols), coordinate
    [student_lambda] = parsed.steps["multipliers"].entries.values()
    assert _numeric_equal(student_lambda, multiplier, symbols, up_to_sign=True)
