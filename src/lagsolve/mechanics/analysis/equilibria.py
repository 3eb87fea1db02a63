r"""Routh reduction to one degree of freedom: effective potential, equilibria, small oscillations.

When every independent coordinate but one, :math:`q`, is cyclic with momentum
:math:`p_c` (a symbol ``p_<c>``), solving :math:`p_c = \partial L/\partial\dot q_c` for the
cyclic velocities gives the Routhian Lagrangian

.. math::
    L_R(q, \dot q) = \Big(L - \sum_c p_c\dot q_c\Big)\Big|_{\dot q_c(q, \dot q, p)}
    = \tfrac12 m_{eff}(q)\,\dot q^2 + g_1(q)\,\dot q - V_{eff}(q),

whose equation is :math:`m_{eff}\ddot q + \tfrac12 m_{eff}'\dot q^2 = -V_{eff}'(q)` (the
:math:`g_1` terms cancel). With T quadratic, :math:`L = \tfrac12 v^TAv + (b + C\dot q)^Tv + \dots`
in the cyclic velocities v, these are computed from small pieces:
:math:`v = A^{-1}(p - b - C\dot q)`, :math:`m_{eff} = \partial^2L/\partial\dot q^2 - C^TA^{-1}C` and
:math:`V_{eff} = -L|_{\dot q = v = 0} + \tfrac12(p - b)^TA^{-1}(p - b)` (so that
:math:`(p_\phi - p_\psi\cos\theta)^2/(2I_1\sin^2\theta)` of the heavy top appears as such).
Additive constants are dropped from :math:`V_{eff}`. With no cyclic
coordinate at all, :math:`V_{eff}` is the potential of the one remaining coordinate (with
the centrifugal part of a moving constraint). Equilibria solve :math:`V_{eff}'(q_0) = 0`;
one is stable when :math:`V_{eff}''(q_0) > 0`, and small oscillations about it have

.. math:: \omega^2 = V_{eff}''(q_0)/m_{eff}(q_0).

Notes
-----
* Needs a reduced system (no constraint left), no explicit t in L, no friction, and no
  generalized force on :math:`q` at rest (damping is allowed; ω is then the undamped frequency).
* :math:`V_{eff}' = 0` is solved in closed form only when it factors into pieces that are
  polynomials of degree ≤ 2 in one of :math:`q, \sin q, \cos q, \tan q` (or :math:`a q^k + b`);
  otherwise the equilibrium is given as a condition and ω in terms of :math:`q_0`, with
  the momentum eliminated through that condition.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.analysis.conserved import Conservation, MotionSystem
from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.signs import relation, sign_core
from lagsolve.mechanics.symbolic.simplify import tidy, tidy_sum
from lagsolve.problem.names import momentum_symbol

#: factors of V_eff' larger than this are not handed to ``sympy.solve``
SOLVE_LIMIT = 40
#: at most this many equilibria are listed
MAX_EQUILIBRIA = 8
#: V_eff larger than this (operations) is not offered to ``tidy`` as one fraction
COMPACT_LIMIT = 40
#: the raw expanded V_eff is grouped over denominators only up to this size
GROUP_LIMIT = 200


@dataclass(frozen=True)
class Equilibrium:
    r"""One equilibrium :math:`q_0` of the effective potential.

    ``value`` is :math:`q_0` in closed form, or None when only ``condition`` (an ``Eq``)
    is known; ``exists_if`` a relation the parameters must satisfy for it to be real;
    ``curvature`` :math:`V_{eff}''(q_0)`; ``stable`` True/False, or None with
    ``stability_condition``; ``frequency`` :math:`\omega` (None when unstable), in terms of
    ``value`` or, without one, of :math:`q` standing for :math:`q_0`; ``frequency_squared_at``
    :math:`\omega^2` written with :math:`q` for :math:`q_0` and the momenta eliminated, and
    ``curvature_at`` :math:`V_{eff}''` in the same form; ``frequency_squared`` is
    :math:`\omega^2` itself (None when unstable).
    """

    value: Any
    condition: Any
    exists_if: Any = None
    curvature: Any = None
    stable: bool | None = None
    stability_condition: Any = None
    frequency: Any = None
    frequency_squared_at: Any = None
    curvature_at: Any = None
    frequency_squared: Any = None


@dataclass(frozen=True)
class EffectivePotential:
    """The one-degree-of-freedom reduction (module docstring).

    ``cyclic`` lists ``(q_c, p_c, q̇_c in terms of p_c)``; ``routhian`` is :math:`L_R` (up to a
    constant, as :math:`\tfrac12 m_{eff}\\dot q^2 + g_1\\dot q - V_{eff}`),
    ``mass`` :math:`m_{eff}(q)`, ``expression`` :math:`V_{eff}(q)`, ``equation`` the pair
    (left side, right side) of the reduced equation; ``damped`` says a velocity-dependent
    force acts on q.
    """

    coordinate: Any
    cyclic: tuple[tuple[Any, Any, Any], ...]
    routhian: Any
    mass: Any
    expression: Any
    equation: tuple[Any, Any]
    equilibria: tuple[Equilibrium, ...]
    damped: bool = False
    note: str = ""


def effective_potential(system: MotionSystem, conservation: Conservation,
                        friction: bool) -> tuple[EffectivePotential | None, str]:
    """The reduction of ``system`` to its one non-cyclic coordinate, or None and the reason."""
    model = system.model
    cyclic = [q for q in conservation.cyclic if any(c.coordinate == q for c in conservation.quantities)]
    rest = [i for i, q in enumerate(model.coordinates) if q not in cyclic]
    why_not = _why_not_reducible(system, rest, friction)
    if why_not:
        return None, why_not
    L = model.lagrangian
    k = rest[0]
    q, qd, qdd = model.coordinates[k], model.velocities[k], model.accelerations[k]
    force = system.generalized_forces[k]
    indices = [model.coordinates.index(c) for c in cyclic]
    velocities = [model.velocities[i] for i in indices]
    momenta = [momentum_symbol(c) for c in cyclic]
    part = _cyclic_part(L, velocities, momenta, qd, model.velocities)
    if part is None:
        return None, "the cyclic velocities cannot be solved from their momenta"
    at_zero = {v: 0 for v in model.velocities}
    at_rest = {v: tidy(e) for v, e in zip(velocities, part.inverse * (part.P - part.b), strict=True)}
    solution = {v: _display(e) for v, e in zip(velocities, part.inverse * (part.P - part.b - part.C * qd),
                                                 strict=True)}
    # Routh: L_R = 1/2 m_eff qd^2 + g1 qd - V_eff, with (module docstring)
    mass = _effective_mass(L, qd, part)
    if mass == 0:
        return None, f"{q.name} has no inertia once the cyclic motion is removed"
    gyroscopic = _display(sympy.diff(L, qd).xreplace({**at_zero, **at_rest}).xreplace({qd: 0}))
    potential = _drop_constants(_raw_potential(L, at_zero, part), q)
    lhs = mass * qdd + sympy.diff(mass, q) * qd**2 / 2
    rhs = -sympy.diff(potential, q)
    if not _routh_form_holds(system, qdd, solution, (lhs, rhs, force)):
        return None, "the Routh form could not be verified against the reduced equation"
    routhian = mass * qd**2 / 2 + gyroscopic * qd - potential
    equilibria = tuple(_equilibria(potential, mass, q, momenta))
    return EffectivePotential(q, tuple(zip(cyclic, momenta, (solution[v] for v in velocities), strict=True)),
                              routhian, mass, potential, (tidy_sum(lhs), _display(rhs)), equilibria,
                              damped=not proved_zero(force)), ""


def _why_not_reducible(system: MotionSystem, rest: list[int], friction: bool) -> str:
    """Why ``system`` has no effective potential in the one coordinate ``rest`` leaves (its index), or ``""``:
    it needs minimal coordinates, one coordinate besides the cyclic ones, no friction, no time in L, no
    generalized force on the coordinate at rest, and T quadratic in the velocities."""
    model = system.model
    if system.kind != "reduced":
        return "needs minimal coordinates (no constraint left)"
    if len(rest) != 1:
        return f"{len(rest)} coordinates are left after removing the cyclic ones (one is needed)"
    if friction:
        return "Coulomb friction acts: equilibria are not isolated points"
    L = model.lagrangian
    if not proved_zero(sympy.diff(L, model.time)):
        return "L depends explicitly on the time"
    k = rest[0]
    if not proved_zero(system.generalized_forces[k].xreplace({v: 0 for v in model.velocities})):
        return f"a generalized force acts on {model.coordinates[k].name} at rest, so it has no potential"
    if any(sympy.diff(L, v, 3) != 0 for v in model.velocities):
        return "T is not quadratic in the velocities"
    return ""


@dataclass(frozen=True)
class _CyclicPart:
    """L = 1/2 v^T A v + (b + C qd)^T v + (terms without v), v the cyclic velocities: :math:`A^{-1}`, b, C, and
    the momenta P of the cyclic coordinates."""

    velocities: list[Any]
    inverse: Any
    b: Any
    C: Any
    P: Any


def _cyclic_part(L: Any, velocities: list[Any], momenta: list[Any], qd: Any, all_velocities: Iterable[Any]
                 ) -> _CyclicPart | None:
    """The part of L in the cyclic ``velocities`` (:class:`_CyclicPart`); None when A cannot be inverted."""
    at_zero = {v: 0 for v in all_velocities}
    A = sympy.Matrix(len(velocities), len(velocities), lambda i, j: sympy.diff(L, velocities[i], velocities[j]))
    b = sympy.Matrix([sympy.diff(L, v).xreplace(at_zero) for v in velocities])
    C = sympy.Matrix([sympy.diff(L, v, qd) for v in velocities])
    P = sympy.Matrix(momenta)
    try:
        inverse = A.inv(method="LU").applyfunc(lambda e: tidy(sympy.cancel(e))) if velocities else A
    except (ValueError, ZeroDivisionError):
        return None
    return _CyclicPart(velocities, inverse, b, C, P)


def _effective_mass(L: Any, qd: Any, part: _CyclicPart) -> Any:
    """:math:`m_{eff} = \\partial^2L/\\partial\\dot q^2 - C^TA^{-1}C`."""
    if part.velocities:
        return _display(sympy.diff(L, qd, 2) - (part.C.T * part.inverse * part.C)[0, 0])
    return tidy(sympy.diff(L, qd, 2))


def _raw_potential(L: Any, at_zero: dict[Any, Any], part: _CyclicPart) -> Any:
    """:math:`V_{eff} = -L|_{\\dot q = v = 0} + \\tfrac12(p - b)^TA^{-1}(p - b)`, its constants not yet
    dropped."""
    if part.velocities:
        return -L.xreplace(at_zero) + ((part.P - part.b).T * part.inverse * (part.P - part.b))[0, 0] / 2
    return -L.xreplace(at_zero)


def _routh_form_holds(system: MotionSystem, qdd: Any, solution: dict[Any, Any], equation: tuple[Any, Any, Any]
                      ) -> bool:
    """Whether the reduced equation, with the cyclic velocities written through the momenta (``solution``),
    reads lhs = rhs + Q (``equation`` is lhs, rhs, Q); True when the system has no acceleration for it."""
    lhs, rhs, force = equation
    acceleration = system.accelerations[qdd].xreplace(solution) if qdd in system.accelerations else None
    return acceleration is None or proved_zero(lhs.xreplace({qdd: acceleration}) - rhs - force)


def _display(expr: Any) -> Any:
    """``tidy`` for small expressions; a sum over common denominators for large ones (cheaper)."""
    return tidy(expr) if ops(expr) <= COMPACT_LIMIT else _by_denominator(sympy.expand(expr))


def _drop_constants(expr: Any, q: Any) -> Any:
    """``expr`` without its additive terms free of ``q``: a sum of terms, one per denominator
    (the textbook's ``m2*g*r + p**2/(2*m1*r**2)``), unless one fraction is much shorter."""
    def varying(e: Any) -> Any:
        return sympy.Add(*[t for t in sympy.Add.make_args(e) if t.has(q)])

    def size(e: Any) -> tuple[int, int, str]:
        return (ops(e), len(str(e)), str(e))

    # grouped twice (merged groups may share a denominator); constants dropped before and after
    expanded = sympy.expand(expr)
    forms = [sympy.expand(tidy_sum(expr))]
    if ops(expanded) <= GROUP_LIMIT:  # grouping a long raw sum costs seconds
        forms.append(expanded)
    terms = min((varying(_by_denominator(_by_denominator(varying(form)))) for form in forms), key=size)
    if ops(terms) > COMPACT_LIMIT:
        return terms
    compact = tidy(terms)
    return compact if 2 * ops(compact) < ops(terms) else terms


def _by_denominator(expr: Any) -> Any:
    """The terms of a sum collected over common denominators (numeric factors aside), each factored."""
    groups: dict[Any, list[Any]] = {}
    for term in sympy.Add.make_args(expr):
        numerator, denominator = sympy.fraction(sympy.together(term))
        coefficient, rest = sympy.factor(denominator).as_coeff_Mul()
        groups.setdefault(rest, []).append(numerator / coefficient)
    out = []
    for key, parts in groups.items():
        total = sympy.Add(*parts)
        if key == 1:
            out.append(total)
            continue
        out.append(_positive_sums(sympy.factor(total) / key))
    return sympy.Add(*out)


def _positive_sums(term: Any) -> Any:
    """``-(-a + b)/k`` written ``(a - b)/k``: sums inside a product lose a leading minus sign."""
    if not term.is_Mul:
        return term
    flips = [a.is_Add and a.could_extract_minus_sign() for a in term.args]
    return (-1) ** sum(flips) * sympy.Mul(*[-a if f else a for a, f in zip(term.args, flips, strict=True)])


def _equilibria(potential: Any, mass: Any, q: Any, momenta: list[Any]) -> list[Equilibrium]:
    slope = sympy.together(sympy.diff(potential, q))
    numerator = sympy.numer(slope)
    try:
        _, factors = sympy.factor_list(numerator)
    except (sympy.PolynomialError, ValueError, TypeError):
        factors = [(numerator, 1)]
    curvature = sympy.diff(potential, q, 2)
    eliminated = _eliminate_momentum(potential, q, momenta)
    out: list[Equilibrium] = []
    for factor, _ in factors:
        if not factor.has(q) or factor.is_positive or factor.is_negative:
            continue
        factor = _canonical_sign(factor)
        condition = _condition(factor, q)
        values = _solve(factor, q)
        if values is None and eliminated is None and any(factor.has(p) for p in momenta):
            out.append(Equilibrium(None, condition))  # a relation between q0 and several momenta: no more
        elif values is None:
            out.append(_at_condition(condition, curvature, mass, q, eliminated))
        else:
            out += [_at_value(v, condition, curvature, mass, q, eliminated) for v in values]
    out.sort(key=lambda e: (e.value is None, sympy.default_sort_key(e.value if e.value is not None else e.condition)))
    return out[:MAX_EQUILIBRIA]


def _canonical_sign(factor: Any) -> Any:
    """``factor`` or ``-factor``, whichever has fewer negative terms (then the smaller sort key):
    SymPy's ``factor_list`` may return either sign, depending on what it computed before."""
    forms = [sympy.expand(factor), sympy.expand(-factor)]
    return min(forms, key=lambda f: (sum(t.could_extract_minus_sign() for t in sympy.Add.make_args(f)),
                                     sympy.default_sort_key(f)))


def _condition(factor: Any, q: Any) -> Any:
    """``factor = 0`` as ``lhs = rhs``: ``u**k = X`` when only one term holds q, else positive = negative terms."""
    terms = sympy.Add.make_args(sympy.expand(factor))
    with_q = [t for t in terms if t.has(q)]
    without = sympy.Add(*[t for t in terms if not t.has(q)])
    if len(with_q) == 1:
        coefficient, part = with_q[0].as_independent(q, as_Add=False)
        return sympy.Eq(part, tidy(-without / coefficient), evaluate=False)
    left = sympy.Add(*[t for t in terms if not t.could_extract_minus_sign()])
    right = sympy.Add(*[-t for t in terms if t.could_extract_minus_sign()])
    if ops(factor) <= COMPACT_LIMIT:
        left, right = tidy(left), tidy(right)
    return sympy.Eq(left, right, evaluate=False)


def _generators(expr: Any, q: Any) -> set[Any]:
    """The pieces through which ``expr`` depends on ``q``: ``q`` itself and functions of it."""
    found = {f for f in expr.atoms(sympy.Function) if f.has(q)}
    if expr.xreplace({f: sympy.Dummy() for f in found}).has(q):
        found.add(q)
    return found


def _solve(factor: Any, q: Any) -> list[Any] | None:
    """Real solutions of ``factor = 0`` for ``q`` when the factor is simple, else None."""
    if ops(factor) > SOLVE_LIMIT:
        return None
    generators = _generators(factor, q)
    if len(generators) != 1:
        return None
    u = generators.pop()
    if u != q and not (isinstance(u, sympy.sin | sympy.cos | sympy.tan) and u.args[0] == q):
        return None
    poly = sympy.Poly(factor, u)
    if poly.degree() > 2 and len(poly.terms()) > 2:
        return None
    if u == q and len(poly.terms()) == 2 and poly.coeff_monomial(1) != 0:
        k = poly.degree()
        root = (-poly.coeff_monomial(1) / poly.coeff_monomial(q**k)) ** sympy.Rational(1, k)
        if k % 2 == 1 or q.is_positive:
            return [root]
        return [-root, root]
    try:
        found = sympy.solve(factor, q)
    except (NotImplementedError, ValueError, TypeError):
        return None
    values = []
    for v in found:
        if v.has(sympy.I) or v.is_real is False or (q.is_positive and v.is_positive is False):
            continue
        if v.has(sympy.pi) and ops(v - 2 * sympy.pi) < ops(v):
            v = v - 2 * sympy.pi
        values.append(tidy(v))
    return values


def _exists_if(value: Any) -> Any:
    """The parameters' condition for ``acos(X)``/``asin(X)`` in ``value`` to be real (|X| ≤ 1)."""
    inverse = [f for f in value.atoms(sympy.acos, sympy.asin)]
    if len(inverse) != 1:
        return None
    x = inverse[0].args[0]
    numerator, denominator = sympy.fraction(sympy.cancel(x))
    if x.is_positive and denominator.is_positive:
        return relation(denominator - numerator, strict=False)
    if x.is_negative and denominator.is_positive:
        return relation(denominator + numerator, strict=False)
    return sympy.And(sympy.Le(x, 1), sympy.Ge(x, -1))


def _stability(curvature: Any, exists: Any) -> tuple[bool | None, Any]:
    sign, core = sign_core(curvature)
    if sign is not None:
        return sign > 0, None
    condition = relation(core)
    if exists is not None and isinstance(exists, sympy.GreaterThan) and \
            proved_zero((exists.lhs - exists.rhs) - (condition.lhs - condition.rhs)):
        return True, condition  # stable wherever it exists (the boundary is degenerate)
    return None, condition


def _frequency(curvature: Any, mass: Any, stable: bool | None) -> tuple[Any, Any]:
    """(ω, ω²) from V'' and m_eff, or (None, None) for an unstable equilibrium."""
    if stable is False:
        return None, None
    square = tidy(curvature / mass)
    root = sympy.sqrt(square)
    return min((root, tidy(root)), key=lambda e: (ops(e), len(str(e)))), square


def _at_value(value: Any, condition: Any, curvature: Any, mass: Any, q: Any,
              eliminated: tuple[Any, Any] | None) -> Equilibrium:
    c0 = tidy(curvature.xreplace({q: value}))
    exists = _exists_if(value)
    stable, stability_condition = _stability(c0, exists)
    if stable is None and eliminated is not None and (core_sign := sign_core(eliminated[0])[0]) is not None:
        stable, stability_condition = core_sign > 0, None  # V'' at any equilibrium
    at = curvature_at = None
    if eliminated is not None:
        curvature_at, at = eliminated[0], tidy(eliminated[0] / mass)
    frequency, square = _frequency(c0, mass.xreplace({q: value}), stable)
    return Equilibrium(value, condition, exists, c0, stable, stability_condition, frequency, at, curvature_at, square)


def _at_condition(condition: Any, curvature: Any, mass: Any, q: Any,
                  eliminated: tuple[Any, Any] | None) -> Equilibrium:
    c_q, exists = (eliminated if eliminated is not None else (tidy(curvature), None))
    lhs = condition.lhs
    if isinstance(lhs, sympy.Derivative | sympy.core.function.AppliedUndef | sympy.sin | sympy.cos | sympy.tan):
        c_q = tidy(c_q.xreplace({lhs: condition.rhs}))  # f'(x) = 0 at the equilibrium
        mass = tidy(mass.xreplace({lhs: condition.rhs}))
    stable, stability_condition = _stability(c_q, exists)
    frequency, square = _frequency(c_q, mass, stable)
    return Equilibrium(None, condition, exists, c_q, stable, stability_condition, frequency, square, c_q, square)


def _eliminate_momentum(potential: Any, q: Any, momenta: list[Any]) -> tuple[Any, Any] | None:
    r"""With one momentum :math:`p` entering :math:`V_{eff}` as :math:`p^2` only: the curvature
    :math:`V_{eff}''` at an equilibrium written in :math:`q` alone (using :math:`V_{eff}' = 0` to
    express :math:`p^2`), and the condition :math:`p^2 \ge 0` as a relation (or None)."""
    present = [p for p in momenta if potential.has(p)]
    if len(present) != 1:
        return None
    p = present[0]
    if not proved_zero(potential - potential.xreplace({p: -p})):
        return None
    square = sympy.Dummy("S", nonnegative=True)
    even = potential.subs(p**2, square)
    if even.has(p):
        return None
    slope = sympy.diff(even, q)
    if sympy.diff(slope, square, 2) != 0 or sympy.diff(slope, square) == 0:
        return None
    value = tidy(-slope.xreplace({square: 0}) / sympy.diff(slope, square))
    curvature = tidy(sympy.diff(even, q, 2).xreplace({square: value}))
    sign, core = sign_core(value)
    exists = None if sign is not None else relation(core, strict=False)
    return curvature, exists
