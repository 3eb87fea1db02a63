"""Conserved quantities (``lagsolve.mechanics.conserved``): cyclic momenta and the Jacobi integral,
each verified along the equations, and never claimed when a force or a moving constraint does work."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.conserved import MotionSystem, conserved_quantities, constraint_surface
from lagsolve.mechanics.constraints import constraint_terms
from lagsolve.mechanics.model import build_model
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
