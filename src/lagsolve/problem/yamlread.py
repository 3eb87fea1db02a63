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
from dataclasses import dataclass
from typing import Any

from lagsolve.errors import Issue, SpecError

MAX_BYTES = 256 * 1024
MAX_NODES = 20_000
MAX_DEPTH = 24
MAX_INT_DIGITS = 40

_STANDARD = "tag:yaml.org,2002:"
_ALLOWED_TAGS = {_STANDARD + t for t in ("str", "int", "float", "bool", "null", "map", "seq")}


@dataclass(frozen=True)
class Document:
    """A parsed file: ``data`` is plain dicts/lists/scalars; ``lines`` maps a path
    (tuple of keys and indices) to the 1-based line where that value starts."""

    data: Any
    lines: dict[tuple, int]


def read_document(raw: bytes, source: str) -> Document:
    """Parse ``raw`` (the bytes of ``source``) into a :class:`Document`.

    Raises
    ------
    SpecError
        For anything that is not one well-formed, plain YAML mapping.
    """

    def fail(line: int, message: str, hint: str = "") -> SpecError:
        return SpecError([Issue(source, line, "", message, hint)])

    if len(raw) > MAX_BYTES:
        raise fail(0, f"file is {len(raw)} bytes; the limit is {MAX_BYTES}", "problem files are small")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise fail(line, f"file is not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset {exc.start})",
                   "save the file as UTF-8") from None
    if text.startswith("\ufeff"):
        text = text[1:]
    if not text.strip() or all(ln.strip().startswith("#") or not ln.strip() for ln in text.splitlines()):
        raise fail(1, "file is empty", "a problem file is a mapping with at least name and coordinates")

    from ruamel.yaml import YAML
    from ruamel.yaml.error import MarkedYAMLError, YAMLError

    yaml = YAML(typ="rt", pure=True)
    try:
        nodes = list(yaml.compose_all(io.StringIO(text)))
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else 0
        problem = (exc.problem or "").strip() or "syntax error"
        context = f" ({exc.context.strip()})" if exc.context else ""
        raise fail(line, f"YAML syntax error: {problem}{context}",
                   "check indentation, colons and quotes on that line") from None
    except (YAMLError, RecursionError, ValueError) as exc:
        raise fail(0, f"YAML error: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}") from None
    nodes = [n for n in nodes if n is not None]
    if not nodes:
        raise fail(1, "file is empty", "a problem file is a mapping with at least name and coordinates")
    if len(nodes) > 1:
        line = nodes[1].start_mark.line + 1
        raise fail(line, f"file holds {len(nodes)} YAML documents",
                   "put one problem per file (remove the '---' separators)")
    return _Converter(source).document(nodes[0])


class _Converter:
    def __init__(self, source: str) -> None:
        self.source = source
        self.lines: dict[tuple, int] = {}
        self.seen: set[int] = set()
        self.count = 0

    def fail(self, node: Any, path: tuple, message: str, hint: str = "") -> SpecError:
        return SpecError([Issue(self.source, node.start_mark.line + 1, dotted(path), message, hint)])

    def document(self, root: Any) -> Document:
        from ruamel.yaml.nodes import MappingNode

        if not isinstance(root, MappingNode):
            kind = "a list" if type(root).__name__ == "SequenceNode" else "a single value"
            raise self.fail(root, (), f"the file holds {kind}, not a mapping of fields",
                            "start with 'name: ...' and 'coordinates: [...]'")
        return Document(self.value(root, (), 0), self.lines)

    def value(self, node: Any, path: tuple, depth: int) -> Any:
        from ruamel.yaml.nodes import MappingNode, ScalarNode, SequenceNode

        self.count += 1
        if self.count > MAX_NODES:
            raise self.fail(node, path, f"the file has more than {MAX_NODES} values", "problem files are small")
        if depth > MAX_DEPTH:
            raise self.fail(node, path, f"values are nested more than {MAX_DEPTH} levels deep")
        if id(node) in self.seen or getattr(node, "anchor", None):
            raise self.fail(node, path, "anchors and aliases (&name, *name) are not allowed in problem files",
                            "write the value out in full")
        self.seen.add(id(node))
        if node.tag not in _ALLOWED_TAGS:
            tag = str(node.tag).replace(_STANDARD, "!!")
            raise self.fail(node, path, f"YAML tag {tag!r} is not allowed",
                            "remove the tag; problem files hold plain text, numbers, lists and mappings")
        self.lines[path] = node.start_mark.line + 1
        if isinstance(node, MappingNode):
            result: dict[str, Any] = {}
            for key_node, value_node in node.value:
                if not isinstance(key_node, ScalarNode) or key_node.tag not in _ALLOWED_TAGS:
                    raise self.fail(key_node, path, "mapping keys must be plain text")
                key = self.scalar(key_node, path)
                if not isinstance(key, str):
                    key = str(key_node.value)
                if key in result:
                    first = self.lines.get((*path, key), 0)
                    raise self.fail(key_node, (*path, key), f"duplicate key {key!r} (first given on line {first})",
                                    "give each key once")
                result[key] = self.value(value_node, (*path, key), depth + 1)
            return result
        if isinstance(node, SequenceNode):
            return [self.value(item, (*path, i), depth + 1) for i, item in enumerate(node.value)]
        return self.scalar(node, path)

    def scalar(self, node: Any, path: tuple) -> Any:
        tag = node.tag[len(_STANDARD):]
        text = node.value
        if tag == "str":
            # ruamel marks the folds of a '>' scalar with BEL characters for round-tripping
            return text.replace("\a", "") if node.style == ">" else text
        if tag == "null":
            return None
        if tag == "bool":
            return text.lower() == "true"
        if tag == "int":
            digits = text.lstrip("+-")
            if len(digits) > MAX_INT_DIGITS:
                raise self.fail(node, path, f"integer with {len(digits)} digits is too large")
            try:
                if digits.startswith(("0o", "0x")):
                    return int(text.replace("0o", "").replace("0x", ""), 8 if "0o" in text else 16)
                return int(text)
            except ValueError:
                raise self.fail(node, path, f"cannot read integer {text!r}") from None
        if tag == "float":
            lowered = text.lower()
            if lowered in (".inf", "+.inf", "-.inf", ".nan"):
                raise self.fail(node, path, f"{text} is not a usable number", "give a finite number")
            if len(text) > 60:
                raise self.fail(node, path, "number is too long")
            value = float(text)
            if value != value or value in (float("inf"), float("-inf")):
                raise self.fail(node, path, f"number {text} is out of range", "give a finite number")
            return value
        return text  # pragma: no cover - tags are filtered above


def dotted(path: tuple) -> str:
    """``('constraints', 'wire', 'on')`` → ``constraints.wire.on``; list indices as ``[i]``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out
