"""`lagsolve.mechanics.results`: a Derivation is composed of parts built before its one constructor (issue 30
item 6); the names people read are the parts' fields."""

from __future__ import annotations

import dataclasses

import pytest

from lagsolve.mechanics.results import Canonical, Contract, Derivation, Display, Solution

#: each flat name and the part it reads
THROUGH = {
    "problem": "form", "model": "form", "lagrange": "form",
    **{f.name: "display" for f in dataclasses.fields(Display)},
    **{f.name: "solution" for f in dataclasses.fields(Solution)},
    **{f.name: "contract" for f in dataclasses.fields(Contract)},
    "hamiltonian": "canonical",
}


def test_the_derivation_has_its_parts_as_fields() -> None:
    """Nine fields, the parts; everything else is read through them."""
    assert [f.name for f in dataclasses.fields(Derivation)] == [
        "form", "elimination", "display", "solution", "friction", "analysis", "contract", "canonical", "notes"]


@pytest.mark.parametrize("name", ["bead", "hole_table", "rough_wedge"])
def test_names_read_through_the_parts(name: str, shipped_derivation) -> None:  # type: ignore[no-untyped-def]
    """``d.kinetic`` is ``d.display.kinetic``, ``d.accelerations`` ``d.solution.accelerations`` ..., and the
    Hamiltonian's note is ``d.canonical.note``."""
    d = shipped_derivation(name)
    for attribute, part in THROUGH.items():
        assert getattr(d, attribute) is getattr(getattr(d, part), attribute), attribute
    assert d.hamiltonian_note == d.canonical.note
    assert isinstance(d.canonical, Canonical)
    with pytest.raises(dataclasses.FrozenInstanceError):
        d.kinetic = 0  # type: ignore[misc]


def test_the_parts_are_filled_by_the_stages(shipped_derivation) -> None:  # type: ignore[no-untyped-def]
    """The hole table: solved, analysed (its contract forms from the analysis), with a Hamiltonian."""
    d = shipped_derivation("hole_table")
    assert d.solution.accelerations is not None and d.solution.constraint_forces is not None
    assert d.analysis is not None and d.contract.conserved is not None
    assert d.canonical.hamiltonian is not None and d.canonical.note == ""
