"""What make prepares beside the install (lagsolve.caches, lagsolve.prepare): read, never written, by a command;
the same units with and without pint's parsed definitions."""

from __future__ import annotations

from pathlib import Path

import pint
import pytest

from lagsolve import caches, prepare

UNITS = ["kg", "m/s^2", "N*m", "kg*m^2", "rad", "km", "J", "W", "lbf", "inch", "hour", "1", "N/m", "Pa*s"]


def test_pint_reads_the_prepared_definitions_and_gives_the_same_units(tmp_path: Path,
                                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(caches, "UNITS", tmp_path)
    assert caches.pint_cache(pint.__version__) is None  # nothing prepared: pint parses its own
    folder = prepare.prepare_units()
    assert caches.pint_cache(pint.__version__) == folder
    before = {p.name: p.stat().st_mtime_ns for p in folder.iterdir()}
    cached = pint.UnitRegistry(autoconvert_offset_to_baseunit=False, cache_folder=str(folder))
    plain = pint.UnitRegistry(autoconvert_offset_to_baseunit=False)
    for text in UNITS:
        a, b = cached.Quantity(1, text.replace("^", "**")), plain.Quantity(1, text.replace("^", "**"))
        assert a.dimensionality == b.dimensionality
        assert a.to_base_units().magnitude == pytest.approx(b.to_base_units().magnitude, rel=1e-15)
    assert {p.name: p.stat().st_mtime_ns for p in folder.iterdir()} == before  # read, not written


def test_an_unprepared_or_linked_folder_is_not_used(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(caches, "UNITS", tmp_path)
    folder = caches.pint_folder("0.0")
    folder.mkdir(parents=True)
    assert caches.pint_cache("0.0") is None  # no marker: another pint's, or half written
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / caches.MARKER).write_text("x")
    caches.pint_folder("9.9").symlink_to(elsewhere)
    assert caches.pint_cache("9.9") is None


def test_the_problems_units_are_read_with_the_installed_cache() -> None:
    """The command's registry (problem/units.py) reads the folder make prepared for this pint, when there is one."""
    from lagsolve.problem import units

    registry = units.registry()
    folder = caches.pint_cache(pint.__version__)
    assert registry is not None
    if folder is not None:  # make prepared it (make test does, .ci/run too)
        assert any(folder.iterdir())


def test_prepare_compiles_the_package_bytecode() -> None:
    """make's prepare step leaves every module of the package compiled (what Python reads at each command, even
    where PYTHONDONTWRITEBYTECODE keeps it from writing them), and says how many modules there are."""
    import importlib.util

    import lagsolve.cli

    count = prepare.compile_package()
    sources = list(Path(lagsolve.cli.__file__).parent.rglob("*.py"))
    assert count == len(sources) > 100
    assert all(Path(importlib.util.cache_from_source(str(s))).is_file() for s in sources)
