"""A trajectory as a table (CSV, NPZ) and as a short text summary.

CSV columns (format section 3): ``t``, each coordinate, each ``<q>_dot``, then
``lambda_<c>`` and ``F_<c>`` per constraint, ``energy`` (the Jacobi integral,
conserved or not), then ``N_<contact>``, ``friction_<contact>`` and ``stuck_<contact>``
(1 while it sticks, 0 while it slides) per friction contact, ``residual`` and any
conserved quantities. With units (a problem that declares them) each header cell carries its column's
unit, ``x [m]``; a column whose unit is not known keeps its bare name.
"""

from __future__ import annotations

import io
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from lagsolve.numeric.integrate import Trajectory


def columns(trajectory: Trajectory) -> dict[str, np.ndarray]:
    """Every column, in the documented order."""
    out: dict[str, np.ndarray] = {"t": trajectory.t}
    for k, name in enumerate(trajectory.coordinates):
        out[name] = trajectory.q[:, k]
    for k, name in enumerate(trajectory.coordinates):
        out[f"{name}_dot"] = trajectory.qd[:, k]
    for j, name in enumerate(trajectory.constraints):
        out[f"lambda_{name}"] = trajectory.multipliers[:, j]
    for j, name in enumerate(trajectory.constraints):
        out[f"F_{name}"] = trajectory.magnitudes[:, j]
    out["energy"] = trajectory.energy
    for c, name in enumerate(trajectory.contacts):
        out[f"N_{name}"] = trajectory.normal_forces[:, c]
    for c, name in enumerate(trajectory.contacts):
        out[f"friction_{name}"] = trajectory.friction[:, c]
    for c, name in enumerate(trajectory.contacts):
        out[f"stuck_{name}"] = trajectory.stuck[:, c].astype(float)
    out["residual"] = trajectory.residual
    for name, values in trajectory.conserved.items():
        if name != "energy":
            out[name] = values
    return out


def to_csv(trajectory: Trajectory, units: Mapping[str, str] | None = None) -> str:
    """The trajectory as CSV text with a header row (17 significant digits: no information lost).

    ``units`` maps a column name to its unit (``{"x": "m"}`` gives the header cell ``x [m]``)."""
    data = columns(trajectory)
    units = units or {}
    lines = [",".join(f"{name} [{units[name]}]" if name in units else name for name in data)]
    table = np.column_stack(list(data.values()))
    lines += [",".join(f"{v:.17g}" for v in row) for row in table]
    return "\n".join(lines) + "\n"


def to_npz(trajectory: Trajectory) -> bytes:
    """The same columns as a NumPy ``.npz`` archive."""
    buffer = io.BytesIO()
    arrays: dict[str, Any] = columns(trajectory)
    np.savez(buffer, **arrays)
    return buffer.getvalue()


def summary(trajectory: Trajectory, name: str, timing: bool = True) -> str:
    """What a person wants to know after a run: final state, events, diagnostics.

    ``timing=False`` leaves out the wall time, for reports that must be byte-identical run to run."""
    stats: dict[str, Any] = dict(trajectory.stats)
    lines = [f"{name}: simulated to t = {trajectory.t[-1]:.6g} with {stats['method']} "
             f"(rtol {stats['rtol']:g}, atol {stats['atol']:g})"]
    state = ", ".join(f"{c} = {v:.6g}" for c, v in zip(trajectory.coordinates, trajectory.q[-1], strict=True))
    rates = ", ".join(f"{c}_dot = {v:.6g}" for c, v in zip(trajectory.coordinates, trajectory.qd[-1], strict=True))
    lines.append(f"  final state: {state}")
    lines.append(f"               {rates}")
    for event in trajectory.events:
        where = ", ".join(f"{k} = {v:.6g}" for k, v in event.state.items() if not k.endswith("_dot"))
        if event.kind == "release" and event.time == trajectory.t[0] and event.action == "stopped":
            lines.append(f"  event: constraint {event.name!r} would have to pull at the start, t = {event.time:.10g} "
                         f"({where}), so contact is lost at once; stopped there (--after-release continue goes on "
                         "without it)")
        elif event.kind == "release":
            verb = "stopped there" if event.action == "stopped" else "continued without it"
            lines.append(f"  event: constraint {event.name!r} released at t = {event.time:.10g} ({where}); {verb}")
        elif event.kind == "contact":
            lines.append(f"  event: constraint {event.name!r} reached again at t = {event.time:.10g} ({where}): the "
                         "motion comes back to it, an impact that lagsolve does not model; stopped there")
        elif event.kind == "rest":
            lines.append(f"  event: contact {event.name!r} comes to rest at t = {event.time:.10g} ({where}): friction "
                         "that acts in a plane is modelled only while the contact slides; stopped there")
        else:
            verb = "sticks" if event.kind == "stick" else "slips again"
            lines.append(f"  event: contact {event.name!r} {verb} at t = {event.time:.10g} ({where})")
    work = f"  steps: {stats['steps']}, right-hand-side evaluations: {stats['evaluations']}"
    lines.append(work + (f", wall time: {stats['wall_time']:.3g} s" if timing else ""))
    if "coordinates" in stats:
        lines.append(f"  coordinates: {stats['coordinates']}")
    if trajectory.constraints:
        projected = stats.get("projected", True)
        lines.append(f"  largest constraint residual{' (before projection)' if projected else ''}: "
                     f"{stats['max_residual']:.3g}")
    until = stats.get("conserved_until", math.nan)
    # after a release the quantities of the system with the constraint held need not be conserved
    upto = "" if math.isnan(until) else f" (up to the release at t = {until:.10g})"
    if stats.get("energy_conserved"):
        drift = stats.get("conserved_drift", {}).get("energy", stats["energy_drift"])
        lines.append(f"  energy (Jacobi integral) conserved: relative drift {drift:.3g}{upto}")
    else:
        lines.append(f"  energy not conserved: {stats.get('energy_note', '')}")
    for quantity, drift in stats.get("conserved_drift", {}).items():
        if quantity != "energy" or not stats.get("energy_conserved"):
            lines.append(f"  {quantity} conserved: relative drift {drift:.3g}{upto}")
    return "\n".join(lines) + "\n"


#: frames of the HTML page's animation (the trajectory is sampled down to at most this many)
FRAMES = 400


def animation(trajectory: Trajectory, frames: int = FRAMES, scene: Any = None) -> dict[str, Any] | None:
    """Plain data for the HTML report's time slider: times, each particle's path in the plane of its first
    two components, the relative drift of the Jacobi integral and each constraint force's magnitude,
    at most ``frames`` samples (rounded to 5 significant digits). With a
    :class:`~lagsolve.numeric.scene.Scene`, also the rods (both ends at each frame), pivots, surfaces
    (a point and the normal at each frame) and wires (a fixed polyline) to draw. None without particles."""
    if not trajectory.particles or len(trajectory.t) < 2:
        return None
    pick = np.unique(np.linspace(0, len(trajectory.t) - 1, min(frames, len(trajectory.t))).round().astype(int))

    def values(column: Any, rows: Any = pick) -> list[float]:
        return [float(f"{v:.5g}") if np.isfinite(v) else 0.0 for v in np.asarray(column, dtype=float)[rows]]

    particles = []
    offset = 0
    for name, dims in trajectory.particles:
        xy = trajectory.positions[:, offset:offset + dims]
        offset += dims
        particles.append({"name": name, "x": values(xy[:, 0]),
                          "y": values(xy[:, 1]) if dims > 1 else [0.0] * len(pick)})
    h = np.asarray(trajectory.energy, dtype=float)
    scale = max(abs(h[0]), np.max(np.abs(h)) * 1e-3, 1e-300)
    series = [{"name": "relative drift of h", "values": values((h - h[0]) / scale)}] if np.all(np.isfinite(h)) else []
    series += [{"name": f"|F_{c}|", "values": values(trajectory.magnitudes[:, j])}
               for j, c in enumerate(trajectory.constraints)]
    out: dict[str, Any] = {"t": values(trajectory.t), "particles": particles, "series": series}
    if scene:
        out.update(_scene_data(scene, values))
    return out


def _scene_data(scene: Any, values: Any) -> dict[str, Any]:
    """The scene in the plane of the first two components, sampled like the particles."""
    def plane(a: np.ndarray) -> bool:
        return a.shape[1] >= 2

    rods = [{"x1": values(a[:, 0]), "y1": values(a[:, 1]), "x2": values(b[:, 0]), "y2": values(b[:, 1])}
            for _, a, b in scene.rods if plane(a) and plane(b)]
    pivots = [{"x": values(p[:, 0]), "y": values(p[:, 1])} for p in scene.pivots if plane(p)]
    surfaces = [{"x": values(p[:, 0]), "y": values(p[:, 1]), "nx": values(n[:, 0]), "ny": values(n[:, 1])}
                for _, p, n in scene.surfaces if p.shape[1] == 2]
    curves = []
    for _, points in scene.curves:
        if plane(points):
            rows = np.unique(np.linspace(0, len(points) - 1, min(200, len(points))).round().astype(int))
            curves.append({"x": values(points[:, 0], rows), "y": values(points[:, 1], rows)})
    return {"rods": rods, "pivots": pivots, "surfaces": surfaces, "curves": curves}
