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
