"""Session-wide fixtures: each shipped problem is derived, and its reports rendered, once per test session.

A derivation is frozen and a :class:`~lagsolve.app.pipeline.Reports` is only read, so the tests that
merely read them share one copy (`make test` derived each problem four or more times before). A test
that derives with other options (a budget, ``analysis=False``) or checks the derivation itself still
derives on its own.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from lagsolve.app.pipeline import Reports, derive_file
from lagsolve.mechanics.derivation import Derivation
from mechanics_support import derived_file

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"

#: the formats of the shared reports: those with golden files
FORMATS = ("md", "tex", "json")


@pytest.fixture(scope="session")
def shipped_derivation() -> Callable[[str], Derivation]:
    """``derive`` of ``problems/<name>.yaml`` with the default budget, computed once per session."""
    return derived_file


@pytest.fixture(scope="session")
def shipped_reports() -> Callable[[str], Reports]:
    """``derive_file(problems/<name>.yaml, FORMATS)`` (what ``lagsolve derive`` writes), once per session."""
    cache: dict[str, Reports] = {}

    def reports(name: str) -> Reports:
        if name not in cache:
            cache[name] = derive_file(PROBLEMS / f"{name}.yaml", FORMATS)
        return cache[name]

    return reports
