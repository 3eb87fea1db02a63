"""The forces a sketch draws as arrows: each force of constraint and each friction force, at its point.

Part of the sketch's geometry (:mod:`lagsolve.mechanics.geometry.shapes`), read from the matrix form, which already
holds the physical forces (``mechanics/equations/reactions.py``, ``mechanics/equations/friction.py``):

* a constraint's force on each member it acts on is :math:`\\lambda_j\\,\\mathbf u_{j,p}` (``Reaction``): on a
  particle at its position, on a body at the constraint's point (``at:``); the second member of a contact, or
  of a pair that the constraint joins only through their relative position (a block on a wedge), gets the
  opposite force at the first one's point, where they touch;
* a friction contact's force on the member that slides is the run's friction value along the unit tangent
  :math:`\\mathbf t` where it slides along one line, else the kinetic magnitude against the sliding velocity;
  the member that carries the surface gets the opposite force at the same point.

A constraint with no known physical force (no particle or point named) gets no arrow: its generalized forces are
no arrows in space.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.geometry.records import Arrow

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.matrix_form import MatrixForm


def _position(problem: Any, name: str) -> tuple[Any, ...]:
    for member in (*problem.particles, *problem.bodies):
        if member.name == name:
            return tuple(member.position)
    raise KeyError(name)


def _along_the_line(problem: Any, forces: Any) -> bool:
    """Whether the force of a pair lies along the line joining them (a rod), not across it (a face)."""
    first, second = (_position(problem, f.particle) for f in forces)
    if len(first) != len(second):
        return False
    d = [a - b for a, b in zip(first, second, strict=True)]
    f = forces[0].direction
    pairs = [(0, 1)] if len(d) == 2 else [(0, 1), (0, 2), (1, 2)]
    return all(sympy.simplify(f[i] * d[j] - f[j] * d[i]) == 0 for i, j in pairs)


def arrows(form: MatrixForm) -> tuple[Arrow, ...]:
    """An arrow per member for each force of constraint and each friction force the form knows."""
    problem = form.problem
    given = {c.name: c for c in problem.constraints}
    out: list[Arrow] = []
    for j, terms in enumerate(form.constraints):
        react = form.reactions.get(terms.name)
        if react is None or not react.particles:
            continue
        spec = given.get(terms.name)
        forces = react.particles
        pair = len(forces) == 2 and all(sympy.expand(a + b) == 0 for a, b in
                                        zip(forces[0].direction, forces[1].direction, strict=False))
        if pair and spec is not None and spec.at is None and _along_the_line(problem, forces):
            pair = False  # a rod or link: each end is pushed or pulled where it is
        for push in forces:
            if spec is not None and spec.at is not None:
                point = tuple(spec.at)
            elif pair:
                point = _position(problem, forces[0].particle)  # where the two touch: the first one's place
            else:
                point = _position(problem, push.particle)
            out.append(Arrow(terms.name, "constraint", j, push.particle, point, tuple(push.direction)))
    for c, term in enumerate(form.frictions):
        point = tuple(term.point) if term.point else _position(problem, term.particle)
        planar = term.tangent is None
        direction = tuple(term.sliding_velocity) if planar else tuple(term.tangent or ())
        out.append(Arrow(term.name, "friction", c, term.particle, point, direction, 1, planar))
        if term.against is not None:
            out.append(Arrow(term.name, "friction", c, term.against, point, direction, -1, planar))
    return tuple(out)
