"""The analysis in the reports (``lagsolve.render.sections.analysis`` presented): JSON contract shapes,
worked-solution sections and terminal lines."""

from __future__ import annotations

import json

import pytest

from lagsolve.render.model import NotationPrinter, present
from lagsolve.render.notation import Notation
from lagsolve.render.report import render, result_dict, summary
from lagsolve.render.sections.analysis import analysis_section
from mechanics_support import derived_file


@pytest.fixture(scope="module")
def hole():
    return derived_file("hole_table")


def test_json_contract_for_the_hole_table(hole):
    """reduced, conserved and effective_potential appear as format section 2 says, as strings and bools."""
    data = json.loads(render(hole, "json"))
    assert data["reduced"] == {"independent": ["r", "theta"], "accelerations": data["reduced"]["accelerations"]}
    assert set(data["conserved"]) == {"p_theta", "energy"}
    assert data["conserved"]["p_theta"] == "m1*r**2*theta_dot"
    effective = data["effective_potential"]
    assert effective["coordinate"] == "r"
    assert effective["expression"] == "g*m2*r + p_theta**2/(2*m1*r**2)"
    (orbit,) = effective["equilibria"]
    assert orbit["stable"] is True and isinstance(orbit["value"], str) and isinstance(orbit["frequency"], str)
    assert data["analysis"]["constraints"]["string"]["class"] == "holonomic"
    assert data["analysis"]["reduced"]["dependent"] == {"z": "-l + r"}


def test_json_nulls_where_the_analysis_does_not_apply():
    """The knife edge has no reduced system and no effective potential (null), and a reason for each."""
    data = result_dict(derived_file("knife_edge"))
    assert data["reduced"] is None and data["effective_potential"] is None
    assert "nonholonomic" in data["analysis"]["reduced"]["note"]
    assert data["analysis"]["constraints"]["skate"]["frobenius"]["value"] == "-1"


def test_markdown_has_the_worked_analysis(hole):
    """The Markdown report has the classification, minimal coordinates, conserved quantities and V_eff."""
    md = render(hole, "md")
    for heading in ("## Analysis", "### Constraint classification", "### Minimal coordinates",
                    "### Conserved quantities", "### Effective potential"):
        assert heading in md
    assert "checked symbolically" in md
    assert r"V_{\mathrm{eff}}(r) = g m_{2} r + \frac{p_{\theta}^{2}}{2 m_{1} r^{2}}" in md
    assert r"r_{0}^{3} = \frac{p_{\theta}^{2}}{g m_{1} m_{2}}" in md and "**stable**" in md


def test_markdown_equilibria_section_for_several_degrees_of_freedom():
    """The double pendulum's report lists its equilibria with omega^2 and stability."""
    md = render(derived_file("double_pendulum"), "md")
    assert "### Equilibria and small oscillations" in md
    assert r"\omega^2 = \frac{g \left(2 - \sqrt{2}\right)}{l}" in md


def test_latex_has_the_analysis_sections(hole):
    """The LaTeX report carries the same sections."""
    tex = render(hole, "tex")
    assert r"\section*{Analysis}" in tex and r"\subsection*{Effective potential}" in tex


def test_context_is_plain_data(hole):
    """The analysis context holds only strings, numbers, booleans, lists, dicts and None."""

    def check(value: object) -> None:
        if isinstance(value, dict):
            for v in value.values():
                check(v)
        elif isinstance(value, list):
            for v in value:
                check(v)
        else:
            assert value is None or isinstance(value, str | int | float | bool), type(value)

    for name in ("hole_table", "knife_edge", "rotating_tube", "double_pendulum", "spherical_pendulum"):
        derivation = derived_file(name)
        note = Notation([c.name for c in derivation.problem.coordinates])
        for kind in ("latex", "mathml", "text"):
            check(present(analysis_section(derivation), NotationPrinter(kind, note)))


def test_summary_shows_the_analysis(hole):
    """The terminal summary lists the conserved quantities, V_eff and the circular orbit."""
    text = summary(hole)
    assert "p_θ = m1*r²*θ̇" in text
    assert "V_eff(r) = g*m2*r + p_θ²/(2*m1*r²)" in text
    assert "r_0³ = p_θ²/(g*m1*m2): stable, ω² = 3*g*m2/(r_0*(m1 + m2))" in text


def test_normal_modes_in_every_projection():
    """The coupled pendulums' modes hanging down: in the JSON each ω² with its shape by coordinate and the note
    on how the equilibria were found; in Markdown and HTML each ω² beside its shape; in the terminal one line
    per mode."""
    pendulums = derived_file("coupled_pendulums")
    linear = result_dict(pendulums)["analysis"]["linearization"]
    down = linear["equilibria"][0]
    assert down["squared_frequencies"] == ["g/l", "g/l + 2*k/m"]
    assert down["mode_shapes"] == [{"theta1": "1", "theta2": "1"}, {"theta1": "1", "theta2": "-1"}]
    assert "Found without a general solve" in linear["search"] and "finds no other" in linear["search"]
    md = render(pendulums, "md")
    assert r"$`\omega^2 = \frac{g}{l}`$ with $`u = \left(1, 1\right)`$ and" in md
    assert r"$`u = \left(1, -1\right)`$: **stable**" in md
    html = render(pendulums, "html")
    assert ('<mi>u</mi><mo>=</mo><mrow><mo stretchy="false">(</mo><mn>1</mn><mo>,</mo><mrow><mo>&#8722;</mo><mn>1</mn>'
            '</mrow><mo stretchy="false">)</mo></mrow>') in html
    text = summary(pendulums)
    assert ("θ1 = 0, θ2 = 0: stable\n      ω² = g/l, mode shape (1, 1)\n"
            "      ω² = g/l + 2*k/m, mode shape (1, -1)") in text


def test_numeric_modes_are_labelled_in_the_json():
    """Where ω² are numeric (the triple pendulum hanging down) the equilibrium's note says so in the JSON too."""
    down = result_dict(derived_file("triple_pendulum"))["analysis"]["linearization"]["equilibria"][0]
    assert "numeric, at the simulation values" in down["note"]
    assert [float(x) for x in down["mode_shapes"][0].values()] == pytest.approx([1.0, 1.2921127, 1.6312233])


def test_the_readme_shows_the_modes_lagsolve_prints():
    """The README's coupled-pendulum excerpt is the terminal summary's equilibria block, line for line."""
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    (block,) = [b for b in readme.split("```\n")[1::2] if "mode shape (1, 1)" in b]
    assert block.startswith("  equilibria:\n")
    assert block in summary(derived_file("coupled_pendulums")) + "\n"


def test_steady_motions_in_json_reports_and_terminal():
    """The top's steady precession is in the JSON analysis (condition, two rates, stable, omega^2, the eliminated g),
    under *Steady motions* in Markdown, LaTeX and HTML, and in the terminal summary."""
    top = derived_file("heavy_top")
    steady = result_dict(top)["analysis"]["steady_motions"]
    assert (steady["coordinate"], steady["rate"], steady["stable"]) == ("theta", "phi", True)
    assert len(steady["values"]) == 2 and set(steady["eliminated"]) == {"g"}
    assert steady["verified"] == "equations of motion" and list(steady["held"]) == ["p_psi"]
    assert "### Steady motions" in render(top, "md")
    assert r"\subsection*{Steady motions}" in render(top, "tex")
    assert '<h3 id="steady-motions">Steady motions</h3>' in render(top, "html")
    assert "  steady motions (θ_0 fixed, φ̇ constant, p_ψ held): " in summary(top)
    assert result_dict(derived_file("atwood"))["analysis"]["steady_motions"] == {
        "note": "no coordinate is cyclic: the equilibria of the effective potential are states of rest"}


def test_symmetry_momenta_in_json_reports_and_terminal():
    """The bowl's L_z carries its symmetry and generator in the JSON and the reports; a cyclic momentum that is a
    symmetry's (the spherical pendulum's p_phi) is named as such."""
    bowl = derived_file("bowl")
    data = result_dict(bowl)
    assert data["conserved"]["L_z"] == "m*(x*y_dot - x_dot*y)"
    assert data["analysis"]["conserved"]["L_z"]["symmetry"] == "rotation about z"
    assert data["analysis"]["conserved"]["L_z"]["generator"] == {"x": "-y", "y": "x"}
    assert r"\delta x = - y\,\varepsilon,\ \delta y = x\,\varepsilon" in render(bowl, "md")
    (line,) = [line for line in summary(bowl).splitlines() if line.startswith("    L_z = ")]
    assert line.endswith(" (rotation about z)")
    pendulum = result_dict(derived_file("spherical_pendulum"))["analysis"]["conserved"]["p_phi"]
    assert pendulum["symmetry"] == "rotation about z" and pendulum["generator"] == {"phi": "1"}
