"""Physical forces of constraint (``lagsolve.mechanics.equations.reactions`` and their use in
``derive``), checked against forces worked out by hand."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.elimination import eliminate
from lagsolve.mechanics.equations.forces import position_jacobian
from lagsolve.mechanics.equations.model import build_model
from lagsolve.mechanics.equations.reactions import internal, reaction
from lagsolve.mechanics.equations.surface import Surface
from mechanics_support import (
    PROBLEMS,
    TUBE,
    assert_same,
    derived_file,
    derived_text,
    exactly_equal,
    names,
    problem_file,
    problem_text,
)

NO_PARTICLES = """
name: Bead on a wire, energies written directly
parameters: {m: mass, g: gravity}
functions: {f: wire shape}
coordinates: [x, y]
kinetic: m*(x_dot**2 + y_dot**2)/2
potential: m*g*y
constraints:
  wire: {holonomic: y - f(x)}
"""

TWO_PARTICLES_NO_ON = """
name: Two particles and a constraint that names none
parameters: {m: mass, l: length}
coordinates: [x1, x2]
particles:
  a: {mass: m, position: [x1, 0]}
  b: {mass: m, position: [x2, 0]}
constraints:
  rod: {holonomic: x2 - x1 - l}
"""

POLAR_PENDULUM = """
name: Pendulum in polar coordinates
parameters: {m: mass, g: gravity, l: length}
coordinates: [r, theta]
particles:
  bob: {mass: m, position: [r*sin(theta), -r*cos(theta)]}
gravity: [0, -g]
constraints:
  rod: {holonomic: r - l}
"""

CARTESIAN_PENDULUM = """
name: Pendulum in Cartesian coordinates
parameters: {m: mass, g: gravity, l: length}
coordinates: [x, y]
particles:
  bob: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  rod: {holonomic: x**2 + y**2 - l**2}
"""


def hole_one_sided():
    """The hole-table problem with the string said to act on m1 only."""
    text = (PROBLEMS / "hole_table.yaml").read_text(encoding="utf-8")
    assert "on: [m1, m2]" in text
    return text.replace("on: [m1, m2]", "on: m1")


def reaction_of(problem, name):
    model = build_model(problem)
    (constraint,) = [c for c in problem.constraints if c.name == name]
    terms = constraint_terms(constraint, model)
    every = tuple(constraint_terms(c, model) for c in problem.constraints)
    zero = Surface(every, model, eliminate(every, model)).is_zero
    return model, terms, reaction(problem, model, terms, zero)


def _wire(x):
    return sympy.sin(x) + x**3 / 5


def test_bead_direction_is_the_wire_normal():
    """The wire's force per unit multiplier on the bead is (-f'(x), 1)."""
    problem = problem_file("bead")
    _, _, react = reaction_of(problem, "wire")
    s = names(problem)
    (push,) = react.particles
    assert push.particle == "bead"
    assert exactly_equal(push.direction[0], -sympy.Derivative(s["f"](s["x"]), s["x"]))
    assert exactly_equal(push.direction[1], 1)
    assert react.note == "" and not react.generalized


def test_bead_force_vector_and_magnitude():
    """The wire pushes with lambda (-f', 1), of size m |g + f'' x_dot^2| / sqrt(1 + f'^2)."""
    derivation = derived_file("bead")
    s = names(derivation.problem)
    m, g, x, xd, f = s["m"], s["g"], s["x"], s["x_dot"], s["f"]
    fp, fpp = sympy.Derivative(f(x), x), sympy.Derivative(f(x), (x, 2))
    lam = m * (fpp * xd**2 + g) / (1 + fp**2)
    force = derivation.constraint_forces["wire"]
    assert exactly_equal(force.vector[0], -lam * fp)
    assert exactly_equal(force.vector[1], lam)
    magnitude = m * sympy.Abs(g + fpp * xd**2) / sympy.sqrt(1 + fp**2)
    assert exactly_equal(force.magnitude, magnitude)
    assert_same(force.magnitude, magnitude, functions={f: _wire})


def test_force_satisfies_the_defining_equation():
    """For every constraint with a force, J^T f = a per unit multiplier (the format's rule)."""
    cases = [(problem_file("bead"), "wire"), (problem_file("knife_edge"), "skate"),
             (problem_file("hole_table"), "string"), (problem_text(TUBE), "tilt"),
             (problem_text(TUBE), "spin"), (problem_text(POLAR_PENDULUM), "rod")]
    for problem, name in cases:
        model, terms, react = reaction_of(problem, name)
        total = sympy.zeros(len(model.coordinates), 1)
        for push in react.particles:
            jac = position_jacobian(problem.particle(push.particle).position, model)
            total += jac.T * sympy.Matrix(push.direction)
        assert exactly_equal(total, sympy.Matrix(terms.coefficients)), (problem.name, name)


def test_polar_rod_pulls_along_the_rod():
    """r - l in polar coordinates pushes along e_r = (sin(theta), -cos(theta)) per unit lambda."""
    problem = problem_text(POLAR_PENDULUM)
    _, _, react = reaction_of(problem, "rod")
    th = names(problem)["theta"]
    (push,) = react.particles
    assert exactly_equal(push.direction[0], sympy.sin(th))
    assert exactly_equal(push.direction[1], -sympy.cos(th))


def test_polar_rod_tension():
    """The pendulum rod's force has size m (l theta_dot^2 + g cos(theta)), the textbook tension."""
    derivation = derived_text(POLAR_PENDULUM)
    s = names(derivation.problem)
    m, g, l_, th, thd = s["m"], s["g"], s["l"], s["theta"], s["theta_dot"]
    tension = m * (l_ * thd**2 + g * sympy.cos(th))
    assert exactly_equal(derivation.multipliers["rod"], -tension)
    assert_same(derivation.constraint_forces["rod"].magnitude, sympy.Abs(tension))


def test_cartesian_rod_direction():
    """x^2 + y^2 - l^2 pushes along (2x, 2y) per unit multiplier."""
    problem = problem_text(CARTESIAN_PENDULUM)
    _, _, react = reaction_of(problem, "rod")
    s = names(problem)
    (push,) = react.particles
    assert exactly_equal(push.direction[0], 2 * s["x"])
    assert exactly_equal(push.direction[1], 2 * s["y"])


def test_knife_edge_pushes_sideways():
    """The skate pushes particle 1 along (-sin(theta), cos(theta)) per unit multiplier."""
    problem = problem_file("knife_edge")
    _, _, react = reaction_of(problem, "skate")
    th = names(problem)["theta"]
    (push,) = react.particles
    assert push.particle == "p1"
    assert exactly_equal(push.direction[0], -sympy.sin(th))
    assert exactly_equal(push.direction[1], sympy.cos(th))


def test_tube_directions():
    """In the tube, theta_dot = 0 pushes along e_theta / r and phi_dot = Omega along
    e_phi / (r sin(theta))."""
    problem = problem_text(TUBE)
    s = names(problem)
    r, th, ph = s["r"], s["theta"], s["phi"]
    e_th = (sympy.cos(th) * sympy.cos(ph), sympy.cos(th) * sympy.sin(ph), -sympy.sin(th))
    e_ph = (-sympy.sin(ph), sympy.cos(ph), 0)
    (tilt,) = reaction_of(problem, "tilt")[2].particles
    (spin,) = reaction_of(problem, "spin")[2].particles
    for ours, unit in zip(tilt.direction, e_th, strict=True):
        assert exactly_equal(ours, unit / r)
    for ours, unit in zip(spin.direction, e_ph, strict=True):
        assert exactly_equal(ours, unit / (r * sympy.sin(th)))


def test_string_pulls_both_masses():
    """The string pushes m1 with lambda (cos, sin, 0) and m2 with (0, 0, -lambda), both of
    size m1 m2 |g + r theta_dot^2| / (m1 + m2)."""
    derivation = derived_file("hole_table")
    s = names(derivation.problem)
    m1, m2, g, r, th, thd = (s[k] for k in ("m1", "m2", "g", "r", "theta", "theta_dot"))
    lam = -m1 * m2 * (g + r * thd**2) / (m1 + m2)
    force = derivation.constraint_forces["string"]
    per = {name: (vector, size) for name, vector, size in force.particles}
    expected = {"m1": (lam * sympy.cos(th), lam * sympy.sin(th), 0), "m2": (0, 0, -lam)}
    for name, vector in expected.items():
        for ours, hand in zip(per[name][0], vector, strict=True):
            assert exactly_equal(ours, hand)
        assert exactly_equal(per[name][1], m1 * m2 * sympy.Abs(g + r * thd**2) / (m1 + m2))
    assert force.vector is None
    assert exactly_equal(force.magnitude, m1 * m2 * sympy.Abs(g + r * thd**2) / (m1 + m2))


def test_constraint_that_acts_elsewhere_gets_a_note():
    """A constraint on two particles that names only one gets the 'acts elsewhere' note and
    no force."""
    problem = problem_text(hole_one_sided())
    _, _, react = reaction_of(problem, "string")
    assert react.particles == ()
    assert "also acts elsewhere" in react.note
    assert "m1" in react.note


def test_constraint_that_acts_elsewhere_claims_no_force_in_derive():
    """derive() gives neither vector nor magnitude for such a constraint, and keeps the note."""
    derivation = derived_text(hole_one_sided())
    force = derivation.constraint_forces["string"]
    assert force.vector is None and force.magnitude is None
    assert "also acts elsewhere" in force.note


def test_several_particles_without_on_gets_a_note():
    """With several particles and no 'on', the note asks which particle the constraint acts on."""
    problem = problem_text(TWO_PARTICLES_NO_ON)
    _, _, react = reaction_of(problem, "rod")
    assert react.particles == ()
    assert "does not say which one" in react.note
    assert "on:" in react.note


def test_no_particles_gives_the_generalized_forces_and_no_magnitude():
    """Without particles no physical force is known: the result is the generalized forces of constraint
    lambda*a (here the bead's lambda*(-f'(x), 1)), labelled as such, and no magnitude."""
    problem = problem_text(NO_PARTICLES)
    _, _, react = reaction_of(problem, "wire")
    assert react.generalized and react.particles == ()
    derivation = derived_text(NO_PARTICLES)
    s = names(derivation.problem)
    x, f = s["x"], s["f"]
    force = derivation.constraint_forces["wire"]
    assert force.vector is None and force.magnitude is None
    lam = derivation.multipliers["wire"]
    assert len(force.generalized) == 2
    assert_same(force.generalized[0], -lam * sympy.Derivative(f(x), x), functions={f: _wire})
    assert_same(force.generalized[1], lam, functions={f: _wire})
    assert "generalized forces of constraint" in force.note


ROLLING_DISK = """
name: Disk rolling down an incline, no particles
parameters: {M: mass, R: radius, Ic: moment of inertia, g: gravity, alpha: angle}
coordinates: [x, phi]
bodies:
  disk: {mass: M, position: [x, 0], inertia: Ic, angular_velocity: phi_dot}
potential: -M*g*sin(alpha)*x
constraints:
  roll: {holonomic: x - R*phi}
"""


def test_body_only_problem_note_does_not_claim_particles():
    """A problem with a body and no particles never says it 'has several particles'."""
    problem = problem_text(ROLLING_DISK)
    _, _, react = reaction_of(problem, "roll")
    assert "several particles" not in react.note


def test_body_without_a_point_gets_no_magnitude_that_mixes_force_and_torque():
    """A body-only problem without 'at:' gets the generalized forces (lambda, -R lambda): a force along x and a
    torque about the centre, and never a 'magnitude' |lambda| sqrt(1 + R^2) mixing the two."""
    derivation = derived_text(ROLLING_DISK)
    s = names(derivation.problem)
    big_m, big_r, ic, g, al = (s[k] for k in ("M", "R", "Ic", "g", "alpha"))
    lam = -ic * big_m * g * sympy.sin(al) / (ic + big_m * big_r**2)
    assert exactly_equal(derivation.multipliers["roll"], lam)
    force = derivation.constraint_forces["roll"]
    assert force.magnitude is None and force.vector is None
    assert exactly_equal(force.generalized[0], lam)
    assert exactly_equal(force.generalized[1], -big_r * lam)


def test_rolling_disk_contact_force_is_the_friction_found_by_newton():
    """problems/rolling_incline.yaml names the contact point: the force there is the friction at the contact.
    Newton for the disk, m s_ddot = m g sin(alpha) - f and (m R^2/2) phi_ddot = f R with s_ddot = R phi_ddot,
    solved here with sympy.solve, gives f = m g sin(alpha)/3 up the slope, direction (-cos(alpha), sin(alpha))."""
    derivation = derived_file("rolling_incline")
    s = names(derivation.problem)
    m, g, big_r, al = (s[k] for k in ("m", "g", "R", "alpha"))
    sdd, phdd, f = sympy.symbols("sdd phdd f")
    newton = sympy.solve([m * sdd - (m * g * sympy.sin(al) - f), m * big_r**2 / 2 * phdd - f * big_r,
                          sdd - big_r * phdd], [sdd, phdd, f], dict=True)[0]
    friction = newton[f]
    assert sympy.simplify(friction - m * g * sympy.sin(al) / 3) == 0
    force = derivation.constraint_forces["roll"]
    up_the_slope = (-sympy.cos(al), sympy.sin(al))
    for got, want in zip(force.vector, up_the_slope, strict=True):
        assert sympy.simplify(got - friction * want) == 0
    assert sympy.simplify(force.magnitude - m * g * sympy.Abs(sympy.sin(al)) / 3) == 0
    assert sympy.simplify(derivation.accelerations["s"] - newton[sdd]) == 0


def test_physical_pendulum_axle_force_is_m_a_minus_the_weight():
    """With the axle named as the point of the body, the two constraint forces add up to Newton's axle force
    m a_cm - m g, with a_cm from the textbook theta_ddot = -m g d sin(theta)/(Ic + m d^2)."""
    derivation = derived_file("physical_pendulum")
    s = names(derivation.problem)
    m, ic, d, g, th, thd = (s[k] for k in ("m", "Ic", "d", "g", "theta", "theta_dot"))
    thdd = -m * g * d * sympy.sin(th) / (ic + m * d**2)
    # the centre is the axle plus d (sin(theta), -cos(theta))
    a_cm = (d * sympy.cos(th) * thdd - d * sympy.sin(th) * thd**2,
            d * sympy.sin(th) * thdd + d * sympy.cos(th) * thd**2)
    axle = (m * a_cm[0], m * a_cm[1] + m * g)
    forces = derivation.constraint_forces
    for k in range(2):
        total = forces["axle_x"].vector[k] + forces["axle_y"].vector[k]
        assert sympy.simplify(total - axle[k]) == 0


def test_point_where_the_constraint_cannot_act_gets_a_note():
    """Rolling named at the disk's centre is not a force there (the centre's velocity does not feel phi), so no
    force is claimed and the note says to check 'at:'."""
    text = ROLLING_DISK.replace("roll: {holonomic: x - R*phi}", "roll: {holonomic: x - R*phi, on: disk, at: [x, 0]}")
    _, _, react = reaction_of(problem_text(text), "roll")
    assert react.particles == () and "at:" in react.note


def test_a_cylinder_rolling_on_a_sliding_wedge_pushes_along_the_face_and_back_on_the_wedge():
    """problems/wedge_cylinder.yaml, rolling on a face that moves (on: [cyl, wedge]): the force on the
    cylinder is the friction along the face, f = m s_ddot/2 from Newton's law for its rotation,
    (m R^2/2) phi_ddot = f R with s = R phi, and the wedge gets -f at the contact."""
    d = derived_file("wedge_cylinder")
    s = {str(k): v for k, v in d.problem.symbols.items()}
    m, M, g, a = s["m"], s["M"], s["g"], s["alpha"]
    # the textbook accelerations (Lagrange by hand): (M + m) X'' + m cos a s'' = 0, m cos a X'' + 3m/2 s'' = m g sin a
    s_ddot = g * sympy.sin(a) * (M + m) / (sympy.Rational(3, 2) * (M + m) - m * sympy.cos(a) ** 2)
    assert sympy.simplify(d.accelerations["s"] - s_ddot) == 0
    force = d.constraint_forces["roll"]
    (cyl, on_cyl, size), (wedge, on_wedge, _) = force.particles
    assert (cyl, wedge) == ("cyl", "wedge")
    friction = m * s_ddot / 2  # up the face, along (-cos a, sin a)
    along = (-friction * sympy.cos(a), friction * sympy.sin(a))
    assert all(sympy.simplify(c - e) == 0 for c, e in zip(on_cyl, along, strict=True))
    assert all(sympy.simplify(c + e) == 0 for c, e in zip(on_wedge, on_cyl, strict=True))
    assert sympy.simplify(size.subs({a: sympy.Rational(2, 5)}) - friction.subs({a: sympy.Rational(2, 5)})) == 0


SMOOTH_WEDGE = """
name: block on a smooth wedge that cannot move vertically
parameters: {m: mass, M: mass, g: gravity, alpha: angle}
coordinates: [X, x, y]
particles:
  wedge: {mass: M, position: [X, 0]}
  block: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  face: {holonomic: y*cos(alpha) - (x - X)*sin(alpha), on: [block, wedge]}
"""


def test_a_face_between_two_particles_pushes_both_ways_even_where_one_cannot_move() -> None:
    """The wedge has no vertical coordinate (the floor is built in), so its force is not fixed by its own
    equations; the face depends on block and wedge only through their relative position, so the wedge gets the
    opposite of the block's force, vertical part included (not only the part along X), and the same magnitude."""
    d = derived_text(SMOOTH_WEDGE)
    assert d.constraint_forces is not None
    face = d.constraint_forces["face"]
    (block, on_block, size), (wedge, on_wedge, wedge_size) = face.particles
    assert (block, wedge) == ("block", "wedge")
    assert all(sympy.simplify(a + b) == 0 for a, b in zip(on_block, on_wedge, strict=True))
    assert on_wedge[1] != 0 and sympy.simplify(size - wedge_size) == 0
    assert face.magnitude is not None


def test_strings_are_not_taken_for_contacts() -> None:
    """A string through a hole (no common motion of the two) and Atwood's string over a pulley (a common motion
    lengthens it) pull each particle along the string, not equal and opposite."""
    for name in ("hole_table", "atwood", "incline_pulley"):
        problem = problem_file(name)
        model = build_model(problem)
        string = next(c for c in problem.constraints if c.name == "string")
        terms = constraint_terms(string, model)
        first, second = (position_jacobian(problem.particle(p).position, model) for p in string.on)
        assert not internal(first, second, sympy.Matrix(terms.coefficients), model), name
