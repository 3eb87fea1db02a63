"""The list steps of ``lagsolve grade``: ``equilibria`` compared as a set and ``frequencies`` as a multiset with
the key's (or with what follows from the student's own Lagrangian), each value symbolically, at the shared states,
or numerically (:mod:`.numeric_lists`). A mixin of the grader: it uses its ``context`` (the
:class:`~.grader.GradingKey`), ``grading`` and ``frame``."""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from lagsolve.check.diagnose import close
from lagsolve.grade.analysis_steps import frequency_mistake, same_at_states, same_symbolic, shown_point, whole_turns
from lagsolve.grade.evaluate import MINIMUM_STATES
from lagsolve.grade.numeric_lists import TOLERANCE, Condition, at_values, numeric, same_number
from lagsolve.grade.status import CORRECT, INCORRECT
from lagsolve.grade.status import Entry as _Entry


class ListSteps:
    """``equilibria`` and ``frequencies`` (a mixin of the grader)."""

    context: Any
    grading: Any
    frame: Any

    @property
    def key(self) -> dict[str, dict[str, Any]]:
        """The key's answers (the grader's)."""
        raise NotImplementedError

    # -- equilibria and frequencies: lists compared as a set, a multiset

    def same_value(self, value: Any, reference: Any, *, angle: bool = False) -> bool:
        """A value of the parameters (and conserved momenta) equal to the key's: symbolically (an angle up to
        whole turns), else at every shared state where the key's value is a number (complex ones too: an
        equilibrium that exists only for some parameters), at least :data:`LIST_STATES` of them."""
        values = self.context.values
        if isinstance(reference, Condition):
            return self.satisfies(value, reference)
        if numeric(reference):
            return same_number(value, reference, self.context.simulation, angle=angle)
        if same_symbolic(value, reference) or (angle and whole_turns(value - reference)):
            return True
        return same_at_states(values.values(value), values.values(reference), angle=angle)

    def satisfies(self, value: Any, condition: Condition) -> bool:
        """The key's equilibrium condition holds at the student's value: at the simulation values for a number,
        else at every shared state where the residual is a number."""
        residual = condition.residual.xreplace({condition.coordinate: value})
        simulation = self.context.simulation
        if simulation and at_values(value, simulation) is not None:
            found = at_values(residual, simulation)
            scale = at_values(sympy.Add(*(abs(t) for t in sympy.Add.make_args(sympy.expand(residual)))), simulation)
            return found is not None and abs(found) <= TOLERANCE * max(1.0, abs(scale or 0))
        at = self.context.values.values(residual)
        real = [v for v in at or () if isinstance(v, mpmath.mpf | mpmath.mpc)]
        return len(real) >= MINIMUM_STATES and all(close(v, 0) for v in real)

    def listed(self, step: str, entries: dict[str, Any], reference: list[Any] | None = None) -> list[_Entry]:
        """One entry per item of the key's list (or ``reference``, what follows from the student's own L), matched
        or missing, and one per extra item of the student's."""
        key = list(self.key[step].values()) if reference is None else reference
        if step == "equilibria":
            return self.equilibria(entries, key)
        return self.frequencies(entries, key)

    def equilibria(self, entries: dict[str, Any], key: list[Any]) -> list[_Entry]:
        coordinates = {q for point in key for q in point}
        lone = next(iter(coordinates)) if len(coordinates) == 1 else None
        angles = self.context.angles
        if self.frame is not None:  # a coordinate of the student's that is a function of the key's angles only
            angles = {name for name, f in self.frame.signature()
                      if {str(q) for q in f.free_symbols & set(self.frame.q)} <= angles}
        given: list[dict[str, Any] | None] = []
        out: list[_Entry] = []
        for name, pairs in entries.items():
            point = {(lone or "") if q == "" else q: v for q, v in pairs}
            if "" in point:
                out.append(_Entry(name, INCORRECT, None, f"equilibrium {name}: a bare value, but the key's "
                                  "equilibria have several coordinates: write each as a mapping coordinate: value"))
                given.append(None)
                continue
            given.append(point)

        def same(point: dict[str, Any] | None, reference: dict[str, Any]) -> bool:
            return point is not None and set(point) == set(reference) and all(
                self.same_value(point[q], reference[q], angle=q in angles) for q in reference)

        used: set[int] = set()
        for reference in key:
            found = next((i for i, p in enumerate(given) if i not in used and same(p, reference)), None)
            if found is None:
                shown = shown_point(reference)
                out.append(_Entry(shown, INCORRECT, None, f"the equilibrium {shown} is missing"))
            else:
                used.add(found)
                out.append(_Entry(shown_point(reference), CORRECT))
        for i, extra in enumerate(given):
            if i in used or extra is None:
                continue
            if any(same(extra, reference) for reference in key):
                continue  # the same point again (an angle written another way): no more, no less credit
            out.append(_Entry(str(i + 1), INCORRECT, None, f"{shown_point(extra)} is not an equilibrium of the key's"
                              + ("" if set(extra) == coordinates else
                                 f" (the key's equilibria give {', '.join(sorted(coordinates))})")))
        return out

    def frequencies(self, entries: dict[str, Any], key: list[Any]) -> list[_Entry]:
        either = self.grading.frequency_form == "either"
        given = list(entries.items())

        def how(value: Any, reference: Any) -> str:
            if self.same_value(value, reference):
                return "squared"
            if self.same_value(value**2, reference):
                return "omega"
            return ""

        out: list[_Entry] = []
        used: set[int] = set()
        unmatched: list[Any] = []
        for reference in key:
            found = None
            for i, (_, value) in enumerate(given):
                if i in used:
                    continue
                kind = how(value, reference)
                if kind:
                    found = (i, kind)
                    break
            label = f"ω² = {sympy.sstr(reference)}"
            if found is None:
                if reference == 0:
                    continue  # the zero ω² of a free motion (a continuum of equilibria) may be left out
                unmatched.append(reference)
                out.append(_Entry(label, INCORRECT, None, f"the squared frequency {sympy.sstr(reference)} is missing"))
                continue
            used.add(found[0])
            if found[1] == "omega" and not either:
                out.append(_Entry(label, INCORRECT, None, f"{given[found[0]][0]}: this is ω; the key asks for ω² "
                                  f"({sympy.sstr(reference)})"))
            else:
                out.append(_Entry(label, CORRECT))
        extras = [(i, value) for i, (_, value) in enumerate(given) if i not in used]
        for i, value in extras:
            if any(how(value, reference) for reference in key):
                continue  # the same frequency again (about a symmetric equilibrium)
            mistake, detail = None, "is not a squared frequency (nor a frequency) of the key's"
            if len(unmatched) == 1 and len(extras) == 1:
                mistake, detail = frequency_mistake(value, unmatched[0], detail)
            out.append(_Entry(given[i][0], INCORRECT, mistake, f"{given[i][0]}: {sympy.sstr(value)} {detail}"))
        return out
