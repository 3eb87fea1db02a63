"""The tests' derivations shared between pytest-xdist workers (tests/mechanics_support.py) read back unchanged."""

from __future__ import annotations

import pickle

import pytest
import sympy

from lagsolve.app.pipeline import reports_of
from mechanics_support import PROBLEMS, derived_file, unpickled


@pytest.mark.parametrize("name", ["atwood", "bead", "rough_wedge", "multidof_holonomic"])
def test_a_derivation_read_back_gives_the_same_reports(name: str) -> None:
    derivation = derived_file(name)
    again = unpickled(pickle.dumps(derivation))
    assert reports_of(again, PROBLEMS / f"{name}.yaml", ("md", "tex", "json")).outputs == \
        reports_of(derivation, PROBLEMS / f"{name}.yaml", ("md", "tex", "json")).outputs
    assert sympy.srepr(again.kinetic) == sympy.srepr(derivation.kinetic)


def test_a_plain_pickle_would_not_do() -> None:
    """Why unpickled() turns evaluation off: the Atwood machine's T = (m1 y1'² + m2 y2'²)/2 comes back distributed."""
    kinetic = derived_file("atwood").kinetic
    assert sympy.srepr(pickle.loads(pickle.dumps(kinetic))) != sympy.srepr(kinetic)
    assert sympy.srepr(unpickled(pickle.dumps(kinetic))) == sympy.srepr(kinetic)
