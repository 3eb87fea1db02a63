"""The problem file's particles, bodies and applied forces."""

from __future__ import annotations

from typing import Any

from lagsolve.problem import expr as gateway
from lagsolve.problem.readers.base import Reader, kind_of, known_names, shown
from lagsolve.problem.schema import (
    Body,
    Coordinate,
    Force,
    Particle,
)


class BodiesReader(Reader):
    """Reads ``particles``, ``bodies`` and ``forces``."""

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
            self.issue(("forces",), f"expected a list, found {kind_of(value)}",
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
                    self.issue((*path, "on"), f"unknown particle {shown(on)}",
                               known_names("particles", self.declared_particles))
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
