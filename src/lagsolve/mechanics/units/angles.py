"""Angles given in degrees where radians are read: a warning with the value to write.

Angles are computed in radians (``sin(theta)`` reads theta in rad). A unit of ``deg`` is refused (the unit
system), but a number without a unit cannot say which it is: ``initial: {theta: 60}`` starts the pendulum 9.5 turns
round, at 197.7°, with exit 0. A value whose size is more than a whole turn, 2π, on a quantity the problem uses
only as an angle is almost always a number of degrees, so it gets a warning (the run goes on: a winding count such
as 7.5 rad can be meant).

A coordinate or parameter is used *as an angle* when its declared unit is ``rad``, or when it appears only inside
sines and cosines (and tangents), each time added to the argument with a numeric coefficient: ``sin(theta)``,
``cos(theta - alpha)``, ``sin(Omega*t + phi)`` (theta, alpha, phi); not ``sin(Omega*t)`` (Omega is a rate) nor
``sin(k*x)`` (x is a length).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import fields, is_dataclass
from typing import Any

import sympy

from lagsolve.problem.schema import Problem

_TRIG = (sympy.sin, sympy.cos, sympy.tan)


def angle_warnings(problem: Problem, values: Mapping[str, float] | None = None,
                   initial: Mapping[str, float] | None = None, swept: Mapping[str, Iterable[float]] | None = None
                   ) -> tuple[str, ...]:
    """One warning per value (a parameter's, an initial coordinate's) more than a whole turn on an angle.

    ``values`` and ``initial`` are the command line's (``--set``, ``--initial``): they replace the file's, so a
    file's value they override gets no warning and theirs are checked instead. ``swept`` are a sweep's values of
    each name it varies (``--grid``, ``--random``): they replace the file's too, and one warning says how far the
    sweep goes."""
    angles = _angles(problem)
    if not angles:
        return ()
    ranges = {name: max((abs(v) for v in vs if math.isfinite(v)), default=0.0) for name, vs in (swept or {}).items()}
    out = [f"{problem.source}: the swept {name} reaches {far:g}, an angle in radians, {far / (2 * math.pi):.3g} turns; "
           f"if you meant degrees, {far:g}° is {math.radians(far):.6g}"
           for name, far in ranges.items() if name in angles and far > 2 * math.pi]
    for field, name, value in _values(problem, dict(values or {}), dict(initial or {}), set(ranges)):
        if name in angles and math.isfinite(value) and abs(value) > 2 * math.pi:
            out.append(f"{_where(problem, field, name)}: {name} = {value:g} is an angle in radians, "
                       f"{abs(value) / (2 * math.pi):.3g} turns; if you meant {value:g}°, write "
                       f"{math.radians(value):.6g}")
    return tuple(out)


def _values(problem: Problem, values: dict[str, float], initial: dict[str, float], swept: set[str]
            ) -> list[tuple[str, str, float]]:
    """(field, name, value) of every number a run uses: the file's, unless the command line's or a sweep's
    replace it, and the command line's."""
    spec = problem.simulation
    found = [(f"parameters.{p.name}.value", p.name, p.value) for p in problem.parameters
             if p.value is not None and p.name not in values and p.name not in swept]
    if spec is not None:
        found += [(f"simulation.values.{name}", name, value) for name, value in spec.values.items()
                  if name not in values and name not in swept]
        found += [(f"simulation.initial.{name}", name, value) for name, value in spec.initial.items()
                  if name not in initial and name not in swept]
    found += [("--set", name, value) for name, value in values.items() if name not in swept]
    found += [("--initial", name, value) for name, value in initial.items() if name not in swept]
    return found


def _where(problem: Problem, field: str, name: str) -> str:
    """``FILE:LINE: field`` of a file's value, ``FILE: --set name`` of the command line's."""
    if field.startswith("--"):
        return f"{problem.source}: {field} {name}"
    return f"{problem.source}:{problem.lines.get(field, problem.lines.get(field.rsplit('.', 1)[0], 0))}: {field}"


def _angles(problem: Problem) -> set[str]:
    """The names of the coordinates and parameters ``problem`` uses as angles (see the module's docstring)."""
    named = {c.symbol: c for c in problem.coordinates} | {p.symbol: p for p in problem.parameters}
    inside: set[Any] = set()
    outside: set[Any] = set()
    for expr in _expressions(problem):
        _walk(expr, set(named), inside, outside)
    return {named[s].name for s in named
            if (s in inside and s not in outside) or getattr(named[s], "unit", None) == "rad"}


def _walk(expr: Any, symbols: set[Any], inside: set[Any], outside: set[Any]) -> None:
    """Sort the ``symbols`` met in ``expr``: added to a trig function's argument with a numeric coefficient
    (``inside``), or anywhere else (``outside``)."""
    stack = [expr]
    while stack:
        node = stack.pop()
        if isinstance(node, _TRIG):
            argument = node.args[0]
            for s in argument.free_symbols & symbols:
                (inside if sympy.diff(argument, s).is_number else outside).add(s)
            continue
        if node.is_Symbol:
            if node in symbols:
                outside.add(node)
            continue
        stack.extend(node.args)


def _expressions(problem: Problem) -> Iterator[Any]:
    """Every expression of the problem's model (not its expected answers or simulation settings)."""
    for f in fields(problem):
        if f.name in ("expected", "simulation", "symbols", "lines", "texts", "time", "parameters", "coordinates"):
            continue
        yield from _within(getattr(problem, f.name))


def _within(value: Any) -> Iterator[Any]:
    if isinstance(value, sympy.Basic):
        yield value
    elif isinstance(value, tuple | list):
        for item in value:
            yield from _within(item)
    elif isinstance(value, dict):
        for item in value.values():
            yield from _within(item)
    elif is_dataclass(value) and not isinstance(value, type):
        for f in fields(value):
            yield from _within(getattr(value, f.name))
