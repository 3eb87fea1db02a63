r"""Partial derivatives of an expression (the Lagrangian, mostly), taken once.

Several stages differentiate the same :math:`L`: the conserved quantities (:math:`\partial L/\partial q_k`
of a cyclic coordinate, :math:`\partial L/\partial t`), the energy function (:math:`\partial L/\partial\dot q_i`),
the Hamiltonian (:math:`\partial^2 L/\partial\dot q_i\partial\dot q_j`). SymPy's ``diff`` costs milliseconds
a time on a pendulum's :math:`L`; :func:`partial` takes the derivative with SymEngine where the expression
allows it (no declared function, no ``Derivative``), converts it back with the expression's own symbols
(their assumptions kept), and remembers it. The value is the same as ``sympy.diff``'s; the form may differ
in SymPy's automatic ordering, so it is for expressions that are tested, simplified or compiled afterwards.
"""

from __future__ import annotations

import functools
from typing import Any

import sympy


def partial(expr: Any, *wrt: Any) -> Any:
    """``sympy.diff(expr, *wrt)`` (each of ``wrt`` a symbol, once per occurrence), remembered."""
    if not isinstance(expr, sympy.Basic):
        return sympy.Integer(0)
    return _partial(expr, tuple(wrt))


@functools.lru_cache(maxsize=4096)
def _partial(expr: Any, wrt: tuple[Any, ...]) -> Any:
    if not wrt:
        return expr
    if not set(wrt) <= expr.free_symbols:
        return sympy.Integer(0)
    engine = _engine(expr) if all(w.is_Symbol for w in wrt) else None
    if engine is None:
        return sympy.diff(expr, *wrt)
    form, own = engine
    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        value = form
        for symbol in wrt:
            value = value.diff(sympy2symengine(symbol))
        back = from_engine(value, own)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return sympy.diff(expr, *wrt)
    return sympy.diff(expr, *wrt) if back is None else back


def from_engine(value: Any, own: dict[str, Any]) -> Any | None:
    """A SymEngine result (never text) as a SymPy expression in the symbols ``own`` (by name: SymEngine keeps no
    assumptions, so its symbols come back plain and are put back), or None when it holds a symbol ``own`` lacks or
    an unevaluated derivative (the caller then takes SymPy's own route)."""
    back = value._sympy_()
    if back.has(sympy.Derivative, sympy.Subs) or {s.name for s in back.free_symbols} - own.keys():
        return None
    return back.xreplace({s: own[s.name] for s in back.free_symbols})


#: the functions SymEngine differentiates as SymPy does (to functions of the same kind)
_ELEMENTARY = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.exp, sympy.log,
               sympy.sinh, sympy.cosh, sympy.tanh, sympy.asin, sympy.acos, sympy.atan)


@functools.lru_cache(maxsize=256)
def _engine(expr: Any) -> tuple[Any, dict[str, Any]] | None:
    """``expr`` as a SymEngine expression and its symbols by name, or None where SymEngine is not used: anything
    but sums, products and powers of symbols, rational numbers, π, e and the elementary functions of
    :data:`_ELEMENTARY` (no declared function, no derivative, no float, no ``Abs``), two symbols of one name,
    SymEngine missing."""
    for node in sympy.preorder_traversal(expr):
        if node.is_Atom:
            if not (node.is_Symbol or node.is_Rational or node in (sympy.pi, sympy.E)):
                return None
        elif not (node.is_Add or node.is_Mul or node.is_Pow or isinstance(node, _ELEMENTARY)):
            return None
    own = {s.name: s for s in expr.free_symbols}
    if len(own) != len(expr.free_symbols):
        return None
    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        return sympy2symengine(expr), own
    except (ImportError, RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return None
