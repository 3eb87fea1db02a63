r"""Is a velocity constraint really nonholonomic? Exactness, integrating factors, Frobenius.

A velocity constraint :math:`\sum_i a_i(q, t)\,\dot q_i + b(q, t) = 0` is the Pfaffian form

.. math:: \omega = \sum_i a_i\,dq_i + b\,dt = 0

in the variables :math:`x = (q_1, \dots, q_n, t)`. It is **integrable** (holonomic in
disguise) when some factor :math:`\mu` makes :math:`\mu\omega = d\psi` exact, i.e.
:math:`\partial(\mu\omega_k)/\partial x_l = \partial(\mu\omega_l)/\partial x_k` for all
pairs; then every motion keeps :math:`\psi(q, t) = \psi(q(0), 0)`, a holonomic constraint
with a new constant. By Frobenius' theorem a factor exists (locally) exactly when

.. math:: (\omega\wedge d\omega)_{klm} = \omega_k(\partial_l\omega_m - \partial_m\omega_l)
          + \omega_l(\partial_m\omega_k - \partial_k\omega_m) + \omega_m(\partial_k\omega_l - \partial_l\omega_k)

vanishes for every triple :math:`k < l < m`; a non-zero component proves the constraint
**nonholonomic** (the knife edge: :math:`(\omega\wedge d\omega)_{x y \theta} = -1`).
Each constraint is classified alone (a set of constraints could be jointly integrable
without each being so; that case is reported as nonholonomic per constraint).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from typing import Any

import sympy

from lagsolve.enums import TextEnum
from lagsolve.mechanics.equations.constraints import ConstraintTerms, constraint_terms
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.symbolic.identities import Zero, proved_zero, zero_status
from lagsolve.mechanics.symbolic.simplify import tidy, tidy_sum
from lagsolve.problem.schema import Constraint, ConstraintKind

#: integrands above this many operations are not handed to ``sympy.integrate``
INTEGRATE_LIMIT = 40

class Integrability(TextEnum):
    """What a constraint turned out to be (:class:`Classification` ``kind``)."""

    HOLONOMIC = "holonomic"
    INTEGRABLE = "integrable"
    NONHOLONOMIC = "nonholonomic"
    UNRESOLVED = "unresolved"


HOLONOMIC, INTEGRABLE = Integrability.HOLONOMIC, Integrability.INTEGRABLE
NONHOLONOMIC, UNRESOLVED = Integrability.NONHOLONOMIC, Integrability.UNRESOLVED


@dataclass(frozen=True)
class Classification:
    r"""What one constraint turned out to be.

    ``kind`` is ``"holonomic"`` (given as such), ``"integrable"`` (a velocity constraint
    with :math:`\mu\omega = d\psi`), ``"nonholonomic"`` (Frobenius fails: ``witness`` is a
    non-zero component :math:`((x_k, x_l, x_m), value)` of :math:`\omega\wedge d\omega`) or
    ``"unresolved"`` (integrable by Frobenius or undecided, but no simple factor found).
    For integrable ones ``factor`` is :math:`\mu`, ``integral`` is :math:`\psi`, ``constant``
    the new symbol :math:`C` and ``holonomic`` the constraint :math:`\psi - C = 0` as
    :class:`ConstraintTerms`; ``solved`` is ``(q, value)`` when it fixes a coordinate
    (:math:`\theta = \theta_0`, :math:`\phi = \Omega t + \phi_0`).
    """

    name: str
    kind: Integrability
    form: tuple[Any, ...] = ()
    variables: tuple[Any, ...] = ()
    exact: bool = False
    factor: Any = None
    integral: Any = None
    constant: Any = None
    holonomic: ConstraintTerms | None = None
    solved: tuple[Any, Any] | None = None
    witness: tuple[tuple[Any, ...], Any] | None = None
    note: str = ""


def classify(terms: ConstraintTerms, model: Model, constraint: Constraint,
             taken_names: set[str]) -> Classification:
    """Classify one constraint (see the module docstring); ``taken_names`` are names in use,
    so that a new constant never shadows one (it is extended with the constant's name)."""
    if terms.kind == ConstraintKind.HOLONOMIC:
        return Classification(terms.name, HOLONOMIC)
    variables = (*model.coordinates, model.time)
    form = (*terms.coefficients, terms.offset)
    if _is_exact(form, variables):
        return _integrated(terms, model, constraint, variables, form, sympy.Integer(1), taken_names, exact=True)
    witness, undecided = _frobenius(form, variables)
    if witness is not None:
        return Classification(terms.name, NONHOLONOMIC, form, variables, witness=witness)
    for factor in _factor_candidates(form):
        scaled = tuple(sympy.cancel(factor * w) for w in form)
        if _is_exact(scaled, variables):
            return _integrated(terms, model, constraint, variables, form, factor, taken_names, exact=False)
    note = ("ω∧dω vanishes only numerically here" if undecided else
            "ω∧dω = 0, so an integrating factor exists, but none of the simple ones works")
    return Classification(terms.name, UNRESOLVED, form, variables, note=note + "; kept as a velocity constraint")


def _is_exact(form: tuple[Any, ...], variables: tuple[Any, ...]) -> bool:
    for i, j in combinations(range(len(variables)), 2):
        if not proved_zero(sympy.diff(form[i], variables[j]) - sympy.diff(form[j], variables[i])):
            return False
    return True


def _frobenius(form: tuple[Any, ...], variables: tuple[Any, ...]) -> tuple[tuple[tuple[Any, ...], Any] | None, bool]:
    """The first non-zero component of ω∧dω (or None), and whether some component was undecided."""
    n = len(variables)
    d = [[sympy.diff(form[a], variables[b]) for b in range(n)] for a in range(n)]  # d[a][b] = ∂ω_a/∂x_b
    undecided = False
    for i, j, k in combinations(range(n), 3):
        component = (form[i] * (d[k][j] - d[j][k]) + form[j] * (d[i][k] - d[k][i])
                     + form[k] * (d[j][i] - d[i][j]))
        status = zero_status(component)
        if status is Zero.NONZERO:
            return ((variables[i], variables[j], variables[k]), tidy(component)), undecided
        undecided |= status is Zero.UNDECIDED
    return None, undecided


def _factor_candidates(form: tuple[Any, ...]) -> list[Any]:
    """Simple integrating factors: 1/a_k, and 1/f, 1/f² for each factor f of a coefficient."""
    out: list[Any] = []
    factors: list[Any] = []
    for w in form:
        if w == 0:
            continue
        out.append(1 / w)
        numerator, denominator = sympy.fraction(sympy.factor(w))
        for part, power in ((numerator, -1), (denominator, 1)):
            for base in sympy.Mul.make_args(part):
                base = base.as_base_exp()[0]
                if base.free_symbols and base not in factors:
                    factors.append(base)
                    out.append(base**power)
    out += [1 / (f * g) for i, f in enumerate(factors) for g in factors[i:]]
    unique: list[Any] = []
    for c in out:
        if c not in unique:
            unique.append(c)
    return unique


def _integrate(form: tuple[Any, ...], variables: tuple[Any, ...]) -> Any | None:
    r""":math:`\psi` with :math:`d\psi = \sum_k \omega_k dx_k`, one variable at a time, or None."""
    psi = sympy.Integer(0)
    for k, x in enumerate(variables):
        rest = tidy(form[k] - sympy.diff(psi, x))
        if rest == 0:
            continue
        if sympy.count_ops(rest) > INTEGRATE_LIMIT:
            return None
        part = sympy.integrate(rest, x)
        if part.has(sympy.Integral):
            return None
        psi += part
    return tidy_sum(psi)


def _integrated(terms: ConstraintTerms, model: Model, constraint: Constraint, variables: tuple[Any, ...],
                form: tuple[Any, ...], factor: Any, taken_names: set[str], *, exact: bool) -> Classification:
    scaled = tuple(sympy.cancel(factor * w) for w in form)
    psi = _integrate(scaled, variables)
    if psi is None:
        return Classification(terms.name, UNRESOLVED, form, variables, exact, factor,
                              note="the form is exact but its integral has no closed form here; "
                                   "kept as a velocity constraint")
    solved_for = None
    for q in reversed(model.coordinates):
        coefficient = sympy.diff(psi, q)
        if sympy.diff(psi, q, 2) == 0 and coefficient != 0 and not (coefficient.free_symbols & set(variables)) \
                and not coefficient.atoms(sympy.core.function.AppliedUndef):
            psi, solved_for = sympy.expand(psi / coefficient), q
            break
    if solved_for is not None:
        name = _fresh(f"{solved_for.name}0", taken_names)
        constant = (sympy.Symbol(name, positive=True) if solved_for.is_positive
                    else sympy.Symbol(name, real=True))
    else:
        constant = sympy.Symbol(_fresh(f"C_{terms.name}", taken_names), real=True)
    taken_names.add(constant.name)
    holonomic = constraint_terms(Constraint(terms.name, ConstraintKind.HOLONOMIC, psi - constant, terms.on,
                                            constraint.line), model)
    solved = None
    if solved_for is not None:
        solved = (solved_for, sympy.expand(solved_for - (psi - constant)))
    return Classification(terms.name, INTEGRABLE, form, variables, exact, factor, psi, constant, holonomic, solved)


def _fresh(name: str, taken: set[str]) -> str:
    candidate, k = name, 1
    while candidate in taken:
        candidate = f"{name}_{k}"
        k += 1
    return candidate


def classify_all(constraints: tuple[ConstraintTerms, ...], model: Model, given: tuple[Constraint, ...],
                 taken_names: set[str]) -> tuple[Classification, ...]:
    """:func:`classify` for every constraint, in input order."""
    return tuple(classify(t, model, c, taken_names) for t, c in zip(constraints, given, strict=True))
