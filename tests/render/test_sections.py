"""The report sections (``lagsolve.render.sections``): built once from a derivation, holding exactly its
expressions in display order, and projected alike by the templates' context, the JSON and the terminal."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import pytest
import sympy

from lagsolve.mechanics.derivation import Derivation, core
from lagsolve.render.model import JsonPrinter, metadata, present
from lagsolve.render.notation import Notation, to_json
from lagsolve.render.report import (
    page_parts,
    render_sections,
    result_dict,
    sections_context,
    sections_json,
    sections_summary,
    template_dirs,
)
from lagsolve.render.sections import Sections, build
from lagsolve.render.sections.analysis import Agreement
from lagsolve.render.sections.hamiltonian import HamiltonianSection, NotApplicable, NotDerived
from lagsolve.render.units import unit_tex

Shipped = Callable[[str], Derivation]


def _text(derivation: Derivation) -> Callable[[object], str]:
    return Notation([c.name for c in derivation.problem.coordinates]).text


def _in_order(lines: list[str], wanted: list[str]) -> bool:
    """Each of ``wanted`` is a line of ``lines``, in this order."""
    position = 0
    for want in wanted:
        try:
            position = lines.index(want, position) + 1
        except ValueError:
            return False
    return True


@pytest.fixture(scope="module")
def bead(shipped_derivation: Shipped) -> Derivation:
    return shipped_derivation("bead")


@pytest.fixture(scope="module")
def wedge(shipped_derivation: Shipped) -> Derivation:
    return shipped_derivation("wedge")


def test_core_sections_hold_exactly_the_derivations_expressions(wedge: Derivation) -> None:
    """The records carry the derivation's own SymPy objects, one per coordinate or constraint, in their order."""
    s = build(wedge).core
    assert [c.name for c in s.coordinates] == [c.name for c in wedge.problem.coordinates]
    assert [c.symbol for c in s.coordinates] == [c.symbol for c in wedge.problem.coordinates]
    assert (s.kinetic, s.potential, s.lagrangian) == (wedge.kinetic, wedge.potential, wedge.lagrangian)
    assert [c.name for c in s.constraints] == [c.name for c in wedge.constraints]
    assert [c.expression for c in s.constraints] == [c.expression for c in wedge.constraints]
    assert [[a.value for a in c.coefficients] for c in s.constraints] == [
        list(c.coefficients) for c in wedge.constraints]
    assert [(e.lhs, e.rhs) for e in s.equations] == list(wedge.equation_sides)
    assert wedge.accelerations is not None and s.accelerations is not None
    assert [(a.name, a.value) for a in s.accelerations] == list(wedge.accelerations.items())
    assert wedge.multipliers is not None and s.multipliers is not None
    assert [(m.name, m.value) for m in s.multipliers] == list(wedge.multipliers.items())
    assert [m.symbol for m in s.multipliers] == list(wedge.multiplier_symbols)
    assert s.matrix.mass == wedge.mass_matrix and list(s.matrix.forcing) == list(wedge.forcing)
    assert len(s.matrix.rows) == len(wedge.problem.coordinates)


def test_sections_are_frozen_and_built_alike(bead: Derivation) -> None:
    """A section cannot be changed after it is built, and building twice gives equal sections."""
    sections = build(bead)
    with pytest.raises(dataclasses.FrozenInstanceError):
        sections.core.name = "other"  # type: ignore[misc]
    assert build(bead) == sections


def test_every_projection_lists_the_results_in_the_same_order(wedge: Derivation) -> None:
    """Accelerations and multipliers: the context, the JSON keys and the terminal lines follow the records."""
    sections = build(wedge)
    s = sections.core
    assert s.accelerations is not None and s.multipliers is not None
    context, data = sections_context(sections), sections_json(sections)
    lines = sections_summary(sections).splitlines()
    text = _text(wedge)
    for key, rows in (("accelerations", s.accelerations), ("multipliers", s.multipliers)):
        assert [r["name"] for r in context["core"][key]] == [r.name for r in rows]
        assert list(data[key]) == [r.name for r in rows]
        assert list(data[key].values()) == [to_json(r.value) for r in rows]
        assert _in_order(lines, [f"    {text(r.symbol)} = {text(r.value)}" for r in rows])
    assert list(data["constraints"]) == [c.name for c in s.constraints] == [
        c["name"] for c in context["core"]["constraints"]]
    assert s.forces is not None
    assert list(data["constraint_forces"]) == [f.name for f in s.forces] == [
        f["name"] for f in context["core"]["forces"]]


def test_the_core_writes_the_contracts_keys_in_order(bead: Derivation) -> None:
    """The core's record gives the JSON's top-level keys of format section 2 in the contract's order, and the
    sections put analysis, hamiltonian, notes and units after them."""
    core_keys = ["format_version", "name", "coordinates", "parameters", "kinetic", "potential", "lagrangian",
                 "constraints", "equations", "mass_matrix", "forcing", "accelerations", "multipliers",
                 "constraint_forces", "friction", "reduced", "conserved", "effective_potential", "notes"]
    sections = build(bead)
    assert list(present(sections.core, JsonPrinter())) == core_keys
    assert list(sections_json(sections)) == [*core_keys[:-1], "analysis", "hamiltonian", "notes", "units"]


def test_pages_include_one_partial_per_section_in_field_order(bead: Derivation, wedge: Derivation) -> None:
    """Markdown and LaTeX pages include the sections' partials in the order of the fields of Sections (no units
    partial without units), each figure after its section (in LaTeX, whose figures float, the simulation after the
    results); every partial exists in each template folder."""
    assert page_parts(build(bead), ".md") == ["_core.md.j2", "_units.md.j2", "_analysis.md.j2", "_potential.md.j2",
                                              "_hamiltonian.md.j2", "_simulation.md.j2"]
    no_units = build(wedge)
    assert no_units.units is None
    # LaTeX floats its figures: the simulation follows the results (the units where there are), so that the
    # analysis after it fills the pages around its figures
    assert page_parts(no_units, ".tex") == ["_core.tex.j2", "_simulation.tex.j2", "_analysis.tex.j2",
                                            "_potential.tex.j2", "_hamiltonian.tex.j2"]
    assert page_parts(build(bead), ".tex")[:3] == ["_core.tex.j2", "_units.tex.j2", "_simulation.tex.j2"]
    partials = [meta.partial for f in dataclasses.fields(Sections) if (meta := metadata(f, Sections)).partial]
    for kind, extension in (("markdown", ".md"), ("latex", ".tex"), ("html", ".html")):
        for partial in partials:
            assert any((d / f"{partial}{extension}.j2").is_file() for d in template_dirs(kind)), (kind, partial)


def test_the_json_of_the_sections_is_the_result_contract(bead: Derivation) -> None:
    """result_dict is the JSON projection of the sections, nothing else."""
    assert result_dict(bead) == sections_json(build(bead))


def test_core_only_derivation_projects_the_matrix_form(wedge: Derivation) -> None:
    """Without explicit accelerations, every output says so: null in the JSON and context, one matrix row per
    coordinate in the terminal."""
    assert wedge.form is not None
    stopped = build(core(wedge.form, "stopped for the test"))
    assert stopped.core.accelerations is None and stopped.analysis is None
    assert sections_json(stopped)["accelerations"] is None
    assert sections_context(stopped)["core"]["accelerations"] is None
    text = _text(wedge)
    rows = [f"    ({i + 1}) {text(r.lhs)} = {text(r.forcing)} + Σ λ a" for i, r in enumerate(stopped.core.matrix.rows)]
    assert len(rows) == len(wedge.problem.coordinates)
    assert _in_order(sections_summary(stopped).splitlines(), rows)
    assert sections_json(stopped)["analysis"] is None and sections_context(stopped)["analysis"] is None


def test_friction_section_carries_the_closed_normal_force(shipped_derivation: Shipped) -> None:
    """A friction contact's record holds N as derived; the JSON and the terminal print that N."""
    derivation = shipped_derivation("incline_cartesian")
    sections = build(derivation)
    assert [f.name for f in sections.core.friction] == [f.term.name for f in derivation.friction]
    for record, result in zip(sections.core.friction, derivation.friction, strict=True):
        assert record.normal_force == result.normal_force
        assert sections_json(sections)["friction"][record.name]["normal_force"] == to_json(result.normal_force)
        text = _text(derivation)
        assert f"  friction {record.name}: normal force {text(record.normal)} = {text(record.normal_shown)}" in (
            sections_summary(sections).splitlines())


def test_analysis_sections_list_conserved_quantities_alike(shipped_derivation: Shipped) -> None:
    """Conserved quantities: the derivation's, in its order, in the context, the JSON and the terminal."""
    derivation = shipped_derivation("hole_table")
    sections: Sections = build(derivation)
    analysis = sections.analysis
    assert analysis is not None and derivation.analysis is not None
    quantities = derivation.analysis.conservation.quantities
    assert [(c.name, c.expression) for c in analysis.conserved] == [(c.name, c.expression) for c in quantities]
    context, data = sections_context(sections), sections_json(sections)
    assert [c["name"] for c in context["analysis"]["conserved"]] == [c.name for c in quantities]
    assert list(data["analysis"]["conserved"]) == [c.name for c in quantities]
    text, lines = _text(derivation), sections_summary(sections).splitlines()
    heads = [f"    {text(c.symbol)} = {text(c.expression)}" for c in analysis.conserved]
    positions = [next(i for i, line in enumerate(lines) if line.startswith(head)) for head in heads]
    assert positions == sorted(positions) and len(set(positions)) == len(positions)
    assert analysis.effective is not None
    assert len(context["analysis"]["effective"]["equilibria"]) == len(analysis.effective.equilibria) == len(
        data["analysis"]["effective_potential"]["equilibria"])
    for shown, derived in zip(analysis.effective.equilibria, derivation.analysis.effective_potential.equilibria,
                              strict=True):
        q, q0 = analysis.effective.coordinate, analysis.effective.at
        assert shown.condition == derived.condition.xreplace({q: q0})  # shown in q0, as the text says


def test_hamiltonian_section_follows_the_minimal_coordinates(shipped_derivation: Shipped) -> None:
    """One canonical pair per coordinate of H, in order, in every projection."""
    derivation = shipped_derivation("spherical_pendulum")
    h = derivation.hamiltonian
    assert h is not None
    sections = build(derivation)
    section = sections.hamiltonian
    assert isinstance(section, HamiltonianSection)
    assert [c.coordinate for c in section.coordinates] == list(h.coordinates)
    assert [c.momentum for c in section.coordinates] == list(h.momentum_symbols)
    assert section.expression == h.expression
    data = sections_json(sections)["hamiltonian"]
    assert data["coordinates"] == [q.name for q in h.coordinates]
    assert list(data["momenta"]) == [p.name for p in h.momentum_symbols]
    context = sections_context(sections)["hamiltonian"]
    assert len(context["coordinates"]) == len(h.coordinates)
    text = _text(derivation)
    wanted = [f"    {text(sympy.Symbol(c.coordinate.name + '_dot'))} = {text(c.rate)},  "
              f"ṗ{text(c.momentum)[1:]} = {text(c.momentum_rate)}" for c in section.coordinates]
    assert _in_order(sections_summary(sections).splitlines(), wanted)


@pytest.mark.parametrize(("missing", "json", "sentence", "line"), [
    (NotApplicable("a velocity constraint remains"), {"not_applicable": "a velocity constraint remains"},
     "Not applicable: a velocity constraint remains.", "  Hamiltonian: not applicable: a velocity constraint remains"),
    (NotDerived("did not finish"), None, "Not applicable: did not finish.", None),
    (None, None, None, None),
], ids=["not applicable", "not derived", "no analysis"])
def test_a_missing_hamiltonian_is_said_alike_in_every_format(bead: Derivation, missing: object, json: object,
                                                               sentence: str | None, line: str | None) -> None:
    """Without a formulation, the JSON writes why (null when its stage did not finish or there is no analysis), the
    reports say why (no section without an analysis) and the terminal names a physical reason only."""
    sections = dataclasses.replace(build(bead), hamiltonian=missing)
    assert sections_json(sections)["hamiltonian"] == json
    markdown, summary = render_sections(sections, "md"), sections_summary(sections)
    assert ("## Hamiltonian mechanics" in markdown) is (sentence is not None)
    assert sentence is None or f"\n{sentence}\n" in markdown
    assert [x for x in summary.splitlines() if "Hamiltonian" in x] == ([line] if line else [])


def test_units_section_rows_are_the_tables_rows(bead: Derivation) -> None:
    """The units table of the reports has one row per record; the JSON gives each acceleration's unit."""
    sections = build(bead)
    units = sections.units
    assert units is not None
    latex, mathml = sections_context(sections)["units"], sections_context(sections, "mathml")["units"]
    assert [r["unit"] for r in mathml["rows"]] == [r.unit.text or "?" for r in units.rows]
    assert [r["unit"] for r in latex["rows"]] == [unit_tex(r.unit.text) for r in units.rows]
    assert sections_json(sections)["units"]["accelerations"] == {"x": "m/s^2", "y": "m/s^2"}


#: the sentences the Markdown and LaTeX templates wrote for each agreement before they came from the sections
OLD_SENTENCES = {
    "symbolic": ("Solved for the accelerations they give exactly the accelerations of the multiplier route above, "
                 "with the same substitutions (checked symbolically):"),
    "unchecked": ("Solved for the accelerations they give (the multiplier route has no explicit accelerations to "
                  "compare with here):"),
    "numeric": ("Solved for the accelerations they agree with the multiplier route above at random states "
                "(the symbolic check was inconclusive):"),
    "differ": "{warning}: solved for the accelerations they differ from the multiplier route above; please report "
              "this as a bug:",
}


@pytest.mark.parametrize("agreement", list(OLD_SENTENCES))
def test_agreement_sentence_is_written_once_for_markdown_and_latex(bead: Derivation, agreement: str) -> None:
    """The reduced system's agreement sentence, kept in the sections, reads in Markdown and LaTeX as the two
    templates wrote it (a warning in bold), and the terminal names the agreement."""
    sections = build(bead)
    analysis = sections.analysis
    assert analysis is not None and analysis.reduced is not None and not analysis.reduced.trivial
    changed = dataclasses.replace(sections, analysis=dataclasses.replace(
        analysis, reduced=dataclasses.replace(analysis.reduced, agreement=Agreement(agreement))))
    markdown, latex = render_sections(changed, "md"), render_sections(changed, "tex")
    assert "\n" + OLD_SENTENCES[agreement].format(warning="**Warning**") + "\n" in markdown
    assert "\n" + OLD_SENTENCES[agreement].format(warning="\\textbf{Warning}") + "\n" in latex
    assert changed.analysis is not None and changed.analysis.reduced is not None
    phrase = changed.analysis.reduced.agreement.phrase
    assert any(line.startswith("  minimal coordinates: ") and line.endswith(f"({phrase})")
               for line in sections_summary(changed).splitlines())


def test_a_compact_hamiltonian_is_projected_in_matrix_form() -> None:
    """With a long inverse (the triple pendulum) the reports and the terminal give H = ½ pᵀA⁻¹p + U: the long
    q̇(q, p), H and ṗ are not printed for them (only the JSON carries them in full)."""
    from pathlib import Path

    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    derivation = derive(load_problem(Path(__file__).resolve().parents[2] / "problems" / "triple_pendulum.yaml"))
    sections = build(derivation)
    assert isinstance(sections.hamiltonian, HamiltonianSection) and sections.hamiltonian.compact
    context = sections_context(sections)["hamiltonian"]
    assert context["expression"] == "" and context["remainder"]
    assert all(c["inverse"] == c["momentum_rate"] == "" and c["momentum_value"] for c in context["coordinates"])
    summary = sections_summary(sections)
    assert "H = 1/2 p^T A^-1 p + U (= T + V), U = " in summary and "ṗ" not in summary
    data = sections_json(sections)["hamiltonian"]
    assert set(data["equations"]) == {"theta1_dot", "theta2_dot", "theta3_dot", "p_theta1_dot", "p_theta2_dot",
                                      "p_theta3_dot"}
    assert "p_theta1" in data["H"]
