"""One chunk of a sweep on the compiled path (:mod:`lagsolve.sweep.native`), its table built column by column.

The runs' initial states come straight from the inputs (the compiled path covers problems in minimal
coordinates, so there is nothing to complete from constraints), the compiled integrator runs them one
after the other with the GIL released, and the table is assembled from its arrays: the same columns, in
the same order, with the same rules for ``status`` and ``outcome`` as the rows of
:mod:`lagsolve.sweep.run` (``path`` is ``compiled``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from lagsolve.sweep import kernel
from lagsolve.sweep.run import MEASURED, Compiled, Settings, _drift, _empty_row, _state_names

PATH = "compiled"


def _reason(code: int, t: float, measures: list[str]) -> str:
    """Why a run with the kernel's end ``code`` at time ``t`` failed (the batched path's words), or ""."""
    if code == kernel.BAD_START:
        return "the initial state or its accelerations are not finite"
    if code == kernel.SMALL_STEP:
        return f"the step size fell below the smallest allowed at t = {t:.6g}"
    if code == kernel.NOT_FINITE:
        return (f"the state is no longer finite at t = {t:.6g} (the motion diverged or left the domain of an "
                "expression)")
    if code == kernel.TOO_MANY:
        return "more than 1000000 steps before t_end"
    if code in (kernel.BAD_ENERGY, kernel.BAD_CONSERVED):
        what = f"{' and '.join(measures)} {'is' if len(measures) == 1 else 'are'}"
        return (f"{what} no longer finite at t = {t:.6g} (an expression was evaluated outside its domain, such "
                "as log or sqrt of a number <= 0, or the motion diverged)")
    return ""


def compiled_chunk(problem: Compiled, native: Any, settings: Settings, inputs: Mapping[str, np.ndarray],
                   start: int) -> Any:
    """The result table (a pandas DataFrame) of the runs ``inputs`` on the compiled path."""
    import pandas

    system = problem.system
    n = system.n
    count = len(next(iter(inputs.values())))
    names = system.parameter_names
    parameters = np.tile(np.asarray(system.parameters, dtype=float), (count, 1))
    for name, values in inputs.items():
        if name in names:
            parameters[:, names.index(name)] = values
    states = _state_names(system)
    y0 = np.empty((count, 2 * n))
    for j, name in enumerate(states):
        y0[:, j] = np.asarray(inputs[name], dtype=float) if name in inputs else float(problem.initial.get(name, 0.0))
    section = settings.section
    angular = np.array(problem.angular, dtype=bool)
    (t, y, steps, code, energy0, worst_energy, conserved0, worst_conserved, flip_time, crossings,
     _) = native.integrate(y0, parameters, settings.t_end, settings.method, settings.rtol, settings.atol, angular,
                           None if section is None else (section.index, section.value))
    failed = code != kernel.DONE
    columns: dict[str, Any] = {"run": np.arange(start, start + count)}
    columns.update({name: np.asarray(values, dtype=float) for name, values in inputs.items()})
    template = _empty_row(problem, settings, PATH)
    conserved_names = [f"the conserved quantity {name}" for name in problem.conserved]
    reasons = []
    for r in range(count):
        if not failed[r]:
            reasons.append("")
            continue
        measures = ["the energy"] if not np.isfinite(worst_energy[r]) else []
        measures += [what for c, what in enumerate(conserved_names) if not np.isfinite(worst_conserved[r, c])]
        reasons.append(_reason(int(code[r]), float(t[r]), measures))
    table: dict[str, Any] = {key: None for key in template}
    table["status"] = np.where(failed, "failed", "ok").astype(object)
    table["reason"] = np.array(reasons, dtype=object)
    table["path"] = np.full(count, PATH, dtype=object)
    table["note"] = np.full(count, "", dtype=object)
    table["t_final"] = np.where(code == kernel.BAD_START, np.nan, t)
    started = code != kernel.BAD_START
    for j, name in enumerate(states):
        table[f"final_{name}"] = np.where(started, y[:, j], np.nan)
    table["max_residual"] = np.where(started, 0.0, np.nan)
    table["energy_conserved"] = np.full(count, bool(system.energy_conserved))
    table["energy_drift"] = np.where(started, _drift(energy0, worst_energy), np.nan)
    for c, name in enumerate(problem.conserved):
        table[f"drift_{name}"] = np.where(started, _drift(conserved0[:, c], worst_conserved[:, c]), np.nan)
    flipped = np.isfinite(flip_time) & started
    table["flipped"] = flipped
    table["flip_time"] = np.where(flipped, flip_time, np.nan)
    for key in ("stick_count", "slip_count"):
        table[key] = np.zeros(count, dtype=np.int64)
    for key in ("stick_times", "slip_times"):
        table[key] = [[] for _ in range(count)]
    table["stuck_at_end"] = np.zeros(count, dtype=bool)
    table["release_time"] = np.full(count, np.nan)
    table["release_constraint"] = np.full(count, "", dtype=object)
    for c in system.coordinates:
        table[f"release_{c}"] = np.full(count, np.nan)
    table["steps"] = np.where(started, steps, 0).astype(np.int64)
    if section is not None:
        _crossings(table, crossings, section, states, count, started)
    _settle(table, bool(angular.any()))
    missing = [key for key, value in table.items() if value is None]
    if missing:  # pragma: no cover - every column of the row is filled above
        raise AssertionError(f"columns not filled on the compiled path: {missing}")
    frame = pandas.DataFrame(columns)
    return pandas.concat([frame, pandas.DataFrame(table)], axis=1)


def _crossings(table: dict[str, Any], crossings: np.ndarray, section: Any, states: list[str], count: int,
               started: np.ndarray) -> None:
    """The section's crossings where its conditions hold, as lists per run."""
    keep = section.holds(crossings[:, 2:]) if len(crossings) else np.zeros(0, dtype=bool)
    kept = crossings[keep]
    owner = kept[:, 0].astype(np.int64)
    bounds = np.searchsorted(owner, np.arange(count + 1))  # the kernel writes them run by run, in order
    table["poincare_count"] = np.diff(bounds).astype(np.int64)
    table["poincare_t"] = [kept[bounds[r]: bounds[r + 1], 1].tolist() for r in range(count)]
    for j, name in enumerate(states):
        table[f"poincare_{name}"] = [kept[bounds[r]: bounds[r + 1], 2 + j].tolist() for r in range(count)]


def _settle(table: dict[str, Any], angular: bool) -> None:
    """run._settle for every row at once: a run is ok only if every value it reports is finite; then its
    outcome (flipped, no flip or ok; failed)."""
    status, reason = table["status"], table["reason"]
    keys = [*MEASURED, *(k for k in table if k.startswith(("final_", "drift_")))]
    bad_columns = {k: ~np.isfinite(np.asarray(table[k], dtype=float)) for k in keys}
    bad_columns["flip_time"] = table["flipped"] & ~np.isfinite(table["flip_time"])
    for k in table:
        if k.startswith("poincare_") and isinstance(table[k], list):
            bad_columns[k] = np.array([not np.all(np.isfinite(v)) for v in table[k]], dtype=bool)
    any_bad = np.any(np.array(list(bad_columns.values())), axis=0) & (status == "ok")
    for r in np.flatnonzero(any_bad):
        bad = [k for k, mask in bad_columns.items() if mask[r]]
        status[r] = "failed"
        reason[r] = (f"{', '.join(bad)} {'is' if len(bad) == 1 else 'are'} not finite at the end of the run "
                     "(an expression was evaluated outside its domain, or the motion diverged)")
    quiet = "no flip" if angular else "ok"
    flipped = np.where(table["flipped"], "flipped", quiet)
    table["outcome"] = np.where(status == "failed", "failed", flipped).astype(object)
