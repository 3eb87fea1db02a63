"""Minimal charts (``lagsolve.mechanics.analysis.minimal_chart``): the dependent variables in closed form, for the
numeric
stage."""

from __future__ import annotations

import pytest
import sympy

from lagsolve.mechanics.analysis.minimal_chart import minimal_chart
from lagsolve.mechanics.equations.constraints import constraint_terms
from mechanics_support import TUBE, derived_file, derived_text, exactly_equal, names, shipped


def chart_of(derivation):
    return minimal_chart(derivation.analysis, derivation.model)


def test_bead_chart_is_the_wire():
    """On the wire y = f(x): y and y_dot follow from x and x_dot."""
    bead = derived_file("bead")
    s = names(bead.problem)
    chart, note = chart_of(bead)
    assert note == ""
    assert chart.independent == ("x",) and chart.dependent == ("y",) and chart.sources == ("wire",)
    assert chart.positions == (s["f"](s["x"]),)
    assert exactly_equal(chart.velocities[0], sympy.Derivative(s["f"](s["x"]), s["x"]) * s["x_dot"])
    assert chart.constants == () and chart.integrals == ()


def test_integrated_velocity_constraints_bring_their_constants():
    """theta_dot = 0 and phi_dot = Omega integrate to theta = theta0, phi = Omega t + phi0; the constants'
    values come from the state (theta, phi - Omega t)."""
    tube = derived_text(TUBE)
    s = names(tube.problem)
    chart, _ = chart_of(tube)
    assert chart.independent == ("r",) and chart.dependent == ("theta", "phi")
    theta0, phi0 = chart.constants
    assert (theta0.name, phi0.name) == ("theta0", "phi0")
    assert chart.positions[0] == theta0
    assert exactly_equal(chart.positions[1], s["Omega"] * s["t"] + phi0)
    assert chart.velocities == (0, s["Omega"])
    assert exactly_equal(chart.integrals[0], s["theta"])
    assert exactly_equal(chart.integrals[1], s["phi"] - s["Omega"] * s["t"])


@pytest.mark.parametrize("name, reason", [
    ("knife_edge", "nonholonomic"),
    ("pendulum_cartesian", "not solved for any coordinate in closed form"),
    ("double_pendulum", "already minimal"),
])
def test_no_chart_says_why(name, reason):
    chart, note = chart_of(derived_file(name))
    assert chart is None
    assert reason in note


def _holonomic():
    return [name for name in shipped() if name not in ("knife_edge", "rolling_coin", "rolling_disc")]  # nonholonomic


@pytest.mark.parametrize("name", _holonomic())
def test_chart_satisfies_the_constraints_exactly(name):
    """On every shipped problem with a chart: substituting it into each constraint (position and
    velocity form, with each constant replaced by the integral it stands for) gives exactly zero, and
    each dependent velocity is the time derivative of its position."""
    derivation = derived_file(name)
    chart, note = chart_of(derivation)
    if chart is None:  # then the note says why, in words a user can act on
        assert ("not solved for any coordinate" in note and derivation.constraints) or (
            "already minimal" in note and not derivation.constraints) or (
            "is nonholonomic" in note and any(c.kind == "nonholonomic" for c in derivation.problem.constraints))
        return
    model = derivation.model
    index = {q.name: i for i, q in enumerate(model.coordinates)}
    positions = {model.coordinates[index[d]]: e for d, e in zip(chart.dependent, chart.positions, strict=True)}
    rates = {model.velocities[index[d]]: e for d, e in zip(chart.dependent, chart.velocities, strict=True)}
    for d, position, rate in zip(chart.dependent, chart.positions, chart.velocities, strict=True):
        assert exactly_equal(model.time_derivative(position), rate), d
    for c in derivation.problem.constraints:
        terms = constraint_terms(c, model)
        velocity_form = sum((a * v for a, v in zip(terms.coefficients, model.velocities, strict=True)), terms.offset)
        on_chart = velocity_form.xreplace(rates).xreplace(positions)
        assert exactly_equal(on_chart, 0), c.name
        if terms.kind == "holonomic":
            assert exactly_equal(terms.expression.xreplace(positions), 0), c.name
    # each constant's integral, taken along the chart, is the constant itself
    for constant, integral in zip(chart.constants, chart.integrals, strict=True):
        assert exactly_equal(integral.xreplace(positions), constant)
