"""Units of results (mechanics/units/result_units.py): accelerations, multipliers by their constraint, forces."""

from __future__ import annotations

from pathlib import Path

import pytest

from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.mechanics.units.dimensions import algebra
from lagsolve.mechanics.units.result_units import result_units, unit_text
from lagsolve.problem.load import load_problem
from lagsolve.problem.units import unit_of

PROBLEMS = Path(__file__).resolve().parents[3] / "problems"
SHIPPED_WITH_UNITS = sorted(p.name for p in PROBLEMS.glob("*.yaml") if "unit:" in p.read_text(encoding="utf-8"))


@pytest.mark.parametrize(("name", "expected"), [
    ("bead.yaml", {"x": "m/s^2"}),
    ("double_pendulum.yaml", {"theta1": "rad/s^2"}),
    ("hole_table.yaml", {"r": "m/s^2", "theta": "rad/s^2"}),
])
def test_acceleration_units(name: str, expected: dict[str, str]) -> None:
    """An acceleration has its coordinate's unit over s^2 (rad/s^2 for an angle)."""
    problem = load_problem(PROBLEMS / name)
    units = result_units(problem, matrix_form(problem, display=False).model.kinetic)
    assert units is not None
    for q, unit in expected.items():
        assert units.accelerations[q] == unit


@pytest.mark.parametrize(("name", "multipliers", "force", "generalized"), [
    ("bead.yaml", {"wire": "N"}, "N", {"x": "N", "y": "N"}),  # y - f(x) is in m: λ = J/m
    ("pendulum_cartesian.yaml", {"rod": "N/m"}, "N", {"x": "N"}),  # (x^2 + y^2 - l^2)/2 is in m^2
    ("rolling_incline.yaml", {"roll": "N"}, "N", {"s": "N", "phi": "N*m"}),
    ("rolling_disc.yaml", {"roll_x": "N", "roll_y": "N"}, "N", {"x": "N", "psi": "N*m"}),  # velocity constraints
    ("spring_damper.yaml", {"floor": "N"}, "N", {"x": "N"}),
])
def test_multiplier_and_force_units(name: str, multipliers: dict[str, str], force: str,
                                    generalized: dict[str, str]) -> None:
    """λ's unit is energy over the constraint's unit (and over s for a velocity constraint); forces in N,
    generalized forces N for a length and N*m for an angle."""
    problem = load_problem(PROBLEMS / name)
    form = matrix_form(problem, display=False)
    units = result_units(problem, form.model.kinetic)
    assert units is not None
    assert units.energy == "J"
    assert {k: units.multipliers[k] for k in multipliers} == multipliers
    assert units.force == force
    assert {k: units.generalized_forces[k] for k in generalized} == generalized


@pytest.mark.slow
@pytest.mark.parametrize("name", SHIPPED_WITH_UNITS)
def test_derived_results_have_the_predicted_units(name: str) -> None:
    """Independent route: walking each *derived* expression gives the unit predicted from the declared units
    alone: accelerations [q]/s^2, multipliers energy over the constraint's unit, forces of constraint N
    (generalized ones energy over [q]); a result like g m sqrt(R^2 + 1) would fail here."""
    from lagsolve.mechanics.derivation import derive

    problem = load_problem(PROBLEMS / name)
    derivation = derive(problem, budget=60)
    units = result_units(problem, derivation.kinetic)
    walker = algebra(problem)
    assert units is not None and derivation.accelerations is not None and derivation.multipliers is not None
    for c in problem.coordinates:
        if derivation.accelerations[c.name] == 0:
            continue  # 0 has every dimension
        derived = walker.of(derivation.accelerations[c.name])
        assert derived is not None and derived.dimensionality == unit_of(f"({c.unit})/s^2").dimensionality, c.name
    force = unit_of("N").dimensionality
    for c in derivation.constraints:
        derived = walker.of(derivation.multipliers[c.name])
        assert derived is not None
        assert derived.dimensionality == unit_of(units.multipliers[c.name] or "").dimensionality, c.name
        walker.symbols[c.multiplier] = derived
        for q, a in zip(problem.coordinates, c.coefficients, strict=True):
            if a != 0:
                assert walker.of(c.multiplier * a).dimensionality == (unit_of("J") / unit_of(q.unit or "")
                                                                      ).dimensionality
        result = (derivation.constraint_forces or {}).get(c.name)
        if result is None:
            continue
        for value in (*(result.vector or ()), *((result.magnitude,) if result.magnitude is not None else ())):
            if value != 0:
                assert walker.of(value).dimensionality == force, (c.name, value)
        for q, value in zip(problem.coordinates, result.generalized, strict=False):
            if value != 0:
                assert walker.of(value).dimensionality == (unit_of("J") / unit_of(q.unit or "")).dimensionality


def test_unit_text_names_si_units() -> None:
    """Results are written with N, J, W and N*m for a torque; radians only for angle kinematics."""
    assert unit_text(unit_of("kg*m/s^2")) == "N"
    assert unit_text(unit_of("kg*m^2/s^2")) == "J"
    assert unit_text(unit_of("kg*m^2/s^2/rad"), torque=True) == "N*m"
    assert unit_text(unit_of("kg*m^2/s^3")) == "W"
    assert unit_text(unit_of("kg/s")) == "N*s/m"
    assert unit_text(unit_of("rad/s^2"), angle=True) == "rad/s^2"
    assert unit_text(unit_of("rad/s^2")) == "1/s^2"
    assert unit_text(unit_of("km/min^2")) == "km/min^2"
    assert unit_text(None) is None


def test_unit_text_leaves_radians_out_of_units_that_are_not_si() -> None:
    """An energy in CGS from a swinging angle is g*cm^2/s^2 as the SI one is J (it was written cm^2*g*rad^2/s^2);
    radians stay for angle kinematics, and a degree is not rewritten."""
    assert unit_text(unit_of("g*cm^2*rad^2/s^2")) == "cm^2*g/s^2"
    assert unit_text(unit_of("g*cm^2/s^2/rad"), torque=True) == "cm^2*g/s^2"
    assert unit_text(unit_of("km*rad/h")) == "km/h"
    assert unit_text(unit_of("rad/min"), angle=True) == "rad/min"
    assert unit_text(unit_of("deg/s"), angle=True) == "deg/s"
    assert unit_text(unit_of("deg/s")) == "deg/s"


def test_a_cgs_pendulum_table_names_its_energy_without_radians() -> None:
    """The simulated table of a pendulum in grams and centimetres: θ̇ in rad/s, the energy in g*cm^2/s^2."""
    from lagsolve.mechanics.derivation import derive
    from lagsolve.mechanics.units.result_units import column_units
    from lagsolve.problem.load import load_text

    problem = load_text("""name: CGS pendulum
parameters:
  m: {unit: g}
  l: {unit: cm}
  g: {unit: cm/s^2}
coordinates:
  theta: {unit: rad}
particles:
  bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}
gravity: [0, -g]
""", "cgs.yaml")
    units = column_units(problem, derive(problem).model.kinetic)
    assert (units["theta"], units["theta_dot"], units["energy"]) == ("rad", "rad/s", "cm^2*g/s^2")
