"""``lagsolve export``: a problem's equations as code (issue 32; the Python target)."""

from __future__ import annotations

from pathlib import Path

import sympy

from lagsolve.errors import Issue, SpecError

TARGETS = ("python",)


def export_file(path: Path | str, to: str = "python", output: Path | str = "out") -> Path:
    """Write ``<slug>.py`` for the problem at ``path`` into ``output`` and return its path.

    Raises
    ------
    SpecError
        An unknown target, a missing value, or a problem that cannot be exported correctly (friction).
    """
    from lagsolve import __version__
    from lagsolve.files import safe_slug, write_file
    from lagsolve.mechanics.equations.matrix_form import matrix_form
    from lagsolve.numeric.system import bind
    from lagsolve.problem.load import load_problem
    from lagsolve.render.python_module import python_module

    if to not in TARGETS:
        raise SpecError([Issue("<argument>", 0, "--to", f"unknown target {to!r}",
                               "give one of: " + ", ".join(TARGETS))])
    problem = load_problem(Path(path))
    form = matrix_form(problem, display=False)
    system = bind(form)
    unusable = sorted(group for group in ("matrices", "directions", "sliding", "contact_values")
                      if any(e is sympy.nan for e in system.expressions[group]))
    if unusable:
        raise SpecError([Issue(problem.source, 0, "export", "the equations (" + ", ".join(unusable) + ") hold a "
                               "symbol that is neither a coordinate, a velocity, time nor a parameter with a value",
                               "give every symbol a value under simulation.values, or simulate instead")])
    try:
        text = python_module(system, problem.name, __version__)
    except ValueError as exc:
        raise SpecError([Issue(problem.source, 0, "export", f"the equations cannot be exported to {to}: {exc}",
                               "simulate it with lagsolve simulate instead")]) from None
    return write_file(Path(output), f"{safe_slug(problem.source)}.py", text)
