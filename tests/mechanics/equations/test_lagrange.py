"""Lagrange's equations in matrix form and the augmented solve
(``lagsolve.mechanics.equations.lagrange``), checked against equations derived by hand and by
substituting the solution back."""

from __future__ import annotations

import functools

import pytest
import sympy

from lagsolve.errors import DerivationError, LagsolveError
from lagsolve.mechanics.derivation import derive
from lagsolve.mechanics.equations.constraints import constraint_terms
from lagsolve.mechanics.equations.forces import force_terms
from lagsolve.mechanics.equations.lagrange import lagrange_terms, solve_augmented, solve_linear
from lagsolve.mechanics.equations.model import build_model
from mechanics_support import (
    TUBE,
    assert_zero,
    exactly_equal,
    names,
    problem_file,
    problem_text,
)

SPHERICAL = """
name: Particle in spherical coordinates under gravity
parameters: {m: mass, g: gravity}
coordinates: [r, theta, phi]
particles:
  p: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), r*cos(theta)]}
gravity: [0, 0, -g]
"""

PENDULUM = """
name: Simple pendulum
parameters: {m: mass, g: gravity, l: length}
coordinates: [theta]
particles:
  bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}
gravity: [0, -g]
"""

HOOP = """
name: Bead on a hoop driven about the vertical
parameters: {m: mass, g: gravity, R: radius, Omega: rate of turn}
coordinates: [r, theta, phi]
particles:
  bead: {mass: m, position: [r*sin(theta)*cos(phi), r*sin(theta)*sin(phi), -r*cos(theta)]}
gravity: [0, 0, -g]
constraints:
  hoop: {holonomic: r - R}
  drive: {holonomic: phi - Omega*t}
"""

DAMPED_DRIVEN = """
name: Damped particle on a shaken wire
parameters: {m: mass, g: gravity, c: damping, A: amplitude, w: frequency}
functions: {f: wire shape}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
gravity: [0, -g]
dissipation: c*(x_dot**2 + y_dot**2)/2
constraints:
  wire: {holonomic: y - f(x) - A*sin(w*t)}
"""

NO_INERTIA = """
name: A coordinate without inertia
parameters: {m: mass}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, 0]}
"""

REDUNDANT = """
name: The same constraint twice
parameters: {m: mass, g: gravity}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  floor: {holonomic: y}
  again: {holonomic: 2*y}
"""


@functools.cache
def system(text: str | None = None, name: str | None = None):
    """(problem, model, constraint terms, LagrangeTerms, accelerations, multipliers)."""
    problem = problem_text(text) if text is not None else problem_file(name)
    model = build_model(problem)
    constraints = tuple(constraint_terms(c, model) for c in problem.constraints)
    loads = force_terms(problem, model)
    q = tuple(sum((t.generalized[i] for t in loads), sympy.Integer(0))
              for i in range(len(model.coordinates)))
    terms = lagrange_terms(model, constraints, q)
    acc, lam = solve_augmented(terms)
    return problem, model, constraints, terms, acc, lam


def lagrange_by_hand(lagrangian, model, time, forces=None):
    """d/dt(dL/dq_dot) - dL/dq - Q, with d/dt taken through functions of time."""
    paths = {q: sympy.Function(f"_q{i}")(time) for i, q in enumerate(model.coordinates)}
    speeds = {v: sympy.diff(paths[q], time) for q, v in zip(model.coordinates, model.velocities,
                                                           strict=True)}
    back = {sympy.Derivative(paths[q], (time, 2)): a
            for q, a in zip(model.coordinates, model.accelerations, strict=True)}
    back |= {sympy.Derivative(paths[q], time): v
             for q, v in zip(model.coordinates, model.velocities, strict=True)}
    back |= {p: q for q, p in paths.items()}
    out = []
    for i, (q, v) in enumerate(zip(model.coordinates, model.velocities, strict=True)):
        rate = sympy.diff(sympy.diff(lagrangian, v).xreplace(speeds).xreplace(paths), time)
        rate = rate.xreplace(back)
        out.append(rate - sympy.diff(lagrangian, q) - (forces[i] if forces else 0))
    return out


def test_spherical_mass_matrix_and_forcing():
    """In spherical coordinates M = diag(m, m r^2, m r^2 sin^2) and F holds the textbook
    centripetal, Coriolis and gravity terms."""
    problem, model, _, terms, _, _ = system(SPHERICAL)
    s = names(problem)
    m, g, r, th = s["m"], s["g"], s["r"], s["theta"]
    rd, thd, phd = s["r_dot"], s["theta_dot"], s["phi_dot"]
    st, ct = sympy.sin(th), sympy.cos(th)
    assert exactly_equal(terms.mass_matrix, sympy.diag(m, m * r**2, m * r**2 * st**2))
    forcing = [
        m * r * thd**2 + m * r * st**2 * phd**2 - m * g * ct,
        m * r**2 * st * ct * phd**2 + m * g * r * st - 2 * m * r * rd * thd,
        -2 * m * r * rd * st**2 * phd - 2 * m * r**2 * st * ct * thd * phd,
    ]
    for ours, hand in zip(terms.forcing, forcing, strict=True):
        assert exactly_equal(ours, hand)
    assert terms.constraint_jacobian.shape == (0, 3)


def test_equations_match_lagrange_by_hand_knife_edge():
    """The knife edge's equations equal d/dt(dL/dq_dot) - dL/dq - lambda a_i, L written by hand."""
    problem, model, constraints, terms, _, _ = system(name="knife_edge")
    s = names(problem)
    m, l_, th, xd, yd, thd = s["m"], s["l"], s["theta"], s["x_dot"], s["y_dot"], s["theta_dot"]
    lagrangian = m * (xd**2 + yd**2) / 2 + m * ((xd - l_ * sympy.sin(th) * thd) ** 2
                                               + (yd + l_ * sympy.cos(th) * thd) ** 2) / 2
    lam = constraints[0].multiplier
    a = (-sympy.sin(th), sympy.cos(th), 0)
    hand = lagrange_by_hand(lagrangian, model, problem.time)
    for ours, eq, ai in zip(terms.equations, hand, a, strict=True):
        assert exactly_equal(ours, eq - lam * ai)


def test_equations_match_lagrange_by_hand_with_dissipation():
    """On a shaken wire with damping, each equation is
    d/dt(dL/dq_dot) - dL/dq + dR/dq_dot - lambda a_i."""
    problem, model, constraints, terms, _, _ = system(DAMPED_DRIVEN)
    s = names(problem)
    m, g, c, x, y, xd, yd, f = (s[k] for k in ("m", "g", "c", "x", "y", "x_dot", "y_dot", "f"))
    lagrangian = m * (xd**2 + yd**2) / 2 - m * g * y
    q = (-c * xd, -c * yd)
    lam = constraints[0].multiplier
    a = (-sympy.Derivative(f(x), x), 1)
    hand = lagrange_by_hand(lagrangian, model, problem.time, q)
    for ours, eq, ai in zip(terms.equations, hand, a, strict=True):
        assert exactly_equal(ours, eq - lam * ai)


@pytest.mark.parametrize("key", ["bead", "knife_edge", "hole_table", "tube", "hoop", "damped"])
def test_matrix_form_reproduces_the_equations(key):
    """Each equation equals row i of M q_ddot - F - A^T lambda."""
    _, model, constraints, terms, _, _ = _by_key(key)
    qdd = sympy.Matrix(model.accelerations)
    lam = sympy.Matrix([c.multiplier for c in constraints])
    lhs = terms.mass_matrix * qdd - terms.forcing
    if constraints:
        lhs -= terms.constraint_jacobian.T * lam
    for ours, matrix_row in zip(terms.equations, lhs, strict=True):
        assert sympy.expand(ours - matrix_row) == 0 or exactly_equal(ours, matrix_row)


def _by_key(key):
    texts = {"tube": TUBE, "hoop": HOOP, "damped": DAMPED_DRIVEN}
    return system(texts[key]) if key in texts else system(name=key)


def _wire(x):
    return sympy.sin(x) + x**3 / 5


@pytest.mark.parametrize("key", ["bead", "knife_edge", "hole_table", "tube", "hoop", "damped"])
def test_augmented_solution_satisfies_every_equation(key):
    """The returned accelerations and multipliers make every Lagrange equation and every
    A q_ddot - beta vanish at random states."""
    problem, model, constraints, terms, acc, lam = _by_key(key)
    solution = dict(zip(model.accelerations, acc, strict=True))
    solution |= {c.multiplier: v for c, v in zip(constraints, lam, strict=True)}
    functions = {f.function: _wire for f in problem.functions}
    for eq in terms.equations:
        assert_zero(eq.xreplace(solution), functions=functions, samples=15)
    for c in constraints:
        level = sum(a * q for a, q in zip(c.coefficients, model.accelerations, strict=True))
        assert_zero((level - c.acceleration_rhs).xreplace(solution), functions=functions,
                    samples=15)


def test_unconstrained_pendulum():
    """With no constraints the solve is M q_ddot = F: theta_ddot = -(g/l) sin(theta)."""
    problem, _, _, _, acc, lam = system(PENDULUM)
    s = names(problem)
    assert exactly_equal(acc[0], -s["g"] / s["l"] * sympy.sin(s["theta"]))
    assert lam == ()


def test_hoop_driven_by_a_time_dependent_constraint():
    """A bead on a hoop turned at rate Omega has theta_ddot = sin(th)(Omega^2 cos(th) - g/R)
    on the constraint surface, with lambda_drive = 2 m R^2 sin cos theta_dot Omega."""
    problem, _, _, _, acc, lam = system(HOOP)
    s = names(problem)
    m, g, big_r, omega, th, thd = (s[k] for k in ("m", "g", "R", "Omega", "theta", "theta_dot"))
    on_surface = {s["r"]: big_r, s["r_dot"]: 0, s["phi_dot"]: omega}
    st, ct = sympy.sin(th), sympy.cos(th)
    assert exactly_equal(acc[1].xreplace(on_surface), st * (omega**2 * ct - g / big_r))
    assert exactly_equal(lam[1].xreplace(on_surface), 2 * m * big_r**2 * st * ct * thd * omega)
    assert exactly_equal(lam[0].xreplace(on_surface),
                         -m * big_r * thd**2 - m * big_r * st**2 * omega**2 - m * g * ct)


def test_singular_system_without_inertia_raises():
    """A coordinate with no inertia and no constraint makes solve_augmented raise a
    DerivationError that says the system is singular and why."""
    terms = _singular(NO_INERTIA)
    with pytest.raises(DerivationError) as info:
        solve_augmented(terms)
    message = str(info.value)
    assert "singular" in message
    assert "no inertia" in message
    assert isinstance(info.value, LagsolveError)


def _singular(text):
    """The LagrangeTerms of ``text``, built without solving."""
    problem = problem_text(text)
    model = build_model(problem)
    constraints = tuple(constraint_terms(c, model) for c in problem.constraints)
    zero = tuple(sympy.Integer(0) for _ in model.coordinates)
    return lagrange_terms(model, constraints, zero)


def test_redundant_constraints_are_refused_before_the_derivation():
    """Two redundant constraints are refused (a SpecError naming them and the fix), before anything is solved."""
    from lagsolve.errors import SpecError

    with pytest.raises(SpecError, match="redundant") as info:
        derive(problem_text(REDUNDANT))
    assert "remove again" in str(info.value)


def test_solve_linear_matches_an_independent_solver():
    """solve_linear agrees exactly with SymPy's LUsolve on a symbolic 3x3 system."""
    a, b, c = sympy.symbols("a b c", positive=True)
    matrix = sympy.Matrix([[0, a, 1], [b, 1, c], [1, 0, a + b]])
    rhs = sympy.Matrix([1, a * c, b])
    ours = sympy.Matrix(solve_linear(matrix, rhs))
    assert exactly_equal(ours, matrix.LUsolve(rhs))


def test_solve_linear_rejects_a_singular_matrix():
    """A symbolically singular matrix (rows proportional) raises ValueError 'no pivot'."""
    a = sympy.Symbol("a", positive=True)
    matrix = sympy.Matrix([[a, 2 * a], [1, 2]])
    with pytest.raises(ValueError, match="no pivot"):
        solve_linear(matrix, sympy.Matrix([1, 1]))


def _shipped():
    from mechanics_support import shipped

    return shipped()


@pytest.mark.parametrize("name", _shipped())
def test_symengine_engine_gives_the_same_equations(name):
    """The numeric stage's matrix form (untidied energies, derivatives by SymEngine) equals the derivation's
    (tidied energies, derivatives by SymPy): M, F, the momenta and the equations agree at random points,
    and use the problem's own symbols."""
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    problem = problem_file(name)
    shown, fast = matrix_form(problem), matrix_form(problem, display=False)
    pairs = [(shown.lagrange.mass_matrix, fast.lagrange.mass_matrix), (shown.lagrange.forcing, fast.lagrange.forcing)]
    pairs += list(zip(shown.lagrange.momenta, fast.lagrange.momenta, strict=True))
    pairs += list(zip(shown.lagrange.equations, fast.lagrange.equations, strict=True))
    own = set(problem.symbols.values()) | {c.acceleration for c in problem.coordinates}
    own |= {c.multiplier for c in shown.constraints} | {f.normal for f in shown.frictions}
    for a, b in pairs:
        a, b = sympy.Matrix([a]), sympy.Matrix([b])
        assert set().union(*(e.free_symbols for e in b)) <= own
        for x, y in zip(a, b, strict=True):
            assert_zero(x - y, samples=6)


def test_symengine_engine_on_the_pendulum_is_exact():
    """On the double pendulum the two engines' M and F are symbolically identical."""
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    problem = problem_file("double_pendulum")
    shown, fast = matrix_form(problem), matrix_form(problem, display=False)
    assert exactly_equal(shown.lagrange.mass_matrix, fast.lagrange.mass_matrix)
    assert exactly_equal(shown.lagrange.forcing, fast.lagrange.forcing)


def test_cancelled_is_sympys_cancel_of_a_reduced_fraction():
    """ringsolve.cancelled writes a coprime P/Q exactly as sympy.cancel would (same tree)."""
    from lagsolve.mechanics.symbolic.ringsolve import cancelled

    a, b, m, ell = sympy.symbols("a b m ell", positive=True)
    s, c = sympy.sin(a), sympy.cos(a - b)
    pairs = [(-m * s + 2 * ell * c, 3 - c**2), (6 * m * s, -4 * ell + 2 * m * c), (-s, -ell),
             (sympy.Integer(0), ell * c),
             (2 * m, sympy.Integer(4))]
    for numer, denom in pairs:
        assert sympy.srepr(cancelled(numer, denom)) == sympy.srepr(sympy.cancel(numer / denom))


@pytest.mark.parametrize("name", ["bead", "central_force", "driven_oscillator", "pendulum_cartesian", "rolling_incline",
                                  "sliding_off_sphere", "spring_on_rough_floor"])
def test_a_small_lagrangian_gives_the_same_equations_by_sympy_as_by_symengine(name, monkeypatch):
    """A Lagrangian of fewer than algebra.ENGINE_FROM nodes is differentiated by SymPy (SymEngine is not loaded for
    it); made to go through SymEngine instead, it gives the same momenta, rates, M, F and equations."""
    from lagsolve.mechanics.equations import lagrange
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.mechanics.symbolic.algebra import small

    problem = problem_file(name)
    default = matrix_form(problem, display=False)
    assert small(default.model.lagrangian)
    monkeypatch.setattr(lagrange, "small", lambda expr: False)
    lagrange._lagrange_terms.cache_clear()  # remembered: the call above has the SymPy route's answer
    engine = lagrange.lagrange_terms(default.model, default.constraints, default.lagrange.generalized_forces,
                                     engine="symengine")
    ours = default.lagrange
    assert engine is not ours and lagrange._symengine_parts(default.model) is not None  # SymEngine did take it
    lagrange._lagrange_terms.cache_clear()
    for a, b in [(ours.mass_matrix, engine.mass_matrix), (ours.forcing, engine.forcing),
                 *zip(ours.momenta, engine.momenta, strict=True),
                 *zip(ours.momenta_rates, engine.momenta_rates, strict=True),
                 *zip(ours.equations, engine.equations, strict=True)]:
        assert sympy.simplify(sympy.Matrix([a]) - sympy.Matrix([b])).is_zero_matrix
