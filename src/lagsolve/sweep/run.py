"""Run one chunk of a sweep: the problem compiled once per process, then every run of the chunk.

A chunk is plain data (the problem's text, the settings, the inputs of its runs), so it can be
shipped to a Dask worker; the worker compiles the problem on first use and keeps it
(:func:`compiled`). Three paths:

* **compiled** (``Settings.engine == "compiled"``; no constraint, no friction contact, an explicit
  method; Numba installed): each run integrated alone by machine code (:mod:`lagsolve.sweep.native`)
  with the batched path's step control and measures, the GIL released; the chunk's table is built
  column by column from its arrays;
* **batched** (no friction contact, no unilateral constraint, an explicit method): every run of
  the chunk is integrated together by :func:`lagsolve.sweep.rk.integrate_batch`, with its own
  steps and error control, the right-hand side evaluated for all runs at once; holonomic
  constraints are projected onto after each accepted step (as ``simulate --coordinates full``);
* **per run** (stick–slip, release, implicit methods): the single-run integrator of ``lagsolve
  simulate`` (:func:`lagsolve.numeric.integrate.integrate_motion`, with the same minimal coordinates),
  one run after the other; the ``path`` column says so.
"""

from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from lagsolve.errors import LagsolveError
from lagsolve.problem.methods import DEFAULT, EXPLICIT
from lagsolve.sweep.spec import Section

if TYPE_CHECKING:
    from lagsolve.sweep.rk import Step

#: the ``path`` of a run on the compiled path (lagsolve.sweep.native)
COMPILED_PATH = "compiled"

#: samples a per-run integration keeps (the drift of the conserved quantities is measured on them)
FALLBACK_SAMPLES = 201


@dataclass(frozen=True)
class Settings:
    """How every run of a sweep is integrated."""

    t_end: float
    method: str = DEFAULT
    rtol: float = 1e-10
    atol: float = 1e-12
    section: Section | None = None
    engine: str = "numpy"  # "compiled": lagsolve.sweep.native where it applies; "numpy": rk.integrate_batch


@dataclass(frozen=True)
class Compiled:
    """A problem bound and compiled once in a process."""

    source: str
    system: Any  # NumericSystem with the file's parameter values
    batch: Any  # BatchSystem, or None where only the per-run path applies
    why_per_run: str
    initial: Mapping[str, float]
    angular: tuple[bool, ...]  # per coordinate: L depends on it, and L and the positions repeat when it grows by 2π
    conserved: tuple[str, ...]
    text: str = ""  # the problem's text (the compiled path is built from it on first use)
    natives: dict[str, Any] = dataclasses.field(default_factory=dict)  # "native" -> (NativeSystem or None, why)

    def native(self) -> tuple[Any, str]:
        """The compiled integrator of :mod:`lagsolve.sweep.native` (built on first use, then kept), or None and
        why the compiled path does not apply."""
        if "native" not in self.natives:
            from lagsolve.sweep.native import native_system

            self.natives["native"] = (None, self.why_per_run) if self.batch is None else native_system(self.system)
        found: tuple[Any, str] = self.natives["native"]
        return found


_CACHE: dict[tuple[str, str], Compiled] = {}


def compiled(text: str, source: str) -> Compiled:
    """The problem of ``text`` compiled, once per process (a Dask worker keeps it between chunks)."""
    key = (hashlib.sha256(text.encode("utf-8")).hexdigest(), source)
    found = _CACHE.get(key)
    if found is None:
        found = _compile(text, source)
        _CACHE.clear()  # one problem at a time: a long-lived worker does not collect them
        _CACHE[key] = found
    return found


def _compile(text: str, source: str) -> Compiled:
    import sympy

    from lagsolve.mechanics.analysis.analyse import monitored
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.numeric.system import bind
    from lagsolve.problem.load import load_text
    from lagsolve.sweep.batch import batch_system

    problem = load_text(text, source)
    form = matrix_form(problem, display=False)
    conserved, chart, _, energy_note = monitored(form)
    system = bind(form, {}, conserved, chart, energy_note)
    why = ""
    if system.contacts:
        why = "friction contacts (stick–slip restarts)"
    elif system.unilateral:
        why = "unilateral constraints (release events)"
    batch = batch_system(system) if not why else None
    model = form.model
    positions = [r for p in problem.particles for r in p.position]
    angular = []
    for q in model.coordinates:
        shifted = {q: q + 2 * sympy.pi}
        same = all(sympy.expand(e.xreplace(shifted) - e) == 0 for e in [model.lagrangian, *positions])
        # a cyclic angle (a turning tube's φ, a spherical pendulum's azimuth) goes round; it does not flip
        angular.append(bool(same) and sympy.diff(model.lagrangian, q) != 0)
    initial = dict(problem.simulation.initial) if problem.simulation is not None else {}
    return Compiled(source, system, batch, why, initial, tuple(angular), system.conserved_names, text)


def run_chunk(text: str, source: str, settings: Settings, inputs: Mapping[str, np.ndarray],
              start: int = 0) -> Any:
    """The result rows (a pandas DataFrame) of the runs ``inputs`` (one array per swept name).

    ``start`` numbers the runs (the ``run`` column), so chunks put together keep the sweep's order.
    """
    import pandas

    problem = compiled(text, source)
    count = len(next(iter(inputs.values())))
    native, not_compiled = (problem.native() if settings.engine == "compiled" and settings.method in EXPLICIT
                            else (None, ""))
    if native is not None:
        return _compiled_chunk(problem, native, settings, inputs, start)
    names = problem.system.parameter_names
    parameters = np.tile(problem.system.parameters, (count, 1))
    for name, values in inputs.items():
        if name in names:
            parameters[:, names.index(name)] = values
    starts, failures = _initial_states(problem, inputs, parameters, count)
    batched = problem.batch is not None and settings.method in EXPLICIT
    if batched:
        rows = _batched(problem, settings, parameters, starts, failures)
        for row in rows:  # the compiled path was asked for: why these runs are batched instead
            row["note"] = row["note"] or (f"not compiled: {not_compiled}" if not_compiled else "")
    else:
        why = problem.why_per_run or f"the {settings.method} method (implicit) is not batched"
        rows = _per_run(problem, settings, parameters, starts, failures, why)
    table = {"run": np.arange(start, start + count)}
    table.update({name: np.asarray(values, dtype=float) for name, values in inputs.items()})
    frame = pandas.DataFrame(table)
    return pandas.concat([frame, pandas.DataFrame(rows)], axis=1)



def _initial_states(problem: Compiled, inputs: Mapping[str, np.ndarray], parameters: np.ndarray,
                    count: int) -> tuple[np.ndarray, list[str]]:
    """Each run's whole initial state (dependent values completed from the constraints), or why it has none."""
    from lagsolve.numeric.initial import complete_initial

    system = problem.system
    n = system.n
    states = np.full((count, 2 * n), np.nan)
    failures = [""] * count
    swept = [name for name in inputs if name not in system.parameter_names]
    for r in range(count):
        given = {**problem.initial, **{name: float(inputs[name][r]) for name in swept}}
        own = dataclasses.replace(system, parameters=parameters[r], evaluations=[0])
        try:
            q0, qd0 = complete_initial(own, given, problem.source, field="initial state")
        except LagsolveError as error:
            failures[r] = str(error)
            continue
        states[r] = np.concatenate([q0, qd0])
    return states, failures


def _state_names(system: Any) -> list[str]:
    return [*system.coordinates, *(f"{c}_dot" for c in system.coordinates)]


def columns(problem: Compiled, settings: Settings, swept: Sequence[str]) -> dict[str, bool]:
    """The columns of the sweep's table, each with whether it is numeric, known before any run."""
    row = {"run": 0, **{name: 0.0 for name in swept}, **_empty_row(problem, settings, "")}
    return {k: isinstance(v, bool | int | float) for k, v in row.items()}


def _empty_row(problem: Compiled, settings: Settings, path: str) -> dict[str, Any]:
    system = problem.system
    row: dict[str, Any] = {"status": "failed", "reason": "", "outcome": "failed", "path": path, "note": "",
                           "t_final": np.nan}
    for name in _state_names(system):
        row[f"final_{name}"] = np.nan
    row.update({"max_residual": np.nan, "energy_conserved": bool(system.energy_conserved), "energy_drift": np.nan})
    for name in problem.conserved:
        row[f"drift_{name}"] = np.nan
    row.update({"flipped": False, "flip_time": np.nan, "stick_count": 0, "slip_count": 0, "stick_times": [],
                "slip_times": [],
                "stuck_at_end": False, "release_time": np.nan, "release_constraint": ""})
    for c in system.coordinates:
        row[f"release_{c}"] = np.nan
    row["steps"] = 0
    if settings.section is not None:
        row["poincare_count"] = 0
        row["poincare_t"] = []
        for name in _state_names(system):
            row[f"poincare_{name}"] = []
    return row


def _outcome(row: dict[str, Any], has_contacts: bool, angular: bool) -> str:
    if row["status"] == "failed":
        return "failed"
    if row["status"] == "released":
        return "released"
    if has_contacts:  # friction problems are mapped by their contacts (a turning tube's angle always "flips")
        return "stick" if row["stuck_at_end"] else "slip"
    if row["flipped"]:
        return "flipped"
    return "no flip" if angular else "ok"


def _drift(first: np.ndarray, worst: np.ndarray) -> np.ndarray:
    """max |v − v₀| / |v₀| from the largest deviation (absolute where v₀ is zero), as simulate reports it."""
    scale = np.where(np.abs(first) > 1e-300, np.abs(first), 1.0)
    return worst / scale


def _batched(problem: Compiled, settings: Settings, parameters: np.ndarray, starts: np.ndarray,
             failures: list[str]) -> list[dict[str, Any]]:
    """The rows of the runs integrated together (:func:`lagsolve.sweep.rk.integrate_batch`); a run without an
    initial state keeps its empty row and the reason."""
    from lagsolve.sweep.rk import Tableau, integrate_batch

    ok = np.array([not f for f in failures], dtype=bool)
    rows = [_empty_row(problem, settings, "batched") for _ in range(len(starts))]
    for r in np.flatnonzero(~ok):
        rows[r]["reason"] = failures[r]
    index = np.flatnonzero(ok)
    if not len(index):
        return rows
    watch = _Watch(problem, settings.section, parameters[index], starts[index])
    with np.errstate(all="ignore"):
        t, y, steps, failed = integrate_batch(watch.rhs, starts[index], settings.t_end, Tableau.of(settings.method),
                                              settings.rtol, settings.atol, watch.accepted)
    names = _state_names(problem.system)
    ran = [rows[r] for r in index]
    for i, row in enumerate(ran):
        row["status"] = "failed" if failed[i] else "ok"
        row["reason"] = failed[i]
        row["t_final"] = float(t[i])
        for j, name in enumerate(names):
            row[f"final_{name}"] = float(y[i, j])
        row["steps"] = int(steps[i])
    watch.report(ran, names)
    for row in ran:
        _settle(row, False, bool(watch.angular.any()))
    return rows


class _Watch:
    """What the batched path measures along its runs (one row each), updated after every accepted step: the
    largest constraint residual, the largest deviations of the energy and the conserved quantities from their
    initial values, the first time an angle passes ±π, and the crossings of the Poincaré section. It also
    gives the right-hand side and projects onto the constraints."""

    def __init__(self, problem: Compiled, section: Section | None, p: np.ndarray, y0: np.ndarray) -> None:
        """The measures at the initial states ``y0`` (one run per row, with the parameters ``p``)."""
        self.problem, self.section, self.p = problem, section, p
        batch, n = problem.batch, problem.system.n
        self.batch, self.n = batch, n
        self.project = batch.m > 0
        self.angular = np.array(problem.angular, dtype=bool)
        live = len(y0)
        t0 = np.zeros(live)
        self.energy0 = batch.energy(t0, y0[:, :n], y0[:, n:], p)[:, 0]
        self.conserved0 = batch.conserved(t0, y0[:, :n], y0[:, n:], p)
        self.worst_energy = np.zeros(live)
        self.worst_conserved = np.zeros_like(self.conserved0)
        self.residual = batch.residual(t0, y0[:, :n], y0[:, n:], p)
        self.floor = batch.floors(t0, y0[:, :n], y0[:, n:], p)
        self.flipped = np.any(np.abs(y0[:, :n][:, self.angular]) > np.pi, axis=1)
        self.flip_time = np.where(self.flipped, 0.0, np.nan)
        self.crossings: list[list[np.ndarray]] = [[] for _ in range(live)]

    def rhs(self, t: np.ndarray, y: np.ndarray, which: np.ndarray) -> np.ndarray:
        """The derivative of the states ``y`` of the runs ``which``: velocities, then accelerations."""
        n = self.n
        qdd = self.batch.accelerations(t, y[:, :n], y[:, n:], self.p[which])
        return np.concatenate([y[:, n:], qdd], axis=1)

    def accepted(self, step: Step) -> np.ndarray | None:
        """Measure the accepted ``step``, stopping a run where a measure is
        not finite; the states projected onto the constraints, if there are any."""
        batch, n = self.batch, self.n
        which, t, y = step.rows, step.t_new, step.y_new
        q, qd, pw = y[:, :n], y[:, n:], self.p[which]
        now = batch.residual(t, q, qd, pw)
        self.residual[which] = np.maximum(self.residual[which], now)
        if self.section is not None:
            _crossings(step, self.section, self.crossings)
        if self.project:
            q, qd = batch.project(t, q, qd, pw, self.floor[which])
        with np.errstate(all="ignore"):
            energy = batch.energy(t, q, qd, pw)[:, 0]
            self.worst_energy[which] = np.maximum(self.worst_energy[which], np.abs(energy - self.energy0[which]))
            conserved = batch.conserved(t, q, qd, pw)
            if self.conserved0.shape[1]:
                self.worst_conserved[which] = np.maximum(self.worst_conserved[which],
                                                         np.abs(conserved - self.conserved0[which]))
        _fail_where_not_finite(step, [("the constraint residual", now), ("the energy", energy),
                                      *((f"the conserved quantity {name}", conserved[:, c])
                                        for c, name in enumerate(self.problem.conserved))])
        if self.angular.any():
            self._flips(step)
        return np.concatenate([q, qd], axis=1) if self.project else None

    def _flips(self, step: Step) -> None:
        """The time where an angle of a run that has not flipped yet first passes ±π within ``step``."""
        n, angular, which = self.n, self.angular, step.rows
        over = np.any(np.abs(step.y_new[:, :n][:, angular]) > np.pi, axis=1) & ~self.flipped[which]
        if over.any():
            subset = np.flatnonzero(over)
            self.flip_time[which[subset]] = _first_root(step, subset, lambda y: np.max(
                np.abs(y[:, :n][:, angular]), axis=1) - np.pi)
            self.flipped[which[subset]] = True

    def report(self, rows: list[dict[str, Any]], names: list[str]) -> None:
        """Put the measures into the ``rows`` (one per run; ``names``: the state's components)."""
        energy_drift = _drift(self.energy0, self.worst_energy)
        conserved_drift = _drift(self.conserved0, self.worst_conserved)
        for i, row in enumerate(rows):
            row["max_residual"] = float(self.residual[i])
            row["energy_drift"] = float(energy_drift[i])
            for c, name in enumerate(self.problem.conserved):
                row[f"drift_{name}"] = float(conserved_drift[i, c])
            row["flipped"] = bool(self.flipped[i])
            row["flip_time"] = float(self.flip_time[i])
            if self.section is not None:
                found = self.crossings[i]
                row["poincare_count"] = len(found)
                row["poincare_t"] = [float(c[0]) for c in found]
                for j, name in enumerate(names):
                    row[f"poincare_{name}"] = [float(c[1 + j]) for c in found]


def _fail_where_not_finite(step: Any, monitored: list[tuple[str, np.ndarray]]) -> None:
    """Stop each run whose monitored values (one per row of the step) are not all finite at this step:
    its state may still be finite (a projection that could not move it back onto ψ = 0, log of a
    negative number in the residual only), but nothing measured from there on would mean anything."""
    bad = [(what, ~np.isfinite(values)) for what, values in monitored]
    for i in np.flatnonzero(np.any([mask for _, mask in bad], axis=0)):  # usually none: no loop over the rows
        names = [what for what, mask in bad if mask[i]]
        step.fail(np.array([i]), f"{' and '.join(names)} {'is' if len(names) == 1 else 'are'} no longer finite at "
                                 f"t = {step.t_new[i]:.6g} (an expression was evaluated outside its domain, such as "
                                 "log or sqrt of a number <= 0, or the motion diverged)")


#: the columns of a row that must be finite for the run to count as ok (or released); besides these, every
#: final_<state>, drift_<quantity>, and for a release its time and state
MEASURED = ("t_final", "max_residual", "energy_drift")


def _settle(row: dict[str, Any], has_contacts: bool, angular: bool) -> None:
    """The one rule for the status of a row: a run is ``ok`` (or ``released``) only if every value it reports
    is finite; otherwise it failed, and the reason names the columns that are not. Then its outcome."""
    if row["status"] != "failed":
        keys = [*MEASURED, *(k for k in row if k.startswith(("final_", "drift_")))]
        if row["status"] == "released":
            keys += ["release_time", *(k for k in row if k.startswith("release_") and k != "release_constraint")]
        if row["flipped"]:
            keys.append("flip_time")
        bad = [k for k in dict.fromkeys(keys) if not np.isfinite(row[k])]
        bad += [k for k in row if k.startswith("poincare_") and isinstance(row[k], list)
                and not np.all(np.isfinite(row[k]))]
        if bad:
            row["status"] = "failed"
            row["reason"] = (f"{', '.join(bad)} {'is' if len(bad) == 1 else 'are'} not finite at the end of the run "
                             "(an expression was evaluated outside its domain, or the motion diverged)")
    row["outcome"] = _outcome(row, has_contacts, angular)


def _first_root(step: Any, subset: np.ndarray, g: Any) -> np.ndarray:
    """For the steps ``subset`` where ``g`` (a function of states, one value per row) goes from ≤ 0 to
    > 0, the time where it first becomes > 0, by bisection on the dense output to machine precision."""
    dense = step.dense(subset)
    low, high = step.t_old[subset].copy(), step.t_new[subset].copy()
    for _ in range(64):
        middle = 0.5 * (low + high)
        above = g(dense(middle)) > 0
        low, high = np.where(above, low, middle), np.where(above, middle, high)
        if np.all(high - low <= 4 * np.finfo(float).eps * np.maximum(1.0, np.abs(high))):
            break
    return high


def _crossings(step: Any, section: Section, crossings: list[list[np.ndarray]]) -> None:
    """Record where each accepted step crosses the section: the root of the dense output's component
    located by bisection to machine precision, kept where the section's conditions hold there."""
    g_old = step.y_old[:, section.index] - section.value
    g_new = step.y_new[:, section.index] - section.value
    crossing = ((g_old < 0) & (g_new >= 0)) | ((g_old > 0) & (g_new <= 0))
    if not crossing.any():
        return
    subset = np.flatnonzero(crossing)
    sign = np.where(g_old[subset] < 0, 1.0, -1.0)
    times = _first_root(step, subset, lambda y: sign * (y[:, section.index] - section.value) + 0.0)
    states = step.dense(subset)(times)
    states[:, section.index] = section.value
    keep = section.holds(states)
    for k in np.flatnonzero(keep):
        crossings[step.rows[subset[k]]].append(np.concatenate([[times[k]], states[k]]))


def _per_run(problem: Compiled, settings: Settings, parameters: np.ndarray, starts: np.ndarray,
             failures: list[str], why: str) -> list[dict[str, Any]]:
    from lagsolve.numeric.integrate import AfterRelease, EventKind, integrate_motion

    system = problem.system
    n = system.n
    path = f"per run: {why}"
    names = _state_names(system)
    angular = np.array(problem.angular, dtype=bool)
    rows = []
    for r in range(len(starts)):
        row = _empty_row(problem, settings, path)
        rows.append(row)
        if failures[r]:
            row["reason"] = failures[r]
            continue
        own = dataclasses.replace(system, parameters=parameters[r], evaluations=[0])
        try:
            with np.errstate(all="ignore"):
                motion = integrate_motion(own, starts[r, :n], starts[r, n:], settings.t_end,
                                          samples=FALLBACK_SAMPLES, method=settings.method, rtol=settings.rtol,
                                          atol=settings.atol, after_release=AfterRelease.STOP)
        except LagsolveError as error:
            row["reason"] = str(error)
            continue
        release = next((e for e in motion.events if e.kind == EventKind.RELEASE), None)
        row["status"] = "released" if release is not None else "ok"
        row["t_final"] = float(motion.t[-1])
        for j, name in enumerate(names):
            row[f"final_{name}"] = float(motion.q[-1, j] if j < n else motion.qd[-1, j - n])
        row["max_residual"] = float(motion.stats["max_residual"])
        row["energy_drift"] = float(motion.stats["energy_drift"])
        for name in problem.conserved:
            row[f"drift_{name}"] = float(motion.stats["conserved_drift"].get(name, np.nan))
        over = np.flatnonzero(np.any(np.abs(motion.q[:, angular]) > np.pi, axis=1))
        row["flipped"] = bool(len(over))
        row["flip_time"] = float(motion.t[over[0]]) if len(over) else np.nan  # the first sample past π
        row["stick_times"] = [float(e.time) for e in motion.events if e.kind == EventKind.STICK]
        row["slip_times"] = [float(e.time) for e in motion.events if e.kind == EventKind.SLIP]
        row["stick_count"], row["slip_count"] = len(row["stick_times"]), len(row["slip_times"])
        row["stuck_at_end"] = bool(motion.stuck[-1].any()) if motion.stuck.size else False
        if release is not None:
            row["release_time"] = float(release.time)
            row["release_constraint"] = release.name
            for c in system.coordinates:
                row[f"release_{c}"] = float(release.state[c])
        row["steps"] = int(motion.stats["steps"])
        if settings.section is not None:
            row["note"] = "Poincaré crossings are recorded on the batched path only"
        rest = next((e for e in motion.events if e.kind == EventKind.REST), None)
        if rest is not None:  # t_final is then its time
            row["note"] = (f"contact {rest.name!r} comes to rest at t = {rest.time:.6g}, where friction that acts in a "
                           "plane is not modelled: the run stops there")
        _settle(row, bool(system.contacts), bool(angular.any()))
    return rows


# ---- the compiled path: a chunk's table built column by column from the compiled integrator's arrays ----


def _compiled_reason(code: int, t: float, measures: list[str]) -> str:
    """Why a run with the kernel's end ``code`` at time ``t`` failed (the batched path's words), or ""."""
    from lagsolve.sweep import kernel

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


def _compiled_chunk(problem: Compiled, native: Any, settings: Settings, inputs: Mapping[str, np.ndarray],
                   start: int) -> Any:
    """The result table (a pandas DataFrame) of the runs ``inputs`` on the compiled path."""
    import pandas

    from lagsolve.sweep import kernel

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
    template = _empty_row(problem, settings, COMPILED_PATH)
    conserved_names = [f"the conserved quantity {name}" for name in problem.conserved]
    reasons = []
    for r in range(count):
        if not failed[r]:
            reasons.append("")
            continue
        measures = ["the energy"] if not np.isfinite(worst_energy[r]) else []
        measures += [what for c, what in enumerate(conserved_names) if not np.isfinite(worst_conserved[r, c])]
        reasons.append(_compiled_reason(int(code[r]), float(t[r]), measures))
    table: dict[str, Any] = {key: None for key in template}
    table["status"] = np.where(failed, "failed", "ok").astype(object)
    table["reason"] = np.array(reasons, dtype=object)
    table["path"] = np.full(count, COMPILED_PATH, dtype=object)
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
        _compiled_crossings(table, crossings, section, states, count, started)
    _settle_columns(table, bool(angular.any()))
    missing = [key for key, value in table.items() if value is None]
    if missing:  # pragma: no cover - every column of the row is filled above
        raise AssertionError(f"columns not filled on the compiled path: {missing}")
    frame = pandas.DataFrame(columns)
    return pandas.concat([frame, pandas.DataFrame(table)], axis=1)


def _compiled_crossings(table: dict[str, Any], crossings: np.ndarray, section: Any, states: list[str], count: int,
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


def _settle_columns(table: dict[str, Any], angular: bool) -> None:
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
