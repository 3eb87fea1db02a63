r"""Equilibria and small oscillations of a system with several degrees of freedom.

With the equations in matrix form :math:`M(q)\ddot q = F(q, \dot q)` (no explicit t),
equilibria solve :math:`F(q_0, 0) = 0`. Writing :math:`q = q_0 + \delta q` and keeping first
order terms,

.. math::
    M_0\,\delta\ddot q + (G + D)\,\delta\dot q + K\,\delta q = 0,\qquad
    K = -\frac{\partial F}{\partial q}\Big|_0,\quad
    C = -\frac{\partial F}{\partial\dot q}\Big|_0,\quad G = \tfrac12(C - C^T),\ D = \tfrac12(C + C^T),

with :math:`M_0 = M(q_0)`. Without gyroscopic (G) and damping (D) terms the normal modes
:math:`\delta q = u\,e^{i\omega t}` have :math:`\det(K - \omega^2 M_0) = 0`, i.e. the
:math:`\omega^2` are the eigenvalues of :math:`M_0^{-1}K`; the equilibrium is stable when all
of them are positive and unstable when one is negative.

Each normal mode has a shape u, :math:`(K - \omega^2 M_0)\,u = 0` (:mod:`lagsolve.mechanics.analysis.mode_shapes`).

The equilibria are found in closed form first without a general solve
(:mod:`lagsolve.mechanics.analysis.static_roots`: factors in one coordinate, linear equations, and, where neither
applies, the obvious values of a coordinate, each checked in :math:`F(q, 0) = 0`); only when that search
cannot tell it has found every equilibrium does ``sympy.solve`` get a short, bounded try
(:data:`GENERAL_SOLVE_CAP`), and
:func:`~lagsolve.mechanics.analysis.numeric_equilibria.complete_numerically` then looks for the others at the simulation
values.

Notes
-----
* Equilibria are found symbolically only for at most 3 coordinates; larger systems are skipped
  rather than risking a long solve.
* Normal modes are computed for up to 3 coordinates (a cubic in ω² at most); ω² are symbolic when the
  characteristic polynomial splits into real factors of degree 2 or less, else numeric at the simulation values.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.analysis.conserved import MotionSystem
from lagsolve.mechanics.analysis.mode_shapes import exact_shapes, numeric_shapes
from lagsolve.mechanics.analysis.static_roots import same_solution, static_roots
from lagsolve.mechanics.equations.lagrange import lagrange_terms
from lagsolve.mechanics.symbolic.algebra import ops
from lagsolve.mechanics.symbolic.identities import proved_zero
from lagsolve.mechanics.symbolic.signs import sign_core
from lagsolve.mechanics.symbolic.simplify import tidy

#: equations F(q, 0) larger than this (operations) are not given to ``sympy.solve``
SOLVE_LIMIT = 60
#: equations F(q, 0) larger than this (operations) are not taken apart either
SEARCH_LIMIT = 400
#: CPU seconds ``sympy.solve`` may take once the cheap search has found equilibria but cannot tell it found all
#: (every system it solves among the shipped problems takes under 0.1 s; the two pendulums joined by a spring
#: do not finish in 10 s)
GENERAL_SOLVE_CAP = 0.5
MAX_COORDINATES = 3
#: why a part of the analysis does not apply to a system the constraints leave no freedom
NO_FREEDOM = "no degrees of freedom: the constraints prescribe the motion"
MAX_EQUILIBRIA = 8


@dataclass(frozen=True)
class Mode:
    """Small oscillations about one equilibrium ``point`` (pairs (q, q0)).

    Matrices have shape (n, n): ``mass`` :math:`M_0`, ``gyroscopic`` G, ``damping`` D,
    ``stiffness`` K. ``squared_frequencies`` are the :math:`\\omega^2` (None when G or D is
    present or the characteristic polynomial is too large); ``frequencies`` their square
    roots (None for a negative one); ``stable`` True/False/None. ``free`` are the coordinates
    left arbitrary when the equilibria are not isolated (a continuum, e.g. two masses joined by a
    spring, translated together): ``point`` then gives the others in terms of them, and the
    zero ω² along the continuum is neutral, not a sign of instability. ``shapes`` holds one mode
    shape u per ω² (same order; None where ω² are not given or a shape is not found), with
    :math:`(K - \\omega^2 M_0)u = 0` and its first non-zero component 1.
    """

    point: tuple[tuple[Any, Any], ...]
    mass: sympy.ImmutableMatrix
    gyroscopic: sympy.ImmutableMatrix
    damping: sympy.ImmutableMatrix
    stiffness: sympy.ImmutableMatrix
    squared_frequencies: tuple[Any, ...] | None
    frequencies: tuple[Any, ...] | None
    stable: bool | None
    note: str = ""
    free: tuple[Any, ...] = ()
    shapes: tuple[tuple[Any, ...], ...] | None = None


@dataclass(frozen=True)
class Linearization:
    """Every equilibrium found for ``coordinates``, with its small-oscillation analysis. ``complete`` is False
    when equilibria other than these may exist in closed form; ``search`` then says how these were found and
    what was done about the others."""

    coordinates: tuple[Any, ...]
    modes: tuple[Mode, ...]
    search: str = ""
    complete: bool = True


def applies(system: MotionSystem, cyclic: tuple[Any, ...], friction: bool) -> str:
    """Why equilibria and normal modes do not apply to ``system`` ("" when they do); cheap, so that a
    part that cannot apply is skipped before anything is spent on it."""
    model = system.model
    if system.kind != "reduced":
        return "needs minimal coordinates (no constraint left)"
    if cyclic:
        return "the system has cyclic coordinates: its relative equilibria are not analysed here"
    if friction:
        return "Coulomb friction acts: equilibria are not isolated points"
    if not model.coordinates:
        return NO_FREEDOM
    if len(model.coordinates) < 2:
        return "one coordinate: see the effective potential"
    if model.lagrangian.has(model.time) and not proved_zero(sympy.diff(model.lagrangian, model.time)):
        return "L depends explicitly on the time"
    if any(f.has(model.time) for f in system.generalized_forces):
        return "the generalized forces depend on the time"
    return ""


def linearize(system: MotionSystem, cyclic: tuple[Any, ...], friction: bool,
              values: dict[str, float] | None = None, solve_cap: float | None = None
              ) -> tuple[Linearization | None, str]:
    """Equilibria and normal modes of ``system`` (module docstring), solved symbolically, or None and the reason.
    Where the characteristic polynomial does not split, the squared frequencies are numeric at the
    parameter ``values`` (when given). ``solve_cap``: CPU seconds a general symbolic solve may take when the
    cheap search found nothing (when numeric equilibria can be given instead); without it, all the stage has."""
    model = system.model
    n = len(model.coordinates)
    reason = applies(system, cyclic, friction)
    if reason:
        return None, reason
    if n > MAX_COORDINATES:
        return None, f"{n} coordinates (equilibria are solved symbolically for 2 to {MAX_COORDINATES})"
    terms = lagrange_terms(model, (), system.generalized_forces, engine="symengine")
    rest = {v: 0 for v in model.velocities}
    static = [tidy(f.xreplace(rest)) for f in terms.forcing]
    coordinates = list(model.coordinates)
    found = _equilibria(static, coordinates, solve_cap)
    if isinstance(found, str):
        return None, found
    solutions, complete, search = found
    points = set()
    for s in solutions:
        free = tuple(q for q in coordinates if q not in s)
        if any(v.has(sympy.I) or v.free_symbols & (set(s) - set(free)) for v in s.values()):
            continue
        points.add((tuple((q, _principal(s[q])) for q in coordinates if q in s), free))
    # where M is singular the coordinates themselves are (r = 0 in polar coordinates): F(q, 0) = 0 there only
    # because the equations were multiplied through by M, so such a point is no equilibrium of the motion
    mass = sympy.Matrix(terms.mass_matrix)
    points = {p for p in points if not _singular(mass.xreplace(dict(p[0])))}
    if not points:
        return None, "no isolated equilibrium was found in closed form"
    ordered = sorted(points, key=lambda p: (len(p[1]), sympy.default_sort_key(sympy.Tuple(*[v for _, v in p[0]]))))
    # K and C are wanted at rest only: K from F at rest (q̇ = 0 commutes with ∂/∂q), C by SymEngine
    K_all = -sympy.Matrix([f.xreplace(rest) for f in terms.forcing]).jacobian(coordinates)
    C_all = _damping_at_rest(terms.forcing, list(model.velocities))
    modes = tuple(_mode(point, terms.mass_matrix, K_all, C_all, rest, values, free)
                  for point, free in ordered[:MAX_EQUILIBRIA])
    return Linearization(model.coordinates, modes, search, complete), ""


def _equilibria(static: list[Any], coordinates: list[Any],
                solve_cap: float | None = None) -> tuple[list[dict[Any, Any]], bool, str] | str:
    """The solutions of F(q, 0) = 0 (``static``) in closed form, whether they are every one, and how they were
    found when not; or why none is given. Decoupled equations are solved one by one; otherwise the cheap search
    of :mod:`~lagsolve.mechanics.analysis.static_roots` goes first, and ``sympy.solve`` runs only when that search
    cannot
    tell it found everything (for at most :data:`GENERAL_SOLVE_CAP` s of CPU once the search has found some, else
    ``solve_cap`` when given)."""
    if all(f == 0 for f in static):
        return [{}], True, ""  # no force at rest anywhere: every configuration
    try:
        decoupled = _decoupled(static, coordinates)
    except (NotImplementedError, ValueError, TypeError):
        return "the equilibrium equations could not be solved symbolically"
    if decoupled is not None:
        return decoupled, True, ""
    if any(ops(f) > SEARCH_LIMIT for f in static):
        return "the equilibrium equations are too large to solve symbolically"
    roots = static_roots(static, coordinates)
    if roots.complete:
        return list(roots.solutions), True, ""
    small = all(ops(f) <= SOLVE_LIMIT for f in static)
    general, why = _general_solve(static, coordinates, GENERAL_SOLVE_CAP if roots.solutions else solve_cap) if small \
        else (None, "the equations are too large for a general symbolic solve")
    if general is not None:
        return general + [s for s in roots.solutions if not any(same_solution(s, g) for g in general)], True, ""
    if not roots.solutions:
        return ("the equilibrium equations are too large to solve symbolically" if not small
                else why if "did not finish" in why else "the equilibrium equations could not be solved symbolically")
    tried = ", ".join(q.name for q in roots.tried)
    how = (f"{tried} tried at {'their' if len(roots.tried) > 1 else 'its'} obvious values (the zeros of "
           f"{'their' if len(roots.tried) > 1 else 'its'} sines and cosines, 0 where it appears outside them) and "
           "F(q, 0) = 0 solved for the rest, each point checked") if tried else \
        "F(q, 0) = 0 taken apart factor by factor, but a root in one coordinate was not found"
    search = f"Found without a general solve: {how}; {why}, so other equilibria may exist"
    return list(roots.solutions), False, search


def _general_solve(static: list[Any], coordinates: list[Any],
                   cap: float | None) -> tuple[list[dict[Any, Any]] | None, str]:
    """``sympy.solve`` on the whole system (within ``cap`` CPU seconds, when given, and at most half of what the
    stage has left, so that a solve that does not finish leaves time for the rest), or None and why not."""
    import signal

    from lagsolve.mechanics.stages import StageTimeout, cpu_limit

    unbounded = "the general symbolic solve does not apply to these equations"
    if cap is None:  # nothing found otherwise: the solve may take the stage's whole share
        try:
            return sympy.solve(static, coordinates, dict=True), ""
        except (NotImplementedError, ValueError, TypeError):
            return None, unbounded
    left, _ = signal.getitimer(signal.ITIMER_PROF)  # the stage's own CPU limit, when one is armed
    seconds = min(cap, left / 2) if left > 0 else cap
    try:
        with cpu_limit(seconds):
            return sympy.solve(static, coordinates, dict=True), ""
    except StageTimeout:
        within = f"within {cap:g} s of CPU" if seconds == cap else "within its share of the stage's CPU time"
        return None, f"the general symbolic solve did not finish {within}"
    except (NotImplementedError, ValueError, TypeError):
        return None, unbounded


def _decoupled(static: list[Any], coordinates: list[Any]) -> list[dict[Any, Any]] | None:
    """The solutions ``sympy.solve(static, coordinates, dict=True)`` gives, found equation by equation when
    the equations are decoupled: each involves one coordinate, a different one for each (a chain of
    pendulums at rest, say). Every combination of the roots of each equation is then a solution. A factor
    that is a power of ``sin(q)`` or ``cos(q)`` has the roots ``sympy.solve`` gives (0, π; π/2, 3π/2),
    without its search; any other equation is solved in its coordinate alone. None when the equations are
    not decoupled (the system is then solved as a whole)."""
    if len(static) != len(coordinates) or any(f == 0 for f in static):
        return None
    chosen = set(coordinates)
    owner: dict[Any, Any] = {}
    for f in static:
        involved = f.free_symbols & chosen
        if len(involved) != 1:
            return None
        (q,) = involved
        if q in owner:
            return None
        owner[q] = f
    roots = []
    for q in coordinates:
        f = owner[q]
        varying = [a for a in sympy.Mul.make_args(f) if a.has(q)]
        base, exp = varying[0].as_base_exp() if len(varying) == 1 else (sympy.S.Zero, sympy.S.Zero)
        if exp.is_Integer and exp > 0 and base in (sympy.sin(q), sympy.cos(q)):
            roots.append(_TRIG_ROOTS[base.func])
        else:
            roots.append(sympy.solve(f, q))
    return [dict(zip(coordinates, combination, strict=True)) for combination in itertools.product(*roots)]


#: the roots ``sympy.solve`` gives for sin(q) = 0 and cos(q) = 0
_TRIG_ROOTS: dict[Any, list[Any]] = {
    sympy.sin: [sympy.Integer(0), sympy.pi],
    sympy.cos: [sympy.pi / 2, 3 * sympy.pi / 2],
}


def _continuum_note(free: tuple[Any, ...], n: int) -> str:
    """The note of a continuum of equilibria with the coordinates ``free`` left arbitrary."""
    if len(free) == n:
        return "every configuration is an equilibrium (no force acts at rest)"
    names = ", ".join(q.name for q in free)
    return f"a continuum of equilibria: {names} {'is' if len(free) == 1 else 'are'} arbitrary"


def _principal(value: Any) -> Any:
    """An angle-like value moved into (-π, π] when that makes it shorter (``2*pi - a`` → ``-a``)."""
    if value.has(sympy.pi) and ops(value - 2 * sympy.pi) < ops(value):
        return value - 2 * sympy.pi
    return value


def _mode(point: tuple[tuple[Any, Any], ...], mass: Any, K_all: Any, C_all: Any, rest: dict[Any, Any],
          values: dict[str, float] | None = None, free: tuple[Any, ...] = ()) -> Mode:
    """The equilibrium ``point`` with M₀, G, D and K there and, without gyroscopic or damping terms, its normal
    modes; on a continuum (the coordinates ``free``) its stability is left open and the note says so."""
    at = {**dict(point), **rest}
    M0 = sympy.Matrix(mass).xreplace(at).applyfunc(tidy)
    K = K_all.xreplace(at).applyfunc(tidy)
    C = C_all.xreplace(at).applyfunc(tidy)
    G = ((C - C.T) / 2).applyfunc(tidy)
    D = ((C + C.T) / 2).applyfunc(tidy)
    squares = frequencies = shapes = None
    stable = None
    note = ""
    if any(e != 0 for e in (*G, *D)):
        note = "gyroscopic or damping terms: normal modes are not computed"
    else:
        squares, frequencies, stable, shapes, note = _normal_modes(M0, K, values)
    if free:
        # along the continuum ω² = 0 is neutral: stable only in the other directions, so not decided here
        stable = None if stable is not False else False
        note = _continuum_note(free, K.rows) + (f"; {note}" if note else "")
    return Mode(point, sympy.ImmutableMatrix(M0), sympy.ImmutableMatrix(G), sympy.ImmutableMatrix(D),
                sympy.ImmutableMatrix(K), squares, frequencies, stable, note, free, shapes)


def _normal_modes(M0: Any, K: Any, values: dict[str, float] | None) -> tuple[Any, Any, bool | None, Any, str]:
    """The ω² (roots of det(K - ω² M₀)), ω, stability, mode shapes and a note: exact when the characteristic
    polynomial splits into real factors of degree 2 or less, else numeric at the simulation ``values`` (none
    without them)."""
    s = sympy.Dummy("s")
    # the Poly is canonical, however the determinant is written: Berkowitz's is the quickest to write
    polynomial = sympy.Poly(_determinant(K - s * M0), s)
    roots = sympy.roots(polynomial) if _splits(polynomial, s) else {}
    if sum(roots.values()) != polynomial.degree() or any(r.has(sympy.I) for r in roots):
        # Cardano's radicals of a real frequency carry complex numbers: a numeric ω² says more
        return _numeric_modes(M0, K, values)
    return _exact_modes(M0, K, roots, values)


def _numeric_modes(M0: Any, K: Any, values: dict[str, float] | None) -> tuple[Any, Any, bool | None, Any, str]:
    """:func:`_normal_modes` at the simulation ``values``, for a characteristic polynomial that does not split."""
    note = "the characteristic polynomial does not split into real factors of degree 2 or less"
    numeric = _numeric_squares(M0, K, values)
    if numeric is None:
        return None, None, None, None, note
    squares, stable, frequencies, shapes = numeric
    return squares, frequencies, stable, shapes, note + "; ω² and the mode shapes are numeric, at the simulation values"


def _exact_modes(M0: Any, K: Any, roots: dict[Any, int], values: dict[str, float] | None
                 ) -> tuple[Any, Any, bool | None, Any, str]:
    """:func:`_normal_modes` from the exact ``roots`` (with their multiplicities): ω for each positive ω², and
    the mode shapes exact, else numeric at the simulation ``values`` (the note says so)."""
    ordered = sorted((tidy(r) for r, k in roots.items() for _ in range(k)), key=sympy.default_sort_key)
    squares = tuple(ordered)
    signs, stable = _signs(M0, K, squares)
    frequencies = tuple(tidy(sympy.sqrt(r)) if x == 1 else None for r, x in zip(squares, signs, strict=True))
    note = ""
    shapes = exact_shapes(M0, K, squares)
    if shapes is None:
        shapes = _numeric_shapes_at(M0, K, squares, values)
        if shapes is not None:
            note = "the mode shapes are numeric, at the simulation values"
    return squares, frequencies, stable, shapes, note


def _signs(M0: Any, K: Any, squares: tuple[Any, ...]) -> tuple[list[int | None], bool | None]:
    """The sign of each ω² (None where undecided; K's definiteness decides those its factors leave open), and
    whether the equilibrium is stable: not when an ω² is negative, yes when every one is positive, else None."""
    signs = [sign_core(r)[0] for r in squares]
    stable = None
    if None in signs and -1 not in signs:
        definite = _definiteness(M0, K)
        if definite == 1:
            signs = [1] * len(signs)  # K positive definite: every ω² is positive
        elif definite == -1:
            signs = [-1 if x is None else x for x in signs] if signs.count(None) == 1 else signs
            stable = False
    if stable is None:
        stable = False if -1 in signs else (True if all(x == 1 for x in signs) else None)
    return signs, stable


def _numeric_shapes_at(M0: Any, K: Any, squares: tuple[Any, ...],
                       values: dict[str, float] | None) -> tuple[tuple[Any, ...], ...] | None:
    """The mode shapes of the exact ``squares`` at the parameter ``values`` (floats), or None."""
    numbers = _at_values((M0, K, sympy.Matrix(squares)), values)
    if numbers is None:
        return None
    m0, k0, w = numbers
    found = numeric_shapes(m0, k0, [float(x) for x in w.ravel()])
    return None if found is None else tuple(tuple(sympy.Float(x, 8) for x in u) for u in found)


def _at_values(matrices: tuple[Any, ...], values: dict[str, float] | None) -> tuple[Any, ...] | None:
    """``matrices`` as float arrays at the parameter ``values``; None when a symbol has no value."""
    import numpy as np

    if not values:
        return None
    symbols = set().union(*(m.free_symbols for m in matrices))
    at = {s: sympy.Float(values[s.name]) for s in symbols if s.name in values}
    out = []
    for m in matrices:
        e = m.xreplace(at)
        if e.free_symbols:
            return None
        try:
            out.append(np.array(e.tolist(), dtype=float))
        except TypeError:
            return None
    return tuple(out)


def _definiteness(M0: Any, K: Any) -> int | None:
    r"""+1 when every ω² of :math:`\det(K - \omega^2 M_0) = 0` is positive, -1 when one is negative, None when
    that is not decided. With :math:`M_0` positive definite (its leading principal minors positive), the ω²
    have the signs of K's eigenvalues (Sylvester's law of inertia): all positive when K's leading principal
    minors are (Sylvester's criterion), one negative at least when a diagonal entry of K is negative
    (:math:`e_i^T K e_i < 0`) or det K is (an odd number of negative eigenvalues). The general double
    pendulum's ω² at rest, :math:`g(S \mp \sqrt{R})/(2 m_1 l_1 l_2)`, have no sign the factors alone
    give; its K = diag(...) has."""
    n = K.rows

    def minors(matrix: Any) -> list[int | None]:
        return [sign_core(_determinant(matrix[:k, :k]))[0] for k in range(1, n + 1)]  # sign_core factors

    if any(x != 1 for x in minors(M0)):
        return None
    if all(x == 1 for x in minors(K)):
        return 1
    if any(sign_core(K[i, i])[0] == -1 for i in range(n)) or sign_core(_determinant(K))[0] == -1:
        return -1
    return None


def _exact(matrix: Any) -> Any:
    """``matrix`` as a DomainMatrix over the integers, the rationals or polynomials over them, else None."""
    from sympy.polys.matrices import DomainMatrix

    fast = _over_integers(matrix)
    if fast is not None:
        return fast
    try:
        dm = DomainMatrix.from_Matrix(sympy.Matrix(matrix))
    except (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError, NotImplementedError):
        return None
    ring = dm.domain
    if ring.is_ZZ or ring.is_QQ or (ring.is_PolynomialRing and (ring.domain.is_ZZ or ring.domain.is_QQ)):
        return dm
    return None


def _over_integers(matrix: Any) -> Any:
    """``matrix`` as a DomainMatrix over the polynomials with integer coefficients in its symbols (sorted by name),
    or None when an entry is no such polynomial. The ring is built once for each set of symbols: SymPy's own
    construction finds it again for every matrix, at ten times the cost of the determinant itself (K - s M0 at
    each equilibrium)."""
    from sympy.polys.matrices import DomainMatrix

    rows = sympy.Matrix(matrix).tolist()
    symbols = tuple(sorted({s for row in rows for e in row for s in e.free_symbols}, key=sympy.default_sort_key))
    if not symbols or any(not s.is_Symbol for s in symbols):
        return None
    ring = _integer_ring(symbols)
    try:
        entries = [[ring.from_sympy(e) for e in row] for row in rows]
    except (sympy.CoercionFailed, sympy.PolynomialError, ValueError, TypeError):
        return None
    return DomainMatrix(entries, (len(rows), len(rows[0]) if rows else 0), ring)


@functools.lru_cache(maxsize=64)
def _integer_ring(symbols: tuple[Any, ...]) -> Any:
    return sympy.ZZ[symbols]


def _determinant(matrix: Any) -> Any:
    """det(``matrix``) (the same polynomial whatever way it is written: only its Poly is used), in a polynomial
    ring where the entries allow it (many times faster than SymPy expressions), else by Berkowitz's method."""
    dm = _exact(matrix)
    if dm is None:
        return sympy.Matrix(matrix).det(method="berkowitz")
    return dm.domain.to_sympy(dm.det())


def _singular(matrix: Any) -> bool:
    """det(``matrix``) is identically zero (exactly, in a polynomial ring, where the entries allow it)."""
    dm = _exact(matrix)
    if dm is None:
        return proved_zero(sympy.Matrix(matrix).det(method="berkowitz"))
    return bool(dm.det() == dm.domain.zero)


def _splits(polynomial: sympy.Poly, s: Any) -> bool:
    """Every factor of ``polynomial`` (in ``s``) has degree 2 or less, as ``sympy.factor_list`` finds.

    A polynomial of degree 2 or less needs no factoring. Otherwise it is first looked at with its parameters
    set to distinct primes: a factorization in ``s`` keeps the degree of each factor wherever the leading
    coefficient does not vanish, so when that integer polynomial (of the same degree) is irreducible the
    parameters' one is too, and factoring it in all its parameters would only say so more slowly."""
    degree = polynomial.degree()
    if degree <= 2:
        return True
    parameters = sorted(polynomial.free_symbols - {s}, key=sympy.default_sort_key)
    primes = {p: sympy.Integer(sympy.prime(30 + k)) for k, p in enumerate(parameters)}
    try:
        special = sympy.Poly(polynomial.as_expr().xreplace(primes), s)
        if special.degree() == degree and (special.domain.is_ZZ or special.domain.is_QQ):
            _, factors = special.factor_list()
            if len(factors) == 1 and factors[0][0].degree() == degree:
                return False
    except (sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
        pass
    return all(f.degree() <= 2 for f, _ in sympy.factor_list(polynomial)[1])


def _numeric_squares(M0: Any, K: Any, values: dict[str, float] | None) -> tuple[Any, bool | None, Any, Any] | None:
    """The eigenvalues of :math:`M_0^{-1}K` at the parameter ``values``, their stability, square roots and mode
    shapes."""
    import numpy as np

    numbers = _at_values((M0, K), values)
    if numbers is None:
        return None
    m0, k0 = numbers
    eig = np.sort(np.linalg.eigvals(np.linalg.solve(m0, k0)).real)
    squares = tuple(sympy.Float(float(e), 8) for e in eig)
    stable = bool(np.all(eig > 1e-12)) if np.all(np.abs(eig) > 1e-12) else None
    found = numeric_shapes(m0, k0, [float(e) for e in eig])
    shapes = None if found is None else tuple(tuple(sympy.Float(x, 8) for x in u) for u in found)
    return squares, stable, tuple(sympy.Float(float(np.sqrt(e)), 8) if e > 1e-12 else None for e in eig), shapes


def _damping_at_rest(forcing: Any, velocities: list[Any]) -> sympy.Matrix:
    r""":math:`-\partial F/\partial\dot q` at :math:`\dot q = 0`, differentiated with SymEngine where it can
    (the derivative of the whole of F is the dear part of the numeric search; only its values are used,
    to tell whether damping or gyroscopic terms act)."""
    rest = {v: 0 for v in velocities}
    if not any(f.atoms(sympy.core.function.AppliedUndef) or f.has(sympy.Derivative) for f in forcing):
        try:
            from symengine.lib.symengine_wrapper import sympy2symengine

            own = {s.name: s for f in forcing for s in f.free_symbols}
            engine_v = [sympy2symengine(v) for v in velocities]
            at_rest = dict.fromkeys(engine_v, 0)

            def back(expr: Any) -> Any:
                value = expr._sympy_()  # a SymEngine object, never text
                return value.xreplace({s: own[s.name] for s in value.free_symbols})

            return sympy.Matrix([[back((-sympy2symengine(f).diff(v)).subs(at_rest)) for v in engine_v]
                                 for f in forcing])
        except (ImportError, RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
            pass
    return (-sympy.Matrix(forcing).jacobian(velocities)).xreplace(rest)
