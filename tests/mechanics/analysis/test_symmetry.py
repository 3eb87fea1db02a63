"""Noether's theorem beyond cyclic coordinates (``lagsolve.mechanics.analysis.symmetry``): the momenta of the
translations and
rotations of the whole system, checked against Newton's laws (the total force or the moment about the axis vanishes)
and against simulations integrated from Newton's equations, never against lagsolve itself."""

from __future__ import annotations

import numpy
import pytest
import sympy
from scipy.integrate import solve_ivp

from lagsolve.mechanics.analysis.symmetry import symmetries
from lagsolve.mechanics.stages import StageSkipped
from mechanics_support import PROBLEMS, derived_file, derived_text, exactly_equal, names


def _found(derivation):
    return {c.name: c for c in derivation.analysis.conservation.quantities}


def _noether(derivation):
    return {c.name: c for c in derivation.analysis.conservation.quantities if c.kind == "noether"}


def test_bowl_angular_momentum_is_the_rotations_momentum():
    """The bowl in Cartesian x, y (z eliminated) conserves L_z = m(x y_dot - y x_dot), the momentum of the rotation
    about z, delta(x, y) = (-y, x) epsilon; Newton (weight and a normal force along (-x/a, -y/a, 1)) gives
    x y_ddot - y x_ddot = 0 for any normal force, so its rate vanishes."""
    d = derived_file("bowl")
    s = names(d.problem)
    m, x, y, xd, yd = s["m"], s["x"], s["y"], s["x_dot"], s["y_dot"]
    found = _noether(d)
    assert list(found) == ["L_z"]
    L_z = found["L_z"]
    assert exactly_equal(L_z.expression, m * (x * yd - y * xd))
    assert L_z.symmetry == "rotation about z" and L_z.generator == (-y, x)
    N, a = sympy.Symbol("N"), s["a"]
    newton = {s["x_ddot"]: -N * x / (a * m), s["y_ddot"]: -N * y / (a * m)}
    rate = d.model.time_derivative(L_z.expression, second_order=True).xreplace(newton)
    assert sympy.expand(rate) == 0


def test_two_masses_total_momentum():
    """Two masses on a spring conserve P_x = m1 x1_dot + m2 x2_dot (the translation delta x1 = delta x2 = epsilon);
    Newton's third law: m1 x1_ddot + m2 x2_ddot = k(x2 - x1 - L0) - k(x2 - x1 - L0) = 0. No other translation or
    rotation survives the rail."""
    d = derived_file("two_masses_spring")
    s = names(d.problem)
    found = _noether(d)
    assert list(found) == ["P_x"]
    P = found["P_x"]
    assert exactly_equal(P.expression, s["m1"] * s["x1_dot"] + s["m2"] * s["x2_dot"])
    assert P.generator == (1, 1) and P.symmetry == "translation along x"
    stretch = s["x2"] - s["x1"] - s["L0"]
    newton = {s["x1_ddot"]: s["k"] * stretch / s["m1"], s["x2_ddot"]: -s["k"] * stretch / s["m2"]}
    assert sympy.expand(d.model.time_derivative(P.expression, second_order=True).xreplace(newton)) == 0


def test_cartesian_spherical_pendulum_conserves_only_the_vertical_angular_momentum():
    """On the full system with the rod x^2 + y^2 + z^2 = l^2 kept as a constraint, only the rotation about z leaves T,
    V and the rod unchanged: L_z = m(x y_dot - y x_dot); translations move the rod's sphere and gravity breaks the
    horizontal rotations."""
    d = derived_file("spherical_pendulum_cartesian")
    s = names(d.problem)
    found = _noether(d)
    assert list(found) == ["L_z"]
    assert exactly_equal(found["L_z"].expression, s["m"] * (s["x"] * s["y_dot"] - s["y"] * s["x_dot"]))
    assert d.analysis.system.kind == "full"


def test_cartesian_spherical_pendulum_keeps_L_z_in_a_simulation():
    """Integrated from Newton's equations m r_ddot = lambda r - m g e_z with lambda = m (g z - |v|^2)/l^2 (the rod
    differentiated twice), the file's initial state keeps lagsolve's L_z constant to 1e-9 while it swings."""
    d = derived_file("spherical_pendulum_cartesian")
    s = names(d.problem)
    g, length = 9.81, 1.0
    L_z = sympy.lambdify([s[n] for n in ("m", "x", "y", "x_dot", "y_dot")], _noether(d)["L_z"].expression)

    def rhs(_: float, u: numpy.ndarray) -> numpy.ndarray:
        r, v = u[:3], u[3:]
        lam = (g * r[2] - v @ v) / length**2
        return numpy.concatenate([v, lam * r - numpy.array([0.0, 0.0, g])])

    start = numpy.array([0.6, 0.0, -0.8, 0.0, 1.8, 0.0])
    run = solve_ivp(rhs, (0.0, 10.0), start, rtol=1e-12, atol=1e-12, t_eval=numpy.linspace(0, 10, 401))
    values = numpy.array([L_z(1.0, *run.y[[0, 1, 3, 4], k]) for k in range(run.y.shape[1])])
    assert numpy.ptp(run.y[0]) > 0.5  # it really moves
    assert numpy.abs(values - values[0]).max() < 1e-9 * abs(values[0])


FREE = """
name: Free particle
parameters: {m: mass}
coordinates: [x, y, z]
particles: {p: {mass: m, position: [x, y, z]}}
"""

PROJECTILE = FREE.replace("name: Free particle", "name: Projectile").replace(
    "parameters: {m: mass}", "parameters: {m: mass, g: gravity}") + "gravity: [0, 0, -g]\n"


def test_free_particle_has_all_six_momenta():
    """A free particle conserves P = m v along every axis and L = m r x v about every axis."""
    d = derived_text(FREE)
    s = names(d.problem)
    m, (x, y, z), (xd, yd, zd) = s["m"], (s["x"], s["y"], s["z"]), (s["x_dot"], s["y_dot"], s["z_dot"])
    found = _noether(d)
    assert list(found) == ["L_x", "L_y", "L_z"]  # the translations are the cyclic x, y, z: their p's, named
    assert exactly_equal(found["L_x"].expression, m * (y * zd - z * yd))
    assert exactly_equal(found["L_y"].expression, m * (z * xd - x * zd))
    assert exactly_equal(found["L_z"].expression, m * (x * yd - y * xd))
    momenta = _found(d)
    assert [momenta[f"p_{q}"].symmetry for q in "xyz"] == [f"translation along {q}" for q in "xyz"]


def test_gravity_keeps_the_horizontal_translations_and_the_vertical_rotation():
    """Under gravity along -z the projectile keeps P_x, P_y (the cyclic x, y) and L_z, not P_z, L_x, L_y."""
    d = derived_text(PROJECTILE)
    assert list(_noether(d)) == ["L_z"]
    momenta = _found(d)
    assert momenta["p_x"].symmetry == "translation along x" and momenta["p_y"].symmetry == "translation along y"
    assert "p_z" not in momenta


DAMPED = """
name: Two damped masses
parameters: {m1: mass, m2: mass, k: stiffness, c: damping}
coordinates: [x1, x2]
particles: {a: {mass: m1, position: [x1, 0]}, b: {mass: m2, position: [x2, 0]}}
potential: k*(x2 - x1)**2/2
dissipation: DISSIPATION
"""


@pytest.mark.parametrize(("dissipation", "conserved"), [("c*x1_dot**2/2", False), ("c*(x2_dot - x1_dot)**2/2", True)])
def test_a_force_that_works_along_the_translation_breaks_it(dissipation: str, conserved: bool):
    """Damping of one body's velocity does work along the common translation (Q.xi != 0), so P_x is not conserved;
    damping of the relative velocity does none (its two forces cancel), so P_x stays."""
    d = derived_text(DAMPED.replace("DISSIPATION", dissipation))
    assert ("P_x" in _noether(d)) is conserved


SPINNING_DISC = """
name: Disc on a central spring
parameters: {M: mass, I: moment of inertia, k: stiffness}
coordinates: [x, y, th]
bodies:
  disc: {mass: M, position: [x, y], inertia: I, angular_velocity: th_dot}
potential: k*(x**2 + y**2)/2
"""


def test_a_planar_body_turns_with_the_rotation():
    """Rotating a planar body about z also turns it: the flow is (-y, x, 1) and L_z = M(x y_dot - y x_dot) + I th_dot,
    the total angular momentum (orbital and spin)."""
    d = derived_text(SPINNING_DISC)
    s = names(d.problem)
    L_z = _noether(d)["L_z"]
    assert L_z.generator == (-s["y"], s["x"], 1)
    assert exactly_equal(L_z.expression, s["M"] * (s["x"] * s["y_dot"] - s["y"] * s["x_dot"]) + s["I"] * s["th_dot"])


def test_cyclic_momenta_are_named_by_their_symmetry():
    """A symmetry that shifts one cyclic coordinate gives its momentum, named, not repeated: p_phi of the spherical
    pendulum and of the heavy top is the rotation about z (for the top, with the body turning at unit rate)."""
    for name in ("spherical_pendulum", "heavy_top", "central_force"):
        d = derived_file(name)
        assert not _noether(d)
        turning = [c for c in d.analysis.conservation.quantities if c.symmetry]
        assert [c.symmetry for c in turning] == ["rotation about z"]
        assert turning[0].kind == "momentum"
    top = _found(derived_file("heavy_top"))
    assert top["p_psi"].symmetry == "" and top["p_phi"].generator == (1, 0, 0)


def test_a_rolling_constraint_breaks_the_translations():
    """The knife edge's constraint involves x_dot and y_dot: its force does work along a translation (a.xi != 0)."""
    assert not _noether(derived_file("knife_edge"))


def test_without_positions_the_stage_has_nothing_to_do():
    """The driven oscillator gives T and V directly: no positions to move, so no symmetry is sought (a silent note)."""
    d = derived_file("driven_oscillator")
    assert not any(n.stage == "symmetries" for n in d.notes)  # an 'n/a' note is not shown
    with pytest.raises(StageSkipped, match="no particle or body positions"):
        symmetries(d.problem, d.analysis.system, d.analysis.conservation)


def test_a_name_the_problem_uses_is_not_taken():
    """When the problem already has a parameter L_z, the momentum is called angular_momentum_z."""
    d = derived_text(PROJECTILE.replace("parameters: {m: mass, g: gravity}",
                                        "parameters: {m: mass, g: gravity, L_z: a length}"))
    assert list(_noether(d)) == ["angular_momentum_z"]


def test_the_rotations_poisson_bracket_is_its_flow_on_the_momenta():
    """In Hamiltonian form the bowl's L_z is x p_y - y p_x exactly, and {L_z, H} = 0 is proved (it is the change of L
    along the flow)."""
    d = derived_file("bowl")
    bracket = next(b for b in d.hamiltonian.brackets if b.name == "L_z")
    p_x, p_y = (sympy.Symbol(f"p_{q}", real=True) for q in "xy")
    s = names(d.problem)
    assert sympy.expand(bracket.quantity - (s["x"] * p_y - s["y"] * p_x)) == 0
    assert bracket.status == "symbolic" and bracket.rate == 0


def test_a_simulation_monitors_the_symmetrys_momentum():
    """`simulate` monitors L_z of the Cartesian spherical pendulum next to the energy, as a column and a drift."""
    import lagsolve

    run = lagsolve.simulate(str(PROBLEMS / "spherical_pendulum_cartesian.yaml"), t_end=2.0, samples=201)
    column = run.columns()["L_z"]
    assert numpy.abs(column - column[0]).max() < 1e-8 * abs(column[0])
    assert "L_z conserved: relative drift" in run.summary


def test_large_positions_are_declined_at_once(monkeypatch):
    """Positions past the size limit are declined before any flow is solved, as 'too large'."""
    import lagsolve.mechanics.analysis.symmetry as symmetry

    d = derived_file("bowl")
    monkeypatch.setattr(symmetry, "SIZE_LIMIT", 2)
    with pytest.raises(StageSkipped, match="^too large"):
        symmetry.symmetries(d.problem, d.analysis.system, d.analysis.conservation, d.analysis.reduced.substitution)
