"""`lagsolve.render.model`: the one presentation model (issue 30 items 1-2).

Every field of every section record carries its metadata; the walker prints records for each printer; the
JSON Schema generated from the records describes what the walker writes.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal

import pytest
import sympy

from lagsolve.render.model import Expr, JsonPrinter, NotationPrinter, Rows, json_schema, present, records, shown
from lagsolve.render.notation import Notation
from lagsolve.render.sections import Sections
from lagsolve.render.sections.hamiltonian import NotApplicable, NotDerived

#: the section records (each one's whole tree of records is checked): every section, through Sections, and the
#: records of a Hamiltonian section that is not a formulation (a union's members are not in the tree of types)
MIGRATED = [Sections, NotApplicable, NotDerived]

jsonschema = pytest.importorskip("jsonschema")


@pytest.mark.parametrize("section", MIGRATED, ids=lambda c: c.__name__)
def test_every_field_of_every_record_has_metadata(section: type) -> None:
    """A field declared without ``shown(...)`` would go missing from some format: none exists."""
    missing = [f"{cls.__qualname__}.{f.name}" for cls in records(section)
               for f in dataclasses.fields(cls) if "lagsolve.shown" not in f.metadata]
    assert missing == []


@dataclass(frozen=True)
class _Item:
    name: str = shown(json=None)
    value: Expr = shown(terminal=True)


@dataclass(frozen=True)
class _Inner:
    extra: Expr = shown(json="more")


@dataclass(frozen=True)
class _Record:
    title: str = shown(terminal=True)
    force: Expr = shown(blank_zero=True, terminal=True)
    items: tuple[_Item, ...] = shown(keyed="name", terminal=True)
    matrix: Rows = shown()
    note: str = shown("", optional=True)
    hidden: Expr = shown(sympy.Integer(0), json=None)
    inner: _Inner = shown(factory=lambda: _Inner(sympy.Integer(3)), inline=True)
    table: Mapping[str, Expr] = shown(factory=dict, template=False)


def _example() -> _Record:
    x = sympy.Symbol("x")
    return _Record(title="t", force=sympy.Integer(0), items=(_Item("a", x ** 2), _Item("b", -x)),
                   matrix=sympy.Matrix([[1, x], [x, 2]]), table={"k": x / 2})


def test_the_json_printer_follows_the_metadata() -> None:
    """JSON keys, keyed lists, rows, optional and inline fields, template-only and JSON-only fields."""
    assert present(_example(), JsonPrinter()) == {
        "title": "t", "force": "0", "items": {"a": {"value": "x**2"}, "b": {"value": "-x"}},
        "matrix": [["1", "x"], ["x", "2"]], "more": "3", "table": {"k": "x/2"}}


def test_the_template_printers_follow_the_metadata() -> None:
    """Templates get field names, lists, LaTeX or MathML, "" for a zero ``blank_zero``; the terminal only the fields
    it shows."""
    note = Notation(["x"])
    latex = present(_example(), NotationPrinter("latex", note))
    assert latex == {"title": "t", "force": "", "items": [{"name": "a", "value": "x^{2}"},
                                                          {"name": "b", "value": "- x"}],
                     "matrix": note.latex(sympy.Matrix([[1, sympy.Symbol("x")], [sympy.Symbol("x"), 2]])),
                     "note": "", "hidden": "0", "inner": {"extra": "3"}}
    assert present(_example(), NotationPrinter("text", note)) == {
        "title": "t", "force": "", "items": [{"value": "x²"}, {"value": "-x"}]}
    assert present(_example(), NotationPrinter("mathml", note))["items"][0]["value"].startswith("<msup>")


def test_the_generated_schema_describes_the_json() -> None:
    """What the JSON printer writes is valid against the generated schema, and the schema is closed."""
    schema = json_schema(_Record)
    validator = jsonschema.Draft202012Validator(schema)
    data = present(_example(), JsonPrinter())
    assert list(validator.iter_errors(data)) == []
    assert list(validator.iter_errors({**data, "unknown": 1}))
    assert schema["required"] == ["title", "force", "items", "matrix", "more", "table"]


def test_a_field_without_metadata_is_an_error() -> None:
    """A record field declared without ``shown`` fails loudly instead of silently missing from one format."""

    @dataclass(frozen=True)
    class Bare:
        value: Any = field(default=1)

    with pytest.raises(TypeError, match=r"Bare\.value has no presentation metadata"):
        present(Bare(), JsonPrinter())


@dataclass(frozen=True)
class _Why:
    reason: str = shown(json=None, terminal=True)


def test_a_record_without_json_fields_is_null_there() -> None:
    """A template-only record (why a section is missing) is null in the JSON and in its schema; a union of records
    is described by each one's schema, once each."""
    assert present(_Why("stopped"), JsonPrinter()) is None
    assert present(_Why("stopped"), NotationPrinter("text", Notation(["x"]))) == {"reason": "stopped"}
    assert json_schema(_Why) == {"type": "null"}
    union = json_schema(_Inner | _Why | None)
    assert union == {"anyOf": [json_schema(_Inner), {"type": "null"}]}
    validator = jsonschema.Draft202012Validator(union)
    assert list(validator.iter_errors(None)) == [] and list(validator.iter_errors({"more": "3"})) == []


@dataclass(frozen=True)
class _Pair:
    symbol: Expr = shown(json=None)
    value: Expr = shown()


@dataclass(frozen=True)
class _Flag:
    on: bool = shown()


@dataclass(frozen=True)
class _Part:
    pairs: tuple[_Pair, ...] = shown(keyed="symbol", keyed_value="value")
    one: _Pair | None = shown(keyed="symbol", keyed_value="value")
    flag: _Flag | None = shown(inline=True)
    matrix: Rows = shown(blank_zero=True)


@dataclass(frozen=True)
class _Parts:
    part: _Part | None = shown(absent="why")
    why: str = shown(json=None)


def test_keyed_values_absent_parts_and_optional_inline_records() -> None:
    """``keyed_value`` writes {name: value} (for one record too, null for None); ``absent`` writes {"note": why}
    in place of a None part; an inline None adds no key and its keys are not required; a zero matrix is blank in
    the templates."""
    x, y = sympy.symbols("x y")
    part = _Part((_Pair(x, y ** 2), _Pair(y, x)), None, None, sympy.zeros(2, 2))
    assert present(_Parts(part, ""), JsonPrinter()) == {"part": {
        "pairs": {"x": "y**2", "y": "x"}, "one": None, "matrix": [["0", "0"], ["0", "0"]]}}
    changed = dataclasses.replace(part, one=_Pair(x, y), flag=_Flag(True))
    assert present(changed, JsonPrinter())["one"] == {"x": "y"} and present(changed, JsonPrinter())["on"] is True
    assert present(_Parts(None, "not derived"), JsonPrinter()) == {"part": {"note": "not derived"}}
    latex = present(_Parts(part, ""), NotationPrinter("latex", Notation(["x", "y"])))
    assert latex["part"]["matrix"] == "" and latex["part"]["pairs"][0] == {"symbol": "x", "value": "y^{2}"}
    validator = jsonschema.Draft202012Validator(json_schema(_Parts))
    for value in (_Parts(part, ""), _Parts(changed, ""), _Parts(None, "why")):
        assert list(validator.iter_errors(present(value, JsonPrinter()))) == []
    assert list(validator.iter_errors({"part": {"note": 1}}))


@dataclass(frozen=True)
class _Result:
    name: str = shown(json=None, terminal=True)
    value: Expr = shown(inline=True, terminal=True)


@dataclass(frozen=True)
class _Contract:
    JSON_LAST: ClassVar[tuple[str, ...]] = ("late", "version")

    version: Literal[1] = shown()
    late: str = shown()
    results: tuple[_Result, ...] | None = shown(keyed="name")
    names: tuple[_Result, ...] = shown()
    extra: _Inner | None = shown(optional=True)


def test_a_record_written_as_its_inline_plain_field() -> None:
    """A record whose one JSON field is inline and plain is that value in the JSON (keyed: ``name: value``; None
    stays null); the templates still get its fields; ``JSON_LAST`` keys come last, in their order."""
    x = sympy.Symbol("x")
    record = _Contract(1, "l", (_Result("a", x), _Result("b", 2 * x)), (_Result("c", x),), None)
    data = present(record, JsonPrinter())
    assert data == {"results": {"a": "x", "b": "2*x"}, "names": ["x"], "late": "l", "version": 1}
    assert list(data) == ["results", "names", "late", "version"]
    assert present(dataclasses.replace(record, results=None), JsonPrinter())["results"] is None
    assert present(record, NotationPrinter("latex", Notation(["x"])))["results"] == [
        {"name": "a", "value": "x"}, {"name": "b", "value": "2 x"}]
    schema = json_schema(_Contract)
    assert list(schema["properties"]) == ["results", "names", "extra", "late", "version"]
    assert schema["properties"]["version"] == {"const": 1}
    assert schema["properties"]["results"] == {"anyOf": [
        {"type": "object", "additionalProperties": {"type": "string"}}, {"type": "null"}]}
    assert schema["properties"]["extra"]["type"] == "object"  # optional: a None is left out, never null
    validator = jsonschema.Draft202012Validator(schema)
    assert list(validator.iter_errors(data)) == []


def test_an_inline_plain_field_must_be_alone() -> None:
    """An inline plain field beside other JSON fields has no JSON shape: an error, not a silent loss."""

    @dataclass(frozen=True)
    class Two:
        name: str = shown(inline=True)
        other: str = shown()

    with pytest.raises(TypeError, match="one JSON field"):
        present(Two("a", "b"), JsonPrinter())
    with pytest.raises(TypeError, match="one JSON field"):
        json_schema(Two)
