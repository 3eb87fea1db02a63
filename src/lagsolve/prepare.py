"""``python -m lagsolve.prepare``: what ``make`` runs after installing (:mod:`lagsolve.caches`): the report
templates compiled, and pint's unit definitions parsed, into the virtual environment's folder."""

from __future__ import annotations

from pathlib import Path


def prepare_units() -> Path:
    """Parse pint's definitions into this pint version's cache folder and mark it complete; the folder."""
    from lagsolve.caches import MARKER, pint_folder
    from lagsolve.pint_import import import_pint

    pint = import_pint()

    folder = pint_folder(pint.__version__)
    folder.mkdir(parents=True, exist_ok=True)
    pint.UnitRegistry(cache_folder=str(folder))
    (folder / MARKER).write_text(pint.__version__ + "\n", encoding="utf-8")
    return folder


def main() -> list[str]:
    """Prepare everything; one line per part, to print."""
    from lagsolve.caches import TEMPLATES
    from lagsolve.render.precompile import build

    return [f"lagsolve: compiled {build()} templates into {TEMPLATES}",
            f"lagsolve: parsed pint's unit definitions into {prepare_units()}"]


if __name__ == "__main__":  # pragma: no cover - run by make
    print("\n".join(main()))
