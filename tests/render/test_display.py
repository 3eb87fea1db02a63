"""`lagsolve.render.display`: the notebook forms of a derivation (LaTeX, Markdown, HTML) and of a trajectory."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import lagsolve
from lagsolve.api import FALLING

ROOT = Path(__file__).resolve().parents[2]
BEAD = ROOT / "problems" / "bead.yaml"


def test_latex_block_has_one_row_per_result() -> None:
    """The LaTeX form is one aligned $$ block with the accelerations, multipliers and force magnitudes."""
    text = lagsolve.derive(BEAD)._repr_latex_()
    assert text.startswith("$$\\begin{aligned}") and text.endswith("\\end{aligned}$$")
    assert "\\ddot{x} &=" in text and "\\ddot{y} &=" in text
    assert "\\lambda_{\\mathrm{wire}} &=" in text
    assert "\\left|F_{\\mathrm{wire}}\\right| &=" in text


def test_latex_block_of_an_unconstrained_problem() -> None:
    """Without constraints the block holds the accelerations alone."""
    assert lagsolve.derive(FALLING)._repr_latex_() == "$$\\begin{aligned}\n\\ddot{y} &= - g\n\\end{aligned}$$"


def test_markdown_is_the_report() -> None:
    """The Markdown form is the report `lagsolve derive --format md` writes."""
    from lagsolve.render.report import render

    derivation = lagsolve.derive(BEAD)
    assert derivation._repr_markdown_() == render(derivation, "md")


def test_html_is_well_formed_and_escaped() -> None:
    """The HTML form parses as XML, has the problem's name as title and the LaTeX block escaped."""
    derivation = lagsolve.derive(BEAD)
    root = ET.fromstring(derivation._repr_html_())
    assert root.find("h3").text == "Bead on a wire"
    assert "&" in "".join(root.itertext())  # the aligned block's & survives escaping


def test_html_lists_stages_not_completed() -> None:
    """A derivation whose later stages were skipped lists their notes."""
    from lagsolve.mechanics.derivation import core
    from lagsolve.mechanics.equations.matrix_form import matrix_form

    derivation = core(matrix_form(lagsolve.load_problem(BEAD), display=False), "stopped at its CPU limit")
    html = derivation._repr_html_()
    assert "Not completed:" in html and "stopped at its CPU limit" in html
    assert "&amp;=" in html  # the matrix form instead of the explicit accelerations


def test_trajectory_html_shows_first_and_last_samples() -> None:
    """A trajectory's HTML is a table of its first and last samples, and its summary."""
    run = lagsolve.simulate(FALLING, t_end=1.0, values={"m": 1, "g": 2}, initial={"y": 0, "y_dot": 0}, samples=3)
    root = ET.fromstring(run._repr_html_())
    rows = root.findall("./table/tbody/tr")
    assert [r.find("td").text for r in rows] == ["0", "2"]
    assert [td.text for td in rows[1].findall("td")][:3] == ["2", "1", "-1"]
    assert root.find("pre").text.startswith("falling mass")
