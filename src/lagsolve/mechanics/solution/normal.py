r"""Normal forces of Coulomb friction in closed form.

A friction force is :math:`-\mu N\,\mathbf v/|\mathbf v|` with :math:`N` the magnitude of the
combined force of the contact's constraints, :math:`N = |\sum_j \lambda_j\mathbf u_j|`. The
multipliers are affine in the normal forces (the friction forces are),
:math:`\lambda = \lambda_0 + \Lambda N`, so contact :math:`i` has

.. math:: N_i = \Big|\mathbf a_i + \sum_k \mathbf b_{ik} N_k\Big|,\qquad
          \mathbf a_i = \sum_{j\in i}\lambda_{0j}\mathbf u_j,\quad
          \mathbf b_{ik} = \sum_{j\in i}\frac{\partial\lambda_j}{\partial N_k}\mathbf u_j .

Every coefficient is taken **on the constraint surface**: the dependent coordinates and velocities
the constraints give are substituted, and so are the velocities the remaining velocity forms fix
(:math:`A\dot q + b = 0`). Friction tangent to the surface then leaves the multipliers independent
of :math:`N` (a block on an incline in Cartesian :math:`x, y`: off the surface the multiplier seems
to depend on the friction, on it it does not). The cases:

* **decoupled** (:math:`\mathbf b_{ik} = 0` for every :math:`k`): :math:`N_i = |\mathbf a_i|`;
* **one coupled contact, one constraint** (scalars :math:`a = |\mathbf u|\lambda_0`,
  :math:`b = |\mathbf u|\Lambda`): :math:`N = |a + bN|` gives
  :math:`N = |a|/(1 - b\,\mathrm{sgn}\,a)`, valid while :math:`|b| < 1`;
* **one coupled contact, several constraints**: the quadratic
  :math:`(1 - b^2)N^2 - 2(\mathbf a\cdot\mathbf b)N - a^2 = 0` and its one non-negative root,
  valid while :math:`b^2 < 1`;
* **several coupled contacts, one constraint each**: when the sign :math:`s_i` of every
  :math:`a_i` is known, :math:`N = (I - SB)^{-1}S\,a` with :math:`S = \mathrm{diag}(s)`, valid while
  every :math:`N_i \ge 0` (then :math:`s_i(a_i + \sum_k b_{ik}N_k) = N_i \ge 0`, the assumed signs);
  otherwise :math:`N` stays implicit and the system it solves is stated.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from lagsolve.errors import DerivationError
from lagsolve.mechanics.equations.constraints import ConstraintTerms
from lagsolve.mechanics.equations.elimination import Elimination
from lagsolve.mechanics.equations.friction import FrictionTerm
from lagsolve.mechanics.equations.model import Model
from lagsolve.mechanics.equations.reactions import Reaction
from lagsolve.mechanics.equations.surface import Surface
from lagsolve.mechanics.symbolic.signs import sign_core
from lagsolve.mechanics.symbolic.simplify import norm, root_of_sum_of_squares, tidy, unit_signs


@dataclass(frozen=True)
class NormalForce:
    """The outcome for one contact: ``value`` the closed form of N (None when it stays implicit),
    ``case`` which case applies and why, ``valid_while`` the condition for that form (or None),
    ``system`` the equation N solves (always given: ``Eq(N, |a + B N|)``)."""

    value: Any
    case: str
    valid_while: Any
    system: Any


def normal_forces(frictions: tuple[FrictionTerm, ...], multipliers: tuple[Any, ...],
                  constraints: tuple[ConstraintTerms, ...], reactions: dict[str, Reaction],
                  model: Model, elimination: Elimination) -> dict[str, NormalForce]:
    """Each contact's normal force (see the module docstring), by contact name."""
    surface = Surface(constraints, model, elimination)
    parts = _parts(frictions, multipliers, constraints, reactions)
    zero_n = {f.normal: 0 for f in frictions}
    out, known = _decoupled(frictions, parts, surface, elimination, zero_n)
    coupled = [f for f in frictions if f.name not in out]
    if not coupled:
        return out
    a_vec, b_vec = _coupled_vectors(coupled, parts, elimination, zero_n, known)
    for f in coupled:
        total = a_vec[f.name] + sum((b_vec[f.name, g.normal] * g.normal for g in coupled), sympy.zeros(
            a_vec[f.name].rows, 1))
        system = sympy.Eq(f.normal, norm([unit_signs(tidy(c)) for c in total]))
        out[f.name] = NormalForce(None, "", None, system)
    if len(coupled) == 1:
        f = coupled[0]
        out[f.name] = _one_coupled(f, parts[f.name], a_vec[f.name], b_vec[f.name, f.normal], elimination, zero_n,
                                   known, out[f.name].system)
        return out
    solved = _several(coupled, parts, a_vec, b_vec)
    for f in coupled:
        out[f.name] = _several_coupled(f, solved, out[f.name].system)
    return out


def _parts(frictions: tuple[FrictionTerm, ...], multipliers: tuple[Any, ...],
           constraints: tuple[ConstraintTerms, ...], reactions: dict[str, Reaction],
           ) -> dict[str, list[tuple[sympy.Matrix, Any]]]:
    """Each contact's constraint forces on its particle: (direction, multiplier) for each of its constraints.
    A constraint whose force on the particle is not known leaves the normal force unknown: an error."""
    index = {c.name: j for j, c in enumerate(constraints)}
    parts: dict[str, list[tuple[sympy.Matrix, Any]]] = {}
    for f in frictions:
        parts[f.name] = []
        for name in f.constraints:
            pushes = [p for p in reactions[name].particles if p.particle == f.particle]
            if not pushes:
                raise DerivationError(
                    f"friction {f.name!r}: constraint {name!r} has no known force on {f.particle!r} "
                    f"({reactions[name].note or 'it acts on other particles'}), so the normal force is unknown")
            parts[f.name].append((sympy.Matrix(pushes[0].direction), multipliers[index[name]]))
    return parts


def _decoupled(frictions: tuple[FrictionTerm, ...], parts: dict[str, list[tuple[sympy.Matrix, Any]]],
               surface: Surface, elimination: Elimination, zero_n: dict[Any, Any],
               ) -> tuple[dict[str, NormalForce], dict[Any, Any]]:
    """The normal forces of the contacts whose multipliers do not depend on any N on the constraint surface,
    in closed form, by contact name; and the same values by normal-force symbol."""
    # coupling on the constraint surface: which contacts' N change which multipliers. The values below are
    # written with the elimination alone (shorter than with the surface's velocities put in); they hold on the
    # surface either way, and a coefficient that vanishes there has been found so already.
    symbols = [f.normal for f in frictions]
    depends = {f.name: [N for N in symbols if not all(surface.is_zero(sympy.diff(lam, N)) for _, lam in parts[f.name])]
               for f in frictions}
    out: dict[str, NormalForce] = {}
    known: dict[Any, Any] = {}
    for f in frictions:
        if not depends[f.name]:
            pieces = [(u, elimination.apply(lam.xreplace(zero_n))) for u, lam in parts[f.name]]
            value = _length(pieces)
            known[f.normal] = value
            out[f.name] = NormalForce(value, "decoupled: on the constraint surface the multipliers do not depend "
                                             "on the friction, so N follows from them in closed form", None,
                                      sympy.Eq(f.normal, value))
    return out, known


def _coupled_vectors(coupled: list[FrictionTerm], parts: dict[str, list[tuple[sympy.Matrix, Any]]],
                     elimination: Elimination, zero_n: dict[Any, Any], known: dict[Any, Any],
                     ) -> tuple[dict[str, sympy.Matrix], dict[tuple[str, Any], sympy.Matrix]]:
    """The coupled contacts' constraint force written a + Σ b N: ``a`` by contact, ``b`` by (contact, N)."""
    a_vec: dict[str, sympy.Matrix] = {}
    b_vec: dict[tuple[str, Any], sympy.Matrix] = {}
    for f in coupled:
        rows = parts[f.name][0][0].rows
        a_vec[f.name] = sum((u * elimination.apply(lam.xreplace(zero_n).xreplace(known)) for u, lam in parts[f.name]),
                            sympy.zeros(rows, 1))
        for g in coupled:
            b_vec[f.name, g.normal] = sum((u * elimination.apply(sympy.diff(lam, g.normal).xreplace(known))
                                           for u, lam in parts[f.name]), sympy.zeros(rows, 1))
    return a_vec, b_vec


def _one_coupled(f: FrictionTerm, parts: list[tuple[sympy.Matrix, Any]], a: sympy.Matrix, b: sympy.Matrix,
                 elimination: Elimination, zero_n: dict[Any, Any], known: dict[Any, Any],
                 system: Any) -> NormalForce:
    """The one coupled contact's N solving N = |a + b N|: in closed form with scalars along its one
    constraint's force, or the quadratic's non-negative root with several constraints."""
    if len(parts) == 1:
        # N = |a + b N| with scalars along the one constraint's force
        length = norm(list(parts[0][0]))
        lam = parts[0][1]
        a_s = tidy(length * elimination.apply(lam.xreplace(zero_n).xreplace(known)))
        b_s = tidy(unit_signs(length * elimination.apply(sympy.diff(lam, f.normal))))
        known_sign, core = sign_core(a_s)
        sign_a = sympy.Integer(known_sign) if known_sign is not None and core == 1 else sympy.sign(core)
        value = tidy(sympy.Abs(a_s)) / tidy(1 - b_s * sign_a)
        valid = sympy.StrictLessThan(tidy(unit_signs(sympy.expand(b_s**2))), 1)
        case = ("coupled, one contact: the friction changes the multiplier, so N solves N = |a + b N|; "
                "N = |a|/(1 - b sign(a)) while |b| < 1")
    else:
        aa, ab, bb = (tidy(unit_signs(e)) for e in ((a.T * a)[0], (a.T * b)[0], (b.T * b)[0]))
        value = tidy(unit_signs((ab + sympy.sqrt(ab**2 + (1 - bb) * aa)) / (1 - bb)))
        valid = sympy.StrictLessThan(bb, 1)
        case = ("coupled, one contact: the friction changes the multipliers, so N solves N = |a + b N|, a "
                "quadratic with one non-negative root")
    return NormalForce(value, case, valid, system)


def _several_coupled(f: FrictionTerm, solved: tuple[dict[Any, Any], Any] | None, system: Any) -> NormalForce:
    """One of several coupled contacts: its N from the linear solve for the known sign pattern, or implicit
    (given by its ``system``) when the pattern is not determined."""
    if solved is None:
        case = ("coupled, with several contacts whose sign pattern is not determined: N stays implicit in the "
                "results; it solves the system N = |a + B N| given (simulate solves it at every step)")
        return NormalForce(None, case, None, system)
    values, valid = solved
    case = ("coupled, several contacts with the sign of each a known: N = (I - S B)^-1 S a, valid while "
            "every N is non-negative")
    return NormalForce(values[f.normal], case, valid, system)


def _several(coupled: list[FrictionTerm], parts: dict[str, list[tuple[sympy.Matrix, Any]]],
             a_vec: dict[str, sympy.Matrix], b_vec: dict[tuple[str, Any], sympy.Matrix],
             ) -> tuple[dict[Any, Any], Any] | None:
    """Several coupled contacts, one constraint each: the linear solve for the known sign pattern."""
    if any(len(parts[f.name]) != 1 for f in coupled):
        return None
    a_s, signs = [], []
    for f in coupled:
        u = parts[f.name][0][0]
        length = norm(list(u))
        # a and b are multiples of u: their signed components along u
        k = next(i for i in range(u.rows) if u[i] != 0)
        a_i = tidy(a_vec[f.name][k] / u[k] * length)
        sign, _ = sign_core(a_i)
        if sign is None:
            return None
        a_s.append(a_i)
        signs.append(sign)
    n = len(coupled)
    B = sympy.zeros(n, n)
    for i, f in enumerate(coupled):
        u = parts[f.name][0][0]
        k = next(j for j in range(u.rows) if u[j] != 0)
        for j, g in enumerate(coupled):
            B[i, j] = tidy(unit_signs(b_vec[f.name, g.normal][k] / u[k] * norm(list(u))))
    S = sympy.diag(*signs)
    try:
        values = (sympy.eye(n) - S * B).LUsolve(S * sympy.Matrix(a_s))
    except (ValueError, ZeroDivisionError):
        return None
    out = {f.normal: tidy(v) for f, v in zip(coupled, values, strict=True)}
    valid = sympy.And(*(sympy.GreaterThan(v, 0) for v in out.values()))
    return out, valid


def _length(pieces: list[tuple[sympy.Matrix, Any]]) -> Any:
    """|Σ λ_j u_j|, keeping each force's factored form when the directions are orthogonal."""
    orthogonal = all(tidy((a.T * b)[0]) == 0 for i, (a, _) in enumerate(pieces) for b, _ in pieces[i + 1:])
    if orthogonal:
        return root_of_sum_of_squares([lam * norm(list(u)) for u, lam in pieces])
    total = sum((u * lam for u, lam in pieces), sympy.zeros(pieces[0][0].rows, 1))
    return norm(list(total))

