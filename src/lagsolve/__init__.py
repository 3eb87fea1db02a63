"""lagsolve: Lagrangian mechanics from a YAML problem file.

The pipeline is ``problem`` (read and validate) → ``mechanics`` (derive) →
``render`` (Markdown, LaTeX, JSON). Importing this package is cheap: SymPy is
imported only by the modules that need it, and the public API below is loaded
on first use.

>>> import lagsolve
>>> derivation = lagsolve.derive("problems/bead.yaml")           # doctest: +SKIP
>>> run = lagsolve.simulate(derivation, t_end=5.0)                # doctest: +SKIP
>>> report = lagsolve.check("problems/bead.yaml")                # doctest: +SKIP
"""

from __future__ import annotations

import sys
import types
from typing import TYPE_CHECKING, Any

from lagsolve import notebook

__version__ = "0.1.0"

if TYPE_CHECKING:
    from lagsolve.api import Trajectory, check, derive, export, load_problem, simulate, variants
    from lagsolve.check.compare import CheckReport
    from lagsolve.errors import DerivationError, LagsolveError, RenderError, SimulationError, SpecError
    from lagsolve.mechanics.derivation import Derivation
    from lagsolve.problem.schema import Problem
    from lagsolve.sweep.api import sweep

#: public name → the module that defines it (imported on first use, see ``__getattr__``)
_PUBLIC = {
    "load_problem": "lagsolve.api",
    "derive": "lagsolve.api",
    "simulate": "lagsolve.api",
    "export": "lagsolve.api",
    "sweep": "lagsolve.sweep.api",
    "check": "lagsolve.api",
    "variants": "lagsolve.api",
    "Trajectory": "lagsolve.api",
    "Derivation": "lagsolve.mechanics.derivation",
    "CheckReport": "lagsolve.check.compare",
    "Problem": "lagsolve.problem.schema",
    "LagsolveError": "lagsolve.errors",
    "SpecError": "lagsolve.errors",
    "DerivationError": "lagsolve.errors",
    "SimulationError": "lagsolve.errors",
    "RenderError": "lagsolve.errors",
}

__all__ = [
    "CheckReport", "Derivation", "DerivationError", "LagsolveError", "Problem", "RenderError", "SimulationError",
    "SpecError", "Trajectory", "__version__", "check", "derive", "export", "load_problem", "simulate", "sweep",
    "variants",
]


def __getattr__(name: str) -> Any:
    if name not in _PUBLIC:
        raise AttributeError(f"module 'lagsolve' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(_PUBLIC[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_PUBLIC})


class _Package(types.ModuleType):
    """The package module: ``lagsolve.check`` (and ``lagsolve.variants``) stays the function when the submodule of
    that name is imported (the import system would otherwise set the package attribute to the module)."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name in _PUBLIC and isinstance(value, types.ModuleType):
            self.__dict__.pop(name, None)  # found again through __getattr__
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


def _notebook_display() -> None:
    """The renderers of derivations and check reports, registered when the first result is shown."""
    from lagsolve.render.display import register

    register()


notebook.on_first_use(_notebook_display)
