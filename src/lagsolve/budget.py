"""Run a computation in a child process with a wall-clock budget.

SymPy can spend minutes in loops that a signal alarm cannot interrupt (long
integer arithmetic, C-level polynomial code), so the only budget that really
holds is a separate process that is killed when time is up. The child also gets
an address-space limit so that a runaway expression cannot exhaust memory.
"""

from __future__ import annotations

import multiprocessing
import sys
import traceback
from collections.abc import Callable
from typing import Any

from lagsolve.errors import DerivationError, LagsolveError

MEMORY_LIMIT = 8 * 1024**3


def _child(conn: Any, fn: Callable[..., Any], args: tuple) -> None:
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    except (ImportError, ValueError, OSError):  # pragma: no cover - not on every platform
        pass
    try:
        result = ("ok", fn(*args))
    except LagsolveError as exc:
        result = ("error", exc)
    except MemoryError:
        result = ("error", DerivationError(f"the computation needed more than {MEMORY_LIMIT // 1024**3} GiB of memory"))
    except BaseException:  # noqa: BLE001 - a bug: carry its traceback to the parent
        result = ("crash", traceback.format_exc())
    try:
        conn.send(result)
    except Exception:  # noqa: BLE001 - e.g. an exception that cannot be pickled
        conn.send(("crash", traceback.format_exc()))
    finally:
        conn.close()


def run_with_budget(fn: Callable[..., Any], args: tuple, seconds: float, what: str) -> Any:
    """``fn(*args)`` in a child process, killed after ``seconds``.

    Raises
    ------
    DerivationError
        When the budget runs out (the message says how to raise it) or the child dies.
    LagsolveError
        Whatever lagsolve error ``fn`` raised, re-raised here.
    """
    method = "fork" if sys.platform.startswith("linux") else "spawn"
    ctx = multiprocessing.get_context(method)
    receiver, sender = ctx.Pipe(duplex=False)
    # not a daemon: a simulation runs its analysis in a child of its own
    process = ctx.Process(target=_child, args=(sender, fn, args), daemon=False)
    process.start()
    sender.close()
    try:
        if not receiver.poll(seconds):
            raise DerivationError(
                f"{what} did not finish within the {seconds:g} s budget; raise it with --timeout "
                "or simplify the problem"
            )
        try:
            status, payload = receiver.recv()
        except EOFError:
            raise DerivationError(f"{what} stopped unexpectedly (exit code {process.exitcode})") from None
    finally:
        if process.is_alive():
            process.kill()
        process.join()
        receiver.close()
    if status == "ok":
        return payload
    if status == "error":
        raise payload
    raise RuntimeError(f"{what} failed with an internal error:\n{payload}")
