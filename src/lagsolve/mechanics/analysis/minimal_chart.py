r"""Minimal coordinates for the numeric stage: the dependent variables as functions of the independent ones.

When the analysis (:mod:`~lagsolve.mechanics.analysis.minimal`) solves every constraint in closed
form, :math:`q_d = \varphi_d(q_I, t)`, a simulation can integrate the independent
coordinates alone: the state is :math:`(q_I, \dot q_I)` and the dependent coordinates and
velocities follow from

.. math:: q_d = \varphi_d(q_I, t), \qquad
          \dot q_d = \sum_{k\in I} \frac{\partial\varphi_d}{\partial q_k}\dot q_k
                    + \frac{\partial\varphi_d}{\partial t},

so the constraints hold exactly at every step and nothing has to be projected.
:class:`MinimalChart` carries these expressions, and the integration constants a
velocity constraint introduced when it was integrated (:math:`\theta = \theta_0`) with
the expressions that give their values from the initial state.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.results import Analysis
    from lagsolve.mechanics.equations.model import Model


@dataclass(frozen=True)
class MinimalChart:
    """The closed-form reduction, in the shape the numeric stage needs.

    ``independent`` and ``dependent`` are coordinate names (input order); ``positions``
    and ``velocities`` give each dependent coordinate and velocity in the independent
    coordinates and velocities, time, parameters and ``constants``; ``integrals`` give
    each constant's value as an expression in the full state (evaluated at the start);
    ``sources`` name the constraint that fixes each dependent coordinate.
    """

    independent: tuple[str, ...]
    dependent: tuple[str, ...]
    positions: tuple[Any, ...]
    velocities: tuple[Any, ...]
    constants: tuple[Any, ...]
    integrals: tuple[Any, ...]
    sources: tuple[str, ...]


def minimal_chart(analysis: Analysis, model: Model) -> tuple[MinimalChart | None, str]:
    """The chart of ``analysis``'s reduced system (``model`` is the full one), or None and the
    reason there is none."""
    reduced = analysis.reduced
    if reduced is None:
        return None, analysis.reduced_note
    if reduced.agreement == "differ":
        return None, "the reduced equations disagree with the multiplier route"
    elimination = reduced.substitution
    coordinates, velocities = model.coordinates, model.velocities
    dependent = [i for i, q in enumerate(coordinates) if q in elimination.positions]
    if not dependent:
        return None, "there are no constraints to eliminate: the coordinates are already minimal"
    positions = tuple(elimination.apply(coordinates[i]) for i in dependent)
    rates = tuple(elimination.apply(velocities[i]) for i in dependent)
    removed = {coordinates[i] for i in dependent} | {velocities[i] for i in dependent}
    if any(e.free_symbols & removed for e in (*positions, *rates)):
        return None, "the constraints could not be solved one after another for the dependent coordinates"
    classes = [k for k in analysis.classification if k.constant is not None]
    return MinimalChart(
        independent=reduced.names,
        dependent=tuple(coordinates[i].name for i in dependent),
        positions=positions,
        velocities=rates,
        constants=tuple(k.constant for k in classes),
        integrals=tuple(k.integral for k in classes),
        sources=tuple(elimination.sources[coordinates[i]] for i in dependent),
    ), ""

