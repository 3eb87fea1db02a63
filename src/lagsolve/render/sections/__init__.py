"""Each report section built once, as data; the outputs are projections of it.

:func:`build` walks a :class:`~lagsolve.mechanics.results.Derivation` once and returns
:class:`Sections`: frozen records holding the SymPy expressions and names each part of a report
shows, in display order: :mod:`.core` (the problem, L, the constraints, Lagrange's equations, the
matrix form, accelerations, multipliers, forces of constraint, friction, notes), :mod:`.analysis`,
:mod:`.hamiltonian` and :mod:`.units`. The Markdown, LaTeX and HTML templates (through
:func:`lagsolve.render.report.sections_context`), the JSON contract
(:func:`~lagsolve.render.report.sections_json`) and the terminal summary
(:func:`~lagsolve.render.report.sections_summary`) each print these records; none walks the
derivation again. A new result is a record here and one line in each projection.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from lagsolve.render.sections.analysis import AnalysisSection, analysis_section
from lagsolve.render.sections.core import CoreSections, core_sections
from lagsolve.render.sections.hamiltonian import HamiltonianPart, hamiltonian_section
from lagsolve.render.sections.units import UnitsSection, units_section

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation


@dataclass(frozen=True)
class Sections:
    """The sections of one derivation's report."""

    core: CoreSections
    analysis: AnalysisSection | None  # None: the derivation carries no analysis
    hamiltonian: HamiltonianPart  # None: the derivation carries no analysis
    units: UnitsSection | None  # None: the problem declares no unit


def build(derivation: Derivation) -> Sections:
    """The sections of ``derivation``'s report, each built once."""
    return Sections(core=core_sections(derivation), analysis=analysis_section(derivation),
                    hamiltonian=hamiltonian_section(derivation), units=units_section(derivation))
