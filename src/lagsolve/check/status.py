"""A check verdict's status, in a module of its own: the parent process reads the statuses of the
plain rows a check sends back without importing SymPy."""

from __future__ import annotations

from lagsolve.enums import TextEnum


class Status(TextEnum):
    """A verdict's status (``Verdict.status``)."""

    OK = "ok"
    WARNING = "warning"
    MISMATCH = "mismatch"
    UNCHECKED = "unchecked"
