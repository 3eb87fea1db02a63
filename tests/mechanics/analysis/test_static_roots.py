"""Equilibria found without a general solve (``lagsolve.mechanics.analysis.static_roots``): checked against
``sympy.solve``
where that finishes, and against the equations themselves where it does not."""

from __future__ import annotations

import sympy

from lagsolve.mechanics.analysis.static_roots import same_solution, static_roots

x, y, z = sympy.symbols("x y z", real=True)
a, b = sympy.symbols("theta1 theta2", real=True)
r = sympy.Symbol("r", positive=True)
g, k, m, L0, l0 = sympy.symbols("g k m L0 l0", positive=True)


def _key(solution: dict) -> object:
    return sympy.default_sort_key(sympy.Tuple(*sorted(solution.items(), key=sympy.default_sort_key)))


def _same(ours: tuple[dict, ...], theirs: list[dict]) -> bool:
    """The same solutions, each of ours equal to one of sympy's (values compared exactly)."""
    return len(ours) == len(theirs) and all(any(set(s) == set(t) and same_solution(s, t) for t in theirs)
                                            for s in ours)


def test_a_complete_search_gives_sympys_solutions() -> None:
    """Where the search can tell it found everything (factors in one coordinate, linear equations), its
    solutions are the ones ``sympy.solve`` gives: the elastic pendulum at rest (r = 0 or sin θ = 0, then r in
    closed form), two masses on a spring (a continuum, x1 = x2 - L0), three springs in a row (a linear system),
    a polynomial system and a product of sines."""
    systems = [
        ([m * g * sympy.cos(a) - k * (r - l0), -m * g * r * sympy.sin(a)], [r, a]),
        ([-k * (x - y + L0), k * (x - y + L0)], [x, y]),
        ([-k * x - k * (x - y), -k * y + k * (x - y)], [x, y]),
        ([x * y - 1, x - y], [x, y]),
        ([sympy.sin(x) * sympy.cos(y), sympy.sin(y) * (x - 1)], [x, y]),
        ([x**2 - y, y - 4, z * (z - x)], [x, y, z]),
    ]
    for static, coordinates in systems:
        found = static_roots(static, coordinates)
        assert found.complete and found.tried == ()
        assert _same(found.solutions, sympy.solve(static, coordinates, dict=True)), static


def test_coupled_pendulums_are_tried_at_the_obvious_values() -> None:
    """Two pendulums joined by a spring: no equation has a factor in one angle, so θ1 is tried at the zeros of
    its sines and cosines (0, π; π/2, 3π/2) and θ2 solved from what is left. The four points hanging up or
    down are found, each a root of both equations, and the search says it may have missed others (for
    2k l > m g there are: cos θ1 = -m g/(2 k l), θ2 = -θ1)."""
    static = [-g * m * sympy.sin(a) - k * sympy.sin(a) * sympy.cos(a) + k * sympy.sin(b) * sympy.cos(a),
              -g * m * sympy.sin(b) + k * sympy.sin(a) * sympy.cos(b) - k * sympy.sin(b) * sympy.cos(b)]
    found = static_roots(static, [a, b])
    assert not found.complete and found.tried == (a,)
    points = {(s[a], s[b]) for s in found.solutions}
    assert points == {(0, 0), (0, sympy.pi), (sympy.pi, 0), (sympy.pi, sympy.pi)}
    for s in found.solutions:
        assert all(sympy.simplify(f.xreplace(s)) == 0 for f in static)
    other = {a: sympy.acos(-g * m / (2 * k)), b: -sympy.acos(-g * m / (2 * k))}
    assert all(sympy.simplify(f.xreplace(other)) == 0 for f in static)  # the equilibrium it leaves to others


def test_compound_angles_are_expanded() -> None:
    """sin(θ1 - θ2) = 0 with sin θ2 = 0: the compound angle is taken apart into single angles first."""
    static = [sympy.sin(a - b), sympy.sin(b)]
    found = static_roots(static, [a, b])
    assert {(s[a], s[b]) for s in found.solutions} == {(0, 0), (0, sympy.pi), (sympy.pi, 0), (sympy.pi, sympy.pi)}
    for s in found.solutions:
        assert all(sympy.simplify(f.xreplace(s)) == 0 for f in static)


def test_a_pole_is_no_root() -> None:
    """Only the numerator of an equation is taken apart; a point where a denominator vanishes is dropped."""
    found = static_roots([x / (x - 1) - 1 / (x - 1), y], [x, y])
    assert found.solutions == ()


def test_a_constant_force_leaves_no_equilibrium() -> None:
    """An equation left with no coordinate that is not zero (a constant force m g along x, with k y along y) rules
    its case out: no equilibrium is listed, and the search is complete."""
    found = static_roots([m * g, -k * y], [x, y])
    assert found.solutions == () and found.complete


def test_a_transcendental_root_is_given_up_within_its_cap(monkeypatch) -> None:
    """Two pendulums on torsion springs at rest: θ2 comes out of a linear equation, and the equation left in θ1
    is transcendental (sympy.solve takes well over 18 s on it); the search gives it up after its CPU cap and says
    it is not complete, with no solution invented."""
    from lagsolve.mechanics.analysis import static_roots as module

    monkeypatch.setattr(module, "ROOT_SOLVE_CAP", 0.2)
    rest = sympy.Symbol("a", real=True)
    potential = k * (a - rest) ** 2 / 2 + k * (b - rest) ** 2 / 2 + k * (a - b) ** 2 / 4 - m * g * (sympy.cos(a)
                                                                                                 + sympy.cos(b))
    static = [-sympy.diff(potential, q) for q in (a, b)]
    found = static_roots(static, [a, b])
    assert found.solutions == () and found.complete is False
