"""Run a computation in a child process with a CPU-time budget, and leave nothing behind.

SymPy can spend minutes in loops that a signal cannot interrupt (long integer arithmetic,
C-level polynomial code), so the budget that really holds is a separate process. Its limit is
CPU time (``RLIMIT_CPU``), not wall time, so a loaded machine does not cut it short; a very
generous wall-clock backstop only catches a child that sleeps. The child also gets an
address-space limit so that a runaway expression cannot exhaust memory.

Every child runs in a process group of its own and dies with its parent
(``PR_SET_PDEATHSIG``); the parent kills the whole group when the budget runs out, when the
result is in, and on any exception (a signal included), so no worker outlives the command.

A child may send a partial result first (:func:`report_partial`): when it is then stopped at
its limit, the caller turns that partial result into the answer (``on_partial``), so the core
of a derivation always comes out.

The child can be started before its first argument exists (``first``): it warms up (imports
what it will need) while this process makes that argument (loads the problem file), and receives
it when it is made. The two run side by side on two cores: the start-up of one command.
"""

from __future__ import annotations

import contextlib
import gc
import io
import math
import multiprocessing
import os
import pickle
import signal
import sys
import time
import traceback
from collections.abc import Callable
from typing import Any

from lagsolve.errors import DerivationError, LagsolveError

MEMORY_LIMIT = 8 * 1024**3
#: how the child is started: a fork where there is one that is safe with threads not yet started (Linux), else a
#: fresh interpreter (macOS, Windows), which imports what it needs itself
START_METHOD = "fork" if sys.platform.startswith("linux") else "spawn"
#: a child that has used little CPU but has run for this many times its budget (plus a minute) is stopped
WALL_BACKSTOP = 20.0

_channel: list[Any] = []


def report_partial(payload: Any) -> None:
    """Send a partial result to the parent (inside a child of :func:`run_with_budget`; no-op elsewhere), pickled
    here: the parent keeps the bytes and unpickles them only if it needs them (a large core takes longer to build
    back in SymPy than to derive)."""
    if _channel:
        with contextlib.suppress(Exception):
            _channel[0].send(("partial", pickle.dumps(payload)))


class _Full(Exception):  # noqa: N818 - a signal between two functions, not an error
    """The pickle grew past its limit."""


class _Capped(io.RawIOBase):
    """A file that holds at most ``limit`` bytes: a write past it raises :class:`_Full`."""

    def __init__(self, limit: int) -> None:
        self.parts: list[bytes] = []
        self.size, self.limit = 0, limit

    def writable(self) -> bool:
        return True

    def write(self, data: Any) -> int:
        self.size += len(data)
        if self.size > self.limit:
            raise _Full
        self.parts.append(bytes(data))
        return len(data)


def pickled_within(payload: Any, limit: int) -> bytes | None:
    """``payload`` pickled, or None when its pickle would be longer than ``limit`` bytes (given up as soon as it
    is: a large derivation is not pickled whole to find that out) or it cannot be pickled. Read it back with
    :func:`rebuilt`."""
    out = _Capped(limit)
    try:
        pickle.Pickler(out, protocol=pickle.HIGHEST_PROTOCOL).dump(payload)
    except (_Full, pickle.PicklingError, TypeError, AttributeError, RecursionError):
        return None
    return b"".join(out.parts)


def rebuilt(blob: bytes) -> Any:
    """A pickle this module made (a child's partial result, the first argument sent to a child, or
    :func:`pickled_within`'s) as it was made:
    SymPy's expressions rebuilt without evaluation, since pickle rebuilds each with its class's constructor, which
    would rewrite a display form such as (a + b)/2 as a/2 + b/2."""
    if "sympy" not in sys.modules and b"sympy" not in blob:  # (a spawned child has not imported SymPy yet)
        return pickle.loads(blob)
    from sympy.core.parameters import evaluate

    with evaluate(False):
        return pickle.loads(blob)


def _die_with_parent(parent: int) -> None:
    """Ask the kernel to kill this process when its parent dies (Linux), and start a process group."""
    with contextlib.suppress(OSError):
        os.setpgid(0, 0)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):  # pragma: no cover - no libc
            pass
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)


def _child(conn: Any, fn: Callable[..., Any], args: tuple, seconds: float, parent: int,
           inbox: Any = None, warm: Callable[[], None] | None = None) -> None:
    _die_with_parent(parent)
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
        cpu = max(1, math.ceil(seconds))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 2))
    except (ImportError, ValueError, OSError):  # pragma: no cover - not on every platform
        pass
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    _channel[:] = [conn]
    try:
        if inbox is not None:  # the first argument is made by the parent while this child warms up
            if warm is not None:
                warm()
            try:
                args = (rebuilt(inbox.recv_bytes()), *args)
            except EOFError:  # the parent could not make it (an invalid file): it reports that, not this child
                os._exit(0)
            inbox.close()
        result = ("ok", fn(*args))
    except LagsolveError as exc:
        result = ("error", exc)
    except MemoryError:
        result = ("error", DerivationError(f"the computation ran out of memory (its limit is {MEMORY_LIMIT // 1024**3} "
                                           "GiB; a single number too large to hold does it too)"))
    except BaseException:  # noqa: BLE001 - a bug: carry its traceback to the parent
        result = ("crash", traceback.format_exc())
    try:
        conn.send(result)
    except Exception:  # noqa: BLE001 - e.g. an exception that cannot be pickled
        conn.send(("crash", traceback.format_exc()))
    finally:
        conn.close()


def _kill_group(pid: int) -> None:
    for kill in (lambda: os.killpg(pid, signal.SIGKILL), lambda: os.kill(pid, signal.SIGKILL)):
        with contextlib.suppress(ProcessLookupError, PermissionError, OSError):
            kill()


def _send_first(first: Callable[[], Any], inbox: Any, outbox: Any) -> None:
    """``first()`` made here and sent to the child, which is warming up meanwhile."""
    inbox.close()  # the child's end: a child that died is then a broken pipe here, not a write that waits
    try:
        outbox.send_bytes(pickle.dumps(first()))
    except BrokenPipeError:  # the child is gone: its exit code says why
        pass
    finally:
        outbox.close()


def run_with_budget(fn: Callable[..., Any], args: tuple, seconds: float, what: str, *,
                    on_partial: Callable[[Any, str], Any] | None = None, first: Callable[[], Any] | None = None,
                    warm: Callable[[], None] | None = None, meanwhile: Callable[[], None] | None = None) -> Any:
    """``fn(*args)`` in a child process with ``seconds`` of CPU time.

    When the child is stopped at its limit after sending a partial result, ``on_partial(payload,
    reason)`` gives the answer instead of an error.

    With ``first``, the child computes ``fn(first(), *args)``: ``first()`` is called here after the child has
    started, while the child runs ``warm()`` (imports; its CPU counts in the budget), and its result is sent to
    the child (pickled, read back without evaluation like a partial result). When it raises, the child is ended
    and the exception raised here. ``meanwhile()`` runs here once the child has what it needs, while it computes
    (imports this process will need for the answer).

    Raises
    ------
    DerivationError
        When the budget runs out (the message says how to raise it) or the child dies.
    LagsolveError
        Whatever lagsolve error ``fn`` raised, re-raised here.
    """
    ctx: Any = multiprocessing.get_context(START_METHOD)
    receiver, sender = ctx.Pipe(duplex=False)
    inbox, outbox = ctx.Pipe(duplex=False) if first is not None else (None, None)  # the first argument's way
    # not a daemon: a simulation runs its analysis in a child of its own
    process = ctx.Process(target=_child, args=(sender, fn, args, seconds, os.getpid(), inbox, warm), daemon=False)
    # this process's objects are set aside from collection while the child runs, so that neither process's
    # collections write to them and no page of them is copied on write (Python's advice for fork without exec)
    gc.freeze()
    process.start()
    with contextlib.suppress(OSError):
        os.setpgid(process.pid, process.pid)
    sender.close()
    partial: list[Any] = []
    final: tuple[str, Any] | None = None
    out_of_time = False
    try:
        if first is not None:
            _send_first(first, inbox, outbox)
        if meanwhile is not None:
            meanwhile()
        started = time.monotonic()
        while final is None:
            if time.monotonic() - started > WALL_BACKSTOP * seconds + 60:
                out_of_time = True
                break
            if not receiver.poll(0.25):
                continue
            try:
                message = receiver.recv()
            except EOFError:
                process.join(5)
                code = process.exitcode
                out_of_time = code is not None and code in (-signal.SIGXCPU, -signal.SIGKILL)
                if not out_of_time:
                    raise DerivationError(f"{what} stopped unexpectedly (exit code {code})") from None
                break
            if message[0] == "partial":
                partial[:] = [message[1]]
            else:
                final = message
    finally:
        if process.pid is not None:
            _kill_group(process.pid)
        process.join()
        receiver.close()
        gc.unfreeze()
    if final is None:
        reason = (f"{what} used up its {seconds:g} s CPU budget; raise it with --timeout or simplify the problem")
        if partial and on_partial is not None:
            return on_partial(rebuilt(partial[0]), reason)
        raise DerivationError(reason)
    status, payload = final
    if status == "ok":
        return payload
    if status == "error":
        raise payload
    raise RuntimeError(f"{what} failed with an internal error:\n{payload}")
