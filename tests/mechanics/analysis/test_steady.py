"""Steady motions by Routh's reduction (``lagsolve.mechanics.analysis.steady``): the condition, its roots, stability
and the
frequency of small oscillations, against textbook closed forms, SymPy's LagrangesMethod (numerical eigenvalues of its
linearized equations) and simulations of slightly perturbed steady motions integrated from SymPy's equations."""

from __future__ import annotations

import numpy
import pytest
import sympy
from scipy.integrate import solve_ivp
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.mechanics.analysis.steady import steady_motions
from lagsolve.mechanics.stages import StageSkipped
from mechanics_support import derived_file, derived_text, exactly_equal, names

TOP_VALUES = {"m": 1.0, "l": 0.1, "I1": 0.002, "I3": 0.004, "g": 9.81}


@pytest.fixture(scope="module")
def top():
    return derived_file("heavy_top")


@pytest.fixture(scope="module")
def pendulum():
    return derived_file("spherical_pendulum")


def test_top_condition_is_goldsteins(top):
    """The top's steady precession solves Goldstein's I1' phi_dot^2 cos(theta0) - I3 omega3 phi_dot + m g l = 0
    (I1' = I1 + m l^2, p_psi = I3 omega3): the same roots, real when (I3 omega3)^2 >= 4 I1' m g l cos(theta0), with
    the slow precession m g l/(I3 omega3) and the fast one I3 omega3/(I1' cos(theta0)) for a fast top."""
    steady = top.analysis.steady
    s = names(top.problem)
    m, g, length, I1, th = s["m"], s["g"], s["l"], s["I1"], s["theta"]
    p = sympy.Symbol("p_psi", real=True)
    J = I1 + m * length**2
    assert steady.rate == s["phi"] and steady.velocity == s["phi_dot"] and steady.coordinate == th
    assert [h[1] for h in steady.held] == [p]
    A, B, C = steady.coefficients
    ratio = sympy.simplify(A / (J * sympy.cos(th)))
    assert ratio != 0 and exactly_equal(B / ratio, -p) and exactly_equal(C / ratio, m * g * length)
    textbook = [p * (1 + k * sympy.sqrt(1 - 4 * J * m * g * length * sympy.cos(th) / p**2)) / (2 * J * sympy.cos(th))
                for k in (-1, 1)]
    assert exactly_equal(sum(steady.roots), sum(textbook))
    assert exactly_equal(steady.roots[0] * steady.roots[1], textbook[0] * textbook[1])
    assert exactly_equal(steady.exists_if.lhs - steady.exists_if.rhs, p**2 - 4 * J * m * g * length * sympy.cos(th))
    slow, fast = steady.limits
    assert exactly_equal(slow, m * g * length / p) and exactly_equal(fast, p / (J * sympy.cos(th)))
    assert steady.excluded == (sympy.sin(th),)
    assert steady.verified == "equations of motion"


def test_top_steady_precession_is_stable_with_the_nutation_frequency(top):
    """About a steady precession the top nutates at omega^2 = (p_psi/I1' - 2 phi_dot cos(theta0))^2 +
    phi_dot^2 sin^2(theta0) (by hand from V_eff'' with m g l eliminated), always positive: stable; a fast top
    (phi_dot -> slow root -> 0) nutates at I3 omega3/I1', Goldstein's nutation frequency."""
    steady = top.analysis.steady
    s = names(top.problem)
    m, length, I1, th, w = s["m"], s["l"], s["I1"], s["theta"], s["phi_dot"]
    p = sympy.Symbol("p_psi", real=True)
    J = I1 + m * length**2
    assert exactly_equal(steady.frequency_squared, (p / J - 2 * w * sympy.cos(th)) ** 2 + w**2 * sympy.sin(th) ** 2)
    assert steady.stable is True and steady.stability_condition is None
    assert steady.frequency_squared.xreplace({w: 0}) == (p / J) ** 2
    assert exactly_equal(steady.curvature, J * steady.frequency_squared)


def _top_equations():
    """The heavy top written independently, Goldstein's L = I1'(theta_dot^2 + phi_dot^2 sin^2)/2 +
    I3(psi_dot + phi_dot cos)^2/2 - m g l cos, through SymPy's LagrangesMethod: a numeric right-hand side for the
    state (theta, theta_dot, phi_dot, psi_dot)."""
    phi, theta, psi = dynamicsymbols("phi theta psi")
    t = dynamicsymbols._t
    values = TOP_VALUES
    J = values["I1"] + values["m"] * values["l"] ** 2
    pd, td, sd = phi.diff(t), theta.diff(t), psi.diff(t)
    L = (J * (td**2 + pd**2 * sympy.sin(theta) ** 2) / 2 + values["I3"] * (sd + pd * sympy.cos(theta)) ** 2 / 2
         - values["m"] * values["g"] * values["l"] * sympy.cos(theta))
    method = LagrangesMethod(L, [phi, theta, psi])
    method.form_lagranges_equations()
    accelerations = method.mass_matrix.LUsolve(method.forcing)
    a, b, c, d = sympy.symbols("a b c d")  # theta, theta_dot, phi_dot, psi_dot
    plain = {theta: a, td: b, pd: c, sd: d}
    order = sorted(plain, key=lambda f: -sympy.count_ops(f))  # derivatives before the functions they contain
    rates = [expr.subs([(f, plain[f]) for f in order]) for expr in accelerations]
    f = sympy.lambdify((a, b, c, d), [b, rates[1], rates[0], rates[2]], "numpy")
    return lambda y: numpy.array(f(*y), dtype=float)


def _top_state(steady, theta0: float, spin: float) -> tuple[numpy.ndarray, float]:
    """The slow steady precession at theta0 with I3 omega3 = I3 spin, as (theta, theta_dot, phi_dot, psi_dot), and
    lagsolve's omega there."""
    values = {sympy.Symbol(k, positive=True): v for k, v in TOP_VALUES.items()}
    p = sympy.Symbol("p_psi", real=True)
    th = steady.coordinate
    point = {**{s: values[sympy.Symbol(s.name, positive=True)] for s in steady.frequency_squared.free_symbols
                if s.name in TOP_VALUES},
             **{s: values[sympy.Symbol(s.name, positive=True)] for r in steady.roots for s in r.free_symbols
                if s.name in TOP_VALUES}, p: TOP_VALUES["I3"] * spin, th: theta0}
    rate = float(steady.roots[0].xreplace(point))
    omega = float(sympy.sqrt(steady.frequency_squared.xreplace({**point, steady.velocity: rate})))
    return numpy.array([theta0, 0.0, rate, spin - rate * numpy.cos(theta0)]), omega


def test_top_nutation_frequency_is_an_eigenvalue_of_sympys_linearized_equations(top):
    """The linearized equations of SymPy's LagrangesMethod about the slow steady precession have eigenvalues ±i omega
    with lagsolve's omega (and the precession rate is an equilibrium of them: theta_ddot = 0 there)."""
    rhs = _top_equations()
    state, omega = _top_state(top.analysis.steady, 0.5, 100.0)
    assert numpy.abs(rhs(state)).max() < 1e-9
    h = 1e-6
    jacobian = numpy.column_stack([(rhs(state + h * e) - rhs(state - h * e)) / (2 * h) for e in numpy.eye(4)])
    eigen = numpy.linalg.eigvals(jacobian)
    assert max(abs(eigen.imag)) == pytest.approx(omega, rel=1e-6)
    assert max(abs(eigen.real)) < 1e-6 * omega


def test_top_perturbed_steady_precession_nutates_at_the_predicted_frequency(top):
    """A slightly tilted steady precession, integrated from SymPy's equations, nutates with the period 2 pi/omega."""
    rhs = _top_equations()
    state, omega = _top_state(top.analysis.steady, 0.5, 100.0)
    state[0] += 1e-3
    run = solve_ivp(lambda _, y: rhs(y), (0.0, 2.0), state, rtol=1e-10, atol=1e-12, dense_output=True)
    assert run.success
    period = _period(run, 0)
    assert 2 * numpy.pi / period == pytest.approx(omega, rel=2e-3)


def _period(run, index: int) -> float:
    """The mean period of component ``index`` of a solve_ivp run, from its upward crossings of its mean value."""
    times = numpy.linspace(run.t[0], run.t[-1], 200_001)
    values = run.sol(times)[index]
    values = values - values.mean()
    up = numpy.nonzero((values[:-1] < 0) & (values[1:] >= 0))[0]
    crossings = times[up] - values[up] * (times[up + 1] - times[up]) / (values[up + 1] - values[up])
    assert len(crossings) >= 4
    return float((crossings[-1] - crossings[0]) / (len(crossings) - 1))


def test_conical_pendulum_matches_thornton_and_marion(pendulum):
    """The spherical pendulum's steady motion is the conical pendulum, phi_dot^2 = g/(l cos(theta0)) for
    cos(theta0) > 0, stable, and theta oscillates about it at omega^2 = g (1 + 3 cos^2(theta0))/(l cos(theta0))
    (Thornton and Marion, ch. 7), that is phi_dot^2 (1 + 3 cos^2(theta0))."""
    steady = pendulum.analysis.steady
    s = names(pendulum.problem)
    g, length, th, w = s["g"], s["l"], s["theta"], s["phi_dot"]
    assert steady.held == () and steady.coefficients[1] == 0
    assert exactly_equal(steady.square, g / (length * sympy.cos(th)))
    assert exactly_equal(steady.exists_if.lhs - steady.exists_if.rhs, sympy.cos(th))
    assert isinstance(steady.exists_if, sympy.StrictGreaterThan)
    assert exactly_equal(steady.frequency_squared_at, g * (1 + 3 * sympy.cos(th) ** 2) / (length * sympy.cos(th)))
    assert exactly_equal(steady.frequency_squared, w**2 * (1 + 3 * sympy.cos(th) ** 2))
    assert steady.stable is True


def test_perturbed_conical_pendulum_oscillates_at_the_predicted_frequency(pendulum):
    """A conical pendulum at theta0 = 0.5 started slightly off its angle, integrated from Newton's equations on the
    sphere (theta_ddot = sin cos phi_dot^2 - g sin/l, phi_ddot = -2 cot theta_dot phi_dot), oscillates in theta with
    the period 2 pi/omega of lagsolve's omega."""
    steady = pendulum.analysis.steady
    g, length, theta0 = 9.81, 1.0, 0.5
    s = names(pendulum.problem)
    at = {s["g"]: g, s["l"]: length, s["theta"]: theta0}
    rate = numpy.sqrt(float(steady.square.xreplace(at)))
    omega = numpy.sqrt(float(steady.frequency_squared_at.xreplace(at)))

    def rhs(_: float, y: numpy.ndarray) -> list[float]:
        th, thd, ph_d = y
        return [thd, numpy.sin(th) * numpy.cos(th) * ph_d**2 - g * numpy.sin(th) / length,
                -2 * numpy.cos(th) / numpy.sin(th) * thd * ph_d]

    assert rhs(0, numpy.array([theta0, 0.0, rate]))[1] == pytest.approx(0.0, abs=1e-12)
    run = solve_ivp(rhs, (0.0, 20.0), [theta0 + 1e-3, 0.0, rate], rtol=1e-10, atol=1e-12, dense_output=True)
    assert 2 * numpy.pi / _period(run, 0) == pytest.approx(omega, rel=2e-3)


def test_circular_orbits_of_the_cone_and_the_central_force():
    """The cone's horizontal circles: phi_dot^2 = g cot(alpha)/r0 with omega^2 = 3 g sin(alpha) cos(alpha)/r0 (the
    file's description, by hand); Kepler's circular orbits: theta_dot^2 = k/(m r0^3) with omega = theta_dot, so
    nearly circular orbits close (Goldstein, ch. 3)."""
    cone = derived_file("cone")
    s = names(cone.problem)
    g, a, r, w = s["g"], s["alpha"], s["r"], s["phi_dot"]
    steady = cone.analysis.steady
    assert exactly_equal(steady.square, g / (r * sympy.tan(a)))
    assert exactly_equal(steady.frequency_squared_at, 3 * g * sympy.sin(a) * sympy.cos(a) / r)
    assert exactly_equal(steady.frequency_squared, 3 * w**2 * sympy.sin(a) ** 2) and steady.stable is True
    kepler = derived_file("central_force")
    s = names(kepler.problem)
    steady = kepler.analysis.steady
    assert exactly_equal(steady.square, s["k"] / (s["m"] * s["r"] ** 3))
    assert steady.frequency_squared == s["theta_dot"] ** 2
    assert exactly_equal(steady.frequency_squared_at, steady.square)


def test_no_cyclic_coordinate_declines_with_a_reason():
    """Without a cyclic coordinate there is no steady motion to find but rest: the stage says so, cheaply."""
    bead = derived_file("bead_on_rotating_hoop")
    assert bead.analysis.steady is None
    assert "no coordinate is cyclic" in bead.analysis.steady_note
    found, reason = steady_motions(bead.analysis.system, bead.analysis.effective_potential)
    assert found is None and "no coordinate is cyclic" in reason


def test_a_condition_without_the_rate_is_declined():
    """The cylinder on the sliding wedge: dL/ds at rest does not involve X_dot, so no rate makes s steady."""
    wedge = derived_file("wedge_cylinder")
    assert wedge.analysis.steady is None
    assert wedge.analysis.steady_note.startswith("dL/ds at rest does not involve the cyclic velocities")


def test_a_large_lagrangian_is_declined_at_once(monkeypatch, top):
    """A Lagrangian past the size limit is declined before any solving, as 'too large' (a stage note of kind size)."""
    import lagsolve.mechanics.analysis.steady as steady

    monkeypatch.setattr(steady, "SIZE_LIMIT", 5)
    with pytest.raises(StageSkipped, match="^too large"):
        steady.steady_motions(top.analysis.system, top.analysis.effective_potential)


ORBIT_WITH_DRAG = """
name: Orbit with a radial drag
parameters: {m: mass, k: strength, c: drag}
coordinates: {r: {description: radius, positive: true}, theta: polar angle}
particles: {p: {mass: m, position: [r*cos(theta), r*sin(theta)]}}
potential: -k/r
dissipation: c*r_dot**2/2
"""


def test_radial_damping_keeps_the_circular_orbits():
    """A drag on r alone vanishes on a circular orbit: the steady motions are Kepler's, their omega undamped."""
    d = derived_text(ORBIT_WITH_DRAG)
    s = names(d.problem)
    steady = d.analysis.steady
    assert exactly_equal(steady.square, s["k"] / (s["m"] * s["r"] ** 3))
    assert steady.stable is True
