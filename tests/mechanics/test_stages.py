"""Stages of a derivation: CPU-time shares, notes for stages that cannot finish, limits that nest."""

from __future__ import annotations

import contextlib
import time

import pytest

from lagsolve.mechanics.stages import STAGES, StageNote, Stages, StageSkipped, StageTimeout, StageTooLarge, cpu_limit


def _burn(seconds: float) -> float:
    start = time.process_time()
    while time.process_time() - start < seconds:
        pass
    return seconds


def test_a_stage_that_finishes_returns_its_value() -> None:
    """A stage inside its share returns what its function returns and leaves no note."""
    stages = Stages(10.0)
    assert stages.run("explicit solve", lambda: 42) == 42
    assert stages.notes == []


@pytest.mark.budget
def test_a_stage_past_its_share_is_stopped_with_a_note() -> None:
    """A stage that uses up its CPU share returns None and is named, with its share, in a note."""
    stages = Stages(2.0)
    assert stages.run("equilibria and normal modes", _burn, 60.0) is None
    (note,) = stages.notes
    assert note.stage == "equilibria and normal modes" and note.kind == "budget"
    assert "ran out of its share of the CPU budget" in note.reason and "--timeout" in note.reason


@pytest.mark.budget
def test_a_swallowed_timeout_is_raised_again() -> None:
    """Code that catches one StageTimeout is interrupted again, so a stage cannot run on forever."""

    def stubborn() -> None:
        with contextlib.suppress(StageTimeout):
            _burn(60.0)
        _burn(60.0)

    stages = Stages(1.0)
    assert stages.run("explicit solve", stubborn) is None
    assert stages.notes[0].kind == "budget"


def test_skipped_and_too_large_stages_say_why() -> None:
    """StageSkipped gives a note of kind 'skipped', StageTooLarge one of kind 'size' whose reason starts with
    'too large' (the kind is the exception's, never read back from its sentence)."""
    stages = Stages(10.0)

    def skip(reason: str) -> None:
        raise StageSkipped(reason)

    def large(what: str) -> None:
        raise StageTooLarge(what)

    stages.run("effective potential", skip, "forces depend on t")
    stages.run("explicit solve", large, "3000 operations")
    stages.run("normal forces", skip, "too large, a sentence that only reads like a size")
    assert [(n.stage, n.kind) for n in stages.notes] == [("effective potential", "skipped"),
                                                         ("explicit solve", "size"), ("normal forces", "skipped")]
    assert stages.notes[1].reason == "too large: 3000 operations"
    assert StageNote("explicit solve", "too large", "size").sentence() == "Explicit solve: too large."


def test_not_applicable_notes_are_not_shown() -> None:
    """A stage with nothing to do is recorded but not among the notes a report shows."""
    stages = Stages(10.0)
    stages.skip("normal forces", "no friction acts", "n/a")
    stages.skip("effective potential", "L depends on t")
    assert [n.stage for n in stages.shown()] == ["effective potential"]


def test_shares_follow_the_weights_and_are_capped() -> None:
    """A stage's slice is its weight's part of what is left, never more than MAX_SHARE of the budget."""
    from lagsolve.mechanics.stages import MAX_SHARE

    stages = Stages(100.0)
    first = stages.slice_for("explicit solve")
    assert first <= 100.0 * MAX_SHARE + 1e-9
    assert first == pytest.approx(min(stages.left() * STAGES["explicit solve"] / sum(STAGES.values()),
                                      100.0 * MAX_SHARE), rel=1e-3)


def test_unknown_stage_is_a_bug() -> None:
    """Running a stage that is not declared in STAGES is a programming error."""
    with pytest.raises(KeyError):
        Stages(1.0).run("no such stage", lambda: None)


def test_inner_limit_is_cut_to_the_outer_one() -> None:
    """A limit inside a shorter outer limit stops at the outer one, and the outer one is restored after."""
    with pytest.raises(StageTimeout), cpu_limit(0.5), cpu_limit(30.0):
        _burn(60.0)
    with cpu_limit(30.0):
        with cpu_limit(0.3), pytest.raises(StageTimeout):
            _burn(60.0)
        assert _burn(0.2) == 0.2  # the outer limit is armed again, with time left


def test_a_timeout_inside_a_finaliser_is_not_reported_and_the_stage_still_stops() -> None:
    """A timeout that fires in a ``__del__`` (or a weakref callback during garbage collection) cannot be
    raised there; it must not reach ``sys.unraisablehook`` (pytest turns that into an error of the next
    test, the CLI into an "Exception ignored" on stderr), and the stage still times out on the next tick."""
    import gc
    import sys

    reported: list[object] = []
    previous = sys.unraisablehook
    sys.unraisablehook = lambda unraisable: reported.append(unraisable.exc_value)

    class Finalised:
        def __del__(self) -> None:
            raise StageTimeout  # as _raise_timeout does when SIGPROF lands in a finaliser

    try:
        with pytest.raises(StageTimeout), cpu_limit(0.3):
            Finalised()
            gc.collect()
            _burn(60.0)
        class Other:
            def __del__(self) -> None:
                raise ValueError("not a timeout")

        Other()
        gc.collect()
    finally:
        sys.unraisablehook = previous
    assert [type(e) for e in reported] == [ValueError]  # other unraisable errors are still reported
