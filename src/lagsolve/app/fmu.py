"""``lagsolve export --to fmu``: the FMI 2.0 Model Exchange FMU, built with the system C compiler.

The archive holds ``modelDescription.xml``, ``sources/`` (the exported C99 code, its FMI 2.0 wrapper and the
FMI headers with their licence), ``documentation/`` (the headers' licence) and
``binaries/<platform>/<prefix>.<so|dylib|dll>``. Its entries are sorted and dated 1980-01-01, so the same
equations and the same binary give the same bytes.
"""

from __future__ import annotations

import io
import sys
import tempfile
import zipfile
from importlib import resources
from pathlib import Path

from lagsolve.app.compiler import compile_shared, find_compiler
from lagsolve.errors import Issue, SpecError
from lagsolve.numeric.system import NumericSystem

__all__ = ["build_fmu", "find_compiler", "platform_folder"]

HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")


def platform_folder() -> tuple[str, str]:
    """FMI 2.0's name of this platform's binaries folder and its shared libraries' suffix."""
    bits = "64" if sys.maxsize > 2**32 else "32"
    if sys.platform.startswith("win"):
        return f"win{bits}", ".dll"
    if sys.platform == "darwin":
        return f"darwin{bits}", ".dylib"
    return f"linux{bits}", ".so"


def _start(system: NumericSystem, problem: object) -> list[float]:
    """The file's initial state completed onto the constraints (zeros where the file gives none)."""
    from lagsolve.numeric.initial import complete_initial

    spec = getattr(problem, "simulation", None)
    if spec is None or not spec.initial:
        return [0.0] * (2 * system.n)
    q, qd = complete_initial(system, spec.initial, getattr(problem, "source", ""))
    return [*q.tolist(), *qd.tolist()]


def build_fmu(system: NumericSystem, problem: object, prefix: str, header: str, code: str, output: Path,
              version: str) -> Path:
    """Compile the exported C with its FMI wrapper and write ``<prefix>.fmu`` into ``output``.

    Raises
    ------
    SpecError
        No C compiler, the compiler fails, a name XML cannot carry or two variables of one name.
    """
    from lagsolve.files import write_file
    from lagsolve.render.c_module import _number, c_comment, layout
    from lagsolve.render.fmu import guid, model_description
    from lagsolve.render.fmu_wrapper import fmi2_wrapper

    name = str(getattr(problem, "name", prefix))
    spec = getattr(problem, "simulation", None)
    start = _start(system, problem)
    identifier = guid(header, code, repr(start))
    wrapper = fmi2_wrapper(prefix, c_comment(name), c_comment(version), identifier, [_number(v) for v in start])
    try:
        xml = model_description(layout(system), prefix, name, version, identifier, start,
                                getattr(spec, "t_end", None))
    except ValueError as exc:
        raise SpecError([Issue(str(getattr(problem, "source", prefix)), 0, "export", str(exc),
                               "rename it in the problem file (names must be distinct and printable)")]) from None
    headers = {h: (resources.files("lagsolve.render") / "fmi2" / h).read_bytes() for h in HEADERS}
    licence = (resources.files("lagsolve.render") / "fmi2" / "LICENSE.txt").read_bytes()
    sources = {f"{prefix}.h": header.encode(), f"{prefix}.c": code.encode(), f"fmi2_{prefix}.c": wrapper.encode(),
               **headers}
    folder, suffix = platform_folder()
    with tempfile.TemporaryDirectory(prefix="lagsolve-fmu-") as scratch:
        work = Path(scratch)
        for file, data in sources.items():
            (work / file).write_bytes(data)
        binary = compile_shared([work / f"{prefix}.c", work / f"fmi2_{prefix}.c"], work / f"{prefix}{suffix}",
                                include=[work])
        entries = {"modelDescription.xml": xml.encode(),
                   **{f"sources/{file}": data for file, data in sources.items()},
                   "documentation/licenses/fmi2-headers.txt": licence,
                   f"binaries/{folder}/{prefix}{suffix}": binary.read_bytes()}
    return write_file(output, f"{prefix}.fmu", _zip(entries))


def _zip(entries: dict[str, bytes]) -> bytes:
    """A deflated archive of ``entries`` in name order, every entry dated 1980-01-01 with mode 0644."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in sorted(entries):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.external_attr = 0o644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, entries[name])
    return buffer.getvalue()


