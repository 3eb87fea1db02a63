"""The problem file's ``simulation`` section: values, concrete functions, initial state, integrator."""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.problem import expr as gateway
from lagsolve.problem.methods import METHODS
from lagsolve.problem.readers.base import Reader, known_names
from lagsolve.problem.schema import (
    ConcreteFunction,
    Coordinate,
    Parameter,
    Simulation,
)

_SIMULATION_KEYS = ("values", "functions", "initial", "t_end", "samples", "method", "rtol", "atol")


class SimulationReader(Reader):
    """Reads ``simulation``."""

    def simulation(self, value: Any, parameters: list[Parameter], coordinates: list[Coordinate]) -> Simulation | None:
        path = ("simulation",)
        spec = self.mapping(path, value)
        if spec is None:
            return None
        self.keys(path, spec, _SIMULATION_KEYS)
        parameter_names = [p.name for p in parameters]
        positive = {p.name: p.positive for p in parameters}
        values: dict[str, float] = {}
        for k, v in (self.mapping((*path, "values"), spec.get("values", {})) or {}).items():
            if k not in parameter_names:
                self.issue((*path, "values", k), f"unknown parameter {k!r}", known_names("parameters", parameter_names))
                continue
            number = self.number((*path, "values", k), v)
            if number is not None and self.assumption_holds((*path, "values", k), k, number, positive[k]):
                values[k] = number
        state_names = [c.name for c in coordinates] + [f"{c.name}_dot" for c in coordinates]
        positive_coordinates = {c.name for c in coordinates if c.symbol.is_positive}
        initial: dict[str, float] = {}
        for k, v in (self.mapping((*path, "initial"), spec.get("initial", {})) or {}).items():
            if k not in state_names:
                self.issue((*path, "initial", k), f"unknown coordinate or velocity {k!r}",
                           known_names("names", state_names))
                continue
            number = self.number((*path, "initial", k), v)
            if number is not None and self.assumption_holds((*path, "initial", k), k, number,
                                                            k in positive_coordinates, "coordinate"):
                initial[k] = number
        functions = self.concrete_functions((*path, "functions"), spec.get("functions", {}), parameters)
        t_end = self.number((*path, "t_end"), spec["t_end"], positive=True) if "t_end" in spec else None
        samples = None
        if "samples" in spec:
            raw = spec["samples"]
            if isinstance(raw, bool) or not isinstance(raw, int) or not 2 <= raw <= 1_000_000:
                self.issue((*path, "samples"), "expected a whole number from 2 to 1000000")
            else:
                samples = raw
        method = spec.get("method")
        if method is not None and method not in METHODS:
            self.issue((*path, "method"), f"unknown method {method!r}", "use one of: " + ", ".join(METHODS))
            method = None
        rtol = self.number((*path, "rtol"), spec["rtol"], positive=True) if "rtol" in spec else None
        atol = self.number((*path, "atol"), spec["atol"], positive=True) if "atol" in spec else None
        return Simulation(values, functions, initial, t_end, samples, method, rtol, atol)

    def concrete_functions(self, path: tuple, value: Any, parameters: list[Parameter]) -> dict[str, ConcreteFunction]:
        out: dict[str, ConcreteFunction] = {}
        spec = self.mapping(path, value)
        for key, body in (spec or {}).items():
            kpath = (*path, key)
            head, _, rest = key.partition("(")
            head = head.strip()
            args = [a.strip() for a in rest.rstrip().removesuffix(")").split(",")] if rest else []
            if head not in self.functions:
                self.issue(kpath, f"{head!r} is not a declared function",
                           known_names("functions", sorted(self.functions)))
                continue
            if (not args or not rest.rstrip().endswith(")") or len(set(args)) != len(args)
                    or any(gateway.name_problem(a) for a in args)):
                self.issue(kpath, f"write the function with placeholder arguments, like \"{head}(u)\"")
                continue
            placeholders = {a: sympy.Symbol(a, real=True) for a in args}
            names = gateway.Namespace({**{p.name: p.symbol for p in parameters}, **placeholders})
            parsed = self.expression(kpath, body, names)
            if parsed is not None:
                out[head] = ConcreteFunction(head, tuple(placeholders.values()), parsed)
        return out
