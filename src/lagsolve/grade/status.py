"""The statuses of a graded step (the contract's five, and ``ungraded``) and the verdict on one entry of a step."""

from __future__ import annotations

from dataclasses import dataclass

from lagsolve.enums import TextEnum


class GradeStatus(TextEnum):
    """A step's status: the contract's five, and ``ungraded`` (the comparison used up its CPU budget: 0 points
    until an instructor grades the step by hand)."""

    CORRECT = "correct"
    INCORRECT = "incorrect"
    FOLLOWS = "follows"
    MISSING = "missing"
    UNREADABLE = "unreadable"
    UNGRADED = "ungraded"


CORRECT, INCORRECT, FOLLOWS = GradeStatus.CORRECT, GradeStatus.INCORRECT, GradeStatus.FOLLOWS
MISSING, UNREADABLE, UNGRADED = GradeStatus.MISSING, GradeStatus.UNREADABLE, GradeStatus.UNGRADED


@dataclass(frozen=True)
class Entry:
    """The verdict on one entry of a step."""

    name: str
    status: GradeStatus
    mistake: str | None = None
    message: str = ""


def label(name: str) -> str:
    """``name: `` before an entry's message (nothing for a step of one expression)."""
    return f"{name}: " if name else ""
