"""A :class:`~lagsolve.mechanics.analysis.minimal_chart.MinimalChart` compiled: the integrator's state in minimal
coordinates.

The integrator then carries ``(q_I, q̇_I)`` only. :meth:`NumericChart.full` rebuilds the
whole state from it (the dependent coordinates and velocities from their closed forms,
which satisfy the constraints exactly), and :meth:`NumericChart.local` takes the
independent part of a whole state.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from lagsolve.mechanics.analysis.minimal_chart import MinimalChart
from lagsolve.numeric.compile import StateFunction, compile_state_function


@dataclass(frozen=True)
class NumericChart:
    """``independent``/``dependent`` index the coordinates; ``fill(t, q, qd, p_c)`` gives the
    dependent coordinates then velocities (``p_c`` is the parameters followed by the
    constants); ``integrals(t, q, qd, p)`` the constants' values at a whole state."""

    independent: np.ndarray
    dependent: np.ndarray
    fill: StateFunction
    integrals: StateFunction
    constant_names: tuple[str, ...]

    @property
    def size(self) -> int:
        return len(self.independent)

    def full(self, t: float, y: np.ndarray, n: int, extended: np.ndarray) -> np.ndarray:
        """The whole state ``(q, q̇)`` (length 2n) from the minimal one ``(q_I, q̇_I)``."""
        k = self.size
        q, qd = np.zeros(n), np.zeros(n)
        q[self.independent] = y[:k]
        qd[self.independent] = y[k:]
        values = self.fill(t, q, qd, extended)
        q[self.dependent] = values[: len(self.dependent)]
        qd[self.dependent] = values[len(self.dependent):]
        return np.concatenate([q, qd])

    def local(self, y: np.ndarray, n: int) -> np.ndarray:
        """The minimal state ``(q_I, q̇_I)`` of a whole one."""
        return np.concatenate([y[:n][self.independent], y[n:][self.independent]])

    def extended(self, t: float, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The parameters followed by the constants' values at the state ``(t, q, q̇)``."""
        return np.concatenate([p, self.integrals(t, q, qd, p)])


def compile_chart(chart: MinimalChart, prepare: Callable[[Any], Any], *, time: Any, coordinates: Sequence[Any],
                  velocities: Sequence[Any], parameters: Sequence[Any]) -> NumericChart:
    """Compile ``chart``; ``prepare`` substitutes concrete functions into an expression."""
    index = {q.name: i for i, q in enumerate(coordinates)}
    arguments = {"time": time, "coordinates": coordinates, "velocities": velocities}
    fill = compile_state_function([prepare(e) for e in (*chart.positions, *chart.velocities)],
                                  parameters=[*parameters, *chart.constants], **arguments)
    integrals = compile_state_function([prepare(e) for e in chart.integrals], parameters=parameters, **arguments)
    return NumericChart(
        independent=np.array([index[name] for name in chart.independent], dtype=int),
        dependent=np.array([index[name] for name in chart.dependent], dtype=int),
        fill=fill,
        integrals=integrals,
        constant_names=tuple(c.name for c in chart.constants),
    )
