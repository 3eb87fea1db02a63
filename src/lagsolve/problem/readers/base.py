"""The shared part of the problem file's readers: the document, the names declared so far, the issues
found, and the typed field readers (a mapping, a text, a number, an expression, a vector, a name).

Each section of the file has its reader in this package (:mod:`.bodies`, :mod:`.constraints`,
:mod:`.answers`, :mod:`.simulation`); :class:`lagsolve.problem.load` combines them.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable, Mapping
from typing import Any

from lagsolve.errors import ExpressionError, Issue
from lagsolve.problem import expr as gateway
from lagsolve.problem import units
from lagsolve.problem.schema import Particle
from lagsolve.problem.yamlread import Document, dotted, kind_of

#: longest free text, in characters: the name (a title, drawn on every figure), the problem's
#: description, and a parameter's, coordinate's or function's description
MAX_TITLE_LENGTH = 200
MAX_PROBLEM_DESCRIPTION_LENGTH = 20_000
MAX_DESCRIPTION_LENGTH = 1_000


class Reader:
    """Walks the document once, collecting issues instead of stopping at the first: the state shared by
    the section readers and the typed field readers they use."""

    def __init__(self, document: Document, source: str) -> None:
        self.data: dict[str, Any] = document.data
        self.lines = document.lines
        self.source = source
        self.issues: list[Issue] = []
        self.symbols: dict[str, Any] = {}
        self.kinds: dict[str, str] = {}  # name -> what declared it
        self.declared_at: dict[str, tuple] = {}  # name -> where
        self.functions: dict[str, Any] = {}
        self.velocity_names: dict[str, Any] = {}
        self.declared_particles: list[str] = []
        self.loaded_particles: dict[str, Particle] = {}  # the particles read so far, by name
        self.particles_readable = True  # False: references to particles cannot be checked
        self.acceleration_names: dict[str, Any] = {}
        self.texts: dict[str, str] = {}  # dotted field -> expression text as written (for messages)

    # -- reporting ---------------------------------------------------------------------------

    def line(self, path: tuple) -> int:
        return line_of(self.lines, path)

    def issue(self, path: tuple, message: str, hint: str = "") -> None:
        self.issues.append(Issue(self.source, self.line(path), dotted(path), message, hint))

    # -- typed field readers -----------------------------------------------------------------

    def mapping(self, path: tuple, value: Any, what: str = "a mapping") -> dict[str, Any] | None:
        if isinstance(value, dict):
            return value
        self.issue(path, f"expected {what}, found {kind_of(value)}", "write it as 'key: value' lines")
        return None

    def keys(self, path: tuple, value: dict[str, Any], allowed: Iterable[str], required: Iterable[str] = ()) -> bool:
        allowed = tuple(allowed)
        ok = True
        for key in value:
            if key not in allowed:
                close = difflib.get_close_matches(key, allowed, n=1)
                hint = f"did you mean {close[0]!r}?" if close else "allowed: " + ", ".join(allowed)
                self.issue((*path, key), f"unknown key {key!r}", hint)
                ok = False
        for key in required:
            if key not in value:
                self.issue(path, f"missing required key {key!r}", f"add '{key}: ...'")
                ok = False
        return ok

    def text(self, path: tuple, value: Any, *, one_line: bool = False,
             limit: int = MAX_DESCRIPTION_LENGTH) -> str | None:
        if isinstance(value, str):
            if one_line and ("\n" in value.strip() or not value.strip()):
                self.issue(path, "expected one non-empty line of text")
                return None
            if not self.short_enough(path, value, limit):
                return None
            return value.strip() if one_line else value
        self.issue(path, f"expected text, found {kind_of(value)}")
        return None

    def short_enough(self, path: tuple, value: str, limit: int) -> bool:
        """Whether the free text ``value`` has at most ``limit`` characters; if not, an issue."""
        if len(value) <= limit:
            return True
        self.issue(path, f"text of {len(value)} characters is too long; the limit here is {limit}",
                   "shorten it" + ("; put details in description" if path == ("name",) else ""))
        return False

    def number(self, path: tuple, value: Any, *, positive: bool = False) -> float | None:
        if isinstance(value, bool) or not isinstance(value, int | float):
            self.issue(path, f"expected a number, found {kind_of(value)}")
            return None
        value = float(value)
        if not math.isfinite(value):
            self.issue(path, "expected a finite number")
            return None
        if positive and value <= 0:
            self.issue(path, f"expected a positive number, found {value:g}")
            return None
        return value

    def assumption_holds(self, path: tuple, name: str, value: float, positive: bool,
                         kind: str = "parameter") -> bool:
        """Whether ``value`` agrees with ``name`` being positive (the derivation relies on it); if not, an issue."""
        if not positive or value >= 0:  # 0 is the limit case (mu = 0: no friction)
            return True
        if kind == "parameter":
            why = "(parameters are, unless declared with positive: false)"
            fix = (f"give a value >= 0, or declare it as {name}: {{description: ..., positive: false}} "
                   "under parameters")
        else:
            why = "(declared positive: true)"
            fix = f"give a value >= 0, or remove positive: true from coordinate {name!r}"
        self.issue(path, f"{value:g} contradicts the assumption that {kind} {name!r} is positive {why}, "
                   "which the derivation relies on", fix)
        return False

    def flag(self, path: tuple, value: Any) -> bool | None:
        if isinstance(value, bool):
            return value
        self.issue(path, f"expected true or false, found {kind_of(value)}")
        return None

    def expression(self, path: tuple, value: Any, names: gateway.Namespace) -> Any | None:
        try:
            parsed = gateway.parse(value, names)
        except ExpressionError as exc:
            self.issue(path, exc.message, exc.hint)
            return None
        self.texts[dotted(path)] = str(value)
        return parsed

    def unit(self, path: tuple, value: Any) -> str | None:
        """A ``unit:`` field (:mod:`lagsolve.problem.units`); None and an issue when it is not a unit."""
        try:
            return units.canonical(value)
        except ExpressionError as exc:
            self.issue(path, exc.message, exc.hint)
            return None

    def vector(self, path: tuple, value: Any, names: gateway.Namespace) -> tuple[Any, ...] | None:
        if not isinstance(value, list) or not 2 <= len(value) <= 3:
            found = f"{len(value)} components" if isinstance(value, list) else kind_of(value)
            self.issue(path, f"expected a list of 2 or 3 components, found {found}",
                       "write [x, y] in the plane or [x, y, z] in space")
            return None
        parts = [self.expression((*path, i), item, names) for i, item in enumerate(value)]
        return None if any(p is None for p in parts) else tuple(parts)

    def declare(self, path: tuple, name: str, kind: str) -> bool:
        problem = gateway.name_problem(name)
        if problem is not None:
            self.issue(path, problem)
            return False
        if name in self.kinds:
            self.issue(path, f"{name!r} is already declared as {self.kinds[name]}", "give each name once")
            return False
        for suffix in ("_dot", "_ddot"):
            if name.endswith(suffix) and name[: -len(suffix)] in self.kinds:
                self.issue(path, f"{name!r} clashes with the velocity name of coordinate {name[: -len(suffix)]!r}",
                           "choose another name")
                return False
        if name.startswith("lambda_"):
            self.issue(path, f"{name!r} is reserved for Lagrange multipliers", "choose another name")
            return False
        self.kinds[name] = kind
        self.declared_at[name] = path
        return True

    def generated_names(self, coordinates: list[str], contacts: list[str]) -> None:
        """Refuse a declared name that lagsolve gives to something it derives: ``p_<q>``, the momentum conjugate to
        coordinate q (in the Hamiltonian, conserved quantities, Routhian), and ``N_<c>``, friction contact c's normal
        force: a formula holding both would read as one symbol (``H = x*(k*x/2 + p_x) + p_x**2/(2*m)``)."""
        owners = {f"p_{q}": f"the momentum conjugate to coordinate {q!r}" for q in coordinates}
        owners |= {f"N_{c}": f"the normal force of friction contact {c!r}" for c in contacts}
        for name, owner in owners.items():
            if name in self.declared_at:
                self.issue(self.declared_at[name], f"{name!r} is the name lagsolve gives {owner}, so a formula "
                           "with both would read as one symbol", "choose another name")

    def velocity_symbols(self) -> list[Any]:
        return [s for n, s in self.symbols.items() if n.endswith("_dot") and n[:-4] in self.kinds]

    def names_list(self, path: tuple, value: Any) -> list[tuple[str, str, tuple]]:
        """A list of names, or a mapping name -> description (or -> details)."""
        if isinstance(value, list):
            out = []
            for i, item in enumerate(value):
                if isinstance(item, str):
                    out.append((item, "", (*path, i)))
                else:
                    self.issue((*path, i), f"expected a name, found {kind_of(item)}")
            return out
        if isinstance(value, dict):
            return [(k, v if not isinstance(v, str) or self.short_enough((*path, k), v, MAX_DESCRIPTION_LENGTH)
                     else "", (*path, k)) for k, v in value.items()]
        self.issue(path, f"expected a list of names or a mapping name: description, found {kind_of(value)}")
        return []

    # -- the problem -------------------------------------------------------------------------



def shown(value: Any) -> str:
    """A value for a message: names quoted, anything else described."""
    return repr(value) if isinstance(value, str) else f"({kind_of(value)})"


def known_names(what: str, names: Iterable[str]) -> str:
    """The names a reference could have used, for a message."""
    names = list(names)
    return f"known {what}: " + ", ".join(names) if names else f"no {what} are declared"


def line_of(lines: Mapping[tuple, int], path: tuple) -> int:
    """The line of the field at ``path``, or of the nearest enclosing field that has one (1 for the file)."""
    while path:
        if path in lines:
            return lines[path]
        path = path[:-1]
    return lines.get((), 1)
