"""What ``lagsolve check`` finds, as data: the reasons, :class:`Verdict` (with its :class:`Witness`),
:class:`CheckReport`, and :class:`Item`, one comparison to make, with :func:`symbolically_equal`, the
symbolic step of every comparison.

:mod:`lagsolve.check.compare` makes the verdicts and :mod:`lagsolve.check.modes` those on normal modes;
both build on this module, which imports neither.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field
from typing import Any

import sympy

from lagsolve.check.diagnose import SYMBOLIC_LIMIT
from lagsolve.check.status import Status
from lagsolve.mechanics.symbolic.simplify import tidy
from lagsolve.notebook import shown

OK, WARNING, MISMATCH, UNCHECKED = Status.OK, Status.WARNING, Status.MISMATCH, Status.UNCHECKED

#: reasons (``Verdict.reason``)
SYMBOLIC, NUMERIC = "symbolic", "numeric"
OPPOSITE_SIGN, CONVENTION = "opposite sign", "multiplier convention"
FACTOR, OFFSET, SIGN_DEPENDENT = "constant factor", "constant offset", "holds only where"
UNDEFINED, DIFFERS, ABSENT, SHAPE = "undefined", "differs", "absent", "shape"
INCOMPLETE = "incomplete"
RELEASED = "constraints released"
CONSERVED, NOT_CONSERVED, TRIVIAL = "conserved", "not conserved", "trivially constant"
NOT_DERIVED, TOO_FEW_STATES, SAME = "not derived", "too few states", "same"
BRACKET, NOT_BRACKET = "Poisson bracket", "Poisson bracket not 0"


@dataclass(frozen=True)
class Witness:
    """A state on the constraint surface where the answers differ.

    ``values``: (name, value) of the time, parameters, coordinates and velocities that
    matter; ``functions``: (name, :class:`sympy.Lambda`) used for each declared function;
    ``expected`` and ``derived``: the values there, one per component.
    """

    values: tuple[tuple[str, float], ...]
    functions: tuple[tuple[str, Any], ...]
    expected: tuple[complex | None, ...]
    derived: tuple[complex | None, ...]


@dataclass(frozen=True)
class Verdict:
    """The verdict on one expected quantity.

    ``quantity`` is the result key (``accelerations``, ``multipliers``, ``constraint_forces``,
    ``reduced``, ``conserved``, ``effective_potential``, ``normal_modes``) and ``name`` the entry (``x``,
    ``wire``, ``wire.vector``, ``energy``, ``expression``, ``equilibria[0].frequency``,
    ``normal_modes[0].squared_frequencies[1]``). ``status`` is one
    of ok, warning, mismatch, unchecked; ``reason`` one of the module's reason constants.
    ``expected`` and ``derived`` hold the components compared (one for a scalar).
    ``factor`` (E = factor·D), ``offset`` (E = D + offset) and ``condition`` (where the answer
    holds) are SymPy objects when the diagnosis found them; ``note`` is plain text.
    """

    quantity: str
    name: str
    status: Status
    reason: str
    expected: tuple[Any, ...]
    derived: tuple[Any, ...] | None = None
    factor: Any = None
    offset: Any = None
    condition: Any = None
    states: int = 0
    agreeing: int = 0
    note: str = ""
    witness: Witness | None = None

    @property
    def passed(self) -> bool:
        """True unless the answer is wrong (a warning or an unchecked answer passes)."""
        return self.status != MISMATCH

    def __repr__(self) -> str:
        return f"<Verdict on {self.quantity} {self.name}: {self.status}>"


@dataclass(frozen=True)
class CheckReport:
    """Every verdict on one problem, in the order of the file's ``expected:`` section."""

    name: str
    source: str
    coordinates: tuple[str, ...]
    verdicts: tuple[Verdict, ...]

    def count(self, status: Status) -> int:
        return sum(1 for v in self.verdicts if v.status == status)

    @property
    def passed(self) -> bool:
        """True when no answer is a mismatch."""
        return all(v.passed for v in self.verdicts)

    def __repr__(self) -> str:
        counts = ", ".join(f"{self.count(s)} {s}" for s in Status if self.count(s)) or "nothing to check"
        return f"<CheckReport of {self.name!r}: {counts}>"

    # notebook display (IPython calls these): the renderers are registered by render/display.py (see notebook.py)

    def _repr_html_(self) -> str | None:
        return shown(self, "html")

    def _repr_markdown_(self) -> str | None:
        return shown(self, "markdown")


@dataclass(frozen=True)
class Item:
    """One comparison to make: E and D, component by component."""

    quantity: str
    name: str
    expected: tuple[Any, ...]
    derived: tuple[Any, ...] | None
    note: str = ""
    shifts: bool = False  # an additive constant is harmless (conserved quantities, potentials)
    real: bool = True  # values must be real (not so for equilibria, which may not exist everywhere)
    missing: Status = UNCHECKED  # status when there is nothing derived to compare with
    rate: bool = False  # a claimed constant of the motion, checked by its rate dC/dt along the equations
    extra: dict[str, Any] = field(default_factory=dict)


def symbolically_equal(expected: Any, derived: Any) -> bool:
    """E − D reduces to zero: structural equality, then ``cancel``, then ``tidy`` (cheap steps first)."""
    if expected == derived:
        return True
    difference = expected - derived
    if difference == 0:
        return True
    if sympy.count_ops(difference) > SYMBOLIC_LIMIT:
        return False
    with contextlib.suppress(sympy.PolynomialError, sympy.CoercionFailed, ValueError, TypeError):
        if sympy.cancel(difference) == 0:
            return True
        return bool(tidy(difference) == 0)
    return False
