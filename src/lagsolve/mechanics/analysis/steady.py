r"""Steady motions (relative equilibria) by Routh's reduction: the condition, its roots, stability, frequency.

With one coordinate :math:`q` left after the cyclic ones (:mod:`~lagsolve.mechanics.analysis.equilibria`), a
*steady motion* keeps :math:`q = q_0` while every cyclic coordinate turns at a constant rate: the
conical pendulum, the heavy top's steady precession, a circular orbit. One cyclic velocity,
:math:`\Omega = \dot q_k`, is the *rate*; every other cyclic coordinate keeps its momentum
:math:`p_h` (the top's spin :math:`p_\psi = I_3\omega_3`), so its velocity follows from
:math:`p_h = \partial L/\partial\dot q_h`. With :math:`\dot q = \ddot q = 0` Lagrange's equation
for :math:`q` reads

.. math:: \frac{\partial L}{\partial q}\Big|_{\dot q = 0} = 0
          \quad\Longleftrightarrow\quad A(q_0)\,\Omega^2 + B(q_0, p)\,\Omega + C(q_0) = 0,

quadratic in :math:`\Omega` because T is (factors free of :math:`\Omega`, such as the top's
:math:`\sin\theta_0`, are set aside: their zeros are singular points of the coordinates). Its roots
are :math:`\Omega = (-B \pm \sqrt{B^2 - 4AC})/(2A)`, real when :math:`B^2 \ge 4AC`; when
:math:`B^2 \gg 4|AC|` they are near :math:`-C/B` (slow precession) and :math:`-B/A` (fast). The
condition is the effective potential's :math:`V_{eff}'(q_0) = 0` with
:math:`p_k = \partial L/\partial\dot q_k` at the steady motion (checked), since
:math:`\partial V_{eff}/\partial q|_p = -\partial L/\partial q|_{\dot q_c}`.

Stability and the frequency of small oscillations about the steady motion come from the Routhian's
effective potential at fixed momenta: stable when :math:`V_{eff}''(q_0) > 0`, and

.. math:: \omega^2 = V_{eff}''(q_0)/m_{eff}(q_0),

written in :math:`q_0`, :math:`\Omega` and the held momenta, with a parameter of the potential
alone (:math:`g`, :math:`k`) eliminated through the condition; a quadratic numerator is written as
a sum of squares where that decides its sign. For the heavy symmetric top this gives Goldstein's
:math:`I_1'\Omega^2\cos\theta_0 - I_3\omega_3\Omega + mgl = 0` and the nutation frequency
:math:`\omega^2 = (I_3\omega_3/I_1' - 2\Omega\cos\theta_0)^2 + \Omega^2\sin^2\theta_0`.

Notes
-----
* Needs the effective potential (one coordinate left, no friction, no explicit t) and at least
  one cyclic coordinate; at most :data:`MAX_CYCLIC` of them.
* Of several cyclic coordinates the rate is the one whose condition is shortest (ties: input order).
* The expressions are written with :math:`q` standing for :math:`q_0` and the rate's velocity symbol
  for :math:`\Omega` (constant along the steady motion).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.stages import StageTooLarge
from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.signs import relation, sign_core
from lagsolve.mechanics.symbolic.simplify import measure, tidy

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.conserved import MotionSystem
    from lagsolve.mechanics.analysis.equilibria import EffectivePotential

#: at most this many cyclic coordinates (each is tried as the rate)
MAX_CYCLIC = 3
#: ω² larger than this (operations) is not offered to ``trigsimp``
COMPACT_LIMIT = 60
#: a Lagrangian or effective potential larger than this (operations) is declined at once
SIZE_LIMIT = 400


@dataclass(frozen=True)
class SteadyMotion:
    r"""The steady motions of one reduction (module docstring); :math:`q` stands for :math:`q_0`.

    ``coordinate`` is q, ``rate`` the cyclic coordinate turning at :math:`\Omega` and ``velocity`` its
    velocity symbol (standing for :math:`\Omega`); ``held`` lists ``(q_h, p_h, ∂L/∂q̇_h)`` for the other
    cyclic coordinates and ``velocities`` ``(q̇_h, its value)`` at the steady motion; ``momentum`` is
    ``(p_k, its value)``. ``coefficients`` are (A, B, C) of :math:`A\Omega^2 + B\Omega + C = 0`,
    ``condition`` that equation (``Eq``), ``excluded`` the factors set aside, ``roots`` the values of
    :math:`\Omega` (``square`` :math:`\Omega^2` when B = 0), ``exists_if`` when they are real,
    ``limits`` (slow, fast) when A, B and C are all non-zero. ``frequency_squared`` is
    :math:`\omega^2` in q, Ω and the held momenta (``eliminated``: the parameter written through the
    condition, and its value), ``frequency_squared_at`` the same with Ω eliminated (B = 0), ``curvature``
    :math:`V_{eff}'' = m_{eff}\omega^2`; ``stable`` True/False, or None with ``stability_condition``.
    ``verified`` says how the condition was checked against the equations of motion.
    """

    coordinate: Any
    rate: Any
    velocity: Any
    held: tuple[tuple[Any, Any, Any], ...]
    velocities: tuple[tuple[Any, Any], ...]
    momentum: tuple[Any, Any]
    coefficients: tuple[Any, Any, Any]
    condition: Any
    excluded: tuple[Any, ...]
    roots: tuple[Any, ...]
    square: Any
    exists_if: Any
    limits: tuple[Any, Any] | None
    mass: Any
    curvature: Any
    frequency_squared: Any
    frequency_squared_at: Any
    eliminated: tuple[Any, Any] | None
    stable: bool | None
    stability_condition: Any
    verified: str


@dataclass(frozen=True)
class _Candidate:
    """One choice of the rate: the condition's polynomial in Ω and what it was built from."""

    index: int
    polynomial: Any
    excluded: tuple[Any, ...]
    held_velocities: dict[Any, Any]
    momentum: Any
    slope: Any  # ∂L/∂q at q̇ = 0, the held velocities put in


def steady_motions(system: MotionSystem, effective: EffectivePotential) -> tuple[SteadyMotion | None, str]:
    """The steady motions of ``system`` reduced to ``effective.coordinate``, or None and the reason."""
    cyclic = [c for c, _, _ in effective.cyclic]
    model = system.model
    L = model.lagrangian
    why_not = _why_not_steady(cyclic, L, effective)
    if why_not:
        return None, why_not
    q = effective.coordinate
    qd = model.velocities[model.coordinates.index(q)]
    velocities = [model.velocities[model.coordinates.index(c)] for c in cyclic]
    momenta = [p for _, p, _ in effective.cyclic]
    best, why_not = _best_candidate(L, q, qd, velocities, momenta)
    if best is None:
        return None, why_not
    k = best.index
    omega = velocities[k]
    A, B, C = (tidy(best.polynomial.coeff(omega, n)) for n in (2, 1, 0))
    if A == 0 and B == 0:
        return None, f"the condition does not involve {omega.name}: no rate makes {q.name} steady"
    momentum = best.momentum
    mass = effective.mass
    curvature, eliminated, value = _steady_curvature(effective, best, momenta[k], (A, B, C), model)
    square = _squares(_simplest(curvature / mass), [*(momenta[i] for i in range(len(cyclic)) if i != k),
                                                                omega])
    verified = _verify(system, effective, best, q, qd, omega, eliminated, value, momenta[k])
    roots, squared, exists, limits = _roots(A, B, C, omega)
    if exists is sympy.false:
        return None, f"the condition {sympy.sstr(best.polynomial)} = 0 has no real root"
    at = _square_at_root(square, squared, omega)
    stable, condition = _stability(curvature, square, mass)
    held = tuple((cyclic[i], momenta[i], tidy(sympy.diff(L, velocities[i]))) for i in range(len(cyclic)) if i != k)
    return SteadyMotion(
        coordinate=q, rate=cyclic[k], velocity=omega, held=held,
        velocities=tuple((v, _collected(e, omega)) for v, e in best.held_velocities.items()),
        momentum=(momenta[k], _collected(momentum, omega)), coefficients=(A, B, C),
        condition=sympy.Eq(_condition(A, B, C, omega), 0, evaluate=False), excluded=best.excluded,
        roots=roots, square=squared, exists_if=exists, limits=limits, mass=mass, curvature=curvature,
        frequency_squared=square, frequency_squared_at=at,
        eliminated=(eliminated, _solved_for(A, B, C, omega, eliminated)) if eliminated is not None else None,
        stable=stable,
        stability_condition=condition, verified=verified), ""


def _why_not_steady(cyclic: list[Any], L: Any, effective: EffectivePotential) -> str:
    """Why no steady motion is looked for (no cyclic coordinate, or more than :data:`MAX_CYCLIC`), or ``""``;
    :class:`StageTooLarge` when L or V_eff is too large to try."""
    if not cyclic:
        return "no coordinate is cyclic: the equilibria of the effective potential are states of rest"
    if len(cyclic) > MAX_CYCLIC:
        return f"{len(cyclic)} cyclic coordinates (at most {MAX_CYCLIC} are tried)"
    if ops(L) > SIZE_LIMIT or ops(effective.expression) > SIZE_LIMIT:
        raise StageTooLarge(f"L or V_eff has more than {SIZE_LIMIT} operations")
    return ""


def _best_candidate(L: Any, q: Any, qd: Any, velocities: list[Any], momenta: list[Any]
                    ) -> tuple[_Candidate | None, str]:
    """The choice of the rate whose condition is shortest (ties: input order), or None and why there is none."""
    rest = {qd: sympy.Integer(0)}
    candidates = [c for k in range(len(velocities))
                  if (c := _candidate(L.xreplace(rest), q, velocities, momenta, k)) is not None]
    if not candidates:
        if not sympy.diff(L.xreplace(rest), q).has(*velocities):
            return None, (f"dL/d{q.name} at rest does not involve the cyclic velocities: the steady motions are the "
                          "equilibria of the effective potential")
        return None, "the steady-motion condition is not a polynomial of degree 1 or 2 in any cyclic velocity"
    return min(candidates, key=lambda c: (ops(c.polynomial), c.index)), ""


def _steady_curvature(effective: EffectivePotential, best: _Candidate, rate_momentum: Any,
                      coefficients: tuple[Any, Any, Any], model: Any) -> tuple[Any, Any, Any]:
    """:math:`V_{eff}''(q_0)` with the rate's momentum at its steady value and, when a parameter of the
    potential alone can be eliminated through the condition, with it eliminated; and that parameter and its
    value (None, None without one)."""
    A, B, C = coefficients
    q = effective.coordinate
    momentum = best.momentum
    curvature = sympy.diff(effective.expression, q, 2).xreplace({rate_momentum: momentum})
    eliminated = _eliminable(C, (A, B, effective.mass, momentum, *best.held_velocities.values()), model, q)
    value = None
    if eliminated is not None:
        # the linear solve by hand: SymPy's ``solve`` writes 1/cot as tan, which no later cancellation undoes
        value = -best.polynomial.xreplace({eliminated: 0}) / sympy.diff(best.polynomial, eliminated)
        curvature = curvature.xreplace({eliminated: value})
    return tidy(sympy.together(curvature)), eliminated, value


def _square_at_root(square: Any, squared: Any, omega: Any) -> Any:
    """ω² with Ω² put in from the condition (``squared``, when B = 0), or None when Ω remains."""
    if squared is None or not square.has(omega):
        return None
    at = _simplest(square.subs(omega**2, squared))
    return None if at.has(omega) else at


def _stability(curvature: Any, square: Any, mass: Any) -> tuple[bool | None, Any]:
    """Stable when :math:`V_{eff}'' > 0` (or ω² is a sum of squares and the mass positive), unstable when it is
    negative, else None and the condition for it."""
    sign, core = sign_core(curvature)
    stable, condition = (sign > 0, None) if sign is not None else (None, relation(core))
    if stable is None and _nonnegative(square) and sign_core(mass)[0] == 1:
        stable, condition = True, None
    return stable, condition


def _simplest(expr: Any) -> Any:
    """The shortest of ``tidy`` of ``expr``, its common factors taken out, and (with tan or cot) its ``trigsimp``
    (1 + cot² = 1/sin²), for a small ``expr``."""
    first = tidy(sympy.together(expr))
    if ops(first) > COMPACT_LIMIT:
        return first
    forms = [first, sympy.factor_terms(first)]
    if first.has(sympy.cot, sympy.tan):
        ratios = first.replace(sympy.cot, lambda u: sympy.cos(u) / sympy.sin(u)).replace(
            sympy.tan, lambda u: sympy.sin(u) / sympy.cos(u))
        forms += [tidy(sympy.trigsimp(first)), tidy(sympy.cancel(ratios))]
    return min(forms, key=measure)


def _collected(expr: Any, omega: Any) -> Any:
    r"""``expr`` as a sum of its terms in powers of Ω, each coefficient factored (the top's
    :math:`(I_1 + ml^2)\dot\phi\sin^2\theta + p_\psi\cos\theta`), unless ``tidy`` is shorter."""
    tidied = tidy(expr)
    try:
        collected = sympy.collect(sympy.expand(tidied), omega, func=lambda c: tidy(sympy.factor(c)))
    except (sympy.PolynomialError, ValueError, TypeError):
        return tidied
    return collected if ops(collected) <= ops(tidied) else tidied


def _solved_for(A: Any, B: Any, C: Any, omega: Any, parameter: Any) -> Any:
    r"""The condition solved for ``parameter`` (linear, in C alone): :math:`-(A\Omega^2 + B\Omega + C_0)/c` with
    :math:`C = c\,s + C_0`, the coefficients kept as blocks."""
    scale = tidy(sympy.diff(C, parameter))
    numerator = sympy.Add(-A * omega**2, -B * omega, -tidy(sympy.expand(C - scale * parameter)))
    value = numerator / scale if scale != 1 else numerator
    return min((value, tidy(value)), key=measure)


def _candidate(L0: Any, q: Any, velocities: list[Any], momenta: list[Any], k: int) -> _Candidate | None:
    """The condition with ``velocities[k]`` as the rate and the others' momenta held (None: not quadratic)."""
    omega = velocities[k]
    held = [i for i in range(len(velocities)) if i != k]
    solution: dict[Any, Any] = {}
    if held:
        equations = [sympy.diff(L0, velocities[i]) - momenta[i] for i in held]
        unknowns = [velocities[i] for i in held]
        try:
            found = sympy.solve(equations, unknowns, dict=True)
        except (NotImplementedError, ValueError, TypeError):
            return None
        if len(found) != 1 or set(found[0]) != set(unknowns):
            return None
        solution = {v: sympy.cancel(found[0][v]) for v in unknowns}
    slope = sympy.diff(L0, q).xreplace(solution)
    numerator = sympy.numer(sympy.together(slope))
    try:
        _, factors = sympy.factor_list(numerator)
    except (sympy.PolynomialError, ValueError, TypeError):
        factors = [(numerator, 1)]
    kept = sympy.Mul(*[f**e for f, e in factors if f.has(omega)])
    excluded = tuple(dict.fromkeys(f for f, _ in factors if not f.has(omega) and f.has(q)))
    try:
        poly = sympy.Poly(kept, omega)
    except sympy.PolynomialError:
        return None
    if kept == 1 or poly.degree() > 2 or any(c.has(omega) for c in poly.all_coeffs()):
        return None
    polynomial = _canonical(sympy.expand(kept), omega)
    return _Candidate(k, polynomial, excluded, solution,
                      sympy.diff(L0, omega).xreplace(solution), slope)


def _canonical(polynomial: Any, omega: Any) -> Any:
    """``polynomial`` or its negative: the leading coefficient without a minus sign where possible, then the
    fewer negative terms (``factor_list`` may return either sign)."""
    def key(p: Any) -> tuple[bool, int, Any]:
        lead = sympy.Poly(p, omega).LC()
        terms = sympy.Add.make_args(p)
        return (lead.could_extract_minus_sign(), sum(t.could_extract_minus_sign() for t in terms),
                sympy.default_sort_key(p))

    return min((polynomial, sympy.expand(-polynomial)), key=key)


def _condition(A: Any, B: Any, C: Any, omega: Any) -> Any:
    """:math:`A\\Omega^2 + B\\Omega + C` with each coefficient kept as a block (the textbook's form)."""
    return sympy.Add(A * omega**2, B * omega, C)


def _roots(A: Any, B: Any, C: Any, omega: Any) -> tuple[tuple[Any, ...], Any, Any, tuple[Any, Any] | None]:
    """(roots, Ω² when B = 0, when they exist, (slow, fast) limits)."""
    if A == 0:
        return (tidy(-C / B),), None, None, None
    if B == 0:
        squared = tidy(-C / A)
        if squared == 0:
            return (sympy.Integer(0),), squared, None, None
        sign, core = sign_core(squared)
        # Ω² = 0 is a state of rest, not a turning motion: strict when the numerator can vanish only there
        strict = sign_core(sympy.numer(squared))[0] is not None
        exists = None if sign == 1 else (sympy.false if sign == -1 else relation(core, strict=strict))
        root = sympy.sqrt(squared)
        root = min((root, tidy(root)), key=lambda e: (ops(e), len(str(e))))
        return (-root, root), squared, exists, None
    if C == 0:
        return tuple(sorted((sympy.Integer(0), tidy(-B / A)), key=sympy.default_sort_key)), None, None, None
    discriminant = tidy(B**2 - 4 * A * C)
    sign, _ = sign_core(discriminant)
    exists = None if sign == 1 else (sympy.false if sign == -1 else
                                     sympy.GreaterThan(tidy(B**2), tidy(4 * A * C), evaluate=False))
    root = sympy.sqrt(discriminant)
    roots = tuple(tidy((-B + s * root) / (2 * A)) for s in (-1, 1))
    return roots, None, exists, (tidy(-C / B), tidy(-B / A))


def _eliminable(C: Any, others: tuple[Any, ...], model: Any, q: Any) -> Any:
    """A parameter of the potential alone (in C, linearly, and in nothing else of the condition, the mass
    or the momenta) to write through the condition: ``g`` for gravity, ``k`` for a central force."""
    variables = {*model.coordinates, *model.velocities, model.time, q}
    kinetic = model.kinetic.free_symbols
    taken = set().union(*(sympy.sympify(o, strict=True).free_symbols for o in others))
    for s in sorted(C.free_symbols - variables - taken - kinetic, key=sympy.default_sort_key):
        if s.name.startswith("p_"):
            continue
        if sympy.diff(C, s, 2) == 0 and sympy.diff(C, s) != 0:
            return s
    return None


def _squares(expr: Any, variables: list[Any]) -> Any:
    r"""``expr`` (a fraction N/D) with N, quadratic in one of ``variables`` with a positive leading
    coefficient, written :math:`a(x + b/2a)^2 + (c - b^2/4a)` when the remainder is non-negative (a sum of
    squares, whose sign is then plain); ``expr`` unchanged otherwise."""
    numerator, denominator = sympy.fraction(sympy.together(expr))
    if sign_core(denominator)[0] != 1:
        return expr
    for x in variables:
        if not numerator.has(x):
            continue
        try:
            poly = sympy.Poly(sympy.expand(numerator), x)
        except sympy.PolynomialError:
            continue
        if poly.degree() != 2:
            continue
        a, b, c = (poly.coeff_monomial(x**n) for n in (2, 1, 0))
        if sign_core(a)[0] != 1 or any(e.has(x) for e in (a, b, c)):
            continue
        remainder = tidy(sympy.together(c - b**2 / (4 * a)))
        if not _nonnegative(remainder):
            continue
        scale = sympy.sqrt(a / denominator)
        if any(p.exp.is_Rational and p.exp.q != 1 for p in scale.atoms(sympy.Pow)):
            square = a / denominator * sympy.expand(x + b / (2 * a))**2  # no rational square root: keep the factor
        else:
            square = sympy.Add(tidy(scale * x), tidy(scale * b / (2 * a)))**2
        return sympy.Add(square, tidy(remainder / denominator))
    return expr


def _nonnegative(expr: Any) -> bool:
    """Every term of ``expr`` is a product of positive factors and even powers: non-negative."""
    if expr == 0:
        return False
    for term in sympy.Add.make_args(expr):
        for factor in sympy.Mul.make_args(term):
            if factor.is_positive:
                continue
            base, exp = factor.as_base_exp()
            if exp.is_Integer and int(exp) % 2 == 0 and base.is_real is not False:
                continue
            if factor.is_Pow and factor.base.is_Add and exp.is_Integer and int(exp) % 2 == 0:
                continue
            return False
    return True


def _verify(system: MotionSystem, effective: EffectivePotential, best: _Candidate, q: Any, qd: Any, omega: Any,
            eliminated: Any, value: Any, momentum: Any) -> str:
    """How the condition was checked: it is :math:`V_{eff}' = 0` at the steady motion's momentum, and with it
    the equations of motion give :math:`\\ddot q = 0` and constant cyclic velocities."""
    slope = sympy.diff(effective.expression, q).xreplace({momentum: best.momentum})
    if not proved_zero(slope + best.slope):
        return ""
    if not system.accelerations or eliminated is None:
        return "effective potential"
    state = {qd: sympy.Integer(0), **best.held_velocities}
    model = system.model
    for a in model.accelerations:
        if a not in system.accelerations:
            return "effective potential"
        at = system.accelerations[a].xreplace(state)
        if at.has(eliminated):
            at = at.xreplace({eliminated: value})
        if not proved_zero(at):
            return ""
    return "equations of motion"
