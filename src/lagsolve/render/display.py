r"""Rich display of results in notebooks (IPython's ``_repr_*_`` hooks call these).

A derivation shows its key results as one LaTeX block,

.. math:: \ddot q_i = \dots, \qquad \lambda_j = \dots, \qquad |F_j| = \dots,

(the matrix form :math:`M\ddot q = F + A^T\lambda` when the explicit solve did not finish), its
Markdown report, or HTML holding both a title and that block. A trajectory shows a table of its
final state and its run summary. Everything returns strings; nothing is displayed here. :func:`register`
puts the derivation's and the check report's forms in :mod:`lagsolve.notebook`, which their ``_repr_*_``
hooks ask (the results do not import this module).
"""

from __future__ import annotations

import html
from typing import TYPE_CHECKING, Any

import sympy

from lagsolve import notebook
from lagsolve.mechanics.derivation import Derivation
from lagsolve.render.checks import MARKS, describe, label
from lagsolve.render.notation import Notation

if TYPE_CHECKING:
    from lagsolve.check.compare import CheckReport


def _lines(derivation: Derivation) -> list[str]:
    """The aligned rows of the LaTeX block."""
    problem = derivation.problem
    note = Notation([c.name for c in problem.coordinates])
    tex = note.latex
    rows: list[str] = []
    if derivation.accelerations is not None:
        rows += [f"{tex(c.acceleration)} &= {tex(derivation.accelerations[c.name])}" for c in problem.coordinates]
    else:
        accelerations = derivation.model.accelerations
        for i in range(derivation.mass_matrix.rows):
            lhs = sum((derivation.mass_matrix[i, k] * a for k, a in enumerate(accelerations)), sympy.Integer(0))
            rhs = derivation.forcing[i] + derivation.lagrange.constraint_forces[i]
            rows.append(f"{tex(lhs)} &= {tex(rhs)}")
    for c in derivation.constraints:
        if derivation.multipliers is not None:
            rows.append(f"{tex(c.multiplier)} &= {tex(derivation.multipliers[c.name])}")
    for name, force in (derivation.constraint_forces or {}).items():
        if force.magnitude is not None:
            label = name.replace("_", r"\_")
            rows.append(rf"\left|F_{{\mathrm{{{label}}}}}\right| &= {tex(force.magnitude)}")
    return rows


def derivation_latex(derivation: Derivation) -> str:
    """The accelerations (or the matrix form), multipliers and force magnitudes as one ``$$`` block."""
    return "$$\\begin{aligned}\n" + " \\\\\n".join(_lines(derivation)) + "\n\\end{aligned}$$"


def derivation_markdown(derivation: Derivation) -> str:
    """The whole worked solution, as the Markdown report of ``lagsolve derive``."""
    from lagsolve.render.report import render

    return render(derivation, "md")


def derivation_html(derivation: Derivation) -> str:
    """A title, the results block (typeset by the notebook's MathJax) and the notes of stages not completed."""
    parts = [f"<div class=\"lagsolve-derivation\"><h3>{html.escape(derivation.problem.name)}</h3>",
             f"<div>{html.escape(derivation_latex(derivation))}</div>"]
    if derivation.notes:
        items = "".join(f"<li>{html.escape(n.sentence())}</li>" for n in derivation.notes)
        parts.append(f"<p>Not completed:</p><ul>{items}</ul>")
    parts.append("</div>")
    return "\n".join(parts)


def trajectory_html(trajectory: Any) -> str:
    """A :class:`lagsolve.api.Trajectory` as a table of its first and last samples and its run summary."""
    columns = trajectory.columns()
    names = list(columns)
    last = len(trajectory.t) - 1
    head = "".join(f"<th>{html.escape(n)}</th>" for n in ["sample", *names])
    rows = "".join(
        "<tr>" + f"<td>{i}</td>" + "".join(f"<td>{float(columns[n][i]):.6g}</td>" for n in names) + "</tr>"
        for i in sorted({0, last}))
    return (f"<div class=\"lagsolve-trajectory\"><h3>{html.escape(trajectory.name)}</h3>"
            f"<p>{len(trajectory.t)} samples, t from {float(trajectory.t[0]):.6g} to {float(trajectory.t[-1]):.6g}</p>"
            f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"
            f"<pre>{html.escape(trajectory.summary)}</pre></div>")


def _check_rows(report: CheckReport) -> list[tuple[str, str, str, str]]:
    """(mark, quantity, status, what the check found) for each verdict."""
    note = Notation(report.coordinates)
    return [(MARKS[v.status], label(v, note, report.coordinates), str(v.status), describe(v, note))
            for v in report.verdicts]


def check_html(report: CheckReport) -> str:
    """A :class:`~lagsolve.check.compare.CheckReport` as a table: one row per expected answer."""
    rows = "".join("<tr>" + "".join(f"<td>{html.escape(cell)}</td>" for cell in row) + "</tr>"
                   for row in _check_rows(report))
    verdict = "every answer agrees" if report.passed else "some answers are wrong"
    return (f"<div class=\"lagsolve-check\"><h3>{html.escape(report.name)}</h3><p>{html.escape(report.source)}: "
            f"{verdict}</p><table><thead><tr><th></th><th>answer</th><th>verdict</th><th>found</th></tr></thead>"
            f"<tbody>{rows}</tbody></table></div>")


def check_markdown(report: CheckReport) -> str:
    """The same table in Markdown (cells escaped: a name or a note cannot end a row)."""
    def cell(text: str) -> str:
        return " ".join(text.split()).replace("|", "\\|")

    lines = [f"**{cell(report.name)}** ({cell(report.source)})", "", "| | answer | verdict | found |",
             "|---|---|---|---|"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in _check_rows(report)]
    return "\n".join(lines) + "\n"


def register() -> None:
    """Show derivations and check reports in notebooks with the functions above (see :mod:`lagsolve.notebook`)."""
    from lagsolve.check.compare import CheckReport

    notebook.register(Derivation, "latex", derivation_latex)
    notebook.register(Derivation, "markdown", derivation_markdown)
    notebook.register(Derivation, "html", derivation_html)
    notebook.register(CheckReport, "html", check_html)
    notebook.register(CheckReport, "markdown", check_markdown)
