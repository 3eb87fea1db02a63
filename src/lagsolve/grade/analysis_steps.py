r"""The analysis steps of ``lagsolve grade`` (issue 31): the key's equilibria and ω² (:func:`key_lists`), how
listed values are compared (symbolically, else numerically, an angle modulo 2π), the Hamiltonian's known mistakes
(:func:`hamiltonian_candidates`) and the Legendre transform of a student's own L (:func:`legendre`). The grading
itself is :class:`lagsolve.grade.grader._Grader`'s; see ``docs/grading.md``."""

from __future__ import annotations

import contextlib
from typing import Any

import mpmath
import sympy

from lagsolve.check.diagnose import close
from lagsolve.grade.numeric_lists import Condition
from lagsolve.mechanics.derivation import Derivation

SIGN, FACTOR_MISSING, POTENTIAL_SIGN = "sign_error", "missing_factor", "wrong_potential_sign"
#: fewest shared states at which a listed value (an equilibrium, an ω²) must be a number to be compared there
LIST_STATES = 4


def angle_coordinates(derivation: Derivation) -> set[str]:
    """The coordinates that appear only inside sines and cosines (their equilibria are equal modulo 2π)."""
    from lagsolve.mechanics.analysis.numeric_equilibria import periodic

    analysis = derivation.analysis
    if analysis is None:
        return set()
    system = analysis.system
    coordinates = list(system.model.coordinates)
    flags = periodic([system.model.lagrangian, *system.generalized_forces], coordinates)
    return {str(q) for q, flag in zip(coordinates, flags, strict=True) if flag}


def same_at_states(student: Any, key: Any, *, angle: bool = False) -> bool:
    """The student's values equal the key's at every shared state where the key's is a number (complex ones too),
    at least :data:`LIST_STATES` of them."""
    if student is None or key is None:
        return False
    rows = [(e, d) for e, d in zip(student, key, strict=True) if is_number(d)]
    if len(rows) < LIST_STATES:
        return False
    return all(is_number(e) and near(e, d, angle) for e, d in rows)


def ratio(a: Any, b: Any) -> Any:
    """a / b cancelled (None when it cannot be formed)."""
    with contextlib.suppress(sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError, ZeroDivisionError):
        if b == 0:
            return None
        return sympy.cancel(sympy.together(a / b))
    return None


def frequency_mistake(value: Any, reference: Any, detail: str) -> tuple[str | None, str]:
    """The mistake when one ω² is missing and one other value given: −ω² (or −ω²'s root), or ω² times a number or
    a power of a parameter; else no name and ``detail``."""
    for candidate in (value, value**2):
        found = ratio(candidate, reference)
        if found is None or found == 1 or not monomial(found):
            continue
        if found == -1:
            return SIGN, f"has the opposite sign of the key's {sympy.sstr(reference)}"
        return FACTOR_MISSING, f"is {sympy.sstr(found)} times the key's {sympy.sstr(reference)}"
    return None, detail


def key_lists(derivation: Derivation) -> tuple[list[dict[str, Any]], list[Any]]:
    """The key's equilibria (each a mapping coordinate → value) and the ω² of small oscillations about those not
    known to be unstable (stable, or stable under a condition on the parameters), from the effective potential
    when there is one, else from the normal modes. A point found numerically (at the simulation values) is kept
    as its numbers; one known only by its condition as a :class:`~.numeric_lists.Condition` (no ω²). An
    equilibrium whose ω² are those of an earlier one (a symmetric pair, ±θ₀) adds none."""
    analysis = derivation.analysis
    potential = analysis.effective_potential if analysis is not None else None
    linear = analysis.linearization if analysis is not None else None
    return lists_of(potential, linear)


def lists_of(potential: Any, linear: Any) -> tuple[list[dict[str, Any]], list[Any]]:
    """:func:`key_lists` from an effective potential (or None) and a linearization (or None), the key's or those
    of a student's own Lagrangian."""
    points: list[dict[str, Any]] = []
    groups: list[list[Any]] = []
    if potential is not None and potential.equilibria:
        name = str(potential.coordinate)
        for eq in potential.equilibria:
            if eq.value is None:
                if eq.condition is None or not isinstance(eq.condition, sympy.Eq):
                    return [], []
                points.append({name: Condition(potential.coordinate, eq.condition.lhs - eq.condition.rhs)})
                continue
            points.append({name: eq.value})
            if eq.stable is not False and eq.frequency_squared is not None:
                groups.append([eq.frequency_squared])
    elif linear is not None and linear.modes:
        for mode in linear.modes:
            points.append({str(q): v for q, v in mode.point})
            if mode.stable is not False and mode.squared_frequencies is not None:
                groups.append(list(mode.squared_frequencies))
    squares: list[Any] = []
    seen: list[list[Any]] = []
    for group in groups:
        if any(len(group) == len(other) and all(same_symbolic(a, b) for a, b in zip(group, other, strict=True))
               for other in seen):
            continue
        seen.append(group)
        squares.extend(group)
    return points, squares


def same_symbolic(a: Any, b: Any) -> bool:
    from lagsolve.check.verdicts import symbolically_equal

    with contextlib.suppress(TypeError, ValueError, AttributeError):
        return bool(symbolically_equal(sympy.sympify(a, strict=True), sympy.sympify(b, strict=True)))
    return False


def monomial(expr: Any) -> bool:
    """A number times powers of symbols (a constant factor of values that depend on the parameters only)."""
    return all(not (f.is_Add or f.is_Function) for f in sympy.Mul.make_args(expr)) and bool(expr != 0)


def is_number(value: Any) -> bool:
    return isinstance(value, mpmath.mpf | mpmath.mpc) and bool(mpmath.isfinite(value))


def near(e: Any, d: Any, angle: bool) -> bool:
    """E = D to the comparisons' tolerance; an angle's real part modulo 2π."""
    if not angle:
        return close(e, d)
    gap = mpmath.re(e) - mpmath.re(d)
    turns = mpmath.nint(gap / (2 * mpmath.pi))
    return close(gap - 2 * mpmath.pi * turns, 0) and close(mpmath.im(e), mpmath.im(d))


def whole_turns(difference: Any) -> bool:
    """``difference`` is 2πk for an integer k."""
    with contextlib.suppress(TypeError, ValueError, AttributeError):
        turns = sympy.nsimplify(sympy.simplify(difference / (2 * sympy.pi)))
        return bool(turns.is_Integer)
    return False


def shown_point(point: dict[str, Any]) -> str:
    return ", ".join(f"{q} = {sympy.sstr(v)}" for q, v in point.items())


def hamiltonian_candidates(derivation: Derivation) -> list[tuple[str, Any, str]]:
    """H with −V; with a moving constraint (H = T2 − T0 + V, the Jacobi integral), T + V written in the momenta
    (named when T has no part linear in the velocities: it is then H with T0's sign flipped); the kinetic part
    T2(p) doubled or halved."""
    h, analysis = derivation.hamiltonian, derivation.analysis
    if h is None or analysis is None:
        return []
    potential = analysis.system.model.potential
    to_p = dict(zip(h.velocities, h.inverse, strict=True))
    t2, t1, t0 = (sympy.sympify(part, strict=True).xreplace(to_p) for part in h.kinetic_parts)
    out: list[tuple[str, Any, str]] = [(POTENTIAL_SIGN, h.expression - 2 * potential,
                                        "the potential has the wrong sign (H with −V)")]
    if t0 != 0:
        out.append(("missing_kinetic_term", h.expression + t0, f"the transport term −T0 = {sympy.sstr(-t0)} of the "
                                                               "moving frame is missing"))
        energy = "T + V written in the momenta, but with a moving constraint H = T2 − T0 + V (the Jacobi integral)"
        if t1 == 0:
            out.append((SIGN, h.expression + 2 * t0, f"it is {energy}: the term T0 = {sympy.sstr(t0)} has the "
                                                      "wrong sign"))
        else:
            out.append(("", t2 + t1 + t0 + potential, f"it is {energy}"))
    for k in (2, sympy.Rational(1, 2)):
        out.append((FACTOR_MISSING, h.expression + (k - 1) * t2, f"the kinetic part T2 in the momenta is {k} times "
                                                                   "the key's"))
    return out


def legendre(derivation: Derivation, lagrangian: Any) -> Any:
    """The Legendre transform of the student's L in the key's minimal coordinates (its constraints put in):
    p = A q̇ + b, H = ½ (p − b)ᵀ A⁻¹ (p − b) − L(q̇ = 0); None when L is not quadratic in the velocities."""
    h, analysis = derivation.hamiltonian, derivation.analysis
    if h is None or analysis is None or analysis.reduced is None:
        return None
    L = sympy.expand(analysis.reduced.substitution.apply(lagrangian))
    qd = list(h.velocities)
    zero = {v: 0 for v in qd}
    A = sympy.Matrix(len(qd), len(qd), lambda i, j: sympy.diff(L, qd[i], qd[j]))
    if any(entry.has(*qd) for entry in A) or A.det() == 0:
        return None
    b = sympy.Matrix([sympy.diff(L, v).xreplace(zero) for v in qd])
    w = sympy.Matrix(h.momentum_symbols) - b
    return (w.T * A.LUsolve(w))[0, 0] / 2 - L.xreplace(zero)


def reduction_constants(derivation: Derivation) -> dict[Any, Any]:
    """Each integration constant of the key's minimal coordinates (θ0 of θ = θ0, φ0 of φ = Ωt + φ0) as its
    coordinate gives it at a state (θ0 = θ, φ0 = φ − Ωt): the key's H is written with them, a state has the
    coordinates."""
    analysis = derivation.analysis
    if analysis is None or analysis.reduced is None:
        return {}
    reduced = analysis.reduced
    out: dict[Any, Any] = {}
    for q, position in reduced.substitution.positions.items():
        for constant in set(reduced.constants) & position.free_symbols:
            with contextlib.suppress(TypeError, ValueError, NotImplementedError):
                solved = sympy.solve(sympy.Eq(position, q), constant)
                if len(solved) == 1:
                    out[constant] = solved[0]
    return out
