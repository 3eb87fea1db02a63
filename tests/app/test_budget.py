"""The process budget: results come back, errors pass through, overruns are killed."""

from __future__ import annotations

import time

import pytest

from lagsolve.app.budget import run_with_budget
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


def test_uninterruptible_c_loop_is_killed() -> None:
    """C-level arithmetic that ignores signals is stopped when it has used its CPU budget, with a message
    naming the budget and --timeout."""
    with pytest.raises(DerivationError, match=r"used up its 0.5 s CPU budget; raise it with --timeout"):
        run_with_budget(_busy_integer_power, (), 0.5, "a huge power")


def _partial_then_burn() -> int:
    from lagsolve.app.budget import report_partial

    report_partial("the core")
    return _busy_integer_power()


def test_partial_result_answers_when_the_budget_runs_out() -> None:
    """A child stopped at its CPU limit after sending a partial result gives that result to on_partial."""
    answer = run_with_budget(_partial_then_burn, (), 0.5, "x", on_partial=lambda payload, why: (payload, why))
    assert answer[0] == "the core"
    assert "CPU budget" in answer[1]


def _display_form_then_burn() -> int:
    import sympy

    from lagsolve.app.budget import report_partial

    a, b = sympy.symbols("a b")
    report_partial(sympy.Mul(sympy.Rational(1, 2), a + b, evaluate=False))  # as a display form writes (a + b)/2
    return _busy_integer_power()


def test_a_partial_result_keeps_its_display_form() -> None:
    """The partial result comes back as the child built it: (a + b)/2, not a/2 + b/2 (a plain pickle round trip
    rebuilds SymPy's expressions with evaluation on)."""
    import sympy

    answer = run_with_budget(_display_form_then_burn, (), 0.5, "x", on_partial=lambda payload, why: payload)
    a, b = sympy.symbols("a b")
    assert sympy.srepr(answer) == sympy.srepr(sympy.Mul(sympy.Rational(1, 2), a + b, evaluate=False))
    assert sympy.srepr(answer) != sympy.srepr((a + b) / 2)


def _grandchild_pid() -> int:
    import multiprocessing
    import os

    process = multiprocessing.get_context("fork").Process(target=time.sleep, args=(600,))
    process.start()
    return process.pid if process.pid is not None else os.getpid()


def _alive(pid: int) -> bool:
    import os

    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a zombie has finished: reap-independent check through /proc
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            return stat.read().split(") ")[-1][0] != "Z"
    except OSError:
        return False


def test_no_worker_outlives_the_call() -> None:
    """A worker's own children are killed with its process group when the call returns."""
    pid = run_with_budget(_grandchild_pid, (), 10, "spawning")
    for _ in range(100):
        if not _alive(pid):
            break
        time.sleep(0.05)
    assert not _alive(pid)


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


_WARMED: list[str] = []


def _warm_up() -> None:
    _WARMED.append("warm")


def _first_and_warmed(first: object, second: int) -> tuple[str, int, list[str], int]:
    import os

    import sympy

    return sympy.srepr(first), second, list(_WARMED), os.getpid()  # as the child has it


def test_the_first_argument_is_made_here_while_the_child_warms_up() -> None:
    """With ``first``, the child runs ``warm`` and then fn(first(), *args); first() runs in this process, after
    the child has started, and a display form reaches the child as it was built (no evaluation on the way)."""
    import os

    import sympy

    a, b = sympy.symbols("a b")
    form = sympy.Mul(sympy.Rational(1, 2), a + b, evaluate=False)
    made: list[int] = []

    def first() -> object:
        made.append(os.getpid())
        return form

    value, second, warmed, child = run_with_budget(_first_and_warmed, (7,), 10, "x", first=first, warm=_warm_up)
    assert value == sympy.srepr(form) != sympy.srepr((a + b) / 2)
    assert (second, warmed) == (7, ["warm"])
    assert made == [os.getpid()] != [child]
    assert _WARMED == []  # warm ran in the child only


def test_the_first_argument_reaches_a_spawned_child(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where a child is a fresh interpreter (macOS, Windows: spawn), the warm-up runs there and the first argument
    arrives as it was built, though that interpreter has not imported SymPy when it reads it."""
    import sympy

    from lagsolve.app import budget

    monkeypatch.setattr(budget, "START_METHOD", "spawn")
    a, b = sympy.symbols("a b")
    form = sympy.Mul(sympy.Rational(1, 2), a + b, evaluate=False)
    value, second, warmed, _ = run_with_budget(_first_and_warmed, (7,), 60, "x", first=lambda: form, warm=_warm_up)
    assert (value, second, warmed) == (sympy.srepr(form), 7, ["warm"])


def test_a_first_argument_that_fails_ends_the_child() -> None:
    """When first() raises (an invalid file), its error is raised here and the child, started already, is gone."""
    import multiprocessing
    import os

    before = _descendants(os.getpid())

    def first() -> object:
        raise SpecError([])

    with pytest.raises(SpecError):
        run_with_budget(_first_and_warmed, (7,), 10, "x", first=first, warm=_warm_up)
    assert multiprocessing.active_children() == []
    assert not {pid for pid in _descendants(os.getpid()) - before if _alive(pid)}


def _descendants(pid: int) -> set[int]:
    """Every process below ``pid`` (read from /proc)."""
    import os

    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat", encoding="ascii") as stat:
                    parent = int(stat.read().split(") ")[-1].split()[1])
            except (OSError, ValueError, IndexError):
                continue
            children.setdefault(parent, []).append(int(entry))
    found: set[int] = set()
    todo = [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            if child not in found:
                found.add(child)
                todo.append(child)
    return found


@pytest.mark.parametrize("signum", ["SIGTERM", "SIGINT"])
def test_a_signal_to_the_command_alone_leaves_no_worker(signum: str, tmp_path) -> None:  # noqa: ANN001
    """SIGTERM or SIGINT sent to the lagsolve process alone (not its group) takes its workers with it."""
    import os
    import signal
    import subprocess
    import sys
    from pathlib import Path

    bead = Path(__file__).resolve().parents[2] / "problems" / "bead.yaml"
    command = [sys.executable, "-m", "lagsolve", "simulate", str(bead), "--t-end", "1e7", "--timeout", "600"]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tmp_path)
    workers: set[int] = set()
    for _ in range(200):  # until the budgeted worker has started (at most 20 s)
        workers = _descendants(process.pid)
        if workers:
            break
        time.sleep(0.1)
    assert workers, "the worker never started"
    os.kill(process.pid, getattr(signal, signum))
    process.wait(timeout=30)
    for _ in range(100):
        if not any(_alive(pid) for pid in workers):
            break
        time.sleep(0.05)
    assert not any(_alive(pid) for pid in workers)


def _child_pid() -> int:
    import os

    return os.getpid()


def test_meanwhile_runs_here_while_the_child_computes() -> None:
    """``meanwhile`` runs once, in this process (after the first argument is sent), and the child's answer still
    comes back."""
    import os

    ran: list[int] = []
    child = run_with_budget(_child_pid, (), 10, "x", meanwhile=lambda: ran.append(os.getpid()))
    assert ran == [os.getpid()] != [child]


def test_a_pickle_within_its_limit_comes_back_as_it_was_built() -> None:
    """pickled_within gives the bytes when they fit (read back by rebuilt without evaluation: (a + b)/2 stays so),
    and None, without finishing, when they do not, or when the object cannot be pickled."""
    import sympy

    from lagsolve.app.budget import pickled_within, rebuilt

    a, b = sympy.symbols("a b")
    form = sympy.Mul(sympy.Rational(1, 2), a + b, evaluate=False)
    blob = pickled_within(form, 10_000)
    assert blob is not None and sympy.srepr(rebuilt(blob)) == sympy.srepr(form)
    assert pickled_within(form, len(blob)) == blob
    assert pickled_within(form, len(blob) - 1) is None
    assert pickled_within(sympy.Add(*sympy.symbols("x0:5000")), 1000) is None
    assert pickled_within(lambda: None, 10_000) is None
