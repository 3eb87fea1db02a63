"""Routh reduction and the effective potential (``lagsolve.mechanics.analysis.equilibria``): equilibria,
their stability and small-oscillation frequencies against textbook values."""

from __future__ import annotations

import pytest
import sympy

from mechanics_support import derived_file, derived_text, exactly_equal, names

DAMPED_PENDULUM = """
name: Damped pendulum
parameters: {m: mass, g: gravity, l: length, c: damping}
coordinates: [theta]
particles: {bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}}
gravity: [0, -g]
dissipation: c*theta_dot**2/2
"""


@pytest.fixture(scope="module")
def hoop():
    return derived_file("bead_on_rotating_hoop")


def _by_value(effective):
    return {sympy.srepr(e.value): e for e in effective.equilibria if e.value is not None}


def test_hoop_effective_potential(hoop):
    """The hoop's V_eff(theta) = -m g R cos(theta) - m R^2 Omega^2 sin^2(theta)/2 with m_eff = m R^2."""
    s = names(hoop.problem)
    m, g, R, W, th = s["m"], s["g"], s["R"], s["Omega"], s["theta"]
    effective = hoop.analysis.effective_potential
    assert effective.cyclic == ()
    assert exactly_equal(sympy.diff(effective.expression, th),
                         sympy.diff(-m * g * R * sympy.cos(th) - m * R**2 * W**2 * sympy.sin(th) ** 2 / 2, th))
    assert exactly_equal(effective.mass, m * R**2)


def test_hoop_equilibria_and_the_stability_switch(hoop):
    """theta = 0 is stable exactly while Omega^2 < g/R; pi is unstable; cos(theta) = g/(R Omega^2) is stable."""
    s = names(hoop.problem)
    g, R, W = s["g"], s["R"], s["Omega"]
    effective = hoop.analysis.effective_potential
    found = _by_value(effective)
    bottom, top = found[sympy.srepr(sympy.Integer(0))], found[sympy.srepr(sympy.pi)]
    assert top.stable is False and top.frequency is None
    assert bottom.stable is None
    for omega_squared, stable in ((0.9, True), (1.1, False)):  # in units of g/R
        point = {g: 9.81, R: 0.5, W: sympy.sqrt(omega_squared * 9.81 / 0.5)}
        assert bool(bottom.stability_condition.xreplace(point)) is stable
    assert exactly_equal(bottom.frequency**2, g / R - W**2)
    off = [e for e in effective.equilibria if e.value is not None and e.value.has(sympy.acos)]
    assert len(off) == 2
    for e in off:
        assert exactly_equal(sympy.cos(e.value), g / (R * W**2))
        assert e.stable is True
        assert exactly_equal(e.frequency**2, W**2 - g**2 / (R**2 * W**2))
        assert exactly_equal(e.exists_if.lhs - e.exists_if.rhs, R * W**2 - g)


def test_central_force_circular_orbit():
    """V = -k/r: the circular orbit r0 = p^2/(m k) is stable with omega^2 = k/(m r0^3)."""
    orbit = derived_file("central_force")
    s = names(orbit.problem)
    m, k, r = s["m"], s["k"], s["r"]
    p = sympy.Symbol("p_theta", real=True)
    effective = orbit.analysis.effective_potential
    assert exactly_equal(effective.expression, -k / r + p**2 / (2 * m * r**2))
    (circle,) = effective.equilibria
    assert exactly_equal(circle.value, p**2 / (m * k))
    assert circle.stable is True
    assert exactly_equal(circle.frequency_squared_at, k / (m * r**3))
    assert exactly_equal(circle.frequency**2, k / (m * circle.value**3))


def test_spherical_pendulum_conical_condition_and_frequency():
    """Conical pendulum: p^2 cos = m^2 g l^3 sin^4 (phi_dot^2 = g/(l cos)), stable, omega^2 = g(1 + 3cos^2)/(l cos)."""
    pendulum = derived_file("spherical_pendulum")
    s = names(pendulum.problem)
    m, g, rod, th, phd = s["m"], s["g"], s["l"], s["theta"], s["phi_dot"]
    p = sympy.Symbol("p_phi", real=True)
    effective = pendulum.analysis.effective_potential
    (cone,) = effective.equilibria
    assert cone.value is None and cone.stable is True
    residual = (cone.condition.lhs - cone.condition.rhs).xreplace({p: m * rod**2 * sympy.sin(th) ** 2 * phd})
    conical = (phd**2 - g / (rod * sympy.cos(th))) * m**2 * rod**4 * sympy.sin(th) ** 4 * sympy.cos(th)
    assert exactly_equal(residual, conical) or exactly_equal(residual, -conical)
    assert exactly_equal(cone.frequency_squared_at, g * (1 + 3 * sympy.cos(th) ** 2) / (rod * sympy.cos(th)))


def test_general_wire_equilibria_are_where_the_slope_vanishes():
    """On the wire y = f(x) equilibria have f'(x) = 0, are stable where f'' > 0, with omega^2 = g f''(x)."""
    bead = derived_file("bead")
    s = names(bead.problem)
    x, g, f = s["x"], s["g"], s["f"]
    (rest,) = bead.analysis.effective_potential.equilibria
    assert rest.condition == sympy.Eq(sympy.Derivative(f(x), x), 0)
    assert rest.stability_condition.lhs == sympy.Derivative(f(x), (x, 2))
    assert exactly_equal(rest.frequency_squared_at, g * sympy.Derivative(f(x), (x, 2)))


def test_damping_keeps_the_equilibria():
    """A damped pendulum keeps theta = 0 stable with the undamped omega^2 = g/l, and is marked damped."""
    damped = derived_text(DAMPED_PENDULUM)
    s = names(damped.problem)
    effective = damped.analysis.effective_potential
    assert effective.damped
    bottom = _by_value(effective)[sympy.srepr(sympy.Integer(0))]
    assert bottom.stable is True
    assert exactly_equal(bottom.frequency**2, s["g"] / s["l"])


def test_no_effective_potential_with_friction_or_several_degrees_of_freedom():
    """The rough tube (friction) and the double pendulum (two coordinates left) get none, with reasons."""
    assert derived_file("rotating_tube").analysis.effective_note.startswith("Coulomb friction")
    assert "2 coordinates are left" in derived_file("double_pendulum").analysis.effective_note


@pytest.mark.slow
def test_heavy_top_effective_potential_with_two_momenta():
    """Heavy top: V_eff = m g l cos + (p_phi - p_psi cos)^2/(2 (I1 + m l^2) sin^2) up to a constant; the
    equilibrium relation involves both momenta, so its stability is not claimed."""
    top = derived_file("heavy_top")
    s = names(top.problem)
    m, g, arm, i1, th = s["m"], s["g"], s["l"], s["I1"], s["theta"]
    p_phi, p_psi = sympy.Symbol("p_phi", real=True), sympy.Symbol("p_psi", real=True)
    effective = top.analysis.effective_potential
    assert effective.coordinate == th
    assert exactly_equal(effective.mass, i1 + m * arm**2)
    precession = (p_phi - p_psi * sympy.cos(th)) ** 2 / (2 * (i1 + m * arm**2) * sympy.sin(th) ** 2)
    textbook = m * g * arm * sympy.cos(th) + precession
    assert exactly_equal(sympy.diff(effective.expression - textbook, th), 0)
    (relation,) = effective.equilibria
    assert relation.value is None and relation.stable is None and relation.frequency is None
