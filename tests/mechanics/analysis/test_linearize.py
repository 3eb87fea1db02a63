"""Equilibria and normal modes of several degrees of freedom (``lagsolve.mechanics.analysis.linearize``)."""

from __future__ import annotations

from typing import Any

import pytest
import sympy

from mechanics_support import derived_file, derived_text, exactly_equal, names

COUPLED = """
name: Two masses, three springs, one damper
parameters: {m: mass, k: stiffness, c: damping}
coordinates: [x1, x2]
particles:
  a: {mass: m, position: [x1, 0]}
  b: {mass: m, position: [x2, 0]}
potential: k*x1**2/2 + k*(x2 - x1)**2/2 + k*x2**2/2
dissipation: c*x1_dot**2/2
"""


def test_double_pendulum_normal_modes():
    """Equal masses and lengths: omega^2 = (2 - sqrt 2) g/l and (2 + sqrt 2) g/l about the hanging position."""
    pendulum = derived_file("double_pendulum")
    s = names(pendulum.problem)
    g, rod = s["g"], s["l"]
    modes = pendulum.analysis.linearization.modes
    assert len(modes) == 4
    down = next(m for m in modes if all(v == 0 for _, v in m.point))
    assert down.stable is True
    expected = sorted([(2 - sympy.sqrt(2)) * g / rod, (2 + sympy.sqrt(2)) * g / rod], key=sympy.default_sort_key)
    assert len(down.squared_frequencies) == 2
    for got in down.squared_frequencies:
        assert any(exactly_equal(got, want) for want in expected)
    assert exactly_equal(down.stiffness, sympy.Matrix([[2 * s["m"] * g * rod, 0], [0, s["m"] * g * rod]]))


def test_double_pendulum_other_equilibria_are_unstable():
    """Every equilibrium with a rod pointing up has a negative omega^2: unstable."""
    modes = derived_file("double_pendulum").analysis.linearization.modes
    up = [m for m in modes if any(v != 0 for _, v in m.point)]
    assert len(up) == 3 and all(m.stable is False for m in up)


GENERAL_DOUBLE = """
name: Double pendulum with unequal masses and lengths
parameters: {m1: upper mass, m2: lower mass, l1: upper length, l2: lower length, g: gravity}
coordinates: [a, b]
particles:
  p1: {mass: m1, position: [l1*sin(a), -l1*cos(a)]}
  p2: {mass: m2, position: [l1*sin(a) + l2*sin(b), -l1*cos(a) - l2*cos(b)]}
gravity: [0, -g]
"""


def test_general_double_pendulum_is_stable_hanging_down():
    """ω² = g(S ∓ √R)/(2 m1 l1 l2) with S = (m1 + m2)(l1 + l2), R = (m1 + m2)(S(l1 + l2) − 4 m1 l1 l2)
    (Taylor 11.4, numerically equal at random parameters): neither sign follows from the factors, yet both are
    positive, since K is positive definite (Sylvester); every other equilibrium is unstable."""
    import random

    d = derived_text(GENERAL_DOUBLE)
    s = names(d.problem)
    m1, m2, l1, l2, g = (s[k] for k in ("m1", "m2", "l1", "l2", "g"))
    S = (m1 + m2) * (l1 + l2)
    R = (m1 + m2) * ((m1 + m2) * (l1 + l2) ** 2 - 4 * m1 * l1 * l2)
    textbook = [g * (S - sympy.sqrt(R)) / (2 * m1 * l1 * l2), g * (S + sympy.sqrt(R)) / (2 * m1 * l1 * l2)]
    modes = d.analysis.linearization.modes
    down = next(m for m in modes if all(v == 0 for _, v in m.point))
    assert down.stable is True and all(f is not None for f in down.frequencies)
    rng = random.Random(5)
    for _ in range(10):
        at = {x: sympy.Float(rng.uniform(0.2, 4.0)) for x in (m1, m2, l1, l2, g)}
        got = sorted(float(w.xreplace(at)) for w in down.squared_frequencies)
        want = sorted(float(w.xreplace(at)) for w in textbook)
        assert all(abs(a - b) < 1e-12 * b for a, b in zip(got, want, strict=True))
    assert sorted(m.stable for m in modes) == [False, False, False, True]


def test_damping_gives_d_and_no_modes():
    """With a damper the linearization carries D = diag(c, 0) and says the modes are not computed."""
    coupled = derived_text(COUPLED)
    (mode,) = coupled.analysis.linearization.modes
    c = names(coupled.problem)["c"]
    assert exactly_equal(mode.damping, sympy.Matrix([[c, 0], [0, 0]]))
    assert mode.squared_frequencies is None and "damping" in mode.note


def test_cyclic_coordinates_are_left_to_the_effective_potential():
    """The hole table (one coordinate after removing theta) is handled by the effective potential instead."""
    hole = derived_file("hole_table")
    assert hole.analysis.linearization is None
    assert hole.analysis.effective_potential is not None


def test_two_masses_on_a_spring_form_a_continuum_of_equilibria():
    """Two free masses joined by a spring of rest length L0 are in equilibrium wherever x2 - x1 = L0: the
    equilibria are one line, not isolated points. It is given once, with x2 arbitrary, and the modes are
    the textbook ones (Taylor, ch. 11): the free translation (omega^2 = 0) and the stretching mode
    omega^2 = k (m1 + m2)/(m1 m2), with the reduced mass m1 m2/(m1 + m2)."""
    spring = derived_file("two_masses_spring")
    s = names(spring.problem)
    (mode,) = spring.analysis.linearization.modes
    assert mode.free == (s["x2"],)
    assert exactly_equal(dict(mode.point)[s["x1"]], s["x2"] - s["L0"])
    m1, m2, k = s["m1"], s["m2"], s["k"]
    expected = [sympy.S(0), k * (m1 + m2) / (m1 * m2)]
    assert len(mode.squared_frequencies) == 2
    assert all(any(exactly_equal(got, want) for want in expected) for got in mode.squared_frequencies)
    assert mode.stable is None and "continuum" in mode.note  # neutral along the line, not "unstable"


def test_no_force_at_rest_makes_every_configuration_an_equilibrium():
    """A charge in a uniform magnetic field feels no force at rest: every (x, y) is an equilibrium, said once
    (not eight random points of the plane)."""
    charge = derived_text("""
name: Charge in a magnetic field
parameters: {m: mass, q: charge, B: field}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
forces:
  - on: p
    force: [q*B*y_dot, -q*B*x_dot]
simulation:
  values: {m: 1, q: 1, B: 2}
  initial: {x: 0.3, y: -0.2}
""")
    (mode,) = charge.analysis.linearization.modes
    assert mode.point == () and {q.name for q in mode.free} == {"x", "y"}
    assert "every configuration" in mode.note


def test_a_singular_point_of_the_coordinates_is_no_equilibrium():
    """The elastic pendulum in polar coordinates: F(q, 0) = 0 also at r = 0, but only because the theta
    equation carries the factor r of M (the true theta_ddot = -(2 r_dot theta_dot + g sin theta)/r is
    singular there). Such points are not listed as (stable!) equilibria. The hanging one is
    r0 = l0 + m g/k with omega^2 = k/m (the spring) and g/r0 (the pendulum) — Taylor, problem 7.31."""
    elastic = derived_text("""
name: Elastic pendulum
parameters: {m: mass, k: stiffness, l0: rest length, g: gravity}
coordinates: [r, theta]
particles:
  bob: {mass: m, position: [r*sin(theta), -r*cos(theta)]}
gravity: [0, -g]
potential: k*(r - l0)**2/2
""")
    s = names(elastic.problem)
    modes = elastic.analysis.linearization.modes
    assert all(dict(m.point)[s["r"]] != 0 for m in modes)
    (down,) = [m for m in modes if dict(m.point)[s["theta"]] == 0]
    r0 = s["l0"] + s["m"] * s["g"] / s["k"]
    assert exactly_equal(dict(down.point)[s["r"]], r0)
    assert down.stable is True
    expected = [s["k"] / s["m"], s["g"] / r0]
    assert all(any(exactly_equal(got, want) for want in expected) for got in down.squared_frequencies)


def test_decoupled_equilibria_are_sympys_solutions():
    """Equations that each hold one coordinate are solved one by one, with sympy.solve's solutions."""
    import itertools

    from lagsolve.mechanics.analysis.linearize import _decoupled

    x, y = sympy.symbols("x y", real=True)
    g, a = sympy.symbols("g a", positive=True)
    systems = [[-2 * g * sympy.sin(x), -g * sympy.sin(y) ** 3], [g * sympy.cos(x), sympy.sin(y)],
               [g * sympy.sin(x) - a, sympy.cos(y) * g * a]]
    key = lambda d: sympy.default_sort_key(sympy.Tuple(d[x], d[y]))  # noqa: E731
    for static in systems:
        ours = _decoupled(static, [x, y])
        assert ours is not None
        assert sorted(ours, key=key) == sorted(sympy.solve(static, [x, y], dict=True), key=key)
    assert _decoupled([sympy.sin(x) * sympy.cos(y), sympy.sin(y)], [x, y]) is None
    assert list(itertools.chain(_decoupled([sympy.sin(x), sympy.sin(y)], [x, y]) or [])) != []


def test_splits_agrees_with_factor_list():
    from lagsolve.mechanics.analysis.linearize import _splits

    s, g, ell, m = sympy.symbols("s g ell m", positive=True)
    for expr in [(s - g / ell) * (s**2 - 3 * g * s / ell + g**2 / ell**2),
                 s**3 - 6 * g * s**2 + 9 * g**2 * s - 2 * g**3 * m, s**3 - 2 * g, (s - g) ** 3, s**2 - 2 * g * ell]:
        polynomial = sympy.Poly(expr, s)
        expected = all(f.degree() <= 2 for f, _ in sympy.factor_list(polynomial)[1])
        assert _splits(polynomial, s) is expected


def test_determinants_over_a_shared_integer_ring_equal_sympys():
    """K - s M0 over the integer polynomials in its symbols (the ring built once) has SymPy's determinant, and a
    matrix with fractions, roots or functions in it takes SymPy's own construction."""
    from lagsolve.mechanics.analysis.linearize import _determinant, _over_integers

    g, l, m, s, k = sympy.symbols("g l m s k", positive=True)  # noqa: E741 - the rod length
    K = sympy.Matrix([[3 * g * l * m, 0, -k], [0, 2 * g * l * m, k], [-k, k, g * l * m]])
    M0 = sympy.Matrix([[3 * l**2 * m, 2 * l**2 * m, l**2 * m], [2 * l**2 * m, 2 * l**2 * m, -l**2 * m],
                       [l**2 * m, -l**2 * m, l**2 * m]])
    matrix = K - s * M0
    assert _over_integers(matrix) is not None
    assert sympy.expand(_determinant(matrix) - matrix.det(method="berkowitz")) == 0
    for other in (matrix + sympy.eye(3) * sympy.Rational(1, 2), matrix + sympy.eye(3) * sympy.sqrt(2),
                  matrix + sympy.eye(3) * sympy.cos(g), sympy.eye(3) * 2):
        assert _over_integers(other) is None
        assert sympy.expand(_determinant(other) - other.det(method="berkowitz")) == 0


# -- normal modes against independent routes ----------------------------------------------------------------


def _lagranges_method(kind: str) -> tuple[Any, list[Any], dict[str, Any]]:
    """SymPy's LagrangesMethod, built here from points and particles (an independent route), for the two
    pendulums joined by a spring (``"spring"``) or the double pendulum (``"double"``) of equal masses and rods."""
    from sympy.physics import mechanics as me

    qs = list(me.dynamicsymbols("theta1 theta2"))
    m, g, rod, k = sympy.symbols("m g l k", positive=True)
    frame, origin = me.ReferenceFrame("N"), me.Point("O")
    origin.set_vel(frame, 0)
    particles, anchor = [], origin
    for i, q in enumerate(qs):
        base = anchor if kind == "double" else origin
        p = base.locatenew(f"P{i}", rod * sympy.sin(q) * frame.x - rod * sympy.cos(q) * frame.y)
        p.set_vel(frame, p.pos_from(origin).dt(frame))
        particle = me.Particle(f"p{i}", p, m)
        particle.potential_energy = m * g * p.pos_from(origin).dot(frame.y)
        particles.append(particle)
        anchor = p
    lagrangian = me.Lagrangian(frame, *particles)
    if kind == "spring":
        lagrangian -= k * (rod * sympy.sin(qs[1]) - rod * sympy.sin(qs[0])) ** 2 / 2
    method = me.LagrangesMethod(lagrangian, qs)
    method.form_lagranges_equations()
    return method, qs, {"m": m, "g": g, "l": rod, "k": k}


def _linear_block(method: Any, qs: list[Any], point: dict[str, Any]) -> Any:
    """-M0⁻¹K from LagrangesMethod's own linearization at ``point`` (the lower left block of its A)."""
    from sympy.physics import mechanics as me

    t = me.dynamicsymbols._t
    rates = [q.diff(t) for q in qs]
    op = {q: point[q.name] for q in qs} | {v: 0 for v in rates} | {q.diff(t, 2): 0 for q in qs}
    A, _, _ = method.linearize(q_ind=qs, qd_ind=rates, A_and_B=True, op_point=op)
    return A[len(qs):, :len(qs)]


def _check_against_lagranges_method(derivation: Any, kind: str) -> None:
    """At every equilibrium lagsolve lists, at random parameter values: its ω² are the eigenvalues of
    LagrangesMethod's -A21 = M0⁻¹K and each shape u solves M0⁻¹K u = ω² u."""
    import random

    import numpy as np

    method, qs, params = _lagranges_method(kind)
    rng = random.Random(11)
    for mode in derivation.analysis.linearization.modes:
        block = -_linear_block(method, qs, {q.name: v for q, v in mode.point})
        for _ in range(4):
            values = {name: rng.uniform(0.5, 2.5) for name in params}
            ours = {s: values[s.name] for w in mode.squared_frequencies for s in w.free_symbols}
            numbers = np.array(block.xreplace({params[n]: v for n, v in values.items()}).tolist(), dtype=float)
            want = np.sort(np.linalg.eigvals(numbers).real)
            got = sorted(float(w.xreplace(ours)) for w in mode.squared_frequencies)
            assert got == pytest.approx(list(want), rel=1e-10, abs=1e-10)
            for w, u in zip(mode.squared_frequencies, mode.shapes, strict=True):
                at = {s: values[s.name] for e in (w, *u) for s in e.free_symbols}
                vector = np.array([float(c.xreplace(at)) for c in u])
                assert numbers @ vector == pytest.approx(float(w.xreplace(at)) * vector, rel=1e-9, abs=1e-9)


def test_coupled_pendulums_modes_in_closed_form() -> None:
    """The two pendulums joined by a spring (problems/coupled_pendulums.yaml), the issue's textbook case: hanging
    down, ω² = g/l in phase, u = (1, 1), and ω² = g/l + 2k/m out of phase, u = (1, -1) (Taylor, ch. 11;
    Thornton & Marion, ch. 12), in closed form and without a stage running out of its share; the four
    equilibria and their modes agree with SymPy's LagrangesMethod linearized there."""
    pendulums = derived_file("coupled_pendulums")
    s = names(pendulums.problem)
    g, rod, k, m = s["g"], s["l"], s["k"], s["m"]
    assert not pendulums.notes
    linear = pendulums.analysis.linearization
    assert len(linear.modes) == 4 and "finds no other" in linear.search
    down = linear.modes[0]
    assert all(v == 0 for _, v in down.point) and down.stable is True
    assert exactly_equal(down.squared_frequencies[0], g / rod)
    assert exactly_equal(down.squared_frequencies[1], g / rod + 2 * k / m)
    assert down.shapes == ((1, 1), (1, -1))
    assert sorted(mode.stable for mode in linear.modes) == [False, False, False, True]
    _check_against_lagranges_method(pendulums, "spring")


def test_double_pendulum_mode_shapes() -> None:
    """The double pendulum hanging down: θ2/θ1 = √2 in the slow mode and -√2 in the fast one (Taylor, §11.4),
    and at every equilibrium the modes are LagrangesMethod's."""
    pendulum = derived_file("double_pendulum")
    down = pendulum.analysis.linearization.modes[0]
    assert down.shapes == ((1, sympy.sqrt(2)), (1, -sympy.sqrt(2)))
    _check_against_lagranges_method(pendulum, "double")


def _period(times: Any, signal: Any) -> float:
    """The mean time between upward zero crossings of ``signal`` (linear interpolation between samples)."""
    import numpy as np

    crossings = [times[i] - signal[i] * (times[i + 1] - times[i]) / (signal[i + 1] - signal[i])
                 for i in range(len(signal) - 1) if signal[i] < 0 <= signal[i + 1]]
    return float(np.mean(np.diff(crossings)))


def test_a_small_oscillation_started_in_a_mode_keeps_its_shape_and_period() -> None:
    """Started at rest at ε u (ε = 1e-4) from each of lagsolve's mode shapes hanging down, the full nonlinear
    motion (LagrangesMethod's equations, integrated by SciPy) keeps θ2 = u2 θ1 and repeats with the period
    2π/ω of that mode."""
    import numpy as np
    from scipy.integrate import solve_ivp
    from sympy.physics import mechanics as me

    values = {"m": 1.0, "g": 9.81, "l": 1.0, "k": 2.0}
    method, qs, params = _lagranges_method("spring")
    t = me.dynamicsymbols._t
    plain = {q.diff(t): sympy.Symbol(f"v{i}") for i, q in enumerate(qs)} | {q: sympy.Symbol(f"q{i}")
                                                                             for i, q in enumerate(qs)}
    numbers = {params[n]: v for n, v in values.items()}
    state = [plain[q] for q in qs] + [plain[q.diff(t)] for q in qs]
    mass = sympy.lambdify([state], me.msubs(method.mass_matrix_full, plain).xreplace(numbers), "numpy")
    forcing = sympy.lambdify([state], me.msubs(method.forcing_full, plain).xreplace(numbers), "numpy")

    def rates(_: float, y: Any) -> Any:
        return np.linalg.solve(np.array(mass(y), dtype=float), np.array(forcing(y), dtype=float).ravel())

    down = derived_file("coupled_pendulums").analysis.linearization.modes[0]
    for w, u in zip(down.squared_frequencies, down.shapes, strict=True):
        omega = float(sympy.sqrt(w).xreplace({s: values[s.name] for s in w.free_symbols}))
        shape = np.array([float(c) for c in u])
        times = np.linspace(0, 6 * 2 * np.pi / omega, 6001)
        run = solve_ivp(rates, (0, times[-1]), [*(1e-4 * shape), 0.0, 0.0], t_eval=times, rtol=1e-11, atol=1e-15)
        assert _period(run.t, run.y[0]) == pytest.approx(2 * np.pi / omega, rel=1e-5)
        assert np.max(np.abs(run.y[1] - shape[1] * run.y[0])) <= 1e-8


TORSION = """
name: two pendulums on torsion springs
parameters: {m: mass, g: gravity, l: length, k: torsion stiffness, a: rest angle}
gravity: [0, -g]
coordinates: [theta1, theta2]
particles:
  bob1: {mass: m, position: [l*sin(theta1), -l*cos(theta1)]}
  bob2: {mass: m, position: [l*sin(theta2), -l*cos(theta2)]}
potential: k*(theta1 - a)**2/2 + k*(theta2 - a)**2/2 + k*(theta1 - theta2)**2/4
simulation: {values: {m: 0.5, g: 9.81, l: 2.0, k: 2.0, a: 0.8}, initial: {theta1: 0.3, theta2: 0.2}, t_end: 1.0}
"""


def test_equilibria_without_a_closed_form_are_numeric_and_say_why() -> None:
    """m g l sin θ + k (θ - a) = 0 has no closed form: neither the cheap search nor the general solve (each
    within its CPU cap) finds it, no stage runs out of its share, and the equilibria come from the numeric search,
    whose sentence says why. Checked independently: the first (hanging) one is θ1 = θ2 from SciPy's brentq, its
    ω² the eigenvalues of M₀⁻¹K with K written out by hand; every other one makes ∂V/∂θ vanish (written out by
    hand) and is unstable (the springs are too weak to hold the pendulums up)."""
    import numpy as np
    from scipy.optimize import brentq

    derivation = derived_text(TORSION)
    assert derivation.notes == ()
    linear = derivation.analysis.linearization
    assert linear.search.startswith("No equilibrium in closed form (the general symbolic solve did not finish")
    assert "numeric search at the simulation values" in linear.search
    m, g, length, k, rest = 0.5, 9.81, 2.0, 2.0, 0.8
    theta = brentq(lambda x: m * g * length * np.sin(x) + k * (x - rest), 0.0, rest)
    mode, *others = linear.modes
    assert [float(v) for _, v in mode.point] == pytest.approx([theta, theta], abs=1e-7)
    diagonal = m * g * length * np.cos(theta) + 1.5 * k
    stiffness = np.array([[diagonal, -k / 2], [-k / 2, diagonal]]) / (m * length**2)
    assert [float(w) for w in mode.squared_frequencies] == pytest.approx(sorted(np.linalg.eigvalsh(stiffness)),
                                                                         rel=1e-6)
    assert mode.stable is True
    assert others and all(other.stable is False for other in others)
    for other in others:
        t1, t2 = (float(v) for _, v in other.point)
        assert m * g * length * np.sin(t1) + k * (t1 - rest) + k * (t1 - t2) / 2 == pytest.approx(0, abs=1e-6)
        assert m * g * length * np.sin(t2) + k * (t2 - rest) + k * (t2 - t1) / 2 == pytest.approx(0, abs=1e-6)
