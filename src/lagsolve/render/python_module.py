"""A bound problem's equations as one stand-alone Python module (``lagsolve export --to python``).

The module needs only NumPy. It holds ``PARAMETERS`` (the file's simulation values), ``STATE``
(``q...`` then ``q_dot...``), ``rhs(t, y, p)`` solving the augmented linear system
``[[M, -Aᵀ], [A, 0]] [q̈; λ] = [F; β]`` numerically, and ``outputs(t, y, p)`` with the CSV's names
(``lambda_<c>``, ``F_<c>``, ``energy``), the force of constraint's components ``F_<c>_x`` (``_y``,
``_z``: on the constraint's first particle, λ times its direction) and the residuals ``psi_<c>`` (holonomic
constraints) and ``velocity_<c>`` (A q̇ + offset). Names from the file appear only as string literals (``repr``);
every identifier in the code is generated (``_t``, ``_q0``, ``_p0``, ``_x0``...).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import sympy
from sympy.printing.numpy import NumPyPrinter

from lagsolve.numeric.system import NumericSystem


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _number(value: float) -> str:
    """A float as Python source (a parameter without a value, unused by the equations, is NaN)."""
    return repr(value) if math.isfinite(value) else f"float({str(value)!r})"


def _block(name: str, expressions: Sequence[Any], mapping: dict[Any, Any], printer: NumPyPrinter) -> list[str]:
    """``name = np.array([...])`` of the expressions, with common subexpressions as ``_x0, _x1...``."""
    exprs = [sympy.sympify(e, strict=True).xreplace(mapping) for e in expressions]  # SymPy values, never text
    symbols = sympy.numbered_symbols(f"_{name}")
    replacements, reduced = sympy.cse(exprs, symbols=symbols, order="canonical")
    lines = [f"    {printer.doprint(s)} = {printer.doprint(e)}" for s, e in replacements]
    items = ", ".join(printer.doprint(e) for e in reduced)
    lines.append(f"    {name} = np.array([{items}], dtype=float)")
    return lines


def _friction(system: NumericSystem, unpack: list[str], mapping: dict[Any, Any],
               printer: NumPyPrinter) -> list[str]:
    """``_signs`` (per forcing column: 1, then −sign(σ)... folded in as sign(σ) for contacts that slide along
    one line, 1 otherwise) and ``_normal_forces`` (N = |a + B N| per contact, as lagsolve simulate solves it)."""
    n = system.n
    lines = ["def _sliding_rates(t, y, p):",
             '    """Per contact that can stick: the sliding rate\'s coefficients w, the drift and the forces g."""']
    lines += [*unpack, *_block("_sliding", system.expressions["sliding"], mapping, printer), "    return _sliding",
              "", ""]
    lines += ["def _signs(t, y, p):", '    """1, then per contact sign(sigma) of its sliding rate (1 in a plane)."""',
              "    _sliding = _sliding_rates(t, y, p)"]
    lines.append(f"    out = np.ones({len(system.contacts) + 1})")
    at = 0
    for c, sticks in enumerate(system.sticks):
        if sticks:
            lines.append(f"    out[{c + 1}] = np.sign(_sliding[{at}:{at + n}] @ y[{n}:])")
            at += 2 * n + 1
    lines += ["    return out", "", ""]
    lines += ["def _normal_forces(t, y, p, lam):", '    """N = |a + B N| per contact (lam: columns 1, N...)."""']
    lines += [*unpack, *_block("_u", system.expressions["directions"], mapping, printer)]
    lines.append(f"    contacts = {system.contacts!r}")
    lines += [
        "    k = len(contacts)",
        "    a_parts, b_parts = [], []",
        "    for contact in contacts:",
        "        dims = contact[0][2]",
        "        a, b = np.zeros(dims), np.zeros((dims, k))",
        "        for j, offset, _ in contact:",
        "            direction = _u[offset:offset + dims]",
        "            a = a + lam[j, 0] * direction",
        "            b = b + np.outer(direction, lam[j, 1:])",
        "        a_parts.append(a)",
        "        b_parts.append(b)",
        "    if k == 1:",
        "        a, b = a_parts[0], b_parts[0][:, 0]",
        "        bb, ab, aa = float(b @ b), float(a @ b), float(a @ a)",
        "        if bb >= 1.0:",
        "            raise ValueError('no unique normal force (a Painleve-type inconsistency) at t = %g' % t)",
        "        return np.array([(ab + np.sqrt(ab * ab + (1.0 - bb) * aa)) / (1.0 - bb)])",
        "    normal = np.array([np.linalg.norm(a) for a in a_parts])",
        "    for _ in range(100):",
        "        new = np.array([np.linalg.norm(a + b @ normal) for a, b in zip(a_parts, b_parts)])",
        "        if np.max(np.abs(new - normal)) <= 1e-13 * max(1.0, float(np.max(new))):",
        "            return new",
        "        normal = new",
        "    raise ValueError('the normal forces did not converge at t = %g' % t)",
        "", "",
    ]
    return lines


def force_components(system: NumericSystem) -> list[tuple[str, int, int]]:
    """Per component of each force of constraint (on its first particle): its output name ``F_<c>_x`` (``_y``,
    ``_z``), the constraint's index and the component's row in ``expressions["force_directions"]``."""
    out, at = [], 0
    for j, (c, dims) in enumerate(zip(system.constraints, system.force_dims, strict=True)):
        out += [(f"F_{c}_{axis}", j, at + i) for i, axis in enumerate("xyz"[:dims])]
        at += dims
    return out


def _header(system: NumericSystem, name: str, version: str) -> list[str]:
    """The module's opening comment: the problem, the generator, and what the module does not model."""
    return [
        f"# {_one_line(name)}: equations of motion generated by lagsolve {version} (lagsolve export --to python).",
        "# Generated code: do not edit. Needs only NumPy.",
        "# rhs(t, y, p) solves [[M, -A^T], [A, 0]] [qdd; lambda] = [F; beta] at each call.",
        *(["# Unilateral constraints are held as if bilateral: watch the sign of their lambda_<c>."]
          if system.unilateral else []),
        *(["# Friction is kinetic only (-mu N sign(sigma)); sticking is not modelled."] if system.contacts else []),
    ]


#: the numeric solve of the augmented system, the same for every problem
_SOLVE: tuple[str, ...] = (
    "def _solve(t, y, p):",
        '    """Accelerations, multipliers and friction normal forces at (t, y)."""',
    "    M, F, A, beta = _matrices(t, y, p)",
    "    n, m, k = M.shape[0], A.shape[0], F.shape[1] - 1",
    "    if k:",
    "        F = F * _signs(t, y, p)",
    "    system = np.zeros((n + m, n + m))",
    "    system[:n, :n] = M",
    "    system[:n, n:] = -A.T",
    "    system[n:, :n] = A",
    "    rhs_ = np.zeros((n + m, k + 1))",
    "    rhs_[:n] = F",
    "    rhs_[n:, 0] = beta",
    "    solution = np.linalg.solve(system, rhs_)",
    "    normal = _normal_forces(t, y, p, solution[n:]) if k else np.zeros(0)",
    "    qdd = solution[:n, 0] + solution[:n, 1:] @ normal",
    "    lam = solution[n:, 0] + solution[n:, 1:] @ normal",
    "    return qdd, lam, normal",
    "",
    "",
)


def _rhs(n: int) -> list[str]:
    """``rhs(t, y, p)``: the state's derivative for ``solve_ivp``."""
    return [
        "def rhs(t, y, p=PARAMETERS):",
        '    """dy/dt at (t, y), y in the order of STATE; for scipy.integrate.solve_ivp."""',
        "    y = np.asarray(y, dtype=float)",
        f"    return np.concatenate((y[{n}:], _solve(t, y, p)[0]))",
        "",
        "",
    ]


def _outputs(system: NumericSystem, unpack: list[str], mapping: dict[Any, Any], printer: Any) -> list[str]:
    """``outputs(t, y, p)``: the multipliers, forces' magnitudes, energy h, normal and friction forces and the
    constraints' residuals, named as the CSV of ``lagsolve simulate`` names them."""
    n, m = system.n, system.m
    groups = system.expressions
    holonomic = [system.constraints[j] for j in system.holonomic]
    return [
        "def outputs(t, y, p=PARAMETERS):",
        '    """Multipliers, magnitudes of the forces of constraint, energy h and residuals at (t, y)."""',
        "    y = np.asarray(y, dtype=float)",
        "    _, lam, normal = _solve(t, y, p)",
        *unpack,
        *_block("_scales", groups["scales"], mapping, printer),
        *_block("_fdir", groups["force_directions"], mapping, printer),
        *_block("_energy", groups["energy"], mapping, printer),
        *_block("_psi", groups["psi"], mapping, printer),
        *_block("_jac", groups["velocity_jacobian"], mapping, printer),
        *_block("_offsets", groups["offsets"], mapping, printer),
        *_block("_mu", groups["contact_values"], mapping, printer),
        f"    _velocity = _jac.reshape({m}, {n}) @ y[{n}:] + _offsets" if m else "    _velocity = _offsets",
        "    out = {}",
        *(f"    out[{f'lambda_{c}'!r}] = float(lam[{j}])" for j, c in enumerate(system.constraints)),
        *(f"    out[{f'F_{c}'!r}] = float(abs(lam[{j}]) * _scales[{j}])" for j, c in enumerate(system.constraints)),
        *(f"    out[{name!r}] = float(lam[{j}] * _fdir[{at}])" for name, j, at in force_components(system)),
        "    out['energy'] = float(_energy[0])",
        *(f"    out[{f'N_{c}'!r}] = float(normal[{i}])" for i, c in enumerate(system.contact_names)),
        *(f"    out[{f'friction_{c}'!r}] = float(_mu[{2 * i + 1}] * normal[{i}]"
          + (f" * -_signs(t, y, p)[{i + 1}])" if system.sticks[i] else ")")
          for i, c in enumerate(system.contact_names)),
        *(f"    out[{f'psi_{c}'!r}] = float(_psi[{i}])" for i, c in enumerate(holonomic)),
        *(f"    out[{f'velocity_{c}'!r}] = float(_velocity[{j}])" for j, c in enumerate(system.constraints)),
        "    return out",
        "",
    ]


def event_names(system: NumericSystem) -> list[str]:
    """The event indicators: the sliding rate ``sliding_<c>`` of each contact that can stick, the multiplier
    ``lambda_<c>`` of each unilateral constraint; a sign change is a change of regime."""
    sliding = [f"sliding_{c}" for c, sticks in zip(system.contact_names, system.sticks, strict=True) if sticks]
    return [*sliding, *(f"lambda_{system.constraints[j]}" for j in system.unilateral)]


def _events(system: NumericSystem) -> list[str]:
    """``event_indicators(t, y, p)``: the values of EVENTS at (t, y), for ``solve_ivp``'s events."""
    n = system.n
    lines = ["def event_indicators(t, y, p=PARAMETERS):",
             '    """Sliding rates of the contacts that can stick and multipliers of the unilateral constraints, in',
             '    the order of EVENTS: a zero crossing is a change of regime (stick, slip or release)."""',
             "    y = np.asarray(y, dtype=float)"]
    if system.unilateral:
        lines.append("    lam = _solve(t, y, p)[1]")
    items = []
    if any(system.sticks):
        at = 0
        for sticks in system.sticks:
            if sticks:
                items.append(f"float(_sliding_rates(t, y, p)[{at}:{at + n}] @ y[{n}:])")
                at += 2 * n + 1
    items += [f"float(lam[{j}])" for j in system.unilateral]
    return [*lines, f"    return [{', '.join(items)}]", ""]


def python_module(system: NumericSystem, name: str, version: str) -> str:
    """The module's text (deterministic: the same bytes for the same system)."""
    n, m, k = system.n, system.m, len(system.contacts)
    time, coordinates, velocities, parameters = system.arguments
    mapping: dict[Any, Any] = {time: sympy.Symbol("_t")}
    mapping.update({c: sympy.Symbol(f"_q{i}") for i, c in enumerate(coordinates)})
    mapping.update({v: sympy.Symbol(f"_v{i}") for i, v in enumerate(velocities)})
    mapping.update({s: sympy.Symbol(f"_p{i}") for i, s in enumerate(parameters)})
    printer = NumPyPrinter({"fully_qualified_modules": True, "inline": True, "allow_unknown_functions": False})
    groups = system.expressions
    values = dict(zip(system.parameter_names, system.parameters.tolist(), strict=True))
    state = [*system.coordinates, *(f"{c}_dot" for c in system.coordinates)]
    unpack = ["    _t = t"]
    unpack += [f"    _q{i} = y[{i}]" for i in range(n)]
    unpack += [f"    _v{i} = y[{n + i}]" for i in range(n)]
    unpack += [f"    _p{i} = p[{k!r}]" for i, k in enumerate(system.parameter_names)]
    out = [
        *_header(system, name, version),
        "import numpy",
        "import numpy as np",
        "",
        f"PARAMETERS = {{{', '.join(f'{k!r}: {_number(v)}' for k, v in values.items())}}}",
        f"STATE = ({''.join(f'{s!r}, ' for s in state)})",
        f"CONSTRAINTS = ({''.join(f'{c!r}, ' for c in system.constraints)})",
        f"EVENTS = ({''.join(f'{e!r}, ' for e in event_names(system))})",
        "",
        "",
        "def _matrices(t, y, p):",
        *unpack,
        *_block("_flat", groups["matrices"], mapping, printer),
        f"    n, m, k = {n}, {m}, {k}",
        "    M = _flat[:n * n].reshape(n, n)",
        "    F = _flat[n * n:n * n + n * (k + 1)].reshape(n, k + 1)",
        "    at = n * n + n * (k + 1)",
        "    A = _flat[at:at + m * n].reshape(m, n)",
        "    beta = _flat[at + m * n:]",
        "    return M, F, A, beta",
        "",
        "",
        *_friction(system, unpack, mapping, printer),
        *_SOLVE,
        *_rhs(n),
        *_outputs(system, unpack, mapping, printer),
        "",
        *_events(system),
    ]
    if printer._not_supported:  # a function NumPy has no spelling of: refuse rather than write a module that fails
        unsupported = ", ".join(sorted(str(e) for e in printer._not_supported))
        raise ValueError(f"no NumPy spelling of {unsupported}")
    return "\n".join(out)
