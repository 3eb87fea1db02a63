"""``lagsolve.sweep``: many runs of one problem over parameters and initial conditions, as a DataFrame.

The runs are cut into chunks; each chunk is integrated by :func:`lagsolve.sweep.run.run_chunk`, in
this process, on a local Dask cluster (``workers``) or on an existing one (``scheduler``). A
chunk carries the problem's *text*, so a worker compiles the problem itself (once) and nothing
unpicklable travels. Every run's numbers depend on its inputs alone, never on the chunk it is in
or the worker that ran it.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from lagsolve import ranges
from lagsolve.errors import Issue, SpecError
from lagsolve.files import read_input
from lagsolve.problem.methods import DEFAULT as DEFAULT_METHOD
from lagsolve.problem.yamlread import MAX_BYTES
from lagsolve.sweep import INSTALL

ProgressCallback = Callable[[int, int], None]  # (runs done, runs in all)

#: runs from which ``engine="auto"`` takes the compiled path (below, the NumPy batch is done before Numba
#: would have loaded its cached machine code, let alone compiled it the first time)
COMPILED_FROM = 1000
#: the same without a cache of the compiled code (``$LAGSOLVE_CACHE`` unset): the compilation, in each process, is
#: won back (about 0.4 ms saved per double pendulum against about a minute) only past this many runs
UNCACHED_FROM = 100_000

#: runs from which the default ``workers`` on the compiled path is one thread per core (below, a chunk per
#: thread is too short to pay for the split)
THREADS_FROM = 512
#: chunks per worker by default: a Dask worker process, a thread of the compiled path
PROCESS_CHUNKS, THREAD_CHUNKS = 4, 16
#: the fewest runs in a thread's chunk by default (a chunk's table costs about 2 ms to build)
THREAD_CHUNK_LEAST = 64

#: runs from which the default ``workers`` on the batched NumPy path is a local Dask cluster, one process per core
PROCESSES_FROM = 5000

ENGINES = ("auto", "compiled", "numpy")


def default_workers(runs: int, compiled: bool, batched: bool = False) -> int:
    """The fastest ``workers`` for ``runs`` runs, measured (docs/api.md, "Speed of sweeps"): on the compiled path,
    threads, one per core, for at least :data:`THREADS_FROM` runs; on the batched NumPy path, a local Dask
    cluster of one process per core for at least :data:`PROCESSES_FROM` runs (where Dask is installed): its
    start-up and each worker's own derivation cost about 5 s, which two cores win back from about 4000 runs
    of the double pendulum to t = 10 s; else 0, in this process (and always on the per-run path, whose cost
    per run varies too much with the problem to choose for it: ``--workers N`` asks)."""
    import importlib.util

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    if compiled:
        return max(1, min(cores, runs // (THREADS_FROM // 2))) if runs >= THREADS_FROM else 0
    if batched and runs >= PROCESSES_FROM and cores > 1 and importlib.util.find_spec("distributed") is not None:
        return cores
    return 0


def _engine(engine: str, runs: int, method: str) -> str:
    """The route the runs take: "compiled" or "numpy" (see :func:`sweep`'s ``engine``)."""
    if engine != "auto":
        return engine
    from lagsolve.problem.methods import EXPLICIT
    from lagsolve.sweep.native import cache_folder, numba_available

    # the first compilation takes about a minute: without a cache of the machine code ($LAGSOLVE_CACHE) it is won
    # back only over very many runs
    least = COMPILED_FROM if cache_folder() is not None else UNCACHED_FROM
    return "compiled" if runs >= least and method in EXPLICIT and numba_available() else "numpy"


def _text(path_or_text: str | Path | bytes) -> tuple[str, str]:
    if isinstance(path_or_text, bytes):
        return path_or_text.decode("utf-8", errors="replace"), "<text>"
    if isinstance(path_or_text, str) and "\n" in path_or_text:
        return path_or_text, "<text>"
    path = Path(path_or_text)
    try:  # at most one byte over the limit, which the reader then refuses: /dev/zero or a pipe never hangs here
        return read_input(path, MAX_BYTES).decode("utf-8"), str(path)
    except (OSError, UnicodeDecodeError) as exc:
        raise SpecError([Issue(str(path), 0, "", f"cannot read the problem file: {exc}",
                               "give the path of a YAML problem file")]) from None


def _as_specs(given: Mapping[str, Any] | Sequence[str] | None, option: str) -> list[str] | Mapping[str, Any]:
    if given is None:
        return []
    if isinstance(given, str):
        return [given]
    return given if isinstance(given, Mapping) else list(given)


def sweep(path_or_text: str | Path | bytes, *, grid: Mapping[str, Any] | Sequence[str] | None = None,
          random: Mapping[str, tuple[float, float]] | Sequence[str] | None = None, runs: int | None = None,
          seed: int = 0, t_end: float | None = None, method: str = DEFAULT_METHOD, rtol: float = 1e-10,
          atol: float = 1e-12, poincare: str | None = None, workers: int | None = None,
          scheduler: str | None = None, chunk_size: int | None = None, progress: ProgressCallback | None = None,
          before: Callable[[dict[str, bool]], None] | None = None, engine: str = "auto") -> Any:
    """Run a problem many times and return one row per run (a :class:`pandas.DataFrame`).

    Parameters
    ----------
    path_or_text : str, pathlib.Path or bytes
        A problem file, or its YAML text.
    grid : mapping or sequence of str
        Swept names (parameters, coordinates ``theta1``, velocities ``theta1_dot``) to a
        ``"START:STOP:COUNT"`` string or a sequence of values; or ``"NAME=START:STOP:COUNT"``
        strings. Several names give their Cartesian product (the first varies slowest).
    random : mapping or sequence of str
        Names to ``(low, high)``, or ``"NAME=LOW:HIGH"`` strings: ``runs`` uniform draws
        (per grid point) from ``numpy.random.default_rng(seed)``.
    t_end, method, rtol, atol
        End time (default the file's), integrator and tolerances (those of ``simulate``).
    poincare : str, optional
        A section such as ``"theta2=0, theta2_dot>0"`` (grammar in :mod:`lagsolve.sweep.spec`):
        each run's crossings, located on the dense output.
    workers : int, optional
        0: in this process; N > 0: N threads on the compiled path, else a local Dask cluster of N processes;
        None: the fastest for the sweep (:func:`default_workers`).
    scheduler : str, optional
        Address of an existing Dask scheduler (``tcp://host:8786``), checked first (SpecError if none answers).
    chunk_size : int, optional
        Runs per chunk (default: :func:`default_chunk_size`).
    progress, before : callable, optional
        ``progress(done, total)`` as chunks finish; ``before(columns)`` once the input is checked, before any
        run (the table's columns, each mapped to whether it is numeric: ``lagsolve sweep --color``).
    engine : str
        ``"auto"``, ``"compiled"`` (machine code, :mod:`lagsolve.sweep.native`) or ``"numpy"``
        (:mod:`lagsolve.sweep.rk`): the route, by these inputs and ``$LAGSOLVE_CACHE`` only, never by chunking
        or workers (docs/api.md, "Speed of sweeps"); the ``path`` column names it.

    Returns
    -------
    pandas.DataFrame
        One row per run, in input order: ``run``, the swept inputs, ``status`` (ok, released,
        failed), ``reason``, ``outcome`` (ok, flipped, stick, slip, released, failed), ``path``,
        the final state ``final_<name>``, ``max_residual``, ``energy_drift``, ``drift_<quantity>``,
        the events, and with ``poincare`` the crossings (columns in ``docs/format.md``).

    Raises
    ------
    SpecError
        Bad input (an unknown name, a malformed range or section, no end time, a number out of range, no
        scheduler answering); ImportError: pandas (or, for workers or a scheduler, Dask) missing.
    """
    pandas = _pandas()
    from lagsolve.sweep.run import columns, compiled

    text, source, settings, inputs = _prepare(path_or_text, grid, random, runs, seed, t_end, method, rtol, atol,
                                              poincare, workers, chunk_size, engine)
    if scheduler is not None:  # a wrong address is refused before the problem is compiled
        from lagsolve.sweep.cluster import check_scheduler

        scheduler = check_scheduler(scheduler)
    built = compiled(text, source)  # bad values surface here, as SpecError, before any worker starts
    total = len(next(iter(inputs.values())))
    settings = dataclasses.replace(settings, engine=_engine(engine, total, method))
    fast = settings.engine == "compiled" and built.native()[0] is not None  # compiled once, here
    if workers is None:
        from lagsolve.problem.methods import EXPLICIT

        workers = default_workers(total, fast and scheduler is None,
                                  batched=built.batch is not None and method in EXPLICIT)
    if before is not None:
        before(columns(built, settings, list(inputs)))
    frames = _run_chunks(text, source, settings, inputs, chunk_size, workers, scheduler, progress,
                         threads=fast)
    frame = pandas.concat(frames, ignore_index=True)
    frame.attrs["swept"] = list(inputs)
    if settings.section is not None:
        frame.attrs["section"] = settings.section.name
    return frame


def _pandas() -> Any:
    """The pandas module, or an ImportError saying how to install the sweep extra."""
    try:
        import pandas
    except ImportError as exc:  # pragma: no cover - pandas comes with the sweep extra
        raise ImportError(f"lagsolve sweep needs pandas: {INSTALL}") from exc
    return pandas


def _prepare(path_or_text: str | Path | bytes, grid: Mapping[str, Any] | Sequence[str] | None,
             random: Mapping[str, tuple[float, float]] | Sequence[str] | None, runs: int | None, seed: int,
             t_end: float | None, method: str, rtol: float, atol: float, poincare: str | None,
             workers: int | None, chunk_size: int | None, engine: str = "auto") -> tuple[str, str, Any, dict[str, Any]]:
    """The problem's text and source, how every run is integrated, and each swept name's input values
    (one per run), once the input is checked (SpecError otherwise)."""
    from lagsolve.problem.load import load_text
    from lagsolve.sweep import spec
    from lagsolve.sweep.rk import METHODS as BATCHED
    from lagsolve.sweep.run import Settings

    text, source = _text(path_or_text)
    problem = load_text(text, source)
    names = spec.Names(tuple(p.name for p in problem.parameters),
                       frozenset(p.name for p in problem.parameters if p.positive),
                       tuple(c.name for c in problem.coordinates))
    _check_options(method, rtol, atol, workers, runs, chunk_size, seed, BATCHED, engine)
    ranges.check(t_end=t_end)
    grid_values, random_values = _swept(grid, random, names)
    end = _end_time(t_end, problem, source)
    section = spec.parse_section(poincare, names) if poincare is not None else None
    inputs = spec.inputs(grid_values, random_values, runs, seed)
    return text, source, Settings(float(end), method, float(rtol), float(atol), section), inputs


def _swept(grid: Mapping[str, Any] | Sequence[str] | None,
           random: Mapping[str, tuple[float, float]] | Sequence[str] | None, names: Any) -> tuple[list[Any], list[Any]]:
    """The grid's ranges and the random draws' ranges, each parsed from a mapping or ``NAME=...`` strings."""
    from lagsolve.sweep import spec

    grid_specs = _as_specs(grid, "--grid")
    if isinstance(grid_specs, Mapping):
        grid_values = spec.grid_from_mapping(grid_specs, names)
    else:
        grid_values = [spec.parse_grid(g, names) for g in grid_specs]
    random_specs = _as_specs(random, "--random")
    if isinstance(random_specs, Mapping):
        random_values = [spec.parse_random(f"{k}={float(v[0])!r}:{float(v[1])!r}", names)
                         for k, v in random_specs.items()]
    else:
        random_values = [spec.parse_random(r, names) for r in random_specs]
    return grid_values, random_values


def _end_time(t_end: float | None, problem: Any, source: str) -> float:
    """The runs' end time: ``t_end`` when given, else the file's ``simulation.t_end``; SpecError when there is
    no positive one."""
    end = t_end if t_end is not None else problem.simulation.t_end if problem.simulation is not None else None
    if end is None or not (math.isfinite(end) and end > 0):
        raise SpecError([Issue(source, 0, "simulation.t_end", "no positive end time",
                               "give simulation.t_end in the file or --t-end")])
    return end


def default_chunk_size(total: int, workers: int, threads: bool) -> int:
    """Runs per chunk when ``--chunk-size`` is not given: about :data:`PROCESS_CHUNKS` chunks per worker process,
    :data:`THREAD_CHUNKS` per thread (but at least :data:`THREAD_CHUNK_LEAST` runs), at most 1024 runs."""
    per_worker, least = (THREAD_CHUNKS, THREAD_CHUNK_LEAST) if threads else (PROCESS_CHUNKS, 1)
    return min(1024, max(least, math.ceil(total / (per_worker * max(1, workers)))))


def _run_chunks(text: str, source: str, settings: Any, inputs: dict[str, Any], chunk_size: int | None,
                workers: int, scheduler: str | None, progress: ProgressCallback | None,
                threads: bool = False) -> list[Any]:
    """The runs cut into chunks (about four per worker process, sixteen per thread but at least 64 runs, at most
    1024 runs each, unless ``chunk_size`` is given), each run here, on threads of this process (``threads``: the
    compiled path) or on a Dask cluster: one frame per chunk, in input order. A thread's chunk costs little to
    hand out, and more chunks even out runs of unequal length (a chaotic corner of a grid), so the threads
    finish together."""
    from lagsolve.sweep.run import run_chunk

    total = len(next(iter(inputs.values())))
    size = chunk_size or default_chunk_size(total, workers, threads and scheduler is None)
    chunks = [(start, {k: v[start: start + size] for k, v in inputs.items()}) for start in range(0, total, size)]
    if workers == 0 and scheduler is None:
        frames = []
        for start, chunk in chunks:
            frames.append(run_chunk(text, source, settings, chunk, start))
            if progress is not None:
                progress(start + len(frames[-1]), total)
        return frames
    if threads and scheduler is None:
        return _run_threads(run_chunk, [(text, source, settings, chunk, start) for start, chunk in chunks], workers,
                            progress, total)
    from lagsolve.sweep.cluster import run_distributed

    return run_distributed(run_chunk, [(text, source, settings, chunk, start) for start, chunk in chunks],
                           workers, scheduler, progress, total)


def _run_threads(function: Callable[..., Any], tasks: list[tuple[Any, ...]], workers: int,
                 progress: ProgressCallback | None, total: int) -> list[Any]:
    """``function(*task)`` for every task on ``workers`` threads of this process (the compiled integrator
    releases the GIL); results in the order of ``tasks``. An error or a Ctrl-C cancels the chunks not
    started; those running finish first (a chunk is short)."""
    from concurrent.futures import ThreadPoolExecutor, as_completed

    executor = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="lagsolve-sweep")
    try:
        futures = {executor.submit(function, *task): i for i, task in enumerate(tasks)}
        results: list[Any] = [None] * len(tasks)
        done = 0
        for future in as_completed(futures):
            result = future.result()
            results[futures[future]] = result
            done += len(result)
            if progress is not None:
                progress(done, total)
        return results
    finally:
        executor.shutdown(wait=True, cancel_futures=True)


def _check_options(method: str, rtol: float, atol: float, workers: int | None, runs: int | None,
                   chunk_size: int | None, seed: int, batched: tuple[str, ...], engine: str = "auto") -> None:
    from lagsolve.numeric.integrate import METHODS

    bad = []
    if method not in METHODS:
        bad.append(Issue("<argument>", 0, "method", f"expected one of {', '.join(METHODS)}, found {method!r}",
                         f"{', '.join(batched)} run batched; the others one run at a time"))
    if engine not in ENGINES:
        bad.append(Issue("<argument>", 0, "engine", f"expected one of {', '.join(ENGINES)}, found {engine!r}",
                         "auto takes the compiled path for large sweeps where Numba is installed"))
    bad += ranges.issues((("rtol", rtol), ("atol", atol), ("workers", workers), ("runs", runs),
                          ("chunk_size", chunk_size), ("seed", seed)))
    if bad:
        raise SpecError(bad)
