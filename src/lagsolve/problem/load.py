"""Problem file → validated :class:`~lagsolve.problem.schema.Problem`.

Every problem in a file is collected and reported at once (file, line, field,
what is wrong, how to fix it) in one :class:`~lagsolve.errors.SpecError`.
Expression text reaches SymPy only through :func:`lagsolve.problem.expr.parse`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import sympy

from lagsolve.errors import ExpressionError, Issue, SpecError
from lagsolve.problem import expr as gateway
from lagsolve.problem import units
from lagsolve.problem.schema import (
    Body,
    ConcreteFunction,
    Constraint,
    Coordinate,
    Expected,
    Force,
    Friction,
    FunctionDecl,
    Parameter,
    Particle,
    Problem,
    Simulation,
)
from lagsolve.problem.yamlread import MAX_BYTES, Document, dotted, read_document

TOP_LEVEL = (
    "name", "description", "time", "parameters", "functions", "coordinates", "particles", "bodies",
    "gravity", "kinetic", "potential", "dissipation", "forces", "constraints", "friction",
    "expected", "simulation", "independent",
)
_SIMULATION_KEYS = ("values", "functions", "initial", "t_end", "samples", "method", "rtol", "atol")
_EXPECTED_KEYS = ("accelerations", "multipliers", "constraint_forces", "reduced", "conserved",
                  "effective_potential")
_METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")
#: longest free text, in characters: the name (a title, drawn on every figure), the problem's
#: description, and a parameter's, coordinate's or function's description
MAX_TITLE_LENGTH = 200
MAX_PROBLEM_DESCRIPTION_LENGTH = 20_000
MAX_DESCRIPTION_LENGTH = 1_000


def load_problem(path: str | Path) -> Problem:
    """Read and validate one problem file.

    Raises
    ------
    SpecError
        Listing every problem found, each with file, line, field and a fix.
    """
    source = str(path)
    try:
        # read at most one byte over the limit: a device or pipe never makes this hang
        with Path(path).open("rb") as handle:
            raw = handle.read(MAX_BYTES + 1)
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


class _Loader:
    """Walks the document once, collecting issues instead of stopping at the first."""

    def __init__(self, document: Document, source: str) -> None:
        self.data: dict[str, Any] = document.data
        self.lines = document.lines
        self.source = source
        self.issues: list[Issue] = []
        self.symbols: dict[str, Any] = {}
        self.kinds: dict[str, str] = {}  # name -> what declared it
        self.functions: dict[str, Any] = {}
        self.velocity_names: dict[str, Any] = {}
        self.declared_particles: list[str] = []
        self.particles_readable = True  # False: references to particles cannot be checked
        self.acceleration_names: dict[str, Any] = {}
        self.texts: dict[str, str] = {}  # dotted field -> expression text as written (for messages)

    # -- reporting ---------------------------------------------------------------------------

    def line(self, path: tuple) -> int:
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return self.lines.get((), 1)

    def issue(self, path: tuple, message: str, hint: str = "") -> None:
        self.issues.append(Issue(self.source, self.line(path), dotted(path), message, hint))

    # -- typed field readers -----------------------------------------------------------------

    def mapping(self, path: tuple, value: Any, what: str = "a mapping") -> dict[str, Any] | None:
        if isinstance(value, dict):
            return value
        self.issue(path, f"expected {what}, found {_kind(value)}", "write it as 'key: value' lines")
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
        self.issue(path, f"expected text, found {_kind(value)}")
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
            self.issue(path, f"expected a number, found {_kind(value)}")
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
        self.issue(path, f"expected true or false, found {_kind(value)}")
        return None

    def expression(self, path: tuple, value: Any, names: gateway.Namespace) -> Any | None:
        try:
            parsed = gateway.parse(value, names)
        except ExpressionError as exc:
            self.issue(path, exc.message, exc.hint)
            return None
        self.texts[dotted(path)] = str(value)
        return parsed

    def vector(self, path: tuple, value: Any, names: gateway.Namespace) -> tuple[Any, ...] | None:
        if not isinstance(value, list) or not 2 <= len(value) <= 3:
            found = f"{len(value)} components" if isinstance(value, list) else _kind(value)
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
        return True

    def names_list(self, path: tuple, value: Any) -> list[tuple[str, str, tuple]]:
        """A list of names, or a mapping name -> description (or -> details)."""
        if isinstance(value, list):
            out = []
            for i, item in enumerate(value):
                if isinstance(item, str):
                    out.append((item, "", (*path, i)))
                else:
                    self.issue((*path, i), f"expected a name, found {_kind(item)}")
            return out
        if isinstance(value, dict):
            return [(k, v if not isinstance(v, str) or self.short_enough((*path, k), v, MAX_DESCRIPTION_LENGTH)
                     else "", (*path, k)) for k, v in value.items()]
        self.issue(path, f"expected a list of names or a mapping name: description, found {_kind(value)}")
        return []

    # -- the problem -------------------------------------------------------------------------

    def problem(self) -> Problem:
        data = self.data
        self.keys((), data, TOP_LEVEL, required=("name", "coordinates"))
        name = self.text(("name",), data["name"], one_line=True, limit=MAX_TITLE_LENGTH) if "name" in data else None
        description = ""
        if "description" in data:
            description = self.text(("description",), data["description"], limit=MAX_PROBLEM_DESCRIPTION_LENGTH) or ""

        time_name, time_unit = data.get("time", "t"), None
        if isinstance(time_name, dict):  # time: {name: t, unit: ms}
            time_name, time_unit = self.time_spec(time_name)
        if not isinstance(time_name, str) or not self.declare(("time",), time_name, "the time"):
            if not isinstance(time_name, str):
                self.issue(("time",), f"expected a name, found {_kind(time_name)}")
            time_name = "t"
            self.kinds.setdefault("t", "the time")
        time = sympy.Symbol(time_name, real=True)
        self.symbols[time_name] = time

        parameters = self.parameters(data.get("parameters", {}))
        functions = self.function_decls(data.get("functions", {}))
        coordinates = self.coordinates(data.get("coordinates", []))

        base = gateway.Namespace(self.symbols, self.functions, self.acceleration_names)
        velocity_names = {n for n in self.symbols if n.endswith("_dot") and n[:-4] in self.kinds}
        positions = gateway.Namespace(
            {n: s for n, s in self.symbols.items() if n not in velocity_names}, self.functions,
            {**self.acceleration_names,
             **{n: "positions, masses and inertias cannot depend on velocities" for n in velocity_names}},
        )
        constants = gateway.Namespace(
            {time_name: time, **{p.name: p.symbol for p in parameters}}, {},
            {**{c.name: "a coordinate cannot appear here (only parameters and the time)" for c in coordinates}},
        )
        raw_particles = data.get("particles") or {}
        if not isinstance(raw_particles, dict):
            self.mapping(("particles",), data["particles"])
            raw_particles = {}
            self.particles_readable = False
        elif "particles" in data and data["particles"] is None:
            self.mapping(("particles",), None)
        # every particle the file names, valid or not: a reference to one that failed to load
        # is not reported a second time as "unknown particle"
        self.declared_particles = [n for n in raw_particles if isinstance(n, str)]
        particles = self.particles(raw_particles, positions)
        bodies = self.bodies(data.get("bodies") or {}, positions, base)
        gravity = self.vector(("gravity",), data["gravity"], constants) if "gravity" in data else None
        self.check_dimensions(particles, bodies, gravity)

        kinetic = self.expression(("kinetic",), data["kinetic"], base) if "kinetic" in data else None
        potential = self.expression(("potential",), data["potential"], base) if "potential" in data else None
        dissipation = (self.expression(("dissipation",), data["dissipation"], base)
                       if "dissipation" in data else None)
        if not (data.get("particles") or data.get("bodies") or "kinetic" in data) and coordinates:
            self.issue((), "the problem has no kinetic energy",
                       "add particles, bodies, or a 'kinetic:' expression")

        particle_names = self.declared_particles
        forces = self.forces(data.get("forces", []), base, particles, coordinates)
        constraints = self.constraints(data.get("constraints", {}), base, particle_names, bodies, positions)
        friction = self.friction(data.get("friction", {}), base, particle_names, constraints, coordinates)
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

    def unit(self, path: tuple, value: Any) -> str | None:
        """A ``unit:`` field (:mod:`lagsolve.problem.units`); None and an issue when it is not a unit."""
        try:
            return units.canonical(value)
        except ExpressionError as exc:
            self.issue(path, exc.message, exc.hint)
            return None

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
                self.issue(path, f"expected a description or a mapping, found {_kind(detail)}")
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
                self.issue(path, f"expected a description or a mapping, found {_kind(detail)}")
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
                self.issue(path, f"expected a description or a mapping, found {_kind(detail)}")
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

    def particles(self, value: dict[str, Any], names: gateway.Namespace) -> list[Particle]:
        out = []
        for pname, spec in value.items():
            path = ("particles", pname)
            problem = gateway.name_problem(pname)
            if problem is not None:
                self.issue(path, problem)
                continue
            spec = self.mapping(path, spec)
            if spec is None or not self.keys(path, spec, ("mass", "position"), ("mass", "position")):
                continue
            mass = self.expression((*path, "mass"), spec["mass"], names)
            position = self.vector((*path, "position"), spec["position"], names)
            if mass is not None and position is not None:
                out.append(Particle(pname, mass, position))
        return out

    def bodies(self, value: Any, names: gateway.Namespace, rates: gateway.Namespace) -> list[Body]:
        out: list[Body] = []
        if not isinstance(value, dict):
            self.mapping(("bodies",), value)
            return out
        keys = ("mass", "position", "inertia", "angular_velocity")
        for bname, spec in value.items():
            path = ("bodies", bname)
            problem = gateway.name_problem(bname)
            if problem is not None:
                self.issue(path, problem)
                continue
            spec = self.mapping(path, spec)
            if spec is None or not self.keys(path, spec, keys, keys):
                continue
            mass = self.expression((*path, "mass"), spec["mass"], names)
            position = self.vector((*path, "position"), spec["position"], names)
            inertia, omega = spec["inertia"], spec["angular_velocity"]
            if isinstance(inertia, list) != isinstance(omega, list):
                self.issue(path, "inertia and angular_velocity must both be scalars (planar body) or both lists "
                           "of 3 (3-D body)")
                continue
            if isinstance(inertia, list):
                if len(inertia) != 3 or len(omega) != 3:
                    self.issue(path, "a 3-D body needs 3 principal moments and 3 body-frame angular velocity "
                               "components")
                    continue
                parts_i = [self.expression((*path, "inertia", i), v, names) for i, v in enumerate(inertia)]
                parts_w = [self.expression((*path, "angular_velocity", i), v, rates) for i, v in enumerate(omega)]
            else:
                parts_i = [self.expression((*path, "inertia"), inertia, names)]
                parts_w = [self.expression((*path, "angular_velocity"), omega, rates)]
            if mass is None or position is None or None in parts_i or None in parts_w:
                continue
            if len(parts_i) == 3 and len(position) != 3:
                self.issue((*path, "position"), "a 3-D body needs a 3-component position")
                continue
            out.append(Body(bname, mass, position, tuple(parts_i), tuple(parts_w)))
        return out

    def check_dimensions(self, particles: list[Particle], bodies: list[Body], gravity: tuple | None) -> None:
        dims = {len(p.position) for p in particles} | {len(b.position) for b in bodies}
        if len(dims) > 1:
            self.issue(("particles",), "particles and bodies mix 2- and 3-component positions",
                       "use the same number of components everywhere")
        if gravity is not None and dims and len(gravity) not in dims:
            self.issue(("gravity",), f"gravity has {len(gravity)} components but positions have {dims.pop()}",
                       "give gravity as many components as the positions")

    def forces(self, value: Any, names: gateway.Namespace, particles: list[Particle],
               coordinates: list[Coordinate]) -> list[Force]:
        dims = {p.name: len(p.position) for p in particles}
        out: list[Force] = []
        if not isinstance(value, list):
            self.issue(("forces",), f"expected a list, found {_kind(value)}",
                       "write '- {coordinate: x, value: ...}' or '- {on: particle, force: [...]}'")
            return out
        coordinate_names = [c.name for c in coordinates]
        for i, spec in enumerate(value):
            path = ("forces", i)
            spec = self.mapping(path, spec)
            if spec is None:
                continue
            if "coordinate" in spec:
                if not self.keys(path, spec, ("coordinate", "value"), ("coordinate", "value")):
                    continue
                q = spec["coordinate"]
                if q not in coordinate_names:
                    self.issue((*path, "coordinate"), f"unknown coordinate {q!r}",
                               "known: " + ", ".join(coordinate_names))
                    continue
                val = self.expression((*path, "value"), spec["value"], names)
                if val is not None:
                    out.append(Force(q, None, (val,)))
            elif "on" in spec:
                if not self.keys(path, spec, ("on", "force"), ("on", "force")):
                    continue
                on = spec["on"]
                if not isinstance(on, str) or on not in self.declared_particles:
                    if isinstance(on, str) and not self.particles_readable:
                        continue
                    self.issue((*path, "on"), f"unknown particle {_short(on)}",
                               _known("particles", self.declared_particles))
                    continue
                vec = self.vector((*path, "force"), spec["force"], names)
                if vec is None or on not in dims:  # a particle that failed has its own issue
                    continue
                if len(vec) != dims[on]:
                    self.issue((*path, "force"),
                               f"the force has {len(vec)} components but particle {on!r} has "
                               f"{dims[on]}", "give it as many components as the position")
                else:
                    out.append(Force(None, on, vec))
            else:
                self.issue(path, "a force needs 'coordinate' (a generalized force) or 'on' (a force on a particle)")
        return out

    def constraints(self, value: Any, names: gateway.Namespace, particles: list[str], bodies: list[Body],
                    points: gateway.Namespace) -> list[Constraint]:
        out: list[Constraint] = []
        value = self.mapping(("constraints",), value, "a mapping name: constraint")
        if value is None:
            return out
        velocities = set(self.velocity_symbols())
        positions = {self.symbols[n] for n, k in self.kinds.items() if k == "a coordinate"}
        for cname, spec in value.items():
            path = ("constraints", cname)
            problem = gateway.name_problem(cname)
            if problem is not None:
                self.issue(path, problem)
                continue
            spec = self.mapping(path, spec)
            if spec is None or not self.keys(path, spec, ("holonomic", "nonholonomic", "on", "unilateral", "at")):
                continue
            unilateral = False
            if "unilateral" in spec:
                unilateral = bool(self.flag((*path, "unilateral"), spec["unilateral"]))
            kinds = [k for k in ("holonomic", "nonholonomic") if k in spec]
            if len(kinds) != 1:
                self.issue(path, "give exactly one of 'holonomic: psi(q, t)' or 'nonholonomic: a.q_dot + b'")
                continue
            kind = kinds[0]
            body = next((b for b in bodies if spec.get("on") == b.name), None)
            at = None
            if body is not None or "at" in spec:
                at = self.contact_point(path, spec, body, points)
                if at is None:
                    continue
                on: tuple[str, ...] | None = (body.name,) if body is not None else None
            else:
                on = self.constraint_on(path, spec, particles)
            if on is None:
                continue
            psi = self.expression((*path, kind), spec[kind], names)
            if psi is None:
                continue
            used = psi.free_symbols & velocities
            if kind == "holonomic" and used:
                self.issue((*path, kind), "a holonomic constraint cannot contain velocities (found "
                           + ", ".join(sorted(str(s) for s in used)) + ")",
                           "write it under 'nonholonomic:' instead")
                continue
            if kind == "holonomic" and not psi.free_symbols & positions:
                self.issue((*path, kind), "this constraint contains no coordinate, so it cannot "
                           "restrict the motion", "write psi(q, t) in terms of the coordinates")
                continue
            if kind == "nonholonomic":
                if not used:
                    self.issue((*path, kind), "this velocity constraint contains no velocity",
                               "write a position constraint under 'holonomic:'")
                    continue
                bad = [str(v) for v in sorted(used, key=str)
                       if sympy.diff(psi, v).free_symbols & velocities]
                if bad:
                    self.issue((*path, kind), "velocity constraint is not linear in the velocities ("
                               + ", ".join(bad) + ")",
                               "write it as a_1*q1_dot + a_2*q2_dot + ... + b with a and b free of velocities")
                    continue
            out.append(Constraint(cname, kind, psi, on, self.line((*path, kind)), unilateral, at))
        return out

    def contact_point(self, path: tuple, spec: dict, body: Body | None,
                      positions: gateway.Namespace) -> tuple[Any, ...] | None:
        """``on: disk`` with ``at: [X, Y - R]``: the point of a planar body where a constraint acts."""
        if body is None:
            self.issue((*path, "on"), "'at:' names a point of a body; 'on:' must name that body",
                       _known("bodies", [n for n in (self.data.get("bodies") or {}) if isinstance(n, str)]))
            return None
        if "at" not in spec:
            self.issue((*path, "on"), f"a constraint on the body {body.name!r} needs the point where it acts",
                       f"add 'at: [x, y]', the contact point in the problem's coordinates (the centre of "
                       f"{body.name!r} is {[str(c) for c in body.position]})")
            return None
        if not body.planar:
            self.issue((*path, "at"), f"{body.name!r} is a 3-D body; 'at:' is supported for planar bodies",
                       "leave 'on:' and 'at:' out: the generalized forces of constraint are then reported")
            return None
        point = self.vector((*path, "at"), spec["at"], positions)
        if point is not None and len(point) != len(body.position):
            self.issue((*path, "at"), f"the point has {len(point)} components but {body.name!r} has "
                       f"{len(body.position)}", "give it as many components as the body's position")
            return None
        return point

    def constraint_on(self, path: tuple, spec: dict, particles: list[str]) -> tuple[str, ...] | None:
        if "on" not in spec:
            return (particles[0],) if len(particles) == 1 else ()
        raw = spec["on"]
        items = raw if isinstance(raw, list) else [raw]
        for item in items:
            if not isinstance(item, str) or item not in particles:
                if isinstance(item, str) and not self.particles_readable:
                    return None  # the particles section itself is reported
                self.issue((*path, "on"), f"unknown particle {_short(item)}",
                           _known("particles", particles))
                return None
        return tuple(items)

    def friction(self, value: Any, names: gateway.Namespace, particles: list[str],
                 constraints: list[Constraint], coordinates: list[Coordinate]) -> list[Friction]:
        out: list[Friction] = []
        value = self.mapping(("friction",), value, "a mapping name: contact")
        if value is None:
            return out
        constraint_names = [c.name for c in constraints]
        coordinate_names = [c.name for c in coordinates]
        for fname, spec in value.items():
            path = ("friction", fname)
            spec = self.mapping(path, spec)
            if spec is None or not self.keys(path, spec, ("coefficient", "static", "on", "normal", "sliding"),
                                             ("coefficient", "normal")):
                continue
            coefficient = self.expression((*path, "coefficient"), spec["coefficient"], names)
            static = self.expression((*path, "static"), spec["static"], names) if "static" in spec else None
            on = spec.get("on", particles[0] if len(particles) == 1 else None)
            if not isinstance(on, str) or on not in particles:
                if isinstance(on, str) and not self.particles_readable:
                    continue
                self.issue((*path, "on"),
                           f"unknown particle {_short(on)}" if on else "say which particle slides",
                           _known("particles", particles))
                continue
            normal = self.name_refs((*path, "normal"), spec["normal"], constraint_names, "constraint")
            sliding = (self.name_refs((*path, "sliding"), spec["sliding"], coordinate_names, "coordinate")
                       if "sliding" in spec else tuple(coordinate_names))
            if coefficient is None or normal is None or sliding is None or ("static" in spec and static is None):
                continue
            out.append(Friction(fname, coefficient, static, on, normal, sliding))
        return out

    def name_refs(self, path: tuple, value: Any, known: list[str], what: str) -> tuple[str, ...] | None:
        items = value if isinstance(value, list) else [value]
        for i, item in enumerate(items):
            if not isinstance(item, str) or item not in known:
                self.issue((*path, i) if isinstance(value, list) else path,
                           f"unknown {what} {_short(item)}", _known(what + "s", known))
                return None
        if not items:
            self.issue(path, f"name at least one {what}")
            return None
        return tuple(items)

    def velocity_symbols(self) -> list[Any]:
        return [s for n, s in self.symbols.items() if n.endswith("_dot") and n[:-4] in self.kinds]

    def answer_names(self, constraints: list[Constraint]) -> gateway.Namespace:
        extra = {f"lambda_{c.name}": sympy.Symbol(f"lambda_{c.name}", real=True) for c in constraints}
        extra.update({f"p_{n}": sympy.Symbol(f"p_{n}", real=True)
                      for n, k in self.kinds.items() if k == "a coordinate" and f"p_{n}" not in self.kinds})
        return gateway.Namespace({**self.symbols, **extra}, self.functions, self.acceleration_names)

    def expected(self, value: Any, constraints: list[Constraint]) -> Expected:
        spec = self.mapping(("expected",), value)
        if not spec:
            return Expected()
        self.keys(("expected",), spec, _EXPECTED_KEYS)
        names = self.answer_names(constraints)
        coordinate_names = [n for n, k in self.kinds.items() if k == "a coordinate"]
        constraint_names = [c.name for c in constraints]

        def table(key: str, known: list[str], what: str, parse: Callable[[tuple, Any], Any]) -> dict[str, Any]:
            path = ("expected", key)
            raw = self.mapping(path, spec.get(key, {}))
            out = {}
            for k, v in (raw or {}).items():
                if known and k not in known:
                    self.issue((*path, k), f"unknown {what} {k!r}", _known(what + "s", known))
                    continue
                parsed = parse((*path, k), v)
                if parsed is not None:
                    out[k] = parsed
            return out

        def plain(path: tuple, v: Any) -> Any:
            return self.expression(path, v, names)

        def force(path: tuple, v: Any) -> dict[str, Any] | None:
            if isinstance(v, dict):
                if not self.keys(path, v, ("vector", "magnitude")):
                    return None
                result: dict[str, Any] = {}
                if "magnitude" in v:
                    result["magnitude"] = self.expression((*path, "magnitude"), v["magnitude"], names)
                if "vector" in v:
                    result["vector"] = self.vector((*path, "vector"), v["vector"], names)
                return None if None in result.values() else result
            magnitude = self.expression(path, v, names)
            return None if magnitude is None else {"magnitude": magnitude}

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
            effective = self.effective_potential(spec["effective_potential"], names, coordinate_names)
        return Expected(
            accelerations=table("accelerations", coordinate_names, "coordinate", plain),
            multipliers=table("multipliers", constraint_names, "constraint", plain),
            constraint_forces=table("constraint_forces", constraint_names, "constraint", force),
            reduced=reduced,
            conserved=table("conserved", [], "quantity", plain),
            effective_potential=effective,
        )

    def effective_potential(self, value: Any, names: gateway.Namespace, coordinates: list[str]) -> dict | None:
        path = ("expected", "effective_potential")
        spec = self.mapping(path, value)
        if spec is None or not self.keys(path, spec, ("coordinate", "expression", "equilibria"), ("coordinate",)):
            return None
        if spec["coordinate"] not in coordinates:
            self.issue((*path, "coordinate"), f"unknown coordinate {_short(spec['coordinate'])}",
                       _known("coordinates", coordinates))
            return None
        result: dict[str, Any] = {"coordinate": spec["coordinate"]}
        if "expression" in spec:
            result["expression"] = self.expression((*path, "expression"), spec["expression"], names)
        equilibria = []
        raw = spec.get("equilibria") or []
        if not isinstance(raw, list):
            self.issue((*path, "equilibria"), f"expected a list, found {_kind(raw)}",
                       "write '- {value: ..., stable: true}' items")
            raw = []
        for i, item in enumerate(raw):
            ipath = (*path, "equilibria", i)
            item = self.mapping(ipath, item)
            if item is None or not self.keys(ipath, item, ("value", "stable", "frequency"), ("value",)):
                continue
            entry: dict[str, Any] = {"value": self.expression((*ipath, "value"), item["value"], names)}
            if "stable" in item:
                entry["stable"] = self.flag((*ipath, "stable"), item["stable"])
            if "frequency" in item:
                entry["frequency"] = self.expression((*ipath, "frequency"), item["frequency"], names)
            equilibria.append(entry)
        result["equilibria"] = equilibria
        return result

    def independent(self, value: Any, coordinates: list[Coordinate]) -> tuple[str, ...]:
        """``independent: [x]``: the coordinates to keep as minimal coordinates (each once)."""
        known = [c.name for c in coordinates]
        if not isinstance(value, list) or not value:
            self.issue(("independent",), f"expected a list of coordinate names, found {_kind(value)}",
                       "write e.g. 'independent: [x]'")
            return ()
        out: list[str] = []
        for i, item in enumerate(value):
            if not isinstance(item, str) or item not in known:
                self.issue(("independent", i), f"unknown coordinate {_short(item)}", _known("coordinates", known))
            elif item in out:
                self.issue(("independent", i), f"coordinate {item!r} is listed twice", "give each name once")
            else:
                out.append(item)
        return tuple(out)

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
                self.issue((*path, "values", k), f"unknown parameter {k!r}", _known("parameters", parameter_names))
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
                           _known("names", state_names))
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
        if method is not None and method not in _METHODS:
            self.issue((*path, "method"), f"unknown method {method!r}", "use one of: " + ", ".join(_METHODS))
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
                           _known("functions", sorted(self.functions)))
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


def _kind(value: Any) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"true/false ({value})"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, str):
        return f"text {value[:40]!r}"
    return f"a number ({value})"


def _short(value: Any) -> str:
    """A value for a message: names quoted, anything else described."""
    return repr(value) if isinstance(value, str) else f"({_kind(value)})"


def _known(what: str, names: Iterable[str]) -> str:
    names = list(names)
    return f"known {what}: " + ", ".join(names) if names else f"no {what} are declared"
