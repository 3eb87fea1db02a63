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
        values = self.parameter_values(path, spec, parameters)
        initial = self.initial_state(path, spec, coordinates)
        functions = self.concrete_functions((*path, "functions"), spec.get("functions", {}), parameters)
        t_end = self.positive_setting(path, spec, "t_end")
        samples = self.samples(path, spec)
        method = self.method(path, spec)
        rtol = self.positive_setting(path, spec, "rtol")
        atol = self.positive_setting(path, spec, "atol")
        return Simulation(values, functions, initial, t_end, samples, method, rtol, atol)

    def parameter_values(self, path: tuple, spec: dict, parameters: list[Parameter]) -> dict[str, float]:
        """``values:``, a number for each parameter named (one its assumptions allow)."""
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
        return values

    def initial_state(self, path: tuple, spec: dict, coordinates: list[Coordinate]) -> dict[str, float]:
        """``initial:``, a number for each coordinate or velocity named (a positive coordinate's above zero)."""
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
        return initial

    def positive_setting(self, path: tuple, spec: dict, key: str) -> float | None:
        """A positive number under ``key`` (``t_end``, ``rtol``, ``atol``), or None where it is absent or wrong."""
        return self.number((*path, key), spec[key], positive=True) if key in spec else None

    def samples(self, path: tuple, spec: dict) -> int | None:
        """``samples:``, a whole number from 2 to 1000000."""
        if "samples" not in spec:
            return None
        raw = spec["samples"]
        if isinstance(raw, bool) or not isinstance(raw, int) or not 2 <= raw <= 1_000_000:
            self.issue((*path, "samples"), "expected a whole number from 2 to 1000000")
            return None
        return raw

    def method(self, path: tuple, spec: dict) -> str | None:
        """``method:``, one of the integrators of the registry (:mod:`lagsolve.problem.methods`)."""
        method = spec.get("method")
        if method is not None and method not in METHODS:
            self.issue((*path, "method"), f"unknown method {method!r}", "use one of: " + ", ".join(METHODS))
            return None
        return method

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
