"""Compiled report templates, kept with the install so that a command does not compile them again.

Compiling the Jinja2 templates of the reports costs about a quarter of a second of CPU at each ``lagsolve
derive``, more than rendering them. ``make`` (after installing) runs ``python -m lagsolve.prepare``,
which compiles every packaged template into Jinja2's bytecode cache under the environment's prefix
(``<venv>/share/lagsolve/template-cache/<environment class>``); a command only ever *reads* that folder
(:class:`InstalledCache`), so nothing is written at run time outside the output folder. Jinja2 checks each entry
against the template's source (a checksum) and its own and Python's version, and compiles the template itself
when the entry is missing or stale: an edited template, a ``--templates`` folder, or an install without the
folder (``pip install``) are rendered as before, only not faster.
"""

from __future__ import annotations

import os
from pathlib import Path

import jinja2

from lagsolve.caches import TEMPLATES

#: where ``make`` writes the compiled templates: beside the interpreter's install, never in the user's folders
CACHE = TEMPLATES


class InstalledCache(jinja2.BytecodeCache):
    """Jinja2's bytecode cache over ``folder``, read-only: a command loads what ``make`` compiled, writes nothing.
    A symbolic link in place of an entry is not followed."""

    def __init__(self, folder: Path = CACHE) -> None:
        self.folder = folder

    def _entry(self, bucket: jinja2.bccache.Bucket) -> Path:
        return self.folder / f"{bucket.key}.cache"

    def load_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        path = self._entry(bucket)
        try:
            flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0)
            with os.fdopen(os.open(path, flags), "rb") as handle:
                bucket.load_bytecode(handle)
        except OSError:
            return  # none, or not a plain file: Jinja2 compiles the template

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        return None  # read-only at run time


class Writer(jinja2.FileSystemBytecodeCache):
    """The cache as ``make`` writes it (:mod:`lagsolve.render.precompile`; the entry names :class:`InstalledCache`
    reads)."""

    def __init__(self, folder: Path) -> None:
        super().__init__(str(folder), "%s.cache")
