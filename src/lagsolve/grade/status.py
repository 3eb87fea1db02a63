"""The statuses of a graded step (the contract's five) and the verdict on one entry of a step."""

from __future__ import annotations

from dataclasses import dataclass

from lagsolve.enums import TextEnum


class GradeStatus(TextEnum):
    """A step's status (the contract's five)."""

    CORRECT = "correct"
    INCORRECT = "incorrect"
    FOLLOWS = "follows"
    MISSING = "missing"
    UNREADABLE = "unreadable"


CORRECT, INCORRECT, FOLLOWS = GradeStatus.CORRECT, GradeStatus.INCORRECT, GradeStatus.FOLLOWS
MISSING, UNREADABLE = GradeStatus.MISSING, GradeStatus.UNREADABLE


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
