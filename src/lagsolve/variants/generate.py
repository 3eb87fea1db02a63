"""Candidate numbers for one variant: drawn from a seeded NumPy Generator, rounded to significant figures,
and the initial state completed onto the constraints (the file's velocities that a varied parameter fixes,
``phi_dot = Omega`` say, follow it).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from lagsolve.errors import SpecError
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.system import NumericSystem
from lagsolve.problem.schema import Problem
from lagsolve.variants.spec import Vary


@dataclass(frozen=True)
class Candidate:
    """One draw: every parameter's value, the initial values the file states (completed), and the full state."""

    values: dict[str, float]
    initial: dict[str, float]
    q0: np.ndarray
    qd0: np.ndarray
    varied: dict[str, float]


def round_sig(value: float, figures: int) -> float:
    """``value`` rounded to ``figures`` significant figures (0 stays 0).

    >>> round_sig(0.123456, 3), round_sig(2718.28, 2), round_sig(-0.0004567, 2)
    (0.123, 2700.0, -0.00046)
    """
    if value == 0 or not math.isfinite(value):
        return value
    return float(f"{value:.{figures}g}")


def draw(rng: np.random.Generator, vary: tuple[Vary, ...], figures: int) -> dict[str, float]:
    """One value per varied name, in the order given: uniform in [low, high], or a grid point low + k·step."""
    out: dict[str, float] = {}
    for v in vary:
        if v.step is None:
            value = float(rng.uniform(v.low, v.high))
        else:
            points = int(math.floor((v.high - v.low) / v.step + 1e-9)) + 1
            value = v.low + v.step * int(rng.integers(0, points))
        out[v.name] = round_sig(value, figures)
    return out


def file_values(problem: Problem) -> dict[str, float]:
    """The parameter values a simulation of the file uses: each parameter's default, then ``simulation.values``."""
    values = {p.name: float(p.value) for p in problem.parameters if p.value is not None}
    if problem.simulation:
        values.update({k: float(v) for k, v in problem.simulation.values.items()})
    return values


def _complete(system: NumericSystem, given: dict[str, float], varied: set[str],
              source: str) -> tuple[np.ndarray, np.ndarray]:
    """The state from ``given``; if it violates the constraints (a varied radius or rate of turn), the same
    without one of the file's values that were not varied (velocities first, then coordinates, in the file's
    order: the first that makes it consistent), else without all the file's velocities, else without all."""
    try:
        return complete_initial(system, given, source)
    except SpecError:
        pass
    fixed = [k for k in given if k not in varied]
    velocities = [k for k in fixed if k.endswith("_dot")]
    trials = [[k] for k in velocities] + [[k] for k in fixed if k not in velocities] + [velocities]
    for dropped in trials:
        try:
            return complete_initial(system, {n: v for n, v in given.items() if n not in dropped}, source,
                                    start=given)
        except SpecError:
            continue
    return complete_initial(system, {n: v for n, v in given.items() if n in varied}, source, start=given)


def candidate(problem: Problem, system: NumericSystem, varied: Mapping[str, float],
              vary: tuple[Vary, ...]) -> Candidate:
    """The variant's numbers: parameters (the system is bound to them), and the initial state completed.

    The file's initial values come first, the varied ones over them; when the velocities then violate the
    constraints (a varied rate of turn), the file's velocities that were not varied are dropped and solved
    from the constraints instead. ``initial`` holds the names the file gives, with their completed values.

    Raises
    ------
    SpecError
        The initial state cannot be completed (the candidate is rejected, not the run).
    """
    initial_names = {v.name for v in vary if v.initial}
    spec = problem.simulation
    given = {**(dict(spec.initial) if spec else {}), **{k: varied[k] for k in initial_names}}
    q0, qd0 = _complete(system, given, initial_names, problem.source)
    state = {**dict(zip(system.coordinates, map(float, q0), strict=True)),
             **{f"{c}_dot": float(v) for c, v in zip(system.coordinates, qd0, strict=True)}}
    initial = {k: state[k] for k in given}
    values = {**file_values(problem), **{k: v for k, v in varied.items() if k not in initial_names}}
    return Candidate(values, initial, q0, qd0, dict(varied))
