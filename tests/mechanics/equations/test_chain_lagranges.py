"""The n-link pendulum's equations against independent routes: SymPy's ``LagrangesMethod``, and for a long chain
(where ``LagrangesMethod`` takes most of a minute) the textbook closed form of the chain's M and F.

lagsolve takes a chain of more than ``BULK_SYSTEM`` coordinates through SymEngine (velocities, energies, the rates
and the display forms, :mod:`lagsolve.mechanics.symbolic.bulk`); a smaller one through SymPy. Both must give the
accelerations ``LagrangesMethod`` gives, from its own vector kinematics, at random states; the display forms the
reports print must equal the matrix form they are written from.
"""

from __future__ import annotations

import random
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, Lagrangian, Particle, Point, ReferenceFrame, dynamicsymbols

from lagsolve.mechanics.derivation import derive
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM
from lagsolve.problem.load import load_text

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "bench"))
from pendulum import pendulum_yaml  # noqa: E402 - the benchmarks' chain, the one the issue measures

VALUES = {"m": 1.3, "l": 0.7, "g": 9.81}


def _lagranges_method(n: int) -> tuple[list, list, object]:
    """``LagrangesMethod``'s M and F of the planar chain, numbers put in, as a function of (q, q̇)."""
    q = dynamicsymbols(f"q1:{n + 1}")
    u = [qi.diff() for qi in q]
    m, length, g = (sympy.Float(VALUES[k]) for k in ("m", "l", "g"))
    frame, origin = ReferenceFrame("N"), Point("O")
    origin.set_vel(frame, 0)
    particles, previous = [], origin
    for i in range(n):
        point = previous.locatenew(f"P{i}", length * sympy.sin(q[i]) * frame.x - length * sympy.cos(q[i]) * frame.y)
        point.set_vel(frame, point.pos_from(origin).dt(frame))
        particle = Particle(f"p{i}", point, m)
        particle.potential_energy = m * g * point.pos_from(origin).dot(frame.y)
        particles.append(particle)
        previous = point
    method = LagrangesMethod(Lagrangian(frame, *particles), q, frame=frame)
    method.form_lagranges_equations()
    return q, u, sympy.lambdify([q, u], [method.mass_matrix, method.forcing], "numpy")


def _closed_form(n: int) -> Callable[[list[float], list[float]], tuple[np.ndarray, np.ndarray]]:
    r"""The planar chain of n equal links with equal point masses at the joints, written out (the textbook form):
    with :math:`c_{ij} = m l^2 (n - \max(i, j))` (the masses at and below both joints, 0-based),
    :math:`M_{ij} = c_{ij}\cos(\theta_i - \theta_j)` and
    :math:`F_i = -\sum_j c_{ij}\sin(\theta_i - \theta_j)\,\dot\theta_j^2 - m g l (n - i)\sin\theta_i`."""
    m, length, g = VALUES["m"], VALUES["l"], VALUES["g"]
    below = np.array([[n - max(i, j) for j in range(n)] for i in range(n)], dtype=float)

    def evaluate(angles: list[float], rates: list[float]) -> tuple[np.ndarray, np.ndarray]:
        theta, rate = np.asarray(angles), np.asarray(rates)
        difference = theta[:, None] - theta[None, :]
        mass = m * length**2 * below * np.cos(difference)
        forcing = (-(m * length**2 * below * np.sin(difference)) @ rate**2
                   - m * g * length * (n - np.arange(n)) * np.sin(theta))
        return mass, forcing

    return evaluate


def _accelerations(mass: object, forcing: object, symbols: list, values: list[float]) -> np.ndarray:
    f = sympy.lambdify([symbols], [sympy.Matrix(mass), sympy.Matrix(forcing)], "numpy")
    m, rhs = f(values)
    return np.linalg.solve(np.asarray(m, dtype=float), np.asarray(rhs, dtype=float).ravel())


def _check(n: int, states: int = 3, *, closed_only: bool = False) -> None:
    """Our M, F and the printed M, F against LagrangesMethod's (and the closed form against it too), or with
    ``closed_only`` against the closed form alone."""
    derivation = derive(load_text(pendulum_yaml(n, 1.0, "a test"), f"chain{n}.yaml"), budget=600)
    form = derivation.form
    lagrange, model = form.lagrange, form.model
    params = sorted((s for s in lagrange.mass_matrix.free_symbols | lagrange.forcing.free_symbols
                     if s.name in VALUES), key=lambda s: s.name)
    symbols = [*model.coordinates, *model.velocities, *params]
    reference = None if closed_only else _lagranges_method(n)[2]
    closed = _closed_form(n)
    rng = random.Random(n)
    display = derivation.display
    for _ in range(states):
        angles = [rng.uniform(-np.pi, np.pi) for _ in range(n)]
        rates = [rng.uniform(-2.0, 2.0) for _ in range(n)]
        values = [*angles, *rates, *(VALUES[s.name] for s in params)]
        ours = _accelerations(lagrange.mass_matrix, lagrange.forcing, symbols, values)
        m_ref, f_ref = closed(angles, rates) if reference is None else reference(angles, rates)
        theirs = np.linalg.solve(np.asarray(m_ref, dtype=float), np.asarray(f_ref, dtype=float).ravel())
        np.testing.assert_allclose(ours, theirs, rtol=1e-9, atol=1e-9)
        m_closed, f_closed = closed(angles, rates)
        np.testing.assert_allclose(np.linalg.solve(m_closed, f_closed), theirs, rtol=1e-9, atol=1e-9)
        # what the reports print: the display forms of M and F give the same accelerations
        shown = _accelerations(display.mass_matrix, display.forcing, symbols, values)
        np.testing.assert_allclose(shown, theirs, rtol=1e-9, atol=1e-9)
        # and each equation as shown (d/dt ∂L/∂q̇ − ∂L/∂q = Q) vanishes along those accelerations
        point = dict(zip(symbols, values, strict=True)) | dict(zip(model.accelerations, theirs, strict=True))
        for lhs, rhs in display.equation_sides:
            assert abs(float((lhs - rhs).xreplace(point))) < 1e-8


@pytest.mark.parametrize("n", [3, 6, BULK_SYSTEM + 2])
def test_chain_accelerations_agree_with_lagranges_method(n: int) -> None:
    _check(n)


@pytest.mark.slow
def test_twelve_link_chain_agrees_with_the_closed_form() -> None:
    """Twelve links (the closed form, held equal to LagrangesMethod's at 3, 6 and 8 links above)."""
    _check(12, closed_only=True)


def test_bulk_chain_notes_the_light_display_form() -> None:
    derivation = derive(load_text(pendulum_yaml(BULK_SYSTEM + 2, 1.0, "a test"), "chain.yaml"), budget=600)
    [note] = [n for n in derivation.notes if n.stage == "display simplification"]
    assert note.kind == "size" and "light" in note.reason
