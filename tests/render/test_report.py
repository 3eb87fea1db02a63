"""Reports: the JSON contract reads back, templates are found, LaTeX compiles, user text is inert."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import sympy
from sympy.parsing.sympy_parser import parse_expr

from lagsolve.errors import RenderError
from lagsolve.mechanics.derivation import Derivation, derive
from lagsolve.problem.load import load_text
from lagsolve.render.report import context, render, result_dict, summary, template_dirs
from mechanics_support import shipped

ROOT = Path(__file__).resolve().parents[2]

HOSTILE = r"""
name: '<script>alert(1)</script> \input{/etc/passwd} 100%'
description: 'See \input{/etc/passwd} and \write18{rm -rf /}; $x$ & # _ ^ ~ <b>bold</b>'
parameters: {m: mass, k: stiffness}
coordinates: {x: 'position \textbf{x}'}
particles: {p: {mass: m, position: [x, 0]}}
potential: k*x**2/2
"""


@pytest.fixture(scope="module")
def bead(shipped_derivation: Callable[[str], Derivation]) -> Derivation:
    return shipped_derivation("bead")


@pytest.fixture(scope="module")
def hostile() -> Derivation:
    return derive(load_text(HOSTILE, "hostile.yaml"))


def test_json_reads_back_with_parse_expr(bead: Derivation) -> None:
    """Every expression in the JSON parses back (with the input's names) to the derived expression."""
    data = result_dict(bead)
    x, xd = bead.problem.symbols["x"], bead.problem.symbols["x_dot"]
    names = {"x": x, "x_dot": xd, "m": bead.problem.symbols["m"], "g": bead.problem.symbols["g"],
             "f": bead.problem.functions[0].function}
    # the test reads trusted output of lagsolve itself, so parse_expr is fine here
    back = parse_expr(data["accelerations"]["x"], local_dict=names)
    assert sympy.simplify(back - bead.accelerations["x"]) == 0
    lam = parse_expr(data["multipliers"]["wire"], local_dict=names)
    assert sympy.simplify(lam - bead.multipliers["wire"]) == 0
    assert data["format_version"] == 1
    assert json.loads(render(bead, "json")) == data


def test_markdown_is_a_worked_solution(bead: Derivation) -> None:
    """The Markdown report walks through T, V, L, the constraint, each equation and the results."""
    md = render(bead, "md")
    for heading in ("# Bead on a wire", "## Kinetic and potential energy", "## Constraints",
                    "## Lagrange's equations", "### Coordinate $`x`$", "## Eliminating the multipliers",
                    "## Results"):
        assert heading in md
    assert r"a_{x} = - f'\left(x\right)" in md
    assert r"\ddot{x} &= - \frac{\left(g + \dot{x}^{2} f''\left(x\right)\right) f'\left(x\right)}" in md


def test_summary_lists_key_results(bead: Derivation) -> None:
    """The terminal summary shows each acceleration, multiplier and force magnitude."""
    text = summary(bead)
    assert "x\u0308 = " in text and "\u03bb_wire = " in text and "|F_wire| = " in text


def test_user_text_is_escaped_in_latex(hostile: Derivation) -> None:
    """Names and descriptions cannot inject TeX: \\input and \\write18 are printed as text."""
    tex = render(hostile, "tex")
    assert r"\input{/etc/passwd}" not in tex and r"\write18" not in tex
    assert r"\textbackslash{}input\{/etc/passwd\}" in tex
    assert r"100\%" in tex


def test_user_text_is_escaped_in_markdown(hostile: Derivation) -> None:
    """No raw HTML from the file reaches the Markdown report."""
    md = render(hostile, "md")
    assert "<script>" not in md and "<b>" not in md
    assert "&lt;script&gt;" in md


def test_context_is_plain_data(bead: Derivation) -> None:
    """Templates receive only strings, numbers, lists, dicts and None."""

    def check(value: object) -> None:
        if isinstance(value, dict):
            for v in value.values():
                check(v)
        elif isinstance(value, list):
            for v in value:
                check(v)
        else:
            assert value is None or isinstance(value, str | int | float | bool), type(value)

    check(context(bead))


def test_custom_templates_override(bead: Derivation, tmp_path: Path) -> None:
    """A --templates folder is searched before the packaged templates."""
    (tmp_path / "markdown").mkdir()
    (tmp_path / "markdown" / "report.md.j2").write_text("custom {{ core.name }}\n")
    assert render(bead, "md", tmp_path) == "custom Bead on a wire\n"


def test_missing_template_lists_searched_paths(bead: Derivation, tmp_path: Path,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """When no template is found the error names every folder searched."""
    import lagsolve.render.report as report

    monkeypatch.setattr(report, "template_dirs", lambda kind, extra=None: [tmp_path / "nowhere" / kind])
    with pytest.raises(RenderError, match="searched: .*nowhere"):
        render(bead, "md")


@pytest.mark.parametrize("payload", [
    "{{ cycler.__init__.__globals__.os.system('touch MARK') }}",
    "{{ ''.__class__.__mro__[1].__subclasses__() }}",
    "{{ self._TemplateReference__context.cycler.__init__.__globals__.os.popen('touch MARK').read() }}",
    "{% set x = core.coordinates.append(1) %}{{ x }}",
], ids=["globals", "subclasses", "context", "mutation"])
def test_user_templates_cannot_reach_python(bead: Derivation, tmp_path: Path, payload: str) -> None:
    """A --templates folder (a pull request's, in CI) is rendered in Jinja2's sandbox: a template that reaches
    for Python's globals, classes or the context, or mutates it, fails as a RenderError and runs nothing."""
    marker = tmp_path / "ran"
    (tmp_path / "markdown").mkdir()
    (tmp_path / "markdown" / "report.md.j2").write_text(payload.replace("MARK", str(marker)))
    with pytest.raises(RenderError, match="template markdown/report.md.j2 failed: .*(unsafe|not safely|immutable)"):
        render(bead, "md", templates=tmp_path)
    assert not marker.exists()


@pytest.mark.parametrize("fmt", ["md", "tex", "html", "json"])
def test_the_sandbox_renders_the_packaged_templates_unchanged(bead: Derivation, fmt: str,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """Every packaged template renders the same in the sandbox as in a plain Jinja2 environment."""
    import jinja2

    import lagsolve.render.report as report

    sandboxed = render(bead, fmt)
    monkeypatch.setattr(report, "ENVIRONMENT", jinja2.Environment)
    assert report.environment("markdown").__class__ is jinja2.Environment  # not the sandbox kept from before
    assert render(bead, fmt) == sandboxed


def test_templates_are_packaged() -> None:
    """The template folders exist where the installed package or the checkout provides them."""
    assert any((d / "report.md.j2").is_file() for d in template_dirs("markdown"))
    assert any((d / "report.tex.j2").is_file() for d in template_dirs("latex"))


#: how far past the margin a line may run before a report is not of print quality
OVERFULL_LIMIT = 10.0


def compile_latex(tex: str, files: dict[str, bytes], folder: Path) -> tuple[subprocess.CompletedProcess[str], str]:
    """pdflatex on ``tex`` (with the figures it includes) in ``folder``: the run and its log."""
    if shutil.which("pdflatex") is None:
        pytest.skip("pdflatex is not installed (CI installs texlive-latex-base and texlive-latex-recommended)")
    (folder / "r.tex").write_text(tex)
    for file_name, data in files.items():
        (folder / file_name).write_bytes(data)
    run = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "r.tex"],
                         cwd=folder, capture_output=True, text=True, timeout=300)
    log = (folder / "r.log").read_text(errors="replace") if (folder / "r.log").exists() else ""
    return run, log


def overfull(log: str, tex: str) -> list[str]:
    """Each line of the report that runs more than OVERFULL_LIMIT pt past the margin, with its width and source."""
    lines = tex.splitlines()
    out = []
    for m in re.finditer(r"Overfull \\hbox \(([\d.]+)pt too wide\) .*?lines? (\d+)", log):
        if float(m.group(1)) > OVERFULL_LIMIT:
            source = lines[int(m.group(2)) - 1] if int(m.group(2)) <= len(lines) else ""
            out.append(f"{m.group(1)} pt at line {m.group(2)}: {source[:160]}")
    return out


@pytest.mark.parametrize("name", ["knife_edge", "rotating_tube", "double_pendulum", "ladder_rough_floor"])
def test_latex_fits_the_page(name: str, tmp_path: Path, shipped_derivation: Callable[[str], Derivation]) -> None:
    """A freshly rendered report of a problem with long results compiles with no line over 10 pt past the margin."""
    derivation = shipped_derivation(name)
    tex = render(derivation, "tex")
    run, log = compile_latex(tex, {}, tmp_path)
    assert run.returncode == 0, run.stdout[-2000:]
    assert overfull(log, tex) == []


@pytest.mark.slow
@pytest.mark.parametrize("name", shipped())
def test_latex_compiles(name: str, tmp_path: Path, shipped_reports: Callable[[str], Any]) -> None:
    """Each problem's LaTeX report compiles with pdflatex, no line runs over 10 pt past the margin, and it is the
    reviewed golden report (skipped where pdflatex is not installed)."""
    reports = shipped_reports(name)
    tex = reports.outputs["tex"]
    run, log = compile_latex(tex, reports.files, tmp_path)
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / "r.pdf").stat().st_size > 1000
    assert overfull(log, tex) == []
    assert tex == (ROOT / "tests" / "golden" / f"{name}.tex").read_text()


def test_hostile_latex_compiles(hostile: Derivation, tmp_path: Path) -> None:
    """Even a report built from hostile names compiles, and shell escape stays off."""
    if shutil.which("pdflatex") is None:
        pytest.skip("pdflatex is not installed")
    (tmp_path / "h.tex").write_text(render(hostile, "tex"))
    run = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "h.tex"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-2000:]


def test_simulation_summary_cannot_end_its_block_in_latex(hostile: Derivation) -> None:
    """A name in the simulation summary cannot close the block around it and run \\input."""
    summary_text = "\\end{verbatim}\\input{/etc/hostname}: simulated to t = 1\n  final state: x = 1\n"
    tex = render(hostile, "tex", simulation={"summary": summary_text, "figures": []})
    assert r"\input{/etc/hostname}" not in tex and r"\end{verbatim}\input" not in tex
    assert r"\textbackslash{}end\{verbatim\}\textbackslash{}input\{/etc/hostname\}" in tex
    assert r"~~final~state:~x~=~1" in tex


def test_simulation_summary_cannot_end_its_block_in_markdown(hostile: Derivation) -> None:
    """A name with a code fence cannot close the simulation summary's code block in Markdown."""
    summary_text = "Name ``` # heading\n  final state: x = 1\n"
    md = render(hostile, "md", simulation={"summary": summary_text, "figures": []})
    assert "````text\nName ``` # heading\n  final state: x = 1\n````" in md


def test_code_fence_in_a_description_cannot_swallow_the_report() -> None:
    """A ``` or ~~~ line in a description is shown as text: every fence left in the report is lagsolve's own."""
    text = HOSTILE.replace("description: 'See \\input{/etc/passwd} and \\write18{rm -rf /}; $x$ & # _ ^ ~ <b>bold</b>'",
                           "description: |\n  Before\n  ```python\n  code\n   ~~~\n  after")
    md = render(derive(load_text(text, "fence.yaml")), "md")
    assert "Before\n\\```python\ncode\n \\~~~\nafter" in md
    fences = [line for line in md.splitlines() if line.lstrip().startswith(("```", "~~~"))]
    assert len(fences) % 2 == 0 and all(f in ("```", "```math") for f in fences)
