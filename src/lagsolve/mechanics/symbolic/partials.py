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
from collections.abc import Callable
from typing import Any

import sympy
from sympy.core.basic import _args_sortkey

#: a system of more coordinates than this is bulk: its velocities, rates and display forms are built in SymEngine and
#: converted once (:func:`total_rate`, :func:`~lagsolve.mechanics.symbolic.bulk.light`); the values are SymPy's, the
#: grouping of a product with a sum may differ from SymPy's own (``2*x_dot*(x + y)`` for ``x_dot*(2*x + 2*y)``), so
#: smaller systems, whose reports are compared byte for byte, keep SymPy's route
BULK_SYSTEM = 6


def total_rate(expr: Any, time: Any, pairs: tuple[tuple[Any, Any], ...]) -> Any | None:
    """d/dt of ``expr`` along the motion, ``∂expr/∂t + Σ ∂expr/∂q q̇`` over ``pairs`` of (q, q̇), differentiated by
    SymEngine and converted once; None where SymEngine cannot take ``expr`` (:func:`_engine`)."""
    if not isinstance(expr, sympy.Basic):
        return sympy.Integer(0)
    engine = _engine(expr)
    if engine is None:
        return None
    form, own = engine
    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        value = form.diff(sympy2symengine(time))
        for q, v in pairs:
            if q.name in own:
                value += form.diff(sympy2symengine(q)) * sympy2symengine(v)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return None
    return engine_converter({**own, **{v.name: v for _, v in pairs}}, remember=True)(value)


def partial(expr: Any, *wrt: Any) -> Any:
    """``sympy.diff(expr, *wrt)`` (each of ``wrt`` a symbol, once per occurrence), remembered."""
    if not isinstance(expr, sympy.Basic):
        return sympy.Integer(0)
    return _partial(expr, tuple(wrt))


@functools.lru_cache(maxsize=4096)
def _partial(expr: Any, wrt: tuple[Any, ...]) -> Any:
    if not wrt:
        return expr
    engine = _engine(expr) if all(w.is_Symbol for w in wrt) else None
    if engine is None:
        return sympy.diff(expr, *wrt) if set(wrt) <= expr.free_symbols else sympy.Integer(0)
    form, own = engine
    if any(own.get(w.name) != w for w in wrt):
        return sympy.Integer(0)  # a symbol expr does not have
    try:
        from symengine.lib.symengine_wrapper import sympy2symengine

        back = from_engine(_engine_diff(form, tuple(sympy2symengine(w) for w in wrt)), own)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError, KeyError):
        return sympy.diff(expr, *wrt)
    return sympy.diff(expr, *wrt) if back is None else back


@functools.lru_cache(maxsize=1024)
def _engine_diff(form: Any, wrt: tuple[Any, ...]) -> Any:
    """SymEngine's derivative of ``form`` by each of ``wrt`` in turn, the first ones remembered (the n² entries of a
    Hessian differentiate the whole expression n times, not n²)."""
    return form.diff(wrt[0]) if len(wrt) == 1 else _engine_diff(form, wrt[:-1]).diff(wrt[-1])


def from_engine(value: Any, own: dict[str, Any]) -> Any | None:
    """A SymEngine result (never text) as a SymPy expression in the symbols ``own`` (by name: SymEngine keeps no
    assumptions, so its symbols come back plain and are put back), or None when it holds a symbol ``own`` lacks or
    an unevaluated derivative (the caller then takes SymPy's own route).

    Built in one walk, each distinct subtree once (the sines and cosines a chain's expressions share), straight
    into ``own``'s symbols: the same tree as SymEngine's ``_sympy_()`` with the symbols replaced afterwards, at a
    fraction of the cost on a large expression."""
    return engine_converter(own)(value)


def engine_converter(own: dict[str, Any], *, remember: bool = False) -> Callable[[Any], Any | None]:
    """:func:`from_engine` for many values in the symbols ``own``, the subtrees they share converted once; with
    ``remember``, each value's SymEngine form is kept for the next trip to SymEngine (a bulk system's pieces: a small
    system's forms are taken from SymPy as they are, so that they stay what they were)."""
    walk = _Back(own)

    def convert(value: Any) -> Any | None:
        try:
            back = walk.convert(value)
        except _Foreign:
            return None
        if remember:
            _remember(back, value, own)
        return back

    return convert


#: SymEngine's functions (a sine, a cosine, ...) → the SymPy function built from one (:meth:`_Back._function`) and
#: its symbols
_FUNCTIONS: dict[Any, tuple[Any, tuple[Any, ...]]] = {}

#: SymPy expressions converted from SymEngine → (that SymEngine form, the symbols by name), so that taking one to
#: SymEngine again (:func:`_engine`) needs no walk of a long SymPy tree; bounded, emptied when full
_SOURCES: dict[Any, tuple[Any, dict[str, Any]]] = {}
_SOURCES_LIMIT = 50_000


def _remember(back: Any, form: Any, own: dict[str, Any]) -> None:
    if isinstance(back, sympy.Basic) and not back.is_Atom:
        if len(_SOURCES) >= _SOURCES_LIMIT:
            _SOURCES.clear()
        _SOURCES.setdefault(back, (form, own))


def to_engine(expr: Any) -> Any:
    """``expr`` as SymEngine's: the form it was converted from when it was (:data:`_SOURCES`), else
    ``sympy2symengine``'s."""
    known = _SOURCES.get(expr) if isinstance(expr, sympy.Basic) else None
    if known is not None:
        return known[0]
    from symengine.lib.symengine_wrapper import sympy2symengine

    return sympy2symengine(expr)


def engine_sum(parts: Any, *, expand: bool = True) -> Any:
    """``Σ c·e`` over ``parts`` of (integer c, SymPy e), added (and with ``expand`` multiplied out) by SymEngine and
    converted once when each e is known to SymEngine (:func:`_engine`), else by SymPy: a bulk system's equations and
    forcing from their pieces. Multiplied out, a sum of plain products is built in SymPy without its flattening
    (:func:`_canonical_mul`), where the products of sums the derivatives give are not."""
    return _engine_sum(tuple((c, e) for c, e in parts if e != 0), expand)


@functools.lru_cache(maxsize=1024)
def _engine_sum(parts: tuple[tuple[int, Any], ...], expand: bool) -> Any:
    """:func:`engine_sum`, remembered (the core a derivation sends first and its display add the same sides)."""
    forms = [_engine(e) if isinstance(e, sympy.Basic) else None for _, e in parts]
    if not parts or any(f is None for f in forms):
        return sympy.Add(*[c * e for c, e in parts])
    import symengine

    own: dict[str, Any] = {}
    total = symengine.Integer(0)
    for (c, _), found in zip(parts, forms, strict=True):
        form, names = found  # type: ignore[misc]
        own.update(names)
        total += c * form
    back = engine_converter(own, remember=True)(total.expand() if expand else total)
    return sympy.Add(*[c * e for c, e in parts]) if back is None else back


class _Foreign(Exception):  # noqa: N818 - a signal inside from_engine, never raised out of it
    """A symbol ``own`` lacks, or a node SymPy takes back only as a derivative or a substitution."""


class _Back:
    """The walk of :func:`from_engine`: SymEngine node → SymPy, remembered per node."""

    def __init__(self, own: dict[str, Any]) -> None:
        self.own = own
        self.memo: dict[Any, Any] = {}

    def convert(self, node: Any) -> Any:
        done = self.memo.get(node)
        if done is None:
            done = self.memo[node] = self._build(node)
        return done

    def _build(self, node: Any) -> Any:
        import symengine

        if isinstance(node, symengine.Symbol) and not isinstance(node, symengine.Dummy):
            found = self.own.get(node.name)
            if found is None:
                raise _Foreign
            return found
        name = type(node).__name__
        kind = _KINDS.get(name)
        if kind is not None:
            if name not in ("Add", "Mul", "Pow"):
                return self._function(node, kind)
            args = [self.convert(a) for a in node.args]
            built = _canonical_mul(args) if name == "Mul" else _canonical_add(args) if name == "Add" else None
            return kind(*args) if built is None else built
        return self._other(node)

    def _function(self, node: Any, kind: Any) -> Any:
        """A sine, cosine, ... of SymEngine's: SymPy evaluates one (its sign rule for ``sin(b - a)`` compares sort
        keys) in about a millisecond, and a chain's n² of them come back in every expression, so each is built once
        in a process (:data:`_FUNCTIONS`), and used again while its symbols are this walk's."""
        known = _FUNCTIONS.get(node)
        if known is not None and all(self.own.get(s.name) is s for s in known[1]):
            return known[0]
        args = [self.convert(a) for a in node.args]
        built = _sine_or_cosine(kind, args[0]) if len(args) == 1 else None
        if built is None:
            built = kind(*args)
        if len(_FUNCTIONS) >= _SOURCES_LIMIT:
            _FUNCTIONS.clear()
        _FUNCTIONS[node] = (built, tuple(built.free_symbols))
        return built

    def _other(self, node: Any) -> Any:
        back = node._sympy_()  # a number, a constant, anything else: SymEngine's own conversion, then checked
        if back.has(sympy.Derivative, sympy.Subs) or {s.name for s in back.free_symbols} - self.own.keys():
            raise _Foreign
        return back.xreplace({s: self.own[s.name] for s in back.free_symbols})


def _sine_or_cosine(kind: Any, arg: Any) -> Any | None:
    """``sin(arg)`` or ``cos(arg)`` of a sum of symbols with coefficients ±1 (``θ₁ − θ₂``), as SymPy evaluates it:
    where nothing else of its rules applies (no number, no π, no imaginary unit), ``sin(−a) = −sin(a)`` and
    ``cos(−a) = cos(a)`` when SymPy takes the minus sign out of ``arg``; None for any other function or argument
    (SymPy evaluates it)."""
    if kind not in (sympy.sin, sympy.cos) or not arg.is_Add or not all(
            t.is_Symbol or (t.is_Mul and len(t.args) == 2 and t.args[0] is sympy.S.NegativeOne and t.args[1].is_Symbol)
            for t in arg.args) or not all(s.is_extended_real for s in arg.free_symbols):
        return None
    if not arg.could_extract_minus_sign():
        return kind(arg, evaluate=False)
    flipped = kind(-arg, evaluate=False)
    return -flipped if kind is sympy.sin else flipped


def _plain(factor: Any) -> Any | None:
    """The base of a factor SymPy's ``Mul`` leaves as it is beside others with other bases (a symbol, a sine or
    cosine, an integer power of one), else None."""
    base = factor.base if factor.is_Pow and factor.exp.is_Integer else factor
    return base if base.is_Symbol or isinstance(base, sympy.sin | sympy.cos) else None


def _canonical_mul(args: list[Any]) -> Any | None:
    """``Mul(*args)`` without SymPy's flattening, where it would only multiply the rational coefficients: plain
    factors of distinct bases (:func:`_plain`; a product of them, as SymPy's ``-sin(a - b)`` for SymEngine's
    ``sin(b - a)``, taken apart), put in SymPy's canonical order behind the coefficient; None otherwise (SymPy builds
    it). SymEngine's products come this way, each base once."""
    coefficient = sympy.Integer(1)
    rest = []
    for arg in args:
        for factor in arg.args if arg.is_Mul else (arg,):
            if factor.is_Rational:
                coefficient *= factor
            else:
                rest.append(factor)
    bases = [_plain(f) for f in rest]
    if coefficient == 0 or not rest or any(b is None for b in bases) or len(set(bases)) != len(bases):
        return None
    rest.sort(key=_args_sortkey)
    if coefficient == 1:
        return rest[0] if len(rest) == 1 else sympy.Mul._from_args(rest)
    return sympy.Mul._from_args([coefficient, *rest])


def _canonical_add(args: list[Any]) -> Any | None:
    """``Add(*args)`` without SymPy's flattening, where it would change nothing: at most one rational term (not 0)
    and terms that are plain factors or products of them with distinct rest (no two to collect), in SymPy's canonical
    order; None otherwise."""
    numbers = [a for a in args if a.is_Rational]
    rest = [a for a in args if not a.is_Rational]
    if len(numbers) > 1 or (numbers and numbers[0] == 0) or len(args) < 2:
        return None
    seen = set()
    for term in rest:
        if not (term.is_Mul and all(f.is_Rational or _plain(f) is not None for f in term.args)) \
                and _plain(term) is None:
            return None
        seen.add(term.as_coeff_Mul()[1])
    if len(seen) != len(rest):
        return None
    rest.sort(key=_args_sortkey)
    return sympy.Add._from_args(numbers + rest)


#: the functions SymEngine differentiates as SymPy does (to functions of the same kind)
_ELEMENTARY = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.exp, sympy.log,
               sympy.sinh, sympy.cosh, sympy.tanh, sympy.asin, sympy.acos, sympy.atan)


#: SymEngine's node types by name → the SymPy class that builds the same node from converted arguments
_KINDS: dict[str, Any] = {"Add": sympy.Add, "Mul": sympy.Mul, "Pow": sympy.Pow,
                          **{f.__name__: f for f in _ELEMENTARY}}


@functools.lru_cache(maxsize=256)
def _engine(expr: Any) -> tuple[Any, dict[str, Any]] | None:
    """``expr`` as a SymEngine expression and its symbols by name, or None where SymEngine is not used: anything
    but sums, products and powers of symbols, rational numbers, π, e and the elementary functions of
    :data:`_ELEMENTARY` (no declared function, no derivative, no float, no ``Abs``), two symbols of one name,
    SymEngine missing."""
    known = _SOURCES.get(expr)
    if known is not None:
        return known
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
