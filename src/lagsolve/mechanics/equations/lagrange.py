r"""Lagrange's equations with multipliers, in matrix form.

For each coordinate :math:`q_i`

.. math::
    \frac{d}{dt}\frac{\partial L}{\partial\dot q_i} - \frac{\partial L}{\partial q_i}
    = Q_i + \sum_j \lambda_j a_{ji},

which, with :math:`M_{ik} = \partial^2 L/\partial\dot q_i\partial\dot q_k`, reads
:math:`M\ddot q = F + A^T\lambda`, where
:math:`F_i = \partial L/\partial q_i + Q_i - \sum_k (\partial p_i/\partial q_k)\dot q_k - \partial p_i/\partial t`.
With the constraints at acceleration level, :math:`A\ddot q = \beta`, the augmented system

.. math::
    \begin{pmatrix} M & -A^T \\ A & 0\end{pmatrix}
    \begin{pmatrix}\ddot q\\ \lambda\end{pmatrix} = \begin{pmatrix}F\\ \beta\end{pmatrix}

gives the accelerations and the multipliers.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.symbolic.algebra import small
from lagsolve.mechanics.symbolic.linsolve import solve_linear as linear_solve
from lagsolve.mechanics.symbolic.linsolve import solve_structured
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM, engine_converter, engine_sum, to_engine


@dataclass(frozen=True)
class LagrangeTerms:
    """The pieces of each coordinate's equation, as a worked solution shows them.

    Tuples run over coordinates in input order: ``momenta`` :math:`\\partial L/\\partial\\dot q_i`,
    ``momenta_rates`` their total time derivatives, ``gradients`` :math:`\\partial L/\\partial q_i`,
    ``generalized_forces`` :math:`Q_i`, ``constraint_forces`` :math:`\\sum_j\\lambda_j a_{ji}`.
    ``equations`` are left minus right sides (zero along the motion).
    """

    momenta: tuple[Any, ...]
    momenta_rates: tuple[Any, ...]
    gradients: tuple[Any, ...]
    generalized_forces: tuple[Any, ...]
    constraint_forces: tuple[Any, ...]
    equations: tuple[Any, ...]
    mass_matrix: sympy.ImmutableMatrix
    forcing: sympy.ImmutableMatrix
    constraint_jacobian: sympy.ImmutableMatrix
    constraint_rhs: sympy.ImmutableMatrix


def lagrange_terms(model: Model, constraints: tuple[ConstraintTerms, ...],
                   generalized_forces: tuple[Any, ...], *, engine: str = "sympy") -> LagrangeTerms:
    r"""Build each Lagrange equation and the matrix form :math:`M\ddot q = F + A^T\lambda`.

    ``engine="symengine"`` takes the derivatives with SymEngine (tens of times faster on a large
    Lagrangian) and converts them back; the results are the same expressions up to SymPy's
    automatic ordering (the reports show them tidied, which writes both alike). Where SymEngine is
    missing or cannot express the Lagrangian (declared functions), or the Lagrangian is small (fewer than
    ``algebra.ENGINE_FROM`` nodes: loading SymEngine would cost more than it saves), SymPy is used.
    Remembered: the minimal coordinates and the numeric equilibria ask for those of the same model again.
    """
    return _lagrange_terms(model, tuple(constraints), tuple(generalized_forces), engine)


@functools.lru_cache(maxsize=16)
def _lagrange_terms(model: Model, constraints: tuple[ConstraintTerms, ...], generalized_forces: tuple[Any, ...],
                    engine: str) -> LagrangeTerms:
    q, qd, qdd = model.coordinates, model.velocities, model.accelerations
    parts = _symengine_parts(model) if engine == "symengine" and not small(model.lagrangian) else None
    if parts is None:
        L = model.lagrangian
        momenta = tuple(sympy.diff(L, v) for v in qd)
        rates = tuple(model.time_derivative(p, second_order=True) for p in momenta)
        gradients = tuple(sympy.diff(L, c) for c in q)
        M = sympy.Matrix([[sympy.diff(p, v) for v in qd] for p in momenta])
        zero_acc = {a: 0 for a in qdd}
        drift = [r.xreplace(zero_acc) for r in rates]
    else:
        momenta, rates, gradients, M, drift = parts
    C = tuple(sum((c.multiplier * c.coefficients[i] for c in constraints), sympy.Integer(0))
              for i in range(len(q)))
    if len(q) > BULK_SYSTEM:  # added by SymEngine, whose forms of the pieces are kept (engine_sum)
        equations = tuple(engine_sum(((1, rates[i]), (-1, gradients[i]), (-1, generalized_forces[i]), (-1, C[i])))
                          for i in range(len(q)))
        F = sympy.Matrix([engine_sum(((1, gradients[i]), (1, generalized_forces[i]), (-1, drift[i])))
                          for i in range(len(q))])
    else:
        equations = tuple(rates[i] - gradients[i] - generalized_forces[i] - C[i] for i in range(len(q)))
        F = sympy.Matrix([gradients[i] + generalized_forces[i] - drift[i] for i in range(len(q))])
    A = sympy.Matrix(len(constraints), len(q), lambda j, i: constraints[j].coefficients[i])
    beta = sympy.Matrix([c.acceleration_rhs for c in constraints])
    return LagrangeTerms(momenta, rates, gradients, tuple(generalized_forces), C, equations,
                         sympy.ImmutableMatrix(M), sympy.ImmutableMatrix(F),
                         sympy.ImmutableMatrix(A), sympy.ImmutableMatrix(beta))


@functools.lru_cache(maxsize=64)
def _symengine_parts(model: Model) -> tuple[Any, ...] | None:
    """Momenta, their rates, gradients, M and the velocity part of the rates, differentiated with SymEngine
    and converted back to SymPy (with the model's own symbols); None where SymEngine cannot be used.
    Remembered: the minimal coordinates and the equilibria ask for those of the same model."""
    L = model.lagrangian
    if L.atoms(sympy.core.function.AppliedUndef) or L.has(sympy.Derivative):
        return None
    try:
        import symengine
        from symengine.lib.symengine_wrapper import sympy2symengine
    except ImportError:
        return None
    try:
        t, q, qd = (sympy2symengine(model.time), [sympy2symengine(x) for x in model.coordinates],
                    [sympy2symengine(x) for x in model.velocities])
        bulk = len(q) > BULK_SYSTEM
        lagrangian = to_engine(L)
        momenta = [lagrangian.diff(v) for v in qd]
        mass = [[p.diff(v) for v in qd] for p in momenta]
        drift = [p.diff(t) + sum((p.diff(c) * v for c, v in zip(q, qd, strict=True)), symengine.Integer(0))
                 for p in momenta]
        gradients = [lagrangian.diff(c) for c in q]
        own = {s.name: s for s in L.free_symbols | {model.time, *model.coordinates, *model.velocities,
                                                    *model.accelerations}}
        convert = engine_converter(own, remember=bulk)

        def back(expr: Any) -> Any:
            # a bulk system's pieces multiplied out first: a sum of plain products is built in SymPy without its
            # flattening (partials._canonical_mul), where the products of sums the derivatives give are not
            value = convert(expr.expand() if bulk else expr)
            if value is None:  # an unevaluated derivative (of an Abs, say): SymPy differentiates the whole L
                raise KeyError("not expressible")
            return value

        momenta_back = tuple(back(p) for p in momenta)
        mass_back = sympy.Matrix([[back(e) for e in row] for row in mass])
        drift_back = [back(d) for d in drift]
        if bulk:  # the n² products of the rates summed by SymEngine, converted once
            accelerations = [sympy2symengine(a) for a in model.accelerations]
            rates = tuple(back(d + sum((row[k] * a for k, a in enumerate(accelerations)), symengine.Integer(0)))
                          for d, row in zip(drift, mass, strict=True))
        else:
            rates = tuple(d + sum((mass_back[i, k] * a for k, a in enumerate(model.accelerations)), sympy.Integer(0))
                          for i, d in enumerate(drift_back))
        return (momenta_back, rates, tuple(back(g) for g in gradients), sympy.ImmutableMatrix(mass_back),
                tuple(drift_back))
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return None


def solve_augmented(terms: LagrangeTerms, limit: int | None = None) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """Solve the augmented system for (accelerations, multipliers), unsimplified, by its structure
    (:func:`~lagsolve.mechanics.symbolic.linsolve.solve_structured`; ``limit`` bounds the size of the result).

    Raises
    ------
    DerivationError
        When the system is singular (a coordinate without inertia that no
        constraint fixes, or redundant constraints).
    """
    try:
        acc, lam = solve_structured(terms.mass_matrix, terms.forcing, terms.constraint_jacobian,
                                    terms.constraint_rhs, limit)
    except (ValueError, ZeroDivisionError) as exc:
        raise DerivationError(
            "the augmented system [[M, -A^T], [A, 0]] is singular, so the accelerations and multipliers "
            "are not determined: a coordinate has no inertia and no constraint fixes it, or two "
            f"constraints are redundant ({exc})"
        ) from None
    return tuple(acc), tuple(lam)


def solve_linear(system: sympy.Matrix, rhs: sympy.Matrix) -> list[Any]:
    """Solve a square symbolic system with one right-hand side
    (:func:`~lagsolve.mechanics.symbolic.linsolve.solve_linear`).

    Raises ``ValueError`` when no non-zero pivot is found (a singular system).
    """
    return list(linear_solve(sympy.Matrix(system), sympy.Matrix(rhs)))
