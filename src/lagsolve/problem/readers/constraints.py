"""The problem file's constraints and friction contacts."""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.problem import expr as gateway
from lagsolve.problem.readers.base import Reader, known_names, shown
from lagsolve.problem.schema import (
    Body,
    Constraint,
    ConstraintKind,
    Coordinate,
    Friction,
)


class ConstraintsReader(Reader):
    """Reads ``constraints`` and ``friction``."""

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
            kinds = [k for k in ConstraintKind if k in spec]
            if len(kinds) != 1:
                self.issue(path, "give exactly one of 'holonomic: psi(q, t)' or 'nonholonomic: a.q_dot + b'")
                continue
            kind = kinds[0]
            raw_on = spec.get("on")
            first = raw_on[0] if isinstance(raw_on, list) and raw_on else raw_on
            body = next((b for b in bodies if first == b.name), None)
            at = None
            if body is not None or "at" in spec:
                at = self.contact_point(path, spec, body, points)
                if at is None:
                    continue
                on: tuple[str, ...] | None = self.contact_pair(path, raw_on, body, particles, bodies)
            else:
                on = self.constraint_on(path, spec, particles)
            if on is None:
                continue
            psi = self.expression((*path, kind), spec[kind], names)
            if psi is None:
                continue
            used = psi.free_symbols & velocities
            if kind == ConstraintKind.HOLONOMIC and used:
                self.issue((*path, kind), "a holonomic constraint cannot contain velocities (found "
                           + ", ".join(sorted(str(s) for s in used)) + ")",
                           "write it under 'nonholonomic:' instead")
                continue
            if kind == ConstraintKind.HOLONOMIC and not psi.free_symbols & positions:
                self.issue((*path, kind), "this constraint contains no coordinate, so it cannot "
                           "restrict the motion", "write psi(q, t) in terms of the coordinates")
                continue
            if kind == ConstraintKind.NONHOLONOMIC:
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
            self.issue((*path, "on"),
                       "'at:' names a point of a body; 'on:' must name that body (first, when it names two)",
                       known_names("bodies", [n for n in (self.data.get("bodies") or {}) if isinstance(n, str)]))
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

    def contact_pair(self, path: tuple, raw: Any, body: Body | None, particles: list[str],
                     bodies: list[Body]) -> tuple[str, ...] | None:
        """``on: disk`` or ``on: [disk, other]``: the body the point belongs to, and the particle or planar body
        it presses on (which gets the opposite force at the same point: a surface that moves)."""
        if body is None:
            return None
        if not isinstance(raw, list) or len(raw) == 1:
            return (body.name,)
        planar = [b.name for b in bodies if b.planar]
        if len(raw) != 2 or not isinstance(raw[1], str) or raw[1] == body.name or raw[1] not in [*particles, *planar]:
            self.issue((*path, "on"), f"with 'at:', 'on:' names the body {body.name!r} and at most one particle or "
                       f"planar body it presses on (found {', '.join(shown(x) for x in raw[:4])})",
                       "write on: [" + body.name + ", OTHER] with OTHER one of: "
                       + (", ".join(n for n in [*particles, *planar] if n != body.name) or "(none)"))
            return None
        return (body.name, raw[1])

    def constraint_on(self, path: tuple, spec: dict, particles: list[str]) -> tuple[str, ...] | None:
        if "on" not in spec:
            return (particles[0],) if len(particles) == 1 else ()
        raw = spec["on"]
        items = raw if isinstance(raw, list) else [raw]
        for item in items:
            if not isinstance(item, str) or item not in particles:
                if isinstance(item, str) and not self.particles_readable:
                    return None  # the particles section itself is reported
                self.issue((*path, "on"), f"unknown particle {shown(item)}",
                           known_names("particles", particles))
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
                           f"unknown particle {shown(on)}" if on else "say which particle slides",
                           known_names("particles", particles))
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
                           f"unknown {what} {shown(item)}", known_names(what + "s", known))
                return None
        if not items:
            self.issue(path, f"name at least one {what}")
            return None
        return tuple(items)
