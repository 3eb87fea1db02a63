r"""Equilibria and normal modes found numerically, at the file's simulation values.

:func:`numeric_linearization` finds the equilibria of a system with several coordinates where no closed form is
had in time: Newton's method on :math:`F(q, 0) = 0` from :data:`STARTS` starting points, then :math:`M_0`, K, the
:math:`\omega^2` (eigenvalues of :math:`M_0^{-1}K`) and the mode shapes at each, every one a floating-point number.
:func:`complete_numerically` looks, the same way, for the equilibria a list found in closed form may miss
(:mod:`lagsolve.mechanics.analysis.linearize`, when the equilibria were found without a general solve).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import sympy

from lagsolve.mechanics.analysis.conserved import MotionSystem
from lagsolve.mechanics.analysis.linearize import MAX_EQUILIBRIA, Linearization, Mode, _damping_at_rest
from lagsolve.mechanics.analysis.mode_shapes import numeric_shapes
from lagsolve.mechanics.equations.lagrange import lagrange_terms
from lagsolve.mechanics.stages import StageSkipped
from lagsolve.mechanics.symbolic.partials import BULK_SYSTEM, to_engine

#: how many starting points the numeric search for equilibria tries (:data:`BULK_STARTS` for a bulk system)
STARTS = 64
BULK_STARTS = 16
#: how a report names that search
NUMERIC_SEARCH = f"the numeric search at the simulation values ({STARTS} starting points)"


class NoEquilibriumFound(StageSkipped):  # noqa: N818 - a reason, not an error
    """The numeric search ran and found no equilibrium (not a search that could not run)."""


def numeric_linearization(system: MotionSystem, values: dict[str, float], initial: dict[str, float]) -> Linearization:
    r"""Equilibria and normal modes of ``system`` at the parameter ``values``, found numerically.

    The equilibria solve :math:`F(q_0, 0) = 0` by Newton's method (``scipy.optimize.root``) from
    :data:`STARTS` starting points around the ``initial`` state (angles anywhere in
    :math:`(-\pi, \pi]`, the same points on every run); the squared frequencies are the eigenvalues
    of :math:`M_0^{-1}K`. Every result is a floating-point number, and the note says so.

    Raises
    ------
    StageSkipped
        When a parameter has no value; :class:`NoEquilibriumFound` when no equilibrium is found.
    """
    import numpy as np

    model = system.model
    functions = _lambdified(system, values)
    found = _search(functions, initial)
    if not found:
        raise NoEquilibriumFound(f"no equilibrium found numerically from {STARTS} starting points")
    found.sort(key=lambda p: (float(np.sum(p**2)), tuple(p)))
    modes = [_numeric_mode(functions, point) for point in found[:MAX_EQUILIBRIA]]
    # a search from starting points proves no list complete (a continuum is found as some of its points)
    return Linearization(model.coordinates, tuple(modes), complete=False)


@dataclasses.dataclass(frozen=True)
class _Lambdified:
    """The numeric functions of the coordinates at rest that the search and the modes evaluate: F(q, 0), its
    Jacobian (-K), M and the damping matrix, and which coordinates are angles."""

    coordinates: list[Any]
    static: Any
    jacobian: Any
    mass: Any
    damping: Any
    angles: list[bool]


def _lambdified(system: MotionSystem, values: dict[str, float]) -> _Lambdified:
    """F(q, 0), its Jacobian, M and the damping matrix at rest with the parameter ``values`` put in, as numeric
    functions of the coordinates; :class:`StageSkipped` when a parameter has no value."""
    model = system.model
    q, qd = list(model.coordinates), list(model.velocities)
    terms = lagrange_terms(model, (), system.generalized_forces, engine="symengine")
    params = {s: sympy.Float(values[s.name]) for s in model.lagrangian.free_symbols | set().union(
        *(f.free_symbols for f in system.generalized_forces)) if s.name in values}
    engine = _engine_functions(terms.forcing, terms.mass_matrix, q, qd, params)
    if engine is not None:
        static_f, jacobian_f, mass_f, damping_f = engine
        return _Lambdified(q, static_f, jacobian_f, mass_f, damping_f, periodic([*terms.forcing, *terms.mass_matrix],
                                                                                q))
    rest = {v: 0 for v in qd}
    static = sympy.Matrix(terms.forcing).xreplace(rest).xreplace(params)
    mass = sympy.Matrix(terms.mass_matrix).xreplace(params)
    _check_values(static.free_symbols | mass.free_symbols, q)
    stiffness = -static.jacobian(q)
    damping_all = _damping_at_rest(terms.forcing, qd).xreplace(params)
    return _Lambdified(q, sympy.lambdify([q], list(static), "numpy"), sympy.lambdify([q], stiffness * -1, "numpy"),
                       sympy.lambdify([q], mass, "numpy"), sympy.lambdify([q], damping_all, "numpy"),
                       periodic([*static, *mass], q))


def _check_values(symbols: set[Any], q: list[Any]) -> None:
    names = {getattr(s, "name", str(s)) for s in symbols} - {c.name for c in q}
    if names:
        raise StageSkipped(f"needs values for {', '.join(sorted(names))} (simulation.values)")


def _engine_functions(forcing: Any, mass: Any, q: list[Any], qd: list[Any],
                      params: dict[Any, Any]) -> tuple[Any, ...] | None:
    """F(q, 0), ∂F/∂q there, M and −∂F/∂q̇ at rest with the parameter values put in, as numeric functions of q,
    all done by SymEngine (a few hundredths of a second, where SymPy's substitution, Jacobian and ``lambdify`` of a
    20-link chain take seconds); None where SymEngine cannot compile them (a declared function, the derivative of
    an ``Abs``): SymPy's route then. The values are the same; only the work differs."""
    import numpy as np

    try:  # a declared function or a derivative SymEngine keeps unevaluated does not compile: RuntimeError
        import symengine
        from symengine.lib.symengine_wrapper import sympy2symengine

        eq, ev = [sympy2symengine(x) for x in q], [sympy2symengine(v) for v in qd]
        values = {sympy2symengine(k): symengine.RealDouble(float(v)) for k, v in params.items()}
        at_rest = dict.fromkeys(ev, 0)
        engine_forcing = [to_engine(e).subs(values) for e in forcing]
        f_static = symengine.Matrix([f.subs(at_rest) for f in engine_forcing])
        f_mass = symengine.Matrix(mass.shape[0], mass.shape[1], [to_engine(e).subs(values) for e in mass])
        free = set().union(*(e.free_symbols for e in [*f_static, *f_mass]))
        f_jac = f_static.jacobian(symengine.Matrix(eq))
        f_damp = symengine.Matrix(len(forcing), len(qd), [(-f.diff(v)).subs(at_rest) for f in engine_forcing
                                                            for v in ev])
        compiled = [symengine.Lambdify(eq, list(m), cse=True) for m in (f_static, f_jac, f_mass, f_damp)]
    except (ImportError, RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return None
    _check_values(free, q)
    n = len(q)
    shapes = [(n,), (n, n), tuple(mass.shape), (len(forcing), len(qd))]

    def numeric(function: Any, shape: tuple[int, ...]) -> Any:
        return lambda x: np.asarray(function(np.asarray(x, dtype=float)), dtype=float).reshape(shape)

    return tuple(numeric(f, shape) for f, shape in zip(compiled, shapes, strict=True))


def _search(functions: _Lambdified, initial: dict[str, float]) -> list[Any]:
    """The distinct equilibria Newton's method reaches from :data:`STARTS` starting points: the ``initial`` state,
    then points around it (each coordinate moved by up to π, the same points on every run). A bulk system has
    equilibria in every combination of its coordinates' (2ⁿ for a chain), which random starts land on at random: it
    tries :data:`BULK_STARTS`, the origin (where a chain hangs) second, by Newton's own steps (:func:`_newton`)
    rather than SciPy's ``root``, whose import alone costs more than the search."""
    import numpy as np

    q = functions.coordinates
    bulk = len(q) > BULK_SYSTEM
    solve = _newton if bulk else _hybrid
    rng = np.random.default_rng(0)
    centre = np.array([float(initial.get(c.name, 0.0)) for c in q])
    found: list[np.ndarray] = []
    for k in range(BULK_STARTS if bulk else STARTS):
        start = centre if k == 0 else np.zeros(len(q)) if bulk and k == 1 else centre + rng.uniform(-np.pi, np.pi,
                                                                                                      len(q))
        with np.errstate(all="ignore"):
            x = solve(functions, start)
        if x is None or not np.all(np.isfinite(x)):
            continue
        point = _tidy(x, functions.angles)
        if _new_equilibrium(functions, point, found):
            found.append(point)
    return found


def _hybrid(functions: _Lambdified, start: Any) -> Any | None:
    """A root of F(q, 0) from ``start`` by SciPy's ``root`` (Powell's hybrid method), or None."""
    import numpy as np
    from scipy.optimize import root

    sol = root(lambda x: np.asarray(functions.static(x), dtype=float), start,
               jac=lambda x: np.asarray(functions.jacobian(x), dtype=float), method="hybr")
    return sol.x if sol.success else None


#: Newton steps (:func:`_newton`) before a start is given up, and the longest step (radians or lengths)
NEWTON_STEPS = 50
NEWTON_STRIDE = 1.0


def _newton(functions: _Lambdified, start: Any) -> Any | None:
    """A root of F(q, 0) from ``start`` by Newton's method, each step at most :data:`NEWTON_STRIDE` long, or None
    (no convergence in :data:`NEWTON_STEPS` steps, a singular Jacobian); :func:`_new_equilibrium` checks it."""
    import numpy as np

    x = np.array(start, dtype=float)
    for _ in range(NEWTON_STEPS):
        residual = np.asarray(functions.static(x), dtype=float)
        if np.max(np.abs(residual)) < 1e-12:
            return x
        try:
            step = np.linalg.solve(np.asarray(functions.jacobian(x), dtype=float), -residual)
        except np.linalg.LinAlgError:
            return None
        size = float(np.max(np.abs(step)))
        x = x + (step if size <= NEWTON_STRIDE else step * (NEWTON_STRIDE / size))
    return x if np.max(np.abs(np.asarray(functions.static(x), dtype=float))) < 1e-9 else None


def _tidy(x: Any, angles: list[bool]) -> Any:
    """A root as an equilibrium is shown: angles in (-π, π], ±π as π, and the root finder's noise about 0 as 0."""
    import numpy as np

    point = np.array([(v + np.pi) % (2 * np.pi) - np.pi if angles[i] else v for i, v in enumerate(x)])
    periodic_mask = np.array(angles, dtype=bool)  # only an angle is periodic: a length near ±π stays as it is
    point = np.where(periodic_mask & np.isclose(np.abs(point), np.pi, atol=1e-7), np.pi, point)
    return np.where(np.abs(point) < 1e-7, 0.0, point)  # the root finder's own noise


def _new_equilibrium(functions: _Lambdified, point: Any, found: list[Any]) -> bool:
    """Whether a root is an equilibrium to add: F(q, 0) vanishes there, it is none of ``found``, M is regular
    there, and it is not a second point of a continuum of equilibria."""
    import numpy as np

    f_static, f_jac = functions.static, functions.jacobian
    if np.max(np.abs(np.asarray(f_static(point), dtype=float))) > 1e-9:
        return False
    if any(np.allclose(point, p, atol=1e-7) for p in found):
        return False
    if np.linalg.cond(np.asarray(functions.mass(point), dtype=float)) > 1e12:
        return False  # a singular point of the coordinates (M singular), not an equilibrium of the motion
    # the multi-start lands anywhere on a continuum: one point of it is shown
    return not (_on_continuum(f_static, -np.asarray(f_jac(point), dtype=float), point) and any(
        _on_continuum(f_static, -np.asarray(f_jac(p), dtype=float), p) for p in found))


def _numeric_mode(functions: _Lambdified, point: Any) -> Mode:
    """The equilibrium at ``point`` with M₀, K, its squared frequencies, stability and mode shapes, every entry a
    floating-point number; no frequencies where gyroscopic or damping terms act."""
    import numpy as np

    q = functions.coordinates
    m0 = np.asarray(functions.mass(point), dtype=float)
    k0 = -np.asarray(functions.jacobian(point), dtype=float)
    c0 = np.asarray(functions.damping(point), dtype=float)
    squares = frequencies = shapes = None
    stable = None
    note = "numeric, at the simulation values"
    continuum = _on_continuum(functions.static, k0, point)
    if continuum:
        note = "not isolated: one point of a continuum of equilibria (K is singular along it); " + note
    if np.max(np.abs(c0)) > 1e-12:
        note += "; gyroscopic or damping terms: normal modes are not computed"
    else:
        squares, frequencies, stable, shapes = _spectrum(m0, k0, continuum)
    return Mode(tuple((c, sympy.Float(float(v), 8)) for c, v in zip(q, point, strict=True)),
                sympy.ImmutableMatrix(m0.tolist()).applyfunc(lambda e: sympy.Float(e, 8)),
                sympy.ImmutableMatrix(sympy.zeros(len(q))), sympy.ImmutableMatrix(sympy.zeros(len(q))),
                sympy.ImmutableMatrix(k0.tolist()).applyfunc(lambda e: sympy.Float(e, 8)),
                squares, frequencies, stable, note, shapes=shapes)


def _spectrum(m0: Any, k0: Any, continuum: bool) -> tuple[Any, Any, bool | None, Any]:
    """The squared frequencies (eigenvalues of M₀⁻¹K), the frequencies (None for a non-positive one), whether the
    equilibrium is stable (None when a zero eigenvalue leaves it open; unstable on a continuum with a negative
    one) and the mode shapes."""
    import numpy as np

    eig = np.sort(np.linalg.eigvals(np.linalg.solve(m0, k0)).real)
    squares = tuple(sympy.Float(float(e), 8) for e in eig)
    stable = bool(np.all(eig > 1e-12)) if np.all(np.abs(eig) > 1e-12) else None
    if continuum and stable is None and np.any(eig < -1e-12):
        stable = False
    frequencies = tuple(sympy.Float(float(np.sqrt(e)), 8) if e > 1e-12 else None for e in eig)
    found_shapes = numeric_shapes(m0, k0, [float(e) for e in eig])
    shapes = None if found_shapes is None else tuple(tuple(sympy.Float(x, 8) for x in u) for u in found_shapes)
    return squares, frequencies, stable, shapes


def periodic(exprs: list[Any], coordinates: list[Any]) -> list[bool]:
    """Whether each coordinate appears in ``exprs`` only inside sines and cosines (an angle: its equilibria are
    the same modulo 2π)."""
    outside: set[Any] = set()
    seen: set[Any] = set()
    stack = list(exprs)
    while stack:  # the symbols met outside every sine and cosine (each subexpression visited once)
        node = stack.pop()
        if node in seen or isinstance(node, sympy.sin | sympy.cos):
            continue
        seen.add(node)
        if node.is_Symbol:
            outside.add(node)
        stack.extend(node.args)
    return [c not in outside for c in coordinates]


def complete_numerically(linear: Linearization, system: MotionSystem, values: dict[str, float],
                         initial: dict[str, float]) -> Linearization:
    """``linear``, whose equilibria in closed form may not be all (``complete`` False), with the numeric search of
    :func:`numeric_linearization` run at the simulation ``values``: each equilibrium it finds that is none of
    ``linear``'s there (angles modulo 2π; a continuum's points count as it) is added after them, numeric and
    labelled so, and ``search`` says what the numeric search found."""
    try:
        numeric = numeric_linearization(system, values, initial)
    except NoEquilibriumFound:
        numeric = Linearization(linear.coordinates, ())
    except StageSkipped as reason:
        return dataclasses.replace(linear, search=f"{linear.search}; no numeric search for them: {reason}")
    q = list(linear.coordinates)
    terms = lagrange_terms(system.model, (), system.generalized_forces, engine="symengine")
    at_rest = {v: 0 for v in system.model.velocities}
    angles = periodic([*(f.xreplace(at_rest) for f in terms.forcing), *terms.mass_matrix], q)
    extra = [dataclasses.replace(m, note=f"not found in closed form; {m.note}") for m in numeric.modes
             if not any(_same_point(m, known, values, angles) for known in linear.modes)]
    room = max(0, MAX_EQUILIBRIA - len(linear.modes))
    found = (f"finds {len(extra)} more, given numerically below" if extra else "finds no other")
    search = f"{linear.search}; {NUMERIC_SEARCH} {found}"
    return dataclasses.replace(linear, modes=linear.modes + tuple(extra[:room]), search=search)


def _same_point(numeric: Mode, known: Mode, values: dict[str, float], angles: list[bool]) -> bool:
    """The numeric equilibrium ``numeric`` is ``known`` (a point or a continuum in closed form) at the parameter
    ``values``: each value of ``known``, with the numbers put in, equals ``numeric``'s (modulo 2π for an angle)."""
    import numpy as np

    point = dict(numeric.point)
    numbers = {s: sympy.Float(values[s.name]) for v in dict(known.point).values() for s in v.free_symbols
               if s.name in values}
    numbers |= {c: point[c] for c in known.free}
    for i, c in enumerate(numeric.point):
        coordinate, value = c
        if coordinate in known.free:
            continue
        try:
            expected = complex(dict(known.point)[coordinate].xreplace(numbers))
        except (TypeError, KeyError):
            return False
        if abs(expected.imag) > 1e-9:
            return False
        gap = float(value) - expected.real
        if angles[i]:
            gap = (gap + np.pi) % (2 * np.pi) - np.pi
        if abs(gap) > 1e-6 * max(1.0, abs(expected.real)):
            return False
    return True


def _on_continuum(f_static: Any, stiffness: Any, point: Any) -> bool:
    """Whether the equilibrium ``point`` is not isolated: K is singular there and F(q, 0) stays 0 along
    its null directions (checked a small step away on both sides)."""
    import numpy as np

    _, sigma, vt = np.linalg.svd(stiffness)
    scale = max(1.0, float(sigma[0]) if sigma.size else 1.0)
    for k, value in enumerate(sigma):
        if value > 1e-9 * scale:
            continue
        for step in (1e-3, -1e-3):
            with np.errstate(all="ignore"):
                moved = np.asarray(f_static(point + step * vt[k]), dtype=float)
            if not np.all(np.isfinite(moved)) or np.max(np.abs(moved)) > 1e-9 * scale:
                break
        else:
            return True
    return False
