"""A variant's problem file: the original text, round-tripped by ruamel.yaml so that its comments and layout
survive, with only ``simulation.values``, ``simulation.initial`` and the ``expected:`` key changed.

Nothing is templated into the text: values go in as numbers and expressions as quoted strings, through the
YAML emitter.
"""

from __future__ import annotations

import io
from collections.abc import Mapping
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap
from ruamel.yaml.scalarstring import DoubleQuotedScalarString


def _yaml() -> YAML:
    yaml = YAML(typ="rt")
    yaml.preserve_quotes = True
    yaml.width = 4096  # expressions stay on one line
    return yaml


def _mapping(parent: Any, key: str, flow: bool) -> Any:
    """``parent[key]`` as a mapping, created (in flow style when ``flow``) when the file has none."""
    if not isinstance(parent.get(key), dict):
        parent[key] = CommentedMap()
        if flow:
            parent[key].fa.set_flow_style()
    return parent[key]


def variant_text(original: str, values: Mapping[str, float], initial: Mapping[str, float],
                 expected: Mapping[str, Mapping[str, str]], note: str) -> str:
    """The original YAML text with the variant's numbers and the derived ``expected:`` answers.

    ``values`` and ``initial`` hold only what changes (and what the file did not give); the file's order of
    keys is kept and new keys go at the end. ``note`` becomes a comment above ``simulation``.
    """
    yaml = _yaml()
    data = yaml.load(original)
    simulation = _mapping(data, "simulation", flow=False)
    for key, numbers in (("values", values), ("initial", initial)):
        if numbers:
            target = _mapping(simulation, key, flow=True)
            for name, value in numbers.items():
                target[name] = float(value)
    section = CommentedMap()
    for kind, entries in expected.items():
        section[kind] = CommentedMap((k, DoubleQuotedScalarString(v)) for k, v in entries.items())
    data["expected"] = section
    data.yaml_set_comment_before_after_key("simulation", before=note)
    out = io.StringIO()
    yaml.dump(data, out)
    return out.getvalue()
