"""Equilibria and normal modes of several degrees of freedom (``lagsolve.mechanics.linearize``)."""

from __future__ import annotations

import sympy

from mechanics_support import derived_file, derived_text, exactly_equal, names

COUPLED = """
name: Two masses, three springs, one damper
parameters: {m: mass, k: stiffness, c: damping}
coordinates: [x1, x2]
particles:
  a: {mass: m, position: [x1, 0]}
  b: {mass: m, position: [x2, 0]}
potential: k*x1**2/2 + k*(x2 - x1)**2/2 + k*x2**2/2
dissipation: c*x1_dot**2/2
"""


def test_double_pendulum_normal_modes():
    """Equal masses and lengths: omega^2 = (2 - sqrt 2) g/l and (2 + sqrt 2) g/l about the hanging position."""
    pendulum = derived_file("double_pendulum")
    s = names(pendulum.problem)
    g, rod = s["g"], s["l"]
    modes = pendulum.analysis.linearization.modes
    assert len(modes) == 4
    down = next(m for m in modes if all(v == 0 for _, v in m.point))
    assert down.stable is True
    expected = sorted([(2 - sympy.sqrt(2)) * g / rod, (2 + sympy.sqrt(2)) * g / rod], key=sympy.default_sort_key)
    assert len(down.squared_frequencies) == 2
    for got in down.squared_frequencies:
        assert any(exactly_equal(got, want) for want in expected)
    assert exactly_equal(down.stiffness, sympy.Matrix([[2 * s["m"] * g * rod, 0], [0, s["m"] * g * rod]]))


def test_double_pendulum_other_equilibria_are_unstable():
    """Every equilibrium with a rod pointing up has a negative omega^2: unstable."""
    modes = derived_file("double_pendulum").analysis.linearization.modes
    up = [m for m in modes if any(v != 0 for _, v in m.point)]
    assert len(up) == 3 and all(m.stable is False for m in up)


def test_damping_gives_d_and_no_modes():
    """With a damper the linearization carries D = diag(c, 0) and says the modes are not computed."""
    coupled = derived_text(COUPLED)
    (mode,) = coupled.analysis.linearization.modes
    c = names(coupled.problem)["c"]
    assert exactly_equal(mode.damping, sympy.Matrix([[c, 0], [0, 0]]))
    assert mode.squared_frequencies is None and "damping" in mode.note


def test_cyclic_coordinates_are_left_to_the_effective_potential():
    """The hole table (one coordinate after removing theta) is handled by the effective potential instead."""
    hole = derived_file("hole_table")
    assert hole.analysis.linearization is None
    assert hole.analysis.effective_potential is not None
