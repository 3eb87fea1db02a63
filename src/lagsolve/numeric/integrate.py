"""Integrate a :class:`~lagsolve.numeric.system.NumericSystem` into a :class:`Trajectory`.

The state is ``y = (q, q̇)``; accelerations and multipliers come from the
augmented system at each evaluation. SciPy's solvers are stepped one accepted
step at a time (the same solvers ``solve_ivp`` uses), which allows

* **projection** after each accepted step of an explicit Runge–Kutta method:
  positions onto ψ(q, t) = 0 (least-norm Newton), velocities onto A q̇ + b = 0,
  so holonomic constraints integrated at acceleration level do not drift;
* **events**, each located on the step's dense output with Brent's method and
  followed by a restart of the integrator exactly there (no chattering, no tiny
  steps at a discontinuity):

  - *release*: a unilateral constraint holds while its multiplier is ≥ 0; where it
    reaches zero the run stops or continues without it;
  - *contact*: after a release, the motion comes back to the constraint (ψ < 0, the other side
    of a surface, a string longer than itself): an impact, which is not modelled, so the run
    stops there;
  - *stick*: a friction contact's sliding rate σ = w·q̇ (the relative velocity of the
    contact point along its tangent) reaches zero and the tangential force needed to
    hold it, |Φ|, is within μ_s N: the contact sticks (an extra row σ = 0 replaces
    kinetic friction);
  - *slip*: a sticking contact needs more than μ_s N: it slides again, in the
    direction the other forces push it;
  - a sliding rate that reaches zero without sticking reverses, and the kinetic
    friction force flips with it at that exact time.

Samples are taken from the dense output at evenly spaced times.
"""

from __future__ import annotations

import dataclasses
import math
import time as clock
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
from scipy import integrate, optimize

from lagsolve.enums import TextEnum
from lagsolve.errors import SimulationError
from lagsolve.numeric.active import ActiveSystem
from lagsolve.numeric.system import NumericSystem, rate_sign
from lagsolve.problem.methods import DEFAULT, EXPLICIT, METHODS

HOLD_TOLERANCE = 1e-12  # relative slack in |needed force| <= mu_s N when deciding to stick
#: the watched event functions (a release, a stick or a slip) are looked at least this many times over a run,
#: inside steps longer than t_end / WATCH_POINTS too
WATCH_POINTS = 250
#: the residual of a holonomic constraint (of scale 1 or more) below which a state is not projected onto it
PROJECTED = 1e-15
#: how far (relative to its scale) a released unilateral constraint's ψ must go below zero to count as reached
#: again: at the release ψ leaves zero with its first two rates zero, and rounding must not count as a return
RETURN_DEPTH = 1e-9
#: a contact that slides in a plane counts as at rest once its speed is this fraction of the one at the start
REST = 1e-9


def projection_floors(scales: np.ndarray) -> np.ndarray:
    """The residual below which a state is not projected onto each constraint of the given scales
    (:func:`~lagsolve.numeric.system.surface_scales`): :data:`PROJECTED`, scaled down for a scale below 1."""
    return PROJECTED * np.minimum(1.0, scales)


class EventKind(TextEnum):
    """What changed the equations during a run (:class:`Event` ``kind``)."""

    RELEASE = "release"
    CONTACT = "contact"  # a released unilateral constraint is reached again: the run stops there
    STICK = "stick"
    SLIP = "slip"
    REST = "rest"  # a contact that slides in a plane comes to rest: its friction is not modelled there, the run stops


class AfterRelease(TextEnum):
    """What a run does when a unilateral constraint lets go (``--after-release``)."""

    STOP = "stop"
    CONTINUE = "continue"


@dataclass(frozen=True)
class Event:
    """Something that changed the equations at ``time``.

    ``kind`` is "release" (a unilateral constraint lost contact), "contact" (after a release the
    motion came back to it: an impact, not modelled, so the run stopped), "stick" or "slip"
    (a friction contact), "rest" (a contact that slides in a plane came to rest, where its friction is
    not modelled: the run stopped); ``name`` the constraint or contact; ``action`` "stopped",
    "released", "stuck" or "slipped".
    """

    time: float
    kind: EventKind
    name: str
    state: Mapping[str, float]
    action: str

    @property
    def constraint(self) -> str:
        return self.name


@dataclass(frozen=True)
class RunStats(Mapping[str, Any]):
    """What one run did: the integrator and its tolerances, its work, the largest constraint residual,
    whether the energy is conserved (and why not), the coordinates it integrated, and the relative drift
    of the energy and of each monitored conserved quantity.

    A typed record; it also reads as a mapping (``stats["steps"]``, ``dict(stats)``) by field name.
    """

    method: str
    rtol: float
    atol: float
    steps: int
    evaluations: int
    solver_evaluations: int
    wall_time: float
    max_residual: float
    energy_conserved: bool
    energy_note: str
    coordinates: str
    projected: bool
    energy_drift: float = math.nan
    conserved_drift: Mapping[str, float] = field(default_factory=dict)
    #: the time of a release the run went on from (NaN without one): the drifts are measured up to it, since the
    #: conserved quantities are those of the system with every constraint held
    conserved_until: float = math.nan

    def __getitem__(self, key: str) -> Any:
        if key not in _RUN_STATS:
            raise KeyError(key)
        return getattr(self, key)

    def __iter__(self) -> Iterator[str]:
        return iter(_RUN_STATS)

    def __len__(self) -> int:
        return len(_RUN_STATS)


_RUN_STATS = tuple(f.name for f in fields(RunStats))


@dataclass(frozen=True)
class Trajectory:
    """A simulated motion. Arrays have one row per sample time.

    ``q``, ``qd`` shape (samples, n); ``multipliers`` and ``magnitudes`` shape
    (samples, m) in constraint order (λ = 0 and magnitude 0 after release);
    ``normal_forces``, ``stuck`` and ``friction`` shape (samples, contacts) for friction contacts
    (``friction``: see :meth:`NumericSystem.friction_forces`);
    ``energy`` the Jacobi integral h = Σ q̇ ∂L/∂q̇ − L; ``residual`` the largest
    constraint violation of the integrated state before projection; ``positions``
    shape (samples, total particle components).
    """

    t: np.ndarray
    coordinates: tuple[str, ...]
    constraints: tuple[str, ...]
    q: np.ndarray
    qd: np.ndarray
    multipliers: np.ndarray
    magnitudes: np.ndarray
    contacts: tuple[str, ...]
    normal_forces: np.ndarray
    stuck: np.ndarray
    energy: np.ndarray
    conserved: Mapping[str, np.ndarray]
    residual: np.ndarray
    positions: np.ndarray
    particles: tuple[tuple[str, int], ...]
    events: tuple[Event, ...]
    stats: RunStats
    friction: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))

    def __repr__(self) -> str:
        span = f"t = {float(self.t[0]):g} to {float(self.t[-1]):g}" if len(self.t) else "no samples"
        return f"<Trajectory of {', '.join(self.coordinates)}: {len(self.t)} samples, {span}, {self.stats.method}>"


def integrate_motion(system: NumericSystem, q0: np.ndarray, qd0: np.ndarray, t_end: float, *,
                     samples: int = 1001, method: str = DEFAULT, rtol: float = 1e-10, atol: float = 1e-12,
                     max_step: float = np.inf, project: bool = True, minimal: bool = True,
                     after_release: str = "stop", progress: Callable[[float], None] | None = None) -> Trajectory:
    """Integrate from ``(q0, qd0)`` at t = 0 to ``t_end``.

    Parameters
    ----------
    method : str
        One of DOP853 (default), RK45, RK23 (explicit; projected after every step),
        Radau, BDF, LSODA (implicit, for stiff problems; samples are projected).
    minimal : bool
        Integrate in minimal coordinates when the system has a chart (the constraints solved
        in closed form): the state is the independent coordinates and velocities, and the
        dependent ones follow exactly. After a release the run goes on in all coordinates.
    after_release : {"stop", "continue"}
        What to do when a unilateral constraint's force reaches zero.

    Raises
    ------
    SimulationError
        When the integrator fails or the system becomes singular.
    """
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}")
    if not (t_end > 0 and np.isfinite(t_end)):
        raise ValueError("t_end must be a positive number")
    m, k = system.m, len(system.contacts)
    run = ActiveSystem(system, np.ones(m, dtype=bool), np.zeros(k, dtype=bool), np.zeros(k), project,
                       floor=projection_floors(system.surface_scales(0.0, q0, qd0)),
                       resting=REST * system.speeds(0.0, q0, qd0, system.parameters),
                       turning=np.zeros(len(system.planar), dtype=bool))
    coordinates = _coordinates(run, q0, qd0, minimal)
    options = _Options(method, t_end, rtol, atol, max_step, project, after_release, progress)
    record = _Record(np.linspace(0.0, t_end, samples), t_end)
    start = clock.perf_counter()
    record.max_residual = run.residual(0.0, q0, qd0)
    solver, stopped = _segments(run, record, options, np.concatenate([q0, qd0]))
    if record.next_sample < samples and not stopped:
        assert solver is not None  # the run ended with a segment that reached t_end
        y_end = run.full(t_end, solver.y)
        _check_finite(run, t_end, y_end, record.last)
        record.rows.append(_sample(run, t_end, y_end))
    if progress is not None:
        progress(t_end)
    if system.chart is not None and minimal and run.chart is None:
        coordinates += "; all, projected onto the constraints after each step, once a constraint was released"
    return _trajectory(system, record.rows, record.events, RunStats(
        method=method, rtol=rtol, atol=atol, steps=record.steps, evaluations=system.evaluations[0],
        solver_evaluations=record.nfev, wall_time=clock.perf_counter() - start, max_residual=record.max_residual,
        energy_conserved=system.energy_conserved, energy_note=system.energy_note,
        coordinates=coordinates, projected=bool(m) and run.chart is None,
    ))


@dataclass(frozen=True)
class _Options:
    """How :func:`integrate_motion` was asked to integrate."""

    method: str
    t_end: float
    rtol: float
    atol: float
    max_step: float
    project: bool
    after_release: str
    progress: Callable[[float], None] | None

    @property
    def explicit(self) -> bool:
        return self.method in EXPLICIT


@dataclass
class _Record:
    """What a run has gathered so far: its samples and events, its work, the largest constraint residual, and
    the last state found finite (for a message)."""

    times: np.ndarray
    t_end: float
    rows: list[tuple] = field(default_factory=list)
    events: list[Event] = field(default_factory=list)
    last: tuple[float, np.ndarray] | None = None
    next_sample: int = 0
    steps: int = 0
    nfev: int = 0
    max_residual: float = 0.0

    def reached(self, run: ActiveSystem, t: float, y: np.ndarray, rhs: bool = False) -> None:
        """Note a state the run reached, after checking it (or, with ``rhs``, its accelerations) finite."""
        _check_finite(run, t, y, self.last, rhs=rhs)
        self.last = (float(t), y)

    def take_samples(self, run: ActiveSystem, dense: Callable[[float], np.ndarray], t_stop: float) -> None:
        """Sample the dense output at every sample time not taken yet up to ``t_stop``."""
        times = self.times
        while self.next_sample < len(times) and times[self.next_sample] <= t_stop + 1e-12 * max(1.0, self.t_end):
            y_sample = dense(times[self.next_sample])
            _check_finite(run, times[self.next_sample], y_sample, self.last)
            self.rows.append(_sample(run, times[self.next_sample], y_sample))
            self.last = (float(times[self.next_sample]), y_sample)
            self.next_sample += 1


def _coordinates(run: ActiveSystem, q0: np.ndarray, qd0: np.ndarray, minimal: bool) -> str:
    """Put ``run`` in minimal coordinates when asked and the system has a chart; say which coordinates
    it integrates."""
    system = run.system
    if not (minimal and system.chart is not None):
        return "all, projected onto the constraints after each step" if system.m else "all"
    run.chart = system.chart
    run.extended = system.chart.extended(0.0, q0, qd0, system.parameters)
    names = np.array(system.coordinates)
    independent = ", ".join(names[system.chart.independent]) or "none (the constraints prescribe the motion)"
    return f"minimal: {independent}, with {', '.join(names[system.chart.dependent])} from the constraints"


def _segments(run: ActiveSystem, record: _Record, options: _Options, y0: np.ndarray) -> tuple[Any, bool]:
    """Integrate from ``y0`` at t = 0, restarting the integrator at each event, until ``t_end`` or an event
    that stops the run; return the last integrator (None when none ran) and whether the run stopped early."""
    t0 = 0.0  # the whole state at each (re)start is (t0, y0)
    _start_contacts(run, t0, y0, record.events)
    solver = None
    while True:
        let_go = _let_go(run, record, t0, y0, options.after_release)
        if let_go is not None:
            if let_go:
                return solver, True
            continue
        solver, restart = _segment(run, record, options, t0, y0)
        if restart is None:
            return solver, False
        t0, y0, stopped = restart
        if stopped:
            return solver, True


def _let_go(run: ActiveSystem, record: _Record, t0: float, y0: np.ndarray, after_release: str) -> bool | None:
    """A unilateral constraint that would have to pull at ``(t0, y0)`` loses contact at once: the run stops
    there (True) or goes on without it (False). None when no active unilateral constraint pulls."""
    system = run.system
    pulling = [j for j in system.unilateral if run.active[j] and run.solve(t0, y0)[1][j] < 0]
    if not pulling:
        return None
    stop = after_release == AfterRelease.STOP
    record.events.append(Event(float(t0), EventKind.RELEASE, system.constraints[pulling[0]], _state(system, y0),
                               "stopped" if stop else "released"))
    if stop:
        record.rows.append(_sample(run, t0, y0))
        return True
    _release(run, pulling[0], t0, y0)
    return False


def _segment(run: ActiveSystem, record: _Record, options: _Options, t0: float,
             y0: np.ndarray) -> tuple[Any, tuple[float, np.ndarray, bool] | None]:
    """One integrator run from ``(t0, y0)`` until ``t_end`` or the first event; return the integrator and,
    after an event, where to restart and whether the run stops there (None when it reached ``t_end``)."""
    record.reached(run, t0, y0, rhs=True)  # at a (re)start: a NaN step size would make SciPy loop
    solver = getattr(integrate, options.method)(run.rhs, t0, run.local(y0), options.t_end, rtol=options.rtol,
                                                atol=options.atol, max_step=options.max_step)
    watch = _watch(run, t0, y0)
    restart = None
    while solver.status == "running" and restart is None:
        restart, watch = _step(run, record, options, solver, watch)
    record.nfev += solver.nfev
    return solver, restart


def _step(run: ActiveSystem, record: _Record, options: _Options, solver: Any,
          watch_old: dict) -> tuple[tuple[float, np.ndarray, bool] | None, dict]:
    """One accepted step and the samples in it, up to the first event in it: after an event, where to
    restart and whether the run stops there; without one, None (the step's end projected onto the
    constraints). Also the watched values at the step's end."""
    message = solver.step()
    if solver.status == "failed":
        _check_finite(run, solver.t, run.full(solver.t, solver.y), record.last, rhs=True)
        raise SimulationError(f"the integrator ({options.method}) failed at t = {solver.t:.6g}: {message}")
    record.steps += 1
    t_old, t_new = solver.t_old, solver.t
    dense = _whole(run, solver.dense_output())
    y_new = run.full(t_new, solver.y)
    watch_new = _watch(run, t_new, y_new)
    event = _first_event(run, dense, t_old, t_new, watch_old, watch_new, options.t_end / WATCH_POINTS)
    t_stop = event[0] if event is not None else t_new
    record.take_samples(run, dense, t_stop)
    record.reached(run, t_stop, y_new if event is None else dense(t_stop))
    if event is not None:
        t0, y0, stopped = _handle(run, event, dense, record.events, options.after_release)
        if stopped:
            record.rows.append(_sample(run, t0, y0))
        return (t0, y0, stopped), watch_new
    n = run.system.n
    record.max_residual = max(record.max_residual, run.residual(t_new, y_new[:n], y_new[n:]))
    if run.turning.any():  # watched for rest again once it slides off
        speeds = run.system.speeds(t_new, y_new[:n], y_new[n:], run.system.parameters)
        run.turning &= ~(speeds > 2 * run.resting)
        watch_new = _watch(run, t_new, y_new)
    watch_new = _projected_step(run, record, options, solver, y_new, watch_new)
    if options.progress is not None:
        options.progress(t_new)
    return None, watch_new


def _projected_step(run: ActiveSystem, record: _Record, options: _Options, solver: Any, y_new: np.ndarray,
                    watch: dict) -> dict:
    """After an explicit method's step, with constraints integrated in all coordinates or contacts stuck: the
    step's end projected onto them, and the integrator restarted from there. The watched values there."""
    if not (options.explicit and options.project and ((run.system.m and run.chart is None) or run.stuck.any())):
        return watch
    t_new, n = solver.t, run.system.n
    q, qd = run.projected(t_new, y_new[:n], y_new[n:])
    y_new = np.concatenate([q, qd])
    record.reached(run, t_new, y_new)
    solver.y = run.local(y_new)
    solver.f = run.rhs(t_new, solver.y)
    return _watch(run, t_new, y_new)


def _check_finite(run: ActiveSystem, t: float, y: np.ndarray, last: tuple[float, np.ndarray] | None,
                  rhs: bool = False) -> None:
    """Stop with a :class:`SimulationError` at a state (or, with ``rhs``, accelerations) that is not finite.

    NaN or inf means an expression was evaluated outside its domain (log or sqrt of a number
    ≤ 0, a division by zero) or the motion diverged; nothing computed from there on would mean
    anything, so the run stops at the first such state and says where.
    """
    finite = bool(np.all(np.isfinite(y)))
    if finite and not rhs:
        return  # the common case, at every step: nothing more to do
    system = run.system
    names = [*system.coordinates, *(f"{c}_dot" for c in system.coordinates)]
    bad = [] if finite else [name for name, v in zip(names, y, strict=True) if not np.isfinite(v)]
    if not bad and rhs:
        with np.errstate(all="ignore"):
            try:
                accelerations = run.solve(t, y)[0]
            except SimulationError:
                return
        bad = [f"{c}_ddot" for c, v in zip(system.coordinates, accelerations, strict=True) if not np.isfinite(v)]
    what = ""
    if bad:
        what = f"{', '.join(bad)} {'is not a finite number' if len(bad) == 1 else 'are not finite numbers'}"
    if not what:
        return
    state = ", ".join(f"{name} = {v:.6g}" for name, v in zip(names, y, strict=True))
    text = f"the state is no longer finite at t = {t:.10g} ({state}): {what}"
    if last is not None:
        previous = ", ".join(f"{name} = {v:.6g}" for name, v in zip(names, last[1], strict=True))
        text += f"; the last finite state was at t = {last[0]:.10g} ({previous})"
    raise SimulationError(text + ". An expression was evaluated outside its domain (log or sqrt of a number "
                          "<= 0, a division by zero) or the motion diverged; the run stops there. Shorten t_end, "
                          "change the initial state, or check the problem's expressions for where they hold")


def _whole(run: ActiveSystem, dense: Callable[[float], np.ndarray]) -> Callable[[float], np.ndarray]:
    """The step's dense output as whole states."""
    if run.chart is None:
        return dense
    return lambda tau: run.full(tau, dense(tau))


def _release(run: ActiveSystem, j: int, t: float, y: np.ndarray) -> None:
    """Constraint ``j`` no longer holds at ``(t, y)``; minimal coordinates that used it no longer describe the
    motion. A holonomic one is watched from then on for the motion coming back to it."""
    run.active[j] = False
    run.chart = None
    system = run.system
    if j in system.holonomic:
        n = system.n
        run.returning[j] = RETURN_DEPTH * system.surface_scales(t, y[:n], y[n:])[system.holonomic.index(j)]


def _start_contacts(run: ActiveSystem, t: float, y: np.ndarray, events: list[Event]) -> None:
    """At the start, the contacts at rest stick if they can; otherwise they slide the way they are pushed.

    Every contact at rest is held first; then, one at a time, the one whose holding force most exceeds
    μ_s N is let go to slide (the others' forces change with it), until every contact still held holds.
    """
    system = run.system
    resting = []
    for c, sticks in enumerate(system.sticks):
        if not sticks:
            continue
        w = system.sliding_parts(t, y[: system.n], y[system.n:])[c][0]
        sign = rate_sign(w, y[system.n:], 0.0)
        if sign != 0.0:
            run.direction[c] = sign
        else:
            resting.append(c)
            run.stuck[c] = True
    for _ in range(len(resting)):
        held = [c for c in resting if run.stuck[c]]
        margins = {c: run.holding_margin(t, y, c) for c in held}
        slipping = [c for c, (margin, needed) in margins.items() if margin < -HOLD_TOLERANCE * max(1.0, abs(needed))]
        if not slipping:
            break
        worst = min(slipping, key=lambda c: margins[c][0] / max(1.0, abs(margins[c][1])))
        run.stuck[worst] = False
        run.direction[worst] = -np.sign(margins[worst][1])
    for c in resting:
        if run.stuck[c]:
            events.append(Event(float(t), EventKind.STICK, system.contact_names[c], _state(system, y), "stuck"))


def _watch(run: ActiveSystem, t: float, y: np.ndarray) -> dict[tuple[str, int], float]:
    """The event functions at a state: each changes sign where its event happens."""
    system = run.system
    values: dict[tuple[str, int], float] = {}
    if system.unilateral:
        lam = run.solve(t, y)[1]
        for j in system.unilateral:
            if run.active[j]:
                values[(EventKind.RELEASE, j)] = float(lam[j])
    if run.returning:
        n = system.n
        psi = system.position_residual(t, y[:n], y[n:], system.parameters)
        for j, depth in run.returning.items():
            values[(EventKind.CONTACT, j)] = float(psi[system.holonomic.index(j)]) + depth
    if run.resting.size:
        for i, speed in enumerate(system.speeds(t, y[:system.n], y[system.n:], system.parameters)):
            if not run.turning[i]:
                values[(EventKind.REST, i)] = float(speed - run.resting[i])
    for c, sticks in enumerate(system.sticks):
        if not sticks:
            continue
        if run.stuck[c]:
            values[(EventKind.SLIP, c)] = run.holding_margin(t, y, c)[0]
        else:
            values[(EventKind.STICK, c)] = float(run.direction[c] * run.rate(t, y, c))
    return values


def _first_event(run: ActiveSystem, dense: Any, t_old: float, t_new: float, old: dict, new: dict,
                 spacing: float = np.inf) -> tuple | None:
    """The earliest (time, kind, index) at which a watched function goes from ≥ 0 to < 0 (≤ 0 for a rate).

    A step longer than ``spacing`` is looked at every ``spacing`` on its dense output too: an event function can
    go negative and back within one step that the state's error allowed (a ball on a plate that the constraint
    moves, with no coordinate left to integrate, takes its whole run in one step)."""
    if not old or t_new - t_old <= spacing:
        return _crossing(run, dense, t_old, t_new, old, new)
    pieces = int(np.ceil((t_new - t_old) / spacing))
    times = [*np.linspace(t_old, t_new, pieces + 1)[1:-1], t_new]
    t_before = t_old
    for t_mid in times:
        watched = new if t_mid == t_new else _watch(run, t_mid, dense(t_mid))
        found = _crossing(run, dense, t_before, t_mid, old, watched)
        if found is not None:
            return found
        t_before, old = t_mid, watched
    return None


def _crossing(run: ActiveSystem, dense: Any, t_old: float, t_new: float, old: dict, new: dict) -> tuple | None:
    """:func:`_first_event` between two times at which the watched functions are known."""
    first = None
    for key, before in old.items():
        after = new.get(key)
        if after is None:
            continue
        kind, index = key
        crossed = before >= 0 > after if kind != EventKind.STICK else before > 0 >= after
        if not crossed:
            continue

        def g(tau: float, key: tuple = key) -> float:
            return _watch(run, tau, dense(tau))[key]

        exact = g(t_new) == 0.0
        root = t_new if exact else optimize.brentq(g, t_old, t_new, xtol=1e-14, rtol=4 * np.finfo(float).eps)
        if first is None or root < first[0]:
            first = (root, kind, index)
    return first


def _handle(run: ActiveSystem, event: tuple, dense: Any, events: list[Event], after_release: str
            ) -> tuple[float, np.ndarray, bool]:
    """Apply an event; returns the restart time and state, and whether the run stops there."""
    system, n = run.system, run.system.n
    t, kind, index = event
    y = dense(t)
    if kind == EventKind.STICK:
        run.stuck[index] = True  # the projection below then puts the sliding rate at zero
    q, qd = run.projected(t, y[:n], y[n:])
    y = np.concatenate([q, qd])
    if kind == EventKind.RELEASE:
        stop = after_release == AfterRelease.STOP
        events.append(Event(float(t), EventKind.RELEASE, system.constraints[index], _state(system, y),
                            "stopped" if stop else "released"))
        if not stop:
            _release(run, index, t, y)
        return t, y, stop
    if kind == EventKind.REST and run.turns(t, y, index):
        run.turning[index] = True
        return t, y, False  # its velocity only passes through zero, and kinetic friction turns with it
    if kind in (EventKind.CONTACT, EventKind.REST):
        name = system.constraints[index] if kind == EventKind.CONTACT else system.contact_names[system.planar[index]]
        events.append(Event(float(t), kind, name, _state(system, y), "stopped"))
        return t, y, True
    if kind == EventKind.STICK:
        run.stuck[index] = True
        margin, needed = run.holding_margin(t, y, index)
        if margin >= -HOLD_TOLERANCE * max(1.0, abs(needed)):
            events.append(Event(float(t), EventKind.STICK, system.contact_names[index], _state(system, y), "stuck"))
        else:  # the rate only passes through zero: it reverses, and so does kinetic friction
            run.stuck[index] = False
            run.direction[index] = -np.sign(needed)
        return t, y, False
    _, needed = run.holding_margin(t, y, index)
    run.stuck[index] = False
    run.direction[index] = -np.sign(needed)
    events.append(Event(float(t), EventKind.SLIP, system.contact_names[index], _state(system, y), "slipped"))
    return t, y, False


def _state(system: NumericSystem, y: np.ndarray) -> dict[str, float]:
    n = system.n
    return {**{c: float(v) for c, v in zip(system.coordinates, y[:n], strict=True)},
            **{f"{c}_dot": float(v) for c, v in zip(system.coordinates, y[n:], strict=True)}}


def _sample(run: ActiveSystem, t: float, y: np.ndarray) -> tuple:
    n = run.system.n
    residual = run.residual(t, y[:n], y[n:])
    # in minimal coordinates the state is on the constraints by construction
    projecting = run.project and (run.chart is None or run.stuck.any())
    q, qd = run.projected(t, y[:n], y[n:]) if projecting else (y[:n].copy(), y[n:].copy())
    return (float(t), q, qd, residual, run.active.copy(), run.stuck.copy(), run.direction.copy())


def _trajectory(system: NumericSystem, rows: list, events: list[Event], stats: RunStats) -> Trajectory:
    p = system.parameters
    count, k = len(rows), len(system.contacts)
    t = np.array([r[0] for r in rows])
    q = np.array([r[1] for r in rows]).reshape(count, system.n)
    qd = np.array([r[2] for r in rows]).reshape(count, system.n)
    residual = np.array([r[3] for r in rows])
    stuck = np.array([r[5] for r in rows], dtype=bool).reshape(count, k)
    lam = np.zeros((count, system.m))
    mags = np.zeros((count, system.m))
    normals = np.zeros((count, k))
    friction = np.zeros((count, k))
    energy = np.zeros(count)
    conserved = np.zeros((count, len(system.conserved_names)))
    positions = np.zeros((count, sum(d for _, d in system.particles)))
    for i, (ti, qi, qdi, _, active, stuck_i, direction) in enumerate(rows):
        if system.m:
            _, lam[i], normals[i], sticking = system.solve_all(ti, qi, qdi, active, stuck_i, direction)
            if k:
                friction[i] = system.friction_forces(ti, qi, qdi, normals[i], stuck_i, sticking, direction)
            mags[i] = np.where(active, system.magnitudes(ti, qi, qdi, lam[i]), 0.0)
        energy[i] = system.energy(ti, qi, qdi, p)[0]
        if system.conserved_names:
            conserved[i] = system.conserved(ti, qi, qdi, p)
        if positions.shape[1]:
            positions[i] = system.positions(ti, qi, qdi, p)
    until = next((e.time for e in events if e.kind == EventKind.RELEASE and e.action == "released"), math.nan)
    held = slice(None) if math.isnan(until) else t <= until
    stats = dataclasses.replace(stats, energy_drift=_relative_drift(energy[held]), conserved_until=until,
                                conserved_drift={name: _relative_drift(conserved[held, c])
                                                 for c, name in enumerate(system.conserved_names)})
    return Trajectory(t, system.coordinates, system.constraints, q, qd, lam, mags, system.contact_names, normals,
                      stuck, energy, {name: conserved[:, c] for c, name in enumerate(system.conserved_names)},
                      residual, positions, system.particles, tuple(events), stats, friction)


def _relative_drift(values: np.ndarray) -> float:
    """max |v − v₀| / |v₀| (absolute when v₀ is zero)."""
    if values.size == 0 or not np.all(np.isfinite(values)):
        return float("nan")
    scale = abs(values[0]) if abs(values[0]) > 1e-300 else 1.0
    return float(np.max(np.abs(values - values[0])) / scale)
