"""Compile every packaged report template into the install's bytecode cache (:mod:`lagsolve.render.template_cache`),
as ``make`` does after installing (``python -m lagsolve.prepare``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lagsolve.render.report import ENVIRONMENT, environment
from lagsolve.render.template_cache import CACHE, Writer


def build(folder: Path = CACHE) -> int:
    """Compile every packaged template of every kind into ``folder`` (in the subfolder of the environment class
    the reports use: the code Jinja2 compiles for its sandbox differs); the number compiled."""
    folder = folder / ENVIRONMENT.__name__
    folder.mkdir(parents=True, exist_ok=True)
    count = 0
    for kind in ("markdown", "latex", "html", "text"):
        env: Any = environment(kind).overlay(bytecode_cache=Writer(folder))
        for name in env.list_templates(filter_func=lambda n: n.endswith(".j2")):
            env.get_template(name)
            count += 1
    return count
