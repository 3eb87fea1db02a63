"""Read a YAML 1.2 document safely, keeping the line of every value.

ruamel.yaml composes the node graph (YAML 1.2 rules: ``1e-8`` is a number, the
key ``on`` is a string); this module turns it into plain Python values itself,
so that no tag can construct an object. It rejects what a problem file never
needs and a hostile one might use: explicit non-standard tags, anchors and
aliases (the "billion laughs" bomb), duplicate keys, several documents, and
documents that are too large or too deep.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from typing import Any

from lagsolve.errors import Issue, SpecError

MAX_BYTES = 256 * 1024
MAX_NODES = 5_000
MAX_DEPTH = 24
MAX_INT_DIGITS = 40

_STANDARD = "tag:yaml.org,2002:"
_ALLOWED_TAGS = {_STANDARD + t for t in ("str", "int", "float", "bool", "null", "map", "seq")}
#: Characters refused in text: C0/C1 controls other than tab and line feed (a terminal
#: escape sequence in a name would be replayed by ``lagsolve``'s own output), lone
#: surrogates (they cannot be written as UTF-8) and the bidirectional overrides that
#: make text display differently from what it is.
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\ud800-\udfff\u202a-\u202e\u2066-\u2069]")


@dataclass(frozen=True)
class FileKind:
    """What kind of file is read, for the hints of its errors: ``plural`` ("problem files"), ``empty`` (the hint
    for an empty file), ``mapping`` (for a file that is not a mapping), ``tag`` (for a tag on the whole file),
    ``one`` (what a file holds one of)."""

    plural: str
    empty: str
    mapping: str
    tag: str
    one: str


#: a problem file (the default)
PROBLEM = FileKind("problem files", "a problem file is a mapping with at least name and coordinates",
                   "start with 'name: ...' and 'coordinates: [...]'", "a problem file is a plain mapping of fields",
                   "one problem")
#: a submission of ``lagsolve grade`` (docs/grading.md)
SUBMISSION = FileKind("submissions", "a submission is a mapping with 'student' and 'steps' (see docs/grading.md)",
                      "a submission starts with 'student: ...' and 'steps:' (see docs/grading.md)",
                      "a submission is a plain mapping with 'student' and 'steps'", "one submission")


@dataclass(frozen=True)
class Document:
    """A parsed file: ``data`` is plain dicts/lists/scalars; ``lines`` maps a path
    (tuple of keys and indices) to the 1-based line where that value starts."""

    data: Any
    lines: dict[tuple, int]


def read_document(raw: bytes, source: str, kind: FileKind = PROBLEM) -> Document:
    """Parse ``raw`` (the bytes of ``source``) into a :class:`Document`; ``kind`` words the hints.

    Raises
    ------
    SpecError
        For anything that is not one well-formed, plain YAML mapping.
    """

    def fail(line: int, message: str, hint: str = "") -> SpecError:
        return SpecError([Issue(source, line, "", message, hint)])

    if len(raw) > MAX_BYTES:
        raise fail(0, f"file is {len(raw)} bytes; the limit is {MAX_BYTES}",
                   f"{kind.plural} are small")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise fail(line, f"file is not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset "
                   f"{exc.start})", "save the file as UTF-8") from None
    if text.startswith("\ufeff"):
        text = text[1:]
    empty = "file is empty"
    empty_hint = kind.empty
    if all(ln.strip().startswith("#") or not ln.strip() for ln in text.splitlines()):
        raise fail(1, empty, empty_hint)

    from ruamel.yaml import YAML
    from ruamel.yaml.error import MarkedYAMLError, YAMLError
    from ruamel.yaml.reader import ReaderError

    yaml = YAML(typ="rt", pure=True)
    try:
        # a first pass over the parser's events: it is flat (no recursion), so nesting,
        # size, versions and extra documents are refused, with their line, before the
        # recursive composer could exhaust the stack or spend seconds on a huge file
        _check_events(yaml.parse(io.StringIO(text)), fail, kind)
        nodes = list(yaml.compose_all(io.StringIO(text)))
    except SpecError:
        raise
    except ReaderError as exc:
        line = text[: exc.position].count("\n") + 1
        raise fail(line, f"file contains the control character U+{exc.character:04X}",
                   f"remove it; {kind.plural} are plain text") from None
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else 0
        problem = (exc.problem or "").strip() or "syntax error"
        context = f" ({exc.context.strip()})" if exc.context else ""
        raise fail(line, f"YAML syntax error: {problem}{context}",
                   "check indentation, colons and quotes on that line") from None
    except RecursionError:  # pragma: no cover - the event pass bounds the nesting first
        raise fail(0, f"values are nested more than {MAX_DEPTH} levels deep") from None
    except (YAMLError, ValueError) as exc:
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise fail(0, f"YAML error: {first}") from None
    nodes = [n for n in nodes if n is not None and not _is_empty(n)]
    if not nodes:
        raise fail(1, empty, empty_hint)
    return _Converter(source, kind).document(nodes[0])


def _check_events(events: Any, fail: Any, kind: FileKind = PROBLEM) -> None:
    from ruamel.yaml.events import (
        AliasEvent,
        CollectionEndEvent,
        CollectionStartEvent,
        DocumentStartEvent,
        MappingStartEvent,
        ScalarEvent,
    )

    # one entry per open collection: nodes seen so far in a mapping (even: the next is a key),
    # or -1 for a list; values are counted as the converter counts them, keys are not
    open_collections: list[int] = []
    count = documents = 0
    for event in events:
        line = event.start_mark.line + 1
        if isinstance(event, DocumentStartEvent):
            documents += 1
            if documents > 1:
                raise fail(line, "file holds more than one YAML document",
                           f"put {kind.one} per file (remove the '---' separators)")
            version = getattr(event, "version", None)
            if version is not None and tuple(version) != (1, 2):
                shown = ".".join(str(v) for v in version)
                raise fail(line, f"YAML {shown} documents are not supported",
                           f"remove the '%YAML' line; {kind.plural} are read as YAML 1.2")
        if isinstance(event, CollectionStartEvent | ScalarEvent | AliasEvent):
            in_mapping = bool(open_collections) and open_collections[-1] >= 0
            is_key = in_mapping and open_collections[-1] % 2 == 0
            if in_mapping:
                open_collections[-1] += 1
            if not is_key:
                count += 1
                if count > MAX_NODES:
                    raise fail(line, f"the file has more than {MAX_NODES} values",
                               f"{kind.plural} are small")
        if isinstance(event, CollectionStartEvent):
            open_collections.append(0 if isinstance(event, MappingStartEvent) else -1)
            if len(open_collections) > MAX_DEPTH + 1:
                raise fail(line, f"values are nested more than {MAX_DEPTH} levels deep",
                           f"{kind.plural} need only a few levels")
        elif isinstance(event, CollectionEndEvent):
            open_collections.pop()


def _is_empty(node: Any) -> bool:
    """A document that is only ``---`` (an empty plain scalar)."""
    return (type(node).__name__ == "ScalarNode" and node.tag == _STANDARD + "null"
            and node.value == "")


class _Converter:
    def __init__(self, source: str, kind: FileKind = PROBLEM) -> None:
        self.source, self.kind = source, kind
        self.lines: dict[tuple, int] = {}
        self.key_lines: dict[tuple, int] = {}
        self.seen: set[int] = set()
        self.count = 0

    def fail(self, node: Any, path: tuple, message: str, hint: str = "",
             line: int | None = None) -> SpecError:
        line = node.start_mark.line + 1 if line is None else line
        return SpecError([Issue(self.source, line, dotted(path), message, hint)])

    def document(self, root: Any) -> Document:
        from ruamel.yaml.nodes import MappingNode

        if root.tag not in _ALLOWED_TAGS:
            raise self.fail(root, (), f"YAML tag {_show_tag(root.tag)!r} is not allowed",
                            f"remove the tag; {self.kind.tag}")
        if not isinstance(root, MappingNode):
            kind = "a list" if type(root).__name__ == "SequenceNode" else "a single value"
            raise self.fail(root, (), f"the file holds {kind}, not a mapping of fields",
                            self.kind.mapping)
        return Document(self.value(root, (), 0), self.lines)

    def value(self, node: Any, path: tuple, depth: int, line: int | None = None) -> Any:
        from ruamel.yaml.nodes import MappingNode, ScalarNode, SequenceNode

        line = node.start_mark.line + 1 if line is None else line
        self.count += 1
        if self.count > MAX_NODES:
            raise self.fail(node, path, f"the file has more than {MAX_NODES} values",
                            f"{self.kind.plural} are small", line)
        if depth > MAX_DEPTH:
            raise self.fail(node, path, f"values are nested more than {MAX_DEPTH} levels deep",
                            f"{self.kind.plural} need only a few levels", line)
        if id(node) in self.seen or getattr(node, "anchor", None):
            raise self.fail(node, path,
                            f"anchors and aliases (&name, *name) are not allowed in {self.kind.plural}",
                            "write the value out in full", line)
        self.seen.add(id(node))
        if node.tag not in _ALLOWED_TAGS:
            raise self.fail(node, path, f"YAML tag {_show_tag(node.tag)!r} is not allowed",
                            f"remove the tag; {self.kind.plural} hold plain text, numbers, lists and "
                            "mappings", line)
        self.lines[path] = line
        if isinstance(node, MappingNode):
            result: dict[str, Any] = {}
            for key_node, value_node in node.value:
                key_line = key_node.start_mark.line + 1
                if isinstance(key_node, ScalarNode) and key_node.tag == _STANDARD + "merge":
                    raise self.fail(key_node, path, "merge keys ('<<') are not allowed in problem "
                                    "files", "write the values out in full")
                if not isinstance(key_node, ScalarNode) or key_node.tag not in _ALLOWED_TAGS:
                    raise self.fail(key_node, path, "mapping keys must be plain text",
                                    "write keys as names, like 'mass:'")
                key = self.scalar(key_node, path)
                if not isinstance(key, str):
                    key = str(key_node.value)
                    self.check_text(key_node, path, key)
                kpath = (*path, key)
                if key in result:
                    raise self.fail(key_node, kpath,
                                    f"duplicate key {key!r} (first given on line "
                                    f"{self.key_lines.get(kpath, 0)})", "give each key once")
                self.key_lines[kpath] = key_line
                # an empty value (``mass:``) starts where the next token is: use the key's line
                empty = isinstance(value_node, ScalarNode) and value_node.value == ""
                result[key] = self.value(value_node, kpath, depth + 1, key_line if empty else None)
            return result
        if isinstance(node, SequenceNode):
            return [self.value(item, (*path, i), depth + 1) for i, item in enumerate(node.value)]
        return self.scalar(node, path)

    def check_text(self, node: Any, path: tuple, text: str) -> None:
        bad = _CONTROL.search(text)
        if bad is not None:
            code = ord(bad.group())
            what = ("an unpaired surrogate" if 0xD800 <= code <= 0xDFFF
                    else "a bidirectional override" if code >= 0x202A else "a control character")
            raise self.fail(node, path, f"text contains {what} (U+{code:04X})",
                            "remove it; text may hold tabs and line breaks, not other controls")

    def scalar(self, node: Any, path: tuple) -> Any:
        tag = node.tag[len(_STANDARD):]
        text = node.value
        if tag == "str":
            if node.style == ">":
                # ruamel marks the folds of a '>' scalar with BEL characters (for round-tripping);
                # a BEL typed in the file itself is refused earlier by ruamel's reader
                text = text.replace("\a", "")
            self.check_text(node, path, text)
            return text
        if tag == "null":
            return None
        if tag == "bool":
            return text.lower() == "true"
        if tag == "int":
            digits = text.lstrip("+-")
            if len(digits) > MAX_INT_DIGITS:
                raise self.fail(node, path, f"integer with {len(digits)} digits is too large",
                                "use a decimal number like 1.5e20, or fewer digits")
            try:
                if digits.startswith(("0o", "0x")):
                    base = 8 if "0o" in text else 16
                    return int(text.replace("0o", "").replace("0x", ""), base)
                return int(text)
            except ValueError:
                raise self.fail(node, path, f"cannot read integer {text!r}") from None
        if tag == "float":
            lowered = text.lower()
            if lowered in (".inf", "+.inf", "-.inf", ".nan"):
                raise self.fail(node, path, f"{text} is not a usable number",
                                "give a finite number")
            if len(text) > 60:
                raise self.fail(node, path, "number is too long", "use at most 60 characters")
            value = float(text)
            if value != value or value in (float("inf"), float("-inf")):
                raise self.fail(node, path, f"number {text} is out of range",
                                "give a finite number")
            return value
        return text  # pragma: no cover - tags are filtered above


def _show_tag(tag: Any) -> str:
    return str(tag).replace(_STANDARD, "!!")


def dotted(path: tuple) -> str:
    """``('constraints', 'wire', 'on')`` → ``constraints.wire.on``; list indices as ``[i]``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def kind_of(value: Any) -> str:
    """What a YAML value is, for a message."""
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"true/false ({value})"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, str):
        return f"text {value[:40]!r}"
    return f"a number ({value})"
