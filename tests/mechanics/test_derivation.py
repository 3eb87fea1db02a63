"""``derive`` on the seed homework (ESM 3124 HW6) and other textbook problems: the
answers are written out by hand here, never taken from the code."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
import sympy

from lagsolve.mechanics.equations.constraints import velocity_form
from lagsolve.mechanics.symbolic.simplify import norm
from mechanics_support import (
    TUBE,
    assert_same,
    derived_file,
    derived_text,
    exactly_equal,
    names,
)

HOOP = """
name: Bead on a hoop driven about the vertical
parameters: {m: mass, g: gravity, R: radius, Omega: rate of turn}
coordinates: [r, theta, phi]
particles:
  bead: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), -r*cos(theta)]}
gravity: [0, 0, -g]
constraints:
  hoop: {holonomic: r - R}
  drive: {holonomic: phi - Omega*t}
"""


def _wire(x):
    return x**3 / 3 + sympy.sin(x)


@pytest.fixture(scope="module")
def bead():
    return derived_file("bead")


@pytest.fixture(scope="module")
def knife():
    return derived_file("knife_edge")


@pytest.fixture(scope="module")
def hole():
    return derived_file("hole_table")


@pytest.fixture(scope="module")
def tube():
    return derived_text(TUBE)


@pytest.fixture(scope="module")
def hoop():
    return derived_text(HOOP)


def bead_hint(derivation):
    """The homework hint: x_ddot, lambda and |F_c| (the magnitude with Abs)."""
    s = names(derivation.problem)
    m, g, x, xd, f = s["m"], s["g"], s["x"], s["x_dot"], s["f"]
    fp, fpp = sympy.Derivative(f(x), x), sympy.Derivative(f(x), (x, 2))
    return {
        "x_ddot": -fp * (fpp * xd**2 + g) / (1 + fp**2),
        "lambda": m * (fpp * xd**2 + g) / (1 + fp**2),
        "force": m * sympy.Abs(fpp * xd**2 + g) / sympy.sqrt(1 + fp**2),
    }


def test_bead_acceleration_is_the_hint(bead):
    """The bead's x_ddot is -f'(x)(f''(x) x_dot^2 + g)/(1 + f'(x)^2) exactly."""
    assert exactly_equal(bead.accelerations["x"], bead_hint(bead)["x_ddot"])


def test_bead_multiplier_is_the_hint(bead):
    """The wire's multiplier is m (f''(x) x_dot^2 + g)/(1 + f'(x)^2) exactly."""
    assert exactly_equal(bead.multipliers["wire"], bead_hint(bead)["lambda"])


def test_bead_force_magnitude(bead):
    """|F_c| = m |f''(x) x_dot^2 + g| / sqrt(1 + f'(x)^2), exactly and at random states."""
    magnitude = bead.constraint_forces["wire"].magnitude
    expected = bead_hint(bead)["force"]
    assert exactly_equal(magnitude, expected)
    f = names(bead.problem)["f"]
    assert_same(magnitude, expected, functions={f: _wire})


def test_bead_y_acceleration_follows_the_wire(bead):
    """y_ddot = f''(x) x_dot^2 + f'(x) x_ddot, written in x and x_dot only."""
    s = names(bead.problem)
    x, xd, f = s["x"], s["x_dot"], s["f"]
    fp, fpp = sympy.Derivative(f(x), x), sympy.Derivative(f(x), (x, 2))
    expected = fpp * xd**2 + fp * bead_hint(bead)["x_ddot"]
    assert exactly_equal(bead.accelerations["y"], expected)
    assert not bead.accelerations["y"].has(s["y"], s["y_dot"])


def test_bead_equations_are_the_homework_equations(bead):
    """The bead's equations are m x_ddot = -f'(x) lambda and m y_ddot + m g = lambda."""
    s = names(bead.problem)
    m, g, x, f = s["m"], s["g"], s["x"], s["f"]
    lam = bead.multiplier_symbols[0]
    fp = sympy.Derivative(f(x), x)
    assert exactly_equal(bead.equations[0], m * s["x_ddot"] + fp * lam)
    assert exactly_equal(bead.equations[1], m * s["y_ddot"] + m * g - lam)


def test_bead_raw_results_agree_on_the_wire(bead):
    """The unsimplified solve agrees with the displayed results wherever y = f(x) and
    y_dot = f'(x) x_dot."""
    s = names(bead.problem)
    x, y, xd, yd, f = s["x"], s["y"], s["x_dot"], s["y_dot"], s["f"]

    def on_wire(point):
        return {y: _wire(point[x]), yd: sympy.diff(_wire(x), x).subs(x, point[x]) * point[xd]}

    functions = {f: _wire}
    assert_same(bead.raw_accelerations[0], bead.accelerations["x"], functions=functions,
                complete=on_wire, also=(x, xd))
    assert_same(bead.raw_multipliers[0], bead.multipliers["wire"], functions=functions,
                complete=on_wire, also=(x, xd))


def knife_textbook(derivation):
    """The homework's four knife-edge equations as left minus right sides."""
    s = names(derivation.problem)
    m, l_, th, thd = s["m"], s["l"], s["theta"], s["theta_dot"]
    xdd, ydd, thdd, xd, yd = s["x_ddot"], s["y_ddot"], s["theta_ddot"], s["x_dot"], s["y_dot"]
    lam = derivation.multiplier_symbols[0]
    sn, cs = sympy.sin(th), sympy.cos(th)
    return [
        2 * xdd - l_ * thdd * sn - l_ * thd**2 * cs + (lam / m) * sn,
        2 * ydd + l_ * thdd * cs - l_ * thd**2 * sn - (lam / m) * cs,
        l_ * thdd - xdd * sn + ydd * cs,
        -xd * sn + yd * cs,
    ]


def test_knife_edge_equations_are_the_textbook_ones(knife):
    """Each knife-edge equation is the textbook one times m (x, y) or m l (theta)."""
    s = names(knife.problem)
    m, l_ = s["m"], s["l"]
    book = knife_textbook(knife)
    assert exactly_equal(knife.equations[0] / m, book[0])
    assert exactly_equal(knife.equations[1] / m, book[1])
    assert exactly_equal(knife.equations[2] / (m * l_), book[2])


def test_knife_edge_constraint_is_the_velocity_constraint(knife):
    """The fourth equation, -x_dot sin(theta) + y_dot cos(theta) = 0, is the skate constraint."""
    (skate,) = knife.constraints
    assert exactly_equal(velocity_form(skate, knife.model), knife_textbook(knife)[3])


def test_knife_edge_solution_matches_the_textbook_system(knife):
    """Solving the textbook equations (constraint differentiated once) gives the derived
    accelerations and multiplier."""
    s = names(knife.problem)
    lam = knife.multiplier_symbols[0]
    book = knife_textbook(knife)
    unknowns = [s["x_ddot"], s["y_ddot"], s["theta_ddot"], lam]
    book[3] = sympy.diff(book[3], s["theta"]) * s["theta_dot"] + sum(
        sympy.diff(book[3], s[f"{q}_dot"]) * s[f"{q}_ddot"] for q in ("x", "y"))
    (solution,) = sympy.solve(book, unknowns, dict=True)
    for q in ("x", "y", "theta"):
        assert exactly_equal(knife.accelerations[q], solution[s[f"{q}_ddot"]]), q
    assert exactly_equal(knife.multipliers["skate"], solution[lam])


def test_knife_edge_force_on_particle_one(knife):
    """The skate pushes particle 1 with lambda (-sin(theta), cos(theta))."""
    s = names(knife.problem)
    th = s["theta"]
    lam = knife.multipliers["skate"]
    vector = knife.constraint_forces["skate"].vector
    assert exactly_equal(vector[0], -lam * sympy.sin(th))
    assert exactly_equal(vector[1], lam * sympy.cos(th))


def test_hole_table_radial_equation(hole):
    """(m1 + m2) r_ddot = m1 r theta_dot^2 - m2 g, theta_ddot = -2 r_dot theta_dot / r and
    z_ddot = r_ddot."""
    s = names(hole.problem)
    m1, m2, g, r, rd, thd = (s[k] for k in ("m1", "m2", "g", "r", "r_dot", "theta_dot"))
    r_ddot = (m1 * r * thd**2 - m2 * g) / (m1 + m2)
    assert exactly_equal(hole.accelerations["r"], r_ddot)
    assert exactly_equal(hole.accelerations["theta"], -2 * rd * thd / r)
    assert exactly_equal(hole.accelerations["z"], r_ddot)


def test_hole_table_multiplier_is_minus_the_tension(hole):
    """lambda_string = -m1 m2 (g + r theta_dot^2)/(m1 + m2), minus the string tension."""
    s = names(hole.problem)
    m1, m2, g, r, thd = (s[k] for k in ("m1", "m2", "g", "r", "theta_dot"))
    assert exactly_equal(hole.multipliers["string"], -m1 * m2 * (g + r * thd**2) / (m1 + m2))


def test_hole_table_equations(hole):
    """m1 (r_ddot - r th_dot^2) = lambda, m1 r (r th_ddot + 2 r_dot th_dot) = 0 and
    m2 (z_ddot + g) = -lambda."""
    s = names(hole.problem)
    m1, m2, g, r, rd, thd = (s[k] for k in ("m1", "m2", "g", "r", "r_dot", "theta_dot"))
    lam = hole.multiplier_symbols[0]
    expected = [m1 * (s["r_ddot"] - r * thd**2) - lam,
                m1 * r * (r * s["theta_ddot"] + 2 * rd * thd),
                m2 * (s["z_ddot"] + g) + lam]
    for ours, hand in zip(hole.equations, expected, strict=True):
        assert exactly_equal(ours, hand)


def test_tube_multipliers(tube):
    """lambda_tilt = -m r^2 sin cos Omega^2 - m g r sin(theta) and
    lambda_spin = 2 m r r_dot Omega sin^2(theta)."""
    s = names(tube.problem)
    m, g, omega, r, rd, th = (s[k] for k in ("m", "g", "Omega", "r", "r_dot", "theta"))
    sn, cs = sympy.sin(th), sympy.cos(th)
    assert exactly_equal(tube.multipliers["tilt"],
                         -m * r**2 * sn * cs * omega**2 - m * g * r * sn)
    assert exactly_equal(tube.multipliers["spin"], 2 * m * r * rd * omega * sn**2)


def test_tube_acceleration(tube):
    """Along the tube r_ddot = r Omega^2 sin^2(theta) - g cos(theta); theta and phi do not
    accelerate."""
    s = names(tube.problem)
    g, omega, r, th = (s[k] for k in ("g", "Omega", "r", "theta"))
    assert exactly_equal(tube.accelerations["r"],
                         r * omega**2 * sympy.sin(th) ** 2 - g * sympy.cos(th))
    assert tube.accelerations["theta"] == 0
    assert tube.accelerations["phi"] == 0


def test_tube_combined_normal_force(tube):
    """The two constraint forces add up to a normal force of size
    m sin(theta) sqrt(4 Omega^2 r_dot^2 + (r Omega^2 cos(theta) + g)^2) for 0 < theta < pi."""
    s = names(tube.problem)
    m, g, omega, r, rd, th = (s[k] for k in ("m", "g", "Omega", "r", "r_dot", "theta"))
    tilt = tube.constraint_forces["tilt"].vector
    spin = tube.constraint_forces["spin"].vector
    total = [a + b for a, b in zip(tilt, spin, strict=True)]
    square = m**2 * sympy.sin(th) ** 2 * (4 * omega**2 * rd**2
                                          + (r * omega**2 * sympy.cos(th) + g) ** 2)
    assert exactly_equal(sum(c**2 for c in total), square)
    magnitude = m * sympy.sin(th) * sympy.sqrt(4 * omega**2 * rd**2
                                               + (r * omega**2 * sympy.cos(th) + g) ** 2)
    assert_same(norm(total), magnitude, ranges={th: (0.05, 3.09)})


def test_tube_forces_are_perpendicular_to_the_tube(tube):
    """Neither constraint force has a component along the tube direction e_r."""
    s = names(tube.problem)
    th, ph = s["theta"], s["phi"]
    e_r = (sympy.sin(th) * sympy.cos(ph), sympy.sin(th) * sympy.sin(ph), sympy.cos(th))
    for name in ("tilt", "spin"):
        vector = tube.constraint_forces[name].vector
        assert exactly_equal(sum(a * b for a, b in zip(vector, e_r, strict=True)), 0)


def test_time_dependent_constraint_hoop(hoop):
    """On a hoop turned at rate Omega, theta_ddot = sin(th)(Omega^2 cos(th) - g/R),
    lambda_hoop = -m R th_dot^2 - m R Omega^2 sin^2 - m g cos and
    lambda_drive = 2 m R^2 sin cos th_dot Omega."""
    s = names(hoop.problem)
    m, g, big_r, omega, th, thd = (s[k] for k in ("m", "g", "R", "Omega", "theta", "theta_dot"))
    sn, cs = sympy.sin(th), sympy.cos(th)
    assert exactly_equal(hoop.accelerations["theta"], sn * (omega**2 * cs - g / big_r))
    assert exactly_equal(hoop.accelerations["r"], 0)
    assert exactly_equal(hoop.accelerations["phi"], 0)
    assert exactly_equal(hoop.multipliers["hoop"],
                         -m * big_r * thd**2 - m * big_r * omega**2 * sn**2 - m * g * cs)
    assert exactly_equal(hoop.multipliers["drive"], 2 * m * big_r**2 * sn * cs * thd * omega)


def test_results_use_only_declared_symbols(bead, knife, hole, tube, hoop):
    """Accelerations and multipliers contain only time, parameters, coordinates and velocities."""
    for derivation in (bead, knife, hole, tube, hoop):
        allowed = set(derivation.problem.symbols.values())
        for expr in (*derivation.accelerations.values(), *derivation.multipliers.values()):
            assert expr.free_symbols <= allowed, (derivation.problem.name, expr)


def test_equation_sides_recombine(knife, hole):
    """Each equation's (left, right) sides differ by exactly the displayed equation."""
    for derivation in (knife, hole):
        for (left, right), eq in zip(derivation.equation_sides, derivation.equations, strict=True):
            assert exactly_equal(left - right, eq)


def test_lagrangian_is_t_minus_v(hole):
    """The displayed Lagrangian is T - V: m1 (r_dot^2 + r^2 th_dot^2)/2 + m2 z_dot^2/2 - m2 g z."""
    s = names(hole.problem)
    m1, m2, g, r, z, rd, thd, zd = (s[k] for k in ("m1", "m2", "g", "r", "z", "r_dot",
                                                    "theta_dot", "z_dot"))
    expected = m1 * (rd**2 + r**2 * thd**2) / 2 + m2 * zd**2 / 2 - m2 * g * z
    assert exactly_equal(hole.lagrangian, expected)
    assert exactly_equal(hole.kinetic - hole.potential, expected)


def test_derivation_is_frozen(bead):
    """A Derivation cannot be changed after derive() returns it."""
    with pytest.raises(dataclasses.FrozenInstanceError):
        bead.accelerations = {}  # type: ignore[misc]


PUCK = """
name: Puck on a rough table
parameters: {m: mass, g: gravity, mu: friction coefficient}
coordinates: [x, y, z]
particles:
  puck: {mass: m, position: [x, y, z]}
gravity: [0, 0, -g]
constraints:
  table: {holonomic: z}
friction:
  rough: {coefficient: mu, on: puck, normal: [table], sliding: [x, y]}
"""


def test_puck_on_a_rough_table():
    """A sliding puck decelerates at mu g along -v/|v|, with normal force N = m g = lambda_table."""
    derivation = derived_text(PUCK)
    s = names(derivation.problem)
    m, g, mu, xd, yd = s["m"], s["g"], s["mu"], s["x_dot"], s["y_dot"]
    speed = sympy.sqrt(xd**2 + yd**2)
    assert exactly_equal(derivation.accelerations["x"], -mu * g * xd / speed)
    assert exactly_equal(derivation.accelerations["y"], -mu * g * yd / speed)
    assert derivation.accelerations["z"] == 0
    assert exactly_equal(derivation.multipliers["table"], m * g)
    (contact,) = derivation.friction
    assert exactly_equal(contact.normal_force, m * g)


def test_rough_tube_acceleration():
    """With friction the tube gives r_ddot = r Omega^2 sin^2 - g cos - mu sign(r_dot) N/m, where
    N = m |sin(theta)| sqrt(4 Omega^2 r_dot^2 + (r Omega^2 cos + g)^2), multipliers unchanged."""
    derivation = derived_file("rotating_tube")
    s = names(derivation.problem)
    m, g, omega, mu, r, rd, th = (s[k] for k in ("m", "g", "Omega", "mu", "r", "r_dot", "theta"))
    sn, cs = sympy.sin(th), sympy.cos(th)
    normal = m * sympy.Abs(sn) * sympy.sqrt(4 * omega**2 * rd**2 + (r * omega**2 * cs + g) ** 2)
    r_ddot = r * omega**2 * sn**2 - g * cs - mu * sympy.sign(rd) * normal / m
    assert_same(derivation.accelerations["r"], r_ddot)
    (contact,) = derivation.friction
    assert_same(contact.normal_force, normal)
    assert exactly_equal(derivation.multipliers["tilt"],
                         -m * r**2 * sn * cs * omega**2 - m * g * r * sn)
    assert exactly_equal(derivation.multipliers["spin"], 2 * m * r * rd * omega * sn**2)


@pytest.mark.slow
def test_coupled_friction_normal_force_closed_form_matches_the_numeric_solve():
    """On the rough-floor ladder the closed-form N (the quadratic's root) equals the per-step numeric N
    and the floor multiplier's size, and the accelerations use the symbol N with that value."""
    import numpy as np

    from lagsolve.mechanics.derivation import derive
    from lagsolve.numeric.system import bind
    from lagsolve.problem.load import load_problem

    problem = load_problem(Path(__file__).resolve().parents[2] / "problems" / "ladder_rough_floor.yaml")
    derivation = derive(problem)
    friction = derivation.friction[0]
    assert friction.case.startswith("coupled") and friction.valid_while is not None
    system = bind(derivation.form)
    symbols = problem.symbols
    params = {symbols[n]: v for n, v in zip(system.parameter_names, system.parameters, strict=True)}
    rng = np.random.default_rng(11)
    for _ in range(12):
        angle, rate = rng.uniform(0.3, 1.2), rng.choice([-1, 1]) * rng.uniform(0.2, 2.5)
        q = np.array([np.cos(angle), 0.0, 0.0, np.sin(angle)])
        qd = np.array([-np.sin(angle) * rate, 0.0, 0.0, np.cos(angle) * rate])
        values = {**params, **{symbols[c]: v for c, v in zip(system.coordinates, q, strict=True)},
                  **{symbols[f"{c}_dot"]: v for c, v in zip(system.coordinates, qd, strict=True)}}
        closed = float(friction.normal_force.xreplace(values))
        _, lam, normal, _ = system.solve_all(0.0, q, qd)
        assert closed == pytest.approx(normal[0], rel=1e-9)
        values[friction.term.normal] = closed
        assert float(derivation.multipliers["floor"].xreplace(values)) == pytest.approx(lam[0], rel=1e-9)
        assert abs(lam[0]) == pytest.approx(closed, rel=1e-9)
