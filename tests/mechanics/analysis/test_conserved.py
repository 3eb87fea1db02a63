"""Conserved quantities (``lagsolve.mechanics.analysis.conserved``): cyclic momenta and the Jacobi integral,
each verified along the equations, and never claimed when a force or a moving constraint does work."""

from __future__ import annotations

import math
import random

import sympy

from lagsolve.mechanics.analysis.conserved import Energy, EnergyDecision, MotionSystem, conserved_quantities
from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.model import build_model
from lagsolve.mechanics.equations.surface import constraint_surface
from mechanics_support import derived_file, derived_text, exactly_equal, names, problem_file

MAGNETIC = """
name: Charge in a uniform magnetic field
parameters: {m: mass, q: charge, B: field}
coordinates: [x, y]
particles: {p: {mass: m, position: [x, y]}}
forces:
  - {coordinate: x, value: q*B*y_dot}
  - {coordinate: y, value: -q*B*x_dot}
"""

PRESCRIBED = """
name: Wheel turned at a rate set by its position
parameters: {m: mass, v0: speed}
coordinates: [x, phi]
particles: {p: {mass: m, position: [x, 0]}}
kinetic: phi_dot**2/2
constraints:
  rate: {nonholonomic: x*phi_dot - v0}
"""


def test_gyroscopic_force_does_no_work():
    """A magnetic force q v x B does no work: h = T is conserved (no_work), but neither x nor y is cyclic."""
    charge = derived_text(MAGNETIC)
    s = names(charge.problem)
    assert set(charge.conserved) == {"energy"}
    assert exactly_equal(charge.conserved["energy"], s["m"] * (s["x_dot"] ** 2 + s["y_dot"] ** 2) / 2)
    (energy,) = charge.analysis.conservation.quantities
    assert "no_work" in energy.flags


def test_moving_velocity_constraint_does_work():
    """A velocity constraint with b = -v0 != 0 does work: no energy is claimed, and the note says why."""
    wheel = derived_text(PRESCRIBED)
    assert "energy" not in wheel.conserved
    assert any("b != 0" in n for n in wheel.analysis.conservation.notes)


def test_rates_are_zero_along_the_full_system_with_constraints():
    """On the knife edge, dh/dt along the multiplier route's accelerations vanishes on the constraint surface."""
    knife = derived_file("knife_edge")
    system = knife.analysis.system
    assert system.kind == "full"
    assert exactly_equal(system.rate(knife.conserved["energy"]), 0)


def test_constraint_surface_solves_one_velocity_per_constraint():
    """The knife edge's surface gives one velocity through the others, and the constraint then vanishes."""
    problem = problem_file("knife_edge")
    model = build_model(problem)
    terms = tuple(constraint_terms(c, model) for c in problem.constraints)
    surface = constraint_surface(terms, model)
    assert len(surface) == 1
    (c,) = terms
    rate = sum((a * v for a, v in zip(c.coefficients, model.velocities, strict=True)), c.offset)
    assert sympy.simplify(rate.xreplace(surface)) == 0


def test_a_candidate_that_fails_verification_is_dropped():
    """With wrong accelerations the verification fails and nothing is claimed, only noted."""
    hole = derived_file("hole_table")
    reduced = hole.analysis.reduced
    wrong = {a: 0 for a in reduced.model.accelerations}  # not the equations of motion
    system = MotionSystem(reduced.model, reduced.generalized_forces, wrong)
    found = conserved_quantities(system)
    assert found.quantities == ()
    assert any("did not simplify to 0" in n for n in found.notes)
    assert found.energy.kind == Energy.NOT_PROVED and found.energy.note() in found.notes


def test_the_energy_decision_is_a_value_written_as_sentences():
    """The decision is data (a kind, friction, the moving constraints); its note and reason are written from it."""
    moving = EnergyDecision(Energy.MOVING, moving=("a", "b"))
    assert moving.note() == "energy: not conserved, constraint a, b has b != 0, so its force does work"
    assert moving.reason() == "constraint a, b has b != 0, so its force does work"
    assert EnergyDecision(Energy.WORK, friction=True).reason() == "friction does work (sum of Q_i q_i_dot is not 0)"
    assert EnergyDecision(Energy.TIME).reason() == "L depends explicitly on the time"
    assert EnergyDecision(Energy.CONSERVED).reason() == "" and EnergyDecision(Energy.CONSERVED).note() == ""
    assert EnergyDecision().reason() == "the analysis finds no conserved energy"  # no decision made


def test_shipped_energy_decisions_agree_with_the_quantities_and_notes():
    """Energy is claimed exactly when the decision is CONSERVED, and the notes carry the decision's note."""
    kinds = {}
    for name in ("bead", "driven_oscillator", "rough_incline", "turntable", "moving_support"):
        conservation = derived_file(name).analysis.conservation
        kinds[name] = conservation.energy.kind
        claimed = any(q.name == "energy" for q in conservation.quantities)
        assert claimed == (conservation.energy.kind == Energy.CONSERVED), name
        assert [n for n in conservation.notes if n.startswith("energy: ")] == (
            [conservation.energy.note()] if conservation.energy.note() else []), name
    assert kinds["bead"] == Energy.CONSERVED and kinds["rough_incline"] == Energy.WORK


def test_momentum_of_a_coordinate_only_in_other_coefficients_is_conserved():
    """The upright rolling coin's heading φ enters the rolling constraints only through cos φ, sin φ (coefficients of
    θ̇): p_φ = Id φ̇ is still conserved, and SymPy's LagrangesMethod confirms dp_φ/dt = 0 at random rolling states."""
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

    coin = derived_file("rolling_coin")
    s = names(coin.problem)
    assert exactly_equal(coin.conserved["p_phi"], s["Id"] * s["phi_dot"])
    assert s["phi"] in coin.analysis.conservation.cyclic
    assert set(coin.conserved) == {"p_phi", "energy"}  # x, y, theta are absent from L but their velocities constrained
    # independent route: Lagrange's equations with multipliers by SymPy, the coin written out by hand
    x, y, phi, theta = dynamicsymbols("x y phi theta")
    m, R, Ia, Id = sympy.symbols("m R Ia Id", positive=True)
    t = dynamicsymbols._t
    lagrangian = (m * (x.diff(t) ** 2 + y.diff(t) ** 2) + Ia * theta.diff(t) ** 2 + Id * phi.diff(t) ** 2) / 2
    rolling = [x.diff(t) - R * theta.diff(t) * sympy.cos(phi), y.diff(t) - R * theta.diff(t) * sympy.sin(phi)]
    method = LagrangesMethod(lagrangian, [x, y, phi, theta], nonhol_coneqs=rolling)
    method.form_lagranges_equations()
    rhs = method.rhs()
    state = [x, y, phi, theta, *(q.diff(t) for q in (x, y, phi, theta))]
    plain = sympy.symbols("x y phi theta x_d y_d phi_d theta_d")
    rate = Id * rhs[6].xreplace(dict(zip(state[::-1], plain[::-1], strict=True)))  # Id * phi_ddot
    rng = random.Random(5)
    for _ in range(20):
        values = {sym: rng.uniform(-2, 2) for sym in plain}
        values |= {m: rng.uniform(0.5, 2), R: rng.uniform(0.5, 2), Ia: rng.uniform(0.5, 2), Id: rng.uniform(0.5, 2)}
        values[plain[4]] = values[R] * values[plain[7]] * math.cos(values[plain[2]])  # on the rolling surface
        values[plain[5]] = values[R] * values[plain[7]] * math.sin(values[plain[2]])
        assert abs(float(rate.xreplace(values))) < 1e-12


def test_constant_proves_the_energy_and_refuses_what_changes():
    """MotionSystem.constant (its quick proof over the accelerations' common denominator, then the full one)
    proves h of the double pendulum constant along the motion, and refuses T alone, a velocity and the
    angle, whose rates along the same equations are not zero (checked numerically, independently)."""
    double = derived_file("double_pendulum")
    system = double.analysis.system
    assert system.accelerations
    model = system.model
    assert system.constant(double.conserved["energy"])
    assert system.constant(model.kinetic + model.potential)
    for changing in (model.kinetic, model.velocities[0], model.coordinates[1]):
        assert not system.constant(changing)
        rate = system.rate(changing)
        rng = random.Random(5)
        point = {s: rng.uniform(0.5, 1.5) for s in rate.free_symbols}
        assert abs(float(rate.xreplace(point))) > 1e-9
