"""The problem file's friction contacts.

A contact is a pair: the particle or planar body that slides (``on``, first) and the particle or planar
body that carries the surface (second; none: the fixed surroundings), touching at a point (``at``, or a
particle's own position). The pair and the point come from the friction itself or from its normal
constraints; each normal constraint is then a contact between the same pair at the same point, so the
second member gets the opposite force (Newton's third law).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import sympy

from lagsolve.problem import expr as gateway
from lagsolve.problem.readers.base import known_names, shown
from lagsolve.problem.readers.constraints import ConstraintsReader
from lagsolve.problem.schema import Body, Constraint, Coordinate, Friction, Particle

#: the keys of a friction contact
KEYS = ("coefficient", "static", "on", "at", "normal", "sliding")


class FrictionReader(ConstraintsReader):
    """Reads ``friction`` (after ``constraints``, whose normal constraints it makes contacts)."""

    def friction(self, value: Any, names: gateway.Namespace, positions: gateway.Namespace, bodies: list[Body],
                 constraints: list[Constraint], coordinates: list[Coordinate],
                 ) -> tuple[list[Friction], list[Constraint]]:
        """The friction contacts, and the constraints with each normal constraint made a contact (its pair and
        point)."""
        out: list[Friction] = []
        value = self.mapping(("friction",), value, "a mapping name: contact")
        if value is None:
            return out, constraints
        updated = {c.name: c for c in constraints}
        coordinate_names = [c.name for c in coordinates]
        for fname, spec in value.items():
            path = ("friction", fname)
            problem = gateway.name_problem(fname)
            if problem is not None:
                self.issue(path, problem)
                continue
            spec = self.mapping(path, spec)
            if spec is None or not self.keys(path, spec, KEYS, ("coefficient", "normal")):
                continue
            coefficient = self.expression((*path, "coefficient"), spec["coefficient"], names)
            static = self.expression((*path, "static"), spec["static"], names) if "static" in spec else None
            normal = self.name_refs((*path, "normal"), spec["normal"], list(updated), "constraint")
            sliding = (self.name_refs((*path, "sliding"), spec["sliding"], coordinate_names, "coordinate")
                       if "sliding" in spec else tuple(coordinate_names))
            if coefficient is None or normal is None or sliding is None or ("static" in spec and static is None):
                continue
            negative = [key for key, c in (("coefficient", coefficient), ("static", static))
                        if c is not None and c.is_negative]
            for key in negative:
                self.issue((*path, key), f"a coefficient of friction cannot be negative (found {spec[key]})",
                           "give a value >= 0 (0: no friction)")
            if negative:
                continue
            pair = self._pair(path, spec, normal, updated, bodies, positions)
            if pair is None:
                continue
            first, against, point = pair
            for cname in normal:  # each normal constraint acts at the contact, between the same pair
                on = (first,) if against is None else (first, against)
                updated[cname] = dataclasses.replace(updated[cname], on=on, at=point)
            out.append(Friction(fname, coefficient, static, first, normal, sliding, against, point))
        return out, [updated[c.name] for c in constraints]

    def _pair(self, path: tuple, spec: dict[str, Any], normal: tuple[str, ...], constraints: dict[str, Constraint],
              bodies: list[Body], positions: gateway.Namespace,
              ) -> tuple[str, str | None, tuple[Any, ...]] | None:
        """The member that slides, the one that carries the surface (None: the surroundings) and the point."""
        members = self._members(path, spec, normal, constraints, bodies)
        if members is None:
            return None
        first, against = members
        member = self.member(first, bodies)
        if member is None:
            if self.particles_readable:
                self.issue((*path, "on"), f"unknown particle or body {shown(first)}",
                           known_names("particles and bodies", [*self.declared_particles, *(b.name for b in bodies)]))
            return None
        if isinstance(member, Body) and not member.planar:
            self.issue((*path, "on"), f"friction on the 3-D body {first!r} is not supported: the velocity of a point "
                       "of a 3-D body needs its orientation, which the file does not give",
                       "model the contact point as a particle of the body, or write the problem in a plane")
            return None
        planar = [b.name for b in bodies if b.planar]
        if against is not None and (against == first or against not in [*self.declared_particles, *planar]):
            self.issue((*path, "on"), f"{shown(against)} cannot carry the surface {first!r} slides on",
                       "name a particle or planar body other than " + repr(first) + ": "
                       + (", ".join(n for n in [*self.declared_particles, *planar] if n != first) or "(none)"))
            return None
        for cname in normal:
            c = constraints[cname]
            if not c.on:
                continue
            if c.on[0] != first or len(c.on) > 2:
                self.issue((*path, "normal"), f"constraint {cname!r} acts on {', '.join(c.on)}, but the friction "
                           f"{path[-1]!r} on {first!r}: a normal force acts between the two members of the contact",
                           f"name {first!r} first in both 'on:' lists (and what carries the surface second)")
                return None
            if len(c.on) == 2 and against is None:
                against = c.on[1]
            elif len(c.on) == 2 and c.on[1] != against:
                self.issue((*path, "on"), f"the friction acts between {first!r} and {against!r}, but its normal "
                           f"constraint {cname!r} between {c.on[0]!r} and {c.on[1]!r}",
                           "name the same two members in both")
                return None
        point = self._point(path, spec, member, normal, constraints, positions)
        return None if point is None else (first, against, point)

    def _members(self, path: tuple, spec: dict[str, Any], normal: tuple[str, ...],
                 constraints: dict[str, Constraint], bodies: list[Body]) -> tuple[str, str | None] | None:
        """The names in the friction's ``on:``, else in its first normal constraint's, else the only particle."""
        raw = spec.get("on")
        if raw is None:
            given = next((constraints[c].on for c in normal if constraints[c].on), ())
            if given:
                return given[0], given[1] if len(given) > 1 else None
            if len(self.declared_particles) == 1 and not bodies:
                return self.declared_particles[0], None
            self.issue(path, "say which particle or body slides",
                       "add 'on: NAME' (with what carries the surface second when it moves: on: [block, wedge]), or "
                       "name it in the normal constraint's 'on:'")
            return None
        items = raw if isinstance(raw, list) else [raw]
        if not 1 <= len(items) <= 2 or not all(isinstance(i, str) for i in items):
            self.issue((*path, "on"), f"expected the name of what slides, or [it, what carries the surface], found "
                       f"{', '.join(shown(i) for i in items[:4]) or 'an empty list'}",
                       "write on: block, or on: [block, wedge]")
            return None
        return items[0], items[1] if len(items) > 1 else None

    def _point(self, path: tuple, spec: dict[str, Any], member: Body | Particle, normal: tuple[str, ...],
               constraints: dict[str, Constraint], positions: gateway.Namespace) -> tuple[Any, ...] | None:
        """The contact point: the friction's ``at:``, else its normal constraints', else a particle's position."""
        given = [(c, constraints[c].at) for c in normal if constraints[c].at is not None]
        if "at" in spec:
            point = self.contact_point(path, spec, member, positions)
        elif given:
            point = given[0][1]
        elif isinstance(member, Particle):
            point = member.position
        else:
            self.issue(path, f"friction on the body {member.name!r} needs the point where it acts",
                       f"add 'at: [x, y]' (the contact point in the problem's coordinates; the centre of "
                       f"{member.name!r} is {[str(c) for c in member.position]}) to the friction or to its normal "
                       "constraint")
            return None
        if point is None:
            return None
        for cname, at in given:
            assert at is not None
            if len(at) != len(point) or any(sympy.expand(a - b) != 0 for a, b in zip(at, point, strict=False)):
                self.issue((*path, "at"), f"the friction acts at {[str(c) for c in point]} but its normal constraint "
                           f"{cname!r} at {[str(c) for c in at]}: the normal force and the friction act at one point",
                           "give the same point in both (or 'at:' in one of them only)")
                return None
        return point
