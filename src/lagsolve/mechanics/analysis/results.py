"""The frozen result of the analysis after the equations: :class:`Analysis`, built by
:func:`lagsolve.mechanics.analysis.analyse.analyse` (data only, so that a step can name it without importing
the steps that build it)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lagsolve.mechanics.analysis.conserved import Conservation, MotionSystem
    from lagsolve.mechanics.analysis.contact import ContactCheck
    from lagsolve.mechanics.analysis.equilibria import EffectivePotential
    from lagsolve.mechanics.analysis.freedom import Freedom
    from lagsolve.mechanics.analysis.integrability import Classification
    from lagsolve.mechanics.analysis.linearize import Linearization
    from lagsolve.mechanics.analysis.minimal import ReducedSystem
    from lagsolve.mechanics.analysis.steady import SteadyMotion


@dataclass(frozen=True)
class Analysis:
    """Everything :func:`analyse` found; each ``*_note`` says why a part is absent."""

    classification: tuple[Classification, ...]
    reduced: ReducedSystem | None
    reduced_note: str
    system: MotionSystem
    conservation: Conservation
    effective_potential: EffectivePotential | None
    effective_note: str
    linearization: Linearization | None
    linearization_note: str
    #: per equilibrium of ``effective_potential`` / ``linearization``: the unilateral constraints' forces there
    effective_contact: tuple[tuple[ContactCheck, ...], ...] = ()
    modes_contact: tuple[tuple[ContactCheck, ...], ...] = ()
    #: the steady motions about the effective potential's coordinate (:mod:`lagsolve.mechanics.analysis.steady`)
    steady: SteadyMotion | None = None
    steady_note: str = ""
    #: how many coordinates fix a configuration and how many velocities are free
    #: (:mod:`lagsolve.mechanics.analysis.freedom`)
    freedom: Freedom | None = None
