"""The examples in the docstrings run and give what they show (every module of src/lagsolve)."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
MODULES = sorted(".".join(p.relative_to(SRC).with_suffix("").parts).removesuffix(".__init__")
                 for p in (SRC / "lagsolve").rglob("*.py") if p.name != "__main__.py")
#: docstring examples known to disagree with the code, each with why (the test reports them as xfail)
KNOWN: dict[str, str] = {}


def _examples() -> list[tuple[str, str]]:
    out = []
    finder = doctest.DocTestFinder()
    for name in MODULES:
        module = importlib.import_module(name)
        out += [(name, test.name) for test in finder.find(module, name) if test.examples]
    return out


@pytest.mark.parametrize(("module", "name"), _examples(), ids=lambda x: x)
def test_docstring_examples(module: str, name: str) -> None:
    if name in KNOWN:
        pytest.xfail(KNOWN[name])
    test = next(t for t in doctest.DocTestFinder().find(importlib.import_module(module), module) if t.name == name)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    result = runner.run(test, out=lambda text: None)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples fail (run pytest " \
                               "--doctest-modules on the module to see them)"
