"""Figures of a simulated motion (matplotlib figures on their own Agg canvas, :mod:`lagsolve.render.picture`;
nothing is shown from here, and no backend is chosen, so a notebook shows them inline).

Every function takes plain data — a :class:`~lagsolve.numeric.integrate.Trajectory`,
the :class:`~lagsolve.numeric.scene.Scene` of its rods, surfaces and wires, plus
labels — and returns a :class:`matplotlib.figure.Figure`. :func:`figures` returns them
all under stable names (``sketch``, ``path``, ``coordinates``, ``phase``, ``forces``,
``conservation``), which the command line turns into ``<problem>_<name>.png``.

``units`` (optional everywhere) maps a coordinate name, ``"t"`` (time), ``"length"``
(the axes of physical space), ``"force"`` and ``"energy"`` to a unit string; an axis
whose unit is known is labelled ``x [m]``, one whose unit is not known as before.

No figure has an empty panel: a coordinate that stays constant or moves uniformly, an
exactly zero constraint residual, a conserved quantity that is not there, are said in
a line of text under the figure instead of drawn.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from lagsolve.numeric.integrate import EventKind, Trajectory
from lagsolve.numeric.scene import Scene

Units = Mapping[str, str] | None

#: surfaces in muted colours, told apart in the legend
SURFACE_COLOURS = ("0.45", "#9c7a4a", "#5b8a9a", "#8a6a9a")

#: relative size below which a coordinate counts as constant, or its rate as uniform
FLAT = 1e-9


def _fit(text: str, width_inches: float, fontsize: float = 12.0) -> str:
    """``text`` wrapped to lines that fit ``width_inches`` at ``fontsize`` points (about 0.55 em a character)."""
    chars = max(16, int(width_inches * 72 / (0.55 * fontsize)))
    return "\n".join(textwrap.wrap(text, chars)) or text


def _figure(title: str, rows: int = 1, cols: int = 1, **kwargs: Any) -> tuple[Any, Any]:
    from lagsolve.render.picture import Picture

    size = kwargs.pop("figsize", (7.5, 2.2 + 2.4 * rows))
    fig = Picture(figsize=size, layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False, **kwargs)
    fig.suptitle(_fit(title, size[0] - 0.3), parse_math=False)  # user text: a "$" in a name is not mathtext
    return fig, axes


def _note(fig: Any, lines: list[str]) -> None:
    """What the figure leaves out, and why, in small text under it."""
    if lines:
        width = fig.get_figwidth() - 0.3
        fig.supxlabel("\n".join(_fit(line, width, 8.5) for line in lines), fontsize="small", color="0.3",
                      parse_math=False)


def _with_unit(label: str, unit: str | None) -> str:
    return f"{label} [{unit}]" if unit else label


def _time_label(units: Units) -> str:
    return _with_unit("$t$", (units or {}).get("t"))


def _events(ax: Any, trajectory: Trajectory) -> None:
    """Release events as dotted lines; sticking phases of friction contacts shaded."""
    for event in trajectory.events:
        if event.kind == EventKind.RELEASE:
            ax.axvline(event.time, color="0.4", linestyle=":", linewidth=1)
    if trajectory.stuck.size and trajectory.stuck.any():
        stuck = trajectory.stuck.any(axis=1)
        t = trajectory.t
        edges = np.flatnonzero(np.diff(np.concatenate([[0], stuck.astype(int), [0]])))
        for first, last in zip(edges[::2], edges[1::2], strict=True):
            ax.axvspan(t[first], t[min(last, len(t) - 1)], color="0.85", zorder=0,
                       label="sticking" if first == edges[0] else None)


def _offsets(trajectory: Trajectory) -> list[tuple[int, int]]:
    out, offset = [], 0
    for _, d in trajectory.particles:
        out.append((offset, d))
        offset += d
    return out


def _plane(trajectory: Trajectory, offset: int, d: int, i: int, j: int) -> np.ndarray:
    """A particle's components i and j, shape (samples, 2) (0 for a component it does not have)."""
    pos = trajectory.positions
    zero = np.zeros(len(trajectory.t))
    return np.column_stack([pos[:, offset + i] if i < d else zero, pos[:, offset + j] if j < d else zero])


def _padded(values: np.ndarray) -> tuple[float, float]:
    low, high = float(np.min(values)), float(np.max(values))
    pad = 0.1 * (high - low) if high > low else 1.0
    return low - pad, high + pad


# --- the sketch and the animation share one drawing ------------------------------------------------------


class _Drawing:
    """The system drawn in the plane of components (i, j) at one sample: particles (labelled dots), rods,
    pivots, surfaces and wires; :meth:`show` moves everything to another sample."""

    def __init__(self, ax: Any, trajectory: Trajectory, scene: Scene | None, i: int = 0, j: int = 1,
                 units: Units = None, trails: bool = False) -> None:
        self.ax, self.trajectory, self.scene = ax, trajectory, scene or Scene()
        self.i, self.j = i, j
        self.units = units or {}
        plane = [_plane(trajectory, o, d, i, j) for o, d in _offsets(trajectory)]
        self.plane = plane
        pivots = [p[:, [i, j]] for p in self.scene.pivots if p.shape[1] > j]
        points = np.vstack([*plane, *pivots]) if plane or pivots else np.zeros((1, 2))
        (x0, x1), (y0, y1) = _padded(points[:, 0]), _padded(points[:, 1])
        # square-ish limits with room for the labels
        cx, cy, half = (x0 + x1) / 2, (y0 + y1) / 2, max(x1 - x0, y1 - y0) / 2 * 1.08
        ax.set_xlim(cx - half, cx + half)
        ax.set_ylim(cy - half, cy + half)
        self.reach = 4 * half
        ax.set_aspect("equal", adjustable="box")
        ax.grid(alpha=0.25)
        length = self.units.get("length")
        ax.set_xlabel(_with_unit("xyz"[i], length))
        ax.set_ylabel(_with_unit("xyz"[j], length))
        three = any(d > 2 for _, d in trajectory.particles)
        for label, points in self.scene.curves:
            if points.shape[1] > j:
                ax.plot(points[:, i], points[:, j], "-", color="0.55", linewidth=2.2, alpha=0.8, zorder=1,
                        label=label or "wire")
        self.surfaces = []
        if not three:
            for k, (label, point, _) in enumerate(self.scene.surfaces):
                if point.shape[1] != 2:
                    continue
                line, = ax.plot([], [], "-", color=SURFACE_COLOURS[k % len(SURFACE_COLOURS)], linewidth=2.5,
                                zorder=1, label=label)
                self.surfaces.append(line)
        self.rod_ends = [(a, b) for _, a, b in self.scene.rods if a.shape[1] > j and b.shape[1] > j]
        self.rods = [ax.plot([], [], "-", color="0.15", linewidth=2.0, solid_capstyle="round", zorder=2)[0]
                     for _ in self.rod_ends]
        self.pivots = [ax.plot([], [], "^", color="0.15", markersize=9, zorder=3)[0] for _ in pivots]
        self.pivot_points = pivots
        self.trails = [ax.plot([], [], "-", linewidth=0.8, alpha=0.5, zorder=2)[0] for _ in plane] if trails else []
        self.dots, self.labels = [], []
        for k, (name, _) in enumerate(trajectory.particles):
            dot, = ax.plot([], [], "o", markersize=10, color=f"C{k % 10}", markeredgecolor="white", zorder=4)
            self.dots.append(dot)
            self.labels.append(ax.annotate(name, (0, 0), xytext=(7, 7), textcoords="offset points",
                                           fontsize="small", zorder=5, annotation_clip=False))
        if trails:
            for dot, trail in zip(self.dots, self.trails, strict=True):
                trail.set_color(dot.get_color())
        if self.scene.curves or self.surfaces:
            ax.legend(loc="lower right", fontsize="small", framealpha=0.85)
        self.stamp = ax.text(0.03, 0.96, "", transform=ax.transAxes, ha="left", va="top", fontsize="medium",
                             bbox={"boxstyle": "round", "facecolor": "white", "edgecolor": "0.7", "alpha": 0.85},
                             zorder=6)

    def show(self, sample: int) -> list[Any]:
        for (a, b), rod in zip(self.rod_ends, self.rods, strict=True):
            rod.set_data([a[sample, self.i], b[sample, self.i]], [a[sample, self.j], b[sample, self.j]])
        planar = [(p, n) for _, p, n in self.scene.surfaces if p.shape[1] == 2]  # none drawn in 3-D
        for (point, normal), line in zip(planar, self.surfaces, strict=False):
            p, n = point[sample], normal[sample]
            direction = np.array([-n[1], n[0]]) / max(float(np.hypot(n[0], n[1])), 1e-300)
            ends = np.array([p[:2] - self.reach * direction, p[:2] + self.reach * direction])
            line.set_data(ends[:, 0], ends[:, 1])
        for values, marker in zip(self.pivot_points, self.pivots, strict=True):
            marker.set_data([values[sample, 0]], [values[sample, 1]])
        for xy, dot, label in zip(self.plane, self.dots, self.labels, strict=True):
            dot.set_data([xy[sample, 0]], [xy[sample, 1]])
            label.xy = (xy[sample, 0], xy[sample, 1])
        for xy, trail in zip(self.plane, self.trails, strict=False):
            trail.set_data(xy[: sample + 1, 0], xy[: sample + 1, 1])
        unit = self.units.get("t")
        self.stamp.set_text(f"t = {self.trajectory.t[sample]:.2f}" + (f" {unit}" if unit else ""))
        return [*self.rods, *self.surfaces, *self.pivots, *self.trails, *self.dots, *self.labels, self.stamp]


def sketch_figure(trajectory: Trajectory, scene: Scene | None, title: str, units: Units = None,
                  sample: int = 0) -> Any:
    """The system at one sample (the start by default): particles, rods, pivots, surfaces and wires;
    for motion in 3-D, the x–y and x–z views side by side."""
    three = any(d > 2 for _, d in trajectory.particles)
    fig, axes = _figure(f"{title}: sketch", 1, 2 if three else 1, figsize=(10 if three else 5.5, 5.4))
    for ax, (i, j) in zip(axes[0], [(0, 1), (0, 2)] if three else [(0, 1)], strict=False):
        _Drawing(ax, trajectory, scene, i, j, units).show(sample)
    return fig


def animation_gif(trajectory: Trajectory, title: str, frames: int = 120, scene: Scene | None = None,
                  units: Units = None) -> bytes:
    """An animated GIF of the motion (Pillow): the sketch, moving, with the paths so far and a time stamp;
    the first frame is the sketch at t = 0. The layout is worked out on the first frame and then kept
    (the axes do not move), and each frame is drawn once."""
    units = axis_units(units)
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    from lagsolve.render.picture import Picture

    fig = Picture(figsize=(5, 5), layout="constrained")
    canvas = FigureCanvasAgg(fig)
    ax = fig.subplots()
    ax.set_title(_fit(title, 4.7), parse_math=False)
    drawing = _Drawing(ax, trajectory, scene, units=units, trails=True)
    index = np.linspace(0, len(trajectory.t) - 1, max(frames, 1)).astype(int)
    images = []
    for k, i in enumerate(index):
        drawing.show(int(i))
        canvas.draw()
        if k == 0:
            fig.set_layout_engine("none")  # laid out once: the same axes on every frame, at a fraction of the cost
        width, height = canvas.get_width_height()
        images.append(Image.frombuffer("RGBA", (width, height), bytes(canvas.buffer_rgba()), "raw", "RGBA", 0, 1))
    out = io.BytesIO()
    images[0].save(out, format="GIF", save_all=True, append_images=images[1:], duration=int(1000 / 24), loop=0)
    return out.getvalue()


# --- curves against time -------------------------------------------------------------------------------


def path_figure(trajectory: Trajectory, title: str,
                curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
                scene: Scene | None = None, units: Units = None) -> Any:
    """Each particle's path in physical space (x–y; x–z added for 3-D motion), with the scene's wires
    dashed, or the constraint curve when ``curve = (k, c)``: ``c`` maps values of coordinate ``k``
    to the first particle's positions, shape (samples, components)."""
    dims = {d for _, d in trajectory.particles}
    three = 3 in dims
    fig, axes = _figure(f"{title}: paths", 1, 2 if three else 1, figsize=(11 if three else 6.5, 5.5))
    planes = [(0, 1, "x", "y")] + ([(0, 2, "x", "z")] if three else [])
    length = (units or {}).get("length")
    for ax, (i, j, xl, yl) in zip(axes[0], planes, strict=True):
        wires = []
        if curve is not None:
            wires.append(curve[1](np.linspace(*_padded(trajectory.q[:, curve[0]]), 400)))
        elif scene is not None:
            wires += [points for _, points in scene.curves if points.shape[1] > j]
        paths = np.vstack([_plane(trajectory, o, d, i, j) for o, d in _offsets(trajectory)])
        (x0, x1), (y0, y1) = _padded(paths[:, 0]), _padded(paths[:, 1])
        for k, pts in enumerate(wires):
            # only near the paths (the rest would set the limits): points outside the box break the line
            xs, ys = pts[:, i].astype(float), pts[:, j].astype(float)
            outside = (xs < x0) | (xs > x1) | (ys < y0) | (ys > y1)
            ax.plot(np.where(outside, np.nan, xs), np.where(outside, np.nan, ys), "--", color="0.6", linewidth=1,
                    label="constraint" if k == 0 else None)
        for (name, d), (offset, _) in zip(trajectory.particles, _offsets(trajectory), strict=True):
            xy = _plane(trajectory, offset, d, i, j)
            line, = ax.plot(xy[:, 0], xy[:, 1], linewidth=1.4, label=name)
            ax.plot(xy[0, 0], xy[0, 1], "o", color=line.get_color(), markersize=5)
            ax.plot(xy[-1, 0], xy[-1, 1], "s", color=line.get_color(), markersize=5)
        ax.set_xlabel(_with_unit(xl, length))
        ax.set_ylabel(_with_unit(yl, length))
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize="small", title="○ start, □ end", title_fontsize="small")
    return fig


def _informative(trajectory: Trajectory) -> tuple[list[int], dict[int, str]]:
    """The coordinates worth a panel (at least one), and a sentence for each left out (constant, or
    moving uniformly)."""
    keep: list[int] = []
    notes: dict[int, str] = {}
    for k, name in enumerate(trajectory.coordinates):
        q, qd = trajectory.q[:, k], trajectory.qd[:, k]
        scale = max(float(np.max(np.abs(q))), float(np.max(np.abs(qd))) * float(np.ptp(trajectory.t)), 1.0)
        if np.ptp(q) <= FLAT * scale:
            notes[k] = f"{name} = {q[0]:.6g} throughout"
        elif len(q) > 2 and np.ptp(qd) <= FLAT * max(float(np.max(np.abs(qd))), 1.0):
            notes[k] = f"{name} moves uniformly: {name}_dot = {qd[0]:.6g}"
        else:
            keep.append(k)
    if not keep and trajectory.coordinates:
        keep.append(0)
        notes.pop(0, None)
    return keep, notes


def coordinates_figure(trajectory: Trajectory, title: str, labels: Mapping[str, str], units: Units = None) -> Any:
    """Each coordinate that changes in a way worth seeing, against time."""
    keep, notes = _informative(trajectory)
    fig, axes = _figure(f"{title}: coordinates", len(keep), 1, sharex=True)
    for row, k in enumerate(keep):
        name = trajectory.coordinates[k]
        ax = axes[row][0]
        ax.plot(trajectory.t, trajectory.q[:, k], linewidth=1.2)
        ax.set_ylabel(_with_unit(f"${labels.get(name, name)}$", (units or {}).get(name)))
        ax.grid(alpha=0.3)
        _events(ax, trajectory)
    axes[-1][0].set_xlabel(_time_label(units))
    _note(fig, list(notes.values()))
    return fig


def _rate_unit(name: str, units: Units) -> str | None:
    unit, time = (units or {}).get(name), (units or {}).get("t")
    return f"{unit}/{time}" if unit and time else None


def phase_figure(trajectory: Trajectory, title: str, labels: Mapping[str, str], units: Units = None) -> Any:
    """Phase portraits q against q̇ for every coordinate that moves, and not uniformly."""
    moving, notes = _informative(trajectory)
    cols = min(3, len(moving))
    rows = -(-len(moving) // cols)
    fig, axes = _figure(f"{title}: phase portraits", rows, cols, figsize=(3.8 * cols + 1, 3.6 * rows + 0.8))
    for idx, k in enumerate(moving):
        ax = axes[idx // cols][idx % cols]
        name = trajectory.coordinates[k]
        ax.plot(trajectory.q[:, k], trajectory.qd[:, k], linewidth=1)
        ax.plot(trajectory.q[0, k], trajectory.qd[0, k], "o", markersize=4)
        ax.set_xlabel(_with_unit(f"${labels.get(name, name)}$", (units or {}).get(name)))
        ax.set_ylabel(_with_unit(f"$\\dot{{{labels.get(name, name)}}}$", _rate_unit(name, units)))
        ax.grid(alpha=0.3)
    for idx in range(len(moving), rows * cols):
        axes[idx // cols][idx % cols].remove()
    _note(fig, list(notes.values()))
    return fig


def forces_figure(trajectory: Trajectory, title: str, units: Units = None) -> Any:
    """Multipliers λ_j and force-of-constraint magnitudes |F_j| against time; with friction contacts, a
    third panel of the friction forces (sticking phases shaded)."""
    contacts = bool(trajectory.contacts) and trajectory.friction.shape[1] == len(trajectory.contacts)
    measured = [j for j in range(len(trajectory.constraints)) if np.any(np.isfinite(trajectory.magnitudes[:, j]))]
    same = bool(measured) and len(measured) == len(trajectory.constraints) and np.allclose(
        np.abs(trajectory.multipliers), trajectory.magnitudes, rtol=1e-9, atol=1e-12)
    if same:  # the magnitudes would repeat the multipliers: one panel says both
        measured = []
    panels = ["lambda"] + (["magnitude"] if measured else []) + (["friction"] if contacts else [])
    title_text = f"{title}: forces of constraint" + (" and friction" if contacts else "")
    fig, axes = _figure(title_text, len(panels), 1, sharex=True)
    ax = dict(zip(panels, (row[0] for row in axes), strict=True))
    force = (units or {}).get("force")
    for j, name in enumerate(trajectory.constraints):
        unit = (units or {}).get(f"lambda_{name}")  # each multiplier has its constraint's unit
        ax["lambda"].plot(trajectory.t, trajectory.multipliers[:, j], linewidth=1.2,
                          label=f"$\\lambda_{{{name}}}$" + (f" [{unit}]" if unit else ""))
        if j in measured:
            ax["magnitude"].plot(trajectory.t, trajectory.magnitudes[:, j], linewidth=1.2, label=f"$|F_{{{name}}}|$")
    ax["lambda"].set_ylabel("multiplier $\\lambda$")
    if "magnitude" in ax:
        ax["magnitude"].set_ylabel(_with_unit("magnitude $|F|$", force))
    if contacts:
        for c, name in enumerate(trajectory.contacts):
            ax["friction"].plot(trajectory.t, trajectory.friction[:, c], linewidth=1.2, color=f"C{c + 3}",
                                label=f"friction {name}")
        ax["friction"].set_ylabel(_with_unit("friction $f$", force))
    notes = [] if measured or not trajectory.constraints else [
        "each |F| equals |λ| (the constraint's gradient has unit length), so the multipliers are drawn alone"
        if same else "no magnitude of a force of constraint: no particle it acts on is known"]
    for a in ax.values():
        a.grid(alpha=0.3)
        a.axhline(0, color="0.5", linewidth=0.6)
        _events(a, trajectory)
        if a.get_legend_handles_labels()[0]:
            a.legend(loc="best", fontsize="small")
    axes[-1][0].set_xlabel(_time_label(units))
    _note(fig, notes)
    return fig


def conservation_figure(trajectory: Trajectory, title: str, units: Units = None) -> Any:
    """Relative drift of each conserved quantity (log scale); where the energy is not conserved, the
    change of the Jacobi integral h − h₀ (the energy dissipated, or fed in by a drive); and the
    constraint residual where it is not exactly zero."""
    series = {}
    if trajectory.stats.get("energy_conserved"):
        # the conserved h the analysis found (of the reduced system where a constraint moves), else the full one
        series["energy $h$"] = trajectory.conserved.get("energy", trajectory.energy)
    for name, values in trajectory.conserved.items():
        if name != "energy" or "energy $h$" not in series:  # the same h, drawn once
            series[name.replace("_", " ")] = values
    changing = not trajectory.stats.get("energy_conserved") and np.all(np.isfinite(trajectory.energy))
    projected = trajectory.stats.get("projected", True)
    residual = bool(trajectory.constraints) and bool(np.any(trajectory.residual))
    panels = (["drift"] if series else []) + (["energy"] if changing else []) + (["residual"] if residual else [])
    panels = panels or ["energy"]
    what = "conservation and constraints" if trajectory.constraints else "conservation"
    fig, axes = _figure(f"{title}: {what}", len(panels), 1, sharex=True)
    ax = dict(zip(panels, (row[0] for row in axes), strict=True))
    notes = []
    if "drift" in ax:
        for label, values in series.items():
            scale = abs(values[0]) if abs(values[0]) > 1e-300 else 1.0
            ax["drift"].semilogy(trajectory.t, np.maximum(np.abs(values - values[0]) / scale, 1e-17), linewidth=1,
                                 label=label)
        ax["drift"].legend(loc="best", fontsize="small")
        ax["drift"].set_ylabel("relative drift")
        ax["drift"].grid(alpha=0.3, which="both")
    if "energy" in ax:
        h = trajectory.energy
        a = ax["energy"]
        a.plot(trajectory.t, h - h[0], linewidth=1.2, color="C2", label="$h - h_0$")
        a.axhline(0, color="0.5", linewidth=0.6)
        a.set_ylabel(_with_unit("$h - h_0$", (units or {}).get("energy")))
        a.grid(alpha=0.3)
        _events(a, trajectory)
        lost = h[0] - h[-1]
        a.legend(loc="best", fontsize="small",
                 title=("dissipated" if lost > 0 else "gained") + f" by t = {trajectory.t[-1]:.3g}: {abs(lost):.4g}",
                 title_fontsize="small")
        if not trajectory.stats.get("energy_conserved"):
            notes.append("energy not conserved: " + str(trajectory.stats.get("energy_note", "")))
    if "residual" in ax:
        a = ax["residual"]
        a.semilogy(trajectory.t, np.maximum(trajectory.residual, 1e-17), linewidth=1, color="C3")
        a.set_ylabel("constraint residual\n(before projection)" if projected else "constraint residual")
        a.grid(alpha=0.3, which="both")
        _events(a, trajectory)
    elif trajectory.constraints:
        notes.append("the constraint residual is exactly 0 at every sample"
                     + ("" if projected else ": minimal coordinates, the dependent ones computed from the constraints"))
    axes[-1][0].set_xlabel(_time_label(units))
    _note(fig, notes)
    return fig


def axis_units(units: Units) -> Units:
    """The figures' unit keys from a table's column units: ``length`` from ``position``, ``force`` from the
    first force column (``F_c``, ``N_c`` or ``friction_c``); keys already given win."""
    if not units:
        return units
    out = dict(units)
    if "position" in units:
        out.setdefault("length", units["position"])
    force = next((u for k, u in units.items() if k.startswith(("F_", "N_", "friction_"))), None)
    if force is not None:
        out.setdefault("force", force)
    return out


def figures(trajectory: Trajectory, title: str, labels: Mapping[str, str],
            curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
            scene: Scene | None = None, units: Units = None) -> dict[str, Any]:
    """All figures of a trajectory, by stable name. ``units`` maps a coordinate, ``t``, ``length``, ``force``
    and ``energy`` (or the trajectory table's columns: ``position``, ``F_c``, ``lambda_c``) to a unit."""
    units = axis_units(units)
    out: dict[str, Any] = {}
    if trajectory.particles:
        out["sketch"] = sketch_figure(trajectory, scene, title, units)
        out["path"] = path_figure(trajectory, title, curve, scene, units)
    out["coordinates"] = coordinates_figure(trajectory, title, labels, units)
    out["phase"] = phase_figure(trajectory, title, labels, units)
    if trajectory.constraints:
        out["forces"] = forces_figure(trajectory, title, units)
    out["conservation"] = conservation_figure(trajectory, title, units)
    return out


def png_bytes(figure: Any, dpi: int = 110) -> bytes:
    """The figure as PNG bytes (deterministic metadata, so equal figures give equal files)."""
    import io

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=dpi, metadata={"Software": None})
    return buffer.getvalue()
