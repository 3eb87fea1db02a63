"""The problems added for issue 11 (item 7) and issue 12: every `expected:` answer and every claim of their
descriptions checked against an independent route — SymPy's ``LagrangesMethod`` or ``KanesMethod`` built here from
points, frames and bodies, or Newton's laws — at random states, never against lagsolve's own derivation.

These tests only *load* the files; none runs ``derive`` (too slow on the current code for the bigger ones; see
``mechanics_support.AWAITING_DERIVATION``).
"""

from __future__ import annotations

import functools
import random
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import sympy
from sympy.physics import mechanics as me

from lagsolve.problem.load import load_problem
from lagsolve.problem.schema import Problem

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"
NEW = ("coupled_pendulums", "triple_pendulum", "cart_two_wheels", "block_two_pendulums", "rolling_disc", "bowl")
t = me.dynamicsymbols._t


@functools.cache
def problem(name: str) -> Problem:
    return load_problem(PROBLEMS / f"{name}.yaml")


@dataclass(frozen=True)
class Route:
    """An independent derivation turned into numbers: ``accelerations(values)`` → q̈ (numpy array) for a dict of
    plain-name values (coordinates, ``<q>_dot``, parameters), and the plain symbols it uses."""

    coordinates: tuple[str, ...]
    accelerations: Callable[[Mapping[str, float]], np.ndarray]


def plain(expr: Any, qs: Sequence[Any], names: Sequence[str]) -> Any:
    """``expr`` in dynamicsymbols → plain symbols ``<name>``, ``<name>_dot``, ``<name>_ddot`` (real)."""
    swap: dict[Any, Any] = {}
    for q, n in zip(qs, names, strict=True):
        swap[q.diff(t, 2)] = sympy.Symbol(f"{n}_ddot", real=True)
    expr = me.msubs(expr, swap)
    swap = {q.diff(t): sympy.Symbol(f"{n}_dot", real=True) for q, n in zip(qs, names, strict=True)}
    expr = me.msubs(expr, swap)
    return me.msubs(expr, {q: sympy.Symbol(n, real=True) for q, n in zip(qs, names, strict=True)})


def numeric(expr: Any) -> Callable[[Mapping[str, float]], Any]:
    """``expr`` (plain symbols) as a function of a name → value dict."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    fn = sympy.lambdify(symbols, expr, modules="numpy")
    return lambda values: fn(*(values[s.name] for s in symbols))


def lagranges_route(method: me.LagrangesMethod, qs: Sequence[Any], names: Sequence[str]) -> Route:
    """q̈ from SymPy's LagrangesMethod: its full mass matrix and forcing solved numerically (no symbolic solve)."""
    n = len(qs)
    mass = numeric(plain(method.mass_matrix_full, qs, names))
    forcing = numeric(plain(method.forcing_full, qs, names))

    def accelerations(values: Mapping[str, float]) -> np.ndarray:
        solution = np.linalg.solve(np.array(mass(values), dtype=float), np.array(forcing(values), dtype=float))
        return solution.ravel()[n:2 * n]

    return Route(tuple(names), accelerations)


def evaluate(expr: Any, prob: Problem, values: Mapping[str, float], functions: Mapping[str, float] = {}) -> float:
    """An answer of the file (parsed by the loader) at ``values``; each declared function call is given its value."""
    calls = {c: functions[c.func.__name__] for c in expr.atoms(sympy.core.function.AppliedUndef)}
    expr = expr.xreplace(calls)
    swap = {s: values[s.name] for s in expr.free_symbols}
    return float(expr.xreplace(swap))


def draw(rng: random.Random, names: Sequence[str], parameters: Sequence[str]) -> dict[str, float]:
    values = {n: rng.uniform(-1.5, 1.5) for n in names}
    values |= {f"{n}_dot": rng.uniform(-2, 2) for n in names}
    values |= {p: rng.uniform(0.5, 2.5) for p in parameters}
    return values


def parameter_names(prob: Problem) -> list[str]:
    return [p.name for p in prob.parameters]


# -- every new file --------------------------------------------------------------------------------


@pytest.mark.parametrize("name", NEW)
def test_new_problem_loads_with_source_and_simulation(name: str) -> None:
    """Each new problem file loads, names its source in the description and has a complete simulation block."""
    prob = problem(name)
    assert "Source" in prob.description
    assert not prob.expected.is_empty()
    sim = prob.simulation
    assert sim is not None and sim.values and sim.initial and sim.t_end
    assert set(sim.values) == set(parameter_names(prob))


# -- coupled pendulums -------------------------------------------------------------------------------


@functools.cache
def coupled() -> tuple[Route, Any, Any]:
    th1, th2 = me.dynamicsymbols("theta1 theta2")
    m, g, length, k = sympy.symbols("m g l k", positive=True)
    N = me.ReferenceFrame("N")
    origin = me.Point("origin")
    origin.set_vel(N, 0)
    bobs = []
    for th, name in ((th1, "b1"), (th2, "b2")):
        p = origin.locatenew(name, length * sympy.sin(th) * N.x - length * sympy.cos(th) * N.y)
        p.set_vel(N, p.pos_from(origin).dt(N))
        bob = me.Particle(name, p, m)
        bob.potential_energy = m * g * p.pos_from(origin).dot(N.y)
        bobs.append(bob)
    spring = k * (length * sympy.sin(th2) - length * sympy.sin(th1)) ** 2 / 2
    lagrangian = me.Lagrangian(N, *bobs) - spring
    method = me.LagrangesMethod(lagrangian, [th1, th2])
    method.form_lagranges_equations()
    names = ("theta1", "theta2")
    energy = plain(sum(b.kinetic_energy(N) + b.potential_energy for b in bobs) + spring, [th1, th2], names)
    return lagranges_route(method, [th1, th2], names), energy, plain(method.mass_matrix, [th1, th2], names)


def test_coupled_pendulums_accelerations_and_energy() -> None:
    """The file's θ̈1, θ̈2 equal LagrangesMethod's at random states; its energy is T + V and is constant along them."""
    prob = problem("coupled_pendulums")
    route, energy, _ = coupled()
    rate = energy_rate(energy, route.coordinates)
    rng = random.Random(1)
    for _ in range(25):
        values = draw(rng, route.coordinates, parameter_names(prob))
        qdd = route.accelerations(values)
        for q, want in zip(route.coordinates, qdd, strict=True):
            assert evaluate(prob.expected.accelerations[q], prob, values) == pytest.approx(want, rel=1e-10, abs=1e-10)
        assert evaluate(prob.expected.conserved["energy"], prob, values) == pytest.approx(
            float(numeric(energy)(values)), rel=1e-12)
        assert rate(values, qdd) == pytest.approx(0, abs=1e-10)


def test_coupled_pendulums_normal_modes() -> None:
    """Linearized at θ = 0 (mass matrix and Hessian of V from the independent route): ω² = g/l and g/l + 2k/m,
    and the file's expected normal modes are these, each shape an eigenvector of M0⁻¹K for its ω²."""
    _, energy, mass = coupled()
    names = sympy.symbols("theta1 theta2", real=True)
    zero = {n: 0 for n in names} | {sympy.Symbol(f"{n}_dot", real=True): 0 for n in names}
    potential = energy.xreplace({sympy.Symbol(f"{n}_dot", real=True): 0 for n in names})
    stiffness = sympy.hessian(potential, names).xreplace(zero)
    m, g, length, k = sympy.symbols("m g l k", positive=True)
    values = {m: 1.3, g: 9.81, length: 0.7, k: 2.1}
    block = np.array((mass.xreplace(zero).inv() * stiffness).xreplace(values), dtype=float)
    omega2 = np.linalg.eigvals(block)
    want = [9.81 / 0.7, 9.81 / 0.7 + 2 * 2.1 / 1.3]
    assert sorted(omega2.real) == pytest.approx(want, rel=1e-12)
    prob = problem("coupled_pendulums")
    (modes,) = prob.expected.normal_modes
    assert {n: float(v) for n, v in modes.at.items()} == {"theta1": 0.0, "theta2": 0.0} and modes.stable is True
    plain = {s.name: v for s, v in values.items()}
    for w, shape in zip(modes.squared_frequencies, modes.shapes, strict=True):
        w_value = evaluate(w, prob, plain)
        vector = np.array([evaluate(c, prob, plain) for c in shape])
        assert block @ vector == pytest.approx(w_value * vector, rel=1e-12)
    assert sorted(evaluate(w, prob, plain) for w in modes.squared_frequencies) == pytest.approx(want, rel=1e-12)


def energy_rate(energy: Any, names: Sequence[str]) -> Callable[[Mapping[str, float], np.ndarray], float]:
    """dE/dt = Σ ∂E/∂q q̇ + ∂E/∂q̇ q̈ as a function of a state and its accelerations."""
    parts = []
    for n in names:
        q, v = sympy.Symbol(n, real=True), sympy.Symbol(f"{n}_dot", real=True)
        parts.append((numeric(sympy.diff(energy, q)), numeric(sympy.diff(energy, v)), n))

    def rate(values: Mapping[str, float], qdd: np.ndarray) -> float:
        return float(sum(float(dq(values)) * values[f"{n}_dot"] + float(dv(values)) * a
                         for (dq, dv, n), a in zip(parts, qdd, strict=True)))

    return rate


# -- triple pendulum -----------------------------------------------------------------------------------


def test_triple_pendulum_energy_is_conserved() -> None:
    """The file's energy equals T + V of three particles built from points and is constant along LagrangesMethod."""
    prob = problem("triple_pendulum")
    ths = me.dynamicsymbols("theta1:4")
    m, g, length = sympy.symbols("m g l", positive=True)
    N = me.ReferenceFrame("N")
    point = me.Point("origin")
    point.set_vel(N, 0)
    origin = point
    particles = []
    for i, th in enumerate(ths):
        point = point.locatenew(f"P{i}", length * sympy.sin(th) * N.x - length * sympy.cos(th) * N.y)
        point.set_vel(N, point.pos_from(origin).dt(N))
        particle = me.Particle(f"p{i}", point, m)
        particle.potential_energy = m * g * point.pos_from(origin).dot(N.y)
        particles.append(particle)
    method = me.LagrangesMethod(me.Lagrangian(N, *particles), list(ths))
    method.form_lagranges_equations()
    names = ("theta1", "theta2", "theta3")
    route = lagranges_route(method, ths, names)
    energy = plain(sum(p.kinetic_energy(N) + p.potential_energy for p in particles), ths, names)
    rate = energy_rate(energy, names)
    rng = random.Random(2)
    for _ in range(20):
        values = draw(rng, names, parameter_names(prob))
        assert evaluate(prob.expected.conserved["energy"], prob, values) == pytest.approx(
            float(numeric(energy)(values)), rel=1e-12)
        assert rate(values, route.accelerations(values)) == pytest.approx(0, abs=1e-9)


def test_triple_pendulum_normal_modes() -> None:
    """M0⁻¹K of the linearized triple pendulum (from the particles' T and V) has eigenvalues (g/l)·u with
    u³ − 9u² + 18u − 6 = 0, u ≈ 0.415775, 2.29428, 6.28995, as the description says."""
    u = sympy.Symbol("u")
    mass = sympy.Matrix([[3, 2, 1], [2, 2, 1], [1, 1, 1]])  # m l² times this, from T at θ = 0 (checked below)
    ths = sympy.symbols("theta1:4", real=True)
    rates = sympy.symbols("theta1_dot theta2_dot theta3_dot", real=True)
    x = y = vx = vy = sympy.Integer(0)
    kinetic = potential = sympy.Integer(0)
    for th, w in zip(ths, rates, strict=True):  # m = g = l = 1
        x, y = x + sympy.sin(th), y - sympy.cos(th)
        vx, vy = vx + sympy.cos(th) * w, vy + sympy.sin(th) * w
        kinetic += (vx**2 + vy**2) / 2
        potential += y
    zero = dict.fromkeys(ths, 0)
    assert sympy.hessian(kinetic, rates).xreplace(zero) == mass
    stiffness = sympy.hessian(potential, ths).xreplace(zero)
    assert stiffness == sympy.diag(3, 2, 1)
    assert sympy.expand((stiffness - u * mass).det()) == sympy.expand(-(u**3 - 9 * u**2 + 18 * u - 6))
    assert sympy.expand(6 * sympy.assoc_laguerre(3, 0, u)) == sympy.expand(-(u**3 - 9 * u**2 + 18 * u - 6))
    omega2 = sorted(np.linalg.eigvals(np.array(mass.inv() * stiffness, dtype=float)).real)
    assert omega2 == pytest.approx([0.415775, 2.29428, 6.28995], abs=1e-5)


# -- cart on two wheels ----------------------------------------------------------------------------


def test_cart_two_wheels_accelerations_and_friction() -> None:
    """LagrangesMethod with the four velocity constraints gives the file's q̈; the multipliers (lagsolve's convention,
    d/dt ∂L/∂q̇ − ∂L/∂q = Q + Aᵀλ) solved from its equations equal the file's Newton answers."""
    prob = problem("cart_two_wheels")
    x, x1, p1, x2, p2 = qs = me.dynamicsymbols("x x1 phi1 x2 phi2")
    M, m, R, F = sympy.symbols("M m R F", positive=True)
    N = me.ReferenceFrame("N")
    origin = me.Point("origin")
    origin.set_vel(N, 0)
    cart = origin.locatenew("cart", x * N.x + R * N.y)
    cart.set_vel(N, x.diff(t) * N.x)
    parts: list[Any] = [me.Particle("cart", cart, M)]
    for xi, pi, name in ((x1, p1, "w1"), (x2, p2, "w2")):
        centre = origin.locatenew(name, xi * N.x + R * N.y)
        centre.set_vel(N, xi.diff(t) * N.x)
        frame = N.orientnew(f"{name}_frame", "Axis", [-pi, N.z])  # turned clockwise by phi
        parts.append(me.RigidBody(name, centre, frame, m, (me.inertia(N, 0, 0, m * R**2 / 2), centre)))
    constraints = [x1.diff(t) - R * p1.diff(t), x2.diff(t) - R * p2.diff(t), x1.diff(t) - x.diff(t),
                   x2.diff(t) - x.diff(t)]
    lagrangian = me.Lagrangian(N, *parts)
    method = me.LagrangesMethod(lagrangian, list(qs), nonhol_coneqs=constraints, forcelist=[(cart, F * N.x)],
                                frame=N)
    method.form_lagranges_equations()
    names = ("x", "x1", "phi1", "x2", "phi2")
    route = lagranges_route(method, qs, names)
    # lagsolve's multipliers: A^T lam = d/dt dL/dq_dot - dL/dq - Q, solved by least squares (A has full rank)
    residual = plain(sympy.Matrix([lagrangian.diff(q.diff(t)).diff(t) - lagrangian.diff(q) for q in qs])
                     - sympy.Matrix([F, 0, 0, 0, 0]), qs, names)
    A = plain(sympy.Matrix(constraints).jacobian([q.diff(t) for q in qs]), qs, names)
    accelerations = [sympy.Symbol(f"{n}_ddot", real=True) for n in names]
    rng = random.Random(3)
    for _ in range(10):
        values = draw(rng, names, parameter_names(prob))
        speed = values["x_dot"]
        values |= {"x1_dot": speed, "x2_dot": speed, "phi1_dot": speed / values["R"], "phi2_dot": speed / values["R"]}
        qdd = route.accelerations(values)
        for q, want in zip(names, qdd, strict=True):
            assert evaluate(prob.expected.accelerations[q], prob, values) == pytest.approx(want, rel=1e-10)
        at = {**values, **{a.name: v for a, v in zip(accelerations, qdd, strict=True)}}
        rhs = np.array(numeric(residual)(at), dtype=float).ravel()
        matrix = np.array(numeric(A)(at), dtype=float)
        lam, *_ = np.linalg.lstsq(matrix.T, rhs, rcond=None)
        assert np.allclose(matrix.T @ lam, rhs, atol=1e-10)
        for name, want in zip(("roll1", "roll2", "axle1", "axle2"), lam, strict=True):
            assert evaluate(prob.expected.multipliers[name], prob, values) == pytest.approx(want, rel=1e-10)
        # Newton, by hand: x_ddot = F/(M + 3m) (each rolling disk weighs in with 3m/2)
        assert qdd[0] == pytest.approx(values["F"] / (values["M"] + 3 * values["m"]), rel=1e-12)


# -- block with two pendulums ----------------------------------------------------------------------


def test_block_two_pendulums_acceleration_and_work_rate() -> None:
    """The block's Ẍ equals LagrangesMethod's (force F on the block, torque τ on the compound pendulum); along
    those equations d(T + V)/dt = F Ẋ + τ θ̇, and with F = τ = 0 the horizontal momentum is constant."""
    prob = problem("block_two_pendulums")
    X, th, ph = qs = me.dynamicsymbols("X theta phi")
    M, m1, Ic, a, m2, length, g, F, tau = sympy.symbols("M m1 Ic a m2 l g F tau", real=True)
    N = me.ReferenceFrame("N")
    origin = me.Point("origin")
    origin.set_vel(N, 0)
    block = origin.locatenew("block", X * N.x)
    block.set_vel(N, X.diff(t) * N.x)
    frame = N.orientnew("B", "Axis", [th, N.z])
    centre = block.locatenew("c", a * frame.y * -1)  # the body hangs along -B.y: (a sin θ, -a cos θ) from the axle
    centre.set_vel(N, centre.pos_from(origin).dt(N))
    bob = block.locatenew("bob", length * sympy.sin(ph) * N.x - length * sympy.cos(ph) * N.y)
    bob.set_vel(N, bob.pos_from(origin).dt(N))
    compound = me.RigidBody("c", centre, frame, m1, (me.inertia(frame, 0, 0, Ic), centre))
    bodies = [me.Particle("block", block, M), compound, me.Particle("bob", bob, m2)]
    bodies[1].potential_energy = m1 * g * centre.pos_from(origin).dot(N.y)
    bodies[2].potential_energy = m2 * g * bob.pos_from(origin).dot(N.y)
    lagrangian = me.Lagrangian(N, *bodies)
    method = me.LagrangesMethod(lagrangian, list(qs), forcelist=[(block, F * N.x), (frame, tau * N.z)], frame=N)
    method.form_lagranges_equations()
    names = ("X", "theta", "phi")
    route = lagranges_route(method, qs, names)
    energy = plain(sum(b.kinetic_energy(N) for b in bodies) + sum(b.potential_energy for b in bodies[1:]), qs, names)
    rate = energy_rate(energy, names)
    momentum = plain(sum(b.linear_momentum(N).dot(N.x) for b in bodies), qs, names)
    momentum_rate = energy_rate(momentum, names)
    rng = random.Random(4)
    for _ in range(20):
        values = draw(rng, names, parameter_names(prob)) | {"F": rng.uniform(-2, 2), "tau": rng.uniform(-2, 2)}
        qdd = route.accelerations(values)
        expected = evaluate(prob.expected.accelerations["X"], prob, values,
                            {"F": values["F"], "tau": values["tau"]})
        assert expected == pytest.approx(qdd[0], rel=1e-10, abs=1e-10)
        power = values["F"] * values["X_dot"] + values["tau"] * values["theta_dot"]
        assert rate(values, qdd) == pytest.approx(power, rel=1e-9, abs=1e-9)
        free = values | {"F": 0.0, "tau": 0.0}
        assert momentum_rate(free, route.accelerations(free)) == pytest.approx(0, abs=1e-9)


# -- rolling disc ----------------------------------------------------------------------------------------


@functools.cache
def disc_kane() -> tuple[Any, ...]:
    """SymPy's rolling-disc example (KanesMethod, the contact point at rest): ψ̈, θ̈, φ̈, the forward and lateral
    friction from m a_centre, and T + V on the rolling surface, in plain symbols."""
    q1, q2, q3 = me.dynamicsymbols("q1:4")
    u1, u2, u3 = me.dynamicsymbols("u1:4")
    m, r, g = sympy.symbols("m r g", positive=True)
    N = me.ReferenceFrame("N")
    Y = N.orientnew("Y", "Axis", [q1, N.z])
    L = Y.orientnew("L", "Axis", [q2, Y.x])
    R = L.orientnew("R", "Axis", [q3, L.y])
    R.set_ang_vel(N, u1 * N.z + u2 * Y.x + u3 * L.y)
    contact = me.Point("C")
    contact.set_vel(N, 0)
    centre = contact.locatenew("Dmc", r * L.z)
    centre.v2pt_theory(contact, N, R)
    disc = me.RigidBody("D", centre, R, m, (me.inertia(L, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), centre))
    kane = me.KanesMethod(N, q_ind=[q1, q2, q3], u_ind=[u1, u2, u3],
                          kd_eqs=[q1.diff(t) - u1, q2.diff(t) - u2, q3.diff(t) - u3])
    kane.kanes_equations([disc], [(centre, -m * g * N.z)])
    names = ("psi", "theta", "phi")
    speeds = {u: sympy.Symbol(f"{n}_dot", real=True) for u, n in zip((u1, u2, u3), names, strict=True)}
    mass = plain(kane.mass_matrix.xreplace(speeds), (q1, q2, q3), names)
    forcing = plain(kane.forcing.xreplace(speeds), (q1, q2, q3), names)
    acceleration = centre.acc(N)
    rates = {u.diff(t): sympy.Symbol(f"{n}_ddot", real=True) for u, n in zip((u1, u2, u3), names, strict=True)}
    derivatives = {q.diff(t): s for q, s in zip((q1, q2, q3), speeds.values(), strict=True)}

    def clean(e: Any) -> Any:
        return plain(me.msubs(e, rates, derivatives, speeds), (q1, q2, q3), names)

    forward, lateral = clean(m * acceleration.dot(Y.x)), clean(m * acceleration.dot(Y.y))
    energy = clean(disc.kinetic_energy(N) + m * g * centre.pos_from(contact).dot(N.z))
    return mass, forcing, forward, lateral, energy


def rolling_state(rng: random.Random, prob: Problem) -> dict[str, float]:
    values = draw(rng, ("x", "y", "psi", "theta", "phi"), parameter_names(prob))
    values["theta"] = rng.uniform(-1.2, 1.2)  # away from lying flat (cos θ = 0)
    values["x_dot"] = values["r"] * values["phi_dot"] * np.cos(values["psi"])
    values["y_dot"] = values["r"] * values["phi_dot"] * np.sin(values["psi"])
    return values


def test_rolling_disc_accelerations_and_multipliers_against_kane_and_newton() -> None:
    """ψ̈, θ̈, φ̈ equal KanesMethod's; ẍ, ÿ follow from the rolling constraints differentiated; the multipliers equal
    the horizontal components of m a_centre (Newton: the plane's friction is the only horizontal force)."""
    prob = problem("rolling_disc")
    mass, forcing, forward, lateral, _ = disc_kane()
    mass_fn, forcing_fn = numeric(mass), numeric(forcing)
    forward_fn, lateral_fn = numeric(forward), numeric(lateral)
    rng = random.Random(5)
    for _ in range(25):
        values = rolling_state(rng, prob)
        psi_dd, theta_dd, phi_dd = np.linalg.solve(np.array(mass_fn(values), dtype=float),
                                                   np.array(forcing_fn(values), dtype=float)).ravel()
        r, psi, phi_d, psi_d = values["r"], values["psi"], values["phi_dot"], values["psi_dot"]
        want = {"psi": psi_dd, "theta": theta_dd, "phi": phi_dd,
                "x": r * phi_dd * np.cos(psi) - r * phi_d * psi_d * np.sin(psi),
                "y": r * phi_dd * np.sin(psi) + r * phi_d * psi_d * np.cos(psi)}
        for q, w in want.items():
            assert evaluate(prob.expected.accelerations[q], prob, values) == pytest.approx(w, rel=1e-9, abs=1e-9)
        at = values | {"psi_ddot": psi_dd, "theta_ddot": theta_dd, "phi_ddot": phi_dd}
        f_forward, f_lateral = float(forward_fn(at)), float(lateral_fn(at))
        friction = {"roll_x": f_forward * np.cos(psi) - f_lateral * np.sin(psi),
                    "roll_y": f_forward * np.sin(psi) + f_lateral * np.cos(psi)}
        for c, w in friction.items():
            assert evaluate(prob.expected.multipliers[c], prob, values) == pytest.approx(w, rel=1e-9, abs=1e-9)


def test_rolling_disc_energy_is_conserved() -> None:
    """The file's energy equals Kane's T + V on the rolling surface and its rate along Kane's equations is 0."""
    prob = problem("rolling_disc")
    mass, forcing, _, _, energy = disc_kane()
    mass_fn, forcing_fn = numeric(mass), numeric(forcing)
    rate = energy_rate(energy, ("psi", "theta", "phi"))
    rng = random.Random(6)
    for _ in range(20):
        values = rolling_state(rng, prob)
        assert evaluate(prob.expected.conserved["energy"], prob, values) == pytest.approx(
            float(numeric(energy)(values)), rel=1e-12)
        qdd = np.linalg.solve(np.array(mass_fn(values), dtype=float), np.array(forcing_fn(values), dtype=float))
        assert rate(values, qdd.ravel()) == pytest.approx(0, abs=1e-9)


def test_rolling_disc_file_models_the_same_disc() -> None:
    """The file's body (centre position, angular velocity components along L's axes) and constraints are those of
    the frames Y, L, R above: the centre is r L.z from the contact point, ω = ψ̇ N.z + θ̇ Y.x + φ̇ L.y, and the
    disc's material point at the contact has velocity (ẋ − r φ̇ cos ψ, ẏ − r φ̇ sin ψ, 0)."""
    prob = problem("rolling_disc")
    x, y, psi, theta, phi = qs = me.dynamicsymbols("x y psi theta phi")
    r = sympy.Symbol("r", positive=True)
    N = me.ReferenceFrame("N")
    Y = N.orientnew("Y", "Axis", [psi, N.z])
    L = Y.orientnew("L", "Axis", [theta, Y.x])
    R = L.orientnew("R", "Axis", [phi, L.y])
    origin = me.Point("origin")
    origin.set_vel(N, 0)
    contact = origin.locatenew("P", x * N.x + y * N.y)
    centre = contact.locatenew("C", r * L.z)
    names = ("x", "y", "psi", "theta", "phi")
    position = [plain(centre.pos_from(origin).dot(e), qs, names) for e in (N.x, N.y, N.z)]
    omega = [plain(R.ang_vel_in(N).dot(e), qs, names) for e in (L.x, L.y, L.z)]
    slip = centre.pos_from(origin).dt(N) + R.ang_vel_in(N).cross(-r * L.z)
    slip = [plain(slip.dot(e), qs, names) for e in (N.x, N.y, N.z)]
    (disc,) = prob.bodies
    by_name = {s.name: s for s in prob.symbols.values()}
    swap = {s: by_name[s.name] for e in (*position, *omega, *slip) for s in e.free_symbols}
    for ours, theirs in zip(disc.position, position, strict=True):
        assert sympy.simplify(ours - theirs.xreplace(swap)) == 0
    for ours, theirs in zip(disc.angular_velocity, omega, strict=True):
        assert sympy.simplify(ours - theirs.xreplace(swap)) == 0
    rolling = [c.expression for c in prob.constraints] + [sympy.Integer(0)]
    for ours, theirs in zip(rolling, slip, strict=True):
        assert sympy.simplify(ours - theirs.xreplace(swap)) == 0


# -- bowl (issue 12) -------------------------------------------------------------------------------------


def test_bowl_claims_against_newton() -> None:
    """Newton on the bowl (weight and a normal force along ∇ψ = (−x/a, −y/a, 1)): m(x ẏ − y ẋ) and the file's
    energy have zero rate at random states on the bowl."""
    prob = problem("bowl")
    rng = random.Random(7)
    for _ in range(20):
        values = {k: rng.uniform(-1.5, 1.5) for k in ("x", "y", "x_dot", "y_dot")}
        values |= {p: rng.uniform(0.5, 2.5) for p in parameter_names(prob)}
        x, y, xd, yd, m, g, a = (values[k] for k in ("x", "y", "x_dot", "y_dot", "m", "g", "a"))
        values["z"] = (x**2 + y**2) / (2 * a)
        values["z_dot"] = (x * xd + y * yd) / a
        normal = (g + (xd**2 + yd**2) / a) / (1 + (x**2 + y**2) / a**2)  # λ/m along ∇ψ
        xdd, ydd, zdd = -normal * x / a, -normal * y / a, normal - g
        assert zdd == pytest.approx((xd**2 + yd**2 + x * xdd + y * ydd) / a)  # stays on the bowl
        lz_rate = m * (x * ydd - y * xdd)
        assert lz_rate == pytest.approx(0, abs=1e-12)
        energy = prob.expected.conserved["energy"]
        symbols = {s.name: s for s in energy.free_symbols}
        grad = {n: float(sympy.diff(energy, symbols[n]).xreplace({s: values[s.name] for s in energy.free_symbols}))
                if n in symbols else 0.0 for n in ("x", "y", "x_dot", "y_dot", "z", "z_dot")}
        power = grad["x"] * xd + grad["y"] * yd + grad["x_dot"] * xdd + grad["y_dot"] * ydd
        assert power == pytest.approx(0, abs=1e-10)
        claim = prob.expected.conserved["angular_momentum"]
        assert evaluate(claim, prob, values) == pytest.approx(m * (x * yd - y * xd))
