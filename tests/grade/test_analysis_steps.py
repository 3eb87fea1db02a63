"""lagsolve grade's equilibria, frequencies and hamiltonian steps (issue 31) on shipped problems that have them:
correct answers written differently earn full marks, wrong ones are incorrect with the expected mistake; the key's
values are checked against textbook ones (the bead on a rotating hoop, two coupled pendulums)."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest
import sympy

from lagsolve.errors import SpecError
from lagsolve.grade.grader import grade, key_answers
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
WEIGHTS = {"equilibria": 1.0, "frequencies": 1.0, "hamiltonian": 1.0}
HOOP = "bead_on_rotating_hoop"
ACOS = "acos(g/(Omega**2*R))"
H_HOOP = "p_theta**2/(2*m*R**2) - m*g*R*cos(theta) - m*R**2*Omega**2*sin(theta)**2/2"


@cache
def key(name: str) -> tuple:
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    return problem, derive(problem)


def graded(name: str, step: str, yaml_value: str, form: str = "either", extra: str = "") -> object:
    problem, derivation = key(name)
    text = f"student: s\nsteps:\n  {step}: {yaml_value}\n{extra}"
    result = grade(derivation, Grading(WEIGHTS, frequency_form=form), read_text(text, problem, "s.yaml"))
    return next(s for s in result.steps if s.step == step)


# -- the key's values against textbook ones (independent of lagsolve)


def test_hoop_key_frequencies_are_the_textbook_ones() -> None:
    """A bead on a hoop of radius R turning at Ω: ω² = g/R − Ω² about θ = 0, and Ω² − (g/(ΩR))² = Ω² sin²θ₀ about
    cos θ₀ = g/(Ω²R) (Goldstein; Taylor, Classical Mechanics, 8.5 / problem 7.29)."""
    _, derivation = key(HOOP)
    answers = key_answers(derivation)
    g, R, Omega = sympy.symbols("g R Omega", positive=True)
    textbook = [g / R - Omega**2, Omega**2 * (1 - (g / (Omega**2 * R)) ** 2)]
    values = [v.subs({s: {"g": g, "R": R, "Omega": Omega}[s.name] for s in v.free_symbols})
              for v in answers["frequencies"].values()]
    assert len(values) == 2
    for want, got in zip(textbook, values, strict=True):
        assert sympy.simplify(want - got) == 0
    points = {sympy.sstr(p["theta"]) for p in answers["equilibria"].values()}
    assert points == {"0", "pi", f"-{ACOS}", ACOS}


def test_coupled_pendulums_key_modes_are_the_textbook_ones() -> None:
    """Two pendulums (m, l) joined by a spring k at their bobs: ω² = g/l and g/l + 2k/m (in phase, opposite)."""
    _, derivation = key("coupled_pendulums")
    values = list(key_answers(derivation)["frequencies"].values())
    g, length, k, m = (sympy.Symbol(n) for n in "glkm")
    plain = {s.name: s for s in (g, length, k, m)}
    got = [v.xreplace({s: plain[s.name] for s in v.free_symbols}) for v in values]
    textbook = [g / length, g / length + 2 * k / m]
    assert len(got) == 2
    assert all(any(sympy.simplify(a - b) == 0 for b in got) for a in textbook)


# -- equilibria

EQUILIBRIA_CORRECT = [
    (HOOP, f'[0, pi, "{ACOS}", "-{ACOS}"]'),
    (HOOP, f'["-pi", 0, "2*pi - {ACOS}", "acos(g/(R*Omega**2))"]'),    # angles modulo 2π, another order
    (HOOP, f'[{{theta: 0}}, {{theta: pi}}, {{theta: "pi/2 - asin(g/(Omega**2*R))"}}, {{theta: "-{ACOS}"}}]'),
    ("coupled_pendulums", "[{theta1: 0, theta2: 0}, {theta1: pi, theta2: pi}, {theta1: 0, theta2: pi}, "
                          "{theta1: -pi, theta2: 0}]"),
    ("two_masses_spring", '[{x1: "x2 - L0"}]'),
    ("hole_table", '["(p_theta**2/(g*m1*m2))**(1/3)"]'),
    # as a problem file's expected: writes them (shared/grading-format.md: "equilibria: as expected:"); 'value'
    # was read as an unknown coordinate and the step was unreadable
    ("hole_table", '[{value: "(p_theta**2/(g*m1*m2))**(1/3)", stable: true, frequency: "sqrt(g)"}]'),
    (HOOP, f'[{{value: 0}}, {{value: pi, stable: false}}, {{value: "{ACOS}"}}, {{value: "-{ACOS}"}}]'),
    ("coupled_pendulums", "[{at: {theta1: 0, theta2: 0}, stable: true, squared_frequencies: [g/l]}, "
                          "{at: {theta1: pi, theta2: pi}}, {at: {theta1: 0, theta2: pi}}, {theta1: -pi, theta2: 0}]"),
]


@pytest.mark.parametrize(("name", "value"), EQUILIBRIA_CORRECT)
def test_equilibria_written_differently_are_correct(name: str, value: str) -> None:
    found = graded(name, "equilibria", value)
    assert (found.status, found.points) == ("correct", 1.0), found.message


EQUILIBRIA_WRONG = [
    (HOOP, "[0, pi]", f"theta = {ACOS} is missing", 0.5),
    (HOOP, f'[0, pi, "pi/2", "{ACOS}", "-{ACOS}"]', "theta = pi/2 is not an equilibrium", 0.8),
    ("coupled_pendulums", "[{theta1: 0, theta2: 0}, {theta1: 0, theta2: pi}, {theta1: pi, theta2: 0}, "
                          "{theta1: pi, theta2: pi}, {theta1: pi/2, theta2: 0}]",
     "theta1 = pi/2, theta2 = 0 is not an equilibrium", 0.8),
    ("two_masses_spring", '[{x1: "x2 + L0"}]', "x1 = -L0 + x2 is missing", 0.0),
    ("coupled_pendulums", "[0, pi]", "a bare value", 0.0),
    (HOOP, f'[{{value: 0}}, {{value: pi}}, {{value: "{ACOS}"}}, {{value: "pi/2"}}]', f"theta = -{ACOS} is missing",
     0.6),
]


@pytest.mark.parametrize(("name", "value", "said", "points"), EQUILIBRIA_WRONG)
def test_equilibria_missing_or_extra_are_incorrect_and_named(name: str, value: str, said: str, points: float) -> None:
    found = graded(name, "equilibria", value)
    assert found.status == "incorrect"
    assert found.mistake is None
    assert said in found.message
    assert found.points == pytest.approx(points)


# -- frequencies

FREQUENCIES_CORRECT = [
    (HOOP, '["g/R - Omega**2", "Omega**2 - g**2/(Omega**2*R**2)"]'),
    (HOOP, '["Omega**2*(1 - g**2/(Omega**4*R**2))", "sqrt(g/R - Omega**2)", "Omega**2 - g**2/(Omega**2*R**2)"]'),
    ("coupled_pendulums", '["g/l + 2*k/m", "g/l"]'),
    ("coupled_pendulums", '["sqrt(g/l)", "sqrt((g*m + 2*k*l)/(m*l))"]'),              # ω
    ("two_masses_spring", '["k*(m1 + m2)/(m1*m2)"]'),                                   # the zero ω² left out
    ("two_masses_spring", '[0, "k/m1 + k/m2"]'),
    ("hole_table", '["3*g*m2/((m1 + m2)*(p_theta**2/(g*m1*m2))**(1/3))"]'),
]


@pytest.mark.parametrize(("name", "value"), FREQUENCIES_CORRECT)
def test_frequencies_written_differently_are_correct(name: str, value: str) -> None:
    found = graded(name, "frequencies", value)
    assert (found.status, found.points) == ("correct", 1.0), found.message


FREQUENCIES_WRONG = [
    (HOOP, '["g/(m*R) - Omega**2/m", "Omega**2 - g**2/(Omega**2*R**2)"]', "missing_factor", "1/m times"),
    (HOOP, '["Omega**2 - g/R", "Omega**2 - g**2/(Omega**2*R**2)"]', "sign_error", "opposite sign"),
    (HOOP, '["g/R + Omega**2", "Omega**2 - g**2/(Omega**2*R**2)"]', None, "is not a squared frequency"),
    ("coupled_pendulums", '["g/l"]', None, "g/l + 2*k/m is missing"),
    ("coupled_pendulums", '["g/l", "g/l + 2*k/m", "g/l - 2*k/m"]', None, "is not a squared frequency"),
]


@pytest.mark.parametrize(("name", "value", "mistake", "said"), FREQUENCIES_WRONG)
def test_wrong_frequencies_are_incorrect(name: str, value: str, mistake: str | None, said: str) -> None:
    found = graded(name, "frequencies", value)
    assert (found.status, found.mistake) == ("incorrect", mistake), found.message
    assert said in found.message


def test_omega_refused_when_the_key_asks_for_squares() -> None:
    found = graded("coupled_pendulums", "frequencies", '["sqrt(g/l)", "g/l + 2*k/m"]', form="squared")
    assert found.status == "incorrect"
    assert "this is ω" in found.message
    assert found.points == pytest.approx(0.5)


# -- hamiltonian

HAMILTONIAN_CORRECT = [
    (HOOP, f'"{H_HOOP}"'),
    (HOOP, '"(p_theta/R)**2/(2*m) - m*R*(g*cos(theta) + Omega**2*R*(1 - cos(theta)**2)/2) + 7"'),  # a constant
    ("hole_table", '"p_r**2/(2*(m1 + m2)) + p_theta**2/(2*m1*r**2) + m2*g*r"'),
    ("hole_table", '"p_r**2/(2*(m1 + m2)) + p_theta**2/(2*m1*r**2) + m2*g*(r - l)"'),
    ("coupled_pendulums", '"(p_theta1**2 + p_theta2**2)/(2*m*l**2) - m*g*l*(cos(theta1) + cos(theta2)) '
                          '+ k*l**2*(sin(theta1) - sin(theta2))**2/2"'),
    ("two_masses_spring", '"p_x1**2/(2*m1) + p_x2**2/(2*m2) + k*(x2 - x1 - L0)**2/2"'),
]


@pytest.mark.parametrize(("name", "value"), HAMILTONIAN_CORRECT)
def test_hamiltonians_written_differently_are_correct(name: str, value: str) -> None:
    found = graded(name, "hamiltonian", value)
    assert (found.status, found.points) == ("correct", 1.0), found.message


HAMILTONIAN_WRONG = [
    # H with −V
    (HOOP, '"p_theta**2/(2*m*R**2) + m*g*R*cos(theta) - m*R**2*Omega**2*sin(theta)**2/2"', "wrong_potential_sign"),
    # T + V written in p, where H = T2 − T0 + V (the hoop turns)
    (HOOP, '"p_theta**2/(2*m*R**2) - m*g*R*cos(theta) + m*R**2*Omega**2*sin(theta)**2/2"', "sign_error"),
    # p²/m: the kinetic part doubled
    (HOOP, '"p_theta**2/(m*R**2) - m*g*R*cos(theta) - m*R**2*Omega**2*sin(theta)**2/2"', "missing_factor"),
    # the frame's motion left out: −T0 missing
    (HOOP, '"p_theta**2/(2*m*R**2) - m*g*R*cos(theta)"', "missing_kinetic_term"),
    ("hole_table", '"-p_r**2/(2*(m1 + m2)) - p_theta**2/(2*m1*r**2) - m2*g*r"', "sign_error"),
    ("two_masses_spring", '"p_x1**2/(2*m1) + p_x2**2/(2*m2) - k*(x2 - x1 - L0)**2/2"', "wrong_potential_sign"),
    ("hole_table", '"p_r**2/(2*m1) + p_theta**2/(2*m1*r**2) + m2*g*r"', None),
]


@pytest.mark.parametrize(("name", "value", "mistake"), HAMILTONIAN_WRONG)
def test_wrong_hamiltonians_are_incorrect_and_named(name: str, value: str, mistake: str | None) -> None:
    found = graded(name, "hamiltonian", value)
    assert (found.status, found.mistake) == ("incorrect", mistake), found.message


def test_hamiltonian_in_the_momenta_of_other_coordinates_is_said() -> None:
    """The hole table's H written with z (the hanging mass's height) and p_z is a Hamiltonian too, but not in the
    key's momenta (p_r, p_theta): incorrect, and the message says which momenta to use (it said 'not equivalent',
    with a state in r, theta, z)."""
    found = graded("hole_table", "hamiltonian", '"p_z**2/(2*(m1 + m2)) + p_theta**2/(2*m1*(z + l)**2) + m2*g*z"')
    assert found.status == "incorrect"
    assert "written in p_theta, p_z: the key's H is in the momenta of its minimal coordinates (p_r, p_theta)" in (
        found.message)


def test_hamiltonian_in_the_velocities_is_said() -> None:
    found = graded("two_masses_spring", "hamiltonian", '"m1*x1_dot**2/2 + m2*x2_dot**2/2 + k*(x2 - x1 - L0)**2/2"')
    assert found.status == "incorrect"
    assert "written with velocities" in found.message


def test_hamiltonian_follows_from_the_students_own_lagrangian() -> None:
    """L with the centrifugal term's sign flipped gives H = T2 + T0 + V: the H of that L follows."""
    own = "m*R**2*(theta_dot**2 - Omega**2*sin(theta)**2)/2 + m*g*R*cos(theta)"
    wrong_h = '"p_theta**2/(2*m*R**2) - m*g*R*cos(theta) + m*R**2*Omega**2*sin(theta)**2/2"'
    found = graded(HOOP, "hamiltonian", wrong_h, extra=f'  lagrangian: "{own}"\n')
    assert found.status == "follows", found.message
    assert found.points == 1.0


# -- reading


def test_list_items_that_are_not_expressions_are_unreadable() -> None:
    found = graded("coupled_pendulums", "frequencies", "[[1, 2]]")
    assert found.status == "unreadable"
    found = graded("coupled_pendulums", "equilibria", "[{theta3: 0}]")
    assert found.status == "unreadable"
    assert "theta3" in found.message


@pytest.mark.parametrize("text", ["- a\n- b\n", "just text\n", "# nothing\n"])
def test_a_file_that_is_not_a_mapping_is_told_about_submissions(text: str) -> None:
    problem, _ = key("two_masses_spring")
    with pytest.raises(SpecError) as raised:
        read_text(text, problem, "s.yaml")
    message = str(raised.value)
    assert "problem file" not in message
    assert "submission" in message
    assert "'student" in message
