r"""Stages of a derivation, each with its own share of a CPU-time budget.

A derivation first builds its core, the matrix form :math:`M\ddot q = F + A^T\lambda`,
:math:`A\ddot q = \beta`, which is cheap and always comes out. Every later stage (the
explicit solve, the forces of constraint, display simplification, each part of the
analysis) runs through :meth:`Stages.run` with a slice of what is left of the budget. A
stage that runs out of its slice, or that does not apply, is recorded as a
:class:`StageNote` and its result is ``None``; the other stages still run.

The slices are CPU time of this process (``ITIMER_PROF``: user plus system time), not wall
time, so a loaded machine does not cut a stage short. When the slice is used up a
:class:`StageTimeout` is raised inside the stage, again every 0.1 s of CPU until the stage
returns (so code that swallows one exception still stops). A timeout that lands where Python
cannot raise it (a ``__del__`` or a weakref callback during garbage collection) would be
reported as an "Exception ignored" on stderr; while a limit is armed such reports of
:class:`StageTimeout` are dropped, since the next tick raises it again. Outside the main thread,
where Python cannot take signals, the slices are not enforced.
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any, TypeVar

T = TypeVar("T")

#: CPU seconds for a whole derivation when the caller gives none
DEFAULT_BUDGET = 120.0

#: the stages in the order a derivation runs them, with the weight of each one's share of what is left
STAGES: dict[str, float] = {
    "explicit solve": 3.0,
    "normal forces": 1.0,
    "forces of constraint": 1.0,
    "contact forces": 0.5,
    "sticking": 0.5,
    "display simplification": 2.0,
    "constraint classification": 1.0,
    "minimal coordinates": 2.0,
    "conserved quantities": 1.0,
    "symmetries": 1.0,
    "effective potential": 2.0,
    "steady motions": 1.0,
    "equilibria and normal modes": 2.0,
    "numeric equilibria": 1.0,
    "hamiltonian": 2.0,
}

#: the largest part of the whole budget one optional stage may take, however much is left
MAX_SHARE = 0.15

#: the smallest slice a stage is given, so that a cheap stage still runs when the budget is nearly used up
MIN_SLICE = 0.5


class StageTimeout(BaseException):  # noqa: N818 - like KeyboardInterrupt: not caught by `except Exception`
    """A stage used up its share of the CPU budget (raised inside the stage by a profiling timer)."""


class StageSkipped(Exception):  # noqa: N818 - a reason, not an error
    """A stage that does not apply, or would not be useful: the message says why, ``kind`` is its note's."""

    kind = "skipped"


class StageTooLarge(StageSkipped):
    """A result that would be too large to be useful (a note of kind ``"size"``); the message says what grows
    past which limit, after "too large: "."""

    kind = "size"

    def __init__(self, what: str) -> None:
        super().__init__(f"too large: {what}")


@dataclass(frozen=True)
class StageNote:
    """Why one stage gave no result: ``stage`` names it, ``reason`` is a sentence in plain text,
    ``kind`` is ``"budget"`` (ran out of its CPU share), ``"skipped"`` (does not apply, for a reason
    worth telling), ``"size"`` (the result would be too large to be useful) or ``"n/a"`` (nothing to do,
    such as forces of constraint without constraints: not shown in reports)."""

    stage: str
    reason: str
    kind: str

    def sentence(self) -> str:
        """The note as one sentence for a report: ``Explicit solve: ...``."""
        return f"{self.stage[0].upper()}{self.stage[1:]}: {self.reason}."


@dataclass
class Stages:
    """Runs the stages of one derivation under a CPU budget and collects their notes.

    Each stage gets ``left × weight / (weights of the stages not yet run)``, at most
    :data:`MAX_SHARE` of the whole budget and at least :data:`MIN_SLICE`, so time a stage does not
    use flows to the later ones, but no single optional step eats the budget.
    """

    budget: float = DEFAULT_BUDGET
    notes: list[StageNote] = field(default_factory=list)
    _start: float = field(default_factory=time.process_time)
    _done: set[str] = field(default_factory=set)

    def left(self) -> float:
        """CPU seconds left of the budget."""
        return self.budget - (time.process_time() - self._start)

    def slice_for(self, stage: str) -> float:
        rest = sum(w for s, w in STAGES.items() if s not in self._done)
        weight = STAGES[stage]
        share = min(self.left() * weight / rest, self.budget * MAX_SHARE) if rest else 0.0
        return max(MIN_SLICE, share)

    def skip(self, stage: str, reason: str, kind: str = "skipped") -> None:
        """Record that ``stage`` gives no result, and why."""
        self._done.add(stage)
        self.notes.append(StageNote(stage, reason, kind))

    def run(self, stage: str, fn: Callable[..., T], *args: Any, cap: float | None = None, instead: str = "",
            **kwargs: Any) -> T | None:
        """``fn(*args, **kwargs)`` under this stage's slice of the budget (at most ``cap`` seconds, when a
        cheaper route gives the answer ``instead``); None (and a note) when the slice runs out or ``fn``
        raises :class:`StageSkipped`."""
        if stage not in STAGES:
            raise KeyError(f"unknown stage {stage!r}")
        seconds = self.slice_for(stage) if cap is None else min(self.slice_for(stage), cap)
        self._done.add(stage)
        try:
            with cpu_limit(seconds):
                return fn(*args, **kwargs)
        except StageTimeout:
            if cap is not None and seconds >= cap:
                reason = f"did not finish within {seconds:.1f} s of CPU; {instead}"
                self.notes.append(StageNote(stage, reason, "budget"))
            else:
                self.notes.append(StageNote(stage, f"ran out of its share of the CPU budget ({seconds:.1f} s of "
                                                   f"{self.budget:g} s); raise it with --timeout", "budget"))
        except StageSkipped as reason:
            self.notes.append(StageNote(stage, str(reason), reason.kind))
        return None

    def settle(self, stage: str) -> None:
        """Mark ``stage``'s "skipped" note as nothing to report (its answer is given elsewhere)."""
        self.notes = [StageNote(n.stage, n.reason, "n/a") if n.stage == stage and n.kind == "skipped" else n
                      for n in self.notes]

    def shown(self) -> tuple[StageNote, ...]:
        """The notes a report shows (all but ``"n/a"``)."""
        return tuple(n for n in self.notes if n.kind != "n/a")

    def note_for(self, stage: str) -> StageNote | None:
        """The note recorded for ``stage``, if any."""
        return next((n for n in self.notes if n.stage == stage), None)


_armed = [False]


def _raise_timeout(signum: int, frame: Any) -> None:
    if _armed[0]:
        raise StageTimeout


@contextlib.contextmanager
def _quiet_unraisable_timeouts() -> Iterator[None]:
    """Drop the "Exception ignored" report of a :class:`StageTimeout` that fired inside a finaliser."""
    previous = sys.unraisablehook

    def hook(unraisable: Any) -> None:
        if not isinstance(unraisable.exc_value, StageTimeout):
            previous(unraisable)

    sys.unraisablehook = hook
    try:
        yield
    finally:
        sys.unraisablehook = previous


@contextlib.contextmanager
def cpu_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`StageTimeout` inside the block once it has used ``seconds`` of CPU time.

    A limit inside another one is cut to what the outer one has left, and the outer one is
    armed again afterwards.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous_handler = signal.getsignal(signal.SIGPROF)
    outer_left, _ = signal.getitimer(signal.ITIMER_PROF)
    started = time.process_time()
    if outer_left > 0:
        seconds = min(seconds, outer_left)
    was_armed = _armed[0]
    signal.signal(signal.SIGPROF, _raise_timeout)
    _armed[0] = True
    signal.setitimer(signal.ITIMER_PROF, max(seconds, 1e-3), 0.1)
    try:
        with _quiet_unraisable_timeouts():
            yield
    finally:
        _armed[0] = False
        signal.setitimer(signal.ITIMER_PROF, 0, 0)
        signal.signal(signal.SIGPROF, previous_handler)
        _armed[0] = was_armed
        if outer_left > 0:
            remaining = outer_left - (time.process_time() - started)
            signal.setitimer(signal.ITIMER_PROF, max(remaining, 1e-3), 0.1)
