"""Equilibria and normal modes found numerically at the simulation values
(``lagsolve.mechanics.analysis.numeric_equilibria``):
the equilibria a closed-form search may miss, and ω² and mode shapes where the characteristic polynomial does not
split; each checked against SymPy's LagrangesMethod, never against lagsolve itself."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest
import sympy
from sympy.physics import mechanics as me

from mechanics_support import derived_file, derived_text

STIFF = """
name: Two pendulums joined by a stiff spring
parameters: {m: mass, g: gravity, l: length, k: spring constant}
coordinates: [theta1, theta2]
kinetic: m*l**2*(theta1_dot**2 + theta2_dot**2)/2
potential: -m*g*l*(cos(theta1) + cos(theta2)) + k*l**2*(sin(theta2) - sin(theta1))**2/2
simulation:
  values: {m: 1.0, g: 9.81, l: 1.0, k: 10.0}
  initial: {theta1: 0.1, theta2: 0.0}
  t_end: 1.0
"""


def _chain(n: int, spring: bool) -> tuple[Any, list[Any], dict[str, Any]]:
    """LagrangesMethod for n equal particles on rods (a chain, or side by side joined by a spring), built here."""
    qs = list(me.dynamicsymbols(f"theta1:{n + 1}"))
    m, g, rod, k = sympy.symbols("m g l k", positive=True)
    frame, origin = me.ReferenceFrame("N"), me.Point("O")
    origin.set_vel(frame, 0)
    particles, anchor = [], origin
    for i, q in enumerate(qs):
        base = origin if spring else anchor
        p = base.locatenew(f"P{i}", rod * sympy.sin(q) * frame.x - rod * sympy.cos(q) * frame.y)
        p.set_vel(frame, p.pos_from(origin).dt(frame))
        particle = me.Particle(f"p{i}", p, m)
        particle.potential_energy = m * g * p.pos_from(origin).dot(frame.y)
        particles.append(particle)
        anchor = p
    lagrangian = me.Lagrangian(frame, *particles)
    if spring:
        lagrangian -= k * (rod * sympy.sin(qs[1]) - rod * sympy.sin(qs[0])) ** 2 / 2
    method = me.LagrangesMethod(lagrangian, qs)
    method.form_lagranges_equations()
    return method, qs, {"m": m, "g": g, "l": rod, "k": k}


def _jacobian(method: Any, qs: list[Any], params: dict[str, Any], values: dict[str, float], point: Any) -> Any:
    """∂q̈/∂q at rest at ``point``: central differences of LagrangesMethod's accelerations, solved numerically."""
    t = me.dynamicsymbols._t
    plain = {q.diff(t): sympy.Symbol(f"v{i}") for i, q in enumerate(qs)} | {q: sympy.Symbol(f"q{i}")
                                                                             for i, q in enumerate(qs)}
    numbers = {params[n]: v for n, v in values.items() if n in params}
    state = [plain[q] for q in qs] + [plain[q.diff(t)] for q in qs]
    mass = sympy.lambdify([state], me.msubs(method.mass_matrix_full, plain).xreplace(numbers), "numpy")
    forcing = sympy.lambdify([state], me.msubs(method.forcing_full, plain).xreplace(numbers), "numpy")
    n = len(qs)

    def accelerations(q: Any) -> Any:
        y = [*q, *([0.0] * n)]
        return np.linalg.solve(np.array(mass(y), dtype=float), np.array(forcing(y), dtype=float).ravel())[n:]

    h = 1e-6
    columns = [(accelerations(point + h * e) - accelerations(point - h * e)) / (2 * h) for e in np.eye(n)]
    return np.array(columns).T


def _check_modes(mode: Any, jacobian: Any) -> None:
    """ω² are the eigenvalues of -∂q̈/∂q and each shape is an eigenvector of it, with its first component 1."""
    block = -jacobian
    want = np.sort(np.linalg.eigvals(block).real)
    got = [float(w) for w in mode.squared_frequencies]
    assert sorted(got) == pytest.approx(list(want), rel=1e-6, abs=1e-6)
    for w, u in zip(got, mode.shapes, strict=True):
        vector = np.array([float(c) for c in u])
        assert vector[0] == 1.0
        assert block @ vector == pytest.approx(w * vector, rel=1e-5, abs=1e-5)


def test_equilibria_missed_in_closed_form_are_found_numerically() -> None:
    """With a stiff spring (2 k l > m g) the pendulums also rest bent towards each other, cos θ1 = -m g/(2 k l),
    θ2 = -θ1: not found by trying the obvious values, so found by the numeric search at the simulation values,
    listed after the closed-form ones and labelled numeric; their ω² and shapes are those of LagrangesMethod's
    accelerations differentiated numerically there."""
    derivation = derived_text(STIFF)
    linear = derivation.analysis.linearization
    assert not derivation.notes and not linear.complete
    exact, numeric = linear.modes[:4], linear.modes[4:]
    assert all(not isinstance(v, sympy.Float) for m in exact for _, v in m.point)
    assert len(numeric) == 2 and "finds 2 more" in linear.search
    values = {"m": 1.0, "g": 9.81, "l": 1.0, "k": 10.0}
    method, qs, params = _chain(2, spring=True)
    bent = np.arccos(-9.81 / 20.0)
    for mode in numeric:
        assert "not found in closed form" in mode.note and "numeric" in mode.note
        point = np.array([float(v) for _, v in mode.point])
        assert abs(point[0]) == pytest.approx(bent, rel=1e-7) and point[1] == pytest.approx(-point[0], rel=1e-7)
        assert mode.stable is False
        _check_modes(mode, _jacobian(method, qs, params, values, point))


def test_weak_spring_has_only_the_closed_form_equilibria() -> None:
    """With the shipped weak spring (2 k l < m g) the numeric search finds no equilibrium beyond the four."""
    linear = derived_file("coupled_pendulums").analysis.linearization
    assert len(linear.modes) == 4 and "finds no other" in linear.search


def test_triple_pendulum_modes_are_numeric_where_the_cubic_does_not_split() -> None:
    """The triple pendulum hanging down: u³ - 9u² + 18u - 6 = 0 (u = ω² l/g) does not split, so ω² and the
    shapes are numeric at the simulation values, equal to those of LagrangesMethod's equations there; where one
    rod points up the cubic splits (ω² = g/l, ±√6 g/l) and the modes are exact, and LagrangesMethod agrees too."""
    derivation = derived_file("triple_pendulum")
    values = {"m": 1.0, "g": 9.81, "l": 1.0}
    method, qs, params = _chain(3, spring=False)
    modes = derivation.analysis.linearization.modes
    assert len(modes) == 8
    for mode in modes:
        point = np.array([float(v) for _, v in mode.point])
        if any(isinstance(w, sympy.Float) for w in mode.squared_frequencies):
            assert "numeric, at the simulation values" in mode.note
        else:
            numbers = {s: values[s.name] for w in mode.squared_frequencies for s in w.free_symbols}
            mode = dataclasses.replace(
                mode, squared_frequencies=tuple(w.xreplace(numbers) for w in mode.squared_frequencies),
                shapes=tuple(tuple(sympy.sympify(c).xreplace(numbers) for c in u) for u in mode.shapes))
        _check_modes(mode, _jacobian(method, qs, params, values, point))
    down = modes[0]
    u = sorted(float(w) * 1.0 / 9.81 for w in down.squared_frequencies)
    assert u == pytest.approx([0.415775, 2.29428, 6.28995], abs=1e-5)


def test_numeric_equilibria_show_one_point_of_a_continuum() -> None:
    """The numeric multi-start lands anywhere on a continuum of equilibria; one point of it is listed, marked
    as not isolated, and its zero omega^2 is not read as instability."""
    from lagsolve.mechanics.analysis.numeric_equilibria import numeric_linearization

    system = derived_file("two_masses_spring").analysis.system
    values = {"m1": 1.0, "m2": 2.0, "k": 5.0, "L0": 1.0}
    (mode,) = numeric_linearization(system, values, {"x1": 0.0, "x2": 1.0}).modes
    point = {q.name: float(v) for q, v in mode.point}
    assert abs(point["x2"] - point["x1"] - 1.0) < 1e-9
    assert "continuum" in mode.note and mode.stable is None
    assert sorted(float(w) for w in mode.squared_frequencies) == [0.0, 7.5]  # k (m1 + m2)/(m1 m2)




DAMPED_CART = """
name: A cart on a spring with a damped pendulum (written here, not shipped)
parameters: {M: cart, m: bob, g: gravity, l: length, k: spring, b: damping}
coordinates: [x, th]
kinetic: (M + m)*x_dot**2/2 + m*l*x_dot*th_dot*cos(th) + m*l**2*th_dot**2/2
potential: k*x**2/2 - m*g*l*cos(th)
dissipation: b*th_dot**2/2
simulation:
  values: {M: 2.0, m: 0.5, g: 9.81, l: 0.7, k: 3.0, b: 0.2}
  initial: {x: 0.1, th: 0.3}
  t_end: 1.0
"""


@pytest.mark.parametrize("source", ["triple_pendulum", "double_pendulum", "coupled_pendulums", DAMPED_CART])
def test_the_compiled_route_evaluates_what_sympy_evaluates(source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """F(q, 0), its Jacobian, M and the damping at rest, compiled by SymEngine (the route a large chain takes), equal
    SymPy's ``lambdify`` of the same matrices (the route a declared function takes) at 20 random points."""
    from lagsolve.mechanics.analysis import numeric_equilibria as ne
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    derivation = derived_file(source) if "\n" not in source else derived_text(source)
    form = matrix_form(derivation.problem, display=False)
    values = dict(derivation.problem.simulation.values)
    fast = ne._lambdified(form, values)
    monkeypatch.setattr(ne, "_engine_functions", lambda *args: None)
    slow = ne._lambdified(form, values)
    assert fast.angles == slow.angles
    rng = np.random.default_rng(1)
    for _ in range(20):
        x = rng.uniform(-2, 2, len(fast.coordinates))
        for name in ("static", "jacobian", "mass", "damping"):
            a = np.asarray(getattr(fast, name)(x), dtype=float)
            b = np.asarray(getattr(slow, name)(x), dtype=float).reshape(a.shape)
            assert np.allclose(a, b, rtol=1e-12, atol=1e-12), name
    if source == DAMPED_CART:
        assert np.max(np.abs(fast.damping(np.zeros(2)))) > 0.1  # the damping is there, not dropped


def test_a_declared_function_takes_sympys_route() -> None:
    from lagsolve.mechanics.analysis import numeric_equilibria as ne
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    form = matrix_form(derived_file("bead").problem, display=False)
    terms = ne.lagrange_terms(form.model, (), form.generalized_forces, engine="symengine")
    assert ne._engine_functions(terms.forcing, terms.mass_matrix, list(form.model.coordinates),
                                list(form.model.velocities), {}) is None
