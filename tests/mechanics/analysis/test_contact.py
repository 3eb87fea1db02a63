"""Equilibria where a unilateral constraint would have to pull are not admissible."""

from __future__ import annotations

import json

import sympy

from lagsolve.mechanics.analysis.contact import check_point
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_text
from lagsolve.render.report import render, result_dict, summary

#: sliding_off_sphere.yaml in polar coordinates, so that the analysis finds the equilibria θ = 0 and θ = π
SPHERE = """
name: Particle on a sphere
parameters: {m: mass, g: gravity, R: radius}
coordinates: {r: {description: distance from the centre, positive: true}, theta: angle from the top}
particles:
  p: {mass: m, position: [r*sin(theta), r*cos(theta)]}
gravity: [0, -g]
constraints:
  surface: {holonomic: r - R, unilateral: true}
"""


def test_the_multiplier_at_rest_decides() -> None:
    """λ₀ < 0 is not admissible, λ₀ ≥ 0 is, and a sign that depends on the parameters is left open."""
    x, xd = sympy.symbols("x x_dot", real=True)
    m, g, k = sympy.symbols("m g k", positive=True)
    checks = check_point({"c": m * g * sympy.cos(x) + xd**2, "d": k - g}, ("c", "d"), {x: sympy.pi},
                         {xd: sympy.Integer(0)})
    assert [(c.constraint, c.multiplier, c.admissible) for c in checks] == [("c", -g * m, False),
                                                                            ("d", k - g, None)]


def test_the_bottom_of_the_sphere_is_not_admissible() -> None:
    """On the outside of a sphere, θ = π (hanging below it) would need the surface to pull."""
    derivation = derive(load_text(SPHERE, "sphere.yaml"))
    v = derivation.analysis.effective_potential
    verdicts = {e.value: checks[0].admissible for e, checks in zip(v.equilibria,
                                                                  derivation.analysis.effective_contact, strict=True)}
    assert verdicts == {0: True, sympy.pi: False}
    data = result_dict(derivation)
    assert data["constraints"]["surface"]["unilateral"] is True
    json_equilibria = data["analysis"]["effective_potential"]["equilibria"]
    assert [e["admissible"] for e in json_equilibria] == [True, False]
    assert json_equilibria[1]["contact"] == {"surface": "-g*m"}
    json.dumps(data)
    assert "not admissible: surface would pull" in summary(derivation)


def test_reports_say_unilateral_and_not_admissible() -> None:
    """Both reports call the constraint unilateral and mark θ = π not admissible."""
    derivation = derive(load_text(SPHERE, "sphere.yaml"))
    md, tex = render(derivation, "md"), render(derivation, "tex")
    assert "**unilateral**" in md and r"\textbf{unilateral}" in tex
    assert "**not admissible**: the unilateral constraint surface would have to pull" in md
    assert r"\textbf{not admissible}" in tex
