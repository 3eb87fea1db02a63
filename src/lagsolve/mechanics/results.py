"""The frozen results of the mechanics stage: :class:`Derivation` (with :class:`ConstraintForce` and
:class:`FrictionResult`) and its parts; the analysis part is
:class:`~lagsolve.mechanics.analysis.results.Analysis`.

They are data only, built by :func:`lagsolve.mechanics.derivation.derive`; keeping them apart from the code
that builds them lets every stage name the results without importing the stages that run it (no import cycle).
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeVar, overload

from lagsolve.notebook import shown

T = TypeVar("T")

if TYPE_CHECKING:
    from lagsolve.mechanics.equations.constraints import ConstraintTerms
    from lagsolve.mechanics.equations.elimination import Elimination
    from lagsolve.mechanics.equations.forces import ForceTerm
    from lagsolve.mechanics.equations.friction import FrictionTerm
    from lagsolve.mechanics.equations.lagrange import LagrangeTerms  # noqa: F401 - named in _Part["..."] below
    from lagsolve.mechanics.equations.matrix_form import MatrixForm
    from lagsolve.mechanics.equations.model import Model  # noqa: F401 - named in _Part["..."] below
    from lagsolve.mechanics.solution.sticking import Sticking
    from lagsolve.mechanics.stages import StageNote
    from lagsolve.problem.schema import Problem  # noqa: F401 - named in _Part["..."] below


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
class Display:
    """The display forms of the derivation's steps (simplified for reading; plain when display simplification ran
    out of its budget): the energies, the constraints' coefficients, the force terms, Lagrange's equations term by
    term and as (left, right) sides before and after using the constraints, and the matrix form."""

    kinetic: Any
    potential: Any
    lagrangian: Any
    constraints: tuple[ConstraintTerms, ...]
    force_terms: tuple[ForceTerm, ...]
    momenta: tuple[Any, ...]
    momenta_rates: tuple[Any, ...]
    gradients: tuple[Any, ...]
    generalized_forces: tuple[Any, ...]
    equations: tuple[Any, ...]
    equation_sides: tuple[tuple[Any, Any], ...]
    eliminated_accelerations: dict[Any, Any]
    constrained_sides: tuple[tuple[Any, Any], ...]
    mass_matrix: Any
    forcing: Any


@dataclass(frozen=True)
class Solution:
    """The explicit solve: the raw (unsimplified) accelerations and multipliers, their display forms by name and
    the forces of constraint; each None when its stage did not finish (the notes say why)."""

    raw_accelerations: tuple[Any, ...] | None = None
    raw_multipliers: tuple[Any, ...] | None = None
    accelerations: dict[str, Any] | None = None
    multipliers: dict[str, Any] | None = None
    constraint_forces: dict[str, ConstraintForce] | None = None


@dataclass(frozen=True)
class Contract:
    """The format's section 2 forms of the analysis: ``reduced``, ``conserved``, ``effective_potential``
    (:func:`lagsolve.mechanics.analysis.analyse.contract_forms`; all None without an analysis)."""

    reduced: dict[str, Any] | None = None
    conserved: dict[str, Any] | None = None
    effective_potential: dict[str, Any] | None = None


@dataclass(frozen=True)
class Canonical:
    """The Hamiltonian formulation (``hamiltonian``, a :class:`lagsolve.mechanics.hamiltonian.Hamiltonian`) or
    why there is none (``note``: not applicable, or its stage did not finish)."""

    hamiltonian: Any = None
    note: str = ""


class _Part(Generic[T]):
    """A name read through one part: ``derivation.kinetic`` is ``derivation.display.kinetic`` (typed ``T``)."""

    def __init__(self, part: str, name: str | None = None) -> None:
        self.part, self.name = part, name

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = self.name or name

    @overload
    def __get__(self, obj: None, owner: type | None = None) -> _Part[T]: ...

    @overload
    def __get__(self, obj: object, owner: type | None = None) -> T: ...

    def __get__(self, obj: object, owner: type | None = None) -> T | _Part[T]:
        if obj is None:
            return self
        return typing.cast(T, getattr(getattr(obj, self.part), self.name or ""))


@dataclass(frozen=True)
class Derivation:
    """Everything derived for one problem (immutable; nothing to "compute first"), composed of parts, each built
    before the one constructor call in :func:`lagsolve.mechanics.derivation.derive`:

    - ``form``: the matrix form (:class:`~lagsolve.mechanics.equations.matrix_form.MatrixForm`: the problem, its model,
      Lagrange's terms, the raw constraints, loads and friction terms), always there;
    - ``elimination``: the dependent variables the constraints give, put into every display form;
    - ``display``: the display forms of the steps (:class:`Display`);
    - ``solution``: the explicit solve and the forces of constraint (:class:`Solution`);
    - ``friction``: each friction contact's normal force, forces and sticking (:class:`FrictionResult`);
    - ``analysis`` (:class:`~lagsolve.mechanics.analysis.results.Analysis`, None when not asked for) and its
      ``contract`` forms (:class:`Contract`);
    - ``canonical``: the Hamiltonian formulation or why there is none (:class:`Canonical`);
    - ``notes``: each later stage that ran out of its share of the budget, or did not apply, and why.

    The names people and the reports read are properties over the parts (``kinetic``, ``accelerations``,
    ``constraint_forces``, ``hamiltonian``, ...). A later stage that did not finish leaves its result None.
    """

    form: MatrixForm
    elimination: Elimination
    display: Display
    solution: Solution = Solution()
    friction: tuple[FrictionResult, ...] = ()
    analysis: Any = None  # lagsolve.mechanics.analysis.results.Analysis: classification, reduction, ...
    contract: Contract = Contract()
    canonical: Canonical = Canonical()
    notes: tuple[StageNote, ...] = ()

    problem = _Part["Problem"]("form")
    model = _Part["Model"]("form")
    lagrange = _Part["LagrangeTerms"]("form")
    kinetic = _Part["Any"]("display")
    potential = _Part["Any"]("display")
    lagrangian = _Part["Any"]("display")
    constraints = _Part["tuple[ConstraintTerms, ...]"]("display")
    force_terms = _Part["tuple[ForceTerm, ...]"]("display")
    momenta = _Part["tuple[Any, ...]"]("display")
    momenta_rates = _Part["tuple[Any, ...]"]("display")
    gradients = _Part["tuple[Any, ...]"]("display")
    generalized_forces = _Part["tuple[Any, ...]"]("display")
    equations = _Part["tuple[Any, ...]"]("display")
    equation_sides = _Part["tuple[tuple[Any, Any], ...]"]("display")
    eliminated_accelerations = _Part["dict[Any, Any]"]("display")
    constrained_sides = _Part["tuple[tuple[Any, Any], ...]"]("display")
    mass_matrix = _Part["Any"]("display")
    forcing = _Part["Any"]("display")
    raw_accelerations = _Part["tuple[Any, ...] | None"]("solution")
    raw_multipliers = _Part["tuple[Any, ...] | None"]("solution")
    accelerations = _Part["dict[str, Any] | None"]("solution")
    multipliers = _Part["dict[str, Any] | None"]("solution")
    constraint_forces = _Part["dict[str, ConstraintForce] | None"]("solution")
    reduced = _Part["dict[str, Any] | None"]("contract")
    conserved = _Part["dict[str, Any] | None"]("contract")
    effective_potential = _Part["dict[str, Any] | None"]("contract")
    hamiltonian = _Part["Any"]("canonical")
    hamiltonian_note = _Part["str"]("canonical", "note")

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
