"""Reading a problem file's YAML: 1.2 semantics, line numbers, and refusal of hostile input."""

from __future__ import annotations

import time

import pytest

from lagsolve.errors import Issue, LagsolveError, SpecError
from lagsolve.problem import yamlread
from lagsolve.problem.yamlread import Document, dotted, read_document

SOURCE = "problem.yaml"

#: A refusal must come back at once: this is a guard against hangs, not a benchmark.
FAST = 2.0  # CPU seconds: the issue's bound for any refusal; a hang would take far longer


def read(text: str | bytes) -> Document:
    raw = text.encode("utf-8") if isinstance(text, str) else text
    return read_document(raw, SOURCE)


def refusal(raw: bytes) -> Issue:
    """Read ``raw``, expecting a SpecError with one issue within FAST seconds."""
    start = time.process_time()
    with pytest.raises(SpecError) as caught:
        read_document(raw, SOURCE)
    cpu = time.process_time() - start
    assert cpu < FAST, f"refusal took {cpu:.2f} s"
    assert len(caught.value.issues) == 1
    return caught.value.issues[0]


# ------------------------------------------------------------------------------------------
# YAML 1.2 semantics


def test_exponent_numbers_are_floats() -> None:
    """`1e-8` is a float in YAML 1.2 (YAML 1.1 and PyYAML read it as a string)."""
    data = read("tol: 1e-8\nbig: 2.5E+3\n").data
    assert isinstance(data["tol"], float) and data["tol"] == 1e-8
    assert data["big"] == 2500.0


def test_on_yes_no_are_strings() -> None:
    """The key `on` and the values `yes`, `no`, `off` are text, not booleans."""
    data = read("on: bead\nanswer: yes\nother: no\nswitch: off\n").data
    assert data == {"on": "bead", "answer": "yes", "other": "no", "switch": "off"}


def test_explicit_yaml_1_2_directive() -> None:
    """A `%YAML 1.2` directive is accepted and changes nothing."""
    assert read("%YAML 1.2\n---\non: yes\n").data == {"on": "yes"}


def test_core_schema_scalars() -> None:
    """true/false, null, hex, octal and decimal integers follow the YAML 1.2 core schema."""
    data = read("a: true\nb: False\nc: ~\nd: null\ne: 0x1F\nf: 0o17\ng: 017\nh: -3\ni: .5\n").data
    assert data == {"a": True, "b": False, "c": None, "d": None, "e": 31, "f": 15, "g": 17,
                    "h": -3, "i": 0.5}
    assert isinstance(data["g"], int)


def test_keys_are_text() -> None:
    """Scalar keys that look like numbers, booleans or null are kept as their text."""
    assert read("1: a\ntrue: b\n~: c\n").data == {"1": "a", "true": "b", "~": "c"}


def test_quoted_and_block_text() -> None:
    """Quoted strings keep their content and block scalars their line breaks."""
    data = read('name: "1e-8"\ndescription: |\n  first\n  second\n').data
    assert data == {"name": "1e-8", "description": "first\nsecond\n"}


def test_byte_order_mark_and_crlf() -> None:
    """A UTF-8 byte order mark and Windows line ends are accepted."""
    doc = read(b"\xef\xbb\xbfname: a\r\ncoordinates: [x]\r\n")
    assert doc.data == {"name": "a", "coordinates": ["x"]}
    assert doc.lines[("coordinates",)] == 2


def test_unicode_text_is_kept() -> None:
    """Ordinary non-ASCII text (Greek letters, accents) is allowed in values."""
    assert read("description: Pendel mit Länge ℓ und Winkel θ\n").data["description"] == (
        "Pendel mit Länge ℓ und Winkel θ")


# ------------------------------------------------------------------------------------------
# line numbers

LINES_TEXT = """\
name: Bead
# a comment line
parameters:
  m: mass
coordinates: [x, y]
particles:
  bead:
    mass: m
    position:
      - x
      - y
empty:
"""


def test_lines_of_mappings_and_lists() -> None:
    """Document.lines maps each field path, list indices included, to its 1-based line."""
    lines = read(LINES_TEXT).lines
    assert lines[()] == 1
    assert lines[("name",)] == 1
    assert lines[("parameters", "m")] == 4
    assert lines[("coordinates",)] == 5
    assert lines[("coordinates", 1)] == 5
    assert lines[("particles", "bead", "mass")] == 8
    assert lines[("particles", "bead", "position", 0)] == 10
    assert lines[("particles", "bead", "position", 1)] == 11


def test_line_of_an_empty_value_is_its_key_line() -> None:
    """An empty value (`empty:` at the end) is placed on its key's line, not the next one."""
    doc = read(LINES_TEXT)
    assert doc.data["empty"] is None
    assert doc.lines[("empty",)] == 12


def test_dotted_paths() -> None:
    """Field paths print with dots between keys and [i] for list indices."""
    assert dotted(("constraints", "wire", "on")) == "constraints.wire.on"
    assert dotted(("particles", "bead", "position", 2)) == "particles.bead.position[2]"
    assert dotted(("forces", 0, "value")) == "forces[0].value"
    assert dotted(()) == ""


# ------------------------------------------------------------------------------------------
# refusals: (raw bytes, line, field path, message fragment)

BILLION_LAUGHS = b"""\
a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]
b: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]
c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]
d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]
e: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]
f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]
g: &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]
h: &h [*g,*g,*g,*g,*g,*g,*g,*g,*g]
i: &i [*h,*h,*h,*h,*h,*h,*h,*h,*h]
"""

REFUSALS = [
    ("syntax-error", b"name: x\ncoordinates: [x\nfoo: 1\n", 3, "",
     "YAML syntax error: expected ',' or ']', but got ':'"),
    ("syntax-error-colon", b"name: x\n  bad: : :\n", 2, "",
     "YAML syntax error: mapping values are not allowed here"),
    ("tab-indentation", b"name: x\n\tcoordinates: [x]\n", 2, "",
     "found character '\\t' that cannot start any token"),
    ("unclosed-quote", b'name: "abc\ncoordinates: [x]\n', 3, "",
     "YAML syntax error: found unexpected end of stream"),
    ("duplicate-key", b"name: a\ncoordinates: [x]\nname: b\n", 3, "name",
     "duplicate key 'name' (first given on line 1); give each key once"),
    ("duplicate-block-key", b"name: a\nparticles:\n  p: 1\nparticles:\n  q: 2\n", 4, "particles",
     "duplicate key 'particles' (first given on line 2)"),
    ("duplicate-nested-key", b"parameters:\n  m: 1\n  g: 2\n  m: 3\n", 4, "parameters.m",
     "duplicate key 'm' (first given on line 2)"),
    ("python-object-apply", b"name: !!python/object/apply:os.system ['echo hi']\n", 1, "name",
     "YAML tag '!!python/object/apply:os.system' is not allowed"),
    ("python-object-top", b"!!python/object/apply:os.system ['echo hi']\n", 1, "",
     "YAML tag '!!python/object/apply:os.system' is not allowed"),
    ("python-name-tag", b"a: 1\nb: !!python/name:os.system ''\n", 2, "b",
     "YAML tag '!!python/name:os.system' is not allowed"),
    ("verbatim-tag", b"a: !<tag:yaml.org,2002:python/object> 1\n", 1, "a",
     "YAML tag '!!python/object' is not allowed"),
    ("local-tag", b"a: !foo bar\n", 1, "a", "YAML tag '!foo' is not allowed"),
    ("set-tag", b"a: !!set {x, y}\n", 1, "a", "YAML tag '!!set' is not allowed"),
    ("binary-tag", b"a: !!binary aGVsbG8=\n", 1, "a", "YAML tag '!!binary' is not allowed"),
    ("implicit-timestamp", b"a: 2001-12-14\n", 1, "a", "YAML tag '!!timestamp' is not allowed"),
    ("anchor-alias", b"a: &x 1\nb: *x\n", 1, "a",
     "anchors and aliases (&name, *name) are not allowed in problem files"),
    ("billion-laughs", BILLION_LAUGHS, 1, "a", "anchors and aliases"),
    ("undefined-alias", b"a: *nothing\n", 1, "", "YAML syntax error: found undefined alias"),
    ("merge-key", b"a: {x: 1}\nb:\n  <<: {y: 2}\n", 3, "b",
     "merge keys ('<<') are not allowed in problem files"),
    ("complex-key", b"? [a, b]\n: 1\n", 1, "", "mapping keys must be plain text"),
    ("two-documents", b"name: a\n---\nname: b\n", 2, "",
     "file holds more than one YAML document; put one problem per file"),
    ("trailing-empty-document", b"name: a\n---\n", 2, "", "more than one YAML document"),
    ("yaml-1.1-directive", b"%YAML 1.1\n---\non: yes\n", 2, "",
     "YAML 1.1 documents are not supported; remove the '%YAML' line"),
    ("top-level-list", b"- name\n- coordinates\n", 1, "",
     "the file holds a list, not a mapping of fields"),
    ("top-level-scalar", b"just some text\n", 1, "",
     "the file holds a single value, not a mapping of fields"),
    ("top-level-null", b"~\n", 1, "", "the file holds a single value"),
    ("empty-file", b"", 1, "", "file is empty; a problem file is a mapping"),
    ("whitespace-only", b"  \n\n \n", 1, "", "file is empty"),
    ("comment-only", b"# nothing here\n\n# really\n", 1, "", "file is empty"),
    ("document-marker-only", b"---\n", 1, "", "file is empty"),
    ("latin-1", b"name: caf\xe9\n", 1, "", "file is not UTF-8 text (byte 0xe9 at offset 9)"),
    ("latin-1-line-3", b"name: a\ncoordinates: [x]\ndescription: \xff\n", 3, "",
     "save the file as UTF-8"),
    ("utf-16", "name: a\n".encode("utf-16"), 1, "", "file is not UTF-8 text"),
    ("over-size", b"a: " + b"x" * yamlread.MAX_BYTES + b"\n", 0, "",
     f"the limit is {yamlread.MAX_BYTES}; problem files are small"),
    ("deep-flow-lists", b"a: " + b"[" * 10_000 + b"]" * 10_000 + b"\n", 1, "",
     "values are nested more than 24 levels deep"),
    ("deep-flow-maps", b"a: " + b"{b: " * 10_000 + b"1" + b"}" * 10_000 + b"\n", 1, "",
     "values are nested more than 24 levels deep"),
    ("deep-block-maps", b"".join(b" " * i + b"k:\n" for i in range(600)) + b" " * 600 + b"v\n",
     26, "", "values are nested more than 24 levels deep"),
    ("too-many-values", b"a: [" + b"1," * 30_000 + b"1]\n", 1, "",
     f"the file has more than {yamlread.MAX_NODES} values"),
    ("inf", b"a: .inf\n", 1, "a", ".inf is not a usable number; give a finite number"),
    ("negative-inf", b"a: -.Inf\n", 1, "a", "-.Inf is not a usable number"),
    ("nan", b"a: .nan\n", 1, "a", ".nan is not a usable number"),
    ("float-overflow", b"a: 1e999\n", 1, "a", "number 1e999 is out of range"),
    ("huge-integer", b"a: " + b"9" * 50 + b"\n", 1, "a", "integer with 50 digits is too large"),
    ("huge-hex", b"a: 0x" + b"f" * 45 + b"\n", 1, "a", "integer with 47 digits is too large"),
    ("escape-sequence", b'name: "\\e[2Jhi"\n', 1, "name",
     "text contains a control character (U+001B)"),
    ("raw-control-character", b"name: a\x07b\n", 1, "",
     "file contains the control character U+0007"),
    ("nul-byte", b"name: a\nb: \x00\n", 2, "", "file contains the control character U+0000"),
    ("bidi-override", "name: abc\u202edef\n".encode(), 1, "name",
     "text contains a bidirectional override (U+202E)"),
    ("lone-surrogate", b'name: "\\ud800"\n', 1, "name",
     "text contains an unpaired surrogate (U+D800)"),
]


@pytest.mark.parametrize(("raw", "line", "where", "fragment"), [c[1:] for c in REFUSALS],
                         ids=[c[0] for c in REFUSALS])
def test_refusals_name_line_field_and_problem(raw: bytes, line: int, where: str,
                                              fragment: str) -> None:
    """Each refused file yields one issue with the file, its line, the field and the reason."""
    issue = refusal(raw)
    assert (issue.file, issue.line, issue.where) == (SOURCE, line, where)
    assert fragment in str(issue)
    place = f"{SOURCE}:{line}: " if line else f"{SOURCE}: "
    assert str(issue).startswith(place + (f"{where}: " if where else ""))


def test_duplicate_key_is_not_last_wins() -> None:
    """A repeated key is an error even when both values agree (no silent last-wins)."""
    issue = refusal(b"name: a\nname: a\n")
    assert issue.message == "duplicate key 'name' (first given on line 1)"
    assert issue.hint == "give each key once"


def test_depth_limit_boundary() -> None:
    """Values nested up to the documented depth are accepted; one level more is refused."""
    lists = yamlread.MAX_DEPTH - 1  # the top mapping and the key `a` take one level each
    ok = b"a: " + b"[" * lists + b"1" + b"]" * lists + b"\n"
    value = read(ok).data["a"]
    for _ in range(lists):
        value = value[0]
    assert value == 1
    too_deep = b"a: " + b"[" * (lists + 1) + b"1" + b"]" * (lists + 1) + b"\n"
    issue = refusal(too_deep)
    assert issue.where == "a" + "[0]" * (lists + 1)
    assert issue.message == "values are nested more than 24 levels deep"


def test_largest_integer_is_accepted() -> None:
    """Integers up to the digit limit are read exactly."""
    digits = "9" * yamlread.MAX_INT_DIGITS
    assert read(f"a: {digits}\n").data["a"] == int(digits)


def test_spec_error_is_a_value_error() -> None:
    """SpecError belongs to lagsolve's error family and is also a ValueError."""
    with pytest.raises(SpecError) as caught:
        read(b"")
    assert isinstance(caught.value, LagsolveError) and isinstance(caught.value, ValueError)
    assert str(caught.value) == (
        "problem.yaml:1: file is empty; a problem file is a mapping with at least name and "
        "coordinates"
    )


def test_no_python_object_is_constructed(tmp_path: object) -> None:
    """A python/object tag is refused before anything runs: the marker file is never made."""
    import pathlib

    marker = pathlib.Path(str(tmp_path)) / "pwned"
    raw = f"name: !!python/object/apply:os.system ['touch {marker}']\n".encode()
    issue = refusal(raw)
    assert "is not allowed" in issue.message
    assert not marker.exists()
