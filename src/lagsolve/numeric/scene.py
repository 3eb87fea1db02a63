"""The geometry of a problem (``mechanics/geometry.py``) evaluated along a trajectory: plain arrays to draw.

Mechanics decides what is a rod, a surface or a wire; this module only puts numbers in
(the run's parameter values and concrete functions) and evaluates at every sample, so the
figures can draw each frame without SymPy.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.geometry import Anchor, Geometry
from lagsolve.numeric.compile import compile_state_function, substitute_functions

#: points along a drawn curve
CURVE_POINTS = 400


@dataclass(frozen=True)
class Scene:
    """What a sketch draws besides the particles, in physical components.

    ``rods``: (label, start, end), each end an array of shape (samples, dims); ``pivots``:
    arrays (samples, dims); ``surfaces``: (label, point, normal), arrays (samples, dims),
    drawn as the line through the point across the normal; ``curves``: (label, points),
    a fixed polyline of shape (k, dims). Labels name the constraint, or are empty where
    the coordinates fix a distance.
    """

    rods: tuple[tuple[str, np.ndarray, np.ndarray], ...] = ()
    pivots: tuple[np.ndarray, ...] = ()
    surfaces: tuple[tuple[str, np.ndarray, np.ndarray], ...] = ()
    curves: tuple[tuple[str, np.ndarray], ...] = ()

    def __bool__(self) -> bool:
        return bool(self.rods or self.pivots or self.surfaces or self.curves)


def evaluate(geometry: Geometry, problem: Any, parameters: np.ndarray, t: np.ndarray, q: np.ndarray,
             qd: np.ndarray, positions: np.ndarray) -> Scene:
    """Evaluate ``geometry`` at the samples ``t``, ``q``, ``qd`` (shape (samples, n)), with ``parameters``
    in the problem's order; ``positions`` are the particles' positions (the trajectory's, shape
    (samples, total components)). Shapes that do not evaluate to finite numbers are left out."""
    concrete = {}
    if problem.simulation is not None:
        for fn in problem.functions:
            given = problem.simulation.functions.get(fn.name)
            if given is not None:
                concrete[fn.function] = (given.arguments, given.expression)
    arguments = {"time": problem.time, "coordinates": [c.symbol for c in problem.coordinates],
                 "velocities": [c.velocity for c in problem.coordinates],
                 "parameters": [p.symbol for p in problem.parameters]}

    def along(exprs: tuple[Any, ...]) -> np.ndarray | None:
        prepared = [substitute_functions(sympy.Integer(e) if isinstance(e, int) else e, concrete) for e in exprs]
        fn = compile_state_function(prepared, **arguments, backend="python")
        values = np.array([fn(ti, qi, qdi, parameters) for ti, qi, qdi in zip(t, q, qd, strict=True)])
        return values if values.size and np.all(np.isfinite(values)) else None

    columns: dict[str, np.ndarray] = {}
    offset = 0
    for particle in problem.particles:
        d = len(particle.position)
        columns[particle.name] = positions[:, offset:offset + d]
        offset += d

    def end(anchor: Anchor) -> np.ndarray | None:
        return columns.get(anchor.particle) if anchor.particle is not None else along(anchor.point)

    rods: list[tuple[str, np.ndarray, np.ndarray]] = []
    pivots: list[np.ndarray] = []
    for rod in geometry.rods:
        start, stop = end(rod.start), end(rod.end)
        if start is None or stop is None or start.shape != stop.shape:
            continue
        rods.append((rod.constraint or "", start, stop))
        for anchor, values in ((rod.start, start), (rod.end, stop)):
            if anchor.particle is None and not any(np.array_equal(values, p) for p in pivots):
                pivots.append(values)
    surfaces = []
    for surface in geometry.surfaces:
        point, normal = along(surface.point), along(surface.normal)
        if point is not None and normal is not None:
            surfaces.append((surface.constraint, point, normal))
    curves = []
    for curve in geometry.curves:
        points = _curve_points(curve, along, t, q, qd, parameters, arguments, concrete)
        if points is not None:
            curves.append((curve.constraint, points))
    return Scene(tuple(rods), tuple(pivots), tuple(surfaces), tuple(curves))


def _curve_points(curve: Any, along: Any, t: np.ndarray, q: np.ndarray, qd: np.ndarray, parameters: np.ndarray,
                  arguments: dict[str, Any], concrete: dict[Any, Any]) -> np.ndarray | None:
    """A circle (centre, radius at the first sample) or the shape r(u) over three times the range of u
    the motion covers (the figure's limits cut it)."""
    if curve.coordinate is None:
        centre = along((*curve.centre, curve.radius))
        if centre is None:
            return None
        *c, radius = centre[0]
        angle = np.linspace(0.0, 2 * np.pi, CURVE_POINTS)
        circle = np.zeros((CURVE_POINTS, len(c)))
        circle[:, 0] = c[0] + radius * np.cos(angle)
        circle[:, 1] = c[1] + radius * np.sin(angle)
        for k in range(2, len(c)):
            circle[:, k] = c[k]
        return circle
    k = arguments["coordinates"].index(curve.coordinate)
    low, high = float(np.min(q[:, k])), float(np.max(q[:, k]))
    span = high - low if high > low else 1.0
    u = np.linspace(low - span, high + span, CURVE_POINTS)
    prepared = [substitute_functions(e, concrete) for e in curve.shape]
    fn = compile_state_function(prepared, **arguments, backend="python")
    base = np.array(q[0], dtype=float)
    points = []
    for value in u:
        base[k] = value
        points.append(fn(t[0], base, qd[0], parameters))
    out = np.array(points, dtype=float)
    finite = np.all(np.isfinite(out), axis=1)
    return out[finite] if finite.sum() >= 2 else None
