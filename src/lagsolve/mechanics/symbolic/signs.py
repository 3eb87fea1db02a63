"""Signs of symbolic expressions, and the conditions that decide them.

Parameters are positive and coordinates real, so the sign of an expression such as
``m*R*(g - R*Omega**2)`` is that of ``g - R*Omega**2``: :func:`sign_core` drops the
factors of known sign and keeps the rest, which becomes a condition
(``g > R*Omega**2``). Even powers count as positive (a generic point, where they are
not zero); odd powers keep their base.
"""

from __future__ import annotations

from typing import Any

import sympy


def sign_core(expr: Any) -> tuple[int | None, Any]:
    """``(sign, core)``: the sign of ``expr`` when known (+1 or -1, core 1), else ``(None, core)``
    where ``expr`` has the sign of ``core`` (factors of known sign removed).

    >>> import sympy
    >>> m, g, R, W = sympy.symbols("m g R Omega", positive=True)
    >>> sign_core(m*R*(g - R*W**2))
    (None, -Omega**2*R + g)
    >>> sign_core(-3*g/R)
    (-1, 1)
    """
    if expr == 0:
        return None, sympy.Integer(0)
    try:
        factored = sympy.factor(expr)
    except (sympy.PolynomialError, ValueError, TypeError):
        factored = expr
    sign = 1
    core = sympy.Integer(1)
    for factor in sympy.Mul.make_args(factored):
        known = _real_valued(factor)
        if known.is_positive:
            continue
        if known.is_negative:
            sign = -sign
            continue
        base, exp = factor.as_base_exp()
        if exp.is_Integer and int(exp) % 2 == 0:
            continue
        if exp.is_Rational and (exp.p % 2 == 0 or exp.q % 2 == 0):
            continue  # an even root of a square, or an even root: non-negative where it is real
        if base.is_nonnegative and exp.is_real:
            continue  # |p|**(2/3), sqrt(x**2 + 1): positive at a generic point
        if exp.is_Integer or (exp.is_Rational and exp.p % 2 == 1 and exp.q % 2 == 1):
            factor = base
            if base.is_positive:
                continue
            if base.is_negative:
                sign = -sign
                continue
        core *= factor
    if core == 1:
        return sign, core
    core = sympy.expand(sign * core)
    if core.is_positive:
        return 1, sympy.Integer(1)
    if core.is_negative:
        return -1, sympy.Integer(1)
    return None, core


def _real_valued(expr: Any) -> Any:
    """``expr`` with each function of real arguments (``tan(alpha)``, ``f(x)``, a derivative) a real symbol: where
    it is defined it is real, so ``tan(alpha)**2 + 1`` counts as positive."""
    if expr.is_positive is not None or not expr.has(sympy.Function, sympy.Derivative):
        return expr
    atoms = sorted(expr.atoms(sympy.Function, sympy.Derivative), key=sympy.default_sort_key)
    reals = {a: sympy.Dummy(real=True) for a in atoms
             if all(arg.is_real for arg in a.args if not isinstance(arg, sympy.Tuple))}
    return expr.xreplace(reals)


def relation(core: Any, strict: bool = True) -> Any:
    """``core > 0`` (or ``>= 0``) written with the negative terms moved right: ``g - R*W**2 > 0``
    becomes ``g > R*W**2``."""
    terms = sympy.Add.make_args(sympy.expand(core))
    left = [t for t in terms if not t.could_extract_minus_sign()]
    right = [-t for t in terms if t.could_extract_minus_sign()]
    lhs = sympy.Add(*left) if left else sympy.Integer(0)
    rhs = sympy.Add(*right) if right else sympy.Integer(0)
    return sympy.StrictGreaterThan(lhs, rhs, evaluate=False) if strict else sympy.GreaterThan(lhs, rhs, evaluate=False)

