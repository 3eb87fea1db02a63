"""The frozen results of the mechanics stage: :class:`Derivation` (with :class:`ConstraintForce` and
:class:`FrictionResult`) and :class:`Analysis`.

They are data only, built by :func:`lagsolve.mechanics.derivation.derive` and
:func:`lagsolve.mechanics.analysis.analyse`; keeping them apart from the code that builds them lets
every stage name the results without importing the stages that run it (no import cycle).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from lagsolve.notebook import shown

if TYPE_CHECKING:
    from lagsolve.mechanics.conserved import Conservation, MotionSystem
    from lagsolve.mechanics.constraints import ConstraintTerms
    from lagsolve.mechanics.contact import ContactCheck
    from lagsolve.mechanics.elimination import Elimination
    from lagsolve.mechanics.equilibria import EffectivePotential
    from lagsolve.mechanics.forces import ForceTerm
    from lagsolve.mechanics.friction import FrictionTerm
    from lagsolve.mechanics.integrability import Classification
    from lagsolve.mechanics.lagrange import LagrangeTerms
    from lagsolve.mechanics.linearize import Linearization
    from lagsolve.mechanics.matrix_form import MatrixForm
    from lagsolve.mechanics.minimal import ReducedSystem
    from lagsolve.mechanics.model import Model
    from lagsolve.mechanics.stages import StageNote
    from lagsolve.mechanics.steady import SteadyMotion
    from lagsolve.mechanics.sticking import Sticking
    from lagsolve.problem.schema import Problem


@dataclass(frozen=True)
class ConstraintForce:
    """Result for one constraint: the force on its particle, or at the named point of a body (``vector``,
    ``magnitude``), per-particle forces when it acts on several, and a ``note`` when no force is claimed
    (then, with no particles at all, the generalized forces of constraint λ·a, ``generalized``)."""

    name: str
    vector: tuple[Any, ...] | None
    magnitude: Any | None
    particles: tuple[tuple[str, tuple[Any, ...], Any], ...]
    note: str
    generalized: tuple[Any, ...] = ()  # λ·a per coordinate, when no physical force is known (no point named)


@dataclass(frozen=True)
class ContactForce:
    """The force of a friction contact on one of its members, at the contact point: the normal part (the
    combined force of the normal constraints, of length N), the friction force, their sum and its magnitude.
    The second member's is the first's with every vector reversed (Newton's third law)."""

    member: str
    normal: tuple[Any, ...]
    friction: tuple[Any, ...]
    total: tuple[Any, ...]
    magnitude: Any


@dataclass(frozen=True)
class FrictionResult:
    """A friction contact (``term``, with the symbol N in its forces), the closed form of N (the
    symbol itself when only an implicit equation exists), which ``case`` applies and why, the
    condition under which that form is valid, the equation N solves (``system``), and the friction
    force and its generalized forces with the closed form put in."""

    term: FrictionTerm
    normal_force: Any
    case: str = ""
    valid_while: Any = None
    system: Any = None  # the equation N solves, Eq(N, |a + B N|)
    force: tuple[Any, ...] | None = None  # the friction force with N put in (None: as in ``term``)
    generalized: tuple[Any, ...] | None = None  # its generalized forces with N put in
    # the force on each member (the one that slides, then the one carrying the surface, if any); empty when the
    # forces of constraint are not known
    members: tuple[ContactForce, ...] = ()
    sticking: Sticking | None = None  # the contact held: the force that holds it and when it can
    sticking_note: str = ""  # why ``sticking`` is not given


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one problem (immutable; nothing to "compute first").

    Display forms (simplified): ``kinetic``, ``potential``, ``lagrangian``, ``constraints``
    (coefficients), ``momenta``, ``momenta_rates``, ``gradients``, ``generalized_forces``,
    ``equations`` (left minus right side), ``equation_sides`` and ``constrained_sides``
    (each equation as (left, right), before and after using the constraints), ``mass_matrix``
    and ``forcing`` (the matrix form), ``accelerations``, ``multipliers``,
    ``constraint_forces``. Raw forms: ``model``, ``lagrange`` (matrix form) and
    ``raw_accelerations``/``raw_multipliers`` (the augmented solve, unsimplified).
    Analysis (:mod:`lagsolve.mechanics.analysis`): ``analysis`` with every step, and the
    contract forms ``reduced``, ``conserved``, ``effective_potential`` (format section 2).

    The matrix form is always there. A later stage that ran out of its share of the budget,
    or did not apply, leaves its results ``None`` and says why in ``notes``
    (:mod:`lagsolve.mechanics.stages`).
    """

    problem: Problem
    model: Model
    kinetic: Any
    potential: Any
    lagrangian: Any
    constraints: tuple[ConstraintTerms, ...]
    force_terms: tuple[ForceTerm, ...]
    lagrange: LagrangeTerms
    momenta: tuple[Any, ...]
    momenta_rates: tuple[Any, ...]
    gradients: tuple[Any, ...]
    generalized_forces: tuple[Any, ...]
    equations: tuple[Any, ...]
    equation_sides: tuple[tuple[Any, Any], ...]
    elimination: Elimination
    eliminated_accelerations: dict[Any, Any]
    constrained_sides: tuple[tuple[Any, Any], ...]
    raw_accelerations: tuple[Any, ...] | None
    raw_multipliers: tuple[Any, ...] | None
    accelerations: dict[str, Any] | None
    multipliers: dict[str, Any] | None
    constraint_forces: dict[str, ConstraintForce] | None
    friction: tuple[FrictionResult, ...] = ()
    reduced: dict[str, Any] | None = None
    conserved: dict[str, Any] | None = None
    effective_potential: dict[str, Any] | None = None
    analysis: Any = None  # lagsolve.mechanics.analysis.Analysis: classification, reduction, conservation, ...
    form: MatrixForm | None = None  # the unsolved matrix form the numeric stage compiles
    mass_matrix: Any = None  # display form of M
    forcing: Any = None  # display form of F
    notes: tuple[StageNote, ...] = ()
    hamiltonian: Any = None  # lagsolve.mechanics.hamiltonian.Hamiltonian: momenta, H, Hamilton's equations, Routhian
    hamiltonian_note: str = ""  # why there is no Hamiltonian (not applicable, or its stage did not finish)

    @property
    def multiplier_symbols(self) -> tuple[Any, ...]:
        return tuple(c.multiplier for c in self.constraints)

    @property
    def complete(self) -> bool:
        """True when every stage that applies gave its result (no stage ran out of budget or size)."""
        return not any(n.kind in ("budget", "size") for n in self.notes)

    def __repr__(self) -> str:
        problem = self.problem
        n, m = len(problem.coordinates), len(self.constraints)
        missing = [note.stage for note in self.notes if note.kind in ("budget", "size")]
        state = "complete" if not missing else "not completed: " + ", ".join(missing)
        return (f"<Derivation of {problem.name!r}: {n} coordinate{'s' * (n != 1)}, {m} constraint{'s' * (m != 1)}; "
                f"{state}>")

    # notebook display (IPython calls these): the renderers are registered by render/display.py (see notebook.py)

    def _repr_latex_(self) -> str | None:
        return shown(self, "latex")

    def _repr_markdown_(self) -> str | None:
        return shown(self, "markdown")

    def _repr_html_(self) -> str | None:
        return shown(self, "html")



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
    #: the steady motions about the effective potential's coordinate (:mod:`lagsolve.mechanics.steady`)
    steady: SteadyMotion | None = None
    steady_note: str = ""
