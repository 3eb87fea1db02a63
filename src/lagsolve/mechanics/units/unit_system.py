r"""One system of units per file: lagsolve never converts a number, so a file that mixes scales is refused.

Every number a file gives (``value:``, ``simulation.values``, ``simulation.initial``, ``t_end``, ``--set``,
a sweep's grid) is used as written, in the unit declared for its quantity. That is right only when the
declared units form one *coherent system*: one unit for each base dimension (mass, length, time, ...) and
every declared unit a product of powers of those, with no number in front. SI (kg, m, s, N, J, rad) is one;
g, cm, s (dyn, erg) is another; kg, m, ms (with ``g`` in ``m/ms^2``) a third. A file with the time in ``ms``
and ``g`` in ``m/s^2``, a mass in ``g`` next to a spring in ``N/m``, a coordinate in ``km`` next to a length in
``m``, or an angle in ``deg`` (angles are computed in radians: ``sin(theta)`` reads theta in rad) would give
wrong numbers, so it is refused (:func:`scale_issues`), naming the quantity, its unit, the unit it must have in
the file's system, the factor and the values to write.

The file's system is fixed in this order: the time (``s`` unless declared), the coordinates, the parameters, the
declared functions. Each declared unit is a row :math:`(e_d)_d` of exponents of the base dimensions with the
logarithm of its size in SI, :math:`\ln|u|`; the units are coherent when the sizes follow from the exponents,
:math:`\ln|u| = \sum_d e_d \ln s_d` for some scales :math:`s_d`. The rows are reduced in order (Gaussian
elimination in exact fractions); a row that reduces to no exponents but a non-zero logarithm is a unit whose size
disagrees with those before it, which it names.

>>> from lagsolve.problem.load import load_text
>>> p = load_text('''
... name: fall
... time: {name: t, unit: ms}
... parameters: {g: {unit: m/s^2, value: 9.81}, m: {unit: kg}}
... coordinates: {y: {unit: m}}
... particles: {a: {mass: m, position: [0, y]}}
... gravity: [0, -g]
... ''')
>>> [issue.hint.split(', or')[0] for issue in scale_issues(p)]
['declare g: {unit: m/ms^2, value: 9.81e-06}']
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from lagsolve.errors import Issue, SpecError
from lagsolve.mechanics.units.dimensions import dimension, dimension_issues, dimension_text, quantity
from lagsolve.problem.schema import Problem
from lagsolve.problem.units import DEFAULT_TIME_UNIT, format_unit, registry, unit_of

#: two sizes agree when their logarithms differ by less than this (the factors are exact powers of ten, or π/180)
_TOLERANCE = 1e-9
_RULE = "(the units of a file must form one system: docs/format.md, Units)"


def check_units(problem: Problem) -> None:
    """Refuse a file whose units are wrong: a field of the wrong dimension, or units of mixed scales.

    Does nothing for a file without units, or one :func:`units_checked` passed. Every issue of both kinds is
    reported at once.

    Raises
    ------
    SpecError
        One issue per wrong field (:func:`~lagsolve.mechanics.units.dimensions.dimension_issues`) and per unit that is
        not of the file's system (:func:`scale_issues`).
    """
    if not problem.has_units or problem.units_checked:
        return
    issues = dimension_issues(problem) + scale_issues(problem)
    if issues:
        raise SpecError(sorted(issues, key=lambda issue: issue.line))


def units_checked(problem: Problem) -> Problem:
    """``problem`` once :func:`check_units` passed, marked so that a derivation does not check it again: the command's
    process checks a file's units as it loads it (with pint, which it imports for loading anyway), and its budgeted
    child, which derives, then needs no pint (about a tenth of a second of ``lagsolve derive``).

    Raises
    ------
    SpecError
        As :func:`check_units`.
    """
    if not problem.has_units or problem.units_checked:
        return problem
    check_units(problem)
    return dataclasses.replace(problem, units_checked=True)


@dataclass(frozen=True)
class _Declared:
    """A declared unit: whose (``label``), where the file says it, as written, and the numbers given in it."""

    label: str
    kind: str  # "the coordinate ", "the parameter ", ... ("" for the time)
    where: str
    text: str
    unit: Any
    values: tuple[tuple[str, float], ...] = ()


@dataclass
class _Row:
    """A declared unit as exponents of the base dimensions and the logarithm of its SI size, as a combination of
    declared units (their index → power)."""

    exponents: dict[str, Fraction]
    log: float
    combination: dict[int, Fraction]

    def subtract(self, factor: Fraction, other: _Row) -> None:
        for base, e in other.exponents.items():
            self.exponents[base] = self.exponents.get(base, Fraction(0)) - factor * e
        self.log -= float(factor) * other.log
        for index, power in other.combination.items():
            self.combination[index] = self.combination.get(index, Fraction(0)) - factor * power


def scale_issues(problem: Problem) -> list[Issue]:
    """One issue per declared unit that is not of the system fixed by the units before it (see the module).

    Empty for a file without units or with coherent ones.
    """
    if not problem.has_units:
        return []
    declared = _declared(problem)
    basis: list[tuple[str, _Row]] = []
    issues: list[Issue] = []
    for index, item in enumerate(declared):
        size = (1 * item.unit).to_base_units()
        row = _Row({base: _fraction(e) for base, e in dict(item.unit.dimensionality).items() if e},
                   math.log(abs(float(size.magnitude))), {index: Fraction(1)})
        for pivot, previous in basis:
            factor = row.exponents.get(pivot, Fraction(0)) / previous.exponents[pivot]
            if factor:
                row.subtract(factor, previous)
        lead = next((base for base, e in row.exponents.items() if e), None)
        if lead is not None:
            basis.append((lead, row))  # the first unit of a new base dimension: it fixes that dimension's scale
        elif abs(row.log) > _TOLERANCE:
            powers = [(declared[i], -p) for i, p in row.combination.items() if i != index and p]
            issues.append(_issue(problem, item, powers))
    return issues


def _fraction(exponent: float) -> Fraction:
    return Fraction(exponent).limit_denominator(12)


def _declared(problem: Problem) -> list[_Declared]:
    """The declared units in the order that fixes the system: the time, the coordinates, parameters, functions."""
    spec = problem.simulation
    initial = spec.initial if spec is not None else {}
    values = spec.values if spec is not None else {}
    time_text = problem.time_unit or DEFAULT_TIME_UNIT
    out = [_Declared("the time", "", "time.unit" if problem.time_unit else "time", time_text, unit_of(time_text))]
    for c in problem.coordinates:
        if c.unit is not None:
            given = tuple((f"simulation.initial.{k}", initial[k]) for k in (c.name, f"{c.name}_dot") if k in initial)
            out.append(_Declared(c.name, "the coordinate ", f"coordinates.{c.name}.unit", c.unit, unit_of(c.unit),
                                 given))
    for p in problem.parameters:
        if p.unit is not None:
            given = (((f"parameters.{p.name}.value", p.value),) if p.value is not None else ()) + (
                ((f"simulation.values.{p.name}", values[p.name]),) if p.name in values else ())
            out.append(_Declared(p.name, "the parameter ", f"parameters.{p.name}.unit", p.unit, unit_of(p.unit),
                                 given))
    for f in problem.functions:
        if f.unit is not None:
            out.append(_Declared(f.name, "the function ", f"functions.{f.name}.unit", f.unit, unit_of(f.unit)))
    return out


def _radians(unit: Any) -> float:
    """The power of the radian in ``unit``'s SI form (``deg/s`` → 1; ``N*m/rad`` → -1)."""
    return float(dict((1 * unit).to_base_units().unit_items()).get("radian", 0))


def _power(unit: Any, power: Fraction) -> Any:
    return unit ** (int(power) if power.denominator == 1 else float(power))


def _issue(problem: Problem, item: _Declared, powers: list[tuple[_Declared, Fraction]]) -> Issue:
    """The issue for ``item``, whose unit disagrees with the system fixed by ``powers`` (what its unit must be
    made of); no ``powers``: a pure number (or an angle) with a size, like ``deg`` or ``percent``."""
    ureg = registry()
    wanted = ureg.dimensionless
    for other, power in powers:
        wanted = wanted * _power(other.unit / ureg.radian ** _radians(other.unit), power)
    radians = _radians(item.unit)
    if radians:
        wanted = wanted * ureg.radian ** radians
    wanted_text = format_unit(wanted)
    factor = float((1 * item.unit).to(wanted).magnitude)
    conversion = f"1 {item.text} = {factor:.6g}" + (f" {wanted_text}" if wanted_text != "1" else "")
    if powers:
        system = " and ".join(dict.fromkeys(f"{other.kind}{other.label} in {other.text}" for other, _ in powers))
        kind = quantity(dimension(item.unit)) or "a quantity of this kind"
        reason = f"with {system}, {kind} is in {wanted_text} ({conversion})"
    elif radians:
        reason = f"angles are computed in radians (sin({item.label}) reads {item.label} in rad; {conversion})"
    else:
        reason = f"a pure number has no unit ({conversion})"
    used = ", and lagsolve never converts a unit"
    if item.values:
        field, number = item.values[0]
        used += f": {field} = {number:g} would be used as {number:g}" + (f" {wanted_text}" if wanted_text != "1"
                                                                          else "")
    message = f"{item.label} is declared in {item.text}, but {reason}{used}"
    return Issue(problem.source, _line(problem, item.where), item.where, message, _fix(item, powers, wanted_text,
                                                                                      factor))


def _fix(item: _Declared, powers: list[tuple[_Declared, Fraction]], wanted: str, factor: float) -> str:
    """``declare g: {unit: m/ms^2, value: 9.81e-06}, or use SI units: the time in s; ...``"""
    value = next((v for field, v in item.values if field.endswith(".value")), None)
    declaration = f"{{unit: {wanted}" + (f", value: {value * factor:.6g}}}" if value is not None else "}")
    others = [f"{field}: {v * factor:.6g}" for field, v in item.values if not field.endswith(".value")]
    fix = f"declare {item.label}: {declaration}" + (f" and give {', '.join(others)}" if others else "")
    if powers and _coherent_si(item.unit):
        not_si = [f"{other.kind}{other.label} in {dimension_text(dimension(other.unit))}" for other, _ in powers
                  if not _coherent_si(other.unit)]
        if not_si:
            fix += ", or use SI units: " + ", ".join(dict.fromkeys(not_si))
    return f"{fix} {_RULE}"


def _coherent_si(unit: Any) -> bool:
    """Whether ``unit`` is coherent SI (kg, m, s, N, J, rad and their products, no prefix)."""
    return abs(float((1 * unit).to_base_units().magnitude) - 1.0) < 1e-12


def _line(problem: Problem, where: str) -> int:
    """The line of ``where`` (``parameters.g.unit``), or of the quantity, or of the file's start."""
    lines = problem.lines
    return lines.get(where) or lines.get(where.rsplit(".", 1)[0]) or lines.get("", 0)
