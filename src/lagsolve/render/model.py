"""The presentation model: section records whose fields say how every format shows them, and the one walker.

A section record (:mod:`lagsolve.render.sections`) is a frozen dataclass, and every field is declared with
:func:`shown`. Its metadata (:class:`Shown`) says under which JSON key the field is written (or that the JSON
leaves it out), whether the terminal shows it, what unit it carries, and, for a whole section, which template
partial lays it out. :func:`present` walks a record with a :class:`Printer` (LaTeX, MathML, text or JSON) and
returns plain data: the templates' context, the terminal's, or the JSON result. :func:`json_schema` describes
the JSON that :func:`present` writes, from the same declarations, so the output schema cannot drift from the
output. A field declared without :func:`shown` is an error of :func:`present`, never a value silently missing
from one format. A record none of whose fields is in the JSON (a template-only record, such as why a section is
missing) is written as null there.

Types: :data:`Expr` is an expression (printed by the printer; a string in the JSON), :data:`Rows` a matrix (one
expression in the templates, a list of rows in the JSON). A value with a ``present(printer)`` method prints
itself (a Pfaffian form, a mode shape written as a row), which is how a format-specific layout stays out of
the templates and the walker.

Two shapes of the JSON come from the declarations too: a record whose one JSON field is ``inline`` and holds a
plain value is written as that value (a coordinate as its name; with ``keyed``, a list of results as an object
name → value), and a record class may set ``JSON_LAST`` (a tuple of JSON keys) for a contract whose key order
predates the fields' display order: those keys are written last, in that order.
"""

from __future__ import annotations

import dataclasses
import enum
import types
import typing
from collections.abc import Callable, Mapping
from dataclasses import MISSING, dataclass
from typing import Annotated, Any, Literal, Protocol, runtime_checkable

#: a SymPy expression as the derivation holds it: printed by the printer, a string in the JSON
Expr = Annotated[Any, "expression"]
#: a SymPy matrix: one printed expression in the templates, a list of rows of strings in the JSON
Rows = Annotated[Any, "rows"]

#: the key of the dataclass field metadata that holds a field's :class:`Shown`
KEY = "lagsolve.shown"


@dataclass(frozen=True)
class Shown:
    """How a field of a section record is shown.

    ``json``: its key in the JSON ("" for the field's own name; None: not in the JSON). ``template``: False
    keeps it out of the templates' context (a value only the JSON contract writes). ``terminal``: the text
    printer (the terminal summary) shows it. ``optional``: the JSON leaves the key out when the value is empty
    (None, False, "", an empty list). ``inline``: the JSON merges the value's keys into the enclosing object
    (none for a None value). ``keyed``: the JSON writes a list of records (or one record) as an object keyed by
    this field of each; with ``keyed_value``, each key's value is only that field of the record (``{name:
    value}``). ``absent``: the JSON writes ``{"note": <that sibling field>}`` in place of a None value (a part
    not derived, with the reason why). ``blank_zero``: the templates get "" for an expression (or a matrix)
    equal to 0 (they test it as false). ``unit``: what the value measures (for the schema's description).
    ``partial``: the template partial that lays out a section. ``doc``: the schema's description.
    """

    json: str | None = ""
    template: bool = True
    terminal: bool = False
    optional: bool = False
    inline: bool = False
    keyed: str | None = None
    keyed_value: str | None = None
    absent: str | None = None
    blank_zero: bool = False
    unit: str | None = None
    partial: str | None = None
    doc: str = ""


def shown(default: Any = MISSING, *, factory: Callable[[], Any] | None = None, **options: Any) -> Any:
    """A dataclass field with its :class:`Shown` metadata (``default`` or ``factory`` as for ``field``)."""
    metadata = {KEY: Shown(**options)}
    if factory is not None:
        return dataclasses.field(default_factory=factory, metadata=metadata)
    return dataclasses.field(default=default, metadata=metadata)


def metadata(field: dataclasses.Field[Any], owner: type) -> Shown:
    """The :class:`Shown` of ``field``; a field declared without :func:`shown` is an error."""
    meta = field.metadata.get(KEY)
    if meta is None:
        raise TypeError(f"{owner.__qualname__}.{field.name} has no presentation metadata: declare it with "
                        "lagsolve.render.model.shown(...)")
    return typing.cast(Shown, meta)


# -- printers -------------------------------------------------------------------------------------


class Printer(Protocol):
    """How a format prints: ``kind`` ("latex", "mathml", "text" or "json") and one expression as a string."""

    @property
    def kind(self) -> str: ...

    def expr(self, value: Any) -> str: ...


@runtime_checkable
class SelfPresenting(Protocol):
    """A value that prints itself with a printer (a layout one format needs, such as a Pfaffian form)."""

    def present(self, printer: Printer) -> Any: ...


@dataclass(frozen=True)
class NotationPrinter:
    """A template or terminal printer over one problem's :class:`~lagsolve.render.notation.Notation`."""

    kind: str
    notation: Any

    def expr(self, value: Any) -> str:
        print_ = {"latex": self.notation.latex, "mathml": self.notation.mathml, "text": self.notation.text}
        return typing.cast(str, print_[self.kind](value))


@dataclass(frozen=True)
class JsonPrinter:
    """The JSON result's printer: SymPy's ``str()`` syntax with the input's names."""

    kind: str = "json"

    def expr(self, value: Any) -> str:
        from lagsolve.render.notation import to_json

        return to_json(value)


def printer(kind: str, notation: Any = None) -> Printer:
    """The printer of ``kind`` ("latex", "mathml", "text" or "json"; the first three need a ``notation``)."""
    if kind == "json":
        return JsonPrinter()
    if kind not in ("latex", "mathml", "text"):
        raise ValueError(f"unknown printer {kind!r}; use latex, mathml, text or json")
    return NotationPrinter(kind, notation)


# -- the walker -----------------------------------------------------------------------------------


def _empty(value: Any) -> bool:
    return value is None or value is False or (isinstance(value, str | tuple | list | dict) and len(value) == 0)


def _zero(value: Any) -> bool:
    if getattr(value, "is_zero_matrix", None) is True:
        return True
    return getattr(value, "is_zero", None) is True or (isinstance(value, int | float) and value == 0)


_PRESENTS_ITSELF: dict[type, bool] = {}


def _presents_itself(cls: type) -> bool:
    """Instances of ``cls`` are :class:`SelfPresenting` (what ``isinstance`` with the protocol says, decided once per
    class: the protocol's own check inspects the class at every call, a fifth of rendering a small report)."""
    known = _PRESENTS_ITSELF.get(cls)
    if known is None:
        known = _PRESENTS_ITSELF[cls] = issubclass(cls, SelfPresenting)
    return known


def present(value: Any, printer: Printer, *, kind: str = "expression") -> Any:
    """``value`` as plain data for ``printer``: records as dicts (keyed by field name, or by their JSON keys for
    the JSON printer), tuples as lists, expressions printed, plain values kept.

    ``kind`` is how a bare SymPy value is printed: "expression" (one string) or "rows" (a list of rows of
    strings in the JSON, one string elsewhere).
    """
    if not isinstance(value, type) and _presents_itself(type(value)):
        return value.present(printer)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return _record(value, printer)
    if isinstance(value, enum.Enum):
        return value.value
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, Mapping):
        return {str(k): present(v, printer, kind=kind) for k, v in value.items()}
    if isinstance(value, tuple | list):
        return [present(v, printer, kind=kind) for v in value]
    if kind == "rows" and printer.kind == "json":
        return [[printer.expr(x) for x in row] for row in value.tolist()]
    return printer.expr(value)


def _record(record: Any, printer: Printer) -> Any:
    if printer.kind == "json" and not _in_json(type(record)):
        return None
    out: dict[str, Any] = {}
    whole: list[Any] = []  # the value of an inline plain field: the record's whole JSON
    hints = _hints(type(record))
    for field in dataclasses.fields(record):
        meta = metadata(field, type(record))
        key = _key(field.name, meta, printer)
        if key is None:
            continue
        value = getattr(record, field.name)
        if printer.kind == "json" and meta.optional and _empty(value):
            continue
        hint = hints.get(field.name)
        if printer.kind == "json" and value is None and meta.absent is not None:
            shown_value: Any = {"note": present(getattr(record, meta.absent), printer)}
        else:
            shown_value = _field_value(value, meta, _kind(hint), printer)
        if meta.inline and printer.kind == "json" and not _is_record(hint):
            whole.append(shown_value)
        elif meta.inline and printer.kind == "json":
            out.update(shown_value or {})
        else:
            out[key] = shown_value
    if whole:
        if out or len(whole) > 1:
            raise TypeError(f"{type(record).__qualname__}: an inline plain field must be its record's one JSON field")
        return whole[0]
    return _last(out, type(record)) if printer.kind == "json" else out


def _field_value(value: Any, meta: Shown, kind: str, printer: Printer) -> Any:
    """One field's value as ``printer`` shows it (blank for a zero ``blank_zero``, keyed for the JSON)."""
    if meta.blank_zero and printer.kind != "json" and _zero(value):
        return ""
    if meta.keyed is not None and printer.kind == "json" and value is not None:
        return _keyed(value, meta, printer, kind)
    return present(value, printer, kind=kind)


def _last(out: dict[str, Any], cls: type) -> dict[str, Any]:
    """``out`` with the keys of ``cls.JSON_LAST`` moved to the end, in that order."""
    last = [key for key in getattr(cls, "JSON_LAST", ()) if key in out]
    if not last:
        return out
    return {**{k: v for k, v in out.items() if k not in last}, **{k: out[k] for k in last}}


def _in_json(cls: type) -> bool:
    """Whether the JSON writes any field of record class ``cls`` (else it writes the record as null)."""
    return any(metadata(f, cls).json is not None for f in dataclasses.fields(cls))


def _keyed(value: Any, meta: Shown, printer: Printer, kind: str) -> dict[str, Any]:
    """A list of records (or one record) as an object keyed by the field ``meta.keyed`` of each; the values are
    the records, or only their field ``meta.keyed_value``."""
    items = value if isinstance(value, tuple | list) else (value,)
    if meta.keyed_value is None:
        return {str(getattr(item, str(meta.keyed))): present(item, printer, kind=kind) for item in items}
    out = {}
    for item in items:
        inner = _kind(_hints(type(item)).get(meta.keyed_value))
        out[str(getattr(item, str(meta.keyed)))] = present(getattr(item, meta.keyed_value), printer, kind=inner)
    return out


def _key(name: str, meta: Shown, printer: Printer) -> str | None:
    if printer.kind == "json":
        return None if meta.json is None else (meta.json or name)
    if printer.kind == "text" and not meta.terminal:
        return None
    return name if meta.template else None


# -- types and the schema -------------------------------------------------------------------------


_HINTS: dict[type, dict[str, Any]] = {}


def _hints(cls: type) -> dict[str, Any]:
    """``cls``'s field types with their ``Annotated`` marks (cached: records are few and fixed)."""
    if cls not in _HINTS:
        _HINTS[cls] = typing.get_type_hints(cls, include_extras=True)
    return _HINTS[cls]


def _kind(hint: Any) -> str:
    """"rows" for a :data:`Rows` (or a container of them), else "expression"."""
    if hint is None:
        return "expression"
    if typing.get_origin(hint) is Annotated:
        return "rows" if "rows" in typing.get_args(hint)[1:] else "expression"
    return next((k for k in map(_kind, typing.get_args(hint)) if k == "rows"), "expression")


def json_schema(cls: Any, *, root: bool = False) -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of what :func:`present` writes for a record of class ``cls`` with the JSON
    printer: an object with the fields' JSON keys, closed; a key is required unless its field is ``optional``
    (then its value is never null: a None is left out); null for a record none of whose fields is in the JSON. A
    record written as its one inline plain field has that field's schema. ``cls`` may also be a type such as a
    union of records (``A | B | None``: any of their schemas)."""
    if not (isinstance(cls, type) and dataclasses.is_dataclass(cls)):
        return _schema_of(cls)
    if not _in_json(cls):
        return {"type": "null"}
    properties: dict[str, Any] = {}
    required: list[str] = []
    hints = _hints(cls)
    for field in dataclasses.fields(cls):
        meta = metadata(field, cls)
        if meta.json is None:
            continue
        hint = _without_none(hints[field.name]) if meta.optional else hints[field.name]
        if meta.inline and not _is_record(hint):
            if sum(metadata(f, cls).json is not None for f in dataclasses.fields(cls)) > 1:
                raise TypeError(f"{cls.__qualname__}: an inline plain field must be its record's one JSON field")
            return _described(_schema_of(hint, meta), meta)
        if meta.inline:
            inner = json_schema(_record_class(hint))
            properties.update(inner.get("properties", {}))
            required += [] if _nullable(hint) else inner.get("required", [])
            continue
        key = meta.json or field.name
        properties[key] = _described(_schema_of(hint, meta) if meta.absent is None else {"anyOf": [
            _schema_of(_without_none(hint), meta), {"type": "object", "properties": {"note": {"type": "string"}},
                                                "required": ["note"], "additionalProperties": False}]}, meta)
        if not meta.optional:
            required.append(key)
    last = [key for key in getattr(cls, "JSON_LAST", ()) if key in properties]
    properties = {**{k: v for k, v in properties.items() if k not in last}, **{k: properties[k] for k in last}}
    out: dict[str, Any] = {"type": "object", "properties": properties, "additionalProperties": False}
    if required:
        out["required"] = required
    return out


def _without_none(hint: Any) -> Any:
    """``hint`` without None in its union (an optional field's None is never written)."""
    if typing.get_origin(hint) not in (types.UnionType, typing.Union):
        return hint
    args = [a for a in typing.get_args(hint) if a is not type(None)]
    return args[0] if len(args) == 1 else typing.Union[tuple(args)]  # noqa: UP007 - built from a tuple


def _described(schema: dict[str, Any], meta: Shown) -> dict[str, Any]:
    return {**schema, "description": _description(meta)} if meta.doc or meta.unit else schema


def _description(meta: Shown) -> str:
    """The schema's description of a field: its ``doc``, and the unit of its value (the ``units`` key of a result
    gives the unit when the problem declares units)."""
    if not meta.unit:
        return meta.doc
    unit = f"in the unit of {meta.unit}"
    return f"{meta.doc} ({unit})" if meta.doc else unit[0].upper() + unit[1:]


def _nullable(hint: Any) -> bool:
    """Whether ``hint`` admits None (``X | None``)."""
    return type(None) in typing.get_args(hint)


def _is_record(hint: Any) -> bool:
    """Whether ``hint`` is a record class (or a union with one)."""
    return any(isinstance(c, type) and dataclasses.is_dataclass(c) and not issubclass(c, SelfPresenting)
               for c in (hint, *typing.get_args(hint)))


def _record_class(hint: Any) -> type:
    for candidate in (hint, *typing.get_args(hint)):
        if isinstance(candidate, type) and dataclasses.is_dataclass(candidate):
            return candidate
    raise TypeError(f"{hint!r} is not a record")


def _schema_of(hint: Any, meta: Shown | None = None) -> dict[str, Any]:
    """The schema of a value of type ``hint`` as the JSON printer writes it."""
    origin, args = typing.get_origin(hint), typing.get_args(hint)
    if origin is Annotated:
        marks = args[1:]
        if "rows" in marks:
            return {"type": "array", "items": {"type": "array", "items": {"type": "string"}}}
        if "expression" in marks:
            return {"type": "string"}
        return _schema_of(args[0], meta)
    if origin in (types.UnionType, typing.Union):
        options: list[dict[str, Any]] = []
        for option in (_schema_of(a, meta) for a in args):
            options += [] if option in options else [option]
        return options[0] if len(options) == 1 else {"anyOf": options}
    if origin is Literal:
        return {"const": args[0]} if len(args) == 1 else {"enum": list(args)}
    if meta is not None and meta.keyed is not None and (origin in (tuple, list) or dataclasses.is_dataclass(hint)):
        return _keyed_schema(_record_class(args[0] if args else hint), meta)
    if origin in (tuple, list):
        if origin is tuple and not (len(args) == 2 and args[1] is Ellipsis):
            return {"type": "array", "prefixItems": [_schema_of(a) for a in args], "items": False}
        return {"type": "array", "items": _schema_of(args[0])}
    if origin in (dict, Mapping) or hint in (dict, Mapping):
        value = _schema_of(args[1]) if args else {}
        return {"type": "object", "additionalProperties": value}
    return _scalar_schema(hint)


def _keyed_schema(item: type, meta: Shown) -> dict[str, Any]:
    """An object keyed by a field of each record: the records, or only their field ``meta.keyed_value``."""
    value = json_schema(item) if meta.keyed_value is None else _schema_of(_hints(item)[meta.keyed_value])
    return {"type": "object", "additionalProperties": value}


def _scalar_schema(hint: Any) -> dict[str, Any]:
    if hint is type(None):
        return {"type": "null"}
    if isinstance(hint, type) and issubclass(hint, enum.Enum):
        return {"enum": [m.value for m in hint]}
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        if issubclass(hint, SelfPresenting):
            return typing.cast(dict[str, Any], getattr(hint, "SCHEMA", {}))
        return json_schema(hint)
    simple = {bool: "boolean", int: "integer", float: "number", str: "string"}
    if hint in simple:
        return {"type": simple[hint]}
    return {}  # Any: not described further


def records(cls: type) -> list[type]:
    """``cls`` and every record class reachable from its fields' types (for the test that every field of every
    record carries its metadata)."""
    seen: list[type] = []

    def visit(hint: Any) -> None:
        if isinstance(hint, type) and dataclasses.is_dataclass(hint):
            if hint in seen or issubclass(hint, SelfPresenting):
                return
            seen.append(hint)
            for value in _hints(hint).values():
                visit(value)
            return
        for arg in typing.get_args(hint):
            visit(arg)

    visit(cls)
    return seen
