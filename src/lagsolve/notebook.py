"""Notebook display without an import that climbs: a result's ``_repr_*_`` hook asks this registry.

The results IPython shows are made by early stages (``mechanics.results.Derivation``,
``check.compare.CheckReport``), and their renderers live in ``render/display.py``, a later one. So a
result never imports its renderer: its hook calls :func:`shown`, and ``render.display.register``
fills the registry. The package (``lagsolve/__init__.py``) names that registration with
:func:`on_first_use`; it runs when the first result is shown, so nothing of ``render/`` is loaded
before then. This module imports nothing of lagsolve.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

#: (class, "latex" | "markdown" | "html") → the function that writes an instance in that form
_RENDERERS: dict[tuple[type, str], Callable[[Any], str]] = {}

#: registrations still to run (each runs once, before the first lookup)
_PENDING: list[Callable[[], None]] = []


def register(cls: type, kind: str, renderer: Callable[[Any], str]) -> None:
    """Show instances of ``cls`` (and of its subclasses) in the form ``kind`` with ``renderer``."""
    _RENDERERS[(cls, kind)] = renderer


def on_first_use(registration: Callable[[], None]) -> None:
    """Run ``registration`` (which calls :func:`register`) when a result is first shown."""
    _PENDING.append(registration)


def shown(obj: Any, kind: str) -> str | None:
    """``obj`` in the form ``kind``; None (IPython then uses the next form) when no renderer is registered."""
    while _PENDING:
        _PENDING.pop(0)()
    for cls in type(obj).__mro__:
        renderer = _RENDERERS.get((cls, kind))
        if renderer is not None:
            return renderer(obj)
    return None
