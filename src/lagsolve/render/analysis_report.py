"""The contract's analysis keys: :func:`contract_json` prints the format's ``reduced``, ``conserved`` and
``effective_potential`` (the derivation's contract forms). The ``analysis`` key, the analysis templates and
terminal lines are :func:`lagsolve.render.model.present` of
:class:`~lagsolve.render.sections.analysis.AnalysisSection`. Nothing here simplifies.
"""

from __future__ import annotations

from typing import Any

from lagsolve.render.notation import to_json


def _json(value: Any) -> Any:
    """Contract values: expressions as strings, containers walked, plain values kept."""
    if isinstance(value, dict):
        return {k: _json(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json(v) for v in value]
    if value is None or isinstance(value, bool | int | float | str):
        return value
    return to_json(value)


def contract_json(contract: tuple[tuple[str, Any], ...]) -> dict[str, Any]:
    """``reduced``, ``conserved``, ``effective_potential`` of format section 2 (the derivation's contract forms,
    :attr:`~lagsolve.render.sections.core.CoreSections.contract`), as JSON values."""
    return {key: _json(value) for key, value in contract}
