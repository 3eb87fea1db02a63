"""`lagsolve check` on ``expected: normal_modes:`` (``lagsolve.check.modes``): right answers however written, and
deliberately wrong ones, each with the verdict it should get."""

from __future__ import annotations

import functools
from pathlib import Path

import sympy

from lagsolve.check.compare import ABSENT, DIFFERS, MISMATCH, OK, SYMBOLIC, UNCHECKED, WARNING, Verdict, check
from lagsolve.check.modes import AT_VALUES, INCOMPLETE, NOT_EQUILIBRIUM
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_text
from lagsolve.render.checks import check_table

ROOT = Path(__file__).resolve().parents[2]


@functools.cache
def _report(expected: str, spring: str = "2.0") -> tuple[Verdict, ...]:
    """problems/coupled_pendulums.yaml with ``expected:`` replaced (and the spring's value ``spring``), checked."""
    text = (ROOT / "problems" / "coupled_pendulums.yaml").read_text()
    head, tail = text.split("\nexpected:")[0], text.split("\nsimulation:")[1]
    tail = tail.replace("k: 2.0", f"k: {spring}")
    derivation = derive(load_text(f"{head}\nexpected:\n{expected}\nsimulation:{tail}", "pendulums.yaml"))
    return check(derivation).verdicts


def _by_name(verdicts: tuple[Verdict, ...]) -> dict[str, Verdict]:
    return {v.name.removeprefix("normal_modes"): v for v in verdicts if v.quantity == "normal_modes"}


def test_textbook_modes_however_written_are_ok() -> None:
    """ω² in any order and any form, shapes up to a factor (2, 2) and (-3, 3), an angle given as -π for π: ok."""
    found = _by_name(_report("""  normal_modes:
    - at: {theta1: 0, theta2: 0}
      stable: true
      squared_frequencies: ["(g*m + 2*k*l)/(m*l)", "g/l"]
      shapes: [[-3, 3], [2, 2]]
    - at: {theta1: -pi, theta2: -pi}
      stable: false
      squared_frequencies: ["-g/l", "2*k/m - g/l"]
"""))
    assert {v.status for v in found.values()} == {OK}
    assert found["[0].at"].reason == SYMBOLIC and found["[0].shapes[0]"].reason == SYMBOLIC
    assert len(found) == 10


def test_wrong_answers_are_mismatches() -> None:
    """A wrong ω² (k/m for 2k/m) is absent from lagsolve's, with them in the note, and its shape is then not
    checked; a shape that is no multiple of lagsolve's differs; a wrong stability differs; a point that is no
    equilibrium says so (F(q, 0) ≠ 0 there)."""
    found = _by_name(_report("""  normal_modes:
    - at: {theta1: 0, theta2: 0}
      stable: false
      squared_frequencies: ["g/l", "g/l + k/m"]
      shapes: [[1, 2], [1, -1]]
    - at: {theta1: "pi/2", theta2: 0}
"""))
    assert (found["[0].stable"].status, found["[0].stable"].reason) == (MISMATCH, DIFFERS)
    assert found["[0].squared_frequencies[0]"].status == OK
    assert (found["[0].shapes[0]"].status, found["[0].shapes[0]"].reason) == (MISMATCH, DIFFERS)
    wrong = found["[0].squared_frequencies[1]"]
    assert (wrong.status, wrong.reason) == (MISMATCH, ABSENT) and "g/l + 2*k/m" in wrong.note
    assert found["[0].shapes[1]"].status == UNCHECKED
    nowhere = found["[1].at"]
    assert (nowhere.status, nowhere.reason) == (MISMATCH, NOT_EQUILIBRIUM) and "F(q, 0)" in nowhere.note


def test_equilibria_found_numerically_are_checked_at_the_simulation_values() -> None:
    """With a stiff spring (k = 10 at the simulation values) the pendulums also rest bent towards each other,
    cos θ1 = -m g/(2 k l), θ2 = -θ1, found only numerically. By hand, K there is -k l² [[1 + s², c²], [c², 1 + s²]]
    (s, c the sine and cosine of θ1), so ω² = -2k/m in phase and -2k/m + m g²/(2 k l²) out of phase: ok, at the
    simulation values; a shape given wrongly is a mismatch there too."""
    bent = "acos(-g*m/(2*k*l))"
    found = _by_name(_report(f"""  normal_modes:
    - at: {{theta1: "{bent}", theta2: "-{bent}"}}
      stable: false
      squared_frequencies: ["-2*k/m", "-2*k/m + m*g**2/(2*k*l**2)"]
      shapes: [[1, 1], [1, 1]]
""", spring="10.0"))
    assert (found["[0].at"].status, found["[0].at"].reason) == (OK, AT_VALUES)
    assert found["[0].stable"].status == OK
    for k in (0, 1):
        assert (found[f"[0].squared_frequencies[{k}]"].status, found[f"[0].squared_frequencies[{k}]"].reason) == (
            OK, AT_VALUES)
    assert found["[0].shapes[0]"].status == OK
    assert found["[0].shapes[1]"].status == MISMATCH


def test_the_check_table_names_the_modes() -> None:
    """The terminal table labels each answer by its item, ω² and shape number."""
    text = (ROOT / "problems" / "coupled_pendulums.yaml").read_text()
    report = check(derive(load_text(text, "coupled_pendulums.yaml")))
    table = check_table(report)
    assert "✓ modes 1: ω² 2" in table and "✓ modes 1: shape 1" in table and report.passed


def test_a_list_that_leaves_out_a_mode_is_a_warning() -> None:
    """Only g/l of the two pendulums' ω² (g/l, g/l + 2k/m): true as far as it goes, and incomplete, a warning naming
    the one left out (it passed as ok). The full list has no such warning; a wrong ω² stays a mismatch only."""
    partial = """  normal_modes:
    - at: {theta1: 0, theta2: 0}
      squared_frequencies: ["g/l"]
"""
    found = _by_name(_report(partial))
    assert found["[0].squared_frequencies[0]"].status == OK
    left = found["[0].squared_frequencies"]
    assert (left.status, left.reason) == (WARNING, INCOMPLETE)
    assert "lists 1 of lagsolve's 2 non-zero squared frequencies" in left.note
    (missing,) = left.derived
    plain = missing.subs({s: sympy.Symbol(s.name) for s in missing.free_symbols})
    g, k, length, m = sympy.symbols("g k l m")
    assert sympy.simplify(plain - (g / length + 2 * k / m)) == 0
    text = (ROOT / "problems" / "coupled_pendulums.yaml").read_text()
    head, tail = text.split("\nexpected:")[0], text.split("\nsimulation:")[1]
    table = check_table(check(derive(load_text(f"{head}\nexpected:\n{partial}\nsimulation:{tail}", "p.yaml"))))
    assert "warning: lists 1 of lagsolve's 2" in table
    full = _by_name(_report("""  normal_modes:
    - at: {theta1: 0, theta2: 0}
      squared_frequencies: ["g/l", "g/l + 2*k/m"]
"""))
    assert "[0].squared_frequencies" not in full
    wrong = _by_name(_report("""  normal_modes:
    - at: {theta1: 0, theta2: 0}
      squared_frequencies: ["g/l + k/m"]
"""))
    assert "[0].squared_frequencies" not in wrong and wrong["[0].squared_frequencies[0]"].status == MISMATCH


def test_a_listed_zero_is_not_counted_as_a_non_zero_one() -> None:
    """Two free masses and a spring: ω² are 0 (the translation) and 2K/m. A list of only 0 leaves out 2K/m, and
    says it lists 0 of lagsolve's 1 non-zero ω² (it said '1 of lagsolve's 2 non-zero', counting the 0)."""
    text = """name: two free masses
parameters: {m: mass, K: stiffness}
coordinates: [x1, x2]
particles:
  a: {mass: m, position: [x1, 0]}
  b: {mass: m, position: [x2, 0]}
potential: K*(x1 - x2)**2/2
expected:
  normal_modes:
    - {at: {x1: x2}, squared_frequencies: ["0"]}
"""
    found = _by_name(check(derive(load_text(text, "free.yaml"))).verdicts)
    left = found["[0].squared_frequencies"]
    assert (left.status, left.reason) == (WARNING, INCOMPLETE)
    assert "lists 0 of lagsolve's 1 non-zero squared frequencies here; it leaves out 2*K/m" in left.note


def test_a_squared_frequency_listed_twice_says_so() -> None:
    """g/l listed twice (lagsolve has g/l once and g/l + 2k/m): the second is a mismatch that says it repeats one
    already matched (it said that none of lagsolve's equals it, g/l among them)."""
    found = _by_name(_report("""  normal_modes:
    - at: {theta1: 0, theta2: 0}
      squared_frequencies: ["g/l", "g/l"]
"""))
    assert found["[0].squared_frequencies[0]"].status == OK
    twice = found["[0].squared_frequencies[1]"]
    assert twice.status == MISMATCH and "which an earlier item matched already: lagsolve has it once" in twice.note


def test_a_numeric_equilibrium_given_to_float_digits_is_not_called_no_equilibrium() -> None:
    """y = cos y has the root 0.7390851332151607 (here k(y − cos y) = 0, with a free pair beside it, x1 = x2): given
    to those digits (read as that exact decimal), F(q, 0) is zero there up to rounding, not 'no equilibrium' (a
    mismatch); and a list found only numerically (from starting points, one point of the continuum) is not complete,
    so the point it does not list is 'not checked', not a mismatch."""
    from lagsolve.check.compare import NOT_DERIVED

    text = """name: Free pair and a transcendental well
parameters: {m: mass, K: stiffness, k: well}
coordinates: [x1, x2, y]
particles:
  a: {mass: m, position: [x1, 0]}
  b: {mass: m, position: [x2, 0]}
  c: {mass: m, position: [0, y]}
potential: K*(x1 - x2)**2/2 + k*(y**2/2 - sin(y))
expected:
  normal_modes:
    - {at: {x1: x2, y: 0.7390851332151607}}
    - {at: {x1: x2, y: 0.7390851}}
simulation:
  values: {m: 1.0, K: 0.5, k: 2.0}
  initial: {x1: 0.1, x2: 0, y: 0.7}
  t_end: 1
"""
    found = {v.name: v for v in check(derive(load_text(text, "well.yaml"))).verdicts}
    assert (found["normal_modes[0].at"].status, found["normal_modes[0].at"].reason) == (UNCHECKED, NOT_DERIVED)
    assert "F(q, 0) = 0 there" in found["normal_modes[0].at"].note
    assert (found["normal_modes[1].at"].status, found["normal_modes[1].at"].reason) == (MISMATCH, NOT_EQUILIBRIUM)
