"""Random numeric states for the checks that decide by evaluation (a knife edge, an internal constraint, a
surface's identity): a positive symbol gets a value in [0.5, 2], any other one in [-2, 2]."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol


class Uniform(Protocol):
    """What draws the values: ``random.Random`` or NumPy's ``Generator``."""

    def uniform(self, low: float, high: float) -> Any: ...  # noqa: D102


def random_point(symbols: Sequence[Any], rng: Uniform) -> list[float]:
    """One value per symbol, drawn from ``rng``."""
    return [rng.uniform(0.5, 2.0) if s.is_positive else rng.uniform(-2.0, 2.0) for s in symbols]
