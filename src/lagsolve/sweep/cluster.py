"""Chunks of a sweep on Dask: a local cluster of worker processes, or an existing scheduler.

Dask does the scheduling; this module only submits the chunks, reports progress as they finish,
and returns their results in submission order. A local cluster is closed (its worker processes
ended) whatever happens, including an error in a chunk.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from typing import Any

from lagsolve.errors import Issue, SpecError


def run_distributed(function: Callable[..., Any], tasks: Sequence[tuple[Any, ...]], workers: int,
                    scheduler: str | None, progress: Callable[[int, int], None] | None, total: int) -> list[Any]:
    """``function(*task)`` for every task, on Dask; results in the order of ``tasks``.

    Raises
    ------
    ImportError
        dask.distributed is not installed.
    SpecError
        The scheduler cannot be reached.
    """
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError as exc:
        from lagsolve.sweep.api import INSTALL

        raise ImportError(f"--workers and --scheduler need dask.distributed: {INSTALL}") from exc
    cluster = None
    try:
        if scheduler is not None:
            try:
                client = Client(scheduler, timeout="10s")
            except (OSError, TimeoutError, ValueError) as exc:
                raise SpecError([Issue("<command line>", 0, "--scheduler",
                                       f"cannot reach the Dask scheduler at {scheduler!r}: {exc}",
                                       "give the address a running scheduler prints, e.g. tcp://10.0.0.1:8786")]
                                ) from None
        else:
            cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR)
            client = Client(cluster)
        try:
            futures = [client.submit(function, *task, pure=False) for task in tasks]
            order = {future.key: i for i, future in enumerate(futures)}
            results: list[Any] = [None] * len(futures)
            done = 0
            for future in as_completed(futures):
                result = future.result()
                results[order[future.key]] = result
                done += len(result)
                if progress is not None:
                    progress(done, total)
            return results
        finally:
            client.close()
    finally:
        if cluster is not None:
            cluster.close()
