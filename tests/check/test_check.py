"""`lagsolve.check`: verdicts on right, equivalent and deliberately wrong answers, and on every shipped problem."""

from __future__ import annotations

import dataclasses
import functools
from pathlib import Path

import pytest
import sympy

from lagsolve.check.compare import (
    ABSENT,
    CONSERVED,
    CONVENTION,
    DIFFERS,
    FACTOR,
    MISMATCH,
    NOT_CONSERVED,
    NOT_DERIVED,
    NUMERIC,
    OFFSET,
    OK,
    OPPOSITE_SIGN,
    RELEASED,
    SIGN_DEPENDENT,
    SYMBOLIC,
    TRIVIAL,
    UNCHECKED,
    UNDEFINED,
    WARNING,
    CheckReport,
    Verdict,
    check,
)
from lagsolve.mechanics.derivation import Derivation, derive
from lagsolve.mechanics.results import Canonical, Contract
from lagsolve.problem.load import load_text
from mechanics_support import derived_file, shipped

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = [ROOT / "problems" / f"{name}.yaml" for name in shipped()]


@functools.cache
def variant(name: str, expected: str) -> Derivation:
    """``problems/<name>.yaml`` with its ``expected:`` section replaced, derived once per session."""
    head = (ROOT / "problems" / f"{name}.yaml").read_text().split("\nexpected:")[0]
    tail = (ROOT / "problems" / f"{name}.yaml").read_text().split("\nsimulation:")[1]
    return derive(load_text(f"{head}\nexpected:\n{expected}\nsimulation:{tail}", f"{name}_variant.yaml"))


def verdicts(name: str, expected: str) -> dict[str, Verdict]:
    report = check(variant(name, expected))
    return {f"{v.quantity}.{v.name}": v for v in report.verdicts}


# the bead's answers (ESM 3124 HW6), written out once
X_ACC = "-Derivative(f(x), x)*(Derivative(f(x), (x, 2))*x_dot**2 + g)/(1 + Derivative(f(x), x)**2)"
LAMBDA = "m*(Derivative(f(x), (x, 2))*x_dot**2 + g)/(1 + Derivative(f(x), x)**2)"
FORCE = "m*(Derivative(f(x), (x, 2))*x_dot**2 + g)/sqrt(1 + Derivative(f(x), x)**2)"


# -- right answers, written differently ------------------------------------------------------------


def test_textbook_answers_pass_symbolically() -> None:
    """The bead's answers as the homework writes them are ok, found by symbolic simplification."""
    found = verdicts("bead", f'  accelerations: {{x: "{X_ACC}"}}\n  multipliers: {{wire: "{LAMBDA}"}}\n')
    assert found["accelerations.x"].status == OK and found["accelerations.x"].reason == SYMBOLIC
    assert found["multipliers.wire"].status == OK


def test_differently_written_answers_pass() -> None:
    """Expanded forms, the dependent coordinate y in place of f(x), and λ in a force are all accepted."""
    expected = (
        '  accelerations:\n'
        '    x: "-Derivative(f(x), x)*g/(1 + Derivative(f(x), x)**2)'
        ' - x_dot**2*Derivative(f(x), x)*Derivative(f(x), (x, 2))/(1 + Derivative(f(x), x)**2)"\n'
        '    y: "(y - f(x))*g + (x_dot**2*Derivative(f(x), (x, 2)) - g*Derivative(f(x), x)**2)'
        '/(1 + Derivative(f(x), x)**2)"\n'
        '  constraint_forces:\n'
        '    wire: {magnitude: "Abs(lambda_wire)*sqrt(1 + Derivative(f(x), x)**2)",'
        ' vector: ["-lambda_wire*Derivative(f(x), x)", "lambda_wire + 0*(y - f(x))"]}\n'
    )
    found = verdicts("bead", expected)
    assert {k: v.status for k, v in found.items()} == {
        "accelerations.x": OK, "accelerations.y": OK, "constraint_forces.wire": OK, "constraint_forces.wire.vector": OK}


def test_trigonometric_identities_pass() -> None:
    """A cone answer written with cot and 1/(1 + cot²) instead of sin² is ok."""
    found = verdicts("cone", '  accelerations:\n    r: "(r*phi_dot**2 - g*cot(alpha))/(1 + cot(alpha)**2)"\n')
    assert found["accelerations.r"].status == OK


def test_answer_that_holds_only_on_the_surface_is_ok() -> None:
    """An answer that uses x² + y² = l² and x ẋ + y ẏ = 0 agrees only on the constraint surface, which is enough."""
    found = verdicts("pendulum_cartesian", (
        '  accelerations:\n'
        '    x: "x*(g*y - x_dot**2 - y_dot**2)/l**2 + (x**2 + y**2 - l**2)*x_dot**3 + (x*x_dot + y*y_dot)*g"\n'))
    verdict = found["accelerations.x"]
    assert (verdict.status, verdict.reason) == (OK, NUMERIC) and verdict.states >= 20


def test_velocity_constraint_is_used() -> None:
    """A knife-edge answer plus a multiple of the skate's velocity form is ok: states satisfy that constraint."""
    found = verdicts("knife_edge", (
        '  accelerations:\n'
        '    theta: "-theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))/l'
        ' + 7*(-sin(theta)*x_dot + cos(theta)*y_dot)"\n'))
    assert found["accelerations.theta"].status == OK


# -- wrong answers, each kind named --------------------------------------------------------------


def test_flipped_sign_is_named() -> None:
    """An acceleration with the wrong sign is a mismatch named 'opposite sign', with a state where they differ."""
    verdict = verdicts("bead", f'  accelerations: {{x: "-({X_ACC})"}}\n')["accelerations.x"]
    assert (verdict.status, verdict.reason) == (MISMATCH, OPPOSITE_SIGN)
    witness = verdict.witness
    assert witness is not None
    assert witness.expected[0] == pytest.approx(-witness.derived[0]) and abs(witness.derived[0]) > 0
    assert [name for name, _ in witness.functions] == ["f"]


def test_opposite_multiplier_convention_is_named() -> None:
    """λ = −derived is reported as the opposite sign convention, and that it is the only difference."""
    verdict = verdicts("bead", f'  multipliers: {{wire: "-{LAMBDA}"}}\n')["multipliers.wire"]
    assert (verdict.status, verdict.reason) == (MISMATCH, CONVENTION)
    assert verdict.factor == -1 and "only difference" in verdict.note


def test_opposite_convention_with_a_factor() -> None:
    """λ = −2·derived is the opposite convention together with a factor 2."""
    verdict = verdicts("atwood", '  multipliers: {string: "-4*m1*m2*g/(m1 + m2)"}\n')["multipliers.string"]
    assert (verdict.status, verdict.reason, verdict.factor) == (MISMATCH, CONVENTION, -2)


def test_missing_numeric_factor_is_named() -> None:
    """An acceleration off by a factor 2 is a mismatch whose factor is 1/2."""
    verdict = verdicts("bead", f'  accelerations: {{x: "({X_ACC})/2"}}\n')["accelerations.x"]
    assert (verdict.status, verdict.reason, verdict.factor) == (MISMATCH, FACTOR, sympy.Rational(1, 2))


def test_missing_parameter_factor_is_named() -> None:
    """A multiplier without its mass is off by the factor 1/m."""
    found = verdicts("bead", f'  multipliers: {{wire: "({LAMBDA})/m"}}\n')
    verdict = found["multipliers.wire"]
    m = variant("bead", f'  multipliers: {{wire: "({LAMBDA})/m"}}\n').problem.symbols["m"]
    assert (verdict.status, verdict.reason, verdict.factor) == (MISMATCH, FACTOR, 1 / m)


def test_magnitude_without_abs_is_a_warning_with_its_condition() -> None:
    """The homework's magnitude without Abs holds only where g + ẋ² f''(x) > 0: a warning that names it."""
    derivation = variant("bead", f'  constraint_forces: {{wire: "{FORCE}"}}\n')
    verdict = {v.name: v for v in check(derivation).verdicts}["wire"]
    assert (verdict.status, verdict.reason) == (WARNING, SIGN_DEPENDENT)
    x, xd, g = (derivation.problem.symbols[n] for n in ("x", "x_dot", "g"))
    f = derivation.problem.functions[0].function
    assert isinstance(verdict.condition, sympy.StrictGreaterThan)
    assert sympy.simplify(verdict.condition.lhs - (g + xd**2 * sympy.Derivative(f(x), (x, 2)))) == 0
    assert 0 < verdict.agreeing < verdict.states


def test_answer_that_ignores_the_constraint_is_named() -> None:
    """The free-fall answer ÿ = −g for the Cartesian pendulum is the motion with the rod released."""
    verdict = verdicts("pendulum_cartesian", '  accelerations: {y: "-g"}\n')["accelerations.y"]
    assert (verdict.status, verdict.reason) == (MISMATCH, RELEASED) and "'rod'" in verdict.note


def test_answer_undefined_on_the_surface_is_a_mismatch() -> None:
    """An answer that divides by the constraint (y - f(x) = 0 on the wire) is undefined there: a mismatch."""
    verdict = verdicts("bead", f'  accelerations: {{x: "{X_ACC} + x/(y - f(x))"}}\n')["accelerations.x"]
    assert (verdict.status, verdict.reason) == (MISMATCH, UNDEFINED)


def test_wrong_derivative_of_a_declared_function_differs() -> None:
    """f'(x) where f''(x) belongs is told apart: random functions have independent derivatives."""
    wrong = X_ACC.replace("Derivative(f(x), (x, 2))", "Derivative(f(x), x)")
    verdict = verdicts("bead", f'  accelerations: {{x: "{wrong}"}}\n')["accelerations.x"]
    assert (verdict.status, verdict.reason) == (MISMATCH, DIFFERS)
    assert verdict.agreeing < verdict.states


def test_witness_satisfies_the_constraints() -> None:
    """The state shown for a mismatch lies on the constraint surface (the rod's length and its velocity form)."""
    verdict = verdicts("pendulum_cartesian", '  multipliers: {rod: "m*g"}\n')["multipliers.rod"]
    assert verdict.witness is not None
    values = dict(verdict.witness.values)
    assert values["x"] ** 2 + values["y"] ** 2 == pytest.approx(values["l"] ** 2)
    assert values["x"] * values["x_dot"] + values["y"] * values["y_dot"] == pytest.approx(0, abs=1e-12)


# -- analysis results ---------------------------------------------------------------------------------

HOLE_ANALYSIS = """  reduced:
    accelerations: {r: "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)"}
  conserved:
    p_theta: "m1*r**2*theta_dot"
    energy: "(m1 + m2)*r_dot**2/2 + m1*r**2*theta_dot**2/2 + m2*g*r"
  effective_potential:
    coordinate: r
    expression: "m2*g*r + p_theta**2/(2*m1*r**2)"
    equilibria:
      - {value: "(p_theta**2/(m1*m2*g))**(1/3)", frequency: "sqrt(3*m2*g/((m1 + m2)*(p_theta**2/(m1*m2*g))**(1/3)))"}
"""


def test_conserved_quantity_with_another_zero_level_is_ok() -> None:
    """An energy with the potential measured from another level is ok, and the report names the offset."""
    found = verdicts("hole_table", HOLE_ANALYSIS)
    energy = found["conserved.energy"]
    assert (energy.status, energy.reason) == (OK, OFFSET)
    symbols = variant("hole_table", HOLE_ANALYSIS).problem.symbols
    assert sympy.simplify(energy.offset - symbols["g"] * symbols["l"] * symbols["m2"]) == 0
    assert found["conserved.p_theta"].status == OK
    assert found["effective_potential.expression"].status == OK
    assert found["reduced.r"].status == OK


def test_equilibrium_value_and_frequency_are_checked() -> None:
    """The circular orbit r0³ = p_θ²/(m1 m2 g) and its radial frequency agree with the derivation."""
    found = verdicts("hole_table", HOLE_ANALYSIS)
    assert found["effective_potential.equilibria[0].value"].status == OK
    assert found["effective_potential.equilibria[0].frequency"].status == OK


def test_wrong_equilibrium_is_a_mismatch() -> None:
    """An equilibrium that is not among the derived ones is reported with the ones lagsolve finds."""
    found = verdicts("hole_table", (
        '  effective_potential:\n    coordinate: r\n    equilibria:\n      - {value: "p_theta**2/(m1*m2*g)"}\n'))
    verdict = found["effective_potential.equilibria[0].value"]
    assert (verdict.status, verdict.reason) == (MISMATCH, ABSENT) and "it finds" in verdict.note


def test_offset_in_an_acceleration_is_a_mismatch() -> None:
    """A constant added to an acceleration is a mismatch (only potentials and integrals may shift)."""
    verdict = verdicts("hole_table", '  accelerations: {r: "(m1*r*theta_dot**2 - m2*g)/(m1 + m2) + g"}\n')[
        "accelerations.r"]
    assert (verdict.status, verdict.reason) == (MISMATCH, OFFSET)


def test_unknown_conserved_quantity_is_a_mismatch() -> None:
    """Claiming p_r is conserved when r is not cyclic is a mismatch naming what is conserved."""
    verdict = verdicts("hole_table", '  conserved: {p_r: "m1*r_dot"}\n')["conserved.p_r"]
    assert verdict.status == MISMATCH and "p_theta" in verdict.note


def test_analysis_not_derived_yet_is_unchecked() -> None:
    """Without analysis results the expected reduced and V_eff answers are 'not derived', not failures; a claimed
    conserved quantity is still checked by its rate along the equations of motion."""
    bare = dataclasses.replace(variant("hole_table", HOLE_ANALYSIS), contract=Contract(), canonical=Canonical())
    report = check(bare)
    conserved = [v for v in report.verdicts if v.quantity == "conserved"]
    rest = [v for v in report.verdicts if v.quantity != "conserved"]
    assert {v.status for v in rest} == {UNCHECKED}
    assert all(v.reason == NOT_DERIVED and "not derived yet" in v.note for v in rest)
    assert [(v.name, v.status, v.reason) for v in conserved] == [("p_theta", OK, CONSERVED), ("energy", OK, CONSERVED)]
    assert report.passed


BOWL_CLAIMS = """  conserved:
    angular_momentum: "m*(x*y_dot - y*x_dot)"
    half: "m*x*y_dot"
"""


def test_claimed_constant_that_lagsolve_does_not_find_is_confirmed_by_its_rate() -> None:
    """The bowl's m(x ẏ − y ẋ) is no cyclic momentum of (x, y, z), yet check confirms it: dC/dt = 0 on the bowl."""
    derivation = variant("bowl", BOWL_CLAIMS)
    assert "angular_momentum" not in (derivation.conserved or {})
    verdict = verdicts("bowl", BOWL_CLAIMS)["conserved.angular_momentum"]
    assert (verdict.status, verdict.reason) == (OK, CONSERVED)
    assert "does not find" in verdict.note


def test_claimed_constant_that_changes_is_a_mismatch_with_a_state() -> None:
    """m x ẏ on the bowl is not conserved: a mismatch whose witness lies on the bowl and has dC/dt ≠ 0 there."""
    verdict = verdicts("bowl", BOWL_CLAIMS)["conserved.half"]
    assert (verdict.status, verdict.reason) == (MISMATCH, NOT_CONSERVED)
    assert verdict.witness is not None and verdict.agreeing == 0
    values = dict(verdict.witness.values)
    assert values["z"] == pytest.approx((values["x"] ** 2 + values["y"] ** 2) / (2 * values["a"]))
    (rate,) = verdict.witness.expected
    assert rate is not None and abs(rate) > 1e-6
    # independently, Newton on the bowl (normal force along (-x/a, -y/a, 1)): d(m x y')/dt = m(x' y' + x y'')
    x, y, xd, yd, m, g, a = (values[k] for k in ("x", "y", "x_dot", "y_dot", "m", "g", "a"))
    n_over_m = (g + (xd**2 + yd**2) / a) / (1 + (x**2 + y**2) / a**2)  # N/m along the unnormalized normal
    ydd = -n_over_m * y / a
    assert rate.real == pytest.approx(m * (xd * yd + x * ydd), rel=1e-9)


def test_claimed_constant_is_checked_numerically_on_a_surface_no_coordinate_solves() -> None:
    """On the Cartesian pendulum the energy written by hand, m(ẋ² + ẏ²)/2 + m g y, is conserved only on the
    constraint surface (its rate along lagsolve's equations is m(xẋ + yẏ)(g y − v²)/(x² + y²)): ok, by numeric
    states. x² + y², constant on the surface, and a constant of the parameters are true claims that say nothing: a
    warning (they passed as conserved); x ẏ is a mismatch."""
    found = verdicts("pendulum_cartesian", '  conserved: {mechanical: "m*(x_dot**2 + y_dot**2)/2 + m*g*y", '
                                           'radius: "x**2 + y**2", none: "m*g + l", moment: "x*y_dot"}\n')
    mechanical = found["conserved.mechanical"]
    assert (mechanical.status, mechanical.reason) == (OK, CONSERVED)
    assert mechanical.states >= 8
    for name in ("radius", "none"):
        verdict = found[f"conserved.{name}"]
        assert (verdict.status, verdict.reason) == (WARNING, TRIVIAL), name
        assert "constant of the parameters or a constraint" in verdict.note
    assert (found["conserved.moment"].status, found["conserved.moment"].reason) == (MISMATCH, NOT_CONSERVED)


def test_a_conserved_quantity_with_a_large_constant_or_a_small_factor_is_not_trivial() -> None:
    """The energy plus 1e14 m g l, or times 1e-14, still varies from state to state as much as the energy does (each
    was flagged 'trivially constant' when states were compared to 1e-12 absolute); x ẋ + y ẏ, zero on the surface
    up to rounding, is trivial."""
    energy = "m*(x_dot**2 + y_dot**2)/2 + m*g*y"
    found = verdicts("pendulum_cartesian", f'  conserved: {{big: "{energy} + 1e14*m*g*l", small: "1e-14*({energy})", '
                                           'rate: "x*x_dot + y*y_dot"}\n')
    for name in ("big", "small"):
        assert (found[f"conserved.{name}"].status, found[f"conserved.{name}"].reason) == (OK, CONSERVED), name
    assert (found["conserved.rate"].status, found["conserved.rate"].reason) == (WARNING, TRIVIAL)


def test_a_trivial_constant_is_not_flagged_without_a_degree_of_freedom() -> None:
    """Where every state of a set of parameters is the same (no degree of freedom), a constant says as much as any
    quantity: not flagged."""
    source = """name: fixed bead
parameters:
  m: {description: mass}
  g: {description: gravity}
  a: {description: height}
coordinates:
  x: {description: position}
  y: {description: height}
particles:
  bead: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  post: {holonomic: x - a, on: bead}
  floor: {holonomic: y - a, on: bead}
expected:
  conserved: {c: "m*g*a"}
"""
    report = check(derive(load_text(source, "fixed.yaml")))
    (verdict,) = [v for v in report.verdicts if v.quantity == "conserved" and v.name == "c"]
    assert verdict.reason != TRIVIAL and verdict.status == OK


def test_analysis_given_as_text_is_read_safely() -> None:
    """Analysis results in their JSON text form are read through the safe parser and compared."""
    derivation = variant("hole_table", HOLE_ANALYSIS)
    as_text = dataclasses.replace(derivation, contract=dataclasses.replace(
        derivation.contract, conserved={k: sympy.sstr(v) for k, v in (derivation.conserved or {}).items()}))
    found = {f"{v.quantity}.{v.name}": v for v in check(as_text).verdicts}
    assert found["conserved.p_theta"].status == OK


# -- reports ------------------------------------------------------------------------------------------


def test_report_counts_and_passes() -> None:
    """A report counts its verdicts; warnings pass, a mismatch does not."""
    report = check(variant("bead", f'  constraint_forces: {{wire: "{FORCE}"}}\n  accelerations: {{x: "-({X_ACC})"}}\n'))
    assert isinstance(report, CheckReport)
    assert (report.count(WARNING), report.count(MISMATCH), report.passed) == (1, 1, False)
    assert report.coordinates == ("x", "y") and report.source == "bead_variant.yaml"


def test_same_seed_same_states() -> None:
    """Checks are reproducible: the same seed reports the same state for a mismatch."""
    derivation = variant("bead", f'  accelerations: {{x: "-({X_ACC})"}}\n')
    first, second = check(derivation, seed=3), check(derivation, seed=3)
    assert first.verdicts[0].witness == second.verdicts[0].witness


@pytest.mark.slow
@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_every_shipped_answer_is_ok(path: Path) -> None:
    """Every `expected:` answer of every problem in problems/ gets the verdict ok (`lagsolve check` passes)."""
    report = check(derived_file(path.stem))
    assert [(v.quantity, v.name, v.status, v.note) for v in report.verdicts if v.status != OK] == []


# -- steady motions (expected: steady_motions) ------------------------------------------------------------

TOP_STEADY = """  steady_motions:
    coordinate: theta
    rate: phi
    values: [{values}]
    stable: {stable}
    frequency: "{frequency}"
"""
GOLDSTEIN = ('"p_psi*(1 - sqrt(1 - 4*m*g*l*(I1 + m*l**2)*cos(theta)/p_psi**2))/(2*(I1 + m*l**2)*cos(theta))", '
             '"p_psi*(1 + sqrt(1 - 4*m*g*l*(I1 + m*l**2)*cos(theta)/p_psi**2))/(2*(I1 + m*l**2)*cos(theta))"')
NUTATION = "sqrt((p_psi/(I1 + m*l**2) - 2*phi_dot*cos(theta))**2 + phi_dot**2*sin(theta)**2)"


def _steady(values: str = GOLDSTEIN, stable: str = "true", frequency: str = NUTATION) -> dict[str, Verdict]:
    return verdicts("heavy_top", TOP_STEADY.format(values=values, stable=stable, frequency=frequency))


def test_steady_precession_in_goldsteins_form_passes() -> None:
    """Goldstein's roots (in either order) and the nutation frequency, written with g or without, are ok."""
    found = _steady()
    assert [found[f"steady_motions.{k}"].status for k in ("values", "frequency", "stable")] == [OK, OK, OK]
    swapped = ", ".join(reversed(GOLDSTEIN.split(", ")))
    # the same omega^2 with the condition used the other way, I1' phi_dot^2 cos = p_psi phi_dot - m g l:
    # (p_psi/I1')^2 - 4 m g l cos/I1' + phi_dot^2 sin^2
    with_g = "sqrt(p_psi**2/(I1 + m*l**2)**2 - 4*m*g*l*cos(theta)/(I1 + m*l**2) + phi_dot**2*sin(theta)**2)"
    found = _steady(values=swapped, frequency=with_g)
    assert found["steady_motions.values"].status == OK and found["steady_motions.frequency"].status == OK


def test_wrong_steady_answers_are_mismatches() -> None:
    """A root without the factor 2, the nutation frequency without the 2 in 2 phi_dot cos(theta), and 'unstable'
    are each a mismatch."""
    half = GOLDSTEIN.replace("/(2*(I1", "/((I1")
    assert _steady(values=half)["steady_motions.values"].status == MISMATCH
    assert _steady(frequency=NUTATION.replace("2*phi_dot", "phi_dot"))["steady_motions.frequency"].status == MISMATCH
    verdict = _steady(stable="false")["steady_motions.stable"]
    assert (verdict.status, verdict.reason) == (MISMATCH, DIFFERS)


def test_steady_motions_with_another_rate_are_a_mismatch_with_a_reason() -> None:
    """Claiming psi as the rate when lagsolve takes phi says so instead of comparing unlike things."""
    found = verdicts("heavy_top", TOP_STEADY.format(values=GOLDSTEIN, stable="true", frequency=NUTATION).replace(
        "rate: phi", "rate: psi"))
    verdict = found["steady_motions.values"]
    assert verdict.status == MISMATCH and "takes phi as the rate" in verdict.note


def test_steady_motions_where_there_are_none_are_unchecked() -> None:
    """The bead on the rotating hoop has no cyclic coordinate: an expected steady motion is not checked, and the
    note says why."""
    found = verdicts("bead_on_rotating_hoop", '  steady_motions: {coordinate: theta, rate: theta, values: ["0"]}\n')
    verdict = found["steady_motions.values"]
    assert verdict.status == UNCHECKED and "no coordinate is cyclic" in verdict.note
