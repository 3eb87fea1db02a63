"""``python -m lagsolve.prepare``: what ``make`` runs after installing (:mod:`lagsolve.caches`): the report
templates compiled, and pint's unit definitions parsed, into the virtual environment's folder, and the package's
own modules compiled to bytecode (``__pycache__`` beside them, as Python writes it at a first run; an editable
install is not compiled by pip, and an environment with ``PYTHONDONTWRITEBYTECODE`` set would otherwise compile
every module at every command: a tenth of a second of ``lagsolve derive``)."""

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


def compile_package() -> int:
    """The package's modules compiled to bytecode where it is installed; how many modules it has."""
    import compileall

    folder = Path(__file__).resolve().parent
    if not compileall.compile_dir(str(folder), quiet=1):
        raise OSError(f"could not compile the modules in {folder}")
    return sum(1 for _ in folder.rglob("*.py"))


def main() -> list[str]:
    """Prepare everything; one line per part, to print."""
    from lagsolve.caches import TEMPLATES
    from lagsolve.render.precompile import build

    return [f"lagsolve: compiled {build()} templates into {TEMPLATES}",
            f"lagsolve: parsed pint's unit definitions into {prepare_units()}",
            f"lagsolve: compiled the bytecode of {compile_package()} modules"]


if __name__ == "__main__":  # pragma: no cover - run by make
    print("\n".join(main()))
