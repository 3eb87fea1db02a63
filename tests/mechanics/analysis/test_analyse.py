"""The analysis after the equations (``lagsolve.mechanics.analysis.analyse``): textbook results of the
shipped problems, the contract forms, and no conserved quantity claimed where there is none."""

from __future__ import annotations

import pytest
import sympy

from lagsolve.check.compare import CONSERVED, OK, check
from lagsolve.errors import SpecError
from lagsolve.mechanics.analysis.analyse import contract_forms
from mechanics_support import (
    TUBE,
    assert_same,
    derived_file,
    derived_text,
    exactly_equal,
    names,
    problem_text,
    shipped,
)

DAMPED = """
name: Damped oscillator
parameters: {m: mass, k: stiffness, c: damping}
coordinates: [x]
particles: {p: {mass: m, position: [x, 0]}}
potential: k*x**2/2
dissipation: c*x_dot**2/2
"""

SHAKEN = """
name: Pendulum on a shaken support
parameters: {m: mass, g: gravity, l: length, a: amplitude, w: frequency}
coordinates: [theta, s]
particles:
  bob: {mass: m, position: [l*sin(theta), s - l*cos(theta)]}
gravity: [0, -g]
constraints:
  shaker: {holonomic: s - a*cos(w*t)}
"""

HOLE_Z = """
name: Hole table kept in z
parameters: {m1: mass on the table, m2: hanging mass, g: gravity, l: string length}
coordinates:
  r: {description: distance from the hole, positive: true}
  theta: angle
  z: height of m2
particles:
  m1: {mass: m1, position: [r*cos(theta), r*sin(theta), 0]}
  m2: {mass: m2, position: [0, 0, z]}
gravity: [0, 0, -g]
constraints:
  string: {holonomic: r - z - l, on: [m1, m2]}
independent: [theta, z]
"""


@pytest.fixture(scope="module")
def hole():
    return derived_file("hole_table")


def test_hole_table_conserves_p_theta_and_energy(hole):
    """The hole table conserves p_theta = m1 r^2 theta_dot and h = T + V, with z eliminated."""
    s = names(hole.problem)
    m1, m2, g, length, r, rd, thd = s["m1"], s["m2"], s["g"], s["l"], s["r"], s["r_dot"], s["theta_dot"]
    assert set(hole.conserved) == {"p_theta", "energy"}
    assert exactly_equal(hole.conserved["p_theta"], m1 * r**2 * thd)
    energy = (m1 + m2) * rd**2 / 2 + m1 * r**2 * thd**2 / 2 + m2 * g * (r - length)
    assert exactly_equal(hole.conserved["energy"], energy)
    jacobi = next(c for c in hole.analysis.conservation.quantities if c.name == "energy")
    assert jacobi.equals_energy and "h = T + V" in jacobi.reason


def test_hole_table_effective_potential_is_the_textbook_one(hole):
    """V_eff(r) = m2 g r + p_theta^2/(2 m1 r^2) exactly (the constant -m2 g l dropped), m_eff = m1 + m2."""
    s = names(hole.problem)
    m1, m2, g, r = s["m1"], s["m2"], s["g"], s["r"]
    p = sympy.Symbol("p_theta", real=True)
    effective = hole.analysis.effective_potential
    assert effective.coordinate == r
    assert exactly_equal(effective.expression, m2 * g * r + p**2 / (2 * m1 * r**2))
    assert exactly_equal(effective.mass, m1 + m2)


def test_hole_table_circular_orbit_radius_stability_and_frequency(hole):
    """The circular orbit has r0^3 = p_theta^2/(m1 m2 g), is stable, and omega^2 = 3 m2 g/((m1 + m2) r0)."""
    s = names(hole.problem)
    m1, m2, g, r = s["m1"], s["m2"], s["g"], s["r"]
    p = sympy.Symbol("p_theta", real=True)
    (orbit,) = hole.analysis.effective_potential.equilibria
    assert exactly_equal(orbit.value**3, p**2 / (m1 * m2 * g))
    assert orbit.stable is True
    assert exactly_equal(orbit.frequency**2, 3 * m2 * g / ((m1 + m2) * orbit.value))
    assert exactly_equal(orbit.frequency_squared_at, 3 * m2 * g / ((m1 + m2) * r))


def test_knife_edge_is_nonholonomic_and_keeps_its_energy():
    """The knife edge is reported nonholonomic (no reduced system) and only its energy T is conserved."""
    knife = derived_file("knife_edge")
    (skate,) = knife.analysis.classification
    assert skate.kind == "nonholonomic"
    assert knife.reduced is None and "nonholonomic" in knife.analysis.reduced_note
    assert set(knife.conserved) == {"energy"}
    assert exactly_equal(knife.conserved["energy"], knife.model.kinetic)
    assert knife.effective_potential is None


def test_tube_constraints_are_integrated():
    """theta_dot = 0 and phi_dot - Omega = 0 integrate to theta = theta0 and phi = Omega t + phi0."""
    tube = derived_text(TUBE)
    s = names(tube.problem)
    tilt, spin = tube.analysis.classification
    assert tilt.kind == spin.kind == "integrable"
    assert tilt.solved == (s["theta"], tilt.constant) and tilt.constant.name == "theta0"
    assert spin.solved[0] == s["phi"] and spin.constant.name == "phi0"
    assert exactly_equal(spin.solved[1], s["Omega"] * s["t"] + spin.constant)
    assert tube.reduced["independent"] == ["r"]
    assert tube.analysis.reduced.agreement == "symbolic"


def test_smooth_tube_conserves_the_jacobi_integral_but_not_t_plus_v():
    """In the smooth turning tube h = m r_dot^2/2 - m Omega^2 r^2 sin^2/2 + m g r cos is conserved, h != T + V."""
    tube = derived_text(TUBE)
    s = names(tube.problem)
    m, g, om, r, rd, th = s["m"], s["g"], s["Omega"], s["r"], s["r_dot"], s["theta"]
    h = m * rd**2 / 2 - m * om**2 * r**2 * sympy.sin(th) ** 2 / 2 + m * g * r * sympy.cos(th)
    assert set(tube.conserved) == {"energy"}
    assert exactly_equal(tube.conserved["energy"], h)
    (jacobi,) = tube.analysis.conservation.quantities
    assert jacobi.equals_energy is False and jacobi.moving


def test_rough_tube_claims_nothing():
    """With Coulomb friction nothing is conserved and no equilibrium is claimed."""
    rough = derived_file("rotating_tube")
    assert rough.conserved == {}
    assert any("friction" in n for n in rough.analysis.conservation.notes)
    assert rough.effective_potential is None


def test_dissipation_removes_the_energy():
    """A damped oscillator has no conserved quantity; the note says the forces do work."""
    damped = derived_text(DAMPED)
    assert damped.conserved == {}
    assert any("do work" in n for n in damped.analysis.conservation.notes)


def test_time_dependent_constraint_removes_the_energy():
    """A pendulum on a support shaken as a cos(w t) has L depending on t: no energy is claimed."""
    shaken = derived_text(SHAKEN)
    assert shaken.reduced["independent"] == ["theta"]
    assert shaken.conserved == {}
    assert any("explicitly on the time" in n for n in shaken.analysis.conservation.notes)
    assert shaken.effective_potential is None


def test_conserved_quantities_have_zero_rate_along_the_reduced_equations(hole):
    """d/dt of p_theta and of h, with the reduced accelerations substituted, cancels to zero."""
    reduced = hole.analysis.reduced
    model = reduced.model
    for name, expr in hole.conserved.items():
        rate = model.time_derivative(expr, second_order=True).xreplace(reduced.acceleration_map())
        assert sympy.simplify(rate) == 0, name


def test_contract_forms_have_the_format_shapes(hole):
    """reduced, conserved and effective_potential carry exactly the keys of format section 2."""
    forms = contract_forms(hole.analysis)
    assert set(forms["reduced"]) == {"independent", "accelerations"}
    assert forms["reduced"]["independent"] == ["r", "theta"]
    assert set(forms["effective_potential"]) == {"coordinate", "expression", "equilibria"}
    for e in forms["effective_potential"]["equilibria"]:
        assert set(e) == {"value", "stable", "frequency"}


def test_contract_forms_use_only_input_names():
    """Constants of integration are written back as their integrals, so only declared names appear."""
    tube = derived_text(TUBE)
    declared = set(tube.problem.symbols.values())
    for expr in [*tube.reduced["accelerations"].values(), *tube.conserved.values()]:
        assert expr.free_symbols <= declared


def test_independent_list_chooses_the_minimal_coordinates():
    """`independent: [theta, z]` eliminates r = z + l and gives (m1 + m2) z_ddot = m1 (z + l) theta_dot^2 - m2 g."""
    kept = derived_text(HOLE_Z)
    s = names(kept.problem)
    m1, m2, g, length, z, thd = s["m1"], s["m2"], s["g"], s["l"], s["z"], s["theta_dot"]
    assert kept.reduced["independent"] == ["theta", "z"]
    assert exactly_equal(kept.reduced["accelerations"]["z"], (m1 * (z + length) * thd**2 - m2 * g) / (m1 + m2))
    assert kept.analysis.reduced.agreement == "symbolic"


def test_independent_list_that_does_not_fit_is_explained():
    """Listing too many independent coordinates gives no reduced system and says why."""
    wrong = derived_text(HOLE_Z.replace("independent: [theta, z]", "independent: [r, theta, z]"))
    assert wrong.reduced is None
    assert "independent" in wrong.analysis.reduced_note


@pytest.mark.parametrize("text, message", [
    ("independent: [w]", "unknown coordinate 'w'"),
    ("independent: [z, z]", "listed twice"),
    ("independent: z", "expected a list of coordinate names"),
])
def test_independent_list_is_validated(text, message):
    """The loader rejects unknown, repeated or non-list `independent:` entries with a clear message."""
    with pytest.raises(SpecError, match=message):
        problem_text(HOLE_Z.replace("independent: [theta, z]", text))


def _shipped():
    return shipped()


@pytest.mark.slow
@pytest.mark.parametrize("name", _shipped())
def test_both_routes_agree_on_every_shipped_problem(name):
    """Where minimal coordinates exist, the reduced accelerations equal the multiplier route's."""
    derivation = derived_file(name)
    if derivation.analysis.reduced is not None:
        assert derivation.analysis.reduced.agreement in ("symbolic", "numeric")


@pytest.mark.slow
@pytest.mark.parametrize("name", _shipped())
def test_expected_conserved_quantities_hold(name):
    """Every `expected: conserved:` answer that the analysis derives under its name (energy, p_<q>) is equal to it on
    the constraint surface up to a constant; any other claim (the bowl's angular momentum) is confirmed by `check`
    through its rate along the equations."""
    derivation = derived_file(name)
    reduced = derivation.analysis.reduced
    for key, want in derivation.problem.expected.conserved.items():
        if key not in derivation.conserved and not key.startswith("p_") and key != "energy":
            (verdict,) = [v for v in check(derivation).verdicts if (v.quantity, v.name) == ("conserved", key)]
            assert (verdict.status, verdict.reason) == (OK, CONSERVED), (name, key, verdict.note)
            continue
        assert key in derivation.conserved, (name, key, sorted(derivation.conserved))
        got = derivation.conserved[key]
        if reduced is not None:
            want = reduced.substitution.apply(want)
        difference = got - want
        for _ in range(len(derivation.analysis.system.surface) + 1):  # velocity constraints: on their surface
            difference = difference.xreplace(derivation.analysis.system.surface)
        gradient = [sympy.diff(difference, s) for s in difference.free_symbols if s not in _parameters(derivation)]
        for g in gradient:
            assert_same(g, 0)


@pytest.mark.slow
@pytest.mark.parametrize("name", _shipped())
def test_expected_effective_potentials_hold(name):
    """Every `expected: effective_potential:` agrees: same coordinate, V_eff up to a constant, equilibria."""
    derivation = derived_file(name)
    spec = derivation.problem.expected.effective_potential
    if not spec:
        return
    effective = derivation.analysis.effective_potential
    assert effective is not None and effective.coordinate.name == spec["coordinate"]
    q = effective.coordinate
    if "expression" in spec:
        assert_same(sympy.diff(effective.expression - spec["expression"], q), 0)
    for want in spec["equilibria"]:
        matches = [e for e in effective.equilibria if e.value is not None and exactly_equal(e.value, want["value"])]
        assert matches, (name, want["value"], [e.value for e in effective.equilibria])
        got = matches[0]
        if "stable" in want:
            assert got.stable is want["stable"]
        if "frequency" in want:
            assert_same(got.frequency**2, want["frequency"] ** 2)


def _parameters(derivation):
    return {p.symbol for p in derivation.problem.parameters}


@pytest.mark.parametrize("name", _shipped())
def test_conserved_quantities_do_not_drift_in_simulation(name):
    """Along a simulated trajectory (the file's values and initial state) every claimed quantity stays constant."""
    from lagsolve.numeric.initial import complete_initial
    from lagsolve.numeric.integrate import integrate_motion
    from lagsolve.numeric.system import bind

    derivation = derived_file(name)
    problem = derivation.problem
    assert problem.simulation is not None and problem.simulation.t_end is not None
    note = derivation.analysis.conservation.energy.reason()
    system = bind(derivation.form, {}, derivation.conserved, energy_note=note)
    if not derivation.conserved:  # then the run does not claim energy either, and says why
        assert not system.energy_conserved and system.energy_note
        assert problem.friction or "time" in system.energy_note or "forces" in system.energy_note
        return
    q0, qd0 = complete_initial(system, problem.simulation.initial, problem.source)
    trajectory = integrate_motion(system, q0, qd0, problem.simulation.t_end, samples=200)
    drift = trajectory.stats["conserved_drift"]
    assert set(drift) == set(derivation.conserved)
    for quantity, value in drift.items():
        assert value < 1e-6, (quantity, value)
