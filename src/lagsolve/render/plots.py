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

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from lagsolve.numeric.integrate import EventKind, Trajectory
from lagsolve.numeric.scene import Scene
from lagsolve.render.canvas import MAX_HEIGHT, WIDTH, Units, axis_units, figure, fit  # noqa: F401 (used by callers)
from lagsolve.render.sketch import animation_gif, sketch_figure  # noqa: F401 (the sketch: render/sketch.py)

#: relative size below which a coordinate counts as constant, or its rate as uniform
FLAT = 1e-9


def _note(fig: Any, lines: list[str]) -> None:
    """What the figure leaves out, and why, in small text under it."""
    if lines:
        width = fig.get_figwidth() - 0.3
        fig.supxlabel("\n".join(fit(line, width, 8.5) for line in lines), fontsize="small", color="0.3",
                      parse_math=False)


def _with_unit(label: str, unit: str | None) -> str:
    return f"{label} [{unit}]" if unit else label


def _time_label(units: Units) -> str:
    return _with_unit("$t$", (units or {}).get("t"))


def _events(ax: Any, trajectory: Trajectory) -> None:
    """Release events (and a return to a released constraint, or a contact that slides in a plane coming to rest)
    as dotted lines; sticking phases of friction contacts shaded."""
    for event in trajectory.events:
        if event.kind in (EventKind.RELEASE, EventKind.CONTACT, EventKind.REST):
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


# --- curves against time -------------------------------------------------------------------------------


def path_figure(trajectory: Trajectory, title: str,
                curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
                scene: Scene | None = None, units: Units = None) -> Any:
    """Each particle's path in physical space (x–y; x–z added for 3-D motion), with the scene's wires
    dashed, or the constraint curve when ``curve = (k, c)``: ``c`` maps values of coordinate ``k``
    to the first particle's positions, shape (samples, components)."""
    dims = {d for _, d in trajectory.particles}
    three = 3 in dims
    fig, axes = figure(f"{title}: paths", 1, 2 if three else 1, figsize=(WIDTH, 3.5 if three else 4.1))
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
    fig, axes = figure(f"{title}: coordinates", len(keep), 1, sharex=True)
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
    fig, axes = figure(f"{title}: phase portraits", rows, cols,
                       figsize=(WIDTH, min(0.9 + (5.6 / max(cols, 2) + 0.3) * rows, MAX_HEIGHT)))
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
    fig, axes = figure(title_text, len(panels), 1, sharex=True)
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


def _drift_panel(a: Any, trajectory: Trajectory, series: Mapping[str, np.ndarray], notes: list[str]) -> None:
    """The relative drift of each conserved quantity, up to a release the run went on from: after it the
    quantities of the system with the constraint held need not be conserved, and are not drawn."""
    until = float(trajectory.stats.get("conserved_until", np.nan))
    held = trajectory.t <= until if np.isfinite(until) else np.ones(len(trajectory.t), dtype=bool)
    for label, values in series.items():
        scale = abs(values[0]) if abs(values[0]) > 1e-300 else 1.0
        a.semilogy(trajectory.t, np.where(held, np.maximum(np.abs(values - values[0]) / scale, 1e-17), np.nan),
                   linewidth=1, label=label)
    if np.isfinite(until):
        notes.append(f"drifts drawn up to the release at t = {until:.6g}: after it the constraint no longer holds")
    a.legend(loc="best", fontsize="small")
    a.set_ylabel("relative drift")
    a.grid(alpha=0.3, which="both")


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
    fig, axes = figure(f"{title}: {what}", len(panels), 1, sharex=True)
    ax = dict(zip(panels, (row[0] for row in axes), strict=True))
    notes: list[str] = []
    if "drift" in ax:
        _drift_panel(ax["drift"], trajectory, series, notes)
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


def figures(trajectory: Trajectory, title: str, labels: Mapping[str, str],
            curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
            scene: Scene | None = None, units: Units = None) -> dict[str, Any]:
    """All figures of a trajectory, by stable name. ``units`` maps a coordinate, ``t``, ``length``, ``force``
    and ``energy`` (or the trajectory table's columns: ``position``, ``F_c``, ``lambda_c``) to a unit."""
    units = axis_units(units)
    out: dict[str, Any] = {}
    if trajectory.particles or scene:
        out["sketch"] = sketch_figure(trajectory, scene, title, units)
    if trajectory.particles:
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
