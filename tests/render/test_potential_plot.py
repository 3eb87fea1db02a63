"""The effective potential in numbers (``lagsolve.numeric.potential``) and its figure
(``lagsolve.render.potential_plot``)."""

from __future__ import annotations

import math

import pytest

from lagsolve.numeric.potential import potential_curve
from lagsolve.render.potential_plot import potential_figure
from mechanics_support import derived_file

pytest.importorskip("matplotlib")


def test_figure_from_plain_numbers():
    """A figure is built from lists of numbers, with one marker per equilibrium and the axis labelled."""
    figure = potential_figure([1.0, 2.0, 3.0], [1.0, 0.0, 1.0], [(2.0, 0.0, True), (3.0, 1.0, False)],
                              coordinate="r", title="test")
    (axes,) = figure.axes
    assert axes.get_xlabel() == "$r$" and axes.get_title() == "test"
    assert len(axes.lines) == 3


def test_mismatched_samples_are_refused():
    """q and V_eff samples of different lengths raise ValueError."""
    with pytest.raises(ValueError, match="differ in length"):
        potential_figure([1.0, 2.0], [1.0])


def test_hole_table_curve_marks_the_circular_orbit():
    """From the file's values and initial state (p_theta = 3), the orbit is at r0 = (9/9.81)^(1/3), stable."""
    hole = derived_file("hole_table")
    simulation = hole.problem.simulation
    curve = potential_curve(hole, simulation.values, initial=simulation.initial)
    ((r0, v0, stable),) = curve.equilibria
    assert math.isclose(r0, (9 / 9.81) ** (1 / 3), rel_tol=1e-12)
    assert stable is True
    assert v0 == pytest.approx(min(curve.v), rel=1e-4)


def test_condition_only_equilibria_are_found_numerically():
    """The spherical pendulum's conical equilibrium is found where dV_eff/dtheta changes sign."""
    pendulum = derived_file("spherical_pendulum")
    simulation = pendulum.problem.simulation
    curve = potential_curve(pendulum, simulation.values, initial=simulation.initial)
    positive = [q for q, _, stable in curve.equilibria if q > 0 and stable]
    assert len(positive) == 1
    theta0 = positive[0]
    p = math.sin(0.5) ** 2 * 3.6  # m l^2 sin^2(theta) phi_dot at the initial state
    assert p**2 * math.cos(theta0) == pytest.approx(9.81 * math.sin(theta0) ** 4, rel=1e-8)


def test_no_effective_potential_is_an_error():
    """Asking for the curve of a problem without an effective potential raises ValueError."""
    with pytest.raises(ValueError, match="no effective potential"):
        potential_curve(derived_file("knife_edge"), {"m": 1.0, "l": 1.0})


def test_a_title_with_dollar_signs_is_drawn_as_text():
    """A problem name with '$' in the V_eff title is plain text, so the figure still draws."""
    from lagsolve.render.plots import png_bytes

    figure = potential_figure([1.0, 2.0, 3.0], [1.0, 0.0, 1.0], [], coordinate="r", title="bad $\\frac{ $ x")
    assert png_bytes(figure).startswith(b"\x89PNG")
