r"""The compiled path's integrator, as plain Python: the template :mod:`lagsolve.sweep.native` compiles.

:mod:`lagsolve.sweep.native` writes a module made of this file's text followed by the problem's
functions (``matrices``, ``energy``, ``conserved``, printed from SymPy objects by SymPy's code
printer), and compiles it with Numba (``nogil``, cached on disk). The definitions printed after
this text replace the placeholders below, and Numba resolves a function's globals when it compiles
it, so :func:`integrate_runs` calls the problem's own functions. Nothing here is compiled by
itself; run as plain Python (with placeholders replaced) it gives the same numbers, slowly.

Each run is integrated alone, one after the other, with the step control of
:mod:`lagsolve.sweep.rk` (SciPy's ``solve_ivp``: its initial step, error norms and step factors):
a run's numbers depend on its own inputs only, never on the runs beside it. Along each run, after
every accepted step, it measures what the batched path measures (the largest deviation of the energy
and of the conserved quantities from their initial values, the first time an angle passes ±π) and
records the crossings of a Poincaré section, located by bisection on the method's dense output.

The problem's equations are ``M q̈ = F`` (no constraint: the compiled path is for problems in
minimal coordinates without friction contacts), solved by Gaussian elimination with partial pivoting.
"""

from __future__ import annotations

import math
from collections import namedtuple
from typing import Any

import numpy as np

# how a run ended (codes of integrate_runs's ``code``; lagsolve.sweep.native turns them into reasons)
RUNNING, DONE, BAD_START, SMALL_STEP, NOT_FINITE, TOO_MANY, BAD_ENERGY, BAD_CONSERVED = 0, 1, 2, 3, 4, 5, 6, 7

SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0

# what the functions below share (Numba passes named tuples of arrays and numbers as they are)
#: scratch space: M and F, the stages, the dense output's coefficients, state-sized rows, conserved values
Work = namedtuple("Work", "mass force k dense vectors values")  # noqa: PYI024 - Numba takes collections' kind
#: the method's coefficients (SciPy's), its step-factor exponent, order and stage count
Method = namedtuple("Method", "a b c e e3 has_e3 exponent order stages dop853 a_extra c_extra d_rows powers")  # noqa: PYI024
#: per run: final time, state, steps, end code, energy at the start and its largest deviation, the same for
#: the conserved quantities, the first flip's time
Results = namedtuple("Results", "t y steps code energy0 worst_energy conserved0 worst_conserved flip_time")  # noqa: PYI024


def matrices(t: float, y: Any, p: Any, mass: Any, force: Any) -> None:  # pragma: no cover - replaced
    """Placeholder: fills the mass matrix ``mass`` (n, n) and the forcing ``force`` (n,) at the state ``y``."""
    raise NotImplementedError


def energy(t: float, y: Any, p: Any) -> float:  # pragma: no cover - replaced
    """Placeholder: the energy (Jacobi integral) at the state ``y``."""
    raise NotImplementedError


def conserved(t: float, y: Any, p: Any, out: Any) -> None:  # pragma: no cover - replaced
    """Placeholder: the conserved quantities at the state ``y``, into ``out``."""
    raise NotImplementedError


def derivative(t: float, y: Any, p: Any, out: Any, mass: Any, force: Any) -> None:
    """``out`` = (q̇, q̈) at ``y`` = (q, q̇): q̈ from ``M q̈ = F`` by Gaussian elimination with partial
    pivoting; NaN where M is singular."""
    n = mass.shape[0]
    matrices(t, y, p, mass, force)
    for i in range(n):
        out[i] = y[n + i]
    for col in range(n):
        pivot = col
        best = abs(mass[col, col])
        for row in range(col + 1, n):
            if abs(mass[row, col]) > best:
                best = abs(mass[row, col])
                pivot = row
        if not best > 0.0:
            for i in range(n):
                out[n + i] = math.nan
            return
        if pivot != col:
            for k in range(n):
                mass[col, k], mass[pivot, k] = mass[pivot, k], mass[col, k]
            force[col], force[pivot] = force[pivot], force[col]
        for row in range(col + 1, n):
            factor = mass[row, col] / mass[col, col]
            if factor != 0.0:
                for k in range(col, n):
                    mass[row, k] -= factor * mass[col, k]
                force[row] -= factor * force[col]
    for row in range(n - 1, -1, -1):
        total = force[row]
        for k in range(row + 1, n):
            total -= mass[row, k] * out[n + k]
        out[n + row] = total / mass[row, row]


def _finite(x: Any) -> bool:
    for v in x:  # noqa: SIM110 - a loop Numba compiles
        if not math.isfinite(v):
            return False
    return True


def _worst(a: float, b: float) -> float:
    """The larger of ``a`` and ``b``, NaN if either is (``np.maximum``: a measure that was not finite stays so)."""
    if math.isnan(a) or math.isnan(b):
        return math.nan
    return max(a, b)


def _ulp(t: float) -> float:
    """The distance from ``t`` ≥ 0 to the next float up (``np.nextafter(t, inf) - t``), without a call."""
    if t == 0.0:
        return 5e-324
    _, exponent = math.frexp(t)
    return math.ldexp(1.0, exponent - 53)


def _combine(k: Any, stages: int, weights: Any, i: int) -> float:
    """Σ_s w_s K[s, i] over the first ``stages`` stages, skipping zero weights (the order of rk._combine)."""
    total = 0.0
    for s in range(stages):
        w = weights[s]
        if w != 0.0:
            total += w * k[s, i]
    return total


def _weighted(k: Any, stages: int, weights: Any, row: int, out: Any) -> None:
    """``out[i]`` = Σ_s weights[row, s] K[s, i] over the first ``stages`` stages, for every i at once, in the
    order of :func:`_combine` (so the same numbers, with one pass over the weights)."""
    d = out.shape[0]
    for i in range(d):
        out[i] = 0.0
    for s in range(stages):
        w = weights[row, s]
        if w != 0.0:
            for i in range(d):
                out[i] += w * k[s, i]


def _initial_step(t0: float, y0: Any, f0: Any, p: Any, t_end: float, order: int, rtol: float, atol: float,
                  y1: Any, f1: Any, mass: Any, force: Any) -> float:
    """SciPy's ``select_initial_step`` (as rk._initial_step)."""
    d = len(y0)
    d0 = 0.0
    d1 = 0.0
    for i in range(d):
        scale = atol + abs(y0[i]) * rtol
        d0 += (y0[i] / scale) ** 2
        d1 += (f0[i] / scale) ** 2
    d0 = math.sqrt(d0 / d)
    d1 = math.sqrt(d1 / d)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, t_end)
    for i in range(d):
        y1[i] = y0[i] + h0 * f0[i]
    derivative(t0 + h0, y1, p, f1, mass, force)
    d2 = 0.0
    for i in range(d):
        scale = atol + abs(y0[i]) * rtol
        d2 += ((f1[i] - f0[i]) / scale) ** 2
    d2 = math.sqrt(d2 / d) / h0
    quiet = d1 <= 1e-15 and d2 <= 1e-15
    h1 = max(1e-6, h0 * 1e-3) if quiet else (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(min(100 * h0, h1), t_end)


def _dense_prepare(t_old: float, h: float, y_old: Any, y_new: Any, f_old: Any, f_new: Any, k: Any, stages: int,
                   dop853: bool, a_extra: Any, c_extra: Any, d_rows: Any, powers: Any, p: Any, coefficients: Any,
                   work: Any, dy: Any, mass: Any, force: Any) -> None:
    """The dense output's coefficients of one step into ``coefficients`` (rows; see :func:`_dense`). For DOP853
    the three extra stages are evaluated into ``k`` after the step's own (rows stages+1 ...)."""
    d = len(y_old)
    if dop853:
        for e in range(a_extra.shape[0]):
            s = stages + 1 + e
            for i in range(d):
                dy[i] = y_old[i] + _combine(k, s, a_extra[e], i) * h
            derivative(t_old + c_extra[e] * h, dy, p, work, mass, force)
            for i in range(d):
                k[s, i] = work[i]
        for i in range(d):
            delta = y_new[i] - y_old[i]
            coefficients[0, i] = delta
            coefficients[1, i] = h * f_old[i] - delta
            coefficients[2, i] = 2 * delta - h * (f_new[i] + f_old[i])
            for j in range(d_rows.shape[0]):
                coefficients[3 + j, i] = h * _combine(k, stages + 1 + a_extra.shape[0], d_rows[j], i)
    else:
        for j in range(powers.shape[1]):
            for i in range(d):
                coefficients[j, i] = _combine(k, stages + 1, powers[:, j], i)


def _dense(t: float, t_old: float, h: float, y_old: Any, coefficients: Any, rows: int, dop853: bool,
           out: Any) -> None:
    """The state at ``t`` within the step, from its dense output (rk.Step.dense's formulas)."""
    x = (t - t_old) / h
    d = len(y_old)
    if dop853:
        for i in range(d):
            value = 0.0
            for r in range(rows):
                value += coefficients[rows - 1 - r, i]
                value *= x if r % 2 == 0 else 1 - x
            out[i] = value + y_old[i]
    else:
        for i in range(d):
            value = 0.0
            power = 1.0
            for j in range(rows):
                power *= x
                value += coefficients[j, i] * power
            out[i] = y_old[i] + h * value


def _flip_excess(y: Any, angular: Any) -> float:
    """max |angle| − π over the angular coordinates."""
    worst = -math.inf
    for i in range(len(angular)):
        if angular[i]:
            worst = max(worst, abs(y[i]))
    return worst - math.pi


def _bisect(kind: int, sign: float, index: int, value: float, angular: Any, t_old: float, t_new: float, h: float,
            y_old: Any, coefficients: Any, rows: int, dop853: bool, out: Any) -> float:
    """The time within the step where g (kind 0: the flip excess; 1: sign·(y[index] − value)) first becomes
    > 0, by bisection on the dense output until the interval is 4 ulp wide (rk's _first_root, per run)."""
    low, high = t_old, t_new
    eps = 2.220446049250313e-16
    for _ in range(64):
        middle = 0.5 * (low + high)
        _dense(middle, t_old, h, y_old, coefficients, rows, dop853, out)
        g = _flip_excess(out, angular) if kind == 0 else sign * (out[index] - value) + 0.0
        if g > 0:
            high = middle
        else:
            low = middle
        if high - low <= 4 * eps * max(1.0, abs(high)):
            break
    return high


def integrate_runs(y0: Any, params: Any, t_end: float, rtol: float, atol: float, max_steps: int, a: Any, b: Any,
                   c: Any, e: Any, e3: Any, has_e3: bool, order: int, stages: int, dop853: bool, a_extra: Any,
                   c_extra: Any, d_rows: Any, powers: Any, angular: Any, section_index: int, section_value: float,
                   n_conserved: int) -> tuple[Any, ...]:
    """Integrate every run (row of ``y0``, parameters the row of ``params``) from t = 0 to ``t_end``.

    Returns ``(t, y, steps, code, energy0, worst_energy, conserved0, worst_conserved, flip_time, crossings,
    crossing_count)``: per run its final time and state, steps taken, how it ended (the codes above), the
    initial energy and its largest deviation, the same for the conserved quantities, the time it first
    flipped (NaN if never; 0 if it starts past ±π), and the section's crossings as rows (run, t, state...).
    """
    runs, d = y0.shape
    n = d // 2
    work = Work(np.empty((n, n)), np.empty(n), np.zeros((stages + 1 + a_extra.shape[0], d)),
                np.empty((3 + d_rows.shape[0] if dop853 else powers.shape[1], d)), np.empty((8, d)),
                np.empty(max(1, n_conserved)))
    method = Method(a, b.reshape((1, b.shape[0])), c, e.reshape((1, e.shape[0])), e3.reshape((1, e3.shape[0])),
                    has_e3, -1.0 / (order + 1), order, stages, dop853, a_extra, c_extra, d_rows, powers)
    out = Results(np.zeros(runs), np.full((runs, d), np.nan), np.zeros(runs, dtype=np.int64),
                  np.zeros(runs, dtype=np.int64), np.full(runs, np.nan), np.zeros(runs),
                  np.full((runs, n_conserved), np.nan), np.zeros((runs, n_conserved)), np.full(runs, np.nan))
    crossings = np.empty((16, d + 2))
    count = 0
    for r in range(runs):
        crossings, count = _run(r, y0[r], params[r], t_end, rtol, atol, max_steps, method, work, out, angular,
                                section_index, section_value, n_conserved, crossings, count)
    return (out.t, out.y, out.steps, out.code, out.energy0, out.worst_energy, out.conserved0,
            out.worst_conserved, out.flip_time, crossings[:count].copy(), count)


def _run(r: int, y0: Any, p: Any, t_end: float, rtol: float, atol: float, max_steps: int, method: Any, work: Any,
         out: Any, angular: Any, section_index: int, section_value: float, n_conserved: int, crossings: Any,
         count: int) -> tuple[Any, int]:
    """Integrate run ``r`` into ``out``; its section crossings appended to ``crossings`` (grown as needed)."""
    d = len(y0)
    y, f, y_new, f_new = work.vectors[0], work.vectors[1], work.vectors[2], work.vectors[3]
    for i in range(d):
        y[i] = y0[i]
    t = 0.0
    derivative(t, y, p, f, work.mass, work.force)
    out.energy0[r] = energy(t, y, p)
    conserved(t, y, p, work.values)
    for j in range(n_conserved):
        out.conserved0[r, j] = work.values[j]
    if _finite(y) and _flip_excess(y, angular) > 0:
        out.flip_time[r] = 0.0
    if not (_finite(y) and _finite(f)):
        out.code[r] = BAD_START
        return crossings, count
    h_abs = _initial_step(t, y, f, p, t_end, method.order, rtol, atol, y_new, f_new, work.mass, work.force)
    fresh, rejected = True, False
    steps, code = 0, RUNNING
    while code == RUNNING:
        min_step = 10 * _ulp(t)
        h = max(h_abs, min_step) if fresh else h_abs
        if h < min_step:
            code = SMALL_STEP
            break
        t_new = min(t + h, t_end)
        h = t_new - t
        _step(t, h, t_new, y, f, y_new, f_new, p, method, work)
        error = _error(work.k, method.stages, method.e, method.e3, method.has_e3, h, y, y_new, rtol, atol,
                       work.vectors[4], work.vectors[5])
        ok, h_abs = _control(error, h, rejected, method.exponent)
        rejected, fresh = not ok, ok
        if not ok:
            continue
        measure, crossings, count = _accepted(r, t, h, t_new, y, f, y_new, f_new, p, method, work, out, angular,
                                              section_index, section_value, n_conserved, crossings, count)
        t = t_new
        for i in range(d):
            y[i] = y_new[i]
            f[i] = f_new[i]
        steps += 1
        code = _ended(y, f, measure, t, t_end, steps, max_steps)
    out.t[r] = t
    for i in range(d):
        out.y[r, i] = y[i]
    out.steps[r] = steps
    out.code[r] = code
    return crossings, count


def _ended(y: Any, f: Any, measure: int, t: float, t_end: float, steps: int, max_steps: int) -> int:
    """How a run stands after an accepted step (as rk._advance decides, in its order)."""
    if not (_finite(y) and _finite(f)):
        return NOT_FINITE
    if measure != DONE:
        return measure
    if t >= t_end:
        return DONE
    if steps >= max_steps:
        return TOO_MANY
    return RUNNING


def _step(t: float, h: float, t_new: float, y: Any, f: Any, y_new: Any, f_new: Any, p: Any, method: Any,
          work: Any) -> None:
    """One step of the method from (t, y) to t_new: the new state, its derivative and the stages in work.k."""
    d = len(y)
    k, dy, stage = work.k, work.vectors[4], work.vectors[5]
    for i in range(d):
        k[0, i] = f[i]
    for s in range(1, method.stages):
        _weighted(k, s, method.a, s, dy)
        for i in range(d):
            dy[i] = y[i] + dy[i] * h
        derivative(t + method.c[s] * h, dy, p, stage, work.mass, work.force)
        for i in range(d):
            k[s, i] = stage[i]
    _weighted(k, method.stages, method.b, 0, y_new)
    for i in range(d):
        y_new[i] = y[i] + h * y_new[i]
    derivative(t_new, y_new, p, f_new, work.mass, work.force)
    for i in range(d):
        k[method.stages, i] = f_new[i]


def _control(error: float, h: float, rejected: bool, exponent: float) -> tuple[bool, float]:
    """Whether the step is accepted and the next step size (rk._control's rule)."""
    finite = math.isfinite(error)
    ok = finite and error < 1
    if error == 0:
        factor = MAX_FACTOR
    elif finite:
        factor = min(MAX_FACTOR, SAFETY * error ** exponent)
    else:
        factor = math.nan
    if rejected:
        factor = min(1.0, factor)
    if ok:
        return True, h * factor
    shrink = SAFETY * error ** exponent if finite and error != 0 else MIN_FACTOR
    return False, h * max(MIN_FACTOR, shrink)


def _accepted(r: int, t: float, h: float, t_new: float, y: Any, f: Any, y_new: Any, f_new: Any, p: Any,
              method: Any, work: Any, out: Any, angular: Any, section_index: int, section_value: float,
              n_conserved: int, crossings: Any, count: int) -> tuple[int, Any, int]:
    """Measure an accepted step of run ``r`` (as run._Watch.accepted): a section crossing, the energy and the
    conserved quantities, a first flip. Returns DONE or the code of a measure that is not finite, and the
    crossings."""
    prepared = False
    if section_index >= 0:
        g_old = y[section_index] - section_value
        g_new = y_new[section_index] - section_value
        if (g_old < 0 and g_new >= 0) or (g_old > 0 and g_new <= 0):
            _prepare(t, h, y, y_new, f, f_new, p, method, work)
            prepared = True
            crossings, count = _crossing(r, 1.0 if g_old < 0 else -1.0, t, h, t_new, y, method, work, angular,
                                         section_index, section_value, crossings, count)
    measure = DONE
    value = energy(t_new, y_new, p)
    out.worst_energy[r] = _worst(out.worst_energy[r], abs(value - out.energy0[r]))
    if not math.isfinite(value):
        measure = BAD_ENERGY
    conserved(t_new, y_new, p, work.values)
    for j in range(n_conserved):
        out.worst_conserved[r, j] = _worst(out.worst_conserved[r, j], abs(work.values[j] - out.conserved0[r, j]))
        if not math.isfinite(work.values[j]) and measure == DONE:
            measure = BAD_CONSERVED
    if math.isnan(out.flip_time[r]) and _flip_excess(y_new, angular) > 0:
        if not prepared:
            _prepare(t, h, y, y_new, f, f_new, p, method, work)
        out.flip_time[r] = _bisect(0, 1.0, 0, 0.0, angular, t, t_new, h, y, work.dense,
                                   work.dense.shape[0], method.dop853, work.vectors[6])
    return measure, crossings, count


def _prepare(t: float, h: float, y: Any, y_new: Any, f: Any, f_new: Any, p: Any, method: Any, work: Any) -> None:
    _dense_prepare(t, h, y, y_new, f, f_new, work.k, method.stages, method.dop853, method.a_extra, method.c_extra,
                   method.d_rows, method.powers, p, work.dense, work.vectors[5], work.vectors[4], work.mass,
                   work.force)


def _crossing(r: int, sign: float, t: float, h: float, t_new: float, y: Any, method: Any, work: Any, angular: Any,
              section_index: int, section_value: float, crossings: Any, count: int) -> tuple[Any, int]:
    """Append the crossing of the section within the step (time, then the state there) to ``crossings``."""
    d = len(y)
    probe = work.vectors[6]
    rows = work.dense.shape[0]
    when = _bisect(1, sign, section_index, section_value, angular, t, t_new, h, y, work.dense, rows, method.dop853,
                   probe)
    _dense(when, t, h, y, work.dense, rows, method.dop853, probe)
    probe[section_index] = section_value
    if count == crossings.shape[0]:
        grown = np.empty((2 * count, d + 2))
        grown[:count] = crossings
        crossings = grown
    crossings[count, 0] = r
    crossings[count, 1] = when
    for i in range(d):
        crossings[count, 2 + i] = probe[i]
    return crossings, count + 1


def _error(k: Any, stages: int, e: Any, e3: Any, has_e3: bool, h: float, y: Any, y_new: Any, rtol: float,
           atol: float, err5: Any, err3: Any) -> float:
    """SciPy's error norm of the step (DOP853's combines its fifth- and third-order estimates), as rk._error."""
    d = len(y)
    _weighted(k, stages + 1, e, 0, err5)
    if not has_e3:
        total = 0.0
        for i in range(d):
            scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
            x = err5[i] * h / scale
            total += x * x
        return math.sqrt(total / d)
    _weighted(k, stages + 1, e3, 0, err3)
    e5 = 0.0
    e3_sum = 0.0
    for i in range(d):
        scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        e5 += (err5[i] / scale) ** 2
        e3_sum += (err3[i] / scale) ** 2
    if e5 == 0 and e3_sum == 0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3_sum) * d)
