"""The process budget: results come back, errors pass through, overruns are killed."""

from __future__ import annotations

import time

import pytest

from lagsolve.budget import run_with_budget
from lagsolve.errors import DerivationError, SpecError


def _square(x: int) -> int:
    return x * x


def _sleep(seconds: float) -> None:
    time.sleep(seconds)


def _busy_integer_power() -> int:
    # C-level big-integer work that a signal alarm could not interrupt
    return len(str(7 ** (10**8)))


def _raise_derivation_error() -> None:
    raise DerivationError("singular system")


def _raise_bug() -> None:
    raise KeyError("oops")


def test_result_comes_back() -> None:
    """A function that finishes in time returns its value through the child process."""
    assert run_with_budget(_square, (12,), 10, "squaring") == 144


def test_overrun_is_killed_quickly() -> None:
    """A computation past its budget is stopped, with a message naming the budget and --timeout."""
    start = time.perf_counter()
    with pytest.raises(DerivationError, match=r"did not finish within the 0.5 s budget; raise it with --timeout"):
        run_with_budget(_sleep, (30,), 0.5, "sleeping")
    assert time.perf_counter() - start < 5


def test_uninterruptible_c_loop_is_killed() -> None:
    """Even C-level arithmetic that ignores signals is stopped at the budget."""
    start = time.perf_counter()
    with pytest.raises(DerivationError, match="did not finish"):
        run_with_budget(_busy_integer_power, (), 0.5, "a huge power")
    assert time.perf_counter() - start < 5


def test_lagsolve_errors_pass_through() -> None:
    """A LagsolveError raised in the child is raised again in the parent, message intact."""
    with pytest.raises(DerivationError, match="singular system"):
        run_with_budget(_raise_derivation_error, (), 10, "x")


def test_bugs_keep_their_traceback() -> None:
    """An unexpected exception is a bug: it surfaces as RuntimeError carrying the child's traceback."""
    with pytest.raises(RuntimeError, match="KeyError: 'oops'"):
        run_with_budget(_raise_bug, (), 10, "x")


def test_spec_errors_are_picklable() -> None:
    """SpecError survives the trip between processes with its issues."""
    import pickle

    from lagsolve.errors import Issue

    err = SpecError([Issue("f.yaml", 3, "name", "bad", "fix it")])
    again = pickle.loads(pickle.dumps(err))
    assert str(again.issues[0]) == "f.yaml:3: name: bad; fix it"
