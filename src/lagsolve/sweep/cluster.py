"""Chunks of a sweep on Dask: a local cluster of worker processes, or an existing scheduler.

Dask does the scheduling; this module only submits the chunks, reports progress as they finish,
and returns their results in submission order. A local cluster is closed (its worker processes
ended) whatever happens, including an error in a chunk.

An existing scheduler's address is checked before Dask is given it (:func:`check_scheduler`): the
connection is made with a time-out, and what answers must send a Dask handshake within it. Dask
itself would wait for ever on a server that accepts and never answers, and would read another
service's answer (an HTTP server's) as the length of a message and try to allocate exabytes.

Ctrl-C reaches this process alone, not the local workers: a terminal sends SIGINT to every process
of its foreground group, and each worker would print a traceback of its own. The local cluster is
started with SIGINT ignored (:func:`interrupts_held`), which its worker processes inherit; this process
gets the interrupt (as ``KeyboardInterrupt``) and closes the cluster, which ends them.
"""

from __future__ import annotations

import contextlib
import logging
import signal
import socket
import struct
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from lagsolve.errors import Issue, SpecError
from lagsolve.sweep import INSTALL

#: seconds to connect to an existing scheduler, for it to send its handshake, and for it to have a worker
CONNECT_TIMEOUT = 10.0

#: the largest handshake a scheduler sends (a few dozen bytes: compression, Python version, pickle protocol)
HANDSHAKE_LIMIT = 65536

FIX = "give the address a running Dask scheduler prints (dask scheduler), e.g. tcp://10.0.0.1:8786"


def _refuse(message: str, fix: str = FIX) -> SpecError:
    return SpecError([Issue("<command line>", 0, "--scheduler", message, fix)])


def _receive(connection: socket.socket, size: int) -> bytes:
    data = b""
    while len(data) < size:
        chunk = connection.recv(size - len(data))
        if not chunk:
            break
        data += chunk
    return data


def check_scheduler(scheduler: str, timeout: float | None = None) -> str:
    """The ``tcp://host:port`` address of a Dask scheduler listening at ``scheduler``.

    Connects with a time-out of ``timeout`` seconds (default :data:`CONNECT_TIMEOUT`) and reads the
    handshake a Dask scheduler sends as soon as it accepts a connection: an 8-byte little-endian length,
    then that many bytes that name the pickle protocol. Nothing is sent.

    Raises
    ------
    SpecError
        Not a TCP address; nothing listens there; it does not answer in time; it answers, but not as
        a Dask scheduler. The message gives the address and the fix.
    """
    try:
        from distributed.comm.addressing import parse_address, parse_host_port
    except ImportError as exc:
        raise ImportError(f"--workers and --scheduler need dask.distributed: {INSTALL}") from exc
    seconds = CONNECT_TIMEOUT if timeout is None else timeout
    try:
        scheme, location = parse_address(scheduler)
        host, port = parse_host_port(location, 8786)
    except (ValueError, TypeError):
        raise _refuse(f"expected an address such as tcp://10.0.0.1:8786, found {scheduler!r}") from None
    if scheme != "tcp":
        raise _refuse(f"{scheduler!r}: only tcp:// addresses are supported, found {scheme}://")
    address = f"tcp://{host}:{port}" if ":" not in host else f"tcp://[{host}]:{port}"
    try:
        connection = socket.create_connection((host, int(port)), timeout=seconds)
    except (OSError, ValueError, OverflowError) as exc:
        reason = "no answer" if isinstance(exc, TimeoutError) else getattr(exc, "strerror", None) or exc
        raise _refuse(f"cannot connect to {address} within {seconds:g} s: {reason}") from None
    with connection:
        connection.settimeout(seconds)
        try:
            head = _receive(connection, 8)
            length = struct.unpack("<Q", head)[0] if len(head) == 8 else 0
            body = _receive(connection, length) if 0 < length <= HANDSHAKE_LIMIT else b""
        except TimeoutError:
            raise _refuse(f"{address} accepts connections but sent nothing within {seconds:g} s: it is "
                          "not a Dask scheduler, or it does not work") from None
        except OSError as exc:
            raise _refuse(f"{address} closed the connection: {exc}") from None
    if b"pickle-protocol" not in body:
        shown = (head + body)[:24]
        raise _refuse(f"{address} answers, but not as a Dask scheduler (it sent {shown!r})",
                      "check the host and port: " + FIX)
    return address


@contextlib.contextmanager
def interrupts_held() -> Iterator[None]:
    """Inside the block SIGINT is ignored, so that the processes started there inherit it ignored (a disposition
    survives ``exec``; a signal mask does not survive multiprocessing's spawn), and blocked in this thread, so
    that a Ctrl-C meanwhile is not lost but stays pending and is delivered here when the block ends (Linux
    queues a blocked signal even while it is ignored). Only in the main thread, on POSIX. A thread started
    earlier that does not block SIGINT (a BLAS thread pool, which the command line does not start) may take
    such a Ctrl-C while it is ignored: it is then lost, and a second one stops the sweep."""
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    from multiprocessing import resource_tracker

    # started here, not by the first worker: starting it blocks and then *unblocks* SIGINT in the calling
    # thread, and Dask's event-loop thread (which inherits the block from here) would pass the unblocked
    # mask on to its threads, one of which would then take a Ctrl-C while it is ignored and lose it
    resource_tracker.ensure_running()
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, handler)  # a pending Ctrl-C stays pending for the handler
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)  # and is delivered now


def run_distributed(function: Callable[..., Any], tasks: Sequence[tuple[Any, ...]], workers: int,
                    scheduler: str | None, progress: Callable[[int, int], None] | None, total: int) -> list[Any]:
    """``function(*task)`` for every task, on Dask; results in the order of ``tasks``.

    Raises
    ------
    ImportError
        dask.distributed is not installed.
    SpecError
        The scheduler cannot be reached, is not a Dask scheduler (:func:`check_scheduler`) or has no worker.
    """
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError as exc:
        raise ImportError(f"--workers and --scheduler need dask.distributed: {INSTALL}") from exc
    cluster = None
    try:
        if scheduler is not None:
            address = check_scheduler(scheduler)
            try:
                client = Client(address, timeout=f"{CONNECT_TIMEOUT}s")
            except (OSError, TimeoutError, ValueError) as exc:
                raise _refuse(f"cannot reach the Dask scheduler at {address}: {exc}") from None
            try:
                client.wait_for_workers(1, timeout=CONNECT_TIMEOUT)
            except (OSError, TimeoutError) as exc:
                client.close()
                raise _refuse(f"the Dask scheduler at {address} has no worker (waited {CONNECT_TIMEOUT:g} s): {exc}",
                              f"start workers for it (dask worker {address})") from None
        else:
            with interrupts_held():  # the workers never see a Ctrl-C: this process ends them
                # ":0": any free port for the scheduler's HTTP server (None still takes 8787, and a second sweep
                # at the same time then failed to start its cluster, or warned)
                cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                                       dashboard_address=":0", silence_logs=logging.ERROR)
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
