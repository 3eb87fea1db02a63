"""The problem file's constraints."""

from __future__ import annotations

from typing import Any

import sympy

from lagsolve.problem import expr as gateway
from lagsolve.problem.readers.base import Reader, known_names, shown
from lagsolve.problem.schema import (
    Body,
    Constraint,
    ConstraintKind,
    Particle,
)


class ConstraintsReader(Reader):
    """Reads ``constraints``."""

    def constraints(self, value: Any, names: gateway.Namespace, particles: list[str], bodies: list[Body],
                    points: gateway.Namespace) -> list[Constraint]:
        out: list[Constraint] = []
        value = self.mapping(("constraints",), value, "a mapping name: constraint")
        if value is None:
            return out
        for cname, spec in value.items():
            constraint = self.constraint(cname, spec, names, particles, bodies, points)
            if constraint is not None:
                out.append(constraint)
        return out

    def constraint(self, cname: Any, spec: Any, names: gateway.Namespace, particles: list[str], bodies: list[Body],
                   points: gateway.Namespace) -> Constraint | None:
        """The constraint ``cname: spec``, or None where it is reported."""
        path = ("constraints", cname)
        problem = gateway.name_problem(cname)
        if problem is not None:
            self.issue(path, problem)
            return None
        spec = self.mapping(path, spec)
        if spec is None or not self.keys(path, spec, ("holonomic", "nonholonomic", "on", "unilateral", "at")):
            return None
        unilateral = False
        if "unilateral" in spec:
            unilateral = bool(self.flag((*path, "unilateral"), spec["unilateral"]))
        kinds = [k for k in ConstraintKind if k in spec]
        if len(kinds) != 1:
            self.issue(path, "give exactly one of 'holonomic: psi(q, t)' or 'nonholonomic: a.q_dot + b'")
            return None
        kind = kinds[0]
        where = self.acts_on(path, spec, particles, bodies, points)
        if where is None:
            return None
        on, at = where
        psi = self.expression((*path, kind), spec[kind], names)
        if psi is None or not self.fits_its_kind((*path, kind), kind, psi):
            return None
        return Constraint(cname, kind, psi, on, self.line((*path, kind)), unilateral, at)

    def acts_on(self, path: tuple, spec: dict, particles: list[str], bodies: list[Body],
                points: gateway.Namespace) -> tuple[tuple[str, ...], tuple[Any, ...] | None] | None:
        """What a constraint acts on (``on:``) and, on a body or with ``at:``, the point where it acts; None
        where that is reported."""
        raw_on = spec.get("on")
        first = raw_on[0] if isinstance(raw_on, list) and raw_on else raw_on
        member = self.member(first, bodies)
        at = None
        if isinstance(member, Body) or "at" in spec:
            at = self.contact_point(path, spec, member, points)
            if at is None:
                return None
            on = self.contact_pair(path, raw_on, member, particles, bodies)
        else:
            on = self.constraint_on(path, spec, particles)
        return None if on is None else (on, at)

    def fits_its_kind(self, path: tuple, kind: ConstraintKind, psi: Any) -> bool:
        """A holonomic constraint holds coordinates and no velocity; a nonholonomic one is linear in the
        velocities it holds (reported where not)."""
        velocities = set(self.velocity_symbols())
        used = psi.free_symbols & velocities
        if kind == ConstraintKind.HOLONOMIC:
            return self.is_holonomic(path, psi, used)
        if not used:
            self.issue(path, "this velocity constraint contains no velocity",
                       "write a position constraint under 'holonomic:'")
            return False
        bad = [str(v) for v in sorted(used, key=str) if sympy.diff(psi, v).free_symbols & velocities]
        if bad:
            self.issue(path, "velocity constraint is not linear in the velocities (" + ", ".join(bad) + ")",
                       "write it as a_1*q1_dot + a_2*q2_dot + ... + b with a and b free of velocities")
            return False
        return True

    def is_holonomic(self, path: tuple, psi: Any, used: set[Any]) -> bool:
        """A holonomic constraint contains no velocity (``used``) and some coordinate (reported where not)."""
        if used:
            self.issue(path, "a holonomic constraint cannot contain velocities (found "
                       + ", ".join(sorted(str(s) for s in used)) + ")",
                       "write it under 'nonholonomic:' instead")
            return False
        positions = {self.symbols[n] for n, k in self.kinds.items() if k == "a coordinate"}
        if not psi.free_symbols & positions:
            self.issue(path, "this constraint contains no coordinate, so it cannot "
                       "restrict the motion", "write psi(q, t) in terms of the coordinates")
            return False
        return True

    def member(self, name: Any, bodies: list[Body]) -> Body | Particle | None:
        """The body or particle called ``name`` (None: neither, or not a name)."""
        if not isinstance(name, str):
            return None
        return next((b for b in bodies if b.name == name), None) or self.loaded_particles.get(name)

    def contact_point(self, path: tuple, spec: dict, member: Body | Particle | None,
                      positions: gateway.Namespace) -> tuple[Any, ...] | None:
        """``on: disk`` with ``at: [X, Y - R]``: the point of a planar body (or the position of a particle) where a
        constraint or a friction contact acts."""
        if member is None:
            self.issue((*path, "on"),
                       "'at:' names the point of a body or particle where it acts; 'on:' must name that body or "
                       "particle (first, when it names two)",
                       known_names("bodies and particles", [n for n in [
                           *(self.data.get("bodies") or {}), *self.declared_particles] if isinstance(n, str)]))
            return None
        if isinstance(member, Particle):
            if "at" not in spec:
                return member.position
            point = self.vector((*path, "at"), spec["at"], positions)
            if point is not None and (len(point) != len(member.position) or any(
                    sympy.expand(a - b) != 0 for a, b in zip(point, member.position, strict=False))):
                self.issue((*path, "at"), f"{member.name!r} is a particle, a point: a force on it acts at its "
                           f"position {[str(c) for c in member.position]}",
                           f"write at: {_listed(member.position)}, or name a body if the contact is elsewhere")
                return None
            return point
        if "at" not in spec:
            self.issue((*path, "on"), f"a constraint or contact on the body {member.name!r} needs the point where it "
                       "acts", f"add 'at: [x, y]', the contact point in the problem's coordinates (the centre of "
                       f"{member.name!r} is {[str(c) for c in member.position]})")
            return None
        if not member.planar:
            self.issue((*path, "at"), f"{member.name!r} is a 3-D body; 'at:' is supported for planar bodies",
                       "leave 'on:' and 'at:' out: the generalized forces of constraint are then reported")
            return None
        point = self.vector((*path, "at"), spec["at"], positions)
        if point is not None and len(point) != len(member.position):
            self.issue((*path, "at"), f"the point has {len(point)} components but {member.name!r} has "
                       f"{len(member.position)}", "give it as many components as the body's position")
            return None
        return point

    def contact_pair(self, path: tuple, raw: Any, member: Body | Particle | None, particles: list[str],
                     bodies: list[Body]) -> tuple[str, ...] | None:
        """``on: disk`` or ``on: [disk, other]``: the body or particle the point belongs to, and the particle or
        planar body it presses on (which gets the opposite force at the same point: a surface that moves)."""
        if member is None:
            return None
        if not isinstance(raw, list) or len(raw) == 1:
            return (member.name,)
        planar = [b.name for b in bodies if b.planar]
        if len(raw) != 2 or not isinstance(raw[1], str) or raw[1] == member.name or raw[1] not in [*particles, *planar]:
            self.issue((*path, "on"), f"with 'at:', 'on:' names {member.name!r} and at most one particle or "
                       f"planar body it presses on (found {', '.join(shown(x) for x in raw[:4])})",
                       "write on: [" + member.name + ", OTHER] with OTHER one of: "
                       + (", ".join(n for n in [*particles, *planar] if n != member.name) or "(none)"))
            return None
        return (member.name, raw[1])

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


def _listed(vector: tuple[Any, ...]) -> str:
    """A vector as a file writes it: ``[x, y - R]``."""
    return "[" + ", ".join(str(c) for c in vector) + "]"
