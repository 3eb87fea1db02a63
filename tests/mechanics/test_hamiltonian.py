"""Hamiltonian mechanics (mechanics/hamiltonian.py) against textbook results and the Lagrange route."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest
import sympy

from lagsolve.check.compare import check
from lagsolve.mechanics.derivation import derive
from lagsolve.mechanics.hamiltonian import T2_T0_V, T2_T0_V0, T_PLUS_V
from lagsolve.problem.load import load_problem, load_text
from lagsolve.problem.names import momentum_symbol
from lagsolve.render.report import result_dict

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"

MAGNETIC = """
name: Charged particle in a uniform magnetic field
parameters: {m: mass, q: charge, B0: field}
coordinates: [x, y]
particles:
  p: {mass: m, position: [x, y]}
potential: "-q*B0*(x*y_dot - y*x_dot)/2"
"""


#: a triple pendulum hung from a support driven sideways: p = A q_dot + b with b != 0 and a dense 3×3 A whose
#: inverse is long, so H and Hamilton's equations come from the fraction-free inverse (no sum of squares)
DRIVEN_TRIPLE = """
name: Triple pendulum on a driven support
parameters: {m: mass, g: gravity, l: length, a: amplitude, w: angular frequency}
coordinates: [th1, th2, th3]
particles:
  p1: {mass: m, position: [a*cos(w*t) + l*sin(th1), -l*cos(th1)]}
  p2: {mass: m, position: [a*cos(w*t) + l*sin(th1) + l*sin(th2), -l*cos(th1) - l*cos(th2)]}
  p3: {mass: m, position: [a*cos(w*t) + l*sin(th1) + l*sin(th2) + l*sin(th3), -l*cos(th1) - l*cos(th2) - l*cos(th3)]}
gravity: [0, -g]
"""
#: a damped double pendulum on a free cart: a long inverse (compact route) with a cyclic coordinate x and a
#: Rayleigh function
CART_DOUBLE = """
name: Damped double pendulum on a free cart
parameters: {M: cart mass, m: bob mass, l: rod length, g: gravity, c: damping}
coordinates: [x, th1, th2]
particles:
  cart: {mass: M, position: [x, 0]}
  b1: {mass: m, position: [x + l*sin(th1), -l*cos(th1)]}
  b2: {mass: m, position: [x + l*sin(th1) + l*sin(th2), -l*cos(th1) - l*cos(th2)]}
gravity: [0, -g]
dissipation: "c*th1_dot**2/2"
"""
INLINE = {"driven_triple": DRIVEN_TRIPLE, "cart_double": CART_DOUBLE}


def _derived(name: str):
    if name in INLINE:
        return derive(load_text(INLINE[name], f"{name}.yaml"))
    return derive(load_problem(PROBLEMS / f"{name}.yaml"))


def _constant(expr, variables) -> bool:
    """``expr`` does not depend on any of ``variables`` (its derivatives simplify to 0)."""
    return all(sympy.simplify(sympy.diff(expr, v)) == 0 for v in variables)


def _sym(d, name):
    return d.problem.symbols[name]


def test_hole_table_hamiltonian_is_the_textbook_one():
    """H = p_r²/(2(m1 + m2)) + p_θ²/(2 m1 r²) + m2 g r up to a constant, equal to T + V."""
    d = _derived("hole_table")
    h = d.hamiltonian
    r, theta, m1, m2, g = (_sym(d, n) for n in ("r", "theta", "m1", "m2", "g"))
    pr, pt = momentum_symbol(r), momentum_symbol(theta)
    textbook = pr**2 / (2 * (m1 + m2)) + pt**2 / (2 * m1 * r**2) + m2 * g * r
    assert h.coordinates == (r, theta)
    assert _constant(h.expression - textbook, (r, theta, pr, pt))
    assert h.form == T_PLUS_V
    assert h.routhian is not None and h.routhian.cyclic == (theta,)


def test_charged_particle_momentum_is_not_m_v_and_h_is_the_kinetic_energy():
    """With L = m v²/2 + q v·A, p = m v + q A, and H = (p − qA)²/(2m), the kinetic energy."""
    d = derive(load_text(MAGNETIC))
    h = d.hamiltonian
    x, y, m, q, B0 = (_sym(d, n) for n in ("x", "y", "m", "q", "B0"))
    xd, yd = d.model.velocities
    px, py = momentum_symbol(x), momentum_symbol(y)
    assert sympy.simplify(h.momenta[0] - (m * xd - q * B0 * y / 2)) == 0
    assert sympy.simplify(h.momenta[1] - (m * yd + q * B0 * x / 2)) == 0
    assert h.form == T2_T0_V0
    assert sympy.simplify(h.expression - ((px + q * B0 * y / 2) ** 2 + (py - q * B0 * x / 2) ** 2) / (2 * m)) == 0
    assert sympy.simplify(h.expression - h.to_momenta(d.model.kinetic)) == 0


def test_heavy_top_two_cyclic_momenta_and_routhian():
    """Goldstein 5.7: H = p_θ²/(2I₁') + (p_φ − p_ψ cos θ)²/(2I₁' sin²θ) + p_ψ²/(2I₃) + m g l cos θ; φ, ψ cyclic."""
    d = _derived("heavy_top")
    h = d.hamiltonian
    phi, theta, psi, m, arm, I1, I3, g = (_sym(d, n) for n in ("phi", "theta", "psi", "m", "l", "I1", "I3", "g"))
    pphi, ptheta, ppsi = (momentum_symbol(c) for c in (phi, theta, psi))
    J = I1 + m * arm**2
    textbook = (ptheta**2 / (2 * J) + (pphi - ppsi * sympy.cos(theta)) ** 2 / (2 * J * sympy.sin(theta) ** 2)
                + ppsi**2 / (2 * I3) + m * g * arm * sympy.cos(theta))
    assert sympy.simplify(h.expression - textbook) == 0
    assert h.momentum_rates[0] == 0 and h.momentum_rates[2] == 0
    # Goldstein (5.67): the quotient rule on the square, in the textbook's form (printed as it is here)
    rate = (pphi - ppsi * sympy.cos(theta)) * (pphi * sympy.cos(theta) - ppsi) / (J * sympy.sin(theta) ** 3)
    assert h.momentum_rates[1] == rate + m * g * arm * sympy.sin(theta)
    r = h.routhian
    assert r is not None and r.cyclic == (phi, psi) and r.coordinates == (theta,)
    # consistent with the effective potential: -R at rest in θ is V_eff up to a constant
    thetad = d.model.velocities[1]
    veff = d.analysis.effective_potential.expression
    assert _constant(-r.expression.xreplace({thetad: 0}) - veff, (theta,))  # constants in p_c are dropped from V_eff
    assert {b.name for b in h.brackets} == {"p_phi", "p_psi", "energy"}
    assert all(b.status == "symbolic" and b.rate == 0 for b in h.brackets)


def test_bead_on_rotating_hoop_h_is_not_t_plus_v():
    """Taylor ch. 7: H = p²/(2mR²) − mR²Ω² sin²θ/2 − m g R cos θ = T₂ − T₀ + V, not T + V."""
    d = _derived("bead_on_rotating_hoop")
    h = d.hamiltonian
    theta, m, R, g, Om = (_sym(d, n) for n in ("theta", "m", "R", "g", "Omega"))
    p = momentum_symbol(theta)
    textbook = p**2 / (2 * m * R**2) - m * R**2 * Om**2 * sympy.sin(theta) ** 2 / 2 - m * g * R * sympy.cos(theta)
    assert sympy.simplify(h.expression - textbook) == 0
    assert h.form == T2_T0_V
    energy = h.to_momenta(d.analysis.reduced.kinetic + d.analysis.reduced.potential)
    assert sympy.simplify(h.expression - energy) != 0


def test_spherical_pendulum():
    """Thornton–Marion ch. 7: H = p_θ²/(2ml²) + p_φ²/(2ml² sin²θ) − m g l cos θ; R's V_eff as the analysis's."""
    d = _derived("spherical_pendulum")
    h = d.hamiltonian
    theta, phi, m, rod, g = (_sym(d, n) for n in ("theta", "phi", "m", "l", "g"))
    pt, pp = momentum_symbol(theta), momentum_symbol(phi)
    textbook = (pt**2 / (2 * m * rod**2) + pp**2 / (2 * m * rod**2 * sympy.sin(theta) ** 2)
                - m * g * rod * sympy.cos(theta))
    assert sympy.simplify(h.expression - textbook) == 0
    thetad = d.model.velocities[0]
    veff = d.analysis.effective_potential.expression
    assert _constant(-h.routhian.expression.xreplace({thetad: 0}) - veff, (theta,))


CASES = ["hole_table", "heavy_top", "bead_on_rotating_hoop", "spherical_pendulum", "double_pendulum",
         "spring_damper", "driven_oscillator", "moving_support", "wedge", "cone", "atwood", "bowl",
         "triple_pendulum", "driven_triple", "cart_double"]


def _values(symbols, rng):
    return {s: sympy.Float(rng.uniform(0.4, 1.6) * rng.choice((1, 1 if s.is_positive else -1)), 30)
            for s in symbols}


@pytest.mark.parametrize("name", CASES)
def test_hamilton_equations_agree_with_lagrange_at_random_states(name):
    """At 12 random states, ∂H/∂p gives back q̇ and ṗ equals d/dt ∂L/∂q̇ along Lagrange's accelerations;
    H equals the Jacobi integral h = Σ q̇ ∂L/∂q̇ − L written with p."""
    d = _derived(name)
    h = d.hamiltonian
    reduced = d.analysis.reduced
    model = reduced.model
    acc = reduced.acceleration_map()
    assert acc, "the Lagrange route gives explicit accelerations"
    rng = random.Random(7)
    L = model.lagrangian
    jacobi = sum((v * sympy.diff(L, v) for v in model.velocities), sympy.Integer(0)) - L
    for _ in range(12):
        state = _values(sorted(L.free_symbols | set(model.velocities) | set(model.coordinates) | {model.time}
                               | set().union(*(f.free_symbols for f in reduced.generalized_forces)),
                               key=sympy.default_sort_key), rng)
        momenta = {p: sympy.diff(L, v).xreplace(state) for p, v in zip(h.momentum_symbols, model.velocities,
                                                                    strict=True)}
        point = {**state, **momenta}
        for i, v in enumerate(model.velocities):
            assert abs(sympy.N(h.rates[i].xreplace(point)) - state[v]) < 1e-12
            momentum = sympy.diff(L, v)
            lagrange = model.time_derivative(momentum, second_order=True).xreplace(acc).xreplace(state)
            hamilton = (h.momentum_rates[i] + h.forces[i] + h.dissipation[i]).xreplace(point)
            assert abs(sympy.N(hamilton - lagrange)) < 1e-10 * max(1.0, abs(sympy.N(lagrange)))
        assert abs(sympy.N(h.expression.xreplace(point) - jacobi.xreplace(state))) < 1e-10
    energy = next((c for c in d.analysis.conservation.quantities if c.name == "energy"), None)
    if energy is not None:
        assert sympy.simplify(h.to_momenta(energy.expression) - h.expression) == 0


def _concrete(expr):
    """``expr`` with each function of the file (f(x), F(t)) replaced by one known function."""
    u = sympy.Symbol("u")
    for applied in sorted(expr.atoms(sympy.core.function.AppliedUndef), key=sympy.default_sort_key):
        expr = expr.replace(applied.func, sympy.Lambda(u, u**2 / 3 + sympy.sin(u) + 2))
    return expr.doit()


@pytest.mark.parametrize("name", ["double_pendulum", "triple_pendulum", "bowl", "heavy_top", "block_two_pendulums",
                                  "bead", "moving_support", "driven_triple"])
def test_hamilton_equations_are_the_numerical_derivatives_of_h(name):
    """Another route than Lagrange's: at random points, q̇ and ṗ equal ∂H/∂p and −∂H/∂q taken by numerical
    differentiation (mpmath, 30 digits) of H itself."""
    import mpmath

    h = _derived(name).hamiltonian
    H = _concrete(h.expression)
    rates, velocities = [_concrete(e) for e in h.momentum_rates], [_concrete(e) for e in h.rates]
    symbols = sorted(H.free_symbols.union(*(e.free_symbols for e in rates + velocities)), key=sympy.default_sort_key)
    rng = random.Random(11)
    for _ in range(6):
        point = {s: sympy.Rational(rng.randint(5, 20), 10) for s in symbols}
        for i, q in enumerate(h.coordinates):
            for shown, x, sign in ((rates[i], q, -1), (velocities[i], h.momentum_symbols[i], 1)):
                along = sympy.lambdify([x], H.xreplace({k: v for k, v in point.items() if k != x}), "mpmath")
                with mpmath.workdps(30):
                    numeric = sign * mpmath.diff(along, mpmath.mpf(point.get(x, 1)))  # a cyclic q is not in H
                    value = sympy.N(shown.xreplace(point), 30)
                    assert abs(complex(value) - complex(numeric)) < 1e-12 * max(1, abs(complex(numeric)))


@pytest.mark.parametrize(("name", "compact"), [("triple_pendulum", True), ("block_two_pendulums", True),
                                               ("driven_triple", True), ("double_pendulum", False),
                                               ("cart_double", True), ("heavy_top", False)])
def test_a_long_inverse_is_given_in_matrix_form(name, compact):
    """A dense block of three coordinates with a long inverse: no sum of squares, the reports give the matrix
    form (the JSON the full forms, checked above); the short ones are written out as squares."""
    h = _derived(name).hamiltonian
    assert h.compact is compact
    if compact:  # H = ½ (p − b)ᵀ q̇(q, p) + U, one term per momentum, not squares of sums
        assert not any(isinstance(term, sympy.Pow) and term.exp == 2 for term in sympy.Add.make_args(h.expression)
                       if term.free_symbols & set(h.momentum_symbols))


def test_a_conserved_momentum_is_recognised_exactly_with_a_long_inverse():
    """p_x of the cart is ∂L/∂ẋ term for term: shown as p_x, its bracket proved 0 (not only at random points),
    although written with the long q̇(q, p) it is far past what is simplified."""
    h = _derived("cart_double").hamiltonian
    (bracket,) = h.brackets
    assert (bracket.name, bracket.status, bracket.rate) == ("p_x", "symbolic", 0)
    assert bracket.quantity == h.momentum_symbols[0]


def test_nonholonomic_constraint_makes_it_not_applicable():
    """The knife edge keeps a nonholonomic constraint: no H, and the reason says so (JSON not_applicable)."""
    d = _derived("knife_edge")
    assert d.hamiltonian is None
    assert "nonholonomic" in d.hamiltonian_note
    assert result_dict(d)["hamiltonian"] == {"not_applicable": d.hamiltonian_note}


def test_json_shape_of_the_hole_table():
    """momenta p_<q> in q and q_dot, H in q and p, equations <q>_dot and p_<q>_dot, routhian, brackets."""
    out = json.loads(json.dumps(result_dict(_derived("hole_table"))))["hamiltonian"]
    assert out["coordinates"] == ["r", "theta"]
    assert set(out["momenta"]) == {"p_r", "p_theta"} and "theta_dot" in out["momenta"]["p_theta"]
    assert set(out["equations"]) == {"r_dot", "theta_dot", "p_r_dot", "p_theta_dot"}
    assert "p_theta" in out["H"] and "_dot" not in out["H"]
    assert out["routhian"]["cyclic"] == ["theta"]
    assert out["poisson_brackets"]["p_theta"]["rate"] == "0"
    assert out["form"] == "T + V"


def test_check_verifies_a_claim_by_its_poisson_bracket():
    """A true claim passes {C, H} + ∂C/∂t = 0; p_r, which is not conserved, fails it."""
    text = (PROBLEMS / "hole_table.yaml").read_text()
    claim = '    p_theta: "m1*r**2*theta_dot"'
    text = text.replace(claim, claim + '\n    p_r: "(m1 + m2)*r_dot"')
    report = check(derive(load_text(text)))
    by_name = {v.name: v for v in report.verdicts}
    assert by_name["p_theta.poisson_bracket"].status == "ok"
    assert by_name["energy.poisson_bracket"].status == "ok"
    assert by_name["p_r.poisson_bracket"].status == "mismatch"


@pytest.mark.budget
def test_a_hamiltonian_out_of_budget_is_named_and_the_rest_comes_out(monkeypatch):
    """When the Hamiltonian stage runs out of its CPU share, a note names it, the key is null, the rest is there."""
    import lagsolve.mechanics.hamiltonian as module

    def spin(*args, **kwargs):
        while True:
            pass

    monkeypatch.setattr(module, "hamiltonian", spin)
    d = derive(load_problem(PROBLEMS / "hole_table.yaml"), budget=6)
    assert d.hamiltonian is None and d.accelerations is not None and d.conserved
    assert [(n.stage, n.kind) for n in d.notes if n.stage == "hamiltonian"] == [("hamiltonian", "budget")]
    assert result_dict(d)["hamiltonian"] is None
