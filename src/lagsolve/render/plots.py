"""Figures of a simulated motion (matplotlib, Agg backend; nothing is shown from here).

Every function takes plain data — a :class:`~lagsolve.numeric.integrate.Trajectory`
plus labels — and returns a :class:`matplotlib.figure.Figure`. :func:`figures`
returns them all under stable names (``path``, ``coordinates``, ``phase``,
``forces``, ``conservation``), which the command line turns into
``<problem>_<name>.png``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from lagsolve.numeric.integrate import EventKind, Trajectory


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _figure(title: str, rows: int = 1, cols: int = 1, **kwargs: Any) -> tuple[Any, Any]:
    from matplotlib.figure import Figure

    fig = Figure(figsize=kwargs.pop("figsize", (7.5, 2.2 + 2.4 * rows)), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False, **kwargs)
    fig.suptitle(title, parse_math=False)  # user text: a "$" in a name is not mathtext
    return fig, axes


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


def _in(units: Mapping[str, str] | None, column: str) -> str:
    """`` [m]``: the unit of a trajectory column for an axis label or legend, or nothing when it is not known."""
    return f" [{units[column]}]" if units and column in units else ""


def path_figure(trajectory: Trajectory, title: str,
                curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
                units: Mapping[str, str] | None = None) -> Any:
    """Each particle's path in physical space (x–y; x–z added for 3-D motion), with the
    constraint curve dashed when ``curve = (k, c)``: ``c`` maps values of coordinate ``k``
    to the first particle's positions, shape (samples, components)."""
    dims = {d for _, d in trajectory.particles}
    three = 3 in dims
    fig, axes = _figure(f"{title}: paths", 1, 2 if three else 1, figsize=(11 if three else 6.5, 5.5))
    planes = [(0, 1, "x", "y")] + ([(0, 2, "x", "z")] if three else [])
    for ax, (i, j, xl, yl) in zip(axes[0], planes, strict=True):
        offset = 0
        if curve is not None:
            pts = curve[1](np.linspace(*_padded(trajectory.q[:, curve[0]]), 400))
            ax.plot(pts[:, i], pts[:, j], "--", color="0.6", linewidth=1, label="constraint")
        for name, d in trajectory.particles:
            xy = trajectory.positions[:, offset:offset + d]
            line, = ax.plot(xy[:, i], xy[:, j], linewidth=1.4, label=name)
            ax.plot(xy[0, i], xy[0, j], "o", color=line.get_color(), markersize=5)
            ax.plot(xy[-1, i], xy[-1, j], "s", color=line.get_color(), markersize=5)
            offset += d
        ax.set_xlabel(xl + _in(units, "position"))
        ax.set_ylabel(yl + _in(units, "position"))
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize="small", title="○ start, □ end", title_fontsize="small")
    return fig


def _padded(values: np.ndarray) -> tuple[float, float]:
    low, high = float(np.min(values)), float(np.max(values))
    pad = 0.1 * (high - low) if high > low else 1.0
    return low - pad, high + pad


def coordinates_figure(trajectory: Trajectory, title: str, labels: Mapping[str, str],
                       units: Mapping[str, str] | None = None) -> Any:
    """Each coordinate against time."""
    n = len(trajectory.coordinates)
    fig, axes = _figure(f"{title}: coordinates", n, 1, sharex=True)
    for k, name in enumerate(trajectory.coordinates):
        ax = axes[k][0]
        ax.plot(trajectory.t, trajectory.q[:, k], linewidth=1.2)
        ax.set_ylabel(f"${labels.get(name, name)}$" + _in(units, name))
        ax.grid(alpha=0.3)
        _events(ax, trajectory)
    axes[-1][0].set_xlabel("$t$" + _in(units, "t"))
    return fig


def phase_figure(trajectory: Trajectory, title: str, labels: Mapping[str, str],
                 units: Mapping[str, str] | None = None) -> Any:
    """Phase portraits q against q̇ for every coordinate that moves."""
    moving = [k for k in range(len(trajectory.coordinates)) if np.ptp(trajectory.q[:, k]) > 1e-12]
    moving = moving or [0]
    cols = min(3, len(moving))
    rows = -(-len(moving) // cols)
    fig, axes = _figure(f"{title}: phase portraits", rows, cols, figsize=(3.8 * cols + 1, 3.6 * rows + 0.8))
    for idx, k in enumerate(moving):
        ax = axes[idx // cols][idx % cols]
        name = trajectory.coordinates[k]
        ax.plot(trajectory.q[:, k], trajectory.qd[:, k], linewidth=1)
        ax.plot(trajectory.q[0, k], trajectory.qd[0, k], "o", markersize=4)
        ax.set_xlabel(f"${labels.get(name, name)}$" + _in(units, name))
        ax.set_ylabel(f"$\\dot{{{labels.get(name, name)}}}$" + _in(units, f"{name}_dot"))
        ax.grid(alpha=0.3)
    for idx in range(len(moving), rows * cols):
        axes[idx // cols][idx % cols].set_visible(False)
    return fig


def forces_figure(trajectory: Trajectory, title: str, units: Mapping[str, str] | None = None) -> Any:
    """Multipliers λ_j and force-of-constraint magnitudes |F_j| against time."""
    fig, axes = _figure(f"{title}: forces of constraint", 2, 1, sharex=True)
    for j, name in enumerate(trajectory.constraints):
        axes[0][0].plot(trajectory.t, trajectory.multipliers[:, j], linewidth=1.2,
                        label=f"$\\lambda_{{{name}}}$" + _in(units, f"lambda_{name}"))
        axes[1][0].plot(trajectory.t, trajectory.magnitudes[:, j], linewidth=1.2,
                        label=f"$|F_{{{name}}}|$" + _in(units, f"F_{name}"))
    axes[0][0].set_ylabel("multiplier $\\lambda$")
    axes[1][0].set_ylabel("magnitude $|F|$")
    axes[1][0].set_xlabel("$t$" + _in(units, "t"))
    for ax in (axes[0][0], axes[1][0]):
        ax.grid(alpha=0.3)
        ax.axhline(0, color="0.5", linewidth=0.6)
        _events(ax, trajectory)
        if trajectory.constraints:
            ax.legend(loc="best", fontsize="small")
    return fig


def conservation_figure(trajectory: Trajectory, title: str) -> Any:
    """Relative drift of each conserved quantity and the constraint residual, log scale."""
    fig, axes = _figure(f"{title}: conservation and constraints", 2, 1, sharex=True)
    ax = axes[0][0]
    series = {}
    if trajectory.stats.get("energy_conserved"):
        # the conserved h the analysis found (of the reduced system where a constraint moves), else the full one
        series["energy $h$"] = trajectory.conserved.get("energy", trajectory.energy)
    for name, values in trajectory.conserved.items():
        if name != "energy" or "energy $h$" not in series:  # the same h, drawn once
            series[name.replace("_", " ")] = values
    for label, values in series.items():
        scale = abs(values[0]) if abs(values[0]) > 1e-300 else 1.0
        ax.semilogy(trajectory.t, np.maximum(np.abs(values - values[0]) / scale, 1e-17), linewidth=1, label=label)
    if not series:
        ax.text(0.5, 0.5, "no conserved quantity: " + str(trajectory.stats.get("energy_note", "")),
                transform=ax.transAxes, ha="center", va="center", fontsize="small", wrap=True)
    else:
        ax.legend(loc="best", fontsize="small")
    ax.set_ylabel("relative drift")
    ax.grid(alpha=0.3, which="both")
    ax2 = axes[1][0]
    projected = trajectory.stats.get("projected", True)
    if trajectory.constraints and not np.any(trajectory.residual):
        ax2.set_yscale("log")
        ax2.set_ylim(1e-17, 1e-13)
        ax2.text(0.5, 0.5, "the residual is exactly 0 at every sample"
                 + ("" if projected else ":\nminimal coordinates, the dependent ones computed from the constraints"),
                 transform=ax2.transAxes, ha="center", va="center", fontsize="small")
    else:
        ax2.semilogy(trajectory.t, np.maximum(trajectory.residual, 1e-17), linewidth=1, color="C3")
    ax2.set_ylabel("constraint residual\n(before projection)" if projected else "constraint residual")
    ax2.set_xlabel("$t$")
    ax2.grid(alpha=0.3, which="both")
    _events(ax2, trajectory)
    return fig


def figures(trajectory: Trajectory, title: str, labels: Mapping[str, str],
            curve: tuple[int, Callable[[np.ndarray], np.ndarray]] | None = None,
            units: Mapping[str, str] | None = None) -> dict[str, Any]:
    """All figures of a trajectory, by stable name. ``units`` maps a trajectory column (``t``, ``x``,
    ``x_dot``, ``lambda_c``, ``F_c``, and ``position`` for the paths) to its unit, shown on the axes as
    ``x [m]``; without it the labels carry no unit."""
    out: dict[str, Any] = {}
    if trajectory.particles:
        out["path"] = path_figure(trajectory, title, curve, units)
    out["coordinates"] = coordinates_figure(trajectory, title, labels, units)
    out["phase"] = phase_figure(trajectory, title, labels, units)
    if trajectory.constraints:
        out["forces"] = forces_figure(trajectory, title, units)
    out["conservation"] = conservation_figure(trajectory, title)
    return out


def png_bytes(figure: Any, dpi: int = 110) -> bytes:
    """The figure as PNG bytes (deterministic metadata, so equal figures give equal files)."""
    import io

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=dpi, metadata={"Software": None})
    return buffer.getvalue()


def animation_gif(trajectory: Trajectory, title: str, frames: int = 120) -> bytes:
    """An animated GIF of the particles moving (pillow writer)."""
    import tempfile
    from pathlib import Path

    from matplotlib.animation import FuncAnimation, PillowWriter

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5, 5))
    pos = trajectory.positions
    ax.set_xlim(*_padded(pos[:, [o for o, _ in _offsets(trajectory)]].ravel()))
    ax.set_ylim(*_padded(pos[:, [o + 1 for o, _ in _offsets(trajectory)]].ravel()))
    ax.set_aspect("equal", adjustable="box")
    ax.set_title(title, parse_math=False)
    ax.grid(alpha=0.3)
    dots = [ax.plot([], [], "o", markersize=8, label=name)[0] for name, _ in trajectory.particles]
    trails = [ax.plot([], [], "-", linewidth=0.8, alpha=0.6)[0] for _ in trajectory.particles]
    index = np.linspace(0, len(trajectory.t) - 1, frames).astype(int)

    def draw(frame: int) -> list[Any]:
        i = index[frame]
        for (offset, _), dot, trail in zip(_offsets(trajectory), dots, trails, strict=True):
            dot.set_data([pos[i, offset]], [pos[i, offset + 1]])
            trail.set_data(pos[: i + 1, offset], pos[: i + 1, offset + 1])
        return [*dots, *trails]

    animation = FuncAnimation(fig, draw, frames=frames, blit=True)
    with tempfile.TemporaryDirectory() as folder:
        target = Path(folder) / "a.gif"
        animation.save(target, writer=PillowWriter(fps=24))
        plt.close(fig)
        return target.read_bytes()


def _offsets(trajectory: Trajectory) -> list[tuple[int, int]]:
    out, offset = [], 0
    for _, d in trajectory.particles:
        out.append((offset, d))
        offset += d
    return out
