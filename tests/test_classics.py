"""Classic textbook systems the project had not seen (issue 28): PyDy's three-coordinate holonomic system and the
two-wheeled cart with three velocity constraints derive completely, and their accelerations, multipliers and forces
of constraint agree with independent routes — SymPy's ``KanesMethod`` (PyDy's own model of the system) and
``LagrangesMethod``, built here from frames, points and bodies and solved numerically — at random states, never
with lagsolve itself. The files' ``expected:`` answers (derived by hand) are held to the same routes.
"""

from __future__ import annotations

import functools
import random
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp
from sympy.physics import mechanics as me

from lagsolve.mechanics.derivation import Derivation
from mechanics_support import problem_file

t = me.dynamicsymbols._t
PYDY = ("q1", "q2", "q3")
CART = ("x", "y", "theta", "phiR", "phiL")


def _plain(expr: Any, qs: tuple[Any, ...], names: tuple[str, ...]) -> Any:
    """``expr`` in dynamicsymbols → the plain names ``q``, ``q_dot``, ``q_ddot``."""
    swap: dict[Any, Any] = {}
    for q, n in zip(qs, names, strict=True):
        swap[q.diff(t, 2)] = sympy.Symbol(f"{n}_ddot")
    expr = me.msubs(expr, swap)
    expr = me.msubs(expr, {q.diff(t): sympy.Symbol(f"{n}_dot") for q, n in zip(qs, names, strict=True)})
    return me.msubs(expr, {q: sympy.Symbol(n) for q, n in zip(qs, names, strict=True)})


def _numeric(expr: Any) -> Callable[[Mapping[str, float]], Any]:
    """``expr`` (plain names and symbols for the specified inputs) as a function of a name → value mapping."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    fn = sympy.lambdify(symbols, expr, modules="numpy")
    return lambda values: fn(*(values[s.name] for s in symbols))


def _ours(expr: Any, values: Mapping[str, float]) -> float:
    """One of lagsolve's results at ``values`` (each declared function call, F(t), given its value by name)."""
    calls = {c: values[c.func.__name__] for c in expr.atoms(sympy.core.function.AppliedUndef)}
    expr = expr.xreplace(calls)
    return float(expr.xreplace({s: values[s.name] for s in expr.free_symbols}))


# -- PyDy's multi degree of freedom holonomic system ------------------------------------------------------------


@functools.cache
def pydy_kane() -> tuple[Any, ...]:
    """PyDy's model as its documentation builds it: KanesMethod with u1 = q1', u2 = the speed of B's centre along
    B.x, u3 = q3'; loads on the points and frames as given there. Returns q̈ as expressions in the plain names
    (the speeds' rates solved numerically by the caller: the mass matrix and forcing, and the map q̇ → u, u̇ → q̈)."""
    q1, q2, q3 = qs = me.dynamicsymbols("q1 q2 q3")
    u1, u2, u3 = us = me.dynamicsymbols("u1 u2 u3")
    F, T = sympy.symbols("F T")
    k, c, ma, mb, mc, IB, length, kT, g = sympy.symbols("k c ma mb mc IB l kT g")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", (q2, N.z))
    C = B.orientnew("C", "Axis", (q3, N.z))
    O = me.Point("O")  # noqa: E741 - PyDy's name for the origin
    Pab = O.locatenew("Pab", q1 * N.x)
    Bo = Pab.locatenew("Bo", -2 * length / 3 * B.y)
    Pbc = Pab.locatenew("Pbc", -length * B.y)
    Pc = Pbc.locatenew("Pc", -length * C.y)
    Pab.set_vel(N, Pab.pos_from(O).dt(N))
    Bo.v2pt_theory(Pab, N, B)
    Pbc.v2pt_theory(Pab, N, B)
    Pc.v2pt_theory(Pbc, N, C)
    speeds = [sympy.Eq(u1, Pab.vel(N).dot(N.x)), sympy.Eq(u2, Bo.vel(N).dot(B.x)),
              sympy.Eq(u3, C.ang_vel_in(B).dot(B.z))]
    qdots = sympy.solve(speeds, [q.diff(t) for q in qs], dict=True)[0]
    Pab.set_vel(N, Pab.vel(N).subs(qdots))
    Bo.set_vel(N, Bo.vel(N).subs(qdots))
    Pc.set_vel(N, Pc.vel(N).subs(qdots))
    B.set_ang_vel(N, B.ang_vel_in(N).subs(qdots))
    C.set_ang_vel(B, u3 * N.z)
    loads = [(Pab, (F - k * q1 - c * qdots[q1.diff(t)]) * N.x), (Bo, -mb * g * N.y), (Pc, -mc * g * N.y),
             (B, (T + kT * q3) * N.z), (C, -kT * q3 * N.z)]
    bodies = [me.Particle("block", Pab, ma), me.RigidBody("pendulum", Bo, B, mb, (me.inertia(B, 0, 0, IB), Bo)),
              me.Particle("bob", Pc, mc)]
    kane = me.KanesMethod(N, qs, us, kd_eqs=[s.rhs - s.lhs for s in speeds])
    kane.kanes_equations(bodies, loads=loads)
    rates = sympy.Matrix(kane.mass_matrix).LUsolve(sympy.Matrix(kane.forcing))  # u̇(q, u): small, exact
    # q̇(q, u), so q̈ = ∂q̇/∂q q̇ + ∂q̇/∂u u̇; then u(q, q̇) from the speeds' definitions
    qdot = sympy.Matrix([qdots[q.diff(t)] for q in qs])
    qdd = qdot.jacobian(list(qs)) * qdot + qdot.jacobian(list(us)) * rates
    u_of_qdot = {s.lhs: s.rhs for s in speeds}
    return tuple(_plain(me.msubs(e, u_of_qdot), qs, PYDY) for e in qdd), (qs, us, qdot, rates)


def _pydy_state(rng: random.Random) -> dict[str, float]:
    values = {n: rng.uniform(-1.5, 1.5) for n in PYDY} | {f"{n}_dot": rng.uniform(-2, 2) for n in PYDY}
    values |= {p: rng.uniform(0.5, 2.5) for p in ("k", "c", "ma", "mb", "mc", "IB", "l", "kT", "g")}
    return values | {"F": rng.uniform(-3, 3), "T": rng.uniform(-3, 3)}


def test_pydy_system_derives_completely(shipped_derivation: Callable[[str], Derivation]) -> None:
    """PyDy's system derives completely with the default budget: explicit q̈, no stage note at all."""
    derivation = shipped_derivation("multidof_holonomic")
    assert derivation.notes == ()
    assert derivation.accelerations is not None and set(derivation.accelerations) == set(PYDY)


def test_pydy_accelerations_agree_with_kanes_method(shipped_derivation: Callable[[str], Derivation]) -> None:
    """lagsolve's q̈ (raw and as shown) and the file's hand-derived ones equal those of PyDy's own KanesMethod model,
    with its generalized speeds, at random states and inputs."""
    prob = problem_file("multidof_holonomic")
    derivation = shipped_derivation("multidof_holonomic")
    kane = [_numeric(e) for e in pydy_kane()[0]]
    rng = random.Random(28)
    for _ in range(20):
        values = _pydy_state(rng)
        want = [float(f(values)) for f in kane]
        for i, name in enumerate(PYDY):
            assert _ours(derivation.raw_accelerations[i], values) == pytest.approx(want[i], rel=1e-9, abs=1e-9)
            assert _ours(derivation.accelerations[name], values) == pytest.approx(want[i], rel=1e-9, abs=1e-9)
            assert _ours(prob.expected.accelerations[name], values) == pytest.approx(want[i], rel=1e-9, abs=1e-9)


def test_pydy_accelerations_agree_with_lagranges_method(shipped_derivation: Callable[[str], Derivation]) -> None:
    """The same q̈ from SymPy's LagrangesMethod on T − V of the three bodies, with the damper, F and T as loads."""
    q1, q2, q3 = qs = me.dynamicsymbols("q1 q2 q3")
    F, T = sympy.symbols("F T")
    k, c, ma, mb, mc, IB, length, kT, g = sympy.symbols("k c ma mb mc IB l kT g")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", (q2, N.z))
    origin = me.Point("O")
    origin.set_vel(N, 0)
    block = origin.locatenew("block", q1 * N.x)
    centre = block.locatenew("centre", 2 * length / 3 * (sympy.sin(q2) * N.x - sympy.cos(q2) * N.y))
    bob = block.locatenew("bob", length * (sympy.sin(q2) + sympy.sin(q2 + q3)) * N.x
                          - length * (sympy.cos(q2) + sympy.cos(q2 + q3)) * N.y)
    for p in (block, centre, bob):
        p.set_vel(N, p.pos_from(origin).dt(N))
    parts = [me.Particle("block", block, ma), me.RigidBody("B", centre, B, mb, (me.inertia(B, 0, 0, IB), centre)),
             me.Particle("bob", bob, mc)]
    potential = mb * g * centre.pos_from(origin).dot(N.y) + mc * g * bob.pos_from(origin).dot(N.y) \
        + k * q1**2 / 2 + kT * q3**2 / 2
    method = me.LagrangesMethod(me.Lagrangian(N, *parts) - potential, list(qs), frame=N,
                                forcelist=[(block, (F - c * q1.diff(t)) * N.x), (B, T * N.z)])
    method.form_lagranges_equations()
    mass, forcing = _numeric(_plain(method.mass_matrix, qs, PYDY)), _numeric(_plain(method.forcing, qs, PYDY))
    derivation = shipped_derivation("multidof_holonomic")
    rng = random.Random(29)
    for _ in range(20):
        values = _pydy_state(rng)
        want = np.linalg.solve(np.array(mass(values), dtype=float), np.array(forcing(values), dtype=float)).ravel()
        for i in range(3):
            assert _ours(derivation.raw_accelerations[i], values) == pytest.approx(want[i], rel=1e-9, abs=1e-9)


@pytest.mark.slow
def test_pydy_simulation_follows_kanes_equations() -> None:
    """``lagsolve.simulate`` of the file (PyDy's constants, inputs and initial state) ends where an integration of
    PyDy's KanesMethod equations by SciPy ends, to 1e-7."""
    import lagsolve

    prob = problem_file("multidof_holonomic")
    run = lagsolve.simulate(prob, t_end=3.0, samples=2)
    _, (qs, us, qdot, rates) = pydy_kane()
    sim = prob.simulation
    assert sim is not None
    constants = {sympy.Symbol(k): float(v) for k, v in sim.values.items()}
    inputs = {sympy.Symbol("F"): 5 * sympy.sin(2 * sympy.pi * t), sympy.Symbol("T"): 10 * sympy.cos(2 * sympy.pi * t)}
    state = [*qs, *us]
    plain_state = [sympy.Symbol(f"s{i}") for i in range(6)]
    swap = dict(zip(state, plain_state, strict=True))
    rhs = sympy.lambdify([t, plain_state], [me.msubs(e, inputs, constants, swap) for e in (*qdot, *rates)], "numpy")
    start = [float(sim.initial[n]) for n in PYDY] + [0.0, 0.0, 0.0]  # at rest: every u is 0
    done = solve_ivp(lambda time, y: rhs(time, y), (0.0, 3.0), start, method="DOP853", rtol=1e-11, atol=1e-12)
    assert done.success
    assert np.allclose(run.motion.q[-1], done.y[:3, -1], rtol=1e-7, atol=1e-7)


# -- the two-wheeled cart ----------------------------------------------------------------------------------------


@functools.cache
def cart_lagrange() -> tuple[Any, Any, Any]:
    """The cart with SymPy's LagrangesMethod: the chassis and both wheels as rigid bodies in the plane, the wheels'
    spin as their own kinetic energy, the three velocity constraints and the motor torques as generalized forces.
    Returns the full mass matrix and forcing (unknowns q̇, q̈, λ) and the constraints' Jacobian, in plain names."""
    x, y, th, pr, pl = qs = me.dynamicsymbols("x y theta phiR phiL")
    mc, mw, Ic, Iw, Im, r, b, d = sympy.symbols("mc mw Ic Iw Im r b d")
    tauR, tauL = sympy.symbols("tauR tauL")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (th, N.z))
    origin = me.Point("O")
    origin.set_vel(N, 0)
    axle = origin.locatenew("P", x * N.x + y * N.y)
    axle.set_vel(N, axle.pos_from(origin).dt(N))
    parts = []
    for name, offset, mass, inertia in (("chassis", d * A.x, mc, Ic), ("right", -b * A.y, mw, Im),
                                        ("left", b * A.y, mw, Im)):
        point = axle.locatenew(name, offset)
        point.v2pt_theory(axle, N, A)
        parts.append(me.RigidBody(name, point, A, mass, (me.inertia(A, 0, 0, inertia), point)))
    spin = Iw * (pr.diff(t) ** 2 + pl.diff(t) ** 2) / 2
    v = x.diff(t) * sympy.cos(th) + y.diff(t) * sympy.sin(th)
    constraints = [-sympy.sin(th) * x.diff(t) + sympy.cos(th) * y.diff(t), v + b * th.diff(t) - r * pr.diff(t),
                   v - b * th.diff(t) - r * pl.diff(t)]
    method = me.LagrangesMethod(me.Lagrangian(N, *parts) + spin, list(qs), nonhol_coneqs=constraints, frame=N)
    method.form_lagranges_equations()
    # the motors' torques are generalized forces on phiR and phiL: they add to the forcing of those two dynamic
    # equations (rows 8 and 9 of the full system, after the five kinematic rows)
    forcing = sympy.Matrix(method.forcing_full)
    forcing[5 + 3] += tauR
    forcing[5 + 4] += tauL
    jacobian = sympy.Matrix(constraints).jacobian([q.diff(t) for q in qs])
    return tuple(_plain(m, qs, CART) for m in (method.mass_matrix_full, forcing, jacobian))


def _cart_state(rng: random.Random, surface: bool) -> dict[str, float]:
    values = {n: rng.uniform(-1.5, 1.5) for n in CART} | {f"{n}_dot": rng.uniform(-2, 2) for n in CART}
    values |= {p: rng.uniform(0.3, 2.0) for p in ("mc", "mw", "Ic", "Iw", "Im", "r", "b", "d")}
    values |= {"tauR": rng.uniform(-1, 1), "tauL": rng.uniform(-1, 1)}
    if surface:  # on the constraints: no sideways slip, each wheel rolls
        speed, th = values["x_dot"], values["theta"]
        values |= {"x_dot": speed * np.cos(th), "y_dot": speed * np.sin(th)}
        values["phiR_dot"] = (speed + values["b"] * values["theta_dot"]) / values["r"]
        values["phiL_dot"] = (speed - values["b"] * values["theta_dot"]) / values["r"]
    return values


def _cart_solution(values: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """q̈ and λ by LagrangesMethod: its full mass matrix has the block [M, −Aᵀ] (``lam_coeffs`` is −A), so its λ solve
    M q̈ = F + Aᵀλ, lagsolve's sign (its ``eom`` attribute is written with the opposite sign)."""
    mass, forcing, _ = (_numeric(m) for m in cart_lagrange())
    solution = np.linalg.solve(np.array(mass(values), dtype=float), np.array(forcing(values), dtype=float)).ravel()
    return solution[5:10], solution[10:13]


def test_cart_derives_completely(shipped_derivation: Callable[[str], Derivation]) -> None:
    """The two-wheeled cart derives completely with the default budget: q̈, λ and the forces of constraint."""
    derivation = shipped_derivation("differential_drive")
    assert derivation.notes == ()
    assert derivation.accelerations is not None and derivation.multipliers is not None
    assert derivation.constraint_forces is not None and set(derivation.constraint_forces) == {"lateral", "roll_r",
                                                                                               "roll_l"}


@pytest.mark.parametrize("surface", [False, True])
def test_cart_accelerations_and_multipliers_agree_with_lagranges_method(
        shipped_derivation: Callable[[str], Derivation], surface: bool) -> None:
    """lagsolve's q̈ and λ (raw and as shown) equal LagrangesMethod's at random states, on the constraint surface and
    off it (the augmented system holds for any velocities), and each force of constraint is λ times its
    constraint's coefficients."""
    derivation = shipped_derivation("differential_drive")
    jacobian = _numeric(cart_lagrange()[2])
    names = ("lateral", "roll_r", "roll_l")
    rng = random.Random(5 if surface else 6)
    for _ in range(15):
        values = _cart_state(rng, surface)
        acc, lam = _cart_solution(values)
        for i, name in enumerate(CART):
            assert _ours(derivation.raw_accelerations[i], values) == pytest.approx(acc[i], rel=1e-9, abs=1e-9)
            assert _ours(derivation.accelerations[name], values) == pytest.approx(acc[i], rel=1e-9, abs=1e-9)
        A = np.array(jacobian(values), dtype=float)
        for j, name in enumerate(names):
            assert _ours(derivation.raw_multipliers[j], values) == pytest.approx(lam[j], rel=1e-9, abs=1e-9)
            assert _ours(derivation.multipliers[name], values) == pytest.approx(lam[j], rel=1e-9, abs=1e-9)
            generalized = derivation.constraint_forces[name].generalized
            assert [_ours(g, values) for g in generalized] == pytest.approx(lam[j] * A[j], rel=1e-9, abs=1e-9)


def test_cart_expected_answers_agree_with_lagranges_method() -> None:
    """The file's hand-derived q̈ and λ (textbook form, on the constraint surface) equal LagrangesMethod's there."""
    prob = problem_file("differential_drive")
    rng = random.Random(7)
    for _ in range(15):
        values = _cart_state(rng, surface=True)
        acc, lam = _cart_solution(values)
        for i, name in enumerate(CART):
            assert _ours(prob.expected.accelerations[name], values) == pytest.approx(acc[i], rel=1e-9, abs=1e-9)
        for j, name in enumerate(("lateral", "roll_r", "roll_l")):
            assert _ours(prob.expected.multipliers[name], values) == pytest.approx(lam[j], rel=1e-9, abs=1e-9)
