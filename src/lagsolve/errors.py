"""The one family of errors lagsolve raises on purpose.

``cli.py`` alone maps them to exit codes: :class:`SpecError` (bad input) → 2,
every other :class:`LagsolveError` (valid input, failed computation) → 1.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Issue:
    """One thing wrong with an input file.

    ``where`` is the dotted field path (``constraints.wire.holonomic``),
    ``line`` the 1-based line in the file (0 when unknown), ``message`` what is
    wrong and ``hint`` how to fix it.
    """

    file: str
    line: int
    where: str
    message: str
    hint: str = ""

    def __str__(self) -> str:
        place = f"{self.file}:{self.line}" if self.line else self.file
        text = f"{place}: {self.where}: {self.message}" if self.where else f"{place}: {self.message}"
        return f"{text}; {self.hint}" if self.hint else text


class LagsolveError(Exception):
    """Root of every error lagsolve raises on purpose."""


class SpecError(LagsolveError, ValueError):
    """The problem file (or a command-line value) is invalid; carries every issue found."""

    def __init__(self, issues: list[Issue] | tuple[Issue, ...]) -> None:
        self.issues = tuple(issues)
        super().__init__("\n".join(str(i) for i in self.issues))


class ExpressionError(LagsolveError, ValueError):
    """An expression string cannot be accepted; the loader turns it into an :class:`Issue`."""

    def __init__(self, message: str, hint: str = "") -> None:
        self.message = message
        self.hint = hint
        super().__init__(f"{message}; {hint}" if hint else message)


class DerivationError(LagsolveError, ArithmeticError):
    """A valid problem whose derivation failed (singular system, budget exceeded, ...)."""


class SimulationError(LagsolveError, RuntimeError):
    """A valid problem whose simulation failed (integrator failure, singular system at a state)."""


class RenderError(LagsolveError, RuntimeError):
    """A report could not be rendered (missing or broken template)."""
