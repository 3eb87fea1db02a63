r"""Equilibria and small oscillations of a system with several degrees of freedom.

With the equations in matrix form :math:`M(q)\ddot q = F(q, \dot q)` (no explicit t),
equilibria solve :math:`F(q_0, 0) = 0`. Writing :math:`q = q_0 + \delta q` and keeping first
order terms,

.. math::
    M_0\,\delta\ddot q + (G + D)\,\delta\dot q + K\,\delta q = 0,\qquad
    K = -\frac{\partial F}{\partial q}\Big|_0,\quad
    C = -\frac{\partial F}{\partial\dot q}\Big|_0,\quad G = \tfrac12(C - C^T),\ D = \tfrac12(C + C^T),

with :math:`M_0 = M(q_0)`. Without gyroscopic (G) and damping (D) terms the normal modes
:math:`\delta q = u\,e^{i\omega t}` have :math:`\det(K - \omega^2 M_0) = 0`, i.e. the
:math:`\omega^2` are the eigenvalues of :math:`M_0^{-1}K`; the equilibrium is stable when all
of them are positive and unstable when one is negative.

Notes
-----
* Equilibria are solved symbolically only for small equations (at most 3 coordinates);
  larger systems are skipped rather than risking a long solve.
* Normal modes are computed for up to 3 coordinates (a cubic in ω² at most).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.conserved import MotionSystem
from lagsolve.mechanics.identities import proved_zero
from lagsolve.mechanics.lagrange import lagrange_terms
from lagsolve.mechanics.signs import sign_core
from lagsolve.mechanics.simplify import tidy

#: equations F(q, 0) larger than this (operations) are not solved
SOLVE_LIMIT = 60
MAX_COORDINATES = 3
MAX_EQUILIBRIA = 8


@dataclass(frozen=True)
class Mode:
    """Small oscillations about one equilibrium ``point`` (pairs (q, q0)).

    Matrices have shape (n, n): ``mass`` :math:`M_0`, ``gyroscopic`` G, ``damping`` D,
    ``stiffness`` K. ``squared_frequencies`` are the :math:`\\omega^2` (None when G or D is
    present or the characteristic polynomial is too large); ``frequencies`` their square
    roots (None for a negative one); ``stable`` True/False/None.
    """

    point: tuple[tuple[Any, Any], ...]
    mass: sympy.ImmutableMatrix
    gyroscopic: sympy.ImmutableMatrix
    damping: sympy.ImmutableMatrix
    stiffness: sympy.ImmutableMatrix
    squared_frequencies: tuple[Any, ...] | None
    frequencies: tuple[Any, ...] | None
    stable: bool | None
    note: str = ""


@dataclass(frozen=True)
class Linearization:
    """Every equilibrium found for ``coordinates``, with its small-oscillation analysis."""

    coordinates: tuple[Any, ...]
    modes: tuple[Mode, ...]


def linearize(system: MotionSystem, cyclic: tuple[Any, ...], friction: bool) -> tuple[Linearization | None, str]:
    """Equilibria and normal modes of ``system`` (module docstring), or None and the reason."""
    model = system.model
    n = len(model.coordinates)
    if system.kind != "reduced":
        return None, "needs minimal coordinates (no constraint left)"
    if cyclic:
        return None, "the system has cyclic coordinates: its relative equilibria are not analysed here"
    if friction:
        return None, "Coulomb friction acts: equilibria are not isolated points"
    if not 2 <= n <= MAX_COORDINATES:
        return None, f"{n} coordinates (equilibria are solved for 2 to {MAX_COORDINATES})"
    if not proved_zero(sympy.diff(model.lagrangian, model.time)):
        return None, "L depends explicitly on the time"
    terms = lagrange_terms(model, (), system.generalized_forces)
    rest = {v: 0 for v in model.velocities}
    static = [tidy(f.xreplace(rest)) for f in terms.forcing]
    if any(sympy.count_ops(f) > SOLVE_LIMIT for f in static):
        return None, "the equilibrium equations are too large to solve symbolically"
    try:
        solutions = sympy.solve(static, list(model.coordinates), dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return None, "the equilibrium equations could not be solved symbolically"
    points = []
    for s in solutions:
        if set(s) != set(model.coordinates) or any(v.has(sympy.I) or v.free_symbols & set(model.coordinates)
                                                    for v in s.values()):
            continue
        points.append(tuple((q, _principal(s[q])) for q in model.coordinates))
    if not points:
        return None, "no isolated equilibrium was found in closed form"
    points = sorted(set(points), key=lambda p: sympy.default_sort_key(sympy.Tuple(*[v for _, v in p])))
    F = sympy.Matrix(terms.forcing)
    K_all = -F.jacobian(list(model.coordinates))
    C_all = -F.jacobian(list(model.velocities))
    modes = tuple(_mode(point, terms.mass_matrix, K_all, C_all, rest) for point in points[:MAX_EQUILIBRIA])
    return Linearization(model.coordinates, modes), ""


def _principal(value: Any) -> Any:
    """An angle-like value moved into (-π, π] when that makes it shorter (``2*pi - a`` → ``-a``)."""
    if value.has(sympy.pi) and sympy.count_ops(value - 2 * sympy.pi) < sympy.count_ops(value):
        return value - 2 * sympy.pi
    return value


def _mode(point: tuple[tuple[Any, Any], ...], mass: Any, K_all: Any, C_all: Any, rest: dict[Any, Any]) -> Mode:
    at = {**dict(point), **rest}
    M0 = sympy.Matrix(mass).xreplace(at).applyfunc(tidy)
    K = K_all.xreplace(at).applyfunc(tidy)
    C = C_all.xreplace(at).applyfunc(tidy)
    G = ((C - C.T) / 2).applyfunc(tidy)
    D = ((C + C.T) / 2).applyfunc(tidy)
    squares = frequencies = None
    stable = None
    note = ""
    if any(e != 0 for e in (*G, *D)):
        note = "gyroscopic or damping terms: normal modes are not computed"
    else:
        s = sympy.Dummy("s")
        polynomial = sympy.Poly(sympy.factor((K - s * M0).det()), s)
        roots = sympy.roots(polynomial)
        if sum(roots.values()) != polynomial.degree():
            note = "the characteristic polynomial has no closed-form roots"
        else:
            ordered = sorted((tidy(r) for r, k in roots.items() for _ in range(k)), key=sympy.default_sort_key)
            squares = tuple(ordered)
            signs = [sign_core(r)[0] for r in squares]
            stable = False if any(x == -1 for x in signs) else (True if all(x == 1 for x in signs) else None)
            frequencies = tuple(tidy(sympy.sqrt(r)) if x == 1 else None for r, x in zip(squares, signs, strict=True))
    return Mode(point, sympy.ImmutableMatrix(M0), sympy.ImmutableMatrix(G), sympy.ImmutableMatrix(D),
                sympy.ImmutableMatrix(K), squares, frequencies, stable, note)
