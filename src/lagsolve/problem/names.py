"""Names lagsolve makes up: the one place that spells the momentum conjugate to a coordinate."""

from __future__ import annotations

from typing import Any

import sympy


def momentum_name(q: Any) -> str:
    """``p_<q>``, the name of the momentum conjugate to coordinate ``q`` (a symbol or a name).

    >>> momentum_name("theta")
    'p_theta'
    """
    return f"p_{q if isinstance(q, str) else q.name}"


def momentum_symbol(q: Any) -> sympy.Symbol:
    """The real symbol :func:`momentum_name` names."""
    return sympy.Symbol(momentum_name(q), real=True)
