"""What a sweep runs: the swept inputs (grid and random), and the Poincaré section, read strictly.

Nothing here evaluates text: numbers are read with a regular expression and :func:`float`,
names are matched against the problem's parameters, coordinates and velocities.

Grammar of a section (``--poincare``)::

    section   := equation ( "," condition )*
    equation  := NAME "=" NUMBER            the surface: the state variable NAME equals NUMBER
    condition := NAME ( "<" | "<=" | ">" | ">=" ) NUMBER   kept only where it holds at the crossing
    NAME      := a coordinate or a velocity (``theta2``, ``theta2_dot``)
    NUMBER    := [+-] digits [. digits] [e [+-] digits]   (or "pi", "-pi")
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from lagsolve.errors import Issue, SpecError

WHERE = "<command line>"
MAX_RUNS = 10_000_000
_NAME = r"[A-Za-z][A-Za-z0-9_]*"
_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|[+-]?pi"
_NUMBER_RE = re.compile(rf"\s*({_NUMBER})\s*")


def _number(text: str) -> float | None:
    """A finite number from ``text`` (decimal, or ±pi), else None."""
    match = _NUMBER_RE.fullmatch(text)
    if match is None:
        return None
    token = match.group(1)
    value = math.copysign(math.pi, -1.0 if token.startswith("-") else 1.0) if token.endswith("pi") else float(token)
    return value if math.isfinite(value) else None


@dataclass(frozen=True)
class Names:
    """The names a sweep may vary: parameters (and which must be positive), coordinates, velocities."""

    parameters: tuple[str, ...]
    positive: frozenset[str]
    coordinates: tuple[str, ...]

    @property
    def states(self) -> tuple[str, ...]:
        return (*self.coordinates, *(f"{c}_dot" for c in self.coordinates))

    def known(self) -> str:
        return ", ".join([*self.parameters, *self.states])


def _issue(option: str, message: str, hint: str) -> Issue:
    return Issue(WHERE, 0, option, message, hint)


def parse_grid(text: str, names: Names) -> tuple[str, np.ndarray]:
    """``NAME=START:STOP:COUNT`` → (name, COUNT evenly spaced values from START to STOP).

    >>> names = Names(("g",), frozenset({"g"}), ("x",))
    >>> parse_grid("x=0:1:3", names)
    ('x', array([0. , 0.5, 1. ]))
    """
    name, parts = _split(text, "--grid", "NAME=START:STOP:COUNT", 3, names, "theta1=0.1:1.5:32")
    start, stop = _number(parts[0]), _number(parts[1])
    count = parts[2].strip()
    problems = [f"{label} {raw.strip()!r} is not a finite number" for label, raw, value in
                (("START", parts[0], start), ("STOP", parts[1], stop)) if value is None]
    if not re.fullmatch(r"\d+", count) or not 1 <= int(count) <= MAX_RUNS:
        problems.append(f"COUNT {count!r} is not a whole number from 1 to {MAX_RUNS}")
    if problems or start is None or stop is None:
        raise SpecError([_issue("--grid", f"{text!r}: " + "; ".join(problems),
                                "write NAME=START:STOP:COUNT, e.g. theta1=0.1:1.5:32")])
    values = np.linspace(start, stop, int(count))
    _check_sign(name, values, names, "--grid")
    return name, values


def parse_random(text: str, names: Names) -> tuple[str, float, float]:
    """``NAME=LOW:HIGH`` → (name, low, high), values drawn uniformly in [LOW, HIGH)."""
    name, parts = _split(text, "--random", "NAME=LOW:HIGH", 2, names, "theta1=0:1.5")
    low, high = _number(parts[0]), _number(parts[1])
    if low is None or high is None or not low <= high:
        raise SpecError([_issue("--random", f"{text!r}: expected two finite numbers LOW <= HIGH",
                                "write NAME=LOW:HIGH, e.g. theta1=0:1.5")])
    _check_sign(name, np.array([low, high]), names, "--random")
    return name, low, high


def _split(text: str, option: str, form: str, count: int, names: Names, example: str) -> tuple[str, list[str]]:
    name, equals, rest = text.partition("=")
    name = name.strip()
    if not equals or not re.fullmatch(_NAME, name):
        raise SpecError([_issue(option, f"{text!r} is not of the form {form}", f"e.g. {option} {example}")])
    if name not in names.parameters and name not in names.states:
        raise SpecError([_issue(option, f"{text!r}: unknown name {name!r}", f"known: {names.known()}")])
    parts = rest.split(":")
    if len(parts) != count:
        raise SpecError([_issue(option, f"{text!r} is not of the form {form}", f"e.g. {option} {example}")])
    return name, parts


def _check_sign(name: str, values: np.ndarray, names: Names, option: str) -> None:
    if name in names.positive and np.any(values < 0):
        raise SpecError([_issue(option, f"{name} takes negative values, but parameter {name!r} is positive "
                                "(the derivation relies on it)", f"sweep {name} over values >= 0")])


def inputs(grid: Sequence[tuple[str, np.ndarray]], random: Sequence[tuple[str, float, float]],
           runs: int | None, seed: int) -> dict[str, np.ndarray]:
    """The swept inputs, one array per name, one entry per run.

    The grid is a Cartesian product (the first name varies slowest); random names are drawn from
    ``numpy.random.default_rng(seed)`` in the order given, ``runs`` values per grid point.
    """
    issues = []
    seen = [g[0] for g in grid] + [r[0] for r in random]
    for name in sorted({n for n in seen if seen.count(n) > 1}):
        issues.append(_issue("--grid/--random", f"{name!r} is swept twice", "give each name once"))
    if random and runs is None:
        issues.append(_issue("--runs", "--random needs the number of runs", "add e.g. --runs 1000"))
    if runs is not None and not random:
        issues.append(_issue("--runs", "--runs without --random", "add e.g. --random theta1=0:1.5, or drop --runs"))
    if not grid and not random:
        issues.append(_issue("--grid", "nothing to sweep", "give --grid NAME=START:STOP:COUNT or --random with --runs"))
    if issues:
        raise SpecError(issues)
    points = math.prod(len(v) for _, v in grid) if grid else 1
    total = points * (runs or 1)
    if total > MAX_RUNS:
        raise SpecError([_issue("--grid", f"{total} runs is more than {MAX_RUNS}", "sweep fewer points")])
    columns: dict[str, np.ndarray] = {}
    if grid:
        mesh = np.meshgrid(*[v for _, v in grid], indexing="ij")
        for (name, _), values in zip(grid, mesh, strict=True):
            columns[name] = np.repeat(values.ravel(), runs or 1)
    if random:
        rng = np.random.default_rng(seed)
        for name, low, high in random:
            columns[name] = rng.uniform(low, high, total)
    return columns


def grid_from_mapping(grid: Mapping[str, object], names: Names) -> list[tuple[str, np.ndarray]]:
    """The API's grid: each name maps to a "START:STOP:COUNT" string or a sequence of values."""
    out = []
    for name, spec in grid.items():
        if isinstance(spec, str):
            out.append(parse_grid(f"{name}={spec}", names))
            continue
        values = np.asarray(spec, dtype=float).ravel()
        if name not in names.parameters and name not in names.states:
            raise SpecError([_issue("grid", f"unknown name {name!r}", f"known: {names.known()}")])
        if not values.size or not np.all(np.isfinite(values)):
            raise SpecError([_issue("grid", f"{name}: expected finite values", "give a non-empty list of numbers")])
        _check_sign(name, values, names, "grid")
        out.append((name, values))
    return out


@dataclass(frozen=True)
class Section:
    """A Poincaré section: state variable ``index`` (in (q, q̇) order) equal to ``value``, kept where every
    condition (index, operator, number) holds."""

    text: str
    name: str
    index: int
    value: float
    conditions: tuple[tuple[int, str, float], ...]

    def holds(self, y: np.ndarray) -> np.ndarray:
        """Which rows of the states ``y`` (shape (N, 2n)) meet every condition."""
        keep = np.ones(len(y), dtype=bool)
        for index, op, number in self.conditions:
            column = y[:, index]
            keep &= {"<": column < number, "<=": column <= number, ">": column > number,
                     ">=": column >= number}[op]
        return keep


_CONDITION = re.compile(rf"\s*({_NAME})\s*(<=|>=|<|>|=)\s*(.*?)\s*")


def parse_section(text: str, names: Names) -> Section:
    """Read ``--poincare`` by the grammar above.

    >>> names = Names((), frozenset(), ("theta1", "theta2"))
    >>> parse_section("theta2=0, theta2_dot>0", names).conditions
    ((3, '>', 0.0),)
    """
    hint = 'write NAME=NUMBER, then optional conditions NAME>NUMBER (or <, <=, >=), e.g. "theta2=0, theta2_dot>0"'
    states = names.states
    if len(text) > 1000:
        raise SpecError([_issue("--poincare", "the section is longer than 1000 characters", hint)])
    parts = text.split(",")
    parsed = []
    for position, part in enumerate(parts):
        match = _CONDITION.fullmatch(part)
        if match is None:
            raise SpecError([_issue("--poincare", f"{text!r}: cannot read {part.strip()!r}", hint)])
        name, op, raw = match.groups()
        if name not in states:
            raise SpecError([_issue("--poincare", f"{text!r}: {name!r} is not a coordinate or velocity",
                                    f"known: {', '.join(states)}")])
        number = _number(raw)
        if number is None:
            raise SpecError([_issue("--poincare", f"{text!r}: {raw!r} is not a finite number", hint)])
        if (op == "=") != (position == 0):
            what = "the first part must be an equation NAME=NUMBER" if position == 0 else \
                f"only the first part is an equation; {part.strip()!r} must be a condition (<, <=, >, >=)"
            raise SpecError([_issue("--poincare", f"{text!r}: {what}", hint)])
        parsed.append((states.index(name), name, op, number))
    index, name, _, value = parsed[0]
    return Section(text, name, index, value, tuple((i, op, v) for i, _, op, v in parsed[1:]))
