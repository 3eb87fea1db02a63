"""The geometry of a problem (``mechanics/geometry/shapes.py``) evaluated along a trajectory: plain arrays to draw.

Mechanics decides what is a rod, a surface, a wire, a string, a spring, a body or a force; this module only
puts numbers in (the run's parameter values and concrete functions) and evaluates at every sample, so the
figures can draw each frame without SymPy. What depends on the whole run is placed here too: how far a line or
an incline is drawn (the members' extent), where a pulley sits along a strand whose pulley the problem does
not place (so that no strand has a negative length), the wall a spring is fixed to, the base of a wedge.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.geometry.shapes import Anchor
from lagsolve.numeric.compile import compile_state_function, substitute_functions

#: points along a drawn curve
CURVE_POINTS = 400


@dataclass(frozen=True)
class Shape:
    """A polyline to draw: ``points`` of shape (samples, k, dims) (it moves) or (k, dims) (it does not); rows of
    NaN break it into pieces. ``kind`` says how it is drawn (``wire``, ``ground``, ``solid``, ``string``,
    ``pulley``, ``hole``, ``spring``, ``damper``, ``wall``, ``blade``, ``body``, ``spoke``, ``profile``, ``ring``,
    ``centre``); ``views`` the components a view must show to draw it (a plane seen edge-on, the profile of a
    surface of revolution), empty for every view; ``expression`` the SymPy term a spring, damper or centre of
    force stands for (the legend prints it), else None."""

    kind: str
    label: str
    points: np.ndarray
    closed: bool = False
    views: tuple[int, ...] = ()
    expression: Any = None

    def at(self, sample: int) -> np.ndarray:
        """The polyline at one sample, shape (k, dims)."""
        return self.points[sample] if self.points.ndim == 3 else self.points


@dataclass(frozen=True)
class Force:
    """A force drawn as an arrow: on ``member``, at ``point``, the vector ``vector`` (both (samples, dims));
    ``label`` names its constraint or contact, ``kind`` is ``constraint`` or ``friction``."""

    label: str
    kind: str
    member: str
    point: np.ndarray
    vector: np.ndarray


@dataclass(frozen=True)
class Scene:
    """What a sketch draws besides the particles, in physical components.

    ``rods``: (label, start, end), each end an array of shape (samples, dims); ``pivots``:
    arrays (samples, dims); ``surfaces``: (label, point, normal), arrays (samples, dims),
    drawn as the line through the point across the normal; ``curves``: (label, points),
    a fixed polyline of shape (k, dims). Labels name the constraint, or are empty where
    the coordinates fix a distance. ``shapes``: everything else (:class:`Shape`); ``forces``: the arrows;
    ``markers``: the members drawn as labelled dots besides the particles (bodies' centres, a mass on a line),
    (name, (samples, dims)); ``gravity``: its direction, or empty; ``scale``: the size of the system (the
    largest extent of the members and pivots over the run), which sizes blocks, coils and pulleys; ``ends``:
    (label, stop, direction), a surface line that ends at the point ``stop`` (dims,) and runs from it only against
    ``direction`` (an incline that ends at its top corner, where the pulley is).
    """

    rods: tuple[tuple[str, np.ndarray, np.ndarray], ...] = ()
    pivots: tuple[np.ndarray, ...] = ()
    surfaces: tuple[tuple[str, np.ndarray, np.ndarray], ...] = ()
    curves: tuple[tuple[str, np.ndarray], ...] = ()
    shapes: tuple[Shape, ...] = ()
    forces: tuple[Force, ...] = ()
    markers: tuple[tuple[str, np.ndarray], ...] = ()
    gravity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    scale: float = 1.0
    joints: tuple[np.ndarray, ...] = ()  # hinges on a moving member (a bob's rod on the end of a bar), (samples, dims)
    ends: tuple[tuple[str, np.ndarray, np.ndarray], ...] = ()

    def __bool__(self) -> bool:
        return bool(self.rods or self.pivots or self.surfaces or self.curves or self.shapes or self.forces
                    or self.markers)


class Run:
    """A trajectory with the problem's expressions compiled against it: ``along(expressions)`` evaluates at
    every sample, ``member(name)`` is a particle's, body's or marker's position, ``anchor`` an end's."""

    def __init__(self, problem: Any, parameters: np.ndarray, trajectory: Any,
                 markers: tuple[tuple[str, tuple[Any, ...]], ...] = ()) -> None:
        self.problem, self.parameters, self.trajectory = problem, parameters, trajectory
        self.t, self.q, self.qd = trajectory.t, trajectory.q, trajectory.qd
        self.concrete = {}
        if problem.simulation is not None:
            for fn in problem.functions:
                given = problem.simulation.functions.get(fn.name)
                if given is not None:
                    self.concrete[fn.function] = (given.arguments, given.expression)
        self.arguments = {"time": problem.time, "coordinates": [c.symbol for c in problem.coordinates],
                          "velocities": [c.velocity for c in problem.coordinates],
                          "parameters": [p.symbol for p in problem.parameters]}
        self.members: dict[str, np.ndarray] = {}
        offset = 0
        for name, d in trajectory.particles:
            self.members[name] = trajectory.positions[:, offset:offset + d]
            offset += d
        for body in problem.bodies:
            values = self.along(tuple(body.position))
            if values is not None:
                self.members[body.name] = values
        for name, position in markers:
            values = self.along(position)
            if values is not None:
                self.members[name] = values

    def compiled(self, exprs: tuple[Any, ...]) -> Any:
        prepared = [substitute_functions(sympy.Integer(e) if isinstance(e, int) else e, self.concrete) for e in exprs]
        return compile_state_function(prepared, **self.arguments, backend="python")

    def along(self, exprs: tuple[Any, ...]) -> np.ndarray | None:
        """The expressions at every sample, shape (samples, len(exprs)); None where one is not finite."""
        if not exprs:
            return None
        fn = self.compiled(exprs)
        values = np.array([fn(ti, qi, qdi, self.parameters) for ti, qi, qdi in zip(self.t, self.q, self.qd,
                                                                                   strict=True)], dtype=float)
        return values if values.size and np.all(np.isfinite(values)) else None

    def member(self, name: str | None) -> np.ndarray | None:
        return self.members.get(name) if name is not None else None

    def anchor(self, anchor: Anchor) -> np.ndarray | None:
        return self.member(anchor.particle) if anchor.particle is not None else self.along(anchor.point)

    def scale(self, pivots: list[np.ndarray]) -> float:
        """The size of the system: the largest extent of the members and pivots at one sample (a cart's two
        wheels apart, not how far it rolls); for a single member, its extent over the run (1 when nothing moves)."""
        groups = [v for v in self.members.values()] + pivots
        if not groups:
            return 1.0
        dims = max(v.shape[1] for v in groups)
        stacked = np.stack([np.pad(v, ((0, 0), (0, dims - v.shape[1]))) for v in groups], axis=1)  # (s, k, d)
        size = float(np.max(np.ptp(stacked, axis=1))) if len(groups) > 1 else 0.0
        if size < 1e-9:
            size = float(np.max(np.ptp(stacked.reshape(-1, dims), axis=0)))
        if size < 1e-9:
            size = float(np.max(np.abs(stacked))) or 1.0
        return size
