"""lagsolve grade on the bead (issue 31): seeded submissions, each correct form earns full marks, each seeded
mistake is found at its step and named, follow-through gives downstream credit, hostile text is refused per
submission; the correct answers are also built by an independent route (SymPy's LagrangesMethod)."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.grade.grader import grade
from lagsolve.grade.key import Grading, default_weights
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
BEAD = ROOT / "problems" / "bead.yaml"
F1, F2 = "Derivative(f(x), x)", "Derivative(f(x), (x, 2))"


@pytest.fixture(scope="module")
def key() -> tuple:
    problem = load_problem(BEAD)
    return problem, derive(problem)


def graded(key: tuple, text: str, grading: Grading | None = None) -> dict:
    problem, derivation = key
    result = grade(derivation, grading or Grading(default_weights(problem)), read_text(text, problem, "s.yaml"))
    return {s.step: s for s in result.steps}


def steps(**entries: object) -> str:
    lines = ["student: s", "steps:"]
    for name, value in entries.items():
        if isinstance(value, dict):
            inner = ", ".join(f'{k}: "{v}"' for k, v in value.items())
            lines.append(f"  {name}: {{{inner}}}")
        else:
            lines.append(f'  {name}: "{value}"')
    return "\n".join(lines) + "\n"


def test_correct_examples_earn_full_marks(key: tuple) -> None:
    problem, derivation = key
    for name in ("ada", "dan"):
        text = (ROOT / "examples" / "grading" / f"{name}.yaml").read_text()
        result = grade(derivation, Grading(default_weights(problem)), read_text(text, problem, name))
        assert [s.status for s in result.steps] == ["correct"] * len(result.steps), result.steps
        assert result.points == result.max_points == 12


def _lagranges_method_answers() -> dict[str, str]:
    """q̈ and λ of the bead from SymPy's LagrangesMethod, written in the problem's syntax."""
    t = sympy.Symbol("t")
    m, g = sympy.symbols("m g", positive=True)
    f = sympy.Function("f")
    x, y = dynamicsymbols("x y")
    lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y
    method = LagrangesMethod(lagrangian, [x, y], hol_coneqs=[y - f(x)])
    method.form_lagranges_equations()
    rhs = method.rhs()
    xs, xd = sympy.symbols("x x_dot")
    plain = {x.diff(t): xd, y.diff(t): xd * sympy.Derivative(f(xs), xs).subs(xs, xs), x: xs, y: f(xs)}

    def text(expr: object) -> str:
        e = sympy.sympify(expr).subs(plain).doit()
        return sympy.sstr(sympy.simplify(e))

    # rhs = [x_dot, y_dot, x_ddot, y_ddot, lambda]; SymPy writes M q̈ = F + Aᵀλ with its own sign of λ
    return {"x": text(rhs[2]), "y": text(rhs[3]), "lambda": text(rhs[4])}


def test_independent_route_is_graded_correct(key: tuple) -> None:
    answers = _lagranges_method_answers()
    text = steps(accelerations={"x": answers["x"], "y": answers["y"]})
    grades = graded(key, text)
    assert grades["accelerations"].status == "correct", grades["accelerations"]
    # SymPy's λ is lagsolve's up to its sign convention: correct, or named as that convention
    grades = graded(key, steps(multipliers={"wire": answers["lambda"]}))
    assert grades["multipliers"].status == "correct" or grades["multipliers"].mistake == "lambda_sign_convention"
    either = Grading(default_weights(key[0]), lambda_sign="either")
    assert graded(key, steps(multipliers={"wire": answers["lambda"]}), either)["multipliers"].status == "correct"


ACC = f"-{F1}*({F2}*x_dot**2 + g)/(1 + {F1}**2)"
ACC_Y = f"({F2}*x_dot**2 - g*{F1}**2)/(1 + {F1}**2)"
LAM = f"m*({F2}*x_dot**2 + g)/(1 + {F1}**2)"

SEEDED = [
    ("potential", "-m*g*y", "wrong_potential_sign"),
    ("lagrangian", "m*(x_dot**2 + y_dot**2)/2 + m*g*y", "wrong_potential_sign"),
    ("lagrangian", "m*(x_dot**2 + y_dot**2) - m*g*y", "missing_factor"),
    ("kinetic", "m*x_dot**2/2", "missing_kinetic_term"),
    ("kinetic", "m*(x_dot**2 + y_dot**2)", "missing_factor"),
    ("momenta", {"x": "2*m*x_dot", "y": "m*y_dot"}, "missing_factor"),
    ("generalized_forces", {"x": "0", "y": "m*g"}, "sign_error"),
    ("equations", {"x": "m*x_ddot = lambda_wire*" + F1, "y": "m*y_ddot + m*g - lambda_wire"},
     "lambda_sign_convention"),
    ("accelerations", {"x": f"-{F1}*g/(1 + {F1}**2)", "y": ACC_Y}, "missing_velocity_squared_terms"),
    ("accelerations", {"x": f"-{F1}*({F2}*x_dot**2 - g)/(1 + {F1}**2)", "y": ACC_Y}, "sign_error"),
    ("accelerations", {"x": "0", "y": "-g"}, "dropped_constraint"),  # the bead falls freely
    ("multipliers", {"wire": "-" + LAM}, "lambda_sign_convention"),
    ("multipliers", {"wire": "2*" + LAM}, "missing_factor"),
    ("constraint_forces", {"wire": f"m*({F2}*x_dot**2 + g)/sqrt(1 + {F1}**2)"}, "missing_abs"),
]


@pytest.mark.parametrize(("step", "value", "mistake"), SEEDED, ids=[f"{s}-{m}" for s, _, m in SEEDED])
def test_seeded_mistake_found_and_named(key: tuple, step: str, value: object, mistake: str) -> None:
    grades = graded(key, steps(**{step: value}))
    assert grades[step].status == "incorrect", grades[step]
    assert grades[step].mistake == mistake, grades[step]
    assert grades[step].points < grades[step].max_points
    others = [s for name, s in grades.items() if name != step]
    assert all(s.status == "missing" for s in others)


def test_follow_through_after_a_wrong_potential(key: tuple) -> None:
    text = (ROOT / "examples" / "grading" / "bob.yaml").read_text()
    grades = graded(key, text)
    assert grades["potential"].mistake == "wrong_potential_sign"
    for step in ("lagrangian", "generalized_forces", "equations", "accelerations"):
        assert grades[step].status == "follows", grades[step]
        assert grades[step].points == grades[step].max_points
    half = Grading(default_weights(key[0]), follow_through=0.5)
    assert graded(key, text, half)["equations"].points == 1.5  # x is right (1), y follows (half of 1)


def test_follow_through_multipliers_from_own_equations(key: tuple) -> None:
    text = steps(equations={"x": "m*x_ddot = lambda_wire*" + F1, "y": "m*y_ddot + m*g + lambda_wire"},
                 multipliers={"wire": "-" + LAM}, accelerations={"x": ACC, "y": ACC_Y})
    grades = graded(key, text)
    assert grades["equations"].mistake == "lambda_sign_convention"
    assert grades["multipliers"].status == "follows"
    assert grades["accelerations"].status == "correct"  # the same q̈ in either convention


def test_wrong_without_a_known_cause_is_incorrect_and_unnamed(key: tuple) -> None:
    # of the right dimension (an acceleration): F1**3*x_dot, a velocity, is now named wrong_dimension
    grades = graded(key, steps(accelerations={"x": f"{F1}**3*g", "y": ACC_Y}))
    assert grades["accelerations"].status == "incorrect"
    assert grades["accelerations"].mistake is None
    assert grades["accelerations"].points == 1.0  # y is right: half the step


def test_an_equation_off_by_a_term_without_the_state_is_not_a_factor_away(key: tuple) -> None:
    """y: m y_ddot − m g − λ is not the key's m y_ddot + m g − λ times a constant; −3 times the key's is (the
    hole table's z equation, which depends on no coordinate, is the case that needs the accelerations and λ
    drawn anew at each state: tests/grade/test_seeded.py)."""
    right = {"x": f"m*x_ddot = -lambda_wire*{F1}", "y": "m*y_ddot + m*g - lambda_wire"}
    assert graded(key, steps(equations=right))["equations"].status == "correct"
    scaled = {**right, "y": "-3*m*y_ddot - 3*m*g + 3*lambda_wire"}
    assert graded(key, steps(equations=scaled))["equations"].status == "correct"
    wrong = graded(key, steps(equations={**right, "y": "m*y_ddot - m*g - lambda_wire"}))["equations"]
    assert wrong.status == "incorrect" and wrong.points == 1.0, wrong.message  # x is right: half the step


@pytest.mark.parametrize("hostile", ["__import__('os').system('true')", "9**9**9**9", "exp(exp(exp(exp(9))))",
                                     "m*q_dot", "x_ddot", "eval(1)", "m*x_dot = ="])
def test_hostile_text_is_unreadable_and_the_rest_graded(key: tuple, hostile: str) -> None:
    text = steps(momenta={"x": hostile.replace('"', "'"), "y": "m*y_dot"}, potential="m*g*y")
    grades = graded(key, text)
    assert grades["momenta"].status == "unreadable"
    assert "s.yaml:" in grades["momenta"].message and "steps.momenta.x" in grades["momenta"].message
    assert grades["momenta"].points == 0
    assert grades["potential"].status == "correct"


def test_grades_do_not_depend_on_the_order_of_entries(key: tuple) -> None:
    a = graded(key, steps(accelerations={"x": ACC, "y": ACC_Y}, potential="m*g*y"))
    b = graded(key, steps(potential="m*g*y", accelerations={"y": ACC_Y, "x": ACC}))
    assert a == b


def test_a_trivial_constant_earns_no_credit_as_a_conserved_quantity(key: tuple) -> None:
    """A conserved quantity the key does not name is correct when its rate along the key's equations is 0, but not
    when it is the same at every state of a set of parameters: m g (a constant) and y − f(x) (the wire) are
    conserved by any motion (they were graded correct). The energy written by hand under another name still is."""
    energy = "m*(x_dot**2 + y_dot**2)/2 + m*g*y"
    grading = Grading({"conserved": 1.0})
    for value in ("m*g", "y - f(x)", "m*g + y - f(x)"):
        step = graded(key, steps(conserved={"c": value}), grading)["conserved"]
        assert step.status == "incorrect", value
        assert "constant of the parameters or a constraint" in step.message, value
    assert graded(key, steps(conserved={"mechanical": energy}), grading)["conserved"].status == "correct"
    assert graded(key, steps(conserved={"c": "m*x_dot"}), grading)["conserved"].status == "incorrect"


@pytest.mark.parametrize("constant", ["0", "m + g", "y - f(x) + 3"])
def test_a_constant_is_no_conserved_quantity(key: tuple, constant: str) -> None:
    """A quantity the key does not name is correct when it is conserved along the key's motion, but a constant of
    the parameters (on the constraint surface) is conserved by any motion: full marks for ``c: 0`` before."""
    problem, _ = key
    grading = Grading({**default_weights(problem), "conserved": 1.0})
    found = graded(key, steps(conserved={"c": constant}), grading)["conserved"]
    assert found.status == "incorrect"
    assert "a constant of the parameters or a constraint" in found.message
    real = graded(key, steps(conserved={"c": f"2*(m*x_dot**2*(1 + {F1}**2)/2 + m*g*f(x))"}), grading)["conserved"]
    assert real.status == "correct"
