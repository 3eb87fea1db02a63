"""The package's shape stays true: no import cycle between lagsolve modules, no import that climbs
the pipeline, no module too long.

Imports are read with `ast` from the source, not by importing, and every one counts: at module level,
under `if TYPE_CHECKING:` (a type checker follows them) and inside functions (a late import is still a
dependency; a notebook display, for one, is registered from `render/` instead, see `lagsolve/notebook.py`).
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "lagsolve"
MAX_LINES = 750

#: the layers, first to last (docs/architecture.md): a module imports its own package and earlier layers
#: only. The data flows problem → mechanics → numeric → render; check reads a derivation (render shows its
#: reports), app runs the commands, sweep many runs; the library (api), the CLI and the package come last.
LAYERS = ("errors", "enums", "caches", "pint_import", "notebook", "ranges", "files", "problem", "mechanics",
          "numeric", "check", "grade", "render", "app", "sweep", "variants", "schemas", "api", "prepare", "cli",
          "__main__", "")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in sorted((SRC / PACKAGE).rglob("*.py"))}


def _resolve(module: str, path: Path, node: ast.ImportFrom) -> list[str]:
    """Absolute names a `from ... import ...` statement may refer to (a module, or a module's attribute)."""
    if node.level:
        package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
        base_parts = package[: len(package) - (node.level - 1)]
        base = ".".join(base_parts + ([node.module] if node.module else []))
    else:
        base = node.module or ""
    return [base] + [f"{base}.{alias.name}" for alias in node.names]


def _imports(module: str, path: Path, known: set[str]) -> set[str]:
    """The lagsolve modules ``module`` imports anywhere in its source (every node of its tree)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: set[str] = set()
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            names = _resolve(module, path, node)
        for name in names:
            # `import a.b.c` or `from a.b import c` depends on the deepest known module it names
            while name and name not in known:
                name = name.rpartition(".")[0]
            if name and name != module and name.startswith(PACKAGE + "."):
                found.add(name)
    return found


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    known = set(modules)
    return {name: _imports(name, path, known) for name, path in modules.items()}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []

    def connect(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            connect(v)
    return out


def test_no_import_cycle_between_lagsolve_modules():
    cycles = _cycles(_graph())
    assert cycles == [], f"import cycles: {cycles}"


def _layer(module: str) -> str:
    """The layer of a module: its top-level package or module under lagsolve ("" for the package itself)."""
    return module.split(".")[1] if "." in module else ""


def _climbs(graph: dict[str, set[str]]) -> list[str]:
    """Every import of a later layer (or of a module in no layer), as "importer -> imported"."""
    out = []
    for module, imported in sorted(graph.items()):
        for name in sorted(imported):
            here, there = _layer(module), _layer(name)
            if here != there and (here not in LAYERS or there not in LAYERS
                                  or LAYERS.index(there) > LAYERS.index(here)):
                out.append(f"{module} -> {name}")
    return out


def test_no_import_climbs_the_pipeline():
    climbs = _climbs(_graph())
    assert climbs == [], f"imports of a later layer (see LAYERS): {climbs}"


def test_function_local_imports_count():
    """An import inside a function is a dependency like any other."""
    graph = _graph()
    assert "lagsolve.render.display" in graph["lagsolve"]  # imported only in _notebook_display
    assert _climbs({"lagsolve.mechanics.results": {"lagsolve.render.display"}}) == [
        "lagsolve.mechanics.results -> lagsolve.render.display"]


def test_the_cycle_finder_finds_a_cycle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_module_over_the_line_limit():
    long = {name: n for name, path in _modules().items() if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert long == {}, f"modules over {MAX_LINES} lines: {long}"


def test_test_files_have_unique_names():
    """pytest's default import mode refuses two test files of one name in different folders (tests mirror modules,
    and two packages may have modules of one name: the second test takes its package's name as a prefix)."""
    names = [p.name for p in (Path(__file__).resolve().parent).rglob("test_*.py")]
    assert sorted({n for n in names if names.count(n) > 1}) == []
