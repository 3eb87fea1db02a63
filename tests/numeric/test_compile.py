"""Compiling expressions of the state into numeric callables."""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from lagsolve.numeric.compile import compile_state_function, substitute_functions

t, x, y, xd, yd, a, b = sympy.symbols("t x y x_dot y_dot a b", real=True)
f = sympy.Function("f", real=True)
u = sympy.Symbol("u", real=True)


def test_state_function_evaluates_in_the_documented_order() -> None:
    """f(t, q, qd, p) evaluates every expression with coordinates, velocities and parameters in order."""
    fn = compile_state_function([a * x + b * yd, sympy.sin(t) * y, sympy.sign(xd) * sympy.Abs(y)],
                                time=t, coordinates=[x, y], velocities=[xd, yd], parameters=[a, b])
    out = fn(0.5, np.array([1.0, -2.0]), np.array([-3.0, 4.0]), np.array([10.0, 100.0]))
    assert out == pytest.approx([10.0 + 400.0, np.sin(0.5) * -2.0, -2.0])


def test_unknown_symbols_are_refused() -> None:
    """An expression with a symbol that is not a state, time or parameter cannot be compiled."""
    with pytest.raises(ValueError, match="symbols with no value: \\['b'\\]"):
        compile_state_function([x + b], time=t, coordinates=[x], velocities=[xd], parameters=[])


def test_declared_functions_and_their_derivatives_become_concrete() -> None:
    """f(x), f'(x) and f''(x) are replaced consistently by the concrete function and its derivatives."""
    expr = f(x) + sympy.diff(f(x), x) * xd + sympy.diff(f(x), x, 2)
    concrete = substitute_functions(expr, {f: ((u,), sympy.sin(u) + u**3)})
    assert sympy.simplify(concrete - (sympy.sin(x) + x**3 + (sympy.cos(x) + 3 * x**2) * xd - sympy.sin(x) + 6 * x)) == 0


def test_empty_list_compiles_to_empty_array() -> None:
    """No expressions give an empty array (a problem without constraints)."""
    fn = compile_state_function([], time=t, coordinates=[x], velocities=[xd], parameters=[])
    assert fn(0.0, np.zeros(1), np.zeros(1), np.zeros(0)).shape == (0,)


def test_llvm_and_python_backends_agree() -> None:
    """The compiled (LLVM) and pure-Python backends give the same numbers at many states."""
    pytest.importorskip("symengine")
    exprs = [a * sympy.sin(x) * yd**2 + b * sympy.sqrt(x**2 + 1), sympy.atan2(y, x) * sympy.sign(xd),
             sympy.Abs(y - t) / (1 + b**2), sympy.exp(-x * y) * sympy.cos(t)]
    kwargs = {"time": t, "coordinates": [x, y], "velocities": [xd, yd], "parameters": [a, b]}
    fast = compile_state_function(exprs, backend="llvm", **kwargs)
    slow = compile_state_function(exprs, backend="python", **kwargs)
    rng = np.random.default_rng(0)
    for _ in range(50):
        args = (rng.uniform(-2, 2), rng.uniform(-2, 2, 2), rng.uniform(-2, 2, 2), rng.uniform(0.5, 2, 2))
        assert fast(*args) == pytest.approx(slow(*args), rel=1e-12, abs=1e-14)


def test_unknown_backend_is_refused() -> None:
    """A backend name other than auto, llvm and python is an error."""
    with pytest.raises(ValueError, match="unknown backend"):
        compile_state_function([x], time=t, coordinates=[x], velocities=[xd], parameters=[], backend="gpu")


@pytest.mark.parametrize("backend", ["llvm", "python"])
def test_argument_names_never_meet_the_compilers_temporaries(backend: str) -> None:
    """Arguments named like CSE temporaries (x0, x1, ...) or SymPy names keep their own values in every backend."""
    if backend == "llvm":
        pytest.importorskip("symengine")
    names = [f"x{i}" for i in range(10)] + ["y1", "Dummy_0", "I", "N", "cse"]
    q = sympy.symbols(names, real=True)
    qd = sympy.symbols([f"{n}_dot" for n in names], real=True)
    p = sympy.symbols("k x10", positive=True)
    # shared subexpressions make the compiler create temporaries; q[1] (x1) is absent from the group
    shared = sympy.sin(q[2] * q[3]) + sympy.cos(q[4] + p[0])
    exprs = [shared * q[0] + shared**2, shared * q[11] + qd[1] * p[1], (shared + q[12]) ** 3 * q[13] - q[14]]
    fn = compile_state_function(exprs, time=t, coordinates=q, velocities=qd, parameters=p, backend=backend)
    rng = np.random.default_rng(3)
    for _ in range(20):
        qv, qdv, pv, tv = rng.uniform(-2, 2, len(q)), rng.uniform(-2, 2, len(q)), rng.uniform(0.5, 2, 2), rng.uniform()
        values = {t: tv, **dict(zip(q, qv, strict=True)), **dict(zip(qd, qdv, strict=True)),
                  **dict(zip(p, pv, strict=True))}
        expected = [float(e.xreplace(values)) for e in exprs]
        assert fn(tv, qv, qdv, pv) == pytest.approx(expected, rel=1e-12, abs=1e-12)


_CHAIN = ["x0", "x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9", "Dummy_0", "I", "N"]
_NAMED_LIKE_TEMPORARIES = f"""
name: Pendulum in x1, y1 beside a chain named like compiler temporaries
parameters: {{m: mass, g: gravity, l: rod length, k: stiffness, c: coupling}}
coordinates: [x1, y1, {", ".join(_CHAIN)}]
particles: {{bob: {{mass: m, position: [x1, y1]}}}}
gravity: [0, -g]
kinetic: "m*({" + ".join(f"{n}_dot**2" for n in _CHAIN)})/2"
potential: "-k*({" + ".join(f"cos({n})" for n in _CHAIN)}) + c*({" + ".join(
    f"({a} - {b})**2" for a, b in zip(_CHAIN, _CHAIN[1:], strict=False))})/2"
constraints:
  rod: {{holonomic: (x1**2 + y1**2 - l**2)/2, on: bob}}
simulation:
  values: {{m: 1.5, g: 9.81, l: 1.0, k: 2.0, c: 0.7}}
  initial: {{x1: 0.6, y1: -0.8, x1_dot: 0.0, y1_dot: 0.0,
            {", ".join(f"{n}: {0.1 * (i + 1)}" for i, n in enumerate(_CHAIN))},
            {", ".join(f"{n}_dot: 0.0" for n in _CHAIN)}}}
  t_end: 3.0
"""


def test_a_simulation_in_names_like_temporaries_matches_a_hand_written_integration() -> None:
    """Coordinates named x0…x9, y1, Dummy_0, I and N move as an independent solve_ivp run of the same system."""
    from scipy.integrate import solve_ivp

    from simulation_support import run

    m, g, length, k, c = 1.5, 9.81, 1.0, 2.0, 0.7
    trajectory = run(_NAMED_LIKE_TEMPORARIES, 3.0, samples=31)
    chain0 = np.array([0.1 * (i + 1) for i in range(len(_CHAIN))])

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        theta, omega, z, zd = y[0], y[1], y[2: 2 + len(_CHAIN)], y[2 + len(_CHAIN):]
        spring = np.zeros_like(z)
        spring[:-1] += c * (z[:-1] - z[1:])
        spring[1:] -= c * (z[:-1] - z[1:])
        return np.concatenate([[omega, -g / length * np.sin(theta)], zd, (-k * np.sin(z) - spring) / m])

    theta0 = np.arctan2(0.6, 0.8)  # x1 = l sin θ, y1 = -l cos θ
    hand = solve_ivp(rhs, (0.0, 3.0), np.concatenate([[theta0, 0.0], chain0, np.zeros_like(chain0)]),
                     method="DOP853", rtol=1e-12, atol=1e-12, t_eval=trajectory.t)
    order = list(trajectory.coordinates)
    assert trajectory.q[:, order.index("x1")] == pytest.approx(length * np.sin(hand.y[0]), abs=1e-7)
    assert trajectory.q[:, order.index("y1")] == pytest.approx(-length * np.cos(hand.y[0]), abs=1e-7)
    for i, name in enumerate(_CHAIN):
        assert trajectory.q[:, order.index(name)] == pytest.approx(hand.y[2 + i], abs=1e-7)
        assert trajectory.qd[:, order.index(name)] == pytest.approx(hand.y[2 + len(_CHAIN) + i], abs=1e-7)
    z = hand.y[2: 2 + len(_CHAIN)]
    energy = (m * length**2 * hand.y[1] ** 2 / 2 - m * g * length * np.cos(hand.y[0])
              + m * (hand.y[2 + len(_CHAIN):] ** 2).sum(axis=0) / 2 - k * np.cos(z).sum(axis=0)
              + c * ((z[:-1] - z[1:]) ** 2).sum(axis=0) / 2)
    assert trajectory.energy == pytest.approx(energy, abs=1e-7)


def test_a_python_backend_domain_error_is_nan_like_llvm() -> None:
    """With the pure-Python backend, log of a negative number gives NaN (as LLVM does), not a ValueError."""
    fn = compile_state_function([sympy.log(x), x], time=t, coordinates=[x], velocities=[xd], parameters=[],
                                backend="python")
    assert np.isnan(fn(0.0, np.array([-1.0]), np.zeros(1), np.zeros(0))).all()
