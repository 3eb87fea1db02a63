"""mechanics/solution/sticking.py: a friction contact held at rest relative to its surface, in closed form, checked
against
statics, Newton's and Euler's laws for the rolling or riding motion, and the simulation's holding force."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.integrate import integrate_motion
from lagsolve.numeric.system import bind
from mechanics_support import derived_file, names, problem_file


def _held(name: str, contact: str = ""):  # type: ignore[no-untyped-def]
    d = derived_file(name)
    (result,) = [f for f in d.friction if not contact or f.term.name == contact]
    assert result.sticking is not None, result.sticking_note
    return result.sticking, names(problem_file(name))


def test_a_disc_rolls_on_an_incline_while_mu_s_is_at_least_tan_over_3() -> None:
    """Rolling (the contact held): Newton m x_ddot = m g sin(alpha) + Phi and Euler (m R^2/2) x_ddot/R = -Phi R
    give Phi = -m g sin(alpha)/3 along the slope, N = m g |cos(alpha)|, so it rolls while mu_s >= |tan(alpha)|/3."""
    held, s = _held("rough_disc_incline")
    m, g, alpha = s["m"], s["g"], s["alpha"]
    assert sympy.simplify(held.force + m * g * sympy.sin(alpha) / 3) == 0
    assert sympy.simplify(held.normal - m * g * sympy.Abs(sympy.cos(alpha))) == 0
    assert sympy.simplify(held.ratio - sympy.Abs(sympy.tan(alpha)) / 3) == 0


def test_blocks_ride_together_while_the_upper_needs_at_most_mu2_s_g() -> None:
    """The upper block held on the lower: both accelerate at a = (F - mu1 (m1 + m2) g sign(x1_dot))/(m1 + m2), the
    friction on the upper is m2 a and N = m2 g, so they ride together while mu2_s >= |a|/g."""
    held, s = _held("stacked_blocks", "between")
    m1, m2, g, F, mu1 = s["m1"], s["m2"], s["g"], s["F"], s["mu1"]
    a = (F - mu1 * (m1 + m2) * g * sympy.sign(s["x1_dot"])) / (m1 + m2)
    assert sympy.simplify(held.force - m2 * a) == 0
    assert sympy.simplify(held.normal - m2 * g) == 0
    assert sympy.simplify(held.ratio - sympy.Abs(a) / g) == 0


def test_statics_of_the_block_on_the_spring_and_of_the_ladder() -> None:
    """Held at rest: the spring block needs k |x| <= mu_s m g (its band), the ladder's foot m2 g |x1/y2| <= mu_s
    (m1 + m2) g (the wall pushes with m2 g cot(theta); the floor carries both weights)."""
    held, s = _held("spring_on_rough_floor")
    assert sympy.simplify(held.ratio - s["k"] * sympy.Abs(s["x"]) / (s["m"] * s["g"])) == 0
    held, s = _held("ladder_rough_floor")
    expected = s["m2"] * sympy.Abs(s["x1"] / s["y2"]) / (s["m1"] + s["m2"])
    assert sympy.simplify(held.ratio - expected) == 0
    assert sympy.simplify(held.normal - s["g"] * (s["m1"] + s["m2"])) == 0


def test_the_holding_force_is_the_simulation_s_while_it_sticks() -> None:
    """The closed-form Phi of the stacked blocks' upper contact equals the simulation's holding force at every
    sample while they ride together."""
    problem = problem_file("stacked_blocks")
    system = bind(matrix_form(problem))
    q0, qd0 = complete_initial(system, dict(problem.simulation.initial))
    run = integrate_motion(system, q0, qd0, 1.0, samples=101)
    between = system.contact_names.index("between")
    assert run.stuck[1:, between].all()
    held, s = _held("stacked_blocks", "between")
    values = {s[k]: v for k, v in problem.simulation.values.items()}
    x1 = system.coordinates.index("x1")
    for i in range(1, len(run.t), 10):
        phi = float(held.force.xreplace({**values, s["x1_dot"]: float(run.qd[i, x1])}))
        assert run.friction[i, between] == pytest.approx(phi, rel=1e-9)
    assert math.isfinite(float(np.max(run.friction[:, between])))
