"""A bound problem's equations as C99 (``lagsolve export --to c``): ``<prefix>.h`` and ``<prefix>.c``.

The source needs only libm. Each group of expressions (the matrices, the friction's sliding rates and
directions, the outputs' pieces) is one ``static`` function whose common subexpressions are shared (SymPy
``cse``, printed with SymPy's C99 printer). ``<prefix>_rhs`` assembles the augmented system
``[[M, -Aᵀ], [A, 0]] [q̈; λ] = [F; β]`` in fixed-size arrays and solves it by Gaussian elimination with
partial pivoting (no symbolic inverse), with one right-hand side per friction contact as ``lagsolve
simulate`` does; ``<prefix>_outputs`` gives the CSV's columns in the order of ``<prefix>_output_names``.
Names from the file appear only inside escaped string literals and a filtered comment; every identifier
is generated (``q0``, ``v0``, ``k0``, ``x0``...) or made from the file's stem by :func:`c_prefix`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import sympy
from sympy.printing.c import C99CodePrinter

from lagsolve.numeric.system import NumericSystem
from lagsolve.render.c_solve import gauss, normal_forces, sigma, size, solve
from lagsolve.render.python_module import event_names, force_components

#: the groups of ``system.expressions`` the C code evaluates, each one static function
GROUPS = ("matrices", "sliding", "directions", "contact_values", "scales", "force_directions", "energy", "psi",
          "velocity_jacobian", "offsets")

_SAFE_COMMENT = re.compile(r"[^A-Za-z0-9 .,:;()+=_'!#%&<>\[\]{}|~^@$-]")


def c_prefix(stem: str) -> str:
    """A C identifier from a file's stem (``my-bead`` → ``my_bead``, ``2link`` → ``m_2link``).

    Raises
    ------
    ValueError
        The stem holds no ASCII letter or digit, so no identifier says which problem it is.
    """
    ident = re.sub(r"[^A-Za-z0-9_]+", "_", stem).strip("_")
    if not re.search(r"[A-Za-z0-9]", ident):
        raise ValueError(f"the file name {stem!r} gives no C identifier")
    return f"m_{ident}" if ident[0].isdigit() else ident


def c_string(text: str) -> str:
    """``text`` as a C string literal: printable ASCII kept, ``"``, ``\\`` and ``?`` (trigraphs) escaped,
    every other byte of its UTF-8 an octal escape."""
    out = []
    for byte in text.encode("utf-8"):
        char = chr(byte)
        if char in '"\\?':
            out.append("\\" + char)
        elif 32 <= byte < 127:
            out.append(char)
        else:
            out.append(f"\\{byte:03o}")
    return '"' + "".join(out) + '"'


def c_comment(text: str) -> str:
    """One line of ``text`` safe inside ``/* */``: characters outside a plain set become ``_``."""
    return _SAFE_COMMENT.sub("_", " ".join(str(text).split()))


def _number(value: float) -> str:
    if math.isnan(value):
        return "NAN"
    if math.isinf(value):
        return "INFINITY" if value > 0 else "-INFINITY"
    text = repr(float(value))
    return text if any(c in text for c in ".en") else text + ".0"


@dataclass(frozen=True)
class Layout:
    """What the C code holds, by name and in order: the state, the parameters, the outputs and the event
    indicators (each sliding rate σ of a contact that can stick, each multiplier of a unilateral constraint)."""

    states: tuple[str, ...]
    parameters: tuple[str, ...]
    defaults: tuple[float, ...]
    outputs: tuple[str, ...]
    events: tuple[str, ...]


def layout(system: NumericSystem) -> Layout:
    """The names the exported code uses (the CSV's names of ``lagsolve simulate``)."""
    constraints = system.constraints
    holonomic = [constraints[j] for j in system.holonomic]
    outputs = [*(f"lambda_{c}" for c in constraints), *(f"F_{c}" for c in constraints),
               *(name for name, _, _ in force_components(system)), "energy",
               *(f"N_{c}" for c in system.contact_names), *(f"friction_{c}" for c in system.contact_names),
               *(f"psi_{c}" for c in holonomic), *(f"velocity_{c}" for c in constraints)]
    return Layout(states=(*system.coordinates, *(f"{c}_dot" for c in system.coordinates)),
                  parameters=system.parameter_names, defaults=tuple(system.parameters.tolist()),
                  outputs=tuple(outputs), events=tuple(event_names(system)))


class _Writer:
    """Prints each group as a static function over generated names."""

    def __init__(self, system: NumericSystem, prefix: str) -> None:
        time, coordinates, velocities, parameters = system.arguments
        self.n = system.n
        self.parameters = len(parameters)
        self.prefix = prefix
        self.mapping: dict[Any, Any] = {time: sympy.Symbol("t")}
        self.mapping.update({c: sympy.Symbol(f"q{i}") for i, c in enumerate(coordinates)})
        self.mapping.update({v: sympy.Symbol(f"v{i}") for i, v in enumerate(velocities)})
        self.mapping.update({s: sympy.Symbol(f"k{i}") for i, s in enumerate(parameters)})
        self.printer = C99CodePrinter({"allow_unknown_functions": False})

    def code(self, expr: Any) -> str:
        return " ".join(self.printer.doprint(expr).split())

    def unpack(self, symbols: set[Any]) -> list[str]:
        """``const double q0 = y[0];``... for the names the expressions use, in a fixed order."""
        names = {str(s) for s in symbols}
        n = self.n
        out = []
        for i in range(n):
            if f"q{i}" in names:
                out.append(f"    const double q{i} = y[{i}];")
        for i in range(n):
            if f"v{i}" in names:
                out.append(f"    const double v{i} = y[{n + i}];")
        for i in range(self.parameters):
            if f"k{i}" in names:
                out.append(f"    const double k{i} = p[{i}];")
        return out

    def group(self, name: str, expressions: Sequence[Any]) -> list[str]:
        """``static void <prefix>_<name>(t, y, p, out)`` writing ``out[i]``, common subexpressions ``x0...``."""
        exprs = [sympy.sympify(e, strict=True).xreplace(self.mapping) for e in expressions]  # SymPy values only
        replacements, reduced = sympy.cse(exprs, symbols=sympy.numbered_symbols("x"), order="canonical")
        used = set().union(set(), *(e.free_symbols for e in exprs))
        lines = [f"static void {self.prefix}_{name}(double t, const double *y, const double *p, double *out)",
                 "{", "    (void)t; (void)y; (void)p; (void)out;", *self.unpack(used)]
        lines += [f"    const double {self.code(s)} = {self.code(e)};" for s, e in replacements]
        lines += [f"    out[{i}] = {self.code(e)};" for i, e in enumerate(reduced)]
        return [*lines, "}", ""]


def header(system: NumericSystem, prefix: str, name: str, version: str, source: str) -> str:
    """``<prefix>.h``: the sizes, the name arrays and the functions."""
    names = layout(system)
    guard = f"{prefix.upper()}_H"
    p = prefix
    lines = [
        *_banner(system, name, version, source),
        f"#ifndef {guard}", f"#define {guard}", "",
        f"#define {p.upper()}_N_STATES {len(names.states)}",
        f"#define {p.upper()}_N_PARAMETERS {len(names.parameters)}",
        f"#define {p.upper()}_N_OUTPUTS {len(names.outputs)}",
        f"#define {p.upper()}_N_EVENTS {len(names.events)}", "",
        "/* Names (each array ends with NULL) and the file's parameter values (NAN where none is given). */",
        f"extern const char *const {p}_state_names[];",
        f"extern const char *const {p}_parameter_names[];",
        f"extern const double {p}_parameter_defaults[];",
        f"extern const char *const {p}_output_names[];",
        f"extern const char *const {p}_event_names[];", "",
        "/* dy = f(t, y, p), y = (q, q_dot). Returns 0, or 1 where the augmented system is singular, 2 where the",
        "   friction's normal force has no unique value (Painleve-type) or does not converge. */",
        f"int {p}_rhs(double t, const double *y, const double *p, double *dy);",
        f"/* out[{p.upper()}_N_OUTPUTS] in the order of {p}_output_names; returns as {p}_rhs. */",
        f"int {p}_outputs(double t, const double *y, const double *p, double *out);",
        f"/* z[{p.upper()}_N_EVENTS]: sliding rates of the contacts that can stick and multipliers of the",
        "   unilateral constraints; a sign change is a change of regime (see docs/format.md, Export). */",
        f"int {p}_event_indicators(double t, const double *y, const double *p, double *z);", "",
        f"#endif /* {guard} */", "",
    ]
    return "\n".join(lines)


def _banner(system: NumericSystem, name: str, version: str, source: str) -> list[str]:
    return [
        f"/* {c_comment(name)}: equations of motion generated by lagsolve {c_comment(version)}",
        f"   (lagsolve export --to c) from {c_comment(source)}: the matrix form M qdd = F + A^T lambda.",
        "   Generated code: do not edit. C99, needs only libm.",
        *(["   Unilateral constraints are held as if bilateral: watch the sign of their lambda_<c>."]
          if system.unilateral else []),
        *(["   Friction is kinetic only (-mu N sign(sigma)); sticking is not modelled."] if system.contacts else []),
        "*/", "",
    ]


def _arrays(system: NumericSystem, prefix: str) -> list[str]:
    names = layout(system)

    def strings(label: str, items: Sequence[str]) -> str:
        return f"const char *const {prefix}_{label}[] = {{{''.join(c_string(s) + ', ' for s in items)}NULL}};"

    defaults = "".join(_number(v) + ", " for v in names.defaults)
    return [strings("state_names", names.states), strings("parameter_names", names.parameters),
            f"const double {prefix}_parameter_defaults[] = {{{defaults}0.0}};",
            strings("output_names", names.outputs), strings("event_names", names.events), ""]


def _signs(system: NumericSystem, prefix: str) -> list[str]:
    """``signs[1 + c]``: sign(σ) of each contact that can stick, 1 otherwise; ``signs[0]`` = 1."""
    k = len(system.contacts)
    lines = [f"    double signs[{k + 1}];", f"    double sigma[{size(k)}];"]
    lines += [f"    {prefix}_sigma(t, y, p, sigma);"] if k else ["    sigma[0] = 0.0;"]
    lines += ["    signs[0] = 1.0;"]
    lines += [f"    signs[{c + 1}] = " + (f"(double)((sigma[{c}] > 0.0) - (sigma[{c}] < 0.0));"
                                          if sticks else "1.0;") for c, sticks in enumerate(system.sticks)]
    return [*lines, "    (void)sigma;"]


def _solved(system: NumericSystem, prefix: str) -> list[str]:
    """The locals of a function that solves first: q̈, λ, N and the status."""
    n, m, k = system.n, system.m, len(system.contacts)
    return [f"    double qdd[{n}], lam[{size(m)}], normal[{size(k)}];", *_signs(system, prefix),
            f"    int status = {prefix}_solve(t, y, p, signs, qdd, lam, normal);"]


def _rhs(system: NumericSystem, prefix: str) -> list[str]:
    n = system.n
    return [f"int {prefix}_rhs(double t, const double *y, const double *p, double *dy)", "{",
            *_solved(system, prefix), "    int i;", f"    for (i = 0; i < {n}; ++i) {{",
            f"        dy[i] = y[{n} + i];", f"        dy[{n} + i] = qdd[i];", "    }", "    return status;", "}", ""]


def _outputs(system: NumericSystem, prefix: str) -> list[str]:
    """``<prefix>_outputs``: one line per output, in the order of :func:`layout`."""
    n, m = system.n, system.m
    groups = system.expressions
    locals_ = [f"    double {g}[{size(len(groups[g]))}];" for g in GROUPS[3:]]
    calls = [f"    {prefix}_{g}(t, y, p, {g});" for g in GROUPS[3:]]
    values = [*(f"lam[{j}]" for j in range(m)), *(f"fabs(lam[{j}]) * scales[{j}]" for j in range(m)),
              *(f"lam[{j}] * force_directions[{at}]" for _, j, at in force_components(system)), "energy[0]",
              *(f"normal[{c}]" for c in range(len(system.contacts))),
              *(f"contact_values[{2 * c + 1}] * normal[{c}]" + (f" * -signs[{c + 1}]" if sticks else "")
                for c, sticks in enumerate(system.sticks)),
              *(f"psi[{i}]" for i in range(len(system.holonomic))),
              *(" + ".join([*(f"velocity_jacobian[{r * n + j}] * y[{n + j}]" for j in range(n)), f"offsets[{r}]"])
                for r in range(m))]
    names = layout(system).outputs
    return [f"int {prefix}_outputs(double t, const double *y, const double *p, double *out)", "{",
            *_solved(system, prefix), *locals_, *calls,
            *(f"    out[{i}] = {v};  /* {c_comment(name)} */" for i, (v, name) in enumerate(zip(values, names,
                                                                                             strict=True))),
            "    return status;", "}", ""]


def _events(system: NumericSystem, prefix: str) -> list[str]:
    sliding = [c for c, sticks in enumerate(system.sticks) if sticks]
    values = [*(f"sigma[{c}]" for c in sliding), *(f"lam[{j}]" for j in system.unilateral)]
    return [f"int {prefix}_event_indicators(double t, const double *y, const double *p, double *z)", "{",
            *_solved(system, prefix), "    (void)z;", *(f"    z[{i}] = {v};" for i, v in enumerate(values)),
            "    return status;", "}", ""]


def c_module(system: NumericSystem, prefix: str, name: str, version: str, source: str) -> tuple[str, str]:
    """The header's and the source's text (deterministic: the same bytes for the same system).

    Raises
    ------
    ValueError
        An expression holds a function C99 has no spelling of.
    """
    writer = _Writer(system, prefix)
    used = [g for g in GROUPS if system.contacts or g not in ("sliding", "directions")]
    groups = [line for g in used for line in writer.group(g, system.expressions[g])]
    if writer.printer._not_supported:
        unsupported = ", ".join(sorted(str(e) for e in writer.printer._not_supported))
        raise ValueError(f"no C99 spelling of {unsupported}")
    n, m, k = system.n, system.m, len(system.contacts)
    body = [
        *_banner(system, name, version, source),
        "#include <math.h>", "#include <stddef.h>", "#include <string.h>", "", f'#include "{prefix}.h"', "",
        *_arrays(system, prefix), *groups,
        *gauss(n + m, k + 1, prefix), *(sigma(system, prefix) if k else []), *normal_forces(system, prefix),
        *solve(system, prefix), *_rhs(system, prefix), *_outputs(system, prefix), *_events(system, prefix),
    ]
    return header(system, prefix, name, version, source), "\n".join(body)
