"""mechanics/equations/friction.py: friction contacts between two members, on particles and rigid bodies.

Each result is checked by an independent route: Newton's and Euler's laws for each member, solved here as a small
linear system, and SymPy's LagrangesMethod with the friction forces on both members written by hand.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
import sympy
from sympy.physics import mechanics as me

from lagsolve.errors import SpecError
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.problem.load import load_text
from mechanics_support import PROBLEMS, derived_file, names, problem_file

STATES = 12


def _wedge_state(rng: random.Random, s: dict) -> dict:
    """A random state of problems/rough_wedge.yaml on its constraint surface, sliding (sigma != 0)."""
    alpha = rng.uniform(0.2, 1.2)
    X, x = rng.uniform(-1, 1), rng.uniform(-1, 1)
    Xd, xd = rng.uniform(-2, 2), rng.uniform(-2, 2)
    return {s["M"]: rng.uniform(0.5, 3), s["m"]: rng.uniform(0.5, 3), s["g"]: 9.81, s["alpha"]: alpha,
            s["mu"]: rng.uniform(0.05, 0.6), s["X"]: X, s["x"]: x, s["y"]: (x - X) * np.tan(alpha),
            s["X_dot"]: Xd, s["x_dot"]: xd, s["y_dot"]: (xd - Xd) * np.tan(alpha)}


def _wedge_newton(v: dict, s: dict) -> tuple[np.ndarray, float]:
    """Newton's law for the block and the wedge, with the normal force N n and the friction -mu N sign(sigma) e
    on the block and their opposites on the wedge: (x_ddot, y_ddot, X_ddot) and N."""
    M, m, g, a, mu = (float(v[s[k]]) for k in ("M", "m", "g", "alpha", "mu"))
    e, n = np.array([np.cos(a), np.sin(a)]), np.array([-np.sin(a), np.cos(a)])
    relative = np.array([float(v[s["x_dot"]] - v[s["X_dot"]]), float(v[s["y_dot"]])])
    on_block = n - mu * np.sign(relative @ e) * e  # per unit N
    A = np.array([[m, 0, 0, -on_block[0]], [0, m, 0, -on_block[1]], [0, 0, M, on_block[0]],
                  [-np.tan(a), 1, np.tan(a), 0]])
    solution = np.linalg.solve(A, [0, -m * g, 0, 0])
    return solution[:3], float(solution[3])


def test_rough_wedge_matches_newton_for_each_body() -> None:
    """Block on a rough wedge on a smooth floor: the accelerations of both bodies, the normal force and the
    multiplier agree with Newton's law for each body at random sliding states (the friction acts on the block
    and, opposite, on the wedge: Ẍ is not the frictionless value)."""
    d = derived_file("rough_wedge")
    s = names(problem_file("rough_wedge"))
    rng = random.Random(5)
    assert d.accelerations is not None and d.multipliers is not None
    for _ in range(STATES):
        v = _wedge_state(rng, s)
        newton, normal = _wedge_newton(v, s)
        ours = [float(d.accelerations[q].xreplace(v)) for q in ("x", "y", "X")]
        assert ours == pytest.approx(list(newton), rel=1e-9, abs=1e-12)
        assert float(d.friction[0].normal_force.xreplace(v)) == pytest.approx(normal, rel=1e-9)
        assert float(d.multipliers["face"].xreplace(v)) == pytest.approx(normal, rel=1e-9)


def test_rough_wedge_equations_agree_with_lagranges_method() -> None:
    """The matrix form with the normal force a symbol N: SymPy's LagrangesMethod with the friction written by hand
    on both bodies, F = -mu N sign(sigma) e on the block and -F on the wedge, gives the same accelerations."""
    problem = problem_file("rough_wedge")
    form = matrix_form(problem)
    s = names(problem)
    (term,) = form.frictions
    t = me.dynamicsymbols._t
    X, x, y = me.dynamicsymbols("X x y")
    M, m, g, alpha, mu, N, S = sympy.symbols("M m g alpha mu N S")
    frame = me.ReferenceFrame("F")
    origin = me.Point("O")
    origin.set_vel(frame, 0)
    wedge_point = origin.locatenew("W", X * frame.x)
    wedge_point.set_vel(frame, X.diff(t) * frame.x)
    block_point = origin.locatenew("B", x * frame.x + y * frame.y)
    block_point.set_vel(frame, x.diff(t) * frame.x + y.diff(t) * frame.y)
    wedge, block = me.Particle("wedge", wedge_point, M), me.Particle("block", block_point, m)
    block.potential_energy = m * g * y
    friction = -mu * N * S * (sympy.cos(alpha) * frame.x + sympy.sin(alpha) * frame.y)
    method = me.LagrangesMethod(me.Lagrangian(frame, wedge, block), [X, x, y],
                                hol_coneqs=[y * sympy.cos(alpha) - (x - X) * sympy.sin(alpha)],
                                forcelist=[(block_point, friction), (wedge_point, -friction)], frame=frame)
    method.form_lagranges_equations()
    rhs = method.rhs()
    ours_mass, ours_forcing = form.lagrange.mass_matrix, form.lagrange.forcing
    A, beta = form.lagrange.constraint_jacobian, form.lagrange.constraint_rhs
    rng = random.Random(8)
    for _ in range(STATES):
        v = _wedge_state(rng, s)
        value_n = rng.uniform(0.5, 5)
        sigma = float((v[s["x_dot"]] - v[s["X_dot"]]) * np.cos(v[s["alpha"]]) + v[s["y_dot"]] * np.sin(v[s["alpha"]]))
        ours = {**v, term.normal: value_n}
        system = sympy.Matrix(sympy.BlockMatrix([[ours_mass, -A.T], [A, sympy.zeros(A.rows)]])).xreplace(ours)
        solved = np.linalg.solve(np.array(system, dtype=float),
                                 np.array(sympy.Matrix([*ours_forcing, *beta]).xreplace(ours), dtype=float).ravel())
        theirs = {M: v[s["M"]], m: v[s["m"]], g: v[s["g"]], alpha: v[s["alpha"]], mu: v[s["mu"]], N: value_n,
                  S: np.sign(sigma), X: v[s["X"]], x: v[s["x"]], y: v[s["y"]], X.diff(t): v[s["X_dot"]],
                  x.diff(t): v[s["x_dot"]], y.diff(t): v[s["y_dot"]]}
        accelerations = [float(rhs[3 + i].xreplace(theirs)) for i in range(3)]
        assert list(solved[:3]) == pytest.approx(accelerations, rel=1e-9, abs=1e-12)


def test_friction_between_two_bodies_gives_the_pair_no_net_horizontal_force() -> None:
    """Newton's third law in generalized forces: the friction's Q_X (on the wedge) is minus its Q_x (on the block),
    so the floor direction gets no net force and the horizontal momentum is conserved."""
    (term,) = matrix_form(problem_file("rough_wedge")).frictions
    assert sympy.simplify(term.generalized[0] + term.generalized[1]) == 0
    assert term.against == "wedge" and term.particle == "block"


def test_the_force_of_a_contact_is_given_on_both_members() -> None:
    """Each member of the contact gets a vector: the normal part has length N, the friction is orthogonal to it
    and mu N long, the wedge gets the opposite of the block's, and the magnitude is N sqrt(1 + mu^2)."""
    d = derived_file("rough_wedge")
    s = names(problem_file("rough_wedge"))
    (result,) = d.friction
    block, wedge = result.members
    assert (block.member, wedge.member) == ("block", "wedge")
    rng = random.Random(3)
    for _ in range(6):
        v = _wedge_state(rng, s)
        normal = np.array([float(c.xreplace(v)) for c in block.normal])
        friction = np.array([float(c.xreplace(v)) for c in block.friction])
        N = float(result.normal_force.xreplace(v))
        assert np.linalg.norm(normal) == pytest.approx(N, rel=1e-9)
        assert np.linalg.norm(friction) == pytest.approx(float(v[s["mu"]]) * N, rel=1e-9)
        assert normal @ friction == pytest.approx(0, abs=1e-9 * N * N)
        assert [float(c.xreplace(v)) for c in wedge.total] == pytest.approx(list(-(normal + friction)), rel=1e-9)
        assert float(block.magnitude.xreplace(v)) == pytest.approx(N * np.sqrt(1 + float(v[s["mu"]]) ** 2))


def test_friction_on_a_rigid_body_acts_at_its_contact_point() -> None:
    """A disc on a rough incline: the friction acts at its contact point, through that point's velocity
    x_dot - R phi_dot (rotation included), with no particle; while it slides Newton and Euler give
    x_ddot = g (sin(alpha) - mu cos(alpha) S) and (m R^2/2) phi_ddot = mu m g cos(alpha) R S."""
    problem = problem_file("rough_disc_incline")
    s = names(problem)
    (term,) = matrix_form(problem).frictions
    R = s["R"]
    assert sympy.simplify(term.sliding_rate - (s["x_dot"] - R * s["phi_dot"])) == 0
    assert term.unit_generalized == (1, 0, -R)
    d = derived_file("rough_disc_incline")
    assert d.accelerations is not None
    g, alpha, mu = s["g"], s["alpha"], s["mu"]
    slide = sympy.Symbol("S")
    newton_x = g * (sympy.sin(alpha) - mu * sympy.cos(alpha) * slide)
    newton_phi = mu * g * sympy.cos(alpha) * R * slide / (R**2 / 2)
    rng = random.Random(4)
    for _ in range(6):
        v = {g: 9.81, alpha: rng.uniform(0.1, 1.4), mu: rng.uniform(0.05, 1), R: rng.uniform(0.1, 1),
             s["x_dot"]: rng.uniform(-2, 2), s["phi_dot"]: rng.uniform(-5, 5), s["m"]: 1.3}
        v[slide] = np.sign(float((s["x_dot"] - R * s["phi_dot"]).xreplace(v)))
        assert float(d.accelerations["x"].xreplace(v)) == pytest.approx(float(newton_x.xreplace(v)), rel=1e-12)
        assert float(d.accelerations["phi"].xreplace(v)) == pytest.approx(float(newton_phi.xreplace(v)), rel=1e-12)


def test_a_rolling_constraint_that_matches_only_on_the_surface_gets_its_force() -> None:
    """A disc rolling on a fixed cylinder, rolling written (R + a) theta - a phi: its coefficients match the
    contact point's velocity only where r = R + a. On the surface they do, so the friction at the contact is
    found: m g |sin(theta)|/3, from Euler's law (m a^2/2) phi_ddot = f a with phi_ddot = 2 g sin(theta)/(3a)."""
    d = derived_file("disc_on_cylinder")
    s = names(problem_file("disc_on_cylinder"))
    assert d.constraint_forces is not None
    roll = d.constraint_forces["roll"]
    assert roll.magnitude is not None
    assert sympy.simplify(roll.magnitude - s["m"] * s["g"] * sympy.Abs(sympy.sin(s["theta"])) / 3) == 0


FRICTION_FILE = """
name: a friction contact
parameters: {m: mass, M: mass, g: gravity, mu: friction, R: radius}
coordinates: [X, x, y]
particles:
  wedge: {mass: M, position: [X, 0]}
  block: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  face: {holonomic: y - x + X, on: [block, wedge]}
friction:
  rub: {coefficient: mu, normal: [face]}
"""


def _issues(text: str) -> list:
    with pytest.raises(SpecError) as caught:
        matrix_form(load_text(text))
    return list(caught.value.issues)


@pytest.mark.parametrize(("old", "new", "field", "words"), [
    ("rub: {coefficient: mu, normal: [face]}", "rub: {coefficient: mu, on: wedge, normal: [face]}",
     "friction.rub.normal", "acts on block, wedge, but the friction 'rub' on 'wedge'"),
    ("rub: {coefficient: mu, normal: [face]}", "rub: {coefficient: mu, on: [block, block], normal: [face]}",
     "friction.rub.on", "cannot carry the surface"),
    ("rub: {coefficient: mu, normal: [face]}", "rub: {coefficient: mu, on: [block, ghost], normal: [face]}",
     "friction.rub.on", "cannot carry the surface"),
    ("rub: {coefficient: mu, normal: [face]}", "rub: {coefficient: mu, on: ghost, normal: [face]}",
     "friction.rub.on", "unknown particle or body 'ghost'"),
    ("rub: {coefficient: mu, normal: [face]}", "rub: {coefficient: mu, at: [x, 0], normal: [face]}",
     "friction.rub.at", "is a particle, a point"),
    ("face: {holonomic: y - x + X, on: [block, wedge]}",
     "face: {holonomic: y - x + X, on: [block, wedge]}\n  side: {holonomic: x, on: block}",
     "", ""),
])
def test_a_contact_that_cannot_be_modelled_is_refused(old: str, new: str, field: str, words: str) -> None:
    """A pair that does not fit its normal constraint, a member that is no particle or planar body, or a point
    a particle is not at: exit 2 with the field and a fix, never a one-sided force."""
    text = FRICTION_FILE.replace(old, new)
    if not field:  # a second constraint not named by the friction is fine
        matrix_form(load_text(text))
        return
    issues = _issues(text)
    assert any(i.where == field and words in i.message and i.hint for i in issues), issues


def test_normal_constraints_that_hold_the_point_in_every_direction_are_refused() -> None:
    """In a plane, two independent normal constraints leave nothing to slide along: refused with a fix."""
    text = FRICTION_FILE.replace("face: {holonomic: y - x + X, on: [block, wedge]}",
                                 "face: {holonomic: y - x + X, on: [block, wedge]}\n  wall: {holonomic: x - X, "
                                 "on: [block, wedge]}").replace("normal: [face]", "normal: [face, wall]")
    issues = _issues(text)
    assert any(i.where == "friction.rub.normal" and "every direction" in i.message for i in issues), issues


def test_sliding_coordinates_that_do_not_move_the_point_are_refused() -> None:
    """A sliding velocity made only of the normal direction is no sliding: refused, with the field."""
    issues = _issues(FRICTION_FILE.replace("normal: [face]}", "normal: [face], sliding: [X]}").replace(
        "on: [block, wedge]}", "on: block}").replace("y - x + X", "y - x"))
    assert any(i.where == "friction.rub.sliding" for i in issues), issues


def test_friction_on_a_three_dimensional_body_is_refused() -> None:
    """The velocity of a point of a 3-D body needs its orientation: refused with a fix."""
    text = """
name: top on a rough floor
parameters: {m: mass, g: gravity, mu: friction, A: inertia}
coordinates: [x, y, z]
bodies:
  top: {mass: m, position: [x, y, z], inertia: [A, A, A], angular_velocity: [0, 0, 0]}
gravity: [0, 0, -g]
constraints:
  floor: {holonomic: z}
friction:
  rub: {coefficient: mu, on: top, normal: [floor]}
"""
    with pytest.raises(SpecError) as caught:
        load_text(text)
    assert any(i.where == "friction.rub.on" and "3-D body" in i.message and i.hint for i in caught.value.issues)


def test_a_string_between_two_particles_is_no_normal_constraint() -> None:
    """Atwood's string acts on two particles that do not touch: as a friction's normal constraint its force on
    the first is not that of a contact, so the friction is refused instead of getting a wrong normal force."""
    text = (PROBLEMS / "atwood.yaml").read_text(encoding="utf-8") + (
        "friction:\n  rub: {coefficient: 0.1, normal: [string]}\n")
    issues = _issues(text)
    assert any(i.where == "friction.rub.normal" and "no known force" in i.message for i in issues), issues


CONE = """
name: particle on a rough cone
parameters: {m: mass, g: gravity, mu: friction, alpha: half angle}
coordinates:
  r: {description: radius, positive: true}
  phi: angle
  z: height
particles: {p: {mass: m, position: [r*cos(phi), r*sin(phi), z]}}
gravity: [0, 0, -g]
constraints: {cone: {holonomic: z - r*cot(alpha), on: p}}
friction: {rub: {coefficient: mu, normal: [cone]}}
"""


def test_friction_in_a_tangent_plane_opposes_the_velocity() -> None:
    """On a cone (in space, one normal constraint, two sliding directions) the friction is kinetic,
    -mu N v/|v| with v the particle's velocity on the surface: mu N long, against v, orthogonal to the normal."""
    problem = load_text(CONE)
    (term,) = matrix_form(problem).frictions
    assert term.rate is None and term.tangent is None  # no single line: no stick-slip
    s = names(problem)
    rng = random.Random(2)
    for _ in range(6):
        a = rng.uniform(0.3, 1.2)
        r, phi, rd, phid = rng.uniform(0.5, 2), rng.uniform(-3, 3), rng.uniform(-2, 2), rng.uniform(-2, 2)
        v = {s["alpha"]: a, s["mu"]: 0.3, term.normal: 2.0, s["r"]: r, s["phi"]: phi, s["z"]: r / np.tan(a),
             s["r_dot"]: rd, s["phi_dot"]: phid, s["z_dot"]: rd / np.tan(a)}
        force = np.array([float(c.xreplace(v)) for c in term.force])
        velocity = np.array([rd * np.cos(phi) - r * phid * np.sin(phi), rd * np.sin(phi) + r * phid * np.cos(phi),
                             rd / np.tan(a)])
        assert force == pytest.approx(-0.3 * 2.0 * velocity / np.linalg.norm(velocity), rel=1e-9, abs=1e-12)
        normal = np.array([-np.cos(phi) / np.tan(a), -np.sin(phi) / np.tan(a), 1.0])
        assert force @ normal == pytest.approx(0, abs=1e-12)
