"""The base of lagsolve's enumerations of kinds, verdicts, events and options.

A :class:`TextEnum` member *is* its text (a :class:`~enum.StrEnum`): it compares equal to it, formats
as it, goes into JSON and templates as it, and shows as it (``repr`` gives the text's repr), so a
result reads the same as before the enumeration existed while code names each value once.
"""

from __future__ import annotations

from enum import StrEnum


class TextEnum(StrEnum):
    """A string enumeration that shows as its text: ``repr(Status.OK) == "'ok'"``."""

    def __repr__(self) -> str:
        return repr(self.value)
