"""Equilibria and small-oscillation frequencies at a variant's values, for its key.

The analysis gives them in closed form (the effective potential's equilibria of one coordinate, else the normal
modes about equilibria of an unconstrained system); each is evaluated at the variant's parameters and kept only
where it exists there (real) and the second route agrees: the compiled equations give zero accelerations at the
equilibrium at rest, and ω² = −∂q̈/∂q by central differences of them (for several coordinates, the eigenvalues
of that matrix). Equilibrium ``i`` keeps the analysis's numbering, so an answer has the same name in every variant
where it exists.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import sympy

from lagsolve.errors import LagsolveError
from lagsolve.mechanics.results import Derivation
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.system import NumericSystem

#: what an equilibrium's accelerations may be, relative to max(1, the largest parameter value)
AT_REST = 1e-6
#: relative agreement of ω² with its central difference
FREQUENCY = 1e-4

Evaluate = Callable[[Any], float]
Add = Callable[[str, float, float, str, str, float], None]


def _points(derivation: Derivation) -> list[tuple[dict[str, Any], Any, list[Any]]]:
    """(point, stable, ω² list) of each equilibrium in closed form (the point {} where it is numeric); [] for a
    system the second route cannot linearise (normal modes of a constrained system)."""
    analysis = derivation.analysis
    if analysis is None:
        return []
    potential, linear = analysis.effective_potential, analysis.linearization
    if potential is not None and potential.equilibria:
        return [({str(potential.coordinate): eq.value}, eq.stable,
                 [eq.frequency_squared] if eq.frequency_squared is not None else [])
                for eq in potential.equilibria if eq.value is not None]
    if linear is not None and linear.modes and not derivation.problem.constraints:
        # a point or ω² found numerically (a Float: at the file's simulation values, the triple pendulum's ω²) is
        # no closed form at a variant's values: it is left out (it failed the second route, every candidate)
        return [({} if any(_numeric(v) for _, v in mode.point) else {str(q): v for q, v in mode.point}, mode.stable,
                 [w for w in mode.squared_frequencies or [] if not _numeric(w)]) for mode in linear.modes]
    return []


def _numeric(value: Any) -> bool:
    """A value found numerically at the file's values (it holds a Float; closed forms are exact)."""
    return isinstance(value, sympy.Basic) and bool(value.atoms(sympy.Float))


def _accelerations(system: NumericSystem, point: Mapping[str, float]) -> np.ndarray | None:
    given = {**point, **{f"{q}_dot": 0.0 for q in point}}
    try:
        q, qd = complete_initial(system, given)
    except LagsolveError:
        return None
    return np.asarray(system.solve(0.0, q, qd)[0], dtype=float)


def _squares(system: NumericSystem, point: Mapping[str, float]) -> list[float] | None:
    """ω² by central differences: the eigenvalues of −∂q̈/∂q over the point's coordinates."""
    names = list(point)
    index = [system.coordinates.index(n) for n in names]
    jacobian = np.zeros((len(names), len(names)))
    for j, name in enumerate(names):
        h = 1e-5 * max(1.0, abs(point[name]))
        up = _accelerations(system, {**point, name: point[name] + h})
        down = _accelerations(system, {**point, name: point[name] - h})
        if up is None or down is None:
            return None
        jacobian[:, j] = -(up[index] - down[index]) / (2 * h)
    return sorted(float(x.real) for x in np.linalg.eigvals(jacobian))


def equilibrium_answers(derivation: Derivation, system: NumericSystem, evaluate: Evaluate, add: Add,
                        scale: float) -> None:
    """Adds ``equilibrium_<i>_<q>`` and ``omega_<i>`` (ω, of the equilibria not known to be unstable) through
    ``add(name, closed form, second route, what, how checked, tolerance)``."""
    for i, (point, stable, squares) in enumerate(_points(derivation), start=1):
        values = {q: evaluate(v) for q, v in point.items()}
        if not values or not all(math.isfinite(v) for v in values.values()):
            continue  # this equilibrium does not exist at the variant's values
        rest = _accelerations(system, values)
        if rest is None:
            continue
        residual = float(np.max(np.abs(rest))) if rest.size else 0.0
        for q, v in values.items():
            add(f"equilibrium_{i}_{q}", v, v if residual <= AT_REST * scale else math.nan,
                f"{q} at equilibrium {i}", "zero accelerations there (compiled equations)", 1e-12)
        expected = sorted(evaluate(w) for w in squares)
        if stable is False or not expected or not all(math.isfinite(w) and w > 0 for w in expected):
            continue
        found = _squares(system, values)
        if found is None or len(found) != len(expected):
            continue
        for k, (w, f) in enumerate(zip(expected, found, strict=True), start=1):
            suffix = "" if len(expected) == 1 else f"_{k}"
            add(f"omega_{i}{suffix}", math.sqrt(w), math.sqrt(f) if f > 0 else math.nan,
                f"angular frequency of small oscillations about equilibrium {i}",
                "central differences of the compiled equations", FREQUENCY)
