"""pint imported without its optional array back-ends (lagsolve.pint_import)."""

from __future__ import annotations

import subprocess
import sys

SCRIPT = """
import sys
from lagsolve.problem.units import canonical, registry
assert canonical("kg*m/s^2") == "kg*m/s^2"
unit = registry().parse_units("N")
assert str((1 * unit).to_base_units().units) == "kilogram * meter / second ** 2", (1 * unit).to_base_units()
print(sorted(name for name in ("numpy", "scipy", "dask", "babel", "uncertainties") if name in sys.modules))
import numpy, dask  # hidden only while pint was imported
print(numpy.__name__, dask.__name__)
"""


def test_pint_imports_without_array_packages_and_leaves_them_importable():
    out = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, check=True).stdout
    assert out.splitlines() == ["[]", "numpy dask"]


def test_a_package_already_imported_stays_visible():
    script = ("import numpy, sys\nfrom lagsolve.pint_import import import_pint\npint = import_pint()\n"
              "import pint.compat\nprint(pint.compat.HAS_NUMPY, sys.modules['numpy'] is numpy)")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["True", "True"]
