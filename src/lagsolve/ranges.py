"""The accepted range of every numeric option, for the command line and the library alike.

A number that reaches an integrator, a CPU limit or a cluster is checked here first: it must be a
finite number (NaN and infinity are refused everywhere) inside its option's range. The command
line's option type (:class:`lagsolve.cli.Number`) and the library's functions
(:func:`lagsolve.simulate`, :func:`lagsolve.derive`, :func:`lagsolve.sweep.api.sweep`, the
:mod:`lagsolve.app.pipeline` entry points) read the same table, so both refuse the same values
with the same sentence.

>>> RANGES["rtol"].describe()
'a finite number from 1e-13 to 1'
>>> RANGES["timeout"].fault(float("nan"))
'expected a finite number from 0.1 to 1e+06, found nan'
>>> RANGES["workers"].fault(2) is None
True
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from lagsolve.errors import Issue, SpecError


def _number(value: float) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


@dataclass(frozen=True)
class Range:
    """The values a numeric option accepts: ``low`` to ``high`` (``low_open``: strictly above ``low``),
    finite, and a whole number when ``integer``."""

    low: float
    high: float = math.inf
    low_open: bool = False
    integer: bool = False

    def describe(self) -> str:
        """The range in words: ``a finite number > 0``, ``a whole number from 0 to 256``."""
        kind = "a whole number" if self.integer else "a finite number"
        if self.high == math.inf:
            return f"{kind} {'>' if self.low_open else '>='} {_number(self.low)}"
        if self.low_open:
            return f"{kind} > {_number(self.low)} and <= {_number(self.high)}"
        return f"{kind} from {_number(self.low)} to {_number(self.high)}"

    def fault(self, value: Any) -> str | None:
        """What is wrong with ``value`` as a sentence, or None when it is accepted."""
        wanted = numbers.Integral if self.integer else numbers.Real
        if isinstance(value, bool) or not isinstance(value, wanted):
            return f"expected {self.describe()}, found {value!r}"
        number = float(value)
        if not math.isfinite(number) or number < self.low or (self.low_open and number == self.low) \
                or number > self.high:
            return f"expected {self.describe()}, found {_number(number) if isinstance(value, float) else value}"
        return None


#: every numeric option by its name in the library (the command line's ``--t-end`` is ``t_end``)
RANGES: dict[str, Range] = {
    "timeout": Range(0.1, 1e6),  # CPU seconds of a command's child process (--timeout)
    "budget": Range(0.0, 1e6, low_open=True),  # CPU seconds of an in-process derivation (the library)
    "t_end": Range(0.0, low_open=True),
    "rtol": Range(1e-13, 1.0),  # SciPy raises anything below 100 machine epsilons to that, with a warning
    "atol": Range(0.0, low_open=True),
    "max_step": Range(0.0, low_open=True),
    "samples": Range(2, 1_000_000, integer=True),
    "workers": Range(0, 256, integer=True),
    "runs": Range(1, 10_000_000, integer=True),
    "chunk_size": Range(1, 10_000_000, integer=True),
    "seed": Range(0, 2**64 - 1, integer=True),
    "count": Range(1, 10_000, integer=True),  # variants of a problem (lagsolve variants --count)
    "sig_figs": Range(1, 12, integer=True),  # significant figures of a variant's varied numbers
    "attempts": Range(0, 1_000_000, integer=True),  # candidates drawn at most (0: 20 per variant, at least 50)
}


def issues(values: Iterable[tuple[str, Any]], where: str = "<argument>") -> list[Issue]:
    """An :class:`~lagsolve.errors.Issue` for each ``(name, value)`` outside its range (None is not checked:
    the default applies)."""
    found = []
    for name, value in values:
        fault = None if value is None else RANGES[name].fault(value)
        if fault is not None:
            found.append(Issue(where, 0, name, fault))
    return found


def check(**values: Any) -> None:
    """Raise :class:`~lagsolve.errors.SpecError` listing every value outside its option's range.

    >>> check(t_end=1.0, rtol=None)
    >>> check(t_end=float("inf"))
    Traceback (most recent call last):
    ...
    lagsolve.errors.SpecError: <argument>: t_end: expected a finite number > 0, found inf
    """
    found = issues(values.items())
    if found:
        raise SpecError(found)
