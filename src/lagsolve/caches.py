"""What ``make`` prepares beside the install so that a command starts faster, and where: the compiled report
templates (:mod:`lagsolve.render.template_cache`) and pint's parsed unit definitions, under
``<sys.prefix>/share/lagsolve/`` (the virtual environment's own folder). ``python -m lagsolve.prepare`` writes
them; a command only reads them, and works the same, only slower, where they are missing."""

from __future__ import annotations

import sys
from pathlib import Path

#: the folder of everything prepared, beside the interpreter's install
ROOT = Path(sys.prefix) / "share" / "lagsolve"
#: the compiled report templates, one subfolder per Jinja2 environment class
TEMPLATES = ROOT / "template-cache"
#: pint's parsed definitions, one subfolder per pint version (``pint-<version>``), complete when ``MARKER`` is in it
UNITS = ROOT / "pint-cache"
MARKER = "complete"


def pint_folder(version: str) -> Path:
    """The folder of pint ``version``'s parsed definitions."""
    return UNITS / f"pint-{version}"


def pint_cache(version: str) -> Path | None:
    """The folder pint reads its parsed definitions from, when ``make`` prepared it for this ``version`` (so pint
    finds every entry and writes nothing); else None (pint parses its definitions itself)."""
    folder = pint_folder(version)
    return folder if (folder / MARKER).is_file() and not folder.is_symlink() else None
