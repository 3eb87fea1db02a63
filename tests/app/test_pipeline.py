"""Library entry points: output names are safe, golden comparison reports every difference, check returns counts."""

from __future__ import annotations

from pathlib import Path

import pytest

from lagsolve.app.pipeline import Reports, check_file, derive_file, golden_differences
from lagsolve.errors import SpecError
from lagsolve.files import safe_slug

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(("path", "slug"), [
    ("problems/bead.yaml", "bead"),
    ("../../etc/passwd.yaml", "passwd"),
    ("My Bead (v2).yaml", "My_Bead_v2"),
    ("...yaml", "problem"),
    ("/tmp/a/b/..", "problem"),
])
def test_safe_slug_cannot_leave_the_output_folder(path: str, slug: str) -> None:
    """Output names come from the file name alone, with anything but letters, digits, _ and - replaced."""
    assert safe_slug(path) == slug


def test_golden_differences_names_missing_and_changed_files(tmp_path: Path) -> None:
    """A missing golden file and a changed one are both reported; equal files are not."""
    reports = Reports("p.yaml", "p", "P", "", {"md": "a\nb\n", "json": "{}\n", "tex": "x\n"})
    (tmp_path / "p.md").write_text("a\nc\n")
    (tmp_path / "p.json").write_text("{}\n")
    diffs = golden_differences(reports, tmp_path)
    assert len(diffs) == 2
    assert "-c\n+b\n" in diffs[0]
    assert "p.tex (missing; create it with --update-golden)" in diffs[1]


def test_derive_file_validates_before_deriving(tmp_path: Path) -> None:
    """An invalid file raises SpecError from the loader, before any derivation starts."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\n")
    with pytest.raises(SpecError, match="missing required key 'coordinates'"):
        derive_file(bad)


def test_derive_file_returns_all_formats() -> None:
    """derive_file gives the summary and each requested format as text."""
    reports = derive_file(ROOT / "problems" / "bead.yaml", ("json",))
    assert reports.slug == "bead" and set(reports.outputs) == {"json"}
    assert reports.summary.startswith("Bead on a wire")


def test_check_file_returns_the_table_and_counts() -> None:
    """check_file derives and checks in the budgeted child and returns the table and the verdict counts."""
    checked = check_file(ROOT / "problems" / "atwood.yaml")
    assert checked.name == "Atwood machine" and checked.passed
    assert checked.counts == {"ok": 4, "warning": 0, "mismatch": 0, "unchecked": 0}
    assert checked.table.startswith("Atwood machine (") and "✓" in checked.table


def test_check_file_validates_before_deriving(tmp_path: Path) -> None:
    """An invalid file raises SpecError before any derivation or check starts."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\n")
    with pytest.raises(SpecError, match="missing required key 'coordinates'"):
        check_file(bad)


def test_a_derivation_stopped_after_its_core_names_each_missing_stage() -> None:
    """The answer given when the budget stops a derivation after its core (--timeout 0.1) names every stage
    that did not complete, in the terminal summary, the reports and the JSON, instead of "Later stages"."""
    from pathlib import Path

    from lagsolve.app.pipeline import _render_core
    from lagsolve.mechanics.derivation import core
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.problem.load import load_problem

    bead = Path(__file__).resolve().parents[2] / "problems" / "bead.yaml"
    partial = core(matrix_form(load_problem(bead), display=False))
    summary, outputs, _ = _render_core(("md", "json"), None, 0.1)(partial, "the budget ran out")
    for stage in ("Explicit solve", "Display simplification", "Forces of constraint", "Conserved quantities",
                  "Hamiltonian"):
        line = f"{stage}: did not finish within the derivation's 0.1 s CPU budget (raise it with --timeout)"
        assert line in summary and f"- {line}" in outputs["md"]
    assert "Later stages" not in summary + outputs["md"]
    import json

    notes = json.loads(outputs["json"])["notes"]
    assert [n["stage"] for n in notes][:3] == ["explicit solve", "forces of constraint", "display simplification"]
    assert "The explicit solution is not written out: did not finish within" in outputs["md"]


def test_the_child_warms_up_for_the_first_file_and_inherits_for_the_next(monkeypatch: pytest.MonkeyPatch) -> None:
    """The first file's budgeted child imports the mechanics itself while this process loads the file; from the
    next file on this process has imported them before the fork (no warm-up sent), and the reports are the same."""
    import sys

    from lagsolve.app import budget, pipeline

    monkeypatch.setattr(pipeline, "_WARMED", set())
    sent: list[object] = []
    real = budget.run_with_budget

    def spy(*args: object, **kwargs: object) -> object:
        sent.append(kwargs.get("warm"))
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(budget, "run_with_budget", spy)
    first = derive_file(ROOT / "problems" / "bead.yaml", ("md",))
    second = derive_file(ROOT / "problems" / "bead.yaml", ("md",))
    assert sent == [pipeline._warm_derive, None]
    assert "lagsolve.mechanics.derivation" in sys.modules and "sympy.physics.units" in sys.modules
    assert first.outputs == second.outputs and first.summary == second.summary
    with pytest.raises(SpecError):  # a file that does not load: its error, whichever process is warm
        derive_file(ROOT / "problems" / "no such file.yaml")


@pytest.mark.parametrize("name", ["bead", "coupled_pendulums"])
def test_a_small_derivation_rendered_here_gives_the_childs_reports(name: str, monkeypatch: pytest.MonkeyPatch
                                                                    ) -> None:
    """A small derivation comes back from its child to be rendered by this process (which imported the renderers
    meanwhile); rendered in the child instead (RENDER_HERE = 0) every report and figure is byte for byte the same,
    and both are the golden reports."""
    from lagsolve.app import budget, pipeline

    sent: list[object] = []
    real = budget.run_with_budget

    def spy(*args: object, **kwargs: object) -> object:
        answer = real(*args, **kwargs)  # type: ignore[arg-type]
        sent.append(type(answer).__name__)
        return answer

    monkeypatch.setattr(budget, "run_with_budget", spy)
    here = derive_file(ROOT / "problems" / f"{name}.yaml")
    monkeypatch.setattr(pipeline, "RENDER_HERE", 0)
    there = derive_file(ROOT / "problems" / f"{name}.yaml")
    assert sent == ["_Derived", "tuple"]
    assert here.outputs == there.outputs and here.files == there.files and here.summary == there.summary
    assert golden_differences(here, ROOT / "tests" / "golden") == []
