r"""Random states on the constraint surface, for numeric comparisons (``lagsolve check``).

A state assigns a number to the time, every parameter, coordinate and velocity, and
replaces every declared function by a random smooth function, such that every
constraint holds:

* holonomic constraints that :mod:`lagsolve.mechanics.equations.elimination` solves explicitly give their
  coordinate (``y = f(x)``) and velocity directly;
* the other holonomic constraints :math:`\psi_j(q, t) = 0` are solved for one coordinate each
  by Newton's method, :math:`q_d \leftarrow q_d - (\partial\psi/\partial q_d)^{-1}\psi`;
* the velocity forms of all constraints, :math:`\sum_i a_{ji}\dot q_i + b_j = 0`, are solved for
  as many velocities as they fix (the columns with the largest pivots), the others random.

A declared function :math:`f(u_1, \dots, u_n)` becomes

.. math:: c_0 + \sum_k \big(c_{k1} u_k + \tfrac12 c_{k2} u_k^2 + c_{k3}\sin(\omega_k u_k + \varphi_k)\big)
          + c_e\, e^{\sum_k h_k u_k / 2} \; [+\, c_p u_1 u_2]

with random coefficients held as symbols, so that an expression is compiled once and its
derivatives (``Derivative(f(x), x)``) are the exact derivatives of the same function at every
state. Arithmetic is done with mpmath at 30 significant digits.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy

from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.equations.constraints import velocity_form
from lagsolve.mechanics.equations.surface import newton
from lagsolve.problem.schema import ConstraintKind

DIGITS = 30
#: states share their parameter values in groups of this size, so that a ratio that depends only on
#: the parameters can be told from one that depends on the state
GROUP = 4


@dataclass(frozen=True)
class State:
    """One point on the constraint surface.

    ``values`` maps every symbol of the problem (time, parameters, coordinates, velocities,
    extra symbols such as conserved momenta ``p_q``) to an mpmath number; ``coefficients``
    the coefficient symbols of the random functions; ``functions`` each declared function's
    name to the concrete :class:`sympy.Lambda` used here; ``group`` numbers the parameter set.
    """

    values: dict[Any, Any]
    coefficients: dict[Any, Any]
    functions: dict[str, Any]
    group: int


class Compiled:
    """An expression compiled for evaluation at :class:`State` objects.

    Declared functions are replaced by the random function family and the result is
    lambdified for mpmath (SymPy's code printer on a SymPy tree; no text is parsed).
    """

    def __init__(self, expr: Any, space: StateSpace) -> None:
        self.expr = expr
        concrete = space.concrete(expr)
        self.symbols = tuple(sorted(concrete.free_symbols, key=sympy.default_sort_key))
        # an expression that is infinite or undefined as written (x/0 after the constraints) has no value
        undefined = concrete.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo)
        self._fn = None if undefined else sympy.lambdify(self.symbols, concrete, modules="mpmath", dummify=True)

    def __call__(self, state: State) -> Any | None:
        """The value at ``state`` (an mpmath number), or ``None`` where it is undefined."""
        if self._fn is None:
            return None
        args = []
        for s in self.symbols:
            if s in state.values:
                args.append(state.values[s])
            elif s in state.coefficients:
                args.append(state.coefficients[s])
            else:
                return None
        with mpmath.workdps(DIGITS):
            try:
                value = self._fn(*args)
            except (ZeroDivisionError, ValueError, OverflowError, TypeError):
                return None
            value = mpmath.mpmathify(value)
            if not mpmath.isfinite(value):
                return None
            return value


class StateSpace:
    """The variables of one derivation and how to complete them to states on the constraint surface.

    ``extra`` lists further symbols (``p_q``, say) that get random values like parameters.
    """

    def __init__(self, derivation: Derivation, extra: Iterable[Any] = (), seed: int = 0) -> None:
        problem = derivation.problem
        model = derivation.model
        self.derivation = derivation
        self.seed = seed
        self.time = problem.time
        self.parameters = tuple(p.symbol for p in problem.parameters)
        known = {self.time, *self.parameters, *model.coordinates, *model.velocities}
        self.extra = tuple(sorted({s for s in extra if s not in known}, key=sympy.default_sort_key))
        elimination = derivation.elimination
        self.eliminated = tuple(q for q in model.coordinates if q in elimination.positions)
        self.eliminated_velocities = tuple(v for v in model.velocities if v in elimination.velocities)
        self.coordinates = tuple(q for q in model.coordinates if q not in elimination.positions)
        self.velocities = tuple(v for v in model.velocities if v not in elimination.velocities)
        self.positive = {q for q in model.coordinates if q.is_positive}
        self._functions = self._function_family(derivation)
        residuals, dependents = self._implicit_constraints(derivation)
        self.dependents = tuple(dependents)
        self._residuals = [Compiled(r, self) for r in residuals]
        self._jacobian = [[Compiled(sympy.diff(r, q), self) for q in dependents] for r in residuals]
        self._velocity_rows, self._velocity_offsets = self._velocity_forms(derivation)
        self._eliminated = {q: Compiled(elimination.apply(q), self)
                            for q in (*self.eliminated, *self.eliminated_velocities)}

    def _implicit_constraints(self, derivation: Derivation) -> tuple[list[Any], list[Any]]:
        """The holonomic constraints that the elimination does not solve (their residuals ψ after it), and for
        each the coordinate Newton's method solves it for: the last one it holds that no earlier one took."""
        elimination = derivation.elimination
        explicit = {name for q, name in elimination.sources.items() if q in elimination.positions}
        residuals, dependents = [], []
        for c in derivation.constraints:
            if c.kind != ConstraintKind.HOLONOMIC or c.name in explicit:
                continue
            psi = elimination.apply(c.expression)
            free = [q for q in reversed(self.coordinates) if q not in dependents and psi.has(q)]
            if free:
                residuals.append(psi)
                dependents.append(free[0])
        return residuals, dependents

    def _velocity_forms(self, derivation: Derivation) -> tuple[list[list[Compiled]], list[Compiled]]:
        """The velocity form of every constraint that holds a remaining velocity, linear in them: the
        coefficient of each velocity (one row per constraint) and the rest."""
        elimination, model = derivation.elimination, derivation.model
        rows, offsets = [], []
        for c in derivation.constraints:
            form = sympy.expand(elimination.apply(velocity_form(c, model)))
            row = [sympy.diff(form, v) for v in self.velocities]
            if all(a == 0 for a in row):
                continue
            rows.append([Compiled(a, self) for a in row])
            offsets.append(Compiled(form.xreplace({v: 0 for v in self.velocities}), self))
        return rows, offsets

    # -- random functions -----------------------------------------------------------------------

    def _function_family(self, derivation: Derivation) -> dict[Any, tuple[Any, tuple[Any, ...]]]:
        """Each declared function → (Lambda with coefficient symbols, those symbols)."""
        problem = derivation.problem
        arity: dict[Any, int] = {}
        sources = [derivation.model.lagrangian, *(c.expression for c in derivation.constraints),
                   *(derivation.accelerations or {}).values(), *(derivation.multipliers or {}).values()]
        for expr in sources:
            for call in expr.atoms(sympy.core.function.AppliedUndef):
                arity.setdefault(call.func, len(call.args))
        family = {}
        for k, decl in enumerate(problem.functions):
            n = arity.get(decl.function, 1)
            u = sympy.symbols(f"u1:{n + 1}", real=True)
            coef = iter(sympy.symbols(f"c{k}_0:{4 * n + 4}", real=True))
            body = next(coef)
            for uk in u:
                body += next(coef) * uk + next(coef) * uk**2 / 2 + next(coef) * sympy.sin(next(coef) * uk + 1)
            body += next(coef) * sympy.exp(sum((next(coef) * uk for uk in u[:1]), sympy.Integer(0)) / 2)
            if n >= 2:
                body += next(coef) * u[0] * u[1]
            symbols = tuple(sorted(body.free_symbols - set(u), key=sympy.default_sort_key))
            family[decl.function] = (sympy.Lambda(u, body), symbols)
        return family

    def concrete(self, expr: Any) -> Any:
        """``expr`` with each declared function replaced by its random family, derivatives evaluated."""
        if not expr.atoms(sympy.core.function.AppliedUndef):
            return expr
        for fn, (lam, _) in self._functions.items():
            expr = expr.replace(fn, lam)
        return expr.doit()

    def _draw_coefficients(self, rng: random.Random) -> tuple[dict[Any, Any], dict[str, Any]]:
        coefficients: dict[Any, Any] = {}
        functions: dict[str, Any] = {}
        for fn, (lam, symbols) in self._functions.items():
            values = {}
            for s in symbols:
                # frequencies (inside sin) and growth rates (inside exp) stay moderate
                inside = any(s in f.args[0].free_symbols for f in lam.expr.atoms(sympy.sin, sympy.exp))
                low, high = (0.5, 1.8) if inside else (-1.0, 1.0)
                values[s] = mpmath.mpf(rng.uniform(low, high))
            coefficients.update(values)
            shown = lam.expr.xreplace({s: sympy.Float(float(v), 3) for s, v in values.items()})
            functions[fn.__name__] = sympy.Lambda(lam.variables, shown)
        return coefficients, functions

    # -- states ---------------------------------------------------------------------------------

    def states(self, count: int, attempts: int = 40) -> list[State]:
        """``count`` states on the constraint surface (fewer when the constraints are hard to meet).

        Deterministic for a given seed, so a failing comparison can be reproduced.
        """
        rng = random.Random(self.seed)
        out: list[State] = []
        group = 0
        while len(out) < count and group < count:
            base = self._draw_parameters(rng)
            made = tries = 0
            while made < GROUP and len(out) < count and tries < attempts:
                tries += 1
                state = self._complete(rng, dict(base), group)
                if state is not None:
                    out.append(state)
                    made += 1
            group += 1
        return out

    def _draw_parameters(self, rng: random.Random) -> dict[Any, Any]:
        values: dict[Any, Any] = {}
        for p in (*self.parameters, *self.extra):
            low, high = (0.5, 2.5) if p.is_positive else (-2.0, 2.0)
            values[p] = mpmath.mpf(rng.uniform(low, high))
        return values

    def _complete(self, rng: random.Random, values: dict[Any, Any], group: int) -> State | None:
        coefficients, functions = self._draw_coefficients(rng)
        values[self.time] = mpmath.mpf(rng.uniform(0.0, 3.0))
        for q in self.coordinates:
            low, high = (0.3, 2.5) if q in self.positive else (-2.5, 2.5)
            values[q] = mpmath.mpf(rng.uniform(low, high))
        for v in self.velocities:
            values[v] = mpmath.mpf(rng.uniform(-2.0, 2.0))
        state = State(values, coefficients, functions, group)
        if self.dependents and not self._newton(state):
            return None
        if self._velocity_rows and not self._solve_velocities(state):
            return None
        for symbol, compiled in self._eliminated.items():
            value = compiled(state)
            if value is None or not isinstance(value, mpmath.mpf):
                return None
            values[symbol] = value
        return state

    def _newton(self, state: State) -> bool:
        """The dependent coordinates solved from their constraints
        (:func:`~lagsolve.mechanics.equations.surface.newton`,
        LU steps in mpmath), positive where they must be."""

        def at(x: list[Any]) -> State:
            state.values.update(zip(self.dependents, x, strict=True))
            return state

        def jacobian(x: list[Any]) -> Any:
            rows = [[d(at(x)) for d in row] for row in self._jacobian]
            if any(not isinstance(v, mpmath.mpf) for row in rows for v in row):
                raise TypeError("not a real number")
            return mpmath.matrix(rows)

        with mpmath.workdps(DIGITS + 10):
            x, converged = newton(lambda x: [r(at(x)) for r in self._residuals], jacobian,
                                  [state.values[q] for q in self.dependents],
                                  step=lambda J, r: list(mpmath.lu_solve(J, mpmath.matrix(r))),
                                  tolerance=mpmath.mpf(10) ** (-DIGITS + 2), bound=1e6)
            at(x)
        return converged and all(q not in self.positive or state.values[q] > 0 for q in self.dependents)

    def _solve_velocities(self, state: State) -> bool:
        """Solve the velocity forms for the velocities with the largest pivots (Gauss–Jordan)."""
        with mpmath.workdps(DIGITS):
            return self._gauss_jordan(state)

    def _gauss_jordan(self, state: State) -> bool:
        rows: list[list[Any]] = [[a(state) for a in row] for row in self._velocity_rows]
        offsets: list[Any] = [b(state) for b in self._velocity_offsets]
        if any(not isinstance(v, mpmath.mpf) for v in [*offsets, *(x for row in rows for x in row)]):
            return False
        tiny = mpmath.mpf(10) ** (-DIGITS + 5)
        # reduce [A | b] to find which velocities the constraints fix
        matrix = [[*row, b] for row, b in zip(rows, offsets, strict=True)]
        n = len(self.velocities)
        pivots: list[int] = []
        r = 0
        for _ in range(len(matrix)):
            best = max(((abs(matrix[i][j]), i, j) for i in range(r, len(matrix)) for j in range(n)
                        if j not in pivots), default=(0, -1, -1))
            if best[0] <= tiny:
                break
            _, i, j = best
            matrix[r], matrix[i] = matrix[i], matrix[r]
            pivot = matrix[r][j]
            matrix[r] = [x / pivot for x in matrix[r]]
            for k in range(len(matrix)):
                if k != r and matrix[k][j] != 0:
                    factor = matrix[k][j]
                    matrix[k] = [x - factor * y for x, y in zip(matrix[k], matrix[r], strict=True)]
            pivots.append(j)
            r += 1
        if any(abs(row[-1]) > tiny for row in matrix[r:]):
            return False  # inconsistent at this state
        for row, j in zip(matrix[:r], pivots, strict=True):
            rest = sum((row[k] * state.values[self.velocities[k]] for k in range(n) if k not in pivots),
                       mpmath.mpf(0))
            state.values[self.velocities[j]] = -(row[-1] + rest)
        return True


def evaluate(compiled: Sequence[Compiled], states: Sequence[State]) -> list[list[Any | None]]:
    """``compiled[k](state)`` for every state: one row per state."""
    return [[c(s) for c in compiled] for s in states]


def describe(state: State, symbols: Iterable[Any], order: Callable[[Any], Any] | None = None) -> tuple:
    """``((name, float), ...)`` for ``symbols`` at ``state``, in ``order``."""
    chosen = [s for s in symbols if s in state.values]
    if order is not None:
        chosen.sort(key=order)
    return tuple((str(s), float(mpmath.re(state.values[s]))) for s in chosen)
