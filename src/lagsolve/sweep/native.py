"""The compiled path: a problem's equations and the integrator of :mod:`lagsolve.sweep.kernel` as machine code.

The problem's mass matrix, forcing, energy and conserved quantities (SymPy objects, the groups
:func:`lagsolve.numeric.system.bind` compiled) are printed as Python functions by SymPy's code printer
(:class:`sympy.printing.pycode.PythonCodePrinter`, after :func:`sympy.cse`), with the arguments renamed
by :func:`lagsolve.numeric.compile.private_arguments`: the text is made from SymPy objects, never from
the problem file's text. That text follows the kernel's (:mod:`lagsolve.sweep.kernel`) in one module,
which Numba compiles with ``nogil=True``. Nothing is written unless the user names a folder for the compiled
code: with ``$LAGSOLVE_CACHE`` set, the module is written there to a file named by the hash of its text and
compiled with ``cache=True``, so a second process (a later sweep, a Dask worker) loads the machine code from
Numba's cache instead of compiling it again (about a minute the first time on a loaded machine, 0.1–0.4 s
afterwards); without it, the module lives in memory and is compiled in each process that needs it.

Numba is optional (in the ``sweep`` extra): without it, or for a problem this path does not cover
(constraints, friction contacts, an expression the printer cannot write), :func:`native_system`
returns None with the reason, and the sweep takes the NumPy batched path.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import tempfile
import threading
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import FunctionType, ModuleType
from typing import Any, Literal

import numpy as np

#: the functions of the generated module Numba inlines where they are called (no call, no reference counting
#: of the arrays passed): the small ones of every step. Inlining the step itself and its measures too saves
#: about 4 % of the run time and doubles the first compilation (55 s → 100 s on the loaded machine).
INLINED = ("matrices", "derivative", "_finite", "_worst", "_ulp", "_combine", "_weighted", "_error", "_flip_excess",
           "_control", "_ended")

_LOCK = threading.Lock()


def cache_folder() -> Path | None:
    """Where the generated modules (and Numba's cache of their machine code) are kept: the folder the user named
    in ``$LAGSOLVE_CACHE``, or None (nothing is written; a command writes only into its output folder)."""
    given = os.environ.get("LAGSOLVE_CACHE")
    return Path(given) if given else None


@dataclass(frozen=True)
class NativeSystem:
    """A problem's compiled integrator: :func:`lagsolve.sweep.kernel.integrate_runs` for its equations."""

    n: int
    n_conserved: int
    module: ModuleType

    def integrate(self, y0: np.ndarray, params: np.ndarray, t_end: float, method: str, rtol: float, atol: float,
                  angular: np.ndarray, section: tuple[int, float] | None,
                  max_steps: int = 1_000_000) -> tuple[Any, ...]:
        """Every run of ``y0`` (N, 2n) with its parameters ``params`` (N, k): see ``integrate_runs``."""
        tab = _tableau(method)
        index, value = section if section is not None else (-1, 0.0)
        return self.module.integrate_runs(np.ascontiguousarray(y0, dtype=float),
                                          np.ascontiguousarray(params, dtype=float), float(t_end), float(rtol),
                                          float(atol), int(max_steps), *tab, np.asarray(angular, dtype=np.bool_),
                                          int(index), float(value), self.n_conserved)


def _tableau(method: str) -> tuple[Any, ...]:
    """The arguments of ``integrate_runs`` that describe the method (SciPy's coefficients)."""
    from scipy import integrate

    solver = getattr(integrate, method)
    s = solver.n_stages
    none2, none1 = np.zeros((0, s + 1)), np.zeros(0)
    if method == "DOP853":
        return (np.ascontiguousarray(solver.A[:s, :s], dtype=float), np.asarray(solver.B, dtype=float),
                np.asarray(solver.C[:s], dtype=float), np.asarray(solver.E5, dtype=float),
                np.asarray(solver.E3, dtype=float), True, int(solver.error_estimator_order), s, True,
                np.ascontiguousarray(solver.A_EXTRA, dtype=float), np.asarray(solver.C_EXTRA, dtype=float),
                np.ascontiguousarray(solver.D, dtype=float), np.zeros((s + 1, 0)))
    return (np.ascontiguousarray(solver.A, dtype=float), np.asarray(solver.B, dtype=float),
            np.asarray(solver.C, dtype=float), np.asarray(solver.E, dtype=float), np.zeros(s + 1), False,
            int(solver.error_estimator_order), s, False, none2, none1, np.zeros((0, s + 4)),
            np.ascontiguousarray(solver.P, dtype=float))


def numba_available() -> bool:
    return importlib.util.find_spec("numba") is not None


def source(system: Any) -> tuple[str | None, str]:
    """The generated module's text for a bound ``system`` (:class:`lagsolve.numeric.system.NumericSystem`),
    or None and why this path does not cover it."""
    if system.contacts:
        return None, "friction contacts (stick–slip restarts)"
    if system.unilateral:
        return None, "unilateral constraints (release events)"
    if system.m or system.holonomic:
        return None, "constraints (the batched path projects onto them)"
    groups = system.expressions
    n = system.n
    matrices = list(groups.get("matrices", ()))
    if len(matrices) < n * n + n:
        return None, "the equations are not all compiled"
    mass, force = matrices[: n * n], matrices[n * n: n * n + n]
    energy = list(groups.get("energy", ())) or [float("nan")]
    conserved = list(groups.get("conserved", ()))
    time, coordinates, velocities, parameters = system.arguments
    flat = [time, *coordinates, *velocities, *parameters]
    try:
        parts = [_function("matrices", "(t, y, p, mass, force)", flat, n,
                           [(f"mass[{i // n}, {i % n}]", e) for i, e in enumerate(mass)]
                           + [(f"force[{i}]", e) for i, e in enumerate(force)]),
                 _function("energy", "(t, y, p)", flat, n, [("return", energy[0])]),
                 _function("conserved", "(t, y, p, out)", flat, n,
                           [(f"out[{i}]", e) for i, e in enumerate(conserved)])]
    except _Unprintable as exc:
        return None, f"an expression the code printer cannot write ({exc})"
    kernel = Path(__file__).with_name("kernel.py").read_text(encoding="utf-8")
    options = (f"# compiled by lagsolve.sweep.native: nogil, cached, error model numpy, inlined "
               f"{', '.join(INLINED)}\n")
    return (kernel + "\n\n# ---- the problem's functions (printed by SymPy) ----\n" + options + "\n"
            + "\n\n".join(parts) + "\n", "")


class _Unprintable(Exception):
    pass


def _function(name: str, signature: str, flat: Sequence[Any], n: int, targets: list[tuple[str, Any]]) -> str:
    """A function ``name`` assigning each printed expression to its target (or returning it)."""
    import sympy
    from sympy.printing.pycode import PythonCodePrinter

    from lagsolve.numeric.compile import private_arguments

    renamed, exprs = private_arguments(flat, [sympy.sympify(e, strict=True) if isinstance(e, int | float) else e
                                              for _, e in targets])
    printer = _printer(PythonCodePrinter)
    lines = [f"def {name}{signature}:  # noqa: F811, ANN001, ANN202, E501"]
    args = ["t", *(f"y[{i}]" for i in range(2 * n)), *(f"p[{i}]" for i in range(len(renamed) - 1 - 2 * n))]
    for symbol, arg in zip(renamed, args, strict=True):
        lines.append(f"    {printer.doprint(symbol)} = {arg}")
    replacements, reduced = sympy.cse(exprs, symbols=sympy.numbered_symbols("_lagsolve_cse"), optimizations=None)
    for symbol, expr in replacements:
        lines.append(f"    {printer.doprint(symbol)} = {_print(printer, expr)}")
    for (target, _), expr in zip(targets, reduced, strict=True):
        text = _print(printer, expr)
        lines.append(f"    return {text}" if target == "return" else f"    {target} = {text}")
    if not targets or targets[-1][0] != "return":
        lines.append("    return")
    return "\n".join(lines)


def _printer(base: type) -> Any:
    """SymPy's Python printer, writing a negative whole power as a division (``1.0/(x**2)``): Numba raises
    ZeroDivisionError for ``0.0**-2`` whatever its error model, while a division by zero gives an infinity."""
    import sympy

    class Printer(base):
        def _print_Pow(self, expr: Any, rational: bool = False) -> str:
            exponent = expr.exp
            if exponent.is_Integer and exponent < 0:
                power = expr.base if exponent == -1 else sympy.Pow(expr.base, -exponent, evaluate=False)
                return f"(1.0/({self._print(power)}))"
            return str(super()._print_Pow(expr, rational=rational))

    return Printer({"fully_qualified_modules": True, "standard": "python3"})


def _print(printer: Any, expr: Any) -> str:
    import sympy

    if isinstance(expr, sympy.Basic) and expr.has(sympy.zoo, sympy.oo, -sympy.oo):
        raise _Unprintable("an infinite constant")
    text = printer.doprint(expr)
    if printer._not_supported:
        raise _Unprintable(", ".join(sorted(str(e.func) for e in printer._not_supported if hasattr(e, "func")))
                           or "unsupported")
    return f"float({text})"


def load(text: str) -> ModuleType:
    """The module of ``text`` with its functions compiled by Numba (machine code from Numba's on-disk cache
    when this text was compiled before), written once to a file named by the text's hash."""
    import numba

    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()[:24]
    name = f"lagsolve_sweep_{digest}"
    with _LOCK:
        found = sys.modules.get(name)
        if found is not None:
            return found
        path = _written(text, name)
        module = _module(text, name, path)  # the kernel's text and SymPy's printing of SymPy objects only
        functions = [k for k, v in vars(module).items() if isinstance(v, FunctionType) and v.__module__ == name]
        for function in functions:
            inline: Literal["always", "never"] = "always" if function in INLINED else "never"
            jit = numba.njit(cache=path is not None, nogil=True, inline=inline, error_model="numpy")
            setattr(module, function, jit(getattr(module, function)))
        sys.modules[name] = module
        return module


def _module(text: str, name: str, path: Path | None) -> ModuleType:
    """The module of ``text``: loaded from its file in the cache folder, or (no folder) made in memory."""
    if path is not None:
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    module = ModuleType(name)
    module.__dict__["__name__"] = name
    exec(compile(text, f"<{name}>", "exec"), module.__dict__)  # noqa: S102 - printed from SymPy objects, not file text
    return module


def _written(text: str, name: str) -> Path | None:
    """The file holding ``text`` in the cache folder the user named (written atomically if it is not there yet, and
    never through a symbolic link), or None: no folder named, or it cannot be written (the module is then made in
    memory)."""
    folder = cache_folder()
    if folder is None:
        return None
    folder = folder / "sweep"
    path = folder / f"{name}.py"
    try:
        if path.is_symlink():
            return None
        if path.exists() and path.read_text(encoding="utf-8") == text:
            return path
        folder.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=folder, suffix=".tmp")
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        os.replace(temporary, path)
        return path
    except OSError:
        return None


def native_system(system: Any) -> tuple[NativeSystem | None, str]:
    """The compiled integrator of a bound ``system``, or None and why the sweep takes another path."""
    if not numba_available():
        return None, "Numba is not installed (pip install 'lagsolve[sweep]')"
    text, why = source(system)
    if text is None:
        return None, why
    native = NativeSystem(system.n, len(system.expressions.get("conserved", ())), load(text))
    try:  # compiled (or loaded from the cache) here, once, not in a worker thread; one run, one short step
        native.integrate(np.zeros((1, 2 * system.n)), np.asarray(system.parameters, dtype=float)[None, :], 1e-9,
                         "DOP853", 1e-3, 1e-6, np.zeros(system.n, dtype=bool), (0, 0.0))
    except Exception as exc:  # noqa: BLE001 - Numba's typing and lowering errors have no common base to name
        return None, f"Numba could not compile the problem's functions ({type(exc).__name__})"
    return native, ""
