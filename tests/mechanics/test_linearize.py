"""Equilibria and normal modes of several degrees of freedom (``lagsolve.mechanics.linearize``)."""

from __future__ import annotations

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


def test_numeric_equilibria_show_one_point_of_a_continuum():
    """The numeric multi-start lands anywhere on a continuum of equilibria; one point of it is listed, marked
    as not isolated, and its zero omega^2 is not read as instability."""
    from lagsolve.mechanics.linearize import numeric_linearization

    system = derived_file("two_masses_spring").analysis.system
    values = {"m1": 1.0, "m2": 2.0, "k": 5.0, "L0": 1.0}
    (mode,) = numeric_linearization(system, values, {"x1": 0.0, "x2": 1.0}).modes
    point = {q.name: float(v) for q, v in mode.point}
    assert abs(point["x2"] - point["x1"] - 1.0) < 1e-9
    assert "continuum" in mode.note and mode.stable is None
    assert sorted(float(w) for w in mode.squared_frequencies) == [0.0, 7.5]  # k (m1 + m2)/(m1 m2)


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

    from lagsolve.mechanics.linearize import _decoupled

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
    from lagsolve.mechanics.linearize import _splits

    s, g, ell, m = sympy.symbols("s g ell m", positive=True)
    for expr in [(s - g / ell) * (s**2 - 3 * g * s / ell + g**2 / ell**2),
                 s**3 - 6 * g * s**2 + 9 * g**2 * s - 2 * g**3 * m, s**3 - 2 * g, (s - g) ** 3, s**2 - 2 * g * ell]:
        polynomial = sympy.Poly(expr, s)
        expected = all(f.degree() <= 2 for f, _ in sympy.factor_list(polynomial)[1])
        assert _splits(polynomial, s) is expected


def test_determinants_over_a_shared_integer_ring_equal_sympys():
    """K - s M0 over the integer polynomials in its symbols (the ring built once) has SymPy's determinant, and a
    matrix with fractions, roots or functions in it takes SymPy's own construction."""
    from lagsolve.mechanics.linearize import _determinant, _over_integers

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
