"""The named mistakes of ``lagsolve grade`` (the contract's names) and the answers a mistake would give: the key's
answer changed in one known way (:func:`candidates`), each with a sentence of evidence."""

from __future__ import annotations

import contextlib
from collections.abc import Iterable
from typing import Any

import sympy

from lagsolve.grade.analysis_steps import hamiltonian_candidates
from lagsolve.grade.follow import constraint_terms, solve
from lagsolve.grade.frame import Frame
from lagsolve.mechanics.derivation import Derivation
from lagsolve.mechanics.equations.reactions import force_scale

#: the mistake names of the contract (those this version can find are marked in docs/grading.md)
MISTAKES = ("sign_error", "missing_factor", "lambda_sign_convention", "missing_velocity_squared_terms",
            "missing_moving_constraint_term", "dropped_constraint", "wrong_potential_sign", "missing_kinetic_term",
            "wrong_dimension", "missing_abs")
SIGN, FACTOR_MISSING, LAMBDA = "sign_error", "missing_factor", "lambda_sign_convention"
VELOCITY_SQUARED, DROPPED = "missing_velocity_squared_terms", "dropped_constraint"
POTENTIAL_SIGN = "wrong_potential_sign"
KINETIC_TERM, ABS = "missing_kinetic_term", "missing_abs"
MOVING, DIMENSION = "missing_moving_constraint_term", "wrong_dimension"

#: most terms tried one at a time in a diagnosis (a larger answer gets only the whole-answer candidates)
MAX_TERMS = 24

def flip_multipliers(expr: Any, derivation: Derivation) -> Any:
    return expr.xreplace({c.multiplier: -c.multiplier for c in derivation.constraints})


def without_velocity_squared(expr: Any, velocities: Iterable[Any], frame: Frame | None = None) -> Any:
    r"""``expr`` less its part quadratic in the velocities: with :math:`E(s) = E(s\dot q)`,
    :math:`E - (E(2) - 2E(1) + E(0))/2` (exact for E of degree two in :math:`\dot q`); with a ``frame``, in the
    student's velocities (their accelerations held: :meth:`Frame.scaling`)."""
    velocities = tuple(velocities)

    def scaled(k: int) -> Any:
        if frame is not None and frame.scalable:
            return expr.xreplace(frame.scaling(k))
        return expr.xreplace({v: k * v for v in velocities})

    return expr - (scaled(2) - 2 * expr + scaled(0)) / 2


def terms(expr: Any) -> tuple[Any, ...]:
    with contextlib.suppress(TypeError, ValueError):
        terms = sympy.Add.make_args(sympy.expand(expr))
        return terms if 1 < len(terms) <= MAX_TERMS else ()
    return ()


def candidates(step: str, reference: Any, derivation: Derivation, frame: Frame | None = None
                ) -> list[tuple[str, Any, str]]:
    """(mistake, the key's answer with that mistake made, evidence) for ``step``, most specific first; a mistake
    "" is a known difference without a name (said in the evidence only)."""
    model = derivation.model
    out: list[tuple[str, Any, str]] = []
    if step in ("kinetic", "lagrangian") and frame is not None:
        out.extend(student_terms(step, model.kinetic, reference, frame))  # named in the student's variables first
    if step == "lagrangian":
        out.append((POTENTIAL_SIGN, model.kinetic + model.potential, "it is T + V: the potential has the wrong sign"))
        for k in (2, sympy.Rational(1, 2)):
            out.append((FACTOR_MISSING, k * model.kinetic - model.potential,
                        f"the kinetic energy is {k} times the key's"))
        for term in terms(model.kinetic):
            out.append((KINETIC_TERM, model.lagrangian - term, f"the kinetic term {sympy.sstr(term)} is missing"))
    if step == "hamiltonian":
        out.extend(hamiltonian_candidates(derivation))
    if step == "kinetic":
        for term in terms(reference):
            out.append((KINETIC_TERM, reference - term, f"the kinetic term {sympy.sstr(term)} is missing"))
    if step not in ("kinetic", "potential", "lagrangian", "constraints", "hamiltonian"):
        without = without_velocity_squared(reference, model.velocities, frame)
        if without != reference:
            out.append((VELOCITY_SQUARED, without,
                        "the terms quadratic in the velocities (centripetal, Coriolis) are missing"))
    signs = POTENTIAL_SIGN if step == "potential" else SIGN
    for term in terms(reference):
        out.append((signs, reference - 2 * term, f"the term {sympy.sstr(term)} has the wrong sign"))
    return out


# -- a moving constraint taken as still (its ∂ψ/∂t missing) ---------------------------------------------


def moving(derivation: Derivation) -> list[Any]:
    """The key's constraints that move: an offset b = ∂ψ/∂t, or coefficients with an explicit t."""
    time = derivation.model.time
    return [c for c in constraint_terms(derivation)
            if c.offset != 0 or any(sympy.sympify(a, strict=True).has(time) for a in c.coefficients)]


def still_constraint(c: Any, time: Any, model: Any) -> tuple[Any, ...]:
    """ψ less its terms with t, and the velocity form a·q̇ without b: the constraint written as if it did not move
    (the forms that are 0 are left out)."""
    psi = sympy.Add(*(term for term in sympy.Add.make_args(sympy.expand(c.expression)) if not term.has(time)))
    velocity = sum((a * qd for a, qd in zip(c.coefficients, model.velocities, strict=True)), sympy.Integer(0))
    return tuple(form for form in (psi, velocity) if form != 0)


def moving_answers(derivation: Derivation) -> dict[str, dict[str, Any]]:
    """q̈, λ and |F| of constraint from the key's equations with every moving constraint taken as still (its
    ∂²ψ/∂t² and ∂ȧ/∂t dropped from β); {} when no constraint moves or the solve fails."""
    if not moving(derivation) or derivation.lagrange is None:
        return {}
    with contextlib.suppress(TypeError, ValueError, AttributeError, ZeroDivisionError):
        solved = solve(derivation, list(derivation.lagrange.equations), still=True)
        if solved is None:
            return {}
        names = [q.name for q in derivation.problem.coordinates]
        accelerations, multipliers = solved
        lam = {c.name: m for c, m in zip(constraint_terms(derivation), multipliers, strict=True)}
        out: dict[str, dict[str, Any]] = {"accelerations": dict(zip(names, accelerations, strict=True)),
                                          "multipliers": lam}
        if derivation.form is not None:
            forces = {}
            for c in derivation.constraints:
                scale = force_scale(derivation.form.reactions[c.name])
                if scale is not sympy.nan:
                    forces[c.name] = sympy.Abs(lam[c.name]) * scale
            out["constraint_forces"] = forces
        return out
    return {}


def moving_evidence(derivation: Derivation) -> str:
    """Which constraints move, with their ∂ψ/∂t: the evidence of :data:`MOVING`."""
    parts = [f"{c.name} (∂ψ/∂t = {sympy.sstr(c.offset)})" for c in moving(derivation)]
    return ("it is the answer with the moving constraint taken as still: the terms from ∂ψ/∂t of "
            + ", ".join(parts) + " are missing")


def student_terms(step: str, kinetic: Any, reference: Any, frame: Frame) -> list[tuple[str, Any, str]]:
    """In a submission's own coordinates: the key's answer less one term of the key's T written in them (the
    terms of T differ between coordinates: r²φ̇² is no term of ẋ² + ẏ²); none when the map cannot be inverted."""
    own = frame.in_student(kinetic)
    if own is None:
        return []
    out = []
    for term in terms(own):
        out.append((KINETIC_TERM, reference - frame.entry(term), f"the kinetic term {sympy.sstr(term)} (in the "
                                                                 "submission's coordinates) is missing"))
    return out
