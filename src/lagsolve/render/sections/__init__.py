"""Each report section built once, as data; every output is :func:`~lagsolve.render.model.present` of it.

:func:`build` walks a :class:`~lagsolve.mechanics.results.Derivation` once and returns
:class:`Sections`: frozen records holding the SymPy expressions and names each part of a report
shows, in display order: :mod:`.core` (the problem, L, the constraints, Lagrange's equations, the
matrix form, accelerations, multipliers, forces of constraint, friction, notes), :mod:`.units`,
:mod:`.analysis` and :mod:`.hamiltonian`. :class:`Sections` is itself a record: each field's metadata says
where its keys go in the JSON contract (the core's at the top level) and which template partial lays it
out; the Markdown and LaTeX pages include the partials in the order of the fields. The templates' context
(:func:`lagsolve.render.report.sections_context`), the JSON contract
(:func:`~lagsolve.render.report.sections_json`) and the terminal summary
(:func:`~lagsolve.render.report.sections_summary`) each present these records; none walks the
derivation again. A new result is a field of a record here, declared with
:func:`~lagsolve.render.model.shown`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from lagsolve.render.model import shown
from lagsolve.render.sections.analysis import AnalysisSection, analysis_section
from lagsolve.render.sections.core import CoreSections, core_sections
from lagsolve.render.sections.hamiltonian import HamiltonianPart, hamiltonian_section
from lagsolve.render.sections.units import UnitsSection, units_section

if TYPE_CHECKING:
    from lagsolve.mechanics.results import Derivation

UNITS_DOC = ("the unit of each result (docs/format.md, Units); a multiplier's unit is the generalized force's over "
             "its constraint's coefficient, so it depends on how the constraint is written ('constraint' is the "
             "unit of its expression)")


ANALYSIS_DOC = "classification, reduction, reasons, equilibria (docs/format.md, Output)"
HAMILTONIAN_DOC = "Hamiltonian mechanics (docs/format.md, Output)"


@dataclass(frozen=True)
class Sections:
    """The sections of one derivation's report, in reading order (the order of the pages' partials).

    The JSON contract's key order predates it: after the core's keys come ``analysis``, ``hamiltonian``, the
    core's ``notes`` and ``units`` (``JSON_LAST``)."""

    JSON_LAST: ClassVar[tuple[str, ...]] = ("analysis", "hamiltonian", "notes", "units")

    core: CoreSections = shown(inline=True, terminal=True, partial="_core")
    units: UnitsSection | None = shown(optional=True, partial="_units", doc=UNITS_DOC)  # None: no unit declared
    analysis: AnalysisSection | None = shown(terminal=True, partial="_analysis", doc=ANALYSIS_DOC)  # None: no analysis
    # the formulation, why it does not apply, why it was not derived, or None without an analysis
    hamiltonian: HamiltonianPart = shown(terminal=True, partial="_hamiltonian", doc=HAMILTONIAN_DOC)


def build(derivation: Derivation) -> Sections:
    """The sections of ``derivation``'s report, each built once."""
    return Sections(core=core_sections(derivation), units=units_section(derivation),
                    analysis=analysis_section(derivation), hamiltonian=hamiltonian_section(derivation))
