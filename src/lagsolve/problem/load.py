"""Problem file → validated :class:`~lagsolve.problem.schema.Problem`.

Every problem in a file is collected and reported at once (file, line, field,
what is wrong, how to fix it) in one :class:`~lagsolve.errors.SpecError`.
Expression text reaches SymPy only through :func:`lagsolve.problem.expr.parse`.
"""

from __future__ import annotations

import difflib
from pathlib import Path
from typing import Any

import sympy

from lagsolve.errors import Issue, SpecError
from lagsolve.files import read_input
from lagsolve.problem import expr as gateway
from lagsolve.problem.readers.answers import AnswersReader
from lagsolve.problem.readers.base import (
    MAX_DESCRIPTION_LENGTH,
    MAX_PROBLEM_DESCRIPTION_LENGTH,
    MAX_TITLE_LENGTH,
    kind_of,
)
from lagsolve.problem.readers.bodies import BodiesReader
from lagsolve.problem.readers.friction import FrictionReader
from lagsolve.problem.readers.simulation import SimulationReader
from lagsolve.problem.schema import (
    Coordinate,
    FunctionDecl,
    Parameter,
    Particle,
    Problem,
)
from lagsolve.problem.yamlread import MAX_BYTES, dotted, read_document

__all__ = ["MAX_DESCRIPTION_LENGTH", "MAX_PROBLEM_DESCRIPTION_LENGTH", "MAX_TITLE_LENGTH", "TOP_LEVEL", "load_problem",
           "load_text"]

TOP_LEVEL = (
    "name", "description", "time", "parameters", "functions", "coordinates", "particles", "bodies",
    "gravity", "kinetic", "potential", "dissipation", "forces", "constraints", "friction",
    "expected", "simulation", "independent", "grading",
)


def load_problem(path: str | Path) -> Problem:
    """Read and validate one problem file.

    Raises
    ------
    SpecError
        Listing every problem found, each with file, line, field and a fix.
    """
    source = str(path)
    try:
        raw = read_input(path, MAX_BYTES)  # one byte over the limit at most; a pipe without a writer never blocks
    except FileNotFoundError:
        raise SpecError([Issue(source, 0, "", "file not found", "check the path")]) from None
    except IsADirectoryError:
        raise SpecError([Issue(source, 0, "", "is a folder, not a problem file")]) from None
    except OSError as exc:
        raise SpecError([Issue(source, 0, "", f"cannot read the file ({exc.strerror})")]) from None
    return load_text(raw, source)


def load_text(raw: bytes | str, source: str = "<text>") -> Problem:
    """Validate a problem given as YAML text (see :func:`load_problem`)."""
    if isinstance(raw, str):
        raw = raw.encode("utf-8")
    document = read_document(raw, source)
    return _Loader(document, source).problem()

class _Loader(BodiesReader, FrictionReader, AnswersReader, SimulationReader):
    """The whole file: the top level and the declarations here, each other section by its reader
    (:mod:`lagsolve.problem.readers`)."""

    def problem(self) -> Problem:
        self.keys((), self.data, TOP_LEVEL)
        data = self.data = self.misspelt_sections(self.data)
        self.keys((), {k: v for k, v in data.items() if k in TOP_LEVEL}, TOP_LEVEL, required=("name", "coordinates"))
        name, description = self.titles(data)
        time, time_unit = self.time_symbol(data)
        parameters = self.parameters(data.get("parameters", {}))
        functions = self.function_decls(data.get("functions", {}))
        coordinates = self.coordinates(data.get("coordinates", []))
        base, positions, constants = self.namespaces(time, parameters, coordinates)
        particles = self.particle_section(data, positions)
        bodies = self.bodies(data.get("bodies") or {}, positions, base)
        gravity = self.vector(("gravity",), data["gravity"], constants) if "gravity" in data else None
        self.check_dimensions(particles, bodies, gravity)
        kinetic, potential, dissipation = self.energies(data, base, coordinates)
        forces = self.forces(data.get("forces", []), base, particles, coordinates)
        constraints = self.constraints(data.get("constraints", {}), base, self.declared_particles, bodies, positions)
        friction, constraints = self.friction(data.get("friction", {}), base, positions, bodies, constraints,
                                              coordinates)
        self.generated_names([c.name for c in coordinates], [f.name for f in friction])
        expected = self.expected(data.get("expected", {}), constraints)
        simulation = self.simulation(data["simulation"], parameters, coordinates) if "simulation" in data else None
        independent = self.independent(data["independent"], coordinates) if "independent" in data else ()

        if self.issues:
            raise SpecError(sorted(self.issues, key=lambda issue: issue.line))
        return Problem(
            source=self.source, name=name or "", description=description.strip(), time=time,
            parameters=tuple(parameters), functions=tuple(functions), coordinates=tuple(coordinates),
            particles=tuple(particles), bodies=tuple(bodies), gravity=gravity, kinetic=kinetic,
            potential=potential, dissipation=dissipation, forces=tuple(forces),
            constraints=tuple(constraints), friction=tuple(friction), expected=expected,
            simulation=simulation, symbols=dict(self.symbols),
            lines={dotted(k): v for k, v in self.lines.items()}, independent=independent, time_unit=time_unit,
            texts=self.texts,
        )

    def titles(self, data: dict[str, Any]) -> tuple[str | None, str]:
        """The problem's name (None when missing or unreadable) and description ("" when none)."""
        name = self.text(("name",), data["name"], one_line=True, limit=MAX_TITLE_LENGTH) if "name" in data else None
        description = ""
        if "description" in data:
            description = self.text(("description",), data["description"], limit=MAX_PROBLEM_DESCRIPTION_LENGTH) or ""
        return name, description

    def time_symbol(self, data: dict[str, Any]) -> tuple[sympy.Symbol, str | None]:
        """The time's symbol, declared (``t`` when the name given cannot be used), and its unit (None when
        not given)."""
        time_name, time_unit = data.get("time", "t"), None
        if isinstance(time_name, dict):  # time: {name: t, unit: ms}
            time_name, time_unit = self.time_spec(time_name)
        if not isinstance(time_name, str) or not self.declare(("time",), time_name, "the time"):
            if not isinstance(time_name, str):
                self.issue(("time",), f"expected a name, found {kind_of(time_name)}")
            time_name = "t"
            self.kinds.setdefault("t", "the time")
        time = sympy.Symbol(time_name, real=True)
        self.symbols[time_name] = time
        return time, time_unit

    def namespaces(self, time: sympy.Symbol, parameters: list[Parameter], coordinates: list[Coordinate]
                   ) -> tuple[gateway.Namespace, gateway.Namespace, gateway.Namespace]:
        """The names each kind of expression may use: every declared one (``base``), all but the velocities
        (``positions``: positions, masses and inertias), only the parameters and the time (``constants``)."""
        base = gateway.Namespace(self.symbols, self.functions, self.acceleration_names)
        velocity_names = {n for n in self.symbols if n.endswith("_dot") and n[:-4] in self.kinds}
        positions = gateway.Namespace(
            {n: s for n, s in self.symbols.items() if n not in velocity_names}, self.functions,
            {**self.acceleration_names,
             **{n: "positions, masses and inertias cannot depend on velocities" for n in velocity_names}},
        )
        constants = gateway.Namespace(
            {time.name: time, **{p.name: p.symbol for p in parameters}}, {},
            {**{c.name: "a coordinate cannot appear here (only parameters and the time)" for c in coordinates}},
        )
        return base, positions, constants

    def particle_section(self, data: dict[str, Any], positions: gateway.Namespace) -> list[Particle]:
        """The particles, after noting every particle name the file gives (valid or not: a reference to
        one that failed to load is not reported a second time as "unknown particle")."""
        raw_particles = data.get("particles") or {}
        if not isinstance(raw_particles, dict):
            self.mapping(("particles",), data["particles"])
            raw_particles = {}
            self.particles_readable = False
        elif "particles" in data and data["particles"] is None:
            self.mapping(("particles",), None)
        self.declared_particles = [n for n in raw_particles if isinstance(n, str)]
        particles = self.particles(raw_particles, positions)
        self.loaded_particles = {p.name: p for p in particles}
        return particles

    def energies(self, data: dict[str, Any], base: gateway.Namespace, coordinates: list[Coordinate]
                 ) -> tuple[Any, Any, Any]:
        """The ``kinetic``, ``potential`` and ``dissipation`` expressions (None when not given); a problem
        with coordinates and nothing giving a kinetic energy is an issue."""
        kinetic = self.expression(("kinetic",), data["kinetic"], base) if "kinetic" in data else None
        potential = self.expression(("potential",), data["potential"], base) if "potential" in data else None
        dissipation = (self.expression(("dissipation",), data["dissipation"], base)
                       if "dissipation" in data else None)
        if not (data.get("particles") or data.get("bodies") or "kinetic" in data) and coordinates:
            self.issue((), "the problem has no kinetic energy",
                       "add particles, bodies, or a 'kinetic:' expression")
        return kinetic, potential, dissipation

    def misspelt_sections(self, data: dict[str, Any]) -> dict[str, Any]:
        """``data`` with a misspelt top-level key (``particle:``, reported already) read as the section it was meant
        to be, so that what follows from the missing section (unknown particles, no kinetic energy) is not
        reported too: one mistake, one error."""
        out = dict(data)
        for key in data:
            if not isinstance(key, str) or key in TOP_LEVEL:
                continue
            close = difflib.get_close_matches(key, TOP_LEVEL, n=1)
            if close and close[0] not in out:
                out[close[0]] = data[key]
                self.lines.update({(close[0], *path[1:]): line for path, line in list(self.lines.items())
                                   if path[:1] == (key,)})
        return out

    def time_spec(self, value: dict[str, Any]) -> tuple[Any, str | None]:
        """``time: {name: t, unit: ms}`` → the name and the unit."""
        self.keys(("time",), value, ("name", "unit"))
        unit = self.unit(("time", "unit"), value["unit"]) if "unit" in value else None
        return value.get("name", "t"), unit

    def parameters(self, value: Any) -> list[Parameter]:
        out = []
        for name, detail, path in self.names_list(("parameters",), value):
            description, positive, real, default, unit = "", True, True, None, None
            if isinstance(detail, str):
                description = detail
            elif isinstance(detail, dict):
                self.keys(path, detail, ("description", "positive", "real", "value", "unit"))
                unit = self.unit((*path, "unit"), detail["unit"]) if "unit" in detail else None
                description = self.text((*path, "description"), detail.get("description", "")) or ""
                if "positive" in detail:
                    positive = bool(self.flag((*path, "positive"), detail["positive"]))
                if "real" in detail:
                    real = bool(self.flag((*path, "real"), detail["real"]))
                if "value" in detail:
                    default = self.number((*path, "value"), detail["value"])
                    if default is not None and not self.assumption_holds((*path, "value"), name, default, positive):
                        default = None
            elif detail is not None:
                self.issue(path, f"expected a description or a mapping, found {kind_of(detail)}")
            if not self.declare(path, name, "a parameter"):
                continue
            symbol = sympy.Symbol(name, positive=True) if positive else sympy.Symbol(name, real=real or None)
            self.symbols[name] = symbol
            out.append(Parameter(name, description.strip(), positive, real, default, symbol, unit))
        return out

    def function_decls(self, value: Any) -> list[FunctionDecl]:
        out = []
        for name, detail, path in self.names_list(("functions",), value):
            unit = None
            if isinstance(detail, dict):  # f: {description: ..., unit: m}
                self.keys(path, detail, ("description", "unit"))
                unit = self.unit((*path, "unit"), detail["unit"]) if "unit" in detail else None
                detail = self.text((*path, "description"), detail.get("description", "")) or ""
            elif detail is not None and not isinstance(detail, str):
                self.issue(path, f"expected a description or a mapping, found {kind_of(detail)}")
            if not self.declare(path, name, "a function"):
                continue
            fn = sympy.Function(name, real=True)
            self.functions[name] = fn
            out.append(FunctionDecl(name, (detail or "").strip() if isinstance(detail, str) else "", fn, unit))
        return out

    def coordinates(self, value: Any) -> list[Coordinate]:
        out = []
        entries = self.names_list(("coordinates",), value)
        if not entries and "coordinates" in self.data:
            self.issue(("coordinates",), "no coordinates given", "list at least one, e.g. [x, y]")
        for name, detail, path in entries:
            positive, unit = False, None
            if isinstance(detail, dict):
                self.keys(path, detail, ("description", "positive", "unit"))
                unit = self.unit((*path, "unit"), detail["unit"]) if "unit" in detail else None
                if "positive" in detail:
                    positive = bool(self.flag((*path, "positive"), detail["positive"]))
                detail = self.text((*path, "description"), detail.get("description", "")) or ""
            elif detail is not None and not isinstance(detail, str):
                self.issue(path, f"expected a description or a mapping, found {kind_of(detail)}")
            if not self.declare(path, name, "a coordinate"):
                continue
            velocity, acceleration = f"{name}_dot", f"{name}_ddot"
            for derived in (velocity, acceleration):
                if derived in self.kinds:
                    self.issue(path, f"{derived!r} (derived from coordinate {name!r}) is already declared as "
                               f"{self.kinds[derived]}", "rename one of them")
            q = sympy.Symbol(name, positive=True) if positive else sympy.Symbol(name, real=True)
            qd = sympy.Symbol(velocity, real=True)
            qdd = sympy.Symbol(acceleration, real=True)
            self.symbols[name] = q
            self.symbols[velocity] = qd
            self.acceleration_names[acceleration] = "accelerations may not appear in problem expressions"
            out.append(Coordinate(name, (detail or "").strip() if isinstance(detail, str) else "", q, qd, qdd,
                                  unit))
        return out
