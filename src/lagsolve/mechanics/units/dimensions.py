r"""Dimensional analysis of a problem that declares units, before anything is derived.

Each symbol gets the unit declared for it (:mod:`lagsolve.problem.units`): a velocity
``q_dot`` has the unit of ``q`` per unit of time, the time has ``s`` unless the file says
otherwise, and a declared function ``f(...)`` has the unit declared for its value. The unit of
an expression follows from its tree:

* a sum must be homogeneous (every term the same dimension);
* a product multiplies units, a power :math:`u^{p}` with a number ``p`` raises it; a symbolic
  exponent needs a dimensionless base and exponent;
* the argument of ``sin``, ``cos``, ``exp``, ``log``, ``atan``, ... must be dimensionless (angles in
  ``rad`` are: pint counts the radian as dimensionless), and so is the result; ``atan2(y, x)``
  needs ``y`` and ``x`` alike; ``Abs`` keeps the unit;
* :math:`\partial^n f/\partial x^n` has the unit of ``f`` over that of ``x`` to the ``n``.

A symbol without a declared unit makes every expression it enters *unknown*, and an unknown
dimension is never refused: a file with some units but not all is checked where it can be (and
warned about, :func:`missing_units`).

What each field must be: ``kinetic`` and ``potential`` energies, ``dissipation`` a power,
masses masses, positions and contact points lengths, inertias mass times length squared,
angular velocities rates, ``gravity`` an acceleration, a force on a particle a force, a
generalized force :math:`Q_q` such that :math:`Q_q\,q` is an energy (a force for a length, a
torque for an angle), and a friction coefficient a pure number. Each constraint is homogeneous
(a velocity constraint term by term), which the rule for sums checks.

The units of the results are in :mod:`lagsolve.mechanics.units.result_units`.

>>> from lagsolve.problem.load import load_text
>>> p = load_text('''
... name: spring
... parameters: {k: {unit: N/m}, m: {unit: kg}}
... coordinates: {x: {unit: m}}
... particles: {a: {mass: m, position: [x, 0]}}
... potential: k*x/2
... ''')
>>> try:
...     check_dimensions(p)
... except SpecError as error:
...     print(error.issues[0].message)
k*x/2 has dimension kg*m/s^2 (force), but it must be an energy (kg*m^2/s^2)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy

from lagsolve.errors import Issue, SpecError
from lagsolve.problem.schema import Problem
from lagsolve.problem.units import DEFAULT_TIME_UNIT, registry, unit_of

#: pint's base dimensions, written with their SI unit
_BASE = {"[mass]": "kg", "[length]": "m", "[time]": "s", "[current]": "A", "[temperature]": "K",
         "[substance]": "mol", "[luminosity]": "cd"}
_ORDER = tuple(_BASE)
#: SymPy functions whose argument (and value) are pure numbers
_PURE = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.asin, sympy.acos, sympy.atan,
         sympy.sinh, sympy.cosh, sympy.tanh, sympy.exp, sympy.log)
#: names of some dimensions (mass, length, time exponents), for messages
_NAMES: dict[tuple[tuple[str, float], ...], str] = {
    (): "dimensionless", (("[length]", 1),): "length", (("[mass]", 1),): "mass", (("[time]", 1),): "time",
    (("[length]", 1), ("[time]", -1)): "velocity", (("[length]", 1), ("[time]", -2)): "acceleration",
    (("[time]", -1),): "rate", (("[mass]", 1), ("[length]", 1), ("[time]", -2)): "force",
    (("[mass]", 1), ("[length]", 2), ("[time]", -2)): "energy",
    (("[mass]", 1), ("[length]", 2), ("[time]", -3)): "power",
    (("[mass]", 1), ("[length]", 1), ("[time]", -1)): "momentum",
    (("[mass]", 1), ("[length]", 2)): "moment of inertia",
    (("[mass]", 1), ("[time]", -2)): "force per length", (("[mass]", 1), ("[time]", -1)): "force per velocity",
}
_ARTICLE = {"energy": "an energy", "acceleration": "an acceleration", "dimensionless": "dimensionless",
            "rate": "a rate (per time)", "moment of inertia": "a moment of inertia"}


class _Mismatch(Exception):
    """Inside an expression: an inhomogeneous sum, or a function of a dimensional argument."""

    def __init__(self, message: str, hint: str) -> None:
        super().__init__(message)
        self.message = message
        self.hint = hint


Dimension = tuple[tuple[str, float], ...]


def dimension(unit: Any) -> Dimension:
    """The dimension of a pint unit as sorted (base, exponent) pairs; ``()`` for a pure number (or an angle)."""
    dims = {d: _exponent(e) for d, e in dict(unit.dimensionality).items()}
    known = [(d, dims[d]) for d in _ORDER if dims.get(d)]
    other = sorted((d, e) for d, e in dims.items() if d not in _BASE and e)
    return tuple([*known, *other])


def _exponent(e: float) -> float:
    """An exponent rounded to 9 decimals, a whole one as an int: (1/3 + 2/3 in floats) is 1."""
    rounded = round(float(e), 9)
    return int(round(rounded)) if abs(rounded - round(rounded)) < 1e-9 else rounded


def dimension_text(dim: Dimension) -> str:
    """``kg*m/s^2``: a dimension in SI base units (``1`` for a pure number)."""
    return fraction_text([(_BASE.get(d, d.strip("[]")), e) for d, e in dim]) or "1"


def describe(dim: Dimension) -> str:
    """``kg*m/s^2 (force)``, or just the units when the dimension has no common name."""
    name = _NAMES.get(dim)
    text = dimension_text(dim)
    return f"{text} ({name})" if name and name != "dimensionless" else text if name is None else "1 (dimensionless)"


def quantity(dim: Dimension) -> str:
    """``an acceleration``, ``a force``: the common name of a dimension with its article, or ``""``."""
    name = _NAMES.get(dim)
    if name is None:
        return ""
    return "a pure number" if name == "dimensionless" else _ARTICLE.get(name, f"a {name}")


def fraction_text(parts: Iterable[tuple[str, float]]) -> str:
    def power(name: str, e: float) -> str:
        e = abs(e)
        return name if e == 1 else f"{name}^{e:g}"

    parts = list(parts)
    top = "*".join(power(n, e) for n, e in parts if e > 0)
    bottom = [power(n, e) for n, e in parts if e < 0]
    if not bottom:
        return top
    under = bottom[0] if len(bottom) == 1 else "(" + "*".join(bottom) + ")"
    return f"{top or '1'}/{under}"


# -- the unit of an expression --------------------------------------------------------------------


@dataclass
class UnitAlgebra:
    """The units of a problem's symbols and functions, and the unit of any expression in them.

    ``symbols`` maps a SymPy symbol to its pint unit, or to None when no unit is declared; a symbol
    not in it (a multiplier, a momentum) is unknown too.
    """

    symbols: dict[Any, Any]
    functions: dict[str, Any]
    time: Any
    cache: dict[Any, Any] = field(default_factory=dict)

    def of(self, expr: Any) -> Any:
        """The pint unit of ``expr``, or None when a symbol in it has no unit.

        Raises ``_Mismatch`` for a sum that is not homogeneous or a function of a dimensional argument.
        """
        if expr in self.cache:
            return self.cache[expr]
        unit = self._of(expr)
        self.cache[expr] = unit
        return unit

    def known(self, expr: Any) -> Any:
        """The unit of ``expr`` as :meth:`of` gives it, or None also when it is not homogeneous."""
        try:
            return self.of(expr)
        except _Mismatch:
            return None

    def _of(self, expr: Any) -> Any:
        """The unit of ``expr`` from its tree (module docstring), not cached: by the kind of its head."""
        if expr.is_Number or expr.is_NumberSymbol or expr in (sympy.pi, sympy.E, sympy.I):
            return self._number(expr)
        if expr.is_Symbol:
            return self.symbols.get(expr)
        if expr.is_Add:
            return self._sum(expr)
        if expr.is_Mul:
            return self._product(expr)
        if expr.is_Pow:
            return self._power(expr)
        return self._function(expr)

    @staticmethod
    def _number(expr: Any) -> Any:
        """A number is dimensionless, but 0 has every dimension (None)."""
        if expr.is_zero is True and expr.is_Number:
            return None  # 0 has every dimension
        return registry().dimensionless

    def _product(self, expr: Any) -> Any:
        """The product of the factors' units; None when one is unknown."""
        units = [self.of(a) for a in expr.args]
        if any(u is None for u in units):
            return None
        out = registry().dimensionless
        for u in units:
            out = out * u
        return out

    def _function(self, expr: Any) -> Any:
        """The unit of a function's value, its arguments checked: a pure function's and ``atan2``'s are
        dimensionless, ``Abs`` keeps its argument's, a declared function has the unit declared for it, anything
        else (Piecewise, Subs, ...) is checked inside and its own unit unknown."""
        one = registry().dimensionless
        if isinstance(expr, _PURE):
            self._pure(expr, expr.args[0])
            return one
        if isinstance(expr, sympy.atan2):
            self._sum(sympy.Add(*expr.args, evaluate=False), shown=expr, what="the two arguments of atan2")
            return one
        if isinstance(expr, sympy.Abs):
            return self.of(expr.args[0])
        if isinstance(expr, sympy.sign):
            self.of(expr.args[0])
            return one
        if isinstance(expr, sympy.Derivative):
            return self._derivative(expr)
        if isinstance(expr, sympy.core.function.AppliedUndef):
            for a in expr.args:
                self.of(a)
            return self.functions.get(expr.func.__name__)
        for a in expr.args:  # anything else (Piecewise, Subs, ...): checked inside, its own unit unknown
            if isinstance(a, sympy.Expr):
                self.of(a)
        return None

    def _derivative(self, expr: Any) -> Any:
        """The unit of f over that of x to the n, for each variable x differentiated n times; None when one is
        unknown."""
        unit = self.of(expr.expr)
        for var, n in expr.variable_count:
            v = self.of(var)
            if unit is None or v is None:
                return None
            unit = unit / v ** int(n)
        return unit

    def _sum(self, expr: Any, shown: Any = None, what: str = "") -> Any:
        first: tuple[Any, Any] | None = None
        for term in expr.args:
            unit = self.of(term)
            if unit is None:
                continue
            if first is None:
                first = (term, unit)
            elif dimension(unit) != dimension(first[1]):
                where = what or "the terms"
                raise _Mismatch(
                    f"in {_text(shown if shown is not None else expr)}, {where} {_text(first[0])} "
                    f"[{describe(dimension(first[1]))}] and {_text(term)} [{describe(dimension(unit))}] "
                    "have different dimensions",
                    "every term of a sum must have the same dimension; check the units declared for "
                    + _symbols_of(sympy.Add(first[0], term, evaluate=False)))
        return first[1] if first is not None else None

    def _power(self, expr: Any) -> Any:
        base, exponent = expr.args
        unit = self.of(base)
        if exponent.is_Number:
            if unit is None:
                return None
            p = int(exponent) if exponent.is_Integer else float(exponent)
            return unit ** p
        exponent_unit = self.of(exponent)
        for part, u in ((exponent, exponent_unit), (base, unit)):
            if u is not None and dimension(u):
                raise _Mismatch(f"in {_text(expr)}, {_text(part)} has dimension {describe(dimension(u))}, but "
                                "a power with a symbolic exponent needs a dimensionless base and exponent",
                                "make the base a ratio of like quantities")
        return registry().dimensionless if unit is not None and exponent_unit is not None else None

    def _pure(self, expr: Any, argument: Any) -> None:
        unit = self.of(argument)
        if unit is not None and dimension(unit):
            name = type(expr).__name__
            raise _Mismatch(f"the argument of {name}, {_text(argument)}, has dimension "
                            f"{describe(dimension(unit))}, but it must be dimensionless",
                            f"{name} takes a pure number (an angle in rad is one): divide by a quantity of the "
                            f"same dimension, or check the units declared for {_symbols_of(argument)}")


def _text(expr: Any) -> str:
    text = str(expr)
    return text if len(text) <= 120 else text[:117] + "..."


def _symbols_of(expr: Any) -> str:
    names = sorted({s.name for s in expr.free_symbols} | {f.func.__name__ for f in expr.atoms(
        sympy.core.function.AppliedUndef)})
    return ", ".join(names) if names else "its terms"


def algebra(problem: Problem) -> UnitAlgebra:
    """The units of ``problem``'s symbols (see :class:`UnitAlgebra`)."""
    time = unit_of(problem.time_unit or DEFAULT_TIME_UNIT)
    symbols: dict[Any, Any] = {problem.time: time}
    for p in problem.parameters:
        symbols[p.symbol] = unit_of(p.unit) if p.unit is not None else None
    for c in problem.coordinates:
        unit = unit_of(c.unit) if c.unit is not None else None
        symbols[c.symbol] = unit
        symbols[c.velocity] = unit / time if unit is not None else None
        symbols[c.acceleration] = unit / time ** 2 if unit is not None else None
    functions = {f.name: unit_of(f.unit) if f.unit is not None else None for f in problem.functions}
    return UnitAlgebra(symbols, functions, time)


# -- the checks ---------------------------------------------------------------------------------------


_M, _L, _T = "[mass]", "[length]", "[time]"
#: the dimensions the checks ask for, in :func:`dimension`'s order (written out: no pint needed to import this)
ENERGY: Dimension = ((_M, 1), (_L, 2), (_T, -2))
POWER: Dimension = ((_M, 1), (_L, 2), (_T, -3))
FORCE: Dimension = ((_M, 1), (_L, 1), (_T, -2))
LENGTH: Dimension = ((_L, 1),)
MASS: Dimension = ((_M, 1),)
ACCELERATION: Dimension = ((_L, 1), (_T, -2))
INERTIA: Dimension = ((_M, 1), (_L, 2))
RATE: Dimension = ((_T, -1),)


def check_dimensions(problem: Problem) -> None:
    """Refuse a problem whose declared units make a field the wrong kind of quantity.

    Does nothing for a problem that declares no unit. The derivation runs
    :func:`lagsolve.mechanics.units.unit_system.check_units`, which also refuses units of mixed scales.

    Raises
    ------
    SpecError
        One issue per wrong field (file, line, field, the dimension found and the one needed, a hint).
    """
    issues = dimension_issues(problem)
    if issues:
        raise SpecError(sorted(issues, key=lambda issue: issue.line))


def dimension_issues(problem: Problem) -> list[Issue]:
    """One issue per field of ``problem`` whose declared units make it the wrong kind of quantity (see
    :func:`check_dimensions`); empty for a problem that declares no unit."""
    if not problem.has_units:
        return []
    fields = _Fields(problem, algebra(problem))
    _check_members(problem, fields)
    _check_energies(problem, fields)
    _check_forces(problem, fields)
    _check_constraints(problem, fields)
    _check_friction(problem, fields)
    return fields.issues


@dataclass
class _Fields:
    """The check of a problem's fields against the dimensions they must have, and the issues it found."""

    problem: Problem
    units: UnitAlgebra
    issues: list[Issue] = field(default_factory=list)

    def need(self, where: str, expr: Any, dim: Dimension | None, what: str = "", why: str = "",
             hint: str = "") -> Any:
        """Check ``expr`` at ``where`` (its dimension must be ``dim`` unless None); its unit, or None."""
        problem, units = self.problem, self.units
        line = _line(problem.lines, where)
        try:
            unit = units.of(expr)
        except _Mismatch as bad:
            self.issues.append(Issue(problem.source, line, where, bad.message, bad.hint))
            return None
        if unit is None or dim is None or dimension(unit) == dim:
            return unit
        found = dimension(unit)
        name = what or _NAMES.get(dim, "")
        wanted = _ARTICLE.get(name, f"a {name}" if name else "")
        written = _text(problem.texts.get(where) or expr)  # the field as the file writes it
        self.issues.append(Issue(problem.source, line, where,
                                 f"{written} has dimension {describe(found)}, but it must be "
                                 f"{wanted + ' (' if wanted else ''}{dimension_text(dim)}{')' if wanted else ''}{why}",
                                 hint or _hint(expr, found, dim, units)))
        return unit


def _check_members(problem: Problem, fields: _Fields) -> None:
    """Masses, positions, inertias and angular velocities of the particles and bodies, and the gravity."""
    need = fields.need
    for p in problem.particles:
        need(f"particles.{p.name}.mass", p.mass, MASS)
        for i, r in enumerate(p.position):
            need(f"particles.{p.name}.position[{i}]", r, LENGTH)
    for b in problem.bodies:
        need(f"bodies.{b.name}.mass", b.mass, MASS)
        for i, r in enumerate(b.position):
            need(f"bodies.{b.name}.position[{i}]", r, LENGTH)
        for i, inertia in enumerate(b.inertia):
            need(f"bodies.{b.name}.inertia" + (f"[{i}]" if not b.planar else ""), inertia, INERTIA)
        for i, w in enumerate(b.angular_velocity):
            need(f"bodies.{b.name}.angular_velocity" + (f"[{i}]" if not b.planar else ""), w, RATE,
                 "rate", " (an angular velocity, rad/s)")
    for i, g in enumerate(problem.gravity or ()):
        need(f"gravity[{i}]", g, ACCELERATION)


def _check_energies(problem: Problem, fields: _Fields) -> None:
    """The kinetic and potential energies, and the dissipation function (a power)."""
    for key, dim in (("kinetic", ENERGY), ("potential", ENERGY), ("dissipation", POWER)):
        value = getattr(problem, key)
        if value is not None:
            fields.need(key, value, dim, why=" (the Rayleigh dissipation function, d(energy)/dt)"
                        if key == "dissipation" else "")


def _check_forces(problem: Problem, fields: _Fields) -> None:
    """Each generalized force (Q*q an energy) and each force on a particle (a force)."""
    coordinates = {c.name: c for c in problem.coordinates}
    for i, f in enumerate(problem.forces):
        if f.coordinate is not None:
            q_unit = fields.units.symbols.get(coordinates[f.coordinate].symbol)
            fields.need(f"forces[{i}].value", f.value[0], *_generalized_force(f, q_unit))
        else:
            for k, v in enumerate(f.value):
                fields.need(f"forces[{i}].force[{k}]", v, FORCE)


def _generalized_force(force: Any, q_unit: Any) -> tuple[Dimension | None, str, str, str]:
    """What a generalized force on a coordinate of unit ``q_unit`` must be: its dimension (unknown without the
    coordinate's unit), its name (a torque for an angle, a force for a length), why, and a hint."""
    wanted = None if q_unit is None else dimension(unit_of("J") / q_unit)
    kind = "" if q_unit is None else ("torque" if not dimension(q_unit) else
                                     "force" if dimension(q_unit) == LENGTH else "generalized force")
    why = f", so that Q*{force.coordinate} is an energy" + (
        f" ({force.coordinate} is an angle)" if kind == "torque" else
        f" ({force.coordinate} is a length)" if kind == "force" else "")
    hint = ""
    if kind == "torque" and q_unit is not None:
        hint = (f"a generalized force on an angle is a torque: multiply the force by its lever arm, or check "
                f"the units declared for {_symbols_of(force.value[0])}")
    elif kind == "force":
        hint = (f"a generalized force on a length is a force, the one along {force.coordinate}; check the "
                f"expression and the units declared for {_symbols_of(force.value[0])}")
    return wanted, kind, why, hint


def _check_constraints(problem: Problem, fields: _Fields) -> None:
    """Each constraint (homogeneous: the rule for sums checks it) and its contact point (lengths)."""
    for c in problem.constraints:
        fields.need(f"constraints.{c.name}.{c.kind}", c.expression, None)
        for k, r in enumerate(c.at or ()):
            fields.need(f"constraints.{c.name}.at[{k}]", r, LENGTH)


def _check_friction(problem: Problem, fields: _Fields) -> None:
    """The friction coefficients, kinetic and static (pure numbers)."""
    for fr in problem.friction:
        fields.need(f"friction.{fr.name}.coefficient", fr.coefficient, (), "dimensionless")
        if fr.static is not None:
            fields.need(f"friction.{fr.name}.static", fr.static, (), "dimensionless")


def _line(lines: Mapping[str, int], where: str) -> int:
    """The line of the field ``where`` (``forces[0].value``), or of the nearest enclosing one."""
    while where:
        if where in lines:
            return lines[where]
        cut = max(where.rfind("."), where.rfind("["))
        where = where[:cut] if cut > 0 else ""
    return lines.get("", 0)


def _hint(expr: Any, found: Dimension, wanted: Dimension, units: UnitAlgebra) -> str:
    """``did you forget a power?`` when the two differ by the dimension of a symbol in ``expr``."""
    ratio = dimension(_unit(wanted) / _unit(found))
    for s in sorted(expr.free_symbols, key=str):
        u = units.symbols.get(s)
        if u is not None and dimension(u) and ratio == dimension(u):
            return f"did you forget a power? (they differ by {dimension_text(ratio)})"
        if u is not None and dimension(u) and ratio == dimension(1 / u):
            return (f"is there a factor of dimension {dimension_text(dimension(u))} too many? "
                    f"(they differ by {dimension_text(ratio)})")
    return (f"they differ by {dimension_text(ratio)}; check the expression and the units declared for "
            f"{_symbols_of(expr)}")


def _unit(dim: Dimension) -> Any:
    out = registry().dimensionless
    for base, e in dim:
        out = out * unit_of(_BASE[base]) ** e if base in _BASE else out
    return out
