r"""Hamiltonian mechanics: momenta, the Legendre transform, Hamilton's equations, the Routhian.

Where the analysis found minimal coordinates (every constraint holonomic and solved, or no
constraint at all), the reduced Lagrangian :math:`L(q, \dot q, t)` is quadratic in the velocities,

.. math:: L = \tfrac12\,\dot q^T A(q, t)\,\dot q + b(q, t)^T\dot q + L_0(q, t),

so the conjugate momenta :math:`p = \partial L/\partial\dot q = A\dot q + b` are linear in
:math:`\dot q`, and the linear system gives :math:`\dot q = A^{-1}(p - b)`. The Legendre transform is

.. math:: H = \sum_i p_i\dot q_i - L = \tfrac12 (p - b)^T A^{-1} (p - b) - L_0,

which is :math:`T_2 - T_0 + V` (:math:`T + V` when T is a quadratic form in the velocities and V
holds none). Hamilton's equations, with the generalized forces :math:`Q` that have no potential
(a Rayleigh function :math:`\mathcal R` shown apart), are

.. math:: \dot q_i = \frac{\partial H}{\partial p_i}, \qquad
          \dot p_i = -\frac{\partial H}{\partial q_i} + Q_i - \frac{\partial\mathcal R}{\partial\dot q_i}.

**Routhian.** With cyclic coordinates :math:`q_c` (momenta :math:`p_c` constant), solving
:math:`p_c = \partial L/\partial\dot q_c` for :math:`\dot q_c` gives
:math:`R(q, \dot q, p_c) = L - \sum_c p_c\dot q_c`, a Lagrangian for the other coordinates
(:math:`\frac{d}{dt}\partial R/\partial\dot q_k - \partial R/\partial q_k = Q_k`) with
:math:`\dot q_c = -\partial R/\partial p_c`; with one coordinate left it is
:mod:`~lagsolve.mechanics.analysis.equilibria`'s :math:`L_R`, whose part free of :math:`\dot q` is
:math:`-V_{eff}` (same sign convention).

**Poisson brackets.** Each conserved quantity C of the analysis, written in (q, p), has

.. math:: \frac{dC}{dt} = \{C, H\} + \frac{\partial C}{\partial t} + \sum_i \frac{\partial C}{\partial p_i} Q_i,
          \qquad \{C, H\} = \sum_i \frac{\partial C}{\partial q_i}\frac{\partial H}{\partial p_i}
          - \frac{\partial C}{\partial p_i}\frac{\partial H}{\partial q_i},

which must vanish (an independent check of the analysis's claim).

Notes
-----
* Not applicable when a velocity constraint remains (nonholonomic) or a constraint could not be
  solved: the multipliers cannot be removed from the equations, and there is no H(q, p) whose
  equations are the motion's.
* Needs L at most quadratic in the velocities with :math:`\det A \ne 0` (a regular Lagrangian).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve.mechanics.analysis.linearize import NO_FREEDOM
from lagsolve.mechanics.equations.energy import jacobi_integral
from lagsolve.mechanics.equations.model import Model, time_derivative
from lagsolve.mechanics.results import Canonical
from lagsolve.mechanics.stages import Stages, StageSkipped, StageTooLarge
from lagsolve.mechanics.symbolic.algebra import cancel, factor_terms, ops
from lagsolve.mechanics.symbolic.identities import Zero, numerically_zero, proved_zero, zero_status
from lagsolve.mechanics.symbolic.linsolve import SIZE_LIMIT, solve_structured
from lagsolve.mechanics.symbolic.partials import partial
from lagsolve.mechanics.symbolic.ringsolve import coupled
from lagsolve.mechanics.symbolic.simplify import display_forms, measure, smallest, tidy, tidy_sum
from lagsolve.problem.names import momentum_symbol

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.results import Analysis
    from lagsolve.problem.schema import Problem

#: the statements of :attr:`Hamiltonian.form`
T_PLUS_V, T2_T0_V, T2_T0_V0 = "T + V", "T2 - T0 + V", "T2 - T0 + V0"


@dataclass(frozen=True)
class Bracket:
    r"""One conserved quantity's rate in Hamiltonian form: ``quantity`` C(q, p, t), ``bracket``
    :math:`\{C, H\}`, ``partial_t`` :math:`\partial C/\partial t`, ``forces``
    :math:`\sum_i \partial C/\partial p_i\,Q_i` and ``rate`` their sum, simplified (0 when conserved);
    ``status`` is ``"symbolic"`` (proved 0), ``"numeric"`` (0 at random points) or ``"differ"``."""

    name: str
    quantity: Any
    bracket: Any
    partial_t: Any
    forces: Any
    rate: Any
    status: str


@dataclass(frozen=True)
class Routhian:
    r"""Routh's reduction by the cyclic coordinates (module docstring).

    ``cyclic`` are the cyclic coordinates, ``momenta`` their constant momenta (symbols),
    ``velocities`` :math:`\dot q_c(q, \dot q, p_c)`, ``coordinates`` the ones left, ``expression``
    :math:`R = L - \sum_c p_c\dot q_c`, ``equations`` the pairs
    :math:`(\frac{d}{dt}\partial R/\partial\dot q_k,\ \partial R/\partial q_k + Q_k)` of the ones left, and
    ``cyclic_rates`` :math:`-\partial R/\partial p_c`.
    """

    cyclic: tuple[Any, ...]
    momenta: tuple[Any, ...]
    velocities: tuple[Any, ...]
    coordinates: tuple[Any, ...]
    expression: Any
    equations: tuple[tuple[Any, Any], ...]
    cyclic_rates: tuple[Any, ...]


@dataclass(frozen=True)
class Hamiltonian:
    r"""The Hamiltonian formulation of a system in minimal coordinates (module docstring).

    Tuples run over ``coordinates`` (the minimal ones): ``velocities`` :math:`\dot q`,
    ``momentum_symbols`` :math:`p` (``p_<q>``), ``momenta`` :math:`\partial L/\partial\dot q` in
    (q, q̇), ``inverse`` :math:`\dot q(q, p)`; ``mass`` is A and ``offset`` b of :math:`p = A\dot q + b`;
    ``time`` is t; ``lagrangian`` the L transformed; ``expression`` H(q, p, t); ``form`` one of ``"T + V"``,
    ``"T2 - T0 + V"``, ``"T2 - T0 + V0"`` (V with a part linear in the velocities, which drops out),
    or ``""``; ``kinetic_parts`` (T₂, T₁, T₀), the parts of T by degree in q̇. ``forces`` and ``dissipation`` are the
    generalized forces without a potential and :math:`-\partial\mathcal R/\partial\dot q`, in (q, p);
    ``rates`` the right sides of :math:`\dot q = \partial H/\partial p` and ``momentum_rates`` of
    :math:`\dot p = -\partial H/\partial q + Q - \partial\mathcal R/\partial\dot q`.
    ``routhian`` (or ``routhian_note`` why none) and ``brackets`` as in the module docstring.
    ``compact`` says that H, q̇(q, p) and Hamilton's equations are too long to write out in a report, which then
    gives them in matrix form (:func:`hamiltonian`); they are still here in full.
    """

    time: Any
    coordinates: tuple[Any, ...]
    velocities: tuple[Any, ...]
    momentum_symbols: tuple[Any, ...]
    momenta: tuple[Any, ...]
    mass: sympy.ImmutableMatrix
    offset: sympy.ImmutableMatrix
    inverse: tuple[Any, ...]
    lagrangian: Any
    expression: Any
    form: str
    kinetic_parts: tuple[Any, Any, Any]
    forces: tuple[Any, ...]
    dissipation: tuple[Any, ...]
    rates: tuple[Any, ...]
    momentum_rates: tuple[Any, ...]
    routhian: Routhian | None
    routhian_note: str
    brackets: tuple[Bracket, ...]
    time_dependent: bool
    remainder: Any = sympy.Integer(0)  # -L(q, 0, t), the part of H free of the momenta
    compact: bool = False

    def to_momenta(self, expr: Any) -> Any:
        """``expr`` (in q, q̇, t) written in (q, p, t): each velocity replaced by :math:`\\dot q(q, p)`."""
        return expr.xreplace(dict(zip(self.velocities, self.inverse, strict=True)))

    def rate(self, quantity: Any) -> Any:
        r""":math:`dC/dt = \{C, H\} + \partial C/\partial t + \sum_i \partial C/\partial p_i\,Q_i` of a
        quantity C(q, p, t) along Hamilton's equations (unsimplified)."""
        bracket, partial_t, forces = self._pieces(quantity)
        return bracket + partial_t + forces

    def _pieces(self, quantity: Any) -> tuple[Any, Any, Any]:
        H, t = self.expression, self.time
        bracket = sum((sympy.diff(quantity, q) * sympy.diff(H, p) - sympy.diff(quantity, p) * sympy.diff(H, q)
                       for q, p in zip(self.coordinates, self.momentum_symbols, strict=True)), sympy.Integer(0))
        partial_t = sympy.diff(quantity, t)
        forces = sum((sympy.diff(quantity, p) * (f + d) for p, f, d in zip(self.momentum_symbols, self.forces,
                                                                           self.dissipation, strict=True)),
                     sympy.Integer(0))
        return bracket, partial_t, forces


def canonical_form(analysis: Analysis, problem: Problem, stages: Stages) -> Canonical:
    """The :class:`~lagsolve.mechanics.results.Canonical` part of a derivation: the Hamiltonian of its analysis,
    found by the stage of that name, or why not: the reason it does not apply, or the stage's note."""
    found = stages.run("hamiltonian", hamiltonian, analysis, problem.dissipation)
    if found is None:
        note = stages.note_for("hamiltonian")
        return Canonical(note=note.reason if note is not None else "did not finish")
    result, reason = found
    if result is None:
        stages.skip("hamiltonian", reason, "n/a")  # not applicable: said in the Hamiltonian section itself
    return Canonical(result, reason)


def hamiltonian(analysis: Analysis, dissipation: Any = None) -> tuple[Hamiltonian | None, str]:
    """The Hamiltonian formulation of the analysed system, or None and why it does not apply.

    ``dissipation`` is the problem's Rayleigh function :math:`\\mathcal R(\\dot q)` in the full
    coordinates (None without one); its part of the generalized forces is shown apart.
    """
    reduced = analysis.reduced
    if reduced is None:
        reason = analysis.reduced_note or "there are no minimal coordinates"
        return None, f"there are no minimal coordinates: {reason}"
    model = reduced.model
    if not model.coordinates:
        return None, NO_FREEDOM
    L = model.lagrangian
    if any(partial(L, v, v, v) != 0 for v in model.velocities):
        return None, "L is not quadratic in the velocities, so p = dL/dq_dot cannot be inverted as a linear system"
    q, qd, t = model.coordinates, model.velocities, model.time
    n = len(q)
    P = tuple(momentum_symbol(c) for c in q)
    zero = {v: sympy.Integer(0) for v in qd}
    show, _ = display_forms(n)  # a large system's n² entries are each rewritten once, not searched
    A = sympy.Matrix(n, n, lambda i, j: show(partial(L, qd[i], qd[j])))
    b = sympy.Matrix([show(partial(L, v).xreplace(zero)) for v in qd])
    L0 = L.xreplace(zero)
    w = sympy.Matrix(P) - b
    try:
        long_inverse = _long_inverse(A, w)
        squares = None if long_inverse is not None else complete_squares(A, w)
    except ValueError:
        return None, ("the matrix A of p = A q_dot + b is singular (a coordinate without inertia): the momenta "
                      "cannot be solved for the velocities")
    remainder = _shortest(-L0)
    if squares is not None:
        velocities = squares.solution
        H = sympy.Add(*squares.terms, remainder)
    else:
        assert long_inverse is not None
        velocities = long_inverse
        H = sympy.Add(*(wi * v / 2 for wi, v in zip(w, velocities, strict=True)), remainder)
    momenta = tuple(tidy_sum(partial(L, v)) for v in qd)
    form, parts = _statement(model, qd)
    to_p = dict(zip(qd, velocities, strict=True))
    raw_dissipation = _dissipation(reduced, dissipation)
    forces = tuple(tidy(sympy.expand(Q - d).xreplace(to_p))
                   for Q, d in zip(reduced.generalized_forces, raw_dissipation, strict=True))
    damping = tuple(tidy(d.xreplace(to_p)) for d in raw_dissipation)
    # dq/dt = dH/dp = A^-1 (p - b): the velocities just solved for, in the same form
    rates = tuple(velocities)
    if squares is not None:
        momentum_rates = tuple(sympy.Add(*(_square_rate(top, bottom, c, P) for top, bottom in squares.pairs),
                                         _termwise(remainder, c, -1)) for c in q)
    else:
        # -dH/dq at constant p is dL/dq at constant q_dot, with q_dot(q, p) put in (dH = q_dot dp - dL/dq dq
        # - dL/dt dt): the long inverse is substituted once, not differentiated
        momentum_rates = tuple(sympy.factor_terms(partial(L, c)).xreplace(to_p) for c in q)
    compact = squares is None or _too_long(H, velocities, momentum_rates)
    result = Hamiltonian(
        time=t, coordinates=q, velocities=qd, momentum_symbols=P, momenta=momenta, mass=sympy.ImmutableMatrix(A),
        offset=sympy.ImmutableMatrix(b), inverse=velocities, lagrangian=reduced.lagrangian, expression=H,
        form=form, kinetic_parts=parts, forces=forces, dissipation=damping, rates=rates,
        momentum_rates=momentum_rates, routhian=None, routhian_note="", brackets=(),
        time_dependent=not proved_zero(sympy.diff(H, t)), remainder=remainder, compact=compact)
    routhian, note = routh(model, reduced.generalized_forces, analysis)
    energy = jacobi_integral(model)
    brackets = tuple(_symmetry_bracket(result, model, c.name, c.generator) if c.generator and c.kind == "noether"
                     else _bracket(result, c.name, c.expression, energy) for c in analysis.conservation.quantities)
    return dataclasses.replace(result, routhian=routhian, routhian_note=note, brackets=brackets), ""


#: past this many operations H or q̇(q, p) (twice as many for ṗ) is too long to write out in a report, which then
#: gives H and Hamilton's equations in matrix form (:attr:`Hamiltonian.compact`)
COMPACT_LIMIT = 45
#: an inverse A⁻¹(p − b), solved fraction-free, longer than this (operations in one entry) is not written as a
#: sum of squares: the reports give the matrix form, and completing the squares would cost far more than
#: the whole rest of the derivation (the triple pendulum's has 74, the heavy top's, shown, 46)
INVERSE_LIMIT = 60


def _too_long(H: Any, velocities: tuple[Any, ...], momentum_rates: tuple[Any, ...]) -> bool:
    """H, q̇(q, p) or ṗ is past what a report writes out (:data:`COMPACT_LIMIT`)."""
    return (max(ops(e) for e in (H, *velocities)) > COMPACT_LIMIT
            or max(ops(e) for e in momentum_rates) > 2 * COMPACT_LIMIT)


def _long_inverse(A: sympy.Matrix, w: sympy.Matrix) -> tuple[Any, ...] | None:
    """:math:`A^{-1}w` solved fraction-free (:func:`~lagsolve.mechanics.symbolic.linsolve.solve_structured`) when A has
    a dense block of three or more coordinates and the solution is longer than :data:`INVERSE_LIMIT`; None
    when the sum of squares is worth completing (every block of A smaller, or the inverse short).
    ``ValueError`` when A is singular; :class:`StageSkipped` when the inverse is too large to give at all."""
    if max(len(group) for group in coupled(A)) < 3:
        return None
    try:
        solution, _ = solve_structured(A, w, sympy.zeros(0, A.rows), sympy.zeros(0, 1), SIZE_LIMIT)
    except StageSkipped as exc:
        raise StageTooLarge(f"inverting p = A q_dot + b grows past {SIZE_LIMIT} operations per "
                           "expression") from exc
    if max(ops(e) for e in solution) <= INVERSE_LIMIT:
        return None
    return tuple(sympy.factor_terms(e) for e in solution)


@dataclass(frozen=True)
class Squares:
    r""":math:`\tfrac12 w^T A^{-1} w` as a sum of squares, and :math:`A^{-1}w`, by symmetric elimination
    (:math:`A = \mathcal L D \mathcal L^T`, the simplest pivot first): ``terms`` are
    :math:`y_k^2/(2D_k)` with :math:`y = \mathcal L^{-1}w` (the heavy top's
    :math:`(p_\phi - p_\psi\cos\theta)^2/(2I_1\sin^2\theta)`), ``solution`` :math:`A^{-1}w` by back
    substitution (:math:`\dot\psi = p_\psi/I_3 - \cos\theta\,\dot\phi`, written out)."""

    solution: tuple[Any, ...]
    #: (y_k, D_k) of each term, so that term k is y_k**2 / (2 D_k) (in the form shown)
    pairs: tuple[tuple[Any, Any], ...]

    @property
    def terms(self) -> tuple[Any, ...]:
        """The squares :math:`y_k^2/(2D_k)` themselves."""
        return tuple(_square_term(pair) for pair in self.pairs)


def complete_squares(A: sympy.Matrix, w: sympy.Matrix, limit: int = SIZE_LIMIT) -> Squares:
    """:class:`Squares` of the symmetric ``A`` (shape (n, n)) and ``w`` (n); ``ValueError`` when a pivot
    vanishes (A singular), :class:`StageSkipped` when an entry grows past ``limit`` operations."""
    n = A.rows
    M = [[A[i, j] for j in range(n)] for i in range(n)]
    y = [w[i] for i in range(n)]
    order: list[int] = []
    pivots: dict[int, Any] = {}
    factors: dict[tuple[int, int], Any] = {}
    remaining = list(range(n))
    while remaining:
        options = [(measure(tidy(M[i][i])), i) for i in remaining if not proved_zero(M[i][i])]
        if not options:
            raise ValueError("no pivot")
        _, k = min(options)
        d = tidy(M[k][k])
        order.append(k)
        pivots[k] = d
        remaining.remove(k)
        for i in remaining:
            f = tidy(M[i][k] / d)
            factors[(i, k)] = f
            if f == 0:
                continue
            y[i] = sympy.expand(y[i] - f * y[k])
            for j in remaining:
                M[i][j] = cancel(M[i][j] - f * M[k][j])
            _guard((y[i], *M[i]), limit)
    pairs = tuple(_square(y[k], pivots[k]) for k in order if y[k] != 0)
    solution: dict[int, Any] = {}
    for at, k in reversed(list(enumerate(order))):
        later = order[at + 1:]
        solution[k] = sympy.Add(tidy(y[k] / pivots[k]), *(-factors[(i, k)] * solution[i] for i in later))
        _guard((solution[k],), limit)
    return Squares(tuple(solution[i] for i in range(n)), pairs)


def _square(y: Any, d: Any) -> tuple[Any, Any]:
    """:math:`y^2/(2d)` as (top, bottom), the term ``top**2 / (2 bottom)``: the denominators of y cleared
    into d when that is shorter."""
    plain = (tidy_sum(y), d)
    numerator, denominator = sympy.fraction(sympy.together(y))
    if denominator == 1:
        return plain
    cleared = (tidy_sum(numerator), tidy(d * denominator**2))
    return min((plain, cleared), key=lambda pair: measure(_square_term(pair)))


def _square_term(pair: tuple[Any, Any]) -> Any:
    """``top**2 / (2 bottom)`` of a pair (top, bottom) of :class:`Squares`."""
    top, bottom = pair
    return sympy.Rational(1, 2) * top**2 / bottom


def _guard(exprs: tuple[Any, ...], limit: int) -> None:
    largest = max((ops(e) for e in exprs if isinstance(e, sympy.Basic)), default=0)
    if largest > limit:
        raise StageTooLarge(f"inverting p = A q_dot + b grows past {limit} operations per expression")


def _joined(terms: tuple[Any, ...], rest: Any) -> Any:
    """The sum of ``terms`` and ``rest`` (simplified), each term kept as it is."""
    return sympy.Add(*terms, _shortest(rest))


def _square_rate(top: Any, bottom: Any, x: Any, momenta: tuple[Any, ...]) -> Any:
    r""":math:`-\partial(y^2/2D)/\partial x = y\,(y D_x - 2 D y_x)/(2D^2)` of one square of H (``top`` y,
    ``bottom`` D), the quotient rule with y kept as a factor, as a textbook writes the derivative of
    :math:`(p_1 - p_2\cos\theta)^2/(2 m l^2 (2 - \cos^2\theta))`. The bracket is linear in the
    ``momenta``: each coefficient (a short function of q) is simplified apart, which costs far less than
    simplifying the whole derivative. When y has fractions inside, the square with them cleared
    (y = N/d, D → D d²) is tried too, and the shorter result kept."""
    forms = [_quotient_rule(top, bottom, x, momenta)]
    numerator, denominator = sympy.fraction(sympy.together(top))
    if denominator != 1:
        forms.append(_quotient_rule(numerator, bottom * denominator**2, x, momenta))
    return smallest(forms)


def _quotient_rule(top: Any, bottom: Any, x: Any, momenta: tuple[Any, ...]) -> Any:
    dy, dD = sympy.diff(top, x), sympy.diff(bottom, x)
    if dy == 0 and dD == 0:
        return sympy.Integer(0)
    below = factor_terms(sympy.together(bottom))  # m + m x^2/a^2 -> m (a^2 + x^2)/a^2: m cancels, no 1/a^2 inside
    if dD == 0:
        return top * _by_momenta(-dy, momenta) / below
    if dy == 0:
        return top**2 * _shortest(dD) / (2 * below**2)
    return top * _by_momenta(top * dD - 2 * bottom * dy, momenta) / (2 * below**2)


def _by_momenta(expr: Any, momenta: tuple[Any, ...]) -> Any:
    """``expr``, linear in the ``momenta``, as a sum of momenta times simplified coefficients, with any
    common factor taken out."""
    expanded = sympy.expand(expr)
    if ops(expanded) > SHOW_LIMIT:
        return factor_terms(expr)  # expanding only made it longer: left as derived
    parts = sympy.collect(expanded, momenta, evaluate=False)
    return factor_terms(sympy.Add(*(_coefficient(c) * p for p, c in parts.items())))


#: a coefficient of a momentum in Hamilton's equations up to this many operations is simplified fully
COEFFICIENT_LIMIT = 100


def _coefficient(expr: Any) -> Any:
    """One coefficient of a momentum (a function of q): :func:`tidy` (trigonometric identities, cancelled
    fractions) when it is short enough, else its common factors taken out."""
    return tidy(expr) if ops(expr) <= COEFFICIENT_LIMIT else factor_terms(expr)


def _termwise(expr: Any, x: Any, sign: int) -> Any:
    """``sign`` × ∂``expr``/∂``x``, differentiated and simplified term by term (H is a sum of squares and a
    potential: its terms simplify apart far better than together)."""
    return sympy.Add(*(_shortest(sign * sympy.diff(t, x)) for t in sympy.Add.make_args(expr)))


#: above this many operations an expression is left as derived; above TIDY_SHOW only common factors are pulled out
SHOW_LIMIT = 150
TIDY_SHOW = 40


def _shortest(expr: Any) -> Any:
    """The shorter of :func:`tidy_sum` (a sum of terms) and :func:`tidy` (factored); a large expression is left
    as derived (expanding it would only make it longer)."""
    size = ops(expr)
    if size > SHOW_LIMIT:
        return expr
    if size > TIDY_SHOW:
        return sympy.factor_terms(expr)
    return min((tidy_sum(expr), tidy(expr)), key=measure)


def _statement(model: Model, velocities: tuple[Any, ...]) -> tuple[str, tuple[Any, Any, Any]]:
    r"""Which of H = T + V, T₂ − T₀ + V or T₂ − T₀ + V₀ holds, and (T₂, T₁, T₀), the parts of T by degree
    in q̇. By Euler's theorem :math:`\sum_i\dot q_i\,\partial L_k/\partial\dot q_i = k L_k`, so
    :math:`H = L_2 - L_0 = T_2 - V_2 - T_0 + V_0`: decided from the degrees alone."""
    scale = sympy.Dummy("s")
    T, V = model.kinetic, model.potential
    scaled_T = sympy.expand(T.xreplace({v: scale * v for v in velocities}))
    T2, T1, T0 = (scaled_T.coeff(scale, k) for k in (2, 1, 0))
    scaled_V = sympy.expand(V.xreplace({v: scale * v for v in velocities}))
    parts = (tidy_sum(T2), tidy_sum(T1), tidy_sum(T0))
    if not proved_zero(scaled_V.coeff(scale, 2)):
        return "", parts
    if not proved_zero(scaled_V.coeff(scale, 1)):
        return T2_T0_V0, parts
    if proved_zero(T1) and proved_zero(T0):
        return T_PLUS_V, parts
    return T2_T0_V, parts


def _dissipation(reduced: Any, rayleigh: Any) -> tuple[Any, ...]:
    r""":math:`-\partial\mathcal R/\partial\dot q_k` in the minimal coordinates (zeros without a Rayleigh
    function): :math:`\mathcal R` with the dependent velocities put in, since
    :math:`\partial\dot q_i/\partial\dot q_k = \partial q_i/\partial q_k`."""
    model = reduced.model
    if rayleigh is None:
        return tuple(sympy.Integer(0) for _ in model.coordinates)
    R = reduced.substitution.apply(rayleigh)
    return tuple(-sympy.diff(R, v) for v in model.velocities)


def _symmetry_bracket(h: Hamiltonian, model: Model, name: str, flow: tuple[Any, ...]) -> Bracket:
    r"""The rate of the momentum :math:`C = \sum_i \xi_i p_i` of a symmetry's flow ξ
    (:mod:`~lagsolve.mechanics.analysis.symmetry`): :math:`\{C, H\} = X^{(1)}L` at :math:`\dot q(q, p)`, since
    :math:`\partial H/\partial q = -\partial L/\partial q` and :math:`\partial H/\partial p = \dot q`, so it is 0
    exactly when the flow leaves L invariant (proved here again; then the bracket of the long H is not formed);
    else it is computed from C."""
    quantity = sum((x * p for x, p in zip(flow, h.momentum_symbols, strict=True) if x != 0), sympy.Integer(0))
    L = model.lagrangian
    change = sum((sympy.diff(L, q) * x for q, x in zip(model.coordinates, flow, strict=True) if x != 0),
                 sympy.Integer(0))
    change += sum((sympy.diff(L, v) * time_derivative(x, model) for v, x in zip(model.velocities, flow, strict=True)
                   if x != 0), sympy.Integer(0))
    if proved_zero(change):
        bracket, partial_t = sympy.Integer(0), sympy.diff(quantity, h.time)
        forces = sum((x * (f + d) for x, f, d in zip(flow, h.forces, h.dissipation, strict=True) if x != 0),
                     sympy.Integer(0))
    else:
        bracket, partial_t, forces = h._pieces(quantity)
    rate = bracket + partial_t + forces
    status = _status(rate)
    zero = sympy.Integer(0)
    if status == "differ":
        return Bracket(name, quantity, tidy(bracket), tidy(partial_t), tidy(forces), tidy(rate), status)
    return Bracket(name, quantity, zero if bracket == 0 else tidy(bracket), tidy(partial_t), tidy(forces), zero,
                   status)


def _bracket(h: Hamiltonian, name: str, expression: Any, energy: Any) -> Bracket:
    """The rate of one conserved quantity (in q, q̇), computed from it written in (q, p); shown as ``H``
    or ``p_<q>`` when it is that. ``energy`` is the Jacobi integral of the L that H was built from: a
    quantity equal to it term for term once expanded (a cheap exact test) is H written with the velocities,
    by the Legendre transform that built H; one equal to a momentum ∂L/∂q̇ₖ is pₖ, since q̇(q, p) solves
    p = ∂L/∂q̇ exactly."""
    quantity = None  # C written in (q, p), only when it is neither H nor a momentum
    is_energy = sympy.expand(expression - energy) == 0
    momentum = None if is_energy else next(
        (p for p, value in zip(h.momentum_symbols, h.momenta, strict=True) if sympy.expand(expression - value) == 0),
        None)
    if is_energy:
        shown, same = h.expression, "symbolic"
    elif momentum is not None:
        shown, same = momentum, "symbolic"
    else:
        quantity = h.to_momenta(expression)
        shown, same = next(((s, st) for s in (h.expression, *h.momentum_symbols)
                            if (st := _status(quantity - s)) != "differ"), (None, ""))
    # C = H (the energy): {H, H} = 0 identically, so the rate is ∂H/∂t + Σ ∂H/∂p Q with ∂H/∂p = q̇(q, p), the
    # rates already solved, rather than proved 0 from C's longer written form or H differentiated again;
    # C = pₖ: {pₖ, H} = −∂H/∂qₖ, the momentum's rate already derived, and ∂pₖ/∂p Q = Qₖ
    if shown is h.expression:
        bracket, partial_t = sympy.Integer(0), sympy.diff(h.expression, h.time)
        forces = sum((v * (f + d) for v, f, d in zip(h.rates, h.forces, h.dissipation, strict=True)
                      if f + d != 0), sympy.Integer(0))
    elif shown is not None and shown in h.momentum_symbols:
        k = h.momentum_symbols.index(shown)
        bracket, partial_t, forces = h.momentum_rates[k], sympy.Integer(0), h.forces[k] + h.dissipation[k]
    else:
        bracket, partial_t, forces = h._pieces(quantity)
    rate = bracket + partial_t + forces
    status = _status(rate)
    if status == "symbolic" and same == "numeric":
        status = "numeric"  # C = H itself was only checked at random points
    if status == "differ":
        return Bracket(name, shown if shown is not None else _shortest(quantity), tidy(bracket), tidy(partial_t),
                       tidy(forces), tidy(rate), status)
    zero = sympy.Integer(0)
    return Bracket(name, shown if shown is not None else _shortest(quantity), zero if shown is not None else
                   tidy(bracket), tidy(partial_t), tidy(forces), zero, status)


def claimed_rate(h: Hamiltonian, expression: Any, substitution: Any = None) -> tuple[Any, str]:
    r"""The rate :math:`\{C, H\} + \partial C/\partial t + \sum_i \partial C/\partial p_i\,Q_i` of a claimed
    constant of the motion C (in the problem's coordinates and velocities), and whether it is 0:
    ``"symbolic"``, ``"numeric"`` or ``"differ"``. ``substitution`` (an
    :class:`~lagsolve.mechanics.equations.elimination.Elimination`) first writes C in the minimal coordinates."""
    in_minimal = substitution.apply(expression) if substitution is not None else expression
    rate = h.rate(h.to_momenta(in_minimal))
    status = _status(rate)
    return (sympy.Integer(0) if status != "differ" else tidy(rate)), status


#: an identity larger than this (operations) is checked numerically only (exact rewriting costs too much)
PROOF_LIMIT = 400


def _status(expr: Any) -> str:
    """``"symbolic"`` when ``expr`` is proved 0, ``"numeric"`` when it is 0 at random points, else ``"differ"``."""
    if expr == 0:
        return "symbolic"
    if ops(expr) > PROOF_LIMIT:
        zero = _fast_zero(expr) if not expr.atoms(sympy.core.function.AppliedUndef) else numerically_zero(expr)
        return "numeric" if zero else "differ"
    return {Zero.PROVED: "symbolic", Zero.UNDECIDED: "numeric", Zero.NONZERO: "differ"}[zero_status(expr)]


def _fast_zero(expr: Any, samples: int = 6, seed: int = 3) -> bool:
    """``expr`` is 0 (relative to the size of its terms) at ``samples`` random points, evaluated in 30-digit
    floating point through a compiled function (far faster than substituting into a large tree)."""
    import random

    import mpmath

    symbols = sorted(expr.free_symbols, key=sympy.default_sort_key)
    terms = sympy.lambdify(symbols, list(sympy.Add.make_args(expr)), "mpmath", cse=True)
    rng = random.Random(seed)
    with mpmath.workdps(30):
        for _ in range(samples):
            point = [mpmath.mpf(rng.randint(5, 20) if x.is_positive else rng.choice((-1, 1)) * rng.randint(5, 20))
                     / 10 for x in symbols]
            try:
                values = terms(*point)
            except (ZeroDivisionError, ValueError, TypeError):
                continue
            if abs(sum(values)) > mpmath.mpf(10) ** -20 * max(1, sum(abs(v) for v in values)):
                return False
    return True


def routh(model: Model, generalized_forces: tuple[Any, ...], analysis: Analysis) -> tuple[Routhian | None, str]:
    """Routh's reduction of ``model`` by its cyclic coordinates with a conserved momentum (module
    docstring), or None and why there is none."""
    conserved = {c.coordinate for c in analysis.conservation.quantities if c.kind == "momentum"}
    cyclic = tuple(c for c in model.coordinates if c in conserved)
    if not cyclic:
        return None, "no coordinate is cyclic"
    rest = tuple(i for i, c in enumerate(model.coordinates) if c not in conserved)
    if not rest:
        return None, "every coordinate is cyclic, so R = -H and no equation is left"
    L = model.lagrangian
    index = [model.coordinates.index(c) for c in cyclic]
    v = [model.velocities[i] for i in index]
    P = [momentum_symbol(c) for c in cyclic]
    m = len(cyclic)
    zero = {w: sympy.Integer(0) for w in v}
    A = sympy.Matrix(m, m, lambda i, j: sympy.diff(L, v[i], v[j]))
    # L = 1/2 v^T A v + (b + C q_dot)^T v + L_r: with w = p - b - C q_dot, v = A^-1 w and R = L_r - 1/2 w^T A^-1 w
    w = sympy.Matrix([P[i] - sympy.diff(L, v[i]).xreplace(zero) for i in range(m)])
    try:
        squares = complete_squares(A, w)
    except ValueError:
        return None, "the cyclic momenta cannot be solved for the cyclic velocities (a singular matrix)"
    except StageSkipped as exc:
        return None, str(exc)
    velocities = squares.solution
    on = dict(zip(v, velocities, strict=True))
    R = _joined(tuple(-s for s in squares.terms), L.xreplace(zero))
    kept = Model(model.time, tuple(model.coordinates[i] for i in rest), tuple(model.velocities[i] for i in rest),
                 tuple(model.accelerations[i] for i in rest), sympy.Integer(0), sympy.Integer(0), R)
    equations = []
    for k, i in enumerate(rest):
        momentum = sympy.diff(R, kept.velocities[k])
        lhs = time_derivative(momentum, kept, second_order=True)
        rhs = _termwise(R, kept.coordinates[k], 1) + tidy(generalized_forces[i].xreplace(on))
        equations.append((tidy_sum(lhs), rhs))
    rates = tuple(tidy(-sympy.diff(R, p)) for p in P)
    return Routhian(cyclic, tuple(P), velocities, kept.coordinates, R, tuple(equations), rates), ""
