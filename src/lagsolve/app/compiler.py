"""The system C compiler, for the FMU's binary: found on PATH (``$CC``, then ``cc``, ``gcc``, ``clang``) and run
without a shell, with a timeout."""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
from collections.abc import Sequence
from pathlib import Path

from lagsolve.errors import Issue, SpecError

#: the flags every exported source compiles with (the tests hold the code to them)
FLAGS = ("-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC")
TIMEOUT = 120.0


def find_compiler() -> list[str]:
    """The compiler's command (``$CC`` split as a shell would, or the first of cc, gcc, clang on PATH).

    Raises
    ------
    SpecError
        No C compiler is found.
    """
    given = shlex.split(os.environ.get("CC", ""))
    if given and shutil.which(given[0]):
        return [str(shutil.which(given[0])), *given[1:]]
    for name in ("cc", "gcc", "clang"):
        found = shutil.which(name)
        if found:
            return [found]
    raise SpecError([Issue("<environment>", 0, "--to fmu", "building an FMU needs a C compiler, and none was found "
                           "(CC, cc, gcc, clang)",
                           "install one (apt-get install gcc, xcode-select --install) or set CC; "
                           "or export --to c and compile it yourself")])


def compile_shared(sources: Sequence[Path], target: Path, include: Sequence[Path] = ()) -> Path:
    """Compile ``sources`` into the shared library ``target`` (linked with libm) and return it.

    Raises
    ------
    SpecError
        The compiler fails or takes longer than :data:`TIMEOUT` seconds (its messages in the issue).
    """
    command = [*find_compiler(), *FLAGS, *(f"-I{folder}" for folder in include), "-o", str(target),
               *(str(s) for s in sources), "-lm"]
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise SpecError([Issue(str(target), 0, "compile", f"the C compiler did not finish: {exc}",
                               "check the compiler (CC), or export --to c and compile it yourself")]) from None
    if result.returncode != 0:
        raise SpecError([Issue(str(target), 0, "compile", "the C compiler failed: "
                               + " ".join(result.stderr.split())[:2000],
                               "report it with the problem file: the exported C should always compile")])
    return target
