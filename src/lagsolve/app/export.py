"""``lagsolve export``: a problem's equations as code (issue 32): a Python module, C99, an FMU."""

from __future__ import annotations

from pathlib import Path

import sympy

from lagsolve.errors import Issue, SpecError

TARGETS = ("python", "c", "fmu")


def export_file(path: Path | str, to: str = "python", output: Path | str = "out") -> Path:
    """Write the problem at ``path`` as ``to`` into ``output`` and return the main file's path: ``<slug>.py``;
    ``<prefix>.c`` (beside ``<prefix>.h``); ``<prefix>.fmu``.

    Raises
    ------
    SpecError
        An unknown target, a missing value, a file name that gives no C identifier, an expression the target
        cannot spell, or (fmu) no C compiler.
    """
    from lagsolve import __version__
    from lagsolve.files import safe_slug, write_file
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.numeric.system import bind
    from lagsolve.problem.load import load_problem

    if to not in TARGETS:
        raise SpecError([Issue("<argument>", 0, "--to", f"unknown target {to!r}",
                               "give one of: " + ", ".join(TARGETS))])
    problem = load_problem(Path(path))
    if to != "python":
        prefix = _prefix(problem.source)
        if to == "fmu":
            from lagsolve.app.fmu import find_compiler

            find_compiler()  # refuse before deriving anything
    form = matrix_form(problem, display=False)
    system = bind(form)
    unusable = sorted(group for group in ("matrices", "directions", "sliding", "contact_values")
                      if any(e is sympy.nan for e in system.expressions[group]))
    if unusable:
        raise SpecError([Issue(problem.source, 0, "export", "the equations (" + ", ".join(unusable) + ") hold a "
                               "symbol that is neither a coordinate, a velocity, time nor a parameter with a value",
                               "give every symbol a value under simulation.values, or simulate instead")])
    source = Path(problem.source).name
    # only the printing of the equations is caught here: a file that cannot be written says so itself
    try:
        if to == "python":
            from lagsolve.render.python_module import python_module

            text = python_module(system, problem.name, __version__)
        else:
            from lagsolve.render.c_module import c_module

            header, code = c_module(system, prefix, problem.name, __version__, source)
    except ValueError as exc:
        raise SpecError([Issue(problem.source, 0, "export", f"the equations cannot be exported to {to}: {exc}",
                               "simulate it with lagsolve simulate instead")]) from None
    if to == "python":
        return write_file(Path(output), f"{safe_slug(problem.source)}.py", text)
    if to == "c":
        write_file(Path(output), f"{prefix}.h", header)
        return write_file(Path(output), f"{prefix}.c", code)
    from lagsolve.app.fmu import build_fmu

    return build_fmu(system, problem, prefix, header, code, Path(output), __version__)


def _prefix(source: str) -> str:
    """The C identifier of the problem's file, or a refusal that says how to rename it."""
    from lagsolve.render.c_module import c_prefix

    stem = Path(source).name.rsplit(".", 1)[0]
    try:
        return c_prefix(stem)
    except ValueError as exc:
        raise SpecError([Issue(source, 0, "export", str(exc),
                               "rename the file with ASCII letters, digits or _ (e.g. pendulum.yaml)")]) from None
