"""The problem file's expected answers (``expected``) and the chosen independent coordinates."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy

from lagsolve.problem import expr as gateway
from lagsolve.problem.names import momentum_name, momentum_symbol
from lagsolve.problem.readers.base import Reader, kind_of, known_names, shown
from lagsolve.problem.schema import (
    Constraint,
    Coordinate,
    Expected,
    ExpectedEquilibrium,
    ExpectedForce,
    ExpectedModes,
    ExpectedPotential,
    ExpectedSteady,
)

_EXPECTED_KEYS = ("accelerations", "multipliers", "constraint_forces", "reduced", "conserved",
                  "effective_potential", "normal_modes", "steady_motions")


class AnswersReader(Reader):
    """Reads ``expected`` and ``independent``."""

    def answer_names(self, constraints: list[Constraint], *, momenta: bool = False,
                     multipliers: bool = False) -> gateway.Namespace:
        """The names an expected answer may use: the problem's (time, parameters, coordinates, velocities,
        functions); with ``momenta`` the momenta ``p_<q>`` (a cyclic coordinate's constant momentum, in the
        effective potential and the steady motions); with ``multipliers`` the multipliers ``lambda_<c>`` (a force
        of constraint written λ∇ψ, compared with the derived λ put in). Elsewhere a multiplier restates what is
        asked (``multipliers: {rod: lambda_rod}`` was accepted) and a momentum was read as a constant (a conserved
        ``p_x`` "ok"): both are refused."""
        momentum_names = {momentum_name(n): momentum_symbol(n)
                          for n, k in self.kinds.items() if k == "a coordinate" and momentum_name(n) not in self.kinds}
        forbidden = dict(self.acceleration_names)
        multiplier_names = {f"lambda_{c.name}": sympy.Symbol(f"lambda_{c.name}", real=True) for c in constraints}
        if not multipliers:
            forbidden |= dict.fromkeys(multiplier_names, "a multiplier is allowed only in constraint_forces; write "
                                       "the answer in t, the parameters, coordinates and velocities")
        if not momenta:
            forbidden |= dict.fromkeys(momentum_names, "a momentum is allowed only in effective_potential and "
                                       "steady_motions; write it in the coordinates and velocities")
        return gateway.Namespace({**self.symbols, **(momentum_names if momenta else {}),
                                  **(multiplier_names if multipliers else {})}, self.functions, forbidden)

    def expected(self, value: Any, constraints: list[Constraint]) -> Expected:
        spec = self.mapping(("expected",), value)
        if not spec:
            return Expected()
        self.keys(("expected",), spec, _EXPECTED_KEYS)
        names = self.answer_names(constraints)
        with_momenta = self.answer_names(constraints, momenta=True)
        with_multipliers = self.answer_names(constraints, multipliers=True)
        coordinate_names = [n for n, k in self.kinds.items() if k == "a coordinate"]
        constraint_names = [c.name for c in constraints]

        def table(key: str, known: list[str], what: str, parse: Callable[[tuple, Any], Any]) -> dict[str, Any]:
            path = ("expected", key)
            raw = self.mapping(path, spec.get(key, {}))
            out = {}
            for k, v in (raw or {}).items():
                if known and k not in known:
                    self.issue((*path, k), f"unknown {what} {k!r}", known_names(what + "s", known))
                    continue
                parsed = parse((*path, k), v)
                if parsed is not None:
                    out[k] = parsed
            return out

        def plain(path: tuple, v: Any) -> Any:
            return self.expression(path, v, names)

        def force(path: tuple, v: Any) -> ExpectedForce | None:
            if isinstance(v, dict):
                if not self.keys(path, v, ("vector", "magnitude")):
                    return None
                magnitude = vector = None
                if "magnitude" in v:
                    magnitude = self.expression((*path, "magnitude"), v["magnitude"], with_multipliers)
                    if magnitude is None:
                        return None
                if "vector" in v:
                    vector = self.vector((*path, "vector"), v["vector"], with_multipliers)
                    if vector is None:
                        return None
                return ExpectedForce(magnitude, vector)
            magnitude = self.expression(path, v, with_multipliers)
            return None if magnitude is None else ExpectedForce(magnitude)

        reduced_raw = spec.get("reduced", {})
        reduced: dict[str, Any] = {}
        if reduced_raw:
            rmap = self.mapping(("expected", "reduced"), reduced_raw)
            if rmap is not None:
                self.keys(("expected", "reduced"), rmap, ("independent", "accelerations"))
                for k, v in (self.mapping(("expected", "reduced", "accelerations"),
                                          rmap.get("accelerations", {})) or {}).items():
                    if k not in coordinate_names:
                        self.issue(("expected", "reduced", "accelerations", k), f"unknown coordinate {k!r}")
                        continue
                    parsed = self.expression(("expected", "reduced", "accelerations", k), v, names)
                    if parsed is not None:
                        reduced[k] = parsed
        effective = None
        if "effective_potential" in spec:
            effective = self.effective_potential(spec["effective_potential"], with_momenta, coordinate_names)
        modes = self.normal_modes(spec["normal_modes"], names, coordinate_names) if "normal_modes" in spec else ()
        steady = None
        if "steady_motions" in spec:
            steady = self.steady_motions(spec["steady_motions"], with_momenta, coordinate_names)
        return Expected(
            accelerations=table("accelerations", coordinate_names, "coordinate", plain),
            multipliers=table("multipliers", constraint_names, "constraint", plain),
            constraint_forces=table("constraint_forces", constraint_names, "constraint", force),
            reduced=reduced,
            conserved=table("conserved", [], "quantity", plain),
            effective_potential=effective,
            normal_modes=modes,
            steady_motions=steady,
        )

    def steady_motions(self, value: Any, names: gateway.Namespace, coordinates: list[str]) -> ExpectedSteady | None:
        """``steady_motions: {coordinate, rate, values: [...], stable, frequency}``."""
        path = ("expected", "steady_motions")
        spec = self.mapping(path, value)
        if spec is None or not self.keys(path, spec, ("coordinate", "rate", "values", "stable", "frequency"),
                                         ("coordinate", "rate", "values")):
            return None
        ok = True
        for key in ("coordinate", "rate"):
            if spec[key] not in coordinates:
                self.issue((*path, key), f"unknown coordinate {shown(spec[key])}",
                           known_names("coordinates", coordinates))
                ok = False
        raw = spec["values"]
        if not isinstance(raw, list) or not raw:
            self.issue((*path, "values"), f"expected a list of expressions, found {kind_of(raw)}",
                       "write e.g. 'values: [\"sqrt(g/(l*cos(theta)))\"]'")
            return None
        values = [self.expression((*path, "values", i), v, names) for i, v in enumerate(raw)]
        stable = self.flag((*path, "stable"), spec["stable"]) if "stable" in spec else None
        frequency = self.expression((*path, "frequency"), spec["frequency"], names) if "frequency" in spec else None
        if not ok or any(v is None for v in values) or ("frequency" in spec and frequency is None):
            return None
        return ExpectedSteady(spec["coordinate"], spec["rate"], tuple(values), stable, frequency)

    def effective_potential(self, value: Any, names: gateway.Namespace,
                            coordinates: list[str]) -> ExpectedPotential | None:
        path = ("expected", "effective_potential")
        spec = self.mapping(path, value)
        if spec is None or not self.keys(path, spec, ("coordinate", "expression", "equilibria"), ("coordinate",)):
            return None
        if spec["coordinate"] not in coordinates:
            self.issue((*path, "coordinate"), f"unknown coordinate {shown(spec['coordinate'])}",
                       known_names("coordinates", coordinates))
            return None
        expression = None
        if "expression" in spec:
            expression = self.expression((*path, "expression"), spec["expression"], names)
        equilibria: list[ExpectedEquilibrium] = []
        raw = spec.get("equilibria") or []
        if not isinstance(raw, list):
            self.issue((*path, "equilibria"), f"expected a list, found {kind_of(raw)}",
                       "write '- {value: ..., stable: true}' items")
            raw = []
        for i, item in enumerate(raw):
            ipath = (*path, "equilibria", i)
            item = self.mapping(ipath, item)
            if item is None or not self.keys(ipath, item, ("value", "stable", "frequency"), ("value",)):
                continue
            stable = self.flag((*ipath, "stable"), item["stable"]) if "stable" in item else None
            frequency = (self.expression((*ipath, "frequency"), item["frequency"], names) if "frequency" in item
                         else None)
            equilibria.append(ExpectedEquilibrium(self.expression((*ipath, "value"), item["value"], names), stable,
                                                  frequency))
        return ExpectedPotential(spec["coordinate"], expression, tuple(equilibria))

    def normal_modes(self, value: Any, names: gateway.Namespace, coordinates: list[str]) -> tuple[ExpectedModes, ...]:
        """``normal_modes: [{at: {q: value}, stable: true, squared_frequencies: [...], shapes: [[...], ...]}]``."""
        path: tuple = ("expected", "normal_modes")
        if not isinstance(value, list):
            self.issue(path, f"expected a list, found {kind_of(value)}",
                       "write '- {at: {theta1: 0, theta2: 0}, squared_frequencies: [...]}' items")
            return ()
        out = []
        for i, item in enumerate(value):
            ipath = (*path, i)
            item = self.mapping(ipath, item)
            if item is None or not self.keys(ipath, item, ("at", "stable", "squared_frequencies", "shapes"), ("at",)):
                continue
            at: dict[str, Any] = {}
            for q, v in (self.mapping((*ipath, "at"), item["at"]) or {}).items():
                if q not in coordinates:
                    self.issue((*ipath, "at", q), f"unknown coordinate {shown(q)}",
                               known_names("coordinates", coordinates))
                    continue
                parsed = self.expression((*ipath, "at", q), v, names)
                if parsed is not None:
                    at[q] = parsed
            stable = self.flag((*ipath, "stable"), item["stable"]) if "stable" in item else None
            squares = self._list(item, "squared_frequencies", ipath,
                                 lambda p, v: self.expression(p, v, names), "'[g/l, g/l + 2*k/m]'")
            shapes = self._list(item, "shapes", ipath, lambda p, v: self._shape(p, v, names, len(coordinates)),
                                "'[[1, 1], [1, -1]]' (one shape per squared frequency)")
            if shapes is not None and (squares is None or len(shapes) != len(squares)):
                self.issue((*ipath, "shapes"), f"expected one shape per squared frequency ({len(squares or ())}), "
                                                f"found {len(shapes)}", "give squared_frequencies and a shape for each")
                shapes = None
            out.append(ExpectedModes(at, stable, squares, shapes))
        return tuple(out)

    def _list(self, item: dict[str, Any], key: str, path: tuple, parse: Callable[[tuple, Any], Any],
              example: str) -> tuple[Any, ...] | None:
        """``item[key]``, a non-empty list each of whose entries ``parse`` reads; None when absent or wrong."""
        if key not in item:
            return None
        raw = item[key]
        if not isinstance(raw, list) or not raw:
            found = "an empty list" if raw == [] else kind_of(raw)
            self.issue((*path, key), f"expected a non-empty list, found {found}", f"write e.g. {example}")
            return None
        parsed = [parse((*path, key, k), v) for k, v in enumerate(raw)]
        return None if any(p is None for p in parsed) else tuple(parsed)

    def _shape(self, path: tuple, value: Any, names: gateway.Namespace, n: int) -> tuple[Any, ...] | None:
        """A mode shape: one component per coordinate."""
        if not isinstance(value, list) or len(value) != n:
            found = f"{len(value)} components" if isinstance(value, list) else kind_of(value)
            self.issue(path, f"expected a list of {n} components (one per coordinate), found {found}")
            return None
        parts = [self.expression((*path, k), v, names) for k, v in enumerate(value)]
        return None if any(p is None for p in parts) else tuple(parts)

    def independent(self, value: Any, coordinates: list[Coordinate]) -> tuple[str, ...]:
        """``independent: [x]``: the coordinates to keep as minimal coordinates (each once)."""
        known = [c.name for c in coordinates]
        if not isinstance(value, list) or not value:
            self.issue(("independent",), f"expected a list of coordinate names, found {kind_of(value)}",
                       "write e.g. 'independent: [x]'")
            return ()
        out: list[str] = []
        for i, item in enumerate(value):
            if not isinstance(item, str) or item not in known:
                self.issue(("independent", i), f"unknown coordinate {shown(item)}", known_names("coordinates", known))
            elif item in out:
                self.issue(("independent", i), f"coordinate {item!r} is listed twice", "give each name once")
            else:
                out.append(item)
        return tuple(out)
