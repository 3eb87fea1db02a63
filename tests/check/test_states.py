"""`lagsolve.check.states`: random states on the constraint surface, with random smooth functions."""

from __future__ import annotations

import mpmath
import sympy

from lagsolve.check.states import GROUP, Compiled, StateSpace
from lagsolve.mechanics.equations.constraints import velocity_form
from mechanics_support import derived_file


def _residuals(name: str, count: int = 12) -> list[float]:
    """|psi| and |velocity form| of every constraint at ``count`` states of problems/<name>.yaml."""
    derivation = derived_file(name)
    space = StateSpace(derivation, seed=1)
    checks = []
    for c in derivation.constraints:
        forms = [velocity_form(c, derivation.model)]
        if c.kind == "holonomic":
            forms.append(c.expression)
        checks += [Compiled(f, space) for f in forms]
    states = space.states(count)
    assert len(states) == count
    return [float(abs(check(state))) for state in states for check in checks]


def test_implicit_holonomic_constraint_is_met() -> None:
    """Pendulum states satisfy x² + y² = l² (Newton) and x ẋ + y ẏ = 0 (linear solve)."""
    assert max(_residuals("pendulum_cartesian")) < 1e-20


def test_velocity_constraints_are_met() -> None:
    """Knife-edge and rolling-coin states satisfy their nonholonomic constraints."""
    assert max(_residuals("knife_edge") + _residuals("rolling_coin")) < 1e-20


def test_explicit_eliminations_give_dependent_values() -> None:
    """States of problems with explicit eliminations (y = f(x), X = A cos(w t)) meet every constraint."""
    assert max(_residuals("bead") + _residuals("wedge") + _residuals("moving_support")) < 1e-20


def test_states_are_reproducible_and_grouped() -> None:
    """The same seed gives the same states; parameters are shared within groups of GROUP states."""
    derivation = derived_file("atwood")
    first = StateSpace(derivation, seed=5).states(8)
    second = StateSpace(derivation, seed=5).states(8)
    assert [s.values for s in first] == [s.values for s in second]
    m1 = derivation.problem.symbols["m1"]
    assert first[0].values[m1] == first[GROUP - 1].values[m1] != first[GROUP].values[m1]
    assert [s.group for s in first] == [k // GROUP for k in range(8)]


def test_positive_coordinates_stay_positive() -> None:
    """A coordinate declared positive (a distance) gets positive values only."""
    derivation = derived_file("cone")
    r = derivation.problem.symbols["r"]
    assert all(s.values[r] > 0 for s in StateSpace(derivation).states(16))


def test_declared_functions_become_smooth_random_functions() -> None:
    """f and its derivatives are evaluated consistently: f'(x) matches a difference quotient of f."""
    derivation = derived_file("bead")
    x = derivation.problem.symbols["x"]
    f = derivation.problem.functions[0].function
    space = StateSpace(derivation, seed=2)
    value, slope = Compiled(f(x), space), Compiled(sympy.Derivative(f(x), x), space)
    for state in space.states(4):
        with mpmath.workdps(30):
            h = mpmath.mpf(10) ** -12
            shifted = type(state)({**state.values, x: state.values[x] + h}, state.coefficients, state.functions,
                                  state.group)
            assert abs((value(shifted) - value(state)) / h - slope(state)) < 1e-9
        assert "f" in state.functions and state.functions["f"].free_symbols == set()


def test_undefined_expression_has_no_value() -> None:
    """An expression that is infinite as written, or divides by zero at a state, evaluates to None."""
    derivation = derived_file("bead")
    space = StateSpace(derivation)
    state = space.states(1)[0]
    assert Compiled(sympy.zoo, space)(state) is None
    x = derivation.problem.symbols["x"]
    assert Compiled(1 / (x - x.func(x.name, real=True)), space)(state) is None
