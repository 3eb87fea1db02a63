"""Initial conditions consistent with the constraints.

Values the user gives are kept; the other coordinates start at 0 and are solved
from the position constraints by a least-norm Newton iteration, and the other
velocities from the velocity-level constraints by a least-norm linear solve.
Values that cannot satisfy the constraints are rejected with the residual shown.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from lagsolve.errors import Issue, SpecError
from lagsolve.mechanics.equations.surface import least_squares, newton
from lagsolve.numeric.system import NumericSystem

#: the largest residual of a constraint the initial state may have, relative to the constraint's scale (the size
#: its residual takes for a displacement of the state's own size, :meth:`NumericSystem.surface_scales`); velocities:
#: absolute
TOLERANCE = 1e-9


def complete_initial(system: NumericSystem, given: Mapping[str, float], source: str = "",
                     t0: float = 0.0, *, line: int = 0, field: str = "simulation.initial",
                     start: Mapping[str, float] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities at ``t0`` from the ``given`` values (``x``, ``x_dot``, ...).

    ``line`` and ``field`` say where the values were given (``simulation.initial`` at a line of
    ``source``, or ``--initial``), for the messages. ``start`` gives starting values for coordinates
    that are not given, tried before the usual ones (so the solution near them is found first).

    Raises
    ------
    SpecError
        When a name is unknown, or the constraints cannot be met (the residual is shown).
    """
    names = system.coordinates
    issues = [Issue(source, line, field, f"unknown coordinate or velocity {k!r}",
                    "known: " + ", ".join([*names, *(f"{n}_dot" for n in names)]))
              for k in given if k not in names and not (k.endswith("_dot") and k[:-4] in names)]
    if issues:
        raise SpecError(issues)
    p = system.parameters
    q = np.array([float(given.get(n, 0.0)) for n in names])
    qd = np.array([float(given.get(f"{n}_dot", 0.0)) for n in names])
    free_q = np.array([n not in given for n in names])
    free_qd = np.array([f"{n}_dot" not in given for n in names])
    n = len(names)

    if system.holonomic and free_q.any():
        q = _solve_positions(system, q, qd, free_q, t0, start)
    if system.holonomic:
        psi = system.position_residual(t0, q, qd, p)
        if not np.all(np.isfinite(psi)) or np.max(np.abs(psi) / system.surface_scales(t0, q, qd)) > TOLERANCE:
            rows = ", ".join(f"{system.constraints[j]} = {v:.3g}" for j, v in zip(system.holonomic, psi, strict=True))
            raise SpecError([Issue(source, line, field, f"the initial positions violate the constraints ({rows})",
                                   "give fewer coordinates (the others are solved from the constraints) or "
                                   "values that satisfy them")])
    if system.m:
        a = system.velocity_jacobian(t0, q, qd, p).reshape(system.m, n)
        b = system.velocity_offset(t0, q, qd, p)
        if free_qd.any():
            rhs = -(a[:, ~free_qd] @ qd[~free_qd] + b)
            qd[free_qd] = np.linalg.lstsq(a[:, free_qd], rhs, rcond=None)[0]
        residual = a @ qd + b
        if not np.all(np.isfinite(residual)) or np.max(np.abs(residual)) > TOLERANCE:
            rows = ", ".join(f"{c} = {v:.3g}" for c, v in zip(system.constraints, residual, strict=True))
            raise SpecError([Issue(source, line, field, f"the initial velocities violate the constraints ({rows})",
                                   "give fewer velocities (the others are solved from the constraints) or "
                                   "values that satisfy them")])
    if not (np.all(np.isfinite(q)) and np.all(np.isfinite(qd))):
        raise SpecError([Issue(source, line, field, "the initial state is not finite",
                                  "give values at which every expression of the problem can be evaluated")])
    resting = at_rest(system, t0, q, qd)
    if resting:
        raise SpecError([Issue(source, line, field, f"contact {resting[0]!r} does not slide at the start (its sliding "
                               "speed is 0), and friction that acts in a plane, -mu N v/|v|, is modelled only while "
                               "the contact slides", "give it a sliding velocity, or let it slide along one line "
                               "(one coordinate under 'sliding:'), where it can stick")])
    return q, qd


#: a contact that slides in a plane is at rest where its sliding speed is below this fraction of the state's
#: fastest velocity (rounding: the speed of a contact at rest computes as 1e-17 and the like)
AT_REST = 1e-12


def at_rest(system: NumericSystem, t: float, q: np.ndarray, qd: np.ndarray) -> list[str]:
    """The contacts that slide in a plane and are at rest at the state (their friction is undefined there)."""
    if not system.planar:
        return []
    speeds = system.speeds(t, q, qd, system.parameters)
    scale = float(np.max(np.abs(qd), initial=0.0))
    return [system.contact_names[c] for c, speed in zip(system.planar, speeds, strict=True)
            if not speed > AT_REST * scale]


#: starting values tried, in order, for the coordinates the user left free (0 first; below before above)
GUESSES = (0.0, -1.0, 1.0, -0.5, 0.5, -2.0, 2.0)


def _solve_positions(system: NumericSystem, q: np.ndarray, qd: np.ndarray, free: np.ndarray,
                     t0: float, start: Mapping[str, float] | None = None) -> np.ndarray:
    """Least-norm Newton iteration (:func:`~lagsolve.mechanics.equations.surface.newton`) on the free coordinates;
    tries several starting values, since a start such as y = 0 for x² + y² = l² has a singular Jacobian. Each
    constraint's residual is divided by its scale (:meth:`NumericSystem.surface_scales`), rows of the Jacobian
    alike: the steps are the same, and the iteration stops at the same relative accuracy whatever the units."""
    p, n = system.parameters, system.n

    def full(x: list[float]) -> np.ndarray:
        state = q.copy()
        state[free] = x
        return state

    def residual(x: list[float]) -> np.ndarray:
        state = full(x)
        return system.position_residual(t0, state, qd, p) / system.surface_scales(t0, state, qd)

    def jacobian(x: list[float]) -> np.ndarray:
        state = full(x)
        rows = system.position_jacobian(t0, state, qd, p).reshape(len(system.holonomic), n)[:, free]
        return rows / system.surface_scales(t0, state, qd)[:, None]

    best, best_residual = q, np.inf
    first = [[float(start.get(c, 0.0)) for c, f in zip(system.coordinates, free, strict=True) if f]] if start else []
    starts = first + [[guess] * int(free.sum()) for guess in GUESSES]
    for x0 in starts:
        with np.errstate(all="ignore"):
            x, _ = newton(residual, jacobian, x0, step=least_squares, tolerance=1e-14)
            trial = full(x)
            left = np.max(np.abs(residual(x)))
        if np.isfinite(left) and left < best_residual:
            best, best_residual = trial, left
        if best_residual < 1e-13:
            break
    return best
