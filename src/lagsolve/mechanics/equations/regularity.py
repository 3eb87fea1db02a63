r"""Constraints that cannot give a force: degenerate or redundant ones, refused before anything is solved.

Lagrange's multipliers need the constraint Jacobian :math:`A` to have full rank on the constraint
surface. Two ways to break that are mistakes in the problem file, refused with a fix (exit 2):

* **degenerate**: the gradient of :math:`\psi` vanishes where :math:`\psi = 0`, as for
  :math:`(x^2 + y^2 - L^2)^2`. Found symbolically (a factor repeated: the surface is a multiple
  root, and the fix is the product of the distinct factors) or numerically (at random states on the
  surface :math:`|\nabla\psi|` is zero to rounding, relative to its size a small step off the
  surface, where for a good constraint it is about the same);
* **redundant**: the rows of :math:`A` are linearly dependent at every random state on the surface
  (the same constraint written twice, or one implied by the others); the message names the
  constraints in the dependency.

Random states on the surface: parameters and coordinates drawn at random (declared functions
replaced by random smooth ones), then projected onto every holonomic constraint by Newton's method
with the least-norm step :math:`q \leftarrow q - J^{+}\psi`, which converges for redundant and
(linearly) for degenerate constraints too. A deficiency only counts when it holds at every state;
a singular point of a good constraint (a pendulum through the pivot) never does.
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import sympy

from lagsolve.errors import Issue, SpecError
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.surface import least_squares, newton
from lagsolve.problem.schema import ConstraintKind, Problem

#: states drawn on the constraint surface for the numeric tests
STATES = 8
#: |ψ| below this counts as on the surface
ON_SURFACE = 1e-13
#: a gradient this much smaller on the surface than a step off it counts as zero
VANISHING = 1e-2
#: the step off the surface for that comparison
STEP = 1e-2
#: relative size of a singular value that counts as zero in the rank test
RANK_TOLERANCE = 1e-8


def check_constraints(problem: Problem, model: Model, constraints: tuple[ConstraintTerms, ...]) -> None:
    """Refuse degenerate and redundant constraints (see the module docstring).

    Raises
    ------
    SpecError
        Naming each such constraint, with file, line, field and a fix.
    """
    if not constraints:
        return
    lines = {c.name: c.line for c in problem.constraints}
    issues: list[Issue] = []
    degenerate: set[str] = set()
    for c in constraints:
        if c.kind != ConstraintKind.HOLONOMIC:
            continue
        fix = _repeated_factor_fix(c.expression, model)
        if fix is not None:
            issues.append(_issue(problem, c, lines, f"the gradient of {c.name} vanishes where {c.name} = 0",
                                 f"write it as {fix} = 0"))
            degenerate.add(c.name)
    if issues:
        raise SpecError(issues)
    sampler = _Sampler(problem, model, constraints)
    states = sampler.states(STATES)
    if not states:
        return  # no state on the surface was found: nothing can be said numerically
    for j, c in enumerate(constraints):
        if c.kind == ConstraintKind.HOLONOMIC and all(sampler.vanishes(j, s) for s in states):
            issues.append(_issue(problem, c, lines, f"the gradient of {c.name} vanishes where {c.name} = 0",
                                 "write the constraint with a simple zero (not a square or a higher power, "
                                 "for instance) so that its gradient is not zero on the surface"))
            degenerate.add(c.name)
    if issues:
        raise SpecError(issues)
    dependent = sampler.dependencies(states)
    for j, involved in dependent:
        names = [constraints[k].name for k in involved]
        c = constraints[j]
        listed = ", ".join(names)
        issues.append(_issue(problem, c, lines,
                             f"the constraints {listed} are redundant: their gradients are linearly dependent at "
                             f"every state checked, so {c.name} adds nothing the others do not impose and the "
                             "multipliers are not determined",
                             f"remove {c.name}, or replace it by the condition it was meant to add"))
    if issues:
        raise SpecError(issues)


def _issue(problem: Problem, c: ConstraintTerms, lines: dict[str, int], message: str, hint: str) -> Issue:
    return Issue(problem.source, lines.get(c.name, 0), f"constraints.{c.name}.{c.kind}", message, hint)


def _repeated_factor_fix(psi: Any, model: Model) -> str | None:
    """The constraint without its repeated factors, written for the message, when a factor that contains a
    coordinate is repeated (ψ = u² vanishes doubly on u = 0); else None."""
    coordinates = set(model.coordinates)
    try:
        _, factors = sympy.factor_list(sympy.together(psi))
    except (sympy.PolynomialError, NotImplementedError, ValueError, TypeError):
        return None
    moving = [(f, k) for f, k in factors if f.free_symbols & coordinates]
    if not any(int(k) >= 2 for _, k in moving):
        return None
    simple = sympy.Mul(*(f for f, _ in moving))
    return _text(simple, coordinates)


def _text(expr: Any, coordinates: set[Any]) -> str:
    """``x**2 + y**2 - L**2``: terms with coordinates first, positive ones before negative ones."""
    terms = list(sympy.Add.make_args(sympy.expand(expr))) if expr.is_Add else [expr]
    terms.sort(key=lambda t: (not (t.free_symbols & coordinates), t.could_extract_minus_sign()))
    out = ""
    for k, t in enumerate(terms):
        negative = t.could_extract_minus_sign()
        body = sympy.sstr(-t if negative else t)
        out += ("-" if negative else "") + body if k == 0 else (" - " if negative else " + ") + body
    return out


class _Sampler:
    """Random states on the constraint surface, and the constraint rows evaluated there (floats)."""

    def __init__(self, problem: Problem, model: Model, constraints: tuple[ConstraintTerms, ...]) -> None:
        self.problem, self.model, self.constraints = problem, model, constraints
        self.coordinates = list(model.coordinates)
        self.holonomic = [j for j, c in enumerate(constraints) if c.kind == ConstraintKind.HOLONOMIC]
        self.functions, self.coefficients = self._function_family(problem)
        self.parameters = [p.symbol for p in problem.parameters]
        self.arguments = [model.time, *self.parameters, *self.coefficients, *self.coordinates]
        psi = [constraints[j].expression for j in self.holonomic]
        rows = [list(c.coefficients) for c in constraints]
        self._psi = self._compile(psi, derivative=True)
        self._rows = self._compile([a for row in rows for a in row], derivative=False)

    def _function_family(self, problem: Problem) -> tuple[dict[Any, Any], list[Any]]:
        family: dict[Any, Any] = {}
        coefficients: list[Any] = []
        for k, decl in enumerate(problem.functions):
            arity = max((len(call.args) for c in self.constraints
                         for call in c.expression.atoms(sympy.core.function.AppliedUndef)
                         if call.func == decl.function), default=1)
            u = sympy.symbols(f"u1:{arity + 1}", real=True)
            c = sympy.symbols(f"c{k}_0:{3 * arity + 1}", real=True)
            body = c[0] + sum((c[3 * i + 1] * ui + c[3 * i + 2] * ui**2 / 2 + c[3 * i + 3] * sympy.sin(ui + 1)
                               for i, ui in enumerate(u)), sympy.Integer(0))
            family[decl.function] = sympy.Lambda(u, body)
            coefficients += list(c)
        return family, coefficients

    def _compile(self, exprs: list[Any], derivative: bool) -> Any:
        concrete = []
        for e in exprs:
            for fn, lam in self.functions.items():
                e = e.replace(fn, lam)
            concrete.append((e if isinstance(e, sympy.Basic) else sympy.Integer(e)).doit())
        if not concrete:
            return lambda *args: np.zeros(0)
        # the math module: floats in, floats out (NumPy's namespace would import most of NumPy on first use)
        values = sympy.lambdify(self.arguments, concrete, modules="math")
        gradient = values
        if derivative:
            jac = [[sympy.diff(e, q) for q in self.coordinates] for e in concrete]
            gradient = sympy.lambdify(self.arguments, jac, modules="math")
        sizes = {False: len(concrete), True: len(concrete) * len(self.coordinates)}

        def call(*args: Any, derivative: bool = False) -> Any:
            fn = gradient if derivative else values
            try:
                return np.array(fn(*args), dtype=float)
            except (ArithmeticError, TypeError, ValueError):  # outside a domain (a complex result): not a number
                return np.full(sizes[derivative], np.nan)

        return call

    def states(self, count: int) -> list[tuple[list[float], np.ndarray, np.ndarray]]:
        """Up to ``count`` states (fixed values, coordinates, the coordinates they started from)."""
        rng = random.Random(20)
        out: list[tuple[list[float], np.ndarray, np.ndarray]] = []
        for _ in range(6 * count):
            if len(out) >= count:
                break
            fixed = [rng.uniform(0.0, 3.0)]
            fixed += [rng.uniform(0.5, 2.0) if p.is_positive else rng.uniform(-2.0, 2.0) for p in self.parameters]
            fixed += [rng.uniform(-1.0, 1.0) for _ in self.coefficients]
            q0 = np.array([rng.uniform(0.3, 2.5) if q.is_positive else rng.uniform(-2.5, 2.5)
                           for q in self.coordinates])
            q = self._project(fixed, q0.copy())
            if q is not None:
                out.append((fixed, q, q0))
        return out

    def _project(self, fixed: list[float], q: np.ndarray) -> np.ndarray | None:
        if not self.holonomic:
            return q
        shape = (len(self.holonomic), len(q))
        with np.errstate(all="ignore"):
            x, converged = newton(lambda x: self._psi(*fixed, *x),
                                  lambda x: self._psi(*fixed, *x, derivative=True).reshape(shape), q,
                                  step=least_squares, tolerance=ON_SURFACE, iterations=200, bound=1e6)
        return np.array(x, dtype=float) if converged else None

    def _matrix(self, fixed: list[float], q: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            return self._rows(*fixed, *q).reshape(len(self.constraints), len(self.coordinates))

    def vanishes(self, j: int, state: tuple[list[float], np.ndarray, np.ndarray]) -> bool:
        """Whether constraint ``j``'s row is zero at ``state``, relative to its size a step :data:`STEP` off the
        surface (about the same for a good constraint; for ψ = u², |∇ψ| grows like the distance)."""
        fixed, q, q0 = state
        direction = q0 - q if np.linalg.norm(q0 - q) > 0 else np.ones_like(q)
        off = q + STEP * direction / np.linalg.norm(direction)
        here = np.linalg.norm(self._matrix(fixed, q)[j])
        there = np.linalg.norm(self._matrix(fixed, off)[j])
        if not (np.isfinite(here) and np.isfinite(there)):
            return False
        return bool(here <= VANISHING * max(float(there), 1e-300))

    def dependencies(self, states: list[tuple[list[float], np.ndarray, np.ndarray]]) -> list[tuple[int, list[int]]]:
        """Each constraint that depends linearly on earlier ones at every state, with the constraints involved."""
        matrices = [self._matrix(fixed, q) for fixed, q, _ in states]
        matrices = [m for m in matrices if np.all(np.isfinite(m))]
        if not matrices:
            return []
        kept: list[int] = []
        out: list[tuple[int, list[int]]] = []
        for j in range(len(self.constraints)):
            trial = [*kept, j]
            if all(_rank(m[trial]) < len(trial) for m in matrices):
                involved = _involved(matrices[0][trial])
                out.append((j, sorted(trial[i] for i in involved)))
            else:
                kept.append(j)
        return out


def _rank(rows: np.ndarray) -> int:
    if rows.size == 0:
        return 0
    s = np.linalg.svd(rows, compute_uv=False)
    scale = max(float(s[0]), 1e-300)
    return int(np.sum(s > RANK_TOLERANCE * scale))


def _involved(rows: np.ndarray) -> list[int]:
    """The rows with a non-zero coefficient in a linear dependency Σ cᵢ rowᵢ = 0 (the last must be in it)."""
    _, _, vt = np.linalg.svd(rows.T)
    c = vt[-1]
    big = np.max(np.abs(c))
    return [i for i, ci in enumerate(c) if abs(ci) > 1e-6 * big]
