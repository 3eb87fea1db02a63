"""pint, imported without its optional array back-ends.

``import pint`` tries NumPy, SciPy, Dask, Babel and uncertainties on import (about 0.3 s of CPU when they are
installed, as NumPy, SciPy and Dask are here). lagsolve gives pint only unit texts and unit objects, never
arrays, so pint is imported as if those packages were missing: each one not imported yet is hidden for the
length of the import. Packages already imported stay visible (pint then knows them, which changes nothing
lagsolve asks of it).
"""

from __future__ import annotations

import sys
from types import ModuleType

#: the optional packages pint's ``compat`` looks for on import
OPTIONAL = ("numpy", "scipy", "dask", "babel", "uncertainties", "xarray", "pandas", "mip")


def import_pint() -> ModuleType:
    """The ``pint`` module, imported with the optional packages not yet imported hidden from it."""
    if "pint" in sys.modules:
        return sys.modules["pint"]
    hidden = [name for name in OPTIONAL if name not in sys.modules]
    for name in hidden:
        sys.modules[name] = None  # type: ignore[assignment]  # import raises ImportError, find_spec is None
    try:
        import pint
    finally:
        for name in hidden:
            if sys.modules.get(name, 0) is None:
                del sys.modules[name]
    return pint
