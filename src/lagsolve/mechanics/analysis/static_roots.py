r"""Equilibria in closed form found cheaply: the equations at rest :math:`F(q, 0) = 0` taken apart, equation by
equation, before any general solve.

The exact steps, tried in this order on the equations left once the coordinates already fixed are put in:

1. **Split on a factor in one coordinate.** An equation :math:`a(q_k)\,b(q) = 0` holds where :math:`a = 0` (its
   roots: the zeros of :math:`\sin(c q_k)`, :math:`\cos(c q_k)`, :math:`\tan(c q_k)` in :math:`[0, 2\pi)`, else
   ``sympy.solve`` in that one coordinate, for at most :data:`ROOT_SOLVE_CAP` s of CPU) or where :math:`b = 0`;
   each case goes on by itself.
2. **Solve a linear equation.** An equation linear in a coordinate, with a coefficient free of coordinates, fixes
   it in terms of the others (two masses on a spring: :math:`x_1 = x_2 - L_0`, a continuum).
3. **Check what is left.** An equation with no coordinate left holds when it is proved zero; otherwise the case
   has no equilibrium (or has one only for special values of the parameters, which is not listed).

When none applies (the two pendulums joined by a spring: every equation holds both angles inside sines and
cosines), one coordinate is tried at its *obvious values*, the zeros of the sines and cosines of it that appear
(0, π; π/2, 3π/2) and 0 where it appears outside them, and each case goes on as above. Every point found is an
equilibrium: each step is exact and the last one proves every equation zero there. The list is *complete*
(every equilibrium, as ``sympy.solve`` would give them) unless a coordinate had to be tried at its obvious values
or a root in one coordinate was not found; equilibria elsewhere are then left to a general solve or to a numeric
search (:mod:`lagsolve.mechanics.analysis.linearize`).

Notes
-----
* Like ``sympy.solve``, an angle's roots are given in :math:`[0, 2\pi)`; the caller moves them into
  :math:`(-\pi, \pi]`.
* A root where a denominator of F vanishes is no equilibrium and is dropped (the final check fails there).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.mechanics.stages import StageTimeout, cpu_limit
from lagsolve.mechanics.symbolic.algebra import factor_terms, ops
from lagsolve.mechanics.symbolic.identities import proved_zero

#: the cases a search may visit before it stops and says it is not complete
MAX_CASES = 400

#: the largest integer multiple c of a coordinate whose sin(c q), cos(c q) zeros are listed directly
MAX_MULTIPLE = 4

#: the largest equation (operations) solved in one coordinate by ``sympy.solve``
ROOT_LIMIT = 80

#: CPU seconds ``sympy.solve`` may take on one equation in one coordinate (a root it does not find in that time is
#: not found: the search is then incomplete). A transcendental one, g sin θ + k θ = c, takes it well over 18 s;
#: the polynomial and trigonometric ones it solves take a few hundredths.
ROOT_SOLVE_CAP = 0.5

_TRIG = (sympy.sin, sympy.cos, sympy.tan)


@dataclass(frozen=True)
class StaticRoots:
    """What :func:`static_roots` found: the ``solutions`` (each maps the determined coordinates to their values,
    possibly in terms of the others, which are then free), whether they are ``complete``, and the coordinates
    that were ``tried`` at their obvious values (empty when none had to be)."""

    solutions: tuple[dict[Any, Any], ...]
    complete: bool
    tried: tuple[Any, ...] = ()


def static_roots(static: list[Any], coordinates: list[Any]) -> StaticRoots:
    """The equilibria :math:`F(q, 0) = 0` (``static``, one equation per coordinate) has in closed form, found by
    the steps of the module docstring.

    >>> import sympy
    >>> a, b = sympy.symbols("a b", real=True)
    >>> k, g = sympy.symbols("k g", positive=True)
    >>> spring = [-g*sympy.sin(a) - k*(sympy.sin(a) - sympy.sin(b))*sympy.cos(a),
    ...           -g*sympy.sin(b) + k*(sympy.sin(a) - sympy.sin(b))*sympy.cos(b)]
    >>> found = static_roots(spring, [a, b])
    >>> sorted((s[a], s[b]) for s in found.solutions)
    [(0, 0), (0, pi), (pi, 0), (pi, pi)]
    >>> found.complete, found.tried
    (False, (a,))
    """
    search = _Search(list(coordinates))
    equations = [_expanded(f) for f in static]
    search.run(equations, {})
    solutions = []
    for s in search.found:
        if s not in solutions and _holds(static, s):
            solutions.append(s)
    return StaticRoots(tuple(solutions), search.complete, tuple(q for q in coordinates if q in search.tried))


def _expanded(f: Any) -> Any:
    """``f`` as a sum of products of single angles (``sin(a - b)`` expanded), over a common denominator: only
    the numerator matters for its zeros."""
    if any(not a.args[0].is_Symbol for a in f.atoms(*_TRIG)):
        f = sympy.expand_trig(f)
    numerator, _ = sympy.fraction(sympy.together(f))
    return sympy.expand(numerator)


def _holds(static: list[Any], solution: dict[Any, Any]) -> bool:
    """Every equation of ``static`` is proved zero at ``solution`` (and finite there)."""
    for f in static:
        value = f.xreplace(solution)
        if value.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo) or not proved_zero(value):
            return False
    return True


class _Search:
    """The case split of :func:`static_roots`, depth first, in a fixed order (coordinates in input order)."""

    def __init__(self, coordinates: list[Any]) -> None:
        self.coordinates = coordinates
        self.found: list[dict[Any, Any]] = []
        self.complete = True
        self.tried: set[Any] = set()
        self.cases = 0

    def run(self, equations: list[Any], fixed: dict[Any, Any]) -> None:
        self.cases += 1
        if self.cases > MAX_CASES:
            self.complete = False
            return
        unknown = [q for q in self.coordinates if q not in fixed]
        live = []
        for e in equations:
            if e == 0:
                continue
            if not e.free_symbols & set(unknown):
                if not proved_zero(e):
                    return  # no equilibrium in this case (or one only for special parameter values)
                continue
            live.append(e)
        if not live:
            self.found.append(dict(fixed))
            return
        if self._split(live, fixed, unknown) or self._linear(live, fixed, unknown):
            return
        self._try(live, fixed, unknown)

    def _fix(self, equations: list[Any], fixed: dict[Any, Any], q: Any, value: Any) -> None:
        """Go on with ``q = value`` put into the equations and into the values already fixed (not when the value
        contradicts what ``q`` is declared to be: 0 for a positive coordinate)."""
        if (q.is_positive and value.is_positive is False) or (q.is_nonnegative and value.is_negative):
            return
        step = {q: value}
        moved = {k: v.xreplace(step) for k, v in fixed.items()}
        moved[q] = value
        self.run([sympy.expand(e.xreplace(step)) for e in equations], moved)

    def _split(self, live: list[Any], fixed: dict[Any, Any], unknown: list[Any]) -> bool:
        """Step 1: the first equation with a factor in one coordinate (fewest coordinates first)."""
        chosen = None
        for e in sorted(live, key=lambda e: (len(e.free_symbols & set(unknown)), live.index(e))):
            factors = _factors(e, unknown)
            single = [f for f in factors if len(f.free_symbols & set(unknown)) == 1]
            if single:
                chosen = (e, factors, single[0])
                break
        if chosen is None:
            return False
        e, factors, factor = chosen
        (q,) = factor.free_symbols & set(unknown)
        roots = _roots(factor, q)
        if roots is None:
            self.complete = False
            roots = []
        for r in roots:
            self._fix(live, fixed, q, r)
        rest = [f for f in factors if f is not factor]
        if rest:  # the case where the other factors vanish instead
            others = [x for x in live if x is not e]
            self.run([sympy.expand(sympy.Mul(*rest)), *others], fixed)
        return True

    def _linear(self, live: list[Any], fixed: dict[Any, Any], unknown: list[Any]) -> bool:
        """Step 2: the first equation linear in a coordinate with a coefficient free of coordinates."""
        for e in live:
            for q in unknown:
                if q not in e.free_symbols:
                    continue
                poly = e.as_poly(q)
                if poly is None or poly.degree() != 1:
                    continue
                slope, offset = poly.all_coeffs()
                if slope.free_symbols & set(unknown) or offset.has(q):
                    continue
                self._fix(live, fixed, q, sympy.cancel(-offset / slope))
                return True
        return False

    def _try(self, live: list[Any], fixed: dict[Any, Any], unknown: list[Any]) -> None:
        """The coordinate with the fewest obvious values, tried at each of them."""
        options = [(q, _obvious(live, q)) for q in unknown]
        options = [(q, values) for q, values in options if values]
        self.complete = False
        if not options:
            return
        q, values = min(options, key=lambda o: (len(o[1]), unknown.index(o[0])))
        self.tried.add(q)
        for value in values:
            self._fix(live, fixed, q, value)


def _factors(e: Any, unknown: list[Any]) -> list[Any]:
    """The distinct factors of ``e`` that hold an unknown coordinate (constant factors and powers dropped)."""
    out: list[Any] = []
    for f in sympy.Mul.make_args(factor_terms(e)):
        base, exp = f.as_base_exp()
        if not base.free_symbols & set(unknown) or not (exp.is_positive and exp.is_Integer):
            continue
        if base not in out:
            out.append(base)
    return out


def _multiple(argument: Any, q: Any) -> int | None:
    """c when ``argument`` is c·q with c a whole number from 1 to :data:`MAX_MULTIPLE`, else None."""
    c = argument / q
    if c.is_Integer and 1 <= int(c) <= MAX_MULTIPLE:
        return int(c)
    return None


def _trig_zeros(f: Any, q: Any) -> list[Any] | None:
    """The zeros in [0, 2π) of sin(c q), tan(c q) (kπ/c) and cos(c q) ((2k + 1)π/(2c)); None for other forms."""
    if not isinstance(f, _TRIG):
        return None
    c = _multiple(f.args[0], q)
    if c is None:
        return None
    if isinstance(f, sympy.cos):
        return [sympy.pi * (2 * k + 1) / (2 * c) for k in range(2 * c)]
    return [sympy.pi * k / c for k in range(2 * c)]


def _roots(factor: Any, q: Any) -> list[Any] | None:
    """The real roots of ``factor`` (which holds the one coordinate ``q``), or None when they are not found."""
    zeros = _trig_zeros(factor, q)
    if zeros is not None:
        return zeros
    if ops(factor) > ROOT_LIMIT:
        return None
    try:
        with cpu_limit(ROOT_SOLVE_CAP):
            roots = sympy.solve(factor, q)
    except (StageTimeout, NotImplementedError, ValueError, TypeError, sympy.PolynomialError):
        return None
    if any(isinstance(r, sympy.Set) or r.has(sympy.I) or r.free_symbols & {q} for r in roots):
        return None
    return list(roots)


def _obvious(live: list[Any], q: Any) -> list[Any]:
    """The obvious values of ``q`` in the equations ``live``: the zeros of each sine, cosine and tangent of a
    multiple of it, and 0 when it appears outside them; in [0, 2π), sorted."""
    values: set[Any] = set()
    hidden: dict[Any, Any] = {}
    for e in live:
        for a in e.atoms(*_TRIG):
            if q in a.free_symbols:
                hidden[a] = sympy.Dummy()
                values.update(_trig_zeros(a, q) or [])
    if any(q in e.xreplace(hidden).free_symbols for e in live):
        values.add(sympy.Integer(0))
    return sorted(values, key=lambda v: (float(v), sympy.default_sort_key(v)))


def same_solution(found: dict[Any, Any], known: dict[Any, Any]) -> bool:
    """``found`` (a point) is ``known`` or lies on it (a continuum whose free coordinates take ``found``'s values):
    each value of ``known``, with ``found``'s put in, equals ``found``'s exactly."""
    if set(known) - set(found):
        return False
    return all(proved_zero(sympy.expand(found[q] - v.xreplace(found))) for q, v in known.items())

