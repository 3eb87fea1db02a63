"""The sketch of a system and its animation: only draws what a :class:`~lagsolve.numeric.scene.Scene` holds.

``mechanics/geometry/shapes.py`` decides what the parts are, ``numeric/scene.py`` evaluates them along the run; this
module puts them in one or two views (a problem in the plane: x–y; in space: the top view x–y and the side view,
x–z or y–z, whichever shows more of the motion, or only the top view when nothing moves along z), styles them
by kind, draws the particles as labelled dots and each force as an arrow from its point, all arrows of a figure
to one scale (given in the legend), and moves everything to any sample (:meth:`Drawing.show`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from lagsolve.numeric.integrate import Trajectory
from lagsolve.numeric.scene import Scene, Shape
from lagsolve.render.canvas import WIDTH, Units, axis_units, figure, fit

#: surfaces in muted colours, told apart in the legend
SURFACE_COLOURS = ("0.35", "#9c7a4a", "#5b8a9a", "#8a6a9a")
#: the arrows of the forces of constraint, then of friction, by label
FORCE_COLOURS = ("#c0392b", "#8e44ad", "#1f7a5a", "#2c3e50", "#b03a7a", "#5d6d7e")
FRICTION_COLOURS = ("#e67e22", "#a0522d", "#d4ac0d")
#: the longest arrow of a figure, as a fraction of the view's width
ARROW = 0.22
#: a spring's or damper's term longer than this (printed as text) is left out of its legend entry
TERM_LENGTH = 26

#: how each kind of shape is drawn: (line style, fill or None, z-order, legend label or None)
STYLES: dict[str, dict[str, Any]] = {
    "wire": {"color": "0.55", "linewidth": 2.4, "alpha": 0.85, "zorder": 1},
    "ground": {"facecolor": "none", "edgecolor": "0.45", "hatch": "////", "linewidth": 0.0, "zorder": 0},
    "support": {"facecolor": "none", "edgecolor": "0.35", "hatch": "////", "linewidth": 1.0, "zorder": 0},
    "solid": {"facecolor": "#d9cbb0", "edgecolor": "#7a6545", "linewidth": 1.2, "zorder": 0.5},
    "wall": {"facecolor": "none", "edgecolor": "0.35", "hatch": "////", "linewidth": 1.0, "zorder": 0.5},
    "string": {"color": "0.1", "linewidth": 1.1, "zorder": 2},
    "pulley": {"facecolor": "0.92", "edgecolor": "0.2", "linewidth": 1.2, "zorder": 2.5},
    "spring": {"color": "#34495e", "linewidth": 1.2, "zorder": 2},
    "damper": {"color": "#6c3483", "linewidth": 1.2, "zorder": 2},
    "blade": {"color": "#1a1a1a", "linewidth": 4.5, "solid_capstyle": "butt", "zorder": 3.5},
    "body": {"facecolor": "#aed6f1", "edgecolor": "#1b4f72", "linewidth": 1.4, "alpha": 0.9, "zorder": 3},
    "spoke": {"color": "#1b4f72", "linewidth": 1.0, "zorder": 3.2},
    "profile": {"color": "0.4", "linewidth": 2.0, "zorder": 1},
    "ring": {"color": "0.55", "linewidth": 1.0, "linestyle": "--", "zorder": 1},
}
FILLED = ("ground", "support", "solid", "wall", "pulley", "body")
#: shapes whose points set the view's limits (grounds and walls follow the members already)
BOUNDED = ("wire", "solid", "string", "pulley", "spring", "damper", "blade", "body", "spoke", "profile", "ring",
           "centre", "hole")


def with_unit(label: str, unit: str | None) -> str:
    return f"{label} [{unit}]" if unit else label


def _plane(trajectory: Trajectory) -> list[np.ndarray]:
    out, offset = [], 0
    for _, d in trajectory.particles:
        out.append(trajectory.positions[:, offset:offset + d])
        offset += d
    return out


def _cut(values: np.ndarray, i: int, j: int) -> np.ndarray:
    """Components i and j of an array (..., d) (0 for one it does not have)."""
    zero = np.zeros(values.shape[:-1])
    return np.stack([values[..., i] if i < values.shape[-1] else zero,
                     values[..., j] if j < values.shape[-1] else zero], axis=-1)


def views(trajectory: Trajectory, scene: Scene | None) -> list[tuple[int, int]]:
    """The planes to draw: x–y in the plane; in space the top view and the side view that shows more of the
    motion (x–z or y–z), or the top view alone where nothing moves along z and no body or surface stands in it."""
    markers = scene.markers if scene else ()
    if max([d for _, d in trajectory.particles] + [v.shape[1] for _, v in markers], default=2) < 3:
        return [(0, 1)]
    points = [p for p in _plane(trajectory) if p.shape[1] == 3] + [v for _, v in markers if v.shape[1] == 3]
    spread = np.ptp(np.vstack(points) if points else np.zeros((1, 3)), axis=0)
    bodies = [s.at(0) for s in (scene.shapes if scene else ()) if s.kind == "body" and s.points.shape[-1] == 3]
    standing = bool(bodies) or (scene is not None and any(s.kind == "profile" for s in scene.shapes))
    if spread[2] <= 1e-9 * max(float(spread.max()), 1e-300) and not standing:
        return [(0, 1)]
    return [(0, 1), _side_view(points, spread, bodies, standing)]


def _side_view(points: list[np.ndarray], spread: np.ndarray, bodies: list[np.ndarray],
               standing: bool) -> tuple[int, int]:
    """x–z or y–z: the side that shows the bodies broadest (a coin face-on), else the members' motion (their
    ``spread`` along each axis) broadest; round a surface of revolution (``standing``, without bodies) that
    spreads about as far one way as the other, the side whose plane holds the first member at the start, so it
    is drawn on the surface's profile, not inside it."""
    if bodies:
        spread = np.ptp(np.vstack(bodies), axis=0)
    elif standing and points and max(spread[0], spread[1]) < 1.5 * min(spread[0], spread[1]):
        start = np.abs(points[0][0])
        return (0, 2) if start[1] <= start[0] else (1, 2)
    return (0, 2) if spread[0] >= spread[1] else (1, 2)


def force_scale(scene: Scene | None, span: float) -> float:
    """Data length per unit of force: the largest force of the run drawn ARROW × ``span`` long."""
    if scene is None or not scene.forces:
        return 0.0
    largest = max(float(np.max(np.linalg.norm(f.vector, axis=1))) for f in scene.forces)
    return ARROW * span / largest if largest > 0 else 0.0


class Drawing:
    """The system in the plane of components (i, j) at one sample: particles (labelled dots), rods, pivots,
    surfaces, wires and every shape of the scene, and the forces as arrows; :meth:`show` moves everything to
    another sample. ``per_force`` is the arrows' scale (data length per unit of force) shared by a figure."""

    def __init__(self, ax: Any, trajectory: Trajectory, scene: Scene | None, i: int = 0, j: int = 1,
                 units: Units = None, trails: bool = False, per_force: float | None = None,
                 legend: bool = True, sample: int | None = None) -> None:
        self.ax, self.trajectory, self.scene = ax, trajectory, scene or Scene()
        self.i, self.j = i, j
        self.units = units or {}
        scene = self.scene
        self.plane = [_cut(p, i, j) for p in _plane(trajectory)]
        self.markers = [(name, _cut(v, i, j)) for name, v in scene.markers]
        self.shapes = [s for s in scene.shapes if set(s.views) <= {i, j}]
        self.forces = [(f, _cut(f.point, i, j), _cut(f.vector, i, j)) for f in scene.forces]
        self.per_force = 0.0
        self.sample = sample
        self._limits(sample)
        self._axes()
        self._wires()
        self.artists = self._shape_artists()
        self.surfaces = self._surface_lines()
        self._linkage()
        self._members(trails)
        self.per_force = force_scale(scene, self.span) if per_force is None else per_force
        self._limits(sample)  # again, with room for the arrows' heads
        self.arrows = self._arrows()
        self._gravity()
        if legend and ax.get_legend_handles_labels()[0]:
            self.legend = ax.legend(**self.legend_options())
        # the time stamp above the view's top left corner, clear of what is drawn
        self.stamp = ax.text(0.0, 1.015, "", transform=ax.transAxes, ha="left", va="bottom", fontsize="medium",
                             zorder=6)

    # --- the parts, drawn once (placed by :meth:`show`) ---------------------------------------------------

    def _axes(self) -> None:
        """Equal scales on both axes, a light grid, and the axes named by their components (with the unit)."""
        ax = self.ax
        ax.set_aspect("equal", adjustable="box")
        ax.grid(alpha=0.2)
        length = self.units.get("length")
        ax.set_xlabel(with_unit("xyz"[self.i], length))
        ax.set_ylabel(with_unit("xyz"[self.j], length))

    def _wires(self) -> None:
        """The scene's fixed curves (wires) that lie in this view, drawn once: they do not move."""
        for label, points in self.scene.curves:
            if self._in_view(points):
                pts = _cut(points, self.i, self.j)
                self.ax.plot(pts[:, 0], pts[:, 1], **STYLES["wire"], label=label or "wire")

    def _shape_artists(self) -> list[tuple[Shape, Any]]:
        """An artist for each shape of this view, styled by its kind; the legend names each kind and label once."""
        artists: list[tuple[Shape, Any]] = []
        labelled: set[tuple[str, str]] = set()
        for shape in self.shapes:
            name = None if (shape.kind, shape.label) in labelled else self._legend_label(shape)
            labelled.add((shape.kind, shape.label))
            artists.append((shape, self._shape_artist(shape, name)))
        return artists

    def _shape_artist(self, shape: Shape, name: str | None) -> Any:
        """The (empty) artist of one shape: a marker for a centre (a star) or a hole (a ring), a polygon for a
        filled kind, else a line; ``name`` is its legend entry (None: none)."""
        from matplotlib.patches import Polygon

        if shape.kind in ("centre", "hole"):
            marker = "*" if shape.kind == "centre" else "o"
            artist, = self.ax.plot([], [], marker, markersize=14 if shape.kind == "centre" else 7,
                                   color="#d4ac0d" if shape.kind == "centre" else "white",
                                   markeredgecolor="0.1", zorder=4, label=name)
            return artist
        style = dict(STYLES.get(shape.kind, {"color": "0.3"}))
        if shape.kind in FILLED:
            artist = Polygon(np.zeros((3, 2)), closed=True, label=name, **style)
            self.ax.add_patch(artist)
            return artist
        artist, = self.ax.plot([], [], label=name, **style)
        return artist

    def _surface_lines(self) -> list[tuple[str, np.ndarray, np.ndarray, Any]]:
        """(label, point, normal, line) of each surface seen edge-on in this view, each in its own colour."""
        surfaces = []
        for k, (label, point, normal) in enumerate(self.scene.surfaces):
            if not self._edge_on(normal):
                continue
            line, = self.ax.plot([], [], "-", color=SURFACE_COLOURS[k % len(SURFACE_COLOURS)], linewidth=2.2,
                                 zorder=1.2, label=label)
            surfaces.append((label, point, normal, line))
        return surfaces

    def _line_ends(self, label: str, p: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """The two ends of a surface line through ``p`` along ``direction`` in this view: across the view, or
        from its stop (the scene's ``ends``) back across the view."""
        for name, stop, towards in self.scene.ends:
            if name == label:
                s, u = _cut(stop, self.i, self.j), _cut(towards, self.i, self.j)
                back = -self.reach * u / max(float(np.hypot(u[0], u[1])), 1e-300)
                return np.array([s + back, s])
        return np.array([p - self.reach * direction, p + self.reach * direction])

    def _linkage(self) -> None:
        """The rods (their ends in this view and a line each), the pivots (triangles) and the joints (rings)."""
        ax, i, j, scene = self.ax, self.i, self.j, self.scene
        self.rod_ends = [(_cut(a, i, j), _cut(b, i, j)) for _, a, b in scene.rods]
        self.rods = [ax.plot([], [], "-", color="0.15", linewidth=2.0, solid_capstyle="round", zorder=2)[0]
                     for _ in self.rod_ends]
        self.pivot_points = [_cut(p, i, j) for p in scene.pivots]
        self.pivots = [ax.plot([], [], "^", color="0.15", markersize=10, zorder=3.6)[0] for _ in self.pivot_points]
        self.joint_points = [_cut(p, i, j) for p in scene.joints]
        self.joints = [ax.plot([], [], "o", markerfacecolor="white", markeredgecolor="0.15", markersize=6,
                               zorder=3.6)[0] for _ in self.joint_points]

    def _members(self, trails: bool) -> None:
        """Each particle and marker as a labelled dot (a body's centre a small one inside its outline), and,
        with ``trails``, the path it has traced, in the dot's colour."""
        ax = self.ax
        members = self.plane + [v for _, v in self.markers]
        self.trails = [ax.plot([], [], "-", linewidth=0.9, alpha=0.55, zorder=2)[0] for _ in members] if trails else []
        self.dots, self.labels = [], []
        names = [n for n, _ in self.trajectory.particles] + [n for n, _ in self.markers]
        bodies = {s.label for s in self.shapes if s.kind == "body"}
        for k, name in enumerate(names):
            small = name in bodies  # a body's centre: a small dot inside its outline
            dot, = ax.plot([], [], "o", markersize=4 if small else 10, color=f"C{k % 10}",
                           markeredgecolor="white", zorder=4.5)
            self.dots.append(dot)
            self.labels.append(ax.annotate(name, (0, 0), xytext=(7, 7), textcoords="offset points",
                                           fontsize="small", zorder=5, annotation_clip=False))
        for dot, trail in zip(self.dots, self.trails, strict=False):
            trail.set_color(dot.get_color())

    # --- layout ------------------------------------------------------------------------------------------

    def _points(self, sample: int | None, arrows: bool = True) -> np.ndarray:
        """Every member, pivot, rod end and bounded shape in this view, at ``sample`` (None: the whole run), and
        the arrows' heads unless ``arrows`` is False."""
        rows = slice(None) if sample is None else slice(sample, sample + 1)
        groups = [p[rows].reshape(-1, 2) for p in self.plane] + [v[rows].reshape(-1, 2) for _, v in self.markers]
        groups += [_cut(p[rows], self.i, self.j).reshape(-1, 2) for p in self.scene.pivots]
        for _, a, b in self.scene.rods:
            groups += [_cut(a[rows], self.i, self.j), _cut(b[rows], self.i, self.j)]
        for _, curve in self.scene.curves:  # a closed wire (a ring, a hoop) is shown whole
            if len(curve) > 2 and np.allclose(curve[0], curve[-1]) and self._in_view(curve):
                groups.append(_cut(curve, self.i, self.j))
        for shape in self.shapes:
            if shape.kind in BOUNDED:
                points = shape.points if shape.points.ndim == 2 or sample is None else shape.points[sample]
                groups.append(_cut(points, self.i, self.j).reshape(-1, 2))
        if self.per_force > 0 and arrows:  # the arrows' heads
            for _, point, vector in self.forces:
                groups.append((point[rows] + self.per_force * vector[rows]).reshape(-1, 2))
        points = np.vstack(groups) if groups else np.zeros((1, 2))
        points = points[np.all(np.isfinite(points), axis=1)]
        return points if len(points) else np.zeros((1, 2))

    def _in_view(self, points: np.ndarray) -> bool:
        return points.shape[1] > max(self.i, self.j) or (points.shape[1] == 2 and (self.i, self.j) == (0, 1))

    def _limits(self, sample: int | None) -> None:
        """Square limits around every member, pivot and bounded shape, with room for labels and arrows: over the
        whole run (the animation's axes stay put), or for a sketch at one sample, around that sample where the
        run goes far beyond it (a cart that rolls away; not a lone bead, whose system at one sample is a point)."""
        points = self._points(None)
        if sample is not None:
            here = self._points(sample)
            size = float(np.ptp(self._points(sample, arrows=False), axis=0).max())
            if size > 1e-9 * (1 + float(np.abs(here).max())) and np.ptp(points, axis=0).max() > 4 * size:
                points = here
        low, high = points.min(axis=0), points.max(axis=0)
        centre = (low + high) / 2
        half = max(float(np.max(high - low)) / 2, 1e-9)
        half = half * 1.18 + (0.5 if half < 1e-6 else 0.0)
        self.ax.set_xlim(centre[0] - half, centre[0] + half)
        self.ax.set_ylim(centre[1] - half, centre[1] + half)
        self.span = 2 * half
        self.reach = 4 * half

    def _edge_on(self, normal: np.ndarray) -> bool:
        """A surface shows as a line in this view: its normal lies in the view's plane."""
        if normal.shape[1] <= 2:
            return (self.i, self.j) == (0, 1)
        depth = ({0, 1, 2} - {self.i, self.j}).pop()
        n = normal[0]
        return bool(abs(n[depth]) <= 1e-9 * max(float(np.linalg.norm(n)), 1e-300))

    def _legend_label(self, shape: Shape) -> str | None:
        if shape.kind in ("body", "wall", "spoke", "ground"):
            return None
        if shape.kind in ("blade", "pulley", "hole"):
            return f"{shape.kind}: {shape.label}"
        if shape.expression is not None:
            return self._term_label(shape.kind, shape.expression)
        return shape.label or None

    def _term_label(self, kind: str, term: Any) -> str:
        """A spring's, damper's or centre's entry: its kind and the term it stands for as mathematics
        (``spring (k (x₂ − x₁ − L₀)²/2)`` in mathtext), or the kind alone where the term is long or mathtext cannot
        set it."""
        from matplotlib.font_manager import FontProperties
        from matplotlib.mathtext import MathTextParser

        from lagsolve.render.notation import Notation

        name = "centre of force" if kind == "centre" else kind
        note = Notation(self.trajectory.coordinates)
        if len(note.text(term)) > TERM_LENGTH:
            return name
        tex = f"${note.inline(term)}$"
        try:
            MathTextParser("path").parse(tex, 72, FontProperties())
        except ValueError:
            return name
        return f"{name} ({tex})"

    def legend_options(self) -> dict[str, Any]:
        title = None
        if self.forces and self.per_force > 0:
            largest = max(float(np.max(np.linalg.norm(f.vector, axis=1))) for f in self.scene.forces)
            unit = self.units.get("force")
            title = f"arrows: longest {largest:.3g}" + (f" {unit}" if unit else "")
        return {"loc": "lower right", "fontsize": "small", "framealpha": 0.85, "title": title,
                "title_fontsize": "small"}

    def _arrows(self) -> list[Any]:
        from matplotlib.patches import FancyArrowPatch

        out = []
        colours: dict[tuple[str, str], str] = {}
        first: dict[tuple[str, str], list[np.ndarray]] = {}
        for force, _, _ in self.forces:
            key = (force.kind, force.label)
            if key not in colours:
                palette = FORCE_COLOURS if force.kind == "constraint" else FRICTION_COLOURS
                colours[key] = palette[sum(1 for k in colours if k[0] == force.kind) % len(palette)]
            # the opposite force on the second member where the two touch (the wedge under the block): dashed,
            # with its own entry, so the pair does not read as one double-headed arrow
            reaction = any(np.allclose(p, force.point) for p in first.get(key, []))
            first.setdefault(key, []).append(force.point)
            label = self._force_label(force) + (f" on {force.member}" if reaction else "")
            style = "--" if reaction else "-"
            if not any(label == known for known in self.ax.get_legend_handles_labels()[1]):
                # the legend's entry: an arrow-headed line (the arrow itself may be hidden at the sample shown)
                self.ax.plot([], [], color=colours[key], linewidth=1.6, marker=">", markersize=6, linestyle=style,
                             label=label)
            arrow = FancyArrowPatch((0, 0), (0, 0), arrowstyle="-|>", mutation_scale=11, linewidth=1.6,
                                    color=colours[key], zorder=5.5, shrinkA=0, shrinkB=0, linestyle=style,
                                    alpha=0.75 if reaction else 1.0)
            self.ax.add_patch(arrow)
            out.append(arrow)
        return out

    @staticmethod
    def _force_label(force: Any) -> str:
        return f"force of {force.label}" if force.kind == "constraint" else f"friction {force.label}"

    def _gravity(self) -> None:
        g = self.scene.gravity
        if g.size < 2:
            return
        v = _cut(g, self.i, self.j)
        size = float(np.linalg.norm(v))
        if size < 1e-6:
            return
        v = v / size * 0.09
        base = np.array([0.93, 0.90]) - np.maximum(v, 0)
        self.ax.annotate("", xy=tuple(base + v), xytext=tuple(base), xycoords="axes fraction",
                         arrowprops={"arrowstyle": "-|>", "color": "0.3", "linewidth": 1.3}, zorder=6)
        self.ax.text(*(base + v / 2 + np.array([0.025, 0.0])), "g", transform=self.ax.transAxes, color="0.3",
                     fontsize="small", ha="left", va="center")

    # --- one sample -----------------------------------------------------------------------------------------

    def show(self, sample: int) -> list[Any]:
        """Every moving part at ``sample``; the artists that changed (the time stamp last)."""
        for (a, b), rod in zip(self.rod_ends, self.rods, strict=True):
            rod.set_data([a[sample, 0], b[sample, 0]], [a[sample, 1], b[sample, 1]])
        for label, point, normal, line in self.surfaces:
            p, n = _cut(point[sample], self.i, self.j), _cut(normal[sample], self.i, self.j)
            size = float(np.hypot(n[0], n[1]))
            if size < 1e-300:
                continue
            direction = np.array([-n[1], n[0]]) / size
            ends = self._line_ends(label, p, direction)
            line.set_data(ends[:, 0], ends[:, 1])
        for shape, artist in self.artists:
            pts = _cut(shape.at(sample), self.i, self.j)
            if hasattr(artist, "set_xy"):
                artist.set_xy(pts if np.all(np.isfinite(pts)) else np.zeros((3, 2)))
            else:
                artist.set_data(pts[:, 0], pts[:, 1])
        for values, marker in zip(self.pivot_points + self.joint_points, self.pivots + self.joints, strict=True):
            marker.set_data([values[sample, 0]], [values[sample, 1]])
        members = self.plane + [v for _, v in self.markers]
        placed: list[np.ndarray] = []
        for xy, dot, label in zip(members, self.dots, self.labels, strict=True):
            here = xy[sample]
            dot.set_data([here[0]], [here[1]])
            label.xy = (here[0], here[1])
            # members at one place (a wedge's corner under a cylinder's centre): their names one under another
            close = sum(1 for p in placed if float(np.linalg.norm(p - here)) < 0.04 * self.span)
            label.xyann = (7, 7 - 11 * close)
            placed.append(here)
        for xy, trail in zip(members, self.trails, strict=False):
            trail.set_data(xy[: sample + 1, 0], xy[: sample + 1, 1])
        for (_, point, vector), arrow in zip(self.forces, self.arrows, strict=True):
            tail = point[sample]
            head = tail + self.per_force * vector[sample]
            visible = float(np.linalg.norm(head - tail)) > 1e-3 * self.span
            arrow.set_visible(visible)
            arrow.set_positions(tuple(tail), tuple(head))
        unit = self.units.get("t")
        self.stamp.set_text(f"t = {self.trajectory.t[sample]:.2f}" + (f" {unit}" if unit else ""))
        return [*self.rods, *(line for *_, line in self.surfaces), *(a for _, a in self.artists), *self.pivots,
                *self.joints, *self.trails, *self.dots, *self.labels, *self.arrows, self.stamp]


def _figure_size(panels: int) -> tuple[float, float]:
    """One view (with the legend beside it) or two (with the legend under them), two figures to a printed page."""
    return (WIDTH, 4.1) if panels == 1 else (WIDTH, 3.7)


def sketch_figure(trajectory: Trajectory, scene: Scene | None, title: str, units: Units = None,
                  sample: int = 0) -> Any:
    """The system at one sample (the start by default), in its views (:func:`views`), with one legend."""
    planes = views(trajectory, scene)
    if len(planes) == 1:  # the view, and beside it a column (an axes turned off) for the legend
        fig, axes = figure(f"{title}: sketch", 1, 2, figsize=_figure_size(1), width_ratios=[2.6, 1])
    else:
        fig, axes = figure(f"{title}: sketch", 1, 2, figsize=_figure_size(2))
    drawings = _drawings(axes[0], trajectory, scene, planes, units, sample=sample)
    for drawing in drawings:
        drawing.show(sample)
    for drawing in drawings[1:]:  # one time stamp
        drawing.stamp.set_visible(False)
    _legend(fig, drawings, axes[0][1] if len(planes) == 1 else None)
    return fig


def _drawings(axes: Any, trajectory: Trajectory, scene: Scene | None, planes: list[tuple[int, int]],
              units: Units, trails: bool = False, sample: int | None = None) -> list[Drawing]:
    """One drawing per view, the arrows to one scale (the widest view's), the legend gathered apart."""
    drawings = [Drawing(ax, trajectory, scene, i, j, units, trails=trails, legend=False, sample=sample)
                for ax, (i, j) in zip(axes, planes, strict=False)]
    per_force = min((d.per_force for d in drawings if d.per_force > 0), default=0.0)
    for d in drawings:
        if d.per_force != per_force:
            d.per_force = per_force
            d._limits(d.sample)
    return drawings


def _legend(fig: Any, drawings: list[Drawing], beside: Any = None) -> None:
    """One legend for the figure: in the axes ``beside`` a single view (turned off: no panel of its own), else
    under the views."""
    handles: dict[str, Any] = {}
    for d in drawings:
        for handle, label in zip(*d.ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, handle)
    if beside is not None:
        beside.set_axis_off()
    if not handles:
        return
    options = drawings[0].legend_options()
    if beside is not None:
        options.update(loc="center left")
        beside.legend(list(handles.values()), list(handles), **options)
    else:
        options.update(loc="outside lower center", ncols=min(3, len(handles)))
        fig.legend(list(handles.values()), list(handles), **options)


def animation_gif(trajectory: Trajectory, title: str, frames: int = 120, scene: Scene | None = None,
                  units: Units = None) -> bytes:
    """An animated GIF of the motion (Pillow): the sketch in every view that moves, with the paths traced so far,
    the forces and a time stamp; the first frame is the sketch at t = 0. The layout is worked out on the first
    frame and then kept (the axes do not move), and each frame is drawn once."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    from lagsolve.render.picture import Picture
    units = axis_units(units)
    planes = views(trajectory, scene)
    size = (6.6, 4.8) if len(planes) == 1 else (8.6, 4.9)
    fig = Picture(figsize=size, layout="constrained")
    canvas = FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2, squeeze=False, width_ratios=[2.6, 1] if len(planes) == 1 else None)[0]
    fig.suptitle(fit(title, size[0] - 0.3), parse_math=False)
    drawings = _drawings(axes, trajectory, scene, planes, units, trails=True)
    _legend(fig, drawings, axes[1] if len(planes) == 1 else None)
    for d in drawings[1:]:
        d.stamp.set_visible(False)
    index = np.linspace(0, len(trajectory.t) - 1, max(frames, 1)).astype(int)
    images = []
    for k, i in enumerate(index):
        for d in drawings:
            d.show(int(i))
        canvas.draw()
        if k == 0:
            canvas.draw()  # the layout settles in a second pass (the legend under the views clears the labels)
            fig.set_layout_engine("none")  # laid out once: the same axes on every frame, at a fraction of the cost
        width, height = canvas.get_width_height()
        images.append(Image.frombuffer("RGBA", (width, height), bytes(canvas.buffer_rgba()), "raw", "RGBA", 0, 1))
    out = io.BytesIO()
    images[0].save(out, format="GIF", save_all=True, append_images=images[1:], duration=int(1000 / 24), loop=0)
    return out.getvalue()
