"""Names lagsolve makes up: the one place that spells the momentum conjugate to a coordinate, and the
momentum of a translation or rotation of the whole system."""

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


def symmetry_name(kind: str, axis: str, taken: Any = ()) -> str:
    """The momentum of a translation (``P_<axis>``) or rotation (``L_<axis>``) of the whole system; when the
    problem already uses that name, ``momentum_<axis>`` or ``angular_momentum_<axis>`` (then with ``_total``).

    >>> symmetry_name("rotation", "z")
    'L_z'
    >>> symmetry_name("translation", "x", {"P_x"})
    'momentum_x'
    """
    short, long = ("P", "momentum") if kind == "translation" else ("L", "angular_momentum")
    for name in (f"{short}_{axis}", f"{long}_{axis}", f"{long}_{axis}_total"):
        if name not in taken:
            return name
    raise ValueError(f"no free name for the {kind} along {axis}")
