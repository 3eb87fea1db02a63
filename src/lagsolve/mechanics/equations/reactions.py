r"""Physical forces of constraint.

The generalized force of constraint :math:`j` is :math:`\lambda_j a_j`. On the particles
:math:`p` it acts on (``on``), it is the force :math:`\mathbf f` with
:math:`J^T\mathbf f = \lambda_j a_j`, :math:`J = \partial\mathbf r/\partial q` stacked over those
particles. We take the least-norm solution :math:`\mathbf f = \lambda_j\,(J^T)^+ a_j`, which is
:math:`(JJ^T)^{-1}J\lambda_j a_j` (the format's formula) when :math:`JJ^T` is invertible, and check
:math:`J^T\mathbf f = \lambda_j a_j`: when that fails the constraint also acts on something
not named in ``on`` and no force is claimed.

A constraint with a point (``at:``) is a *contact*: it acts at the point :math:`P` of its first member (a
planar body, ``on: disk``, ``at: [X, Y - R]``, or a particle, at its position) against the second member named
in ``on`` (a particle or planar body that carries the surface) or the surroundings. Then :math:`J` is the
velocity Jacobian of :math:`P` relative to the second member (:mod:`lagsolve.mechanics.equations.pair`; for a planar
body
:math:`\mathbf v_P = \dot{\mathbf r}_C + \boldsymbol\omega\times(\mathbf r_P - \mathbf r_C)`, :math:`\omega`
counter-clockwise positive), the first member gets :math:`\mathbf f` and the second :math:`-\mathbf f` at the
same point (Newton's third law): rolling without slipping gives the friction force at the contact. Without a
point (a body, or no particles at all) no physical force is claimed: the generalized forces of constraint
:math:`\lambda_j a_j` are the result (a force for a length, a torque for an angle), and no magnitude mixes the
two.

Every check :math:`J^T\mathbf f = a_j` is made on the constraint surface (the motion never leaves it): a disc
rolling on a cylinder, whose rolling constraint matches its contact point only where the distance constraint
holds, gets its force.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.forces import position_jacobian
from lagsolve.mechanics.equations.lagrange import solve_linear
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.pair import relative_jacobian
from lagsolve.mechanics.symbolic.points import random_point
from lagsolve.mechanics.symbolic.simplify import norm, tidy
from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class ParticleForce:
    """The force of one constraint on one particle is ``multiplier * direction``."""

    particle: str
    direction: tuple[Any, ...]


@dataclass(frozen=True)
class Reaction:
    """How constraint ``name`` pushes: per-particle forces, or a note saying why not.

    With no particles at all, ``particles`` is empty and ``generalized`` is true:
    the force is taken as λ a in the coordinates themselves."""

    name: str
    particles: tuple[ParticleForce, ...]
    generalized: bool
    note: str


def reaction(problem: Problem, model: Model, terms: ConstraintTerms, zero: Callable[[Any], bool]) -> Reaction:
    """Direction and size of the force of one constraint, per unit multiplier. ``zero`` tells whether an
    expression vanishes on the constraint surface (:meth:`lagsolve.mechanics.equations.surface.Surface.is_zero`): a
    force
    is claimed where its generalized forces equal λ·a there, which is all the motion sees."""
    a = sympy.Matrix(terms.coefficients)
    spec = next((c for c in problem.constraints if c.name == terms.name), None)
    if spec is not None and spec.at is not None:
        return _at_point(problem, model, terms, spec.on, spec.at, zero)
    if not problem.particles:
        return Reaction(terms.name, (), True, GENERALIZED)
    if not terms.on:
        return Reaction(terms.name, (), False,
                        "the problem has several particles and the constraint does not say which one it "
                        "acts on; name it with 'on:' to get the physical force")
    blocks = [position_jacobian(problem.particle(p).position, model) for p in terms.on]
    if len(blocks) == 2 and internal(blocks[0], blocks[1], a, model):
        # it depends on the two only through where one is relative to the other: an interaction between them,
        # so the second gets the opposite of the first's force (a block on a wedge that cannot move vertically
        # still gets the face's vertical push, which the floor takes)
        first, second = terms.on
        return _at_point(problem, model, terms, terms.on, problem.particle(first).position, zero,
                         f"it depends on {first} and {second} only through where one is relative to the other: the "
                         f"force on {first}, and the opposite force on {second}")
    J = sympy.Matrix.vstack(*blocks)
    direction = _least_norm(J, a)
    if direction is None or not all(zero(e) for e in (J.T * direction - a)):
        named = ", ".join(terms.on)
        return Reaction(terms.name, (), False,
                        f"this constraint also acts elsewhere: λ·a is not the generalized force of any force on "
                        f"{named} alone, so no physical force is claimed; list every particle it acts on in 'on:'")
    forces = []
    row = 0
    for p, block in zip(terms.on, blocks, strict=True):
        part = direction[row:row + block.rows, 0]
        row += block.rows
        forces.append(ParticleForce(p, tuple(tidy(c) for c in part)))
    return Reaction(terms.name, tuple(forces), False, "")


#: the note of a constraint whose physical force is not known: its generalized forces are given instead
GENERALIZED = ("generalized forces of constraint λ·a, one per coordinate (a force for a length, a torque for an "
               "angle), so no magnitude is given; for the physical force name the body and the point where the "
               "constraint acts with 'on:' and 'at:'")


def internal(first: sympy.Matrix, second: sympy.Matrix, a: sympy.Matrix, model: Model, states: int = 3) -> bool:
    r"""Whether a constraint on two particles (position Jacobians ``first``, ``second``; coefficients ``a``)
    depends on them only through their relative position: some motion of the coordinates moves both alike, and
    every such motion :math:`\delta q` (:math:`J_1\delta q = J_2\delta q`) leaves it unchanged,
    :math:`a\cdot\delta q = 0`. Tested numerically at random states; False where the expressions cannot be
    evaluated (declared functions). A string through a hole (no common motion) or over a pulley (a common
    motion lengthens it) is not internal; a rod, or a face of one body another slides on, is."""
    symbols = sorted((first.free_symbols | second.free_symbols | a.free_symbols) - set(model.velocities),
                     key=sympy.default_sort_key)
    if any(m.has(sympy.core.function.AppliedUndef, sympy.Derivative) for m in (first, second, a)):
        return False
    rng = np.random.default_rng(3)
    compiled = sympy.lambdify(symbols, [(first - second).tolist(), first.tolist(), a.tolist()], modules="math")
    for _ in range(states):
        point = random_point(symbols, rng)
        try:
            with np.errstate(all="raise"):
                difference, moved, coefficients = (np.array(m, dtype=float) for m in compiled(*point))
        except (ArithmeticError, FloatingPointError, TypeError, ValueError):
            return False
        _, singular, vt = np.linalg.svd(difference)
        rank = int(np.sum(singular > 1e-9 * max(1.0, float(singular.max(initial=0.0)))))
        common = vt[rank:]  # the motions that move both alike
        scale = max(1.0, float(np.abs(coefficients).max()))
        if not common.size or np.abs(moved @ common.T).max(initial=0.0) < 1e-9:
            return False  # no motion moves them together
        if np.abs(common @ coefficients.ravel()).max() > 1e-9 * scale:
            return False
    return True


def _at_point(problem: Problem, model: Model, terms: ConstraintTerms, on: tuple[str, ...],
              point: tuple[Any, ...], zero: Callable[[Any], bool], note: str = "") -> Reaction:
    """The force of a constraint acting at ``point`` of ``on[0]`` (a contact): J_relᵀ f = a with J_rel the
    velocity Jacobian of the point relative to what carries the surface (:mod:`lagsolve.mechanics.equations.pair`; least
    norm: the components the constraint does not fix are zero). With a second name (a particle or planar body the
    first presses on, a surface that moves) that member gets the opposite force at the same point."""
    first, second = on[0], (on[1] if len(on) > 1 else None)
    J = relative_jacobian(problem, model, first, second, point)
    a = sympy.Matrix(terms.coefficients)
    direction = _least_norm(J, a)
    where = " and ".join(repr(n) for n in on)
    if direction is None or not all(zero(e) for e in (J.T * direction - a)):
        return Reaction(terms.name, (), False,
                        f"λ·a is not the generalized force of a force at the point {[str(c) for c in point]} of "
                        f"{where}, so no physical force is claimed; check 'at:' (and that a body's "
                        "angular velocity is counter-clockwise positive)")
    force = tuple(tidy(c) for c in direction)
    if second is None:
        return Reaction(terms.name, (ParticleForce(first, force),), False,
                        f"the force on {first} at the point given under 'at:'"
                        if any(b.name == first for b in problem.bodies) else "")
    note = note or f"the force on {first} at the contact, and the opposite force on {second} at the same point"
    return Reaction(terms.name, (ParticleForce(first, force), ParticleForce(second, tuple(-c for c in force))), False,
                    note)


def _least_norm(J: sympy.Matrix, a: sympy.Matrix) -> sympy.Matrix | None:
    """The least-norm solution of J^T f = a, or None when it cannot be formed.

    Uses whichever Gram matrix is the smaller square (J^T J, the metric of the
    coordinates, when J has at least as many rows as columns), simplified first,
    and a linear solve rather than an inverse.
    """
    rows, cols = J.shape
    grams = [("metric", J.T * J), ("rows", J * J.T)] if rows >= cols else [("rows", J * J.T), ("metric", J.T * J)]
    for kind, gram in grams:
        gram = gram.applyfunc(tidy)
        rhs = a if kind == "metric" else J * a
        try:
            y = sympy.Matrix(solve_linear(gram, sympy.Matrix(rhs)))
        except ValueError:
            continue
        return (J * y if kind == "metric" else y).applyfunc(sympy.cancel)
    try:
        return (J.T.pinv() * a).applyfunc(sympy.cancel)
    except (ValueError, ZeroDivisionError, NotImplementedError):
        return None


def force_direction(react: Reaction) -> tuple[Any, ...]:
    """The force of the constraint on its first particle (or named point) per unit λ, by component; empty where
    no physical force is known."""
    return tuple(react.particles[0].direction) if react.particles else ()


def force_scale(react: Reaction) -> Any:
    """|force of the constraint| / |λ|: the length of its direction on its first particle (or named point),
    NaN where no physical force is known (no particle, no point of a body named): no magnitude is claimed."""
    if react.particles:
        return norm(list(react.particles[0].direction))
    return sympy.nan
