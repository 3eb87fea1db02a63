"""Cross-check of ``derive`` against SymPy's own ``LagrangesMethod`` (a second, independent
route): accelerations and multipliers at random states that satisfy the constraints.

Sign convention, checked on the bead below: the multipliers that ``LagrangesMethod.rhs()``
returns (from ``mass_matrix_full`` and ``forcing_full``) equal ours *with the same sign*
when the constraint is passed in the same form (same a_ji). Its ``eom`` expression (what
``form_lagranges_equations`` returns) uses the *opposite* sign for ``lam1`` (it stores
-a as ``lam_coeffs``; see sympy/sympy#30215), so an ``eom`` multiplier is minus ours.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from mechanics_support import TUBE, concrete, derived_file, derived_text, names, value

CARTESIAN_PENDULUM = """
name: Pendulum in Cartesian coordinates
parameters: {m: mass, g: gravity, l: length}
coordinates: [x, y]
particles:
  bob: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  rod: {holonomic: x**2 + y**2 - l**2}
"""

STATES = 20


def _wire(x):
    return sympy.sin(x) + x**3 / 5


@dataclass
class Case:
    """Our derivation, the same system built for LagrangesMethod, and a sampler of states."""

    derivation: Any
    lagrangian: Any  # in dynamicsymbols
    coordinates: list[Any]  # dynamicsymbols, in our order
    hol: list[Any]
    nonhol: list[Any]
    state: Callable[[random.Random, dict[str, Any]], dict[str, float]]
    functions: dict[Any, Any]


def _dyn(derivation):
    """Dynamic symbols named like our coordinates, and the map back to our plain symbols."""
    t = dynamicsymbols._t
    qs = [dynamicsymbols(c.name) for c in derivation.problem.coordinates]
    back = {}
    for c, q in zip(derivation.problem.coordinates, qs, strict=True):
        back[q.diff(t)] = c.velocity
        back[q] = c.symbol
    return t, qs, back


def bead_case() -> Case:
    d = derived_file("bead")
    s = names(d.problem)
    t, (x, y), _ = _dyn(d)
    m, g = s["m"], s["g"]
    lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y

    def state(rng, p):
        xv, xdv = rng.uniform(-2, 2), rng.uniform(-2, 2)
        slope = float(sympy.diff(_wire(s["x"]), s["x"]).subs(s["x"], xv))
        return {"x": xv, "x_dot": xdv, "y": float(_wire(sympy.Float(xv))), "y_dot": slope * xdv}

    return Case(d, lagrangian, [x, y], [y - _wire(x)], [], state, {s["f"]: _wire})


def hole_case() -> Case:
    d = derived_file("hole_table")
    s = names(d.problem)
    t, (r, th, z), _ = _dyn(d)
    m1, m2, g, l_ = s["m1"], s["m2"], s["g"], s["l"]
    lagrangian = (m1 * (r.diff(t) ** 2 + r**2 * th.diff(t) ** 2) / 2 + m2 * z.diff(t) ** 2 / 2
                  - m2 * g * z)

    def state(rng, p):
        rv, rdv = rng.uniform(0.3, 2), rng.uniform(-2, 2)
        return {"r": rv, "theta": rng.uniform(-3, 3), "z": rv - p["l"], "r_dot": rdv,
                "theta_dot": rng.uniform(-3, 3), "z_dot": rdv}

    return Case(d, lagrangian, [r, th, z], [r - z - l_], [], state, {})


def knife_case() -> Case:
    d = derived_file("knife_edge")
    s = names(d.problem)
    t, (x, y, th), _ = _dyn(d)
    m, l_ = s["m"], s["l"]
    xd, yd, thd = x.diff(t), y.diff(t), th.diff(t)
    x2d, y2d = xd - l_ * sympy.sin(th) * thd, yd + l_ * sympy.cos(th) * thd
    lagrangian = m * (xd**2 + yd**2) / 2 + m * (x2d**2 + y2d**2) / 2

    def state(rng, p):
        thv, speed = rng.uniform(-3, 3), rng.uniform(-2, 2)
        return {"x": rng.uniform(-2, 2), "y": rng.uniform(-2, 2), "theta": thv,
                "x_dot": speed * math.cos(thv), "y_dot": speed * math.sin(thv),
                "theta_dot": rng.uniform(-2, 2)}

    return Case(d, lagrangian, [x, y, th], [], [-sympy.sin(th) * xd + sympy.cos(th) * yd],
                state, {})


def tube_case() -> Case:
    d = derived_text(TUBE)
    s = names(d.problem)
    t, (r, th, ph), _ = _dyn(d)
    m, g, omega = s["m"], s["g"], s["Omega"]
    position = [r * sympy.sin(th) * sympy.cos(ph), r * sympy.sin(th) * sympy.sin(ph),
                r * sympy.cos(th)]
    lagrangian = m * sum(c.diff(t) ** 2 for c in position) / 2 - m * g * position[2]

    def state(rng, p):
        return {"r": rng.uniform(0.2, 2), "theta": rng.uniform(0.1, 3.0),
                "phi": rng.uniform(-3, 3), "r_dot": rng.uniform(-2, 2), "theta_dot": 0.0,
                "phi_dot": p["Omega"]}

    return Case(d, lagrangian, [r, th, ph], [], [th.diff(t), ph.diff(t) - omega], state, {})


def pendulum_case() -> Case:
    d = derived_text(CARTESIAN_PENDULUM)
    s = names(d.problem)
    t, (x, y), _ = _dyn(d)
    m, g, l_ = s["m"], s["g"], s["l"]
    lagrangian = m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y

    def state(rng, p):
        angle, rate = rng.uniform(-3, 3), rng.uniform(-3, 3)
        length = p["l"]
        return {"x": length * math.sin(angle), "y": -length * math.cos(angle),
                "x_dot": length * rate * math.cos(angle), "y_dot": length * rate * math.sin(angle)}

    return Case(d, lagrangian, [x, y], [x**2 + y**2 - l_**2], [], state, {})


CASES = {"bead": bead_case, "hole_table": hole_case, "knife_edge": knife_case,
         "rotating_tube": tube_case, "cartesian_pendulum": pendulum_case}


def lagranges_method(case: Case) -> LagrangesMethod:
    method = LagrangesMethod(case.lagrangian, case.coordinates,
                             hol_coneqs=case.hol or None, nonhol_coneqs=case.nonhol or None)
    method.form_lagranges_equations()
    return method


def reference_solver(case: Case, method: LagrangesMethod):
    """A function state -> (accelerations, multipliers) solving SymPy's full system numerically."""
    _, _, back = _dyn(case.derivation)
    params = [p.symbol for p in case.derivation.problem.parameters]
    plain = [c.symbol for c in case.derivation.problem.coordinates]
    plain += [c.velocity for c in case.derivation.problem.coordinates]
    args = [case.derivation.problem.time, *plain, *params]
    mass = sympy.lambdify(args, method.mass_matrix_full.xreplace(back), "numpy")
    forcing = sympy.lambdify(args, method.forcing_full.xreplace(back), "numpy")
    n, m = len(case.coordinates), len(case.hol) + len(case.nonhol)

    def solve(point):
        values = [float(point[a]) for a in args]
        x = np.linalg.solve(np.array(mass(*values), dtype=float),
                            np.array(forcing(*values), dtype=float).reshape(-1))
        return x[n:2 * n], x[2 * n:2 * n + m]

    return solve


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    return CASES[request.param]()


def test_accelerations_and_multipliers_match_lagranges_method(case):
    """Our accelerations and multipliers equal LagrangesMethod's (same multiplier sign) at
    20 random states that satisfy the constraints."""
    derivation = case.derivation
    problem = derivation.problem
    solve = reference_solver(case, lagranges_method(case))
    ours_acc = [concrete(derivation.accelerations[c.name], case.functions)
                for c in problem.coordinates]
    ours_lam = [concrete(derivation.multipliers[c.name], case.functions)
                for c in problem.constraints]
    rng = random.Random(2024)
    for _ in range(STATES):
        params = {p.name: rng.uniform(0.5, 2.0) for p in problem.parameters}
        named = {"t": rng.uniform(-2, 2), **params, **case.state(rng, params)}
        point = {problem.symbols[k]: sympy.Float(v, 30) for k, v in named.items()}
        ref_acc, ref_lam = solve(point)
        for ours, ref in zip(ours_acc, ref_acc, strict=True):
            assert value(ours, point).real == pytest.approx(ref, rel=1e-8, abs=1e-8), named
        for ours, ref in zip(ours_lam, ref_lam, strict=True):
            assert value(ours, point).real == pytest.approx(ref, rel=1e-8, abs=1e-8), named


def test_lagranges_method_sign_convention_on_the_bead():
    """On the bead with f = x^2/2, LagrangesMethod.rhs() gives lambda = m (g + x_dot^2)/(1 + x^2),
    our sign, while its eom holds -lambda (lam1 enters with the opposite sign)."""
    t = dynamicsymbols._t
    x, y = dynamicsymbols("x y")
    m, g = sympy.symbols("m g", positive=True)
    method = LagrangesMethod(m * (x.diff(t) ** 2 + y.diff(t) ** 2) / 2 - m * g * y, [x, y],
                             hol_coneqs=[y - x**2 / 2])
    eom = method.form_lagranges_equations()
    rhs = method.rhs()
    ours = m * (g + x.diff(t) ** 2) / (1 + x**2)
    assert sympy.simplify(rhs[4] - ours) == 0
    (lam1,) = method.lam_vec
    solved = {x.diff(t, 2): rhs[2], y.diff(t, 2): rhs[3]}
    assert sympy.simplify(eom.xreplace({**solved, lam1: -rhs[4]})) == sympy.zeros(2, 1)
    assert sympy.simplify(eom.xreplace({**solved, lam1: rhs[4]})) != sympy.zeros(2, 1)
