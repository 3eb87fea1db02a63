"""The polylines of a scene (``numeric/scene.py``): wires, grounds and wedges, strings and pulleys, springs,
dampers and walls, knife edges, bodies, surfaces of revolution, and the forces, evaluated along a run.

Everything here is arithmetic on what ``mechanics/geometry/shapes.py`` decided; the only choices are of drawing sizes,
proportional to the system's ``scale`` (the members' extent over the run), and of where the problem leaves a
place open: how far a line is drawn (past the members' extent), where a spring's wall stands (beyond the motion,
on the side of the spring's fixed point), where a pulley sits along a strand (so no strand has a negative
length), where a wedge's base is (at its lowest point).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.geometry.shapes import Anchor, Geometry, Surface
from lagsolve.numeric.compile import substitute_functions
from lagsolve.numeric.pulleys import corner, meeting
from lagsolve.numeric.scene import CURVE_POINTS, Force, Run, Scene, Shape

#: points along a moving wire (drawn at every sample) and around a circle
MOVING_POINTS = 72
CIRCLE_POINTS = 48
#: zig-zags of a spring
COILS = 7


def _unit(v: np.ndarray) -> np.ndarray:
    size = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.where(size > 1e-300, v / np.where(size > 1e-300, size, 1.0), 0.0)


def _perpendicular(e: np.ndarray) -> np.ndarray:
    """A unit vector across each row of ``e`` (in the plane: turned a quarter; in space: across z, else x)."""
    if e.shape[-1] == 2:
        return np.stack([-e[..., 1], e[..., 0]], axis=-1)
    other = np.zeros_like(e)
    other[..., 2] = 1.0
    upright = np.abs(e[..., 2]) > 0.9
    other[upright] = [1.0, 0.0, 0.0]
    return _unit(np.cross(e, other))


def _break(*pieces: np.ndarray) -> np.ndarray:
    """Polylines (samples, k_i, d) joined with a row of NaN between them."""
    out = []
    for i, piece in enumerate(pieces):
        if i:
            out.append(np.full(piece.shape[:-2] + (1, piece.shape[-1]), np.nan))
        out.append(piece)
    return np.concatenate(out, axis=-2)


def zigzag(start: np.ndarray, end: np.ndarray, width: float, coils: int = COILS) -> np.ndarray:
    """A spring from ``start`` to ``end`` (samples, d): straight leads, then zig-zags of half-width ``width``."""
    e = end - start
    across = _perpendicular(_unit(e))
    fractions = [0.0, 0.18]
    offsets = [0.0, 0.0]
    for k in range(2 * coils):
        fractions.append(0.18 + 0.64 * (k + 0.5) / (2 * coils))
        offsets.append(width if k % 2 == 0 else -width)
    fractions += [0.82, 1.0]
    offsets += [0.0, 0.0]
    f = np.array(fractions)[None, :, None]
    o = np.array(offsets)[None, :, None]
    return start[:, None, :] + f * e[:, None, :] + o * across[:, None, :]


def dashpot(start: np.ndarray, end: np.ndarray, width: float) -> np.ndarray:
    """A damper from ``start`` to ``end``: a rod into an open cylinder fixed to the start, a piston at the end's rod."""
    e = end - start
    length = np.linalg.norm(e, axis=-1, keepdims=True)
    u = _unit(e)
    across = _perpendicular(u)
    size = np.minimum(length, 4 * width) if np.any(length > 0) else length
    mid = start + 0.5 * e

    def at(base: np.ndarray, along: Any, side: float) -> np.ndarray:
        return base + along * u + side * width * across

    cylinder = np.stack([at(start, 0, 0), at(mid, -0.5 * size, 0), at(mid, -0.5 * size, 1), at(mid, 0.5 * size, 1),
                         np.full_like(start, np.nan), at(mid, -0.5 * size, 0), at(mid, -0.5 * size, -1),
                         at(mid, 0.5 * size, -1)], axis=1)
    piston = np.stack([at(mid, 0.1 * size, 0.75), at(mid, 0.1 * size, -0.75), np.full_like(start, np.nan),
                       at(mid, 0.1 * size, 0), end], axis=1)
    return _break(cylinder, piston)


def circle(centre: np.ndarray, radius: Any, first: np.ndarray, second: np.ndarray,
           points: int = CIRCLE_POINTS) -> np.ndarray:
    """Circles about ``centre`` (samples, d) in the plane of the unit vectors ``first``, ``second``."""
    beta = np.linspace(0.0, 2 * np.pi, points)
    r = np.asarray(radius, dtype=float).reshape(-1, 1, 1) if np.ndim(radius) else float(radius)
    return (centre[:, None, :] + r * np.cos(beta)[None, :, None] * first[:, None, :]
            + r * np.sin(beta)[None, :, None] * second[:, None, :])


def _integrated(rate: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.zeros_like(rate)
    if len(t) > 1:
        out[1:] = np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))
    return out


def _same_line(p1: np.ndarray, n1: np.ndarray, p2: np.ndarray, n2: np.ndarray) -> bool:
    """Whether two surfaces (points and normals at every sample) are the same line or plane throughout."""
    u1, u2 = _unit(n1), _unit(n2)
    if not np.allclose(np.abs(np.einsum("sd,sd->s", u1, u2)), 1.0, atol=1e-9):
        return False
    return bool(np.allclose(np.einsum("sd,sd->s", p2 - p1, u1), 0.0, atol=1e-9 * (1 + np.abs(p1).max())))


class Builder:
    """The shapes of one geometry along one run (``scale``: the system's size)."""

    def __init__(self, run: Run, geometry: Geometry, scale: float) -> None:
        self.run, self.geometry, self.scale = run, geometry, scale
        self.gravity = np.zeros(0)
        if geometry.gravity:
            g = run.along(geometry.gravity)
            if g is not None and np.linalg.norm(g[0]) > 0:
                self.gravity = g[0] / np.linalg.norm(g[0])
        self.bases: dict[str, np.ndarray] = {}  # a carrier's lowest point (the base of its wedge or box)
        self.corners: dict[str, np.ndarray] = {}  # and the corners of that wedge or box
        self.pivots: list[np.ndarray] = []  # fixed points found on the way (a pulley's axle)
        self.pulleys: list[tuple[np.ndarray, list[np.ndarray]]] = []  # a pulley where two strands meet, their ups
        self.ends: list[tuple[str, np.ndarray, np.ndarray]] = []  # a surface line ended at its pulley

    # --- helpers ---------------------------------------------------------------------------------------------

    def grid(self, exprs: tuple[Any, ...], index: int, values: np.ndarray, sample: int | None = None,
             base: np.ndarray | None = None) -> np.ndarray | None:
        """The expressions at every sample (or only at ``sample``, with the coordinates ``base`` when given) with
        coordinate ``index`` replaced by each of ``values`` (samples, m) (or (m,) for every sample alike): shape
        (samples, m, len(exprs)); None where not finite."""
        run = self.run
        arguments = [run.arguments["time"], *run.arguments["coordinates"], *run.arguments["velocities"],
                     *run.arguments["parameters"]]
        prepared = [substitute_functions(sympy.sympify(e, strict=True), run.concrete) for e in exprs]
        fn = sympy.lambdify(arguments, prepared, modules=[{"sign": np.sign, "Heaviside": lambda x: (x > 0) * 1.0},
                                                           "numpy"])
        rows = slice(None) if sample is None else slice(sample, sample + 1)
        states, rates, times = run.q[rows], run.qd[rows], run.t[rows]
        if base is not None:
            states = base[None, :]
        samples, n = states.shape
        values = np.broadcast_to(values, (samples, values.shape[-1])) if values.ndim == 1 else values
        m = values.shape[1]
        q = np.repeat(states[:, None, :], m, axis=1)
        q[:, :, index] = values
        qd = np.repeat(rates[:, None, :], m, axis=1)
        t = np.repeat(times[:, None], m, axis=1)
        p = [np.full((samples, m), v) for v in run.parameters]
        with np.errstate(all="ignore"):
            out = fn(t, *(q[:, :, k] for k in range(n)), *(qd[:, :, k] for k in range(n)), *p)
        stacked = np.stack([np.broadcast_to(np.asarray(c, dtype=float), (samples, m)) for c in out], axis=-1)
        return stacked if np.all(np.isfinite(stacked)) else None

    def extent(self, point: np.ndarray, direction: np.ndarray, only: str | None = None) -> tuple[float, float]:
        """The range of the members' positions (or of ``only``'s) over the run along the unit ``direction`` from
        ``point`` (both (samples, d)), widened by a quarter of the scale (an eighth for one member)."""
        spans = []
        for name, values in self.run.members.items():
            if values.shape[1] == point.shape[1] and only in (None, name):
                spans.append(np.einsum("sd,sd->s", values - point, direction))
        if not spans:
            return -self.scale, self.scale
        every = np.concatenate(spans)
        margin = (0.25 if only is None else 0.12) * self.scale
        return float(every.min()) - margin, float(every.max()) + margin

    def down(self, dims: int) -> np.ndarray | None:
        return self.gravity if self.gravity.size == dims else None

    # --- wires -----------------------------------------------------------------------------------------------

    def curves(self, add_pivot: Callable[[np.ndarray], None]) -> tuple[list[tuple[str, np.ndarray]], list[Shape]]:
        """Fixed wires as polylines (solid ones as shapes), moving ones as shapes at every sample."""
        run = self.run
        fixed: list[tuple[str, np.ndarray]] = []
        shapes: list[Shape] = []
        names = run.arguments["coordinates"]
        for curve in self.geometry.curves:
            if curve.coordinate is None:
                shapes += self._sphere(curve)
                continue
            k = names.index(curve.coordinate)
            u = run.q[:, k]
            low, high = float(u.min()), float(u.max())
            span = high - low if high > low else 1.0
            if curve.closed:
                values = u[:, None] + np.linspace(-np.pi, np.pi, MOVING_POINTS if curve.moving else CURVE_POINTS)
            else:
                start = self.grid(curve.shape, k, np.zeros(1)) if curve.moving else None
                low, high = low - span, high + span
                if start is not None and np.allclose(start[:, 0], start[0, 0], atol=1e-12 * self.scale):
                    low, high = min(low, 0.0), max(high, 0.0)  # it turns about its point at u = 0: from there
                    add_pivot(start[:, 0])
                values = np.linspace(low, high, MOVING_POINTS if curve.moving else CURVE_POINTS)
            if curve.moving:
                points = self.grid(curve.shape, k, values)
                if points is not None:
                    shapes.append(Shape("wire", curve.constraint, points, curve.closed))
                continue
            points = self.grid(curve.shape, k, values[0] if values.ndim == 2 else values, sample=0)
            if points is None:
                continue
            if curve.solid:
                shapes.append(Shape("solid", curve.constraint, points[0], closed=True))
            else:
                fixed.append((curve.constraint, points[0]))
        return fixed, shapes

    def _sphere(self, curve: Any) -> list[Shape]:
        """The outline of a sphere (a circle in the plane) in every view, from its centre and radius."""
        values = self.run.along((*curve.centre, curve.radius))
        if values is None:
            return []
        *centre, radius = values[0]
        dims = len(centre)
        out = []
        for i, j in ((0, 1), (0, 2), (1, 2))[: 1 if dims == 2 else 3]:
            first, second = np.zeros((1, dims)), np.zeros((1, dims))
            first[0, i], second[0, j] = 1.0, 1.0
            ring = circle(np.array([centre]), radius, first, second, CURVE_POINTS)[0]
            kind = "solid" if curve.solid else "wire"
            out.append(Shape(kind, curve.constraint, ring, closed=True, views=(i, j) if dims == 3 else ()))
        return out

    def revolutions(self) -> list[Shape]:
        """A surface of revolution's outline seen across its axis (both sides of the profile) and its rim and a
        middle ring seen along the axis, out to 1.3 times the distance from the axis the particle reaches."""
        run = self.run
        out: list[Shape] = []
        names = run.arguments["coordinates"]
        for rev in self.geometry.revolutions:
            centre = run.along(rev.centre)
            member = run.member(rev.particle)
            if centre is None or member is None:
                continue
            c = centre[0]
            across = [k for k in range(3) if k != rev.axis]
            reach = float(np.max(np.hypot(member[:, across[0]] - c[across[0]], member[:, across[1]] - c[across[1]])))
            reach = 1.3 * reach if reach > 0 else self.scale
            # the profile: along the coordinate that most changes the distance from the axis, from the start
            best, profile_points = None, None
            for name in rev.coordinates:
                index = names.index(name)
                low, high = float(run.q[:, index].min()), float(run.q[:, index].max())
                span = max(high - low, abs(high), abs(low), 1.0)
                values = np.linspace(low - 3 * span, high + 3 * span, 400)
                if getattr(name, "is_positive", False):
                    values = np.linspace(0.0, high + 3 * span, 400)
                grid = self.grid(rev.shape, index, values, sample=0)
                if grid is None:
                    continue
                cloud = grid[0]
                distance = np.hypot(cloud[:, across[0]] - c[across[0]], cloud[:, across[1]] - c[across[1]])
                if best is None or np.ptp(distance) > best:
                    best, profile_points = float(np.ptp(distance)), cloud
            if profile_points is None:
                continue
            cloud = profile_points
            rho = np.hypot(cloud[:, across[0]] - c[across[0]], cloud[:, across[1]] - c[across[1]])
            height = cloud[:, rev.axis] - c[rev.axis]
            keep = rho <= reach
            if keep.sum() < 3:
                continue
            order = np.argsort(rho[keep])
            rho, height = rho[keep][order], height[keep][order]
            bins = np.linspace(0.0, reach, 61)
            which = np.digitize(rho, bins)
            profile = np.array([[rho[which == b].mean(), height[which == b].mean()] for b in np.unique(which)])
            if profile[0, 0] > 0:  # down to the axis
                profile = np.vstack([[0.0, profile[0, 1]], profile])
            for j in across:
                line = np.full((2 * len(profile) + 1, 3), np.nan)
                for side, rows in ((-1, slice(0, len(profile))), (1, slice(len(profile) + 1, None))):
                    pts = np.tile(c, (len(profile), 1))
                    pts[:, j] += side * profile[:, 0]
                    pts[:, rev.axis] += profile[:, 1]
                    line[rows] = pts[::-1] if side < 0 else pts
                out.append(Shape("profile", rev.constraint, line, views=(j, rev.axis)))
            first, second = np.zeros((1, 3)), np.zeros((1, 3))
            first[0, across[0]], second[0, across[1]] = 1.0, 1.0
            for radius, h in (profile[-1], profile[len(profile) // 2]):
                ring_centre = c.copy()
                ring_centre[rev.axis] += h
                ring = circle(ring_centre[None, :], radius, first, second)[0]
                out.append(Shape("ring", "", ring, closed=True, views=tuple(across)))
        return out

    # --- surfaces, grounds and wedges -------------------------------------------------------------------------

    def surfaces(self) -> tuple[list[tuple[str, np.ndarray, np.ndarray]], list[Shape]]:
        """Each surface's point and normal at every sample; the ground beneath fixed ones (a band on the solid
        side), the wedge or box of a member that carries one; a support through a carrier's base."""
        run = self.run
        lines: list[tuple[str, np.ndarray, np.ndarray]] = []
        shapes: list[Shape] = []
        # the faces wedges and boxes carry first (their bodies, bases and corners), then the floors under them
        ordered = sorted(self.geometry.surfaces, key=lambda s: (s.carrier is None, s.implied))
        for surface in ordered:
            point, normal = run.along(surface.point), run.along(surface.normal)
            if point is None or normal is None:
                continue
            if surface.implied and surface.particle in self.bases:
                point = self.bases[surface.particle]
            same = next((k for k, (_, p, n) in enumerate(lines) if p.shape == point.shape and _same_line(p, n, point,
                                                                                                       normal)), None)
            if same is not None:  # two constraints on one floor (two wheels): one line, both names
                lines[same] = (f"{lines[same][0]}, {surface.constraint}", lines[same][1], lines[same][2])
                continue
            if not surface.implied:  # a support the coordinates imply is drawn under its member only
                lines.append((surface.constraint, point, normal))
            solid = run.along(surface.solid) if surface.solid else None
            if solid is None:
                continue
            if surface.carrier is not None and point.shape[1] == 2:
                wedge = self._wedge(surface, point, normal)
                if wedge is not None:
                    shapes.append(wedge)
                continue
            shapes += self._ground(surface, point, normal, solid)
        return lines, shapes

    def _ground(self, surface: Surface, point: np.ndarray, normal: np.ndarray, solid: np.ndarray) -> list[Shape]:
        """A band of material along the line (in space: along each axis across the plane's normal)."""
        n = _unit(normal)
        side = np.sign(np.einsum("sd,sd->s", solid, n))[:, None]
        if not np.any(side):
            return []
        depth = 0.05 * self.scale
        dims = point.shape[1]
        directions: list[tuple[np.ndarray, tuple[int, ...]]] = []
        if dims == 2:
            directions.append((_perpendicular(n), ()))
        else:
            axis = int(np.argmax(np.abs(n[0])))
            if abs(n[0, axis]) < 0.999:
                return []
            for j in (k for k in range(3) if k != axis):
                d = np.zeros_like(n)
                d[:, j] = 1.0
                directions.append((d, (j, axis)))
        out = []
        kind = "support" if surface.implied else "ground"
        if surface.implied:  # a fixed floor or table: where it is at the start, under all the member's travel
            point = np.broadcast_to(point[0], point.shape)
        for d, views in directions:
            low, high = self.extent(point, d, surface.particle if surface.implied else None)
            if surface.particle in self.corners:  # under the whole wedge or box it carries
                along = np.einsum("skd,sd->sk", self.corners[surface.particle] - point[:, None, :], d)
                low, high = min(low, float(along.min())), max(high, float(along.max()))
            a, b = point + low * d, point + high * d
            band = np.stack([a, b, b + side * depth * n, a + side * depth * n], axis=1)
            moving = not np.allclose(band, band[0], atol=1e-12 * self.scale)
            out.append(Shape(kind, surface.constraint, band if moving else band[0], True, views))
        return out

    def holes_in_grounds(self, shapes: list[Shape]) -> list[Shape]:
        """``shapes`` with each fixed band of a floor or table (a ``support`` or ``ground``) that a string's hole
        lies on cut in two at the hole, so that the string goes through a gap in the table, not through it."""
        holes = [s.points[0] for s in shapes if s.kind == "hole" and s.points.ndim == 2]
        if not holes:
            return shapes
        half = 0.07 * self.scale  # wider than the ring that marks the hole
        out: list[Shape] = []
        for shape in shapes:
            pieces = [shape.points] if shape.kind in ("support", "ground") and shape.points.shape[:1] == (4,) else []
            for hole in holes:
                pieces = [cut for piece in pieces for cut in _cut_band(piece, hole, half)]
            if not pieces or (len(pieces) == 1 and pieces[0] is shape.points):
                out.append(shape)
                continue
            out += [Shape(shape.kind, shape.label, piece, shape.closed, shape.views) for piece in pieces]
        return out

    def grounds_at_pulleys(self, shapes: list[Shape]) -> list[Shape]:
        """``shapes`` with each fixed plane that a strand runs along to its pulley ended at the pulley, and a face
        down from there (the top corner of an incline with the weight hanging beside it)."""
        out: list[Shape] = []
        for shape in shapes:
            cut = None
            if shape.kind == "ground" and shape.points.shape == (4, 2) and self.gravity.size == 2:
                cut = next((c for pulley, ups in self.pulleys for u in ups
                            if (c := corner(shape.points, pulley, u, self.gravity, self.scale)) is not None), None)
            if cut is None:
                out.append(shape)
                continue
            out += [Shape(shape.kind, shape.label, band, shape.closed, shape.views) for band in cut]
            self.ends.append((shape.label, cut[0][1], cut[0][1] - cut[0][0]))
        return out

    def _wedge(self, surface: Surface, point: np.ndarray, normal: np.ndarray) -> Shape | None:
        """The carrier's body under the face it carries: from the face (as far as the member on it goes, past its
        ends, and to the carrier's own point) down to the carrier's lowest point, across gravity."""
        down = self.down(2)
        member, carrier = self.run.member(surface.particle), self.run.member(surface.carrier)
        if down is None or member is None or carrier is None:
            return None
        d = _perpendicular(_unit(normal))
        used = np.einsum("sd,sd->s", member - point, d)
        own = np.einsum("sd,sd->s", carrier - point, d)
        margin = 0.15 * self.scale
        low, high = float(used.min()) - margin, float(used.max()) + margin
        rise = float(-(d[0] @ down))  # height gained per unit along d
        if rise > 1e-9 and float(own.min()) <= float(used.min()):
            low = float(own.min())  # the carrier's point is its lowest corner
        elif rise < -1e-9 and float(own.max()) >= float(used.max()):
            high = float(own.max())
        low, high = min(low, float(own.min())), max(high, float(own.max()))
        height = lambda x: -(x @ down)  # noqa: E731
        tall = float(np.max(np.abs(height(point) - height(carrier))))
        if abs(rise) < 1e-9 and high - low < 1.5 * tall:  # a box at least as wide as it is tall
            middle, half = (low + high) / 2, 0.75 * tall
            low, high = middle - half, middle + half
        a = point + low * d
        b = point + high * d
        base = np.minimum(np.minimum(height(a), height(b)), height(carrier))
        a2 = a + (height(a) - base)[:, None] * down
        b2 = b + (height(b) - base)[:, None] * down
        corners = np.stack([a, b, b2, a2], axis=1)
        self.bases[surface.carrier or ""] = a2
        self.corners[surface.carrier or ""] = corners
        return Shape("solid", surface.carrier or "", corners, closed=True)

    # --- strings, springs, knife edges ----------------------------------------------------------------------

    def strings(self) -> list[Shape]:
        """Each string from one end over its pulley (or through its hole) to the other."""
        run = self.run
        out: list[Shape] = []
        trajectory = run.trajectory
        for string in self.geometry.strings:
            first, second = run.member(string.ends[0]), run.member(string.ends[1])
            a1, a2 = run.along(string.anchors[0]), run.along(string.anchors[1])
            if first is None or second is None or a1 is None or a2 is None:
                continue
            ends, anchors = [first, second], [a1, a2]
            j = trajectory.constraints.index(string.constraint) if string.constraint in trajectory.constraints else -1
            lam = trajectory.multipliers[:, j] if j >= 0 else np.ones(1)
            pull = float(np.sign(np.median(lam[lam != 0]))) if np.any(lam != 0) else 1.0
            towards: list[np.ndarray | None] = []
            for i, slide in enumerate(string.slides):
                u = run.along(slide) if slide else None
                if u is None:
                    towards.append(None)
                    continue
                u = pull * _unit(u[0])
                closest = float(np.max((ends[i] - anchors[i]) @ u))
                margin = 0.08 * self.scale
                shift = closest + margin if closest > -margin else 0.0  # past the nearest the end comes
                anchors[i] = anchors[i] + shift * u
                towards.append(u)
            u1, u2 = towards
            meet = meeting(ends, anchors, u1, u2, self.scale)
            if meet is not None:  # both strands' lines meet beyond their ends: one pulley there
                wheel = circle(meet[:1], 0.04 * self.scale, np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]))
                out.insert(0, Shape("string", string.constraint, np.stack([first, meet, second], axis=1)))
                out.append(Shape("pulley", string.constraint, wheel[0], closed=True))
                self.pivots.append(meet)
                self.pulleys.append((meet[0], [u for u in towards if u is not None]))
                continue
            a1, a2 = anchors
            gap = float(np.linalg.norm(a2[0] - a1[0]))
            if gap < 1e-9 * self.scale:
                path = np.stack([first, a1, second], axis=1)
                out.append(Shape("hole", string.constraint, a1[:1]))
            elif u1 is not None and u2 is not None and np.allclose(u1, u2) and abs((a2[0] - a1[0]) @ u1) < 1e-9:
                centre, radius = 0.5 * (a1 + a2), 0.5 * gap
                e = _unit(a2 - a1)
                beta = np.linspace(np.pi, 0.0, 25)[None, :, None]
                arc = centre[:, None, :] + radius * (np.cos(beta) * e[:, None, :] + np.sin(beta) * u1[None, None, :])
                path = np.concatenate([first[:, None, :], arc, second[:, None, :]], axis=1)
                wheel = circle(centre, radius, e, np.broadcast_to(u1, e.shape))
                out.append(Shape("pulley", string.constraint, wheel[0], closed=True))
                self.pivots.append(centre)
            else:
                path = np.stack([first, a1, a2, second], axis=1)
                if a1.shape[1] == 2:
                    for anchor in (a1, a2):
                        small = circle(anchor[:1], 0.03 * self.scale, np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]]))
                        out.append(Shape("pulley", string.constraint, small[0], closed=True))
            out.insert(0, Shape("string", string.constraint, path))
        return out

    def springs(self) -> tuple[list[Shape], list[np.ndarray]]:
        """Springs as zig-zags and dampers as dashpots (side by side where both join the same ends), fixed to a
        wall beyond the motion or to a point; centres of force as points. Also the fixed points springs hang
        from (pivots)."""
        run = self.run
        out: list[Shape] = []
        fixed: list[np.ndarray] = []
        pairs: dict[tuple, int] = {}
        for spring in self.geometry.springs:
            key = (spring.start, spring.end.particle)
            pairs[key] = pairs.get(key, 0) + 1
        seen: dict[tuple, int] = {}
        width = 0.035 * self.scale
        for spring in self.geometry.springs:
            start, end = run.anchor(spring.start), run.anchor(spring.end)
            if start is None or end is None:
                continue
            if spring.kind == "centre":
                out.append(Shape("centre", spring.label, start[:1], expression=spring.term))
                continue
            if spring.wall:
                start, wall = self._wall(start, end, spring.wall, spring.label)
                if wall is not None and not any(s.kind == "wall" and np.allclose(s.points, wall.points) for s in out):
                    out.append(wall)
            elif spring.start.particle is None:
                fixed.append(start)
            key = (spring.start, spring.end.particle)
            if spring.wall and self.gravity.size == start.shape[1]:
                lift = -1.3 * width * (pairs[key] ** 0.5) * self.gravity  # above the floor the member rests on
                start, end = start + lift, end + lift
            if pairs[key] > 1:
                k = seen.get(key, 0)
                seen[key] = k + 1
                shift = (2.2 * width) * (k - (pairs[key] - 1) / 2) * _perpendicular(_unit(end - start))
                start, end = start + shift, end + shift
            drawn = zigzag(start, end, width) if spring.kind == "spring" else dashpot(start, end, width)
            out.append(Shape(spring.kind, spring.label, drawn, expression=spring.term))
        return out, fixed

    def _wall(self, foot: np.ndarray, end: np.ndarray, normal: tuple[Any, ...], label: str
              ) -> tuple[np.ndarray, Shape | None]:
        """The foot of a spring on a wall across the axis ``normal`` points along: beyond the member's motion on the
        side of the foot's own place, by a third of the scale."""
        axis = int(np.argmax([abs(float(n)) for n in normal]))
        origin = float(np.mean(foot[:, axis]))
        motion = end[:, axis]
        gap = max(0.35 * self.scale, 1e-9)
        place = min(origin, float(motion.min())) - gap if float(np.mean(motion)) >= origin else \
            max(origin, float(motion.max())) + gap
        foot = foot.copy()
        foot[:, axis] = place
        if foot.shape[1] != 2:
            return foot, None
        across = 1 - axis
        centre = float(np.mean(end[:, across]))
        half = 0.25 * self.scale
        side = -1.0 if place < float(np.mean(motion)) else 1.0
        corner = np.zeros((4, 2))
        corner[:, axis] = [place, place, place + side * 0.05 * self.scale, place + side * 0.05 * self.scale]
        corner[:, across] = [centre - half, centre + half, centre + half, centre - half]
        return foot, Shape("wall", label, corner, closed=True)

    def blades(self) -> list[Shape]:
        """A knife edge as a short blade through its particle along the direction it may move in."""
        out: list[Shape] = []
        for blade in self.geometry.blades:
            member, direction = self.run.member(blade.particle), self.run.along(blade.direction)
            if member is None or direction is None:
                continue
            e = _unit(direction) * 0.08 * self.scale
            out.append(Shape("blade", blade.constraint, np.stack([member - e, member + e], axis=1)))
        return out

    # --- bodies ---------------------------------------------------------------------------------------------

    def bodies(self) -> tuple[list[Shape], list[tuple[str, np.ndarray, np.ndarray]]]:
        """Each body's outline and the spokes or axle that show it turning; the floor a body in space rolls on."""
        out: list[Shape] = []
        floors: list[tuple[str, np.ndarray, np.ndarray]] = []
        for body in self.geometry.bodies:
            centre = self.run.member(body.name)
            if centre is None:
                continue
            if body.rotation:
                floors += self._spatial(body, centre, out)
            elif centre.shape[1] == 2:
                self._planar(body, centre, out)
        return out, floors

    def _angle(self, body: Any) -> np.ndarray:
        if body.angle is not None:
            values = self.run.along((body.angle,))
            if values is not None:
                return values[:, 0]
        rate = self.run.along((body.rate,)) if body.rate is not None else None
        return _integrated(rate[:, 0], self.run.t) if rate is not None else np.zeros(len(self.run.t))

    def _planar(self, body: Any, centre: np.ndarray, out: list[Shape]) -> None:
        angle = self._angle(body)
        turn = np.stack([np.cos(angle + np.pi / 2), np.sin(angle + np.pi / 2)], axis=1)
        across = _perpendicular(turn)
        if body.shape == "disc" and body.radius is not None:
            radius = self.run.along((body.radius,))
            if radius is None:
                return
            r = float(radius[0, 0])
            out.append(Shape("body", body.name, circle(centre, r, turn, across), closed=True))
            spokes = [np.stack([centre - r * v, centre + r * v], axis=1) for v in (turn, across)]
            out.append(Shape("spoke", body.name, _break(*spokes)))
            return
        if body.shape == "bar" and body.pivot is not None:
            pivot = self.run.anchor(body.pivot)
            if pivot is None:
                return
            e = centre - pivot
            length = np.linalg.norm(e, axis=1, keepdims=True)
            u = _unit(e)
            half = np.minimum(0.09 * length, 0.05 * self.scale)
            w = _perpendicular(u) * half
            a, b = pivot - 0.12 * length * u, centre + 0.45 * length * u
            out.append(Shape("body", body.name, np.stack([a - w, b - w, b + w, a + w], axis=1), closed=True))
            return
        side = 0.07 * self.scale
        corners = [centre + side * (sx * turn + sy * across) for sx, sy in ((1, 1), (1, -1), (-1, -1), (-1, 1))]
        out.append(Shape("body", body.name, np.stack(corners, axis=1), closed=True))
        out.append(Shape("spoke", body.name, np.stack([centre, centre + side * turn], axis=1)))

    def _spatial(self, body: Any, centre: np.ndarray, out: list[Shape]) -> list[tuple[str, np.ndarray, np.ndarray]]:
        flat = self.run.along(tuple(e for row in body.rotation for e in row))
        if flat is None or centre.shape[1] != 3:
            return []
        R = flat.reshape(-1, 3, 3)
        k = body.axis
        axis, first, second = R[:, :, k], R[:, :, (k + 1) % 3], R[:, :, (k + 2) % 3]
        radius = self.run.along((body.radius,)) if body.radius is not None else None
        r = float(radius[0, 0]) if radius is not None else 0.15 * self.scale
        spin = self.run.along((body.spin,)) if body.spin is not None else None
        sigma = _integrated(spin[:, 0], self.run.t)[:, None] if spin is not None else np.zeros((len(self.run.t), 1))
        spoke = np.cos(sigma) * first + np.sin(sigma) * second
        other = -np.sin(sigma) * first + np.cos(sigma) * second
        out.append(Shape("body", body.name, circle(centre, r, first, second), closed=True))
        pieces = [np.stack([centre - r * spoke, centre + r * spoke], axis=1),
                  np.stack([centre - r * other, centre + r * other], axis=1)]
        if body.shape == "top" and body.pivot is not None:
            pivot = self.run.anchor(body.pivot)
            if pivot is not None:
                pieces += [np.stack([pivot, centre + r * v], axis=1) for v in (spoke, other, -spoke, -other)]
        else:
            pieces.append(np.stack([centre - 0.6 * r * axis, centre + 0.6 * r * axis], axis=1))
        out.append(Shape("spoke", body.name, _break(*pieces)))
        down = self.down(3)
        if not body.rolls or down is None:
            return []
        d = _unit(down[None, :] - (axis @ down)[:, None] * axis)
        contact = centre + r * d
        return [(f"floor ({body.name} rolls)", contact, np.broadcast_to(-down, contact.shape).copy())]

    # --- forces ---------------------------------------------------------------------------------------------

    def forces(self) -> list[Force]:
        """Each arrow's point and force vector at every sample (the run's multipliers and friction forces)."""
        run = self.run
        trajectory = run.trajectory
        out: list[Force] = []
        for arrow in self.geometry.arrows:
            point, direction = run.along(arrow.point), run.along(arrow.direction)
            if point is None or direction is None:
                continue
            if arrow.kind == "constraint":
                if arrow.label not in trajectory.constraints:
                    continue
                value = trajectory.multipliers[:, trajectory.constraints.index(arrow.label)]
                vector = arrow.sign * value[:, None] * direction
            else:
                if arrow.label not in trajectory.contacts or trajectory.friction.shape[1] != len(trajectory.contacts):
                    continue
                value = trajectory.friction[:, trajectory.contacts.index(arrow.label)]
                along = -_unit(direction) if arrow.planar else direction
                vector = arrow.sign * value[:, None] * along
            if np.all(np.isfinite(vector)):
                out.append(Force(arrow.label, arrow.kind, arrow.member, point, vector))
        return out


def evaluate(geometry: Geometry, problem: Any, parameters: np.ndarray, trajectory: Any) -> Scene:
    """Evaluate ``geometry`` along ``trajectory`` (a :class:`~lagsolve.numeric.integrate.Trajectory`) with
    ``parameters`` in the problem's order. Shapes that do not evaluate to finite numbers are left out."""
    run = Run(problem, parameters, trajectory, geometry.markers)
    rods: list[tuple[str, np.ndarray, np.ndarray]] = []
    pivots: list[np.ndarray] = []
    joints: list[np.ndarray] = []

    def add_pivot(values: np.ndarray) -> None:
        if not any(v.shape == values.shape and np.allclose(values, v) for v in pivots):
            pivots.append(values)

    for rod in geometry.rods:
        start, stop = run.anchor(rod.start), run.anchor(rod.end)
        if start is None or stop is None or start.shape != stop.shape:
            continue
        rods.append((rod.constraint or "", start, stop))
        for anchor, end in ((rod.start, start), (rod.end, stop)):
            if anchor.particle is None and _on_member(anchor, problem):
                joints.append(end)
            elif anchor.particle is None:
                add_pivot(end)
    for body in geometry.bodies:
        if body.pivot is not None and body.pivot.particle is None:
            pin = run.anchor(body.pivot)
            if pin is not None:
                add_pivot(pin)
    scale = run.scale(pivots)
    build = Builder(run, geometry, scale)
    curves, shapes = build.curves(add_pivot)
    shapes += build.revolutions()
    surfaces, ground = build.surfaces()
    shapes += ground
    shapes += build.strings()
    shapes = build.holes_in_grounds(build.grounds_at_pulleys(shapes))
    for values in build.pivots:
        add_pivot(values)
    springs, fixed = build.springs()
    shapes += springs
    for values in fixed:
        add_pivot(values)
    shapes += build.blades()
    bodies, floors = build.bodies()
    shapes += bodies
    surfaces += floors
    forces = build.forces()
    markers = tuple((name, run.members[name]) for name, _ in geometry.markers if name in run.members)
    markers += tuple((b.name, run.members[b.name]) for b in geometry.bodies if b.name in run.members)
    return Scene(tuple(rods), tuple(pivots), tuple(surfaces), tuple(curves), tuple(shapes), tuple(forces), markers,
                 build.gravity, scale, tuple(joints), tuple(build.ends))


def _cut_band(band: np.ndarray, hole: np.ndarray, half: float) -> list[np.ndarray]:
    """A band of material (corners a, b on the surface, then b and a moved into the material) in two, with a gap
    of half-width ``half`` about ``hole`` where the hole lies on the surface between a and b; else the band."""
    if band.shape[1] != hole.shape[0]:
        return [band]
    a, b, into = band[0], band[1], band[3] - band[0]
    along = b - a
    length, depth = float(np.linalg.norm(along)), float(np.linalg.norm(into))
    if length <= 2 * half or depth <= 0:
        return [band]
    e, n = along / length, into / depth
    t = float((hole - a) @ e)
    if abs(float((hole - a) @ n)) > 1e-6 * length or not half < t < length - half:
        return [band]
    left, right = a + (t - half) * e, a + (t + half) * e
    return [np.stack([a, left, left + into, a + into]), np.stack([right, b, b + into, right + into])]


def _on_member(anchor: Anchor, problem: Any) -> bool:
    """A rod's end at a point that moves with the coordinates (a joint on a member), not a fixed or driven pivot."""
    coordinates = {c.symbol for c in problem.coordinates}
    return any(getattr(p, "free_symbols", set()) & coordinates for p in anchor.point)  # a plain 0 has none
