"""`lagsolve derive` on bad and hostile files: exit code 2, a precise message, no traceback."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

import lagsolve.problem.load  # noqa: F401  (import SymPy before any timing starts)
from lagsolve.cli import main

#: An invalid file must be refused at once: a guard against hangs, not a benchmark.
FAST = 2.0  # CPU seconds for a refusal; a hang would take far longer

BEAD = """\
name: Bead on a wire
parameters:
  m: mass of the bead
  g: gravitational acceleration
functions:
  f: shape of the wire
coordinates: [x, y]
particles:
  bead: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  wire: {holonomic: y - f(x), on: bead}
"""


def bead_with(old: str, new: str) -> str:
    assert old in BEAD, old
    return BEAD.replace(old, new, 1)


BOMB = "".join(
    f"{name}: &{name} [" + ", ".join([f"*{prev}"] * 9 if prev else ['"lol"'] * 9) + "]\n"
    for prev, name in zip([None, *"abcdefgh"], "abcdefghi", strict=True)
)

#: (file content, line, field path or "", key phrase of the message)
BAD_FILES: list[tuple[str, str | bytes, int, str, str]] = [
    ("yaml-syntax-error", "name: x\ncoordinates: [x\nfoo: 1\n", 3, "",
     "YAML syntax error: expected ',' or ']'"),
    ("yaml-bad-indentation", bead_with("gravity: [0, -g]", " gravity: [0, -g]"), 10, "",
     "YAML syntax error: expected <block end>"),
    ("unknown-name", BEAD + "potential: k*x**2/2\n", 13, "potential",
     "unknown name 'k' at column 1"),
    ("misspelt-name", BEAD + "potential: mm*g*y\n", 13, "potential", "did you mean 'm'?"),
    ("undeclared-function", bead_with("y - f(x)", "y - h(x)"), 12, "constraints.wire.holonomic",
     "unknown function 'h' at column 5"),
    ("nonlinear-velocity-constraint",
     bead_with("holonomic: y - f(x)", "nonholonomic: x_dot**2 + y_dot"), 12,
     "constraints.wire.nonholonomic", "velocity constraint is not linear in the velocities"),
    ("velocity-in-holonomic", bead_with("y - f(x)", "y - x_dot"), 12,
     "constraints.wire.holonomic", "a holonomic constraint cannot contain velocities"),
    ("attribute-access", BEAD + "potential: m.__class__\n", 13, "potential",
     "'.' at column 2 is not allowed (attribute access)"),
    ("dunder-name", BEAD + "potential: __import__(x)\n", 13, "potential",
     "name '__import__' at column 1 is not allowed"),
    ("import-os", BEAD + "potential: \"__import__('os').system('echo pwned')\"\n", 13,
     "potential", "unexpected character \"'\" at column 12"),
    ("huge-exponent", BEAD + "potential: 9**9**9**9\n", 13, "potential",
     "exponent 3.8742e+08 of '**' at column 5 is too large"),
    ("huge-literal", BEAD + "potential: \"x*1e999999999\"\n", 13, "potential",
     "number '1e999999999' at column 3 is out of range"),
    ("exp-tower", BEAD + "potential: sin(exp(exp(exp(3))))\n", 13, "potential",
     "a constant in exp(...) at column 5 is too large to evaluate"),
    ("exp-tower-hidden", BEAD + "potential: cos(exp(exp(exp(3 + 0*x)))) + 1\n", 13, "potential",
     "too large to evaluate"),
    ("deep-parentheses-50", BEAD + "potential: " + "(" * 50 + "x" + ")" * 50 + "\n", 13,
     "potential", "expression is nested more than 40 levels deep"),
    ("deep-parentheses-100000", BEAD + "potential: " + "(" * 100_000 + "x" + ")" * 100_000 + "\n",
     13, "potential", "expression is 200001 characters long (limit 2000)"),
    ("complex-constant", BEAD + "potential: m*g*sqrt(-1)\n", 13, "potential",
     "is a complex number"),
    ("division-by-zero", BEAD + "potential: m/(1 - 1)\n", 13, "potential", "division by zero"),
    ("duplicate-coordinate", bead_with("coordinates: [x, y]", "coordinates: [x, y, x]"), 7,
     "coordinates[2]", "'x' is already declared as a coordinate"),
    ("shadowing-sin", bead_with("g: gravitational", "sin: oops\n  g: gravitational"), 4,
     "parameters.sin", "'sin' is the name of a built-in function or constant"),
    ("shadowing-pi", bead_with("coordinates: [x, y]", "coordinates: [x, y, pi]"), 7,
     "coordinates[2]", "'pi' is the name of a built-in function or constant"),
    ("parameter-x_dot", bead_with("m: mass", "x_dot: speed\n  m: mass"), 8, "coordinates[0]",
     "'x_dot' (derived from coordinate 'x') is already declared as a parameter"),
    ("cyrillic-look-alike", bead_with("mass: m,", "mass: \u043c,"), 9, "particles.bead.mass",
     "non-ASCII character '\u043c' (U+043C CYRILLIC SMALL LETTER EM) at column 1"),
    ("on-unknown-particle", bead_with("on: bead", "on: ball"), 12, "constraints.wire.on",
     "unknown particle 'ball'; known particles: bead"),
    ("position-1-component", bead_with("position: [x, y]", "position: [x]"), 9,
     "particles.bead.position", "expected a list of 2 or 3 components, found 1 components"),
    ("position-4-components", bead_with("position: [x, y]", "position: [x, y, 0, 0]"), 9,
     "particles.bead.position", "found 4 components"),
    ("gravity-wrong-length", bead_with("[0, -g]", "[0, -g, 0]"), 10, "gravity",
     "gravity has 3 components but positions have 2"),
    ("missing-name", BEAD.replace("name: Bead on a wire\n", ""), 1, "",
     "missing required key 'name'"),
    ("wrong-type", bead_with("name: Bead on a wire", "name: [a, b]"), 1, "name",
     "expected text, found a list"),
    ("unknown-key", BEAD + "gravty: [0, -g]\n", 13, "gravty",
     "unknown key 'gravty'; did you mean 'gravity'?"),
    ("duplicate-key", BEAD + "gravity: [0, g]\n", 13, "gravity",
     "duplicate key 'gravity' (first given on line 10)"),
    ("python-object-tag", bead_with("name: Bead on a wire",
                                    "name: !!python/object/apply:os.system ['echo pwned']"), 1,
     "name", "YAML tag '!!python/object/apply:os.system' is not allowed"),
    ("alias-bomb", BOMB, 1, "a", "anchors and aliases (&name, *name) are not allowed"),
    ("several-documents", BEAD + "---\n" + BEAD, 13, "", "file holds more than one YAML document"),
    ("top-level-list", "- name\n- coordinates\n", 1, "",
     "the file holds a list, not a mapping of fields"),
    ("top-level-text", "hello\n", 1, "", "the file holds a single value, not a mapping"),
    ("empty-file", "", 1, "", "file is empty"),
    ("comment-only-file", "# name: Bead\n", 1, "", "file is empty"),
    ("not-utf8", BEAD.encode() + b"description: caf\xe9\n", 13, "", "file is not UTF-8 text"),
    ("deep-yaml-nesting", "a: " + "[" * 10_000 + "]" * 10_000 + "\n", 1, "",
     "values are nested more than 24 levels deep"),
    ("terminal-escape-in-name", bead_with("name: Bead on a wire", 'name: "\\e[2J\\e[31mowned"'),
     1, "name", "text contains a control character (U+001B)"),
    ("yaml-1.1", "%YAML 1.1\n---\n" + BEAD, 2, "", "YAML 1.1 documents are not supported"),
    ("infinite-number", BEAD + "simulation:\n  t_end: .inf\n", 14, "simulation.t_end",
     ".inf is not a usable number"),
]


def write(folder: Path, name: str, content: str | bytes) -> Path:
    path = folder / name
    if isinstance(content, str):
        path.write_text(content, encoding="utf-8")
    else:
        path.write_bytes(content)
    return path


def derive(*args: str) -> tuple[Result, float]:
    start = time.process_time()
    result = CliRunner().invoke(main, ["derive", *args])
    return result, time.process_time() - start


@pytest.mark.parametrize(("content", "line", "where", "phrase"), [c[1:] for c in BAD_FILES],
                         ids=[c[0] for c in BAD_FILES])
def test_bad_file_is_refused_with_a_precise_message(tmp_path: Path, content: str | bytes,
                                                    line: int, where: str, phrase: str) -> None:
    """A bad file exits with 2 and says file:line: field: what, fast, without a traceback."""
    path = write(tmp_path, "problem.yaml", content)
    out = tmp_path / "out"
    result, cpu = derive(str(path), "-o", str(out))
    assert result.exit_code == 2, result.output
    assert cpu < FAST, f"took {cpu:.2f} s"
    place = f"error: {path}:{line}: " + (f"{where}: " if where else "")
    assert place in result.stderr, result.stderr
    assert phrase in result.stderr
    assert "Traceback" not in result.output and "Traceback" not in result.stderr
    assert result.stdout == ""
    assert not out.exists()


def test_cases_cover_enough_kinds() -> None:
    """The table holds at least twenty distinct kinds of bad file."""
    assert len({case[0] for case in BAD_FILES}) == len(BAD_FILES) >= 20


def test_every_issue_is_printed(tmp_path: Path) -> None:
    """A file with several mistakes gets one error line per mistake, in file order."""
    text = (BEAD.replace("name: Bead on a wire\n", "")
            .replace("position: [x, y]", "position: [x]")
            + "gravty: 1\n")
    path = write(tmp_path, "several.yaml", text)
    result, _ = derive(str(path))
    assert result.exit_code == 2
    prefix = f"error: {path}:"
    lines = result.stderr.splitlines()
    assert all(ln.startswith(prefix) for ln in lines)
    assert [ln.removeprefix(prefix).split(";")[0] for ln in lines] == [
        "1: missing required key 'name'",
        "8: particles.bead.position: expected a list of 2 or 3 components, found 1 components",
        "12: gravty: unknown key 'gravty'",
    ]


def test_missing_file_and_folder(tmp_path: Path) -> None:
    """A missing file or a folder exits with 2 and names the path."""
    missing = tmp_path / "nope.yaml"
    result, _ = derive(str(missing))
    assert result.exit_code == 2
    assert result.stderr == f"error: {missing}: file not found; check the path\n"
    result, _ = derive(str(tmp_path))
    assert result.exit_code == 2
    assert result.stderr == f"error: {tmp_path}: is a folder, not a problem file\n"


def test_one_bad_file_among_good_ones(tmp_path: Path) -> None:
    """Every file is tried; the bad one is reported and the exit code is 2."""
    bad = write(tmp_path, "bad.yaml", bead_with("on: bead", "on: ball"))
    also_bad = write(tmp_path, "worse.yaml", "")
    result, _ = derive(str(bad), str(also_bad), "-o", str(tmp_path / "out"))
    assert result.exit_code == 2
    assert f"error: {bad}:12: constraints.wire.on: unknown particle 'ball'" in result.stderr
    assert f"error: {also_bad}:1: file is empty" in result.stderr


def test_nothing_is_written_for_invalid_input(tmp_path: Path) -> None:
    """When the input is invalid, the output folder stays empty, in every output mode."""
    bad = write(tmp_path, "bad.yaml", BEAD + "potential: 9**9**9**9\n")
    out = tmp_path / "out"
    out.mkdir()
    for extra in ([], ["--format", "tex"], ["--format", "json", "-o", str(out / "x.json")]):
        args = [str(bad), *extra] if "-o" in extra else [str(bad), "-o", str(out), *extra]
        result, _ = derive(*args)
        assert result.exit_code == 2
        assert list(out.iterdir()) == []


HOSTILE_TEXT = BEAD.replace("name: Bead on a wire", "name: <script>alert(1)</script>").replace(
    "parameters:", "description: '\\input{/etc/passwd} \\write18{rm -rf ~} 100% $x$ & #'\n"
    "parameters:")


def test_tex_output_escapes_hostile_text(tmp_path: Path) -> None:
    """A name or description with LaTeX commands or HTML is printed escaped, never live; only its safe $...$ math
    is kept as math."""
    path = write(tmp_path, "hostile.yaml", HOSTILE_TEXT)
    result, _ = derive(str(path), "--format", "tex")
    assert result.exit_code == 0, result.output
    tex = result.stdout
    assert "\\input{/etc/passwd}" not in tex
    assert "\\write18" not in tex
    assert "\\textbackslash{}input\\{/etc/passwd\\}" in tex
    assert "<script>" not in tex
    assert "\\textless{}script\\textgreater{}" in tex
    assert "100\\% $x$ \\& \\#" in tex


def test_output_cannot_escape_the_output_folder(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    """A path like ../evil.yaml writes to DIR/evil/, never next to or above DIR."""
    work = tmp_path / "work"
    work.mkdir()
    write(tmp_path, "evil.yaml", BEAD.replace("name: Bead on a wire", "name: ../../escaped"))
    monkeypatch.chdir(work)
    result, _ = derive("../evil.yaml", "-o", "out")
    assert result.exit_code == 0, result.output
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")
                     if p.is_file())
    assert written == ["evil.yaml", "work/out/evil/evil.json", "work/out/evil/evil.md",
                       "work/out/evil/evil.tex"]


PENDULUM = """\
name: Pendulum in Cartesian coordinates
parameters: {m: mass, g: gravity, L: length}
coordinates: [x, y]
particles:
  bob: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  rod: {holonomic: CONSTRAINT}
"""


@pytest.mark.parametrize("command", ["derive", "check", "simulate"])
def test_degenerate_constraint_exits_2_with_the_fix(tmp_path: Path, command: str) -> None:
    """(x² + y² − L²)² = 0 would give 0/0 accelerations: every command refuses it with file, line, field and the
    constraint to write instead."""
    path = write(tmp_path, "rod.yaml", PENDULUM.replace("CONSTRAINT", "(x**2 + y**2 - L**2)**2"))
    result = CliRunner().invoke(main, [command, str(path), "-o", str(tmp_path / "out")] if command != "check"
                                else [command, str(path)])
    assert result.exit_code == 2, result.output
    assert result.stderr == (f"error: {path}:8: constraints.rod.holonomic: the gradient of rod vanishes where rod = 0; "
                             "write it as x**2 + y**2 - L**2 = 0\n")
    assert "Traceback" not in result.output


def test_redundant_constraints_exit_2_naming_them(tmp_path: Path) -> None:
    """The rod given twice (once scaled) is redundant: exit 2, both constraints named, the second to remove."""
    text = PENDULUM.replace("CONSTRAINT", "x**2 + y**2 - L**2") + "  rod_again: {holonomic: 2*x**2 + 2*y**2 - 2*L**2}\n"
    path = write(tmp_path, "twice.yaml", text)
    result, _ = derive(str(path), "-o", str(tmp_path / "out"))
    assert result.exit_code == 2, result.output
    assert f"error: {path}:9: constraints.rod_again.holonomic: the constraints rod, rod_again are redundant" \
        in result.stderr
    assert "remove rod_again" in result.stderr


ROUGH_WEDGE = (Path(__file__).resolve().parents[2] / "problems" / "rough_wedge.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize(("rub", "field"), [
    ("{coefficient: mu, normal: [face], on: []}", "friction.rub.on"),
    ("{coefficient: mu, normal: [face], on: [wedge, block]}", "friction.rub.normal"),
    ("{coefficient: mu, normal: [face], on: [block, wedge, block]}", "friction.rub.on"),
    ("{coefficient: mu, normal: [face], on: [block, ghost]}", "friction.rub.on"),
    ("{coefficient: mu, normal: [face], at: [x, 2*y]}", "friction.rub.at"),
    ("{coefficient: mu, normal: [face], at: {x: 1}}", "friction.rub.at"),
    ("{coefficient: mu, on: block, normal: [face]}\n  other: {coefficient: mu, on: wedge, normal: [face]}",
     "friction.other.normal"),
    ("{coefficient: -1, normal: [face]}", "friction.rub.coefficient"),
    ("{coefficient: mu, normal: [ghost]}", "friction.rub.normal[0]"),
])
def test_a_friction_contact_that_cannot_be_modelled_exits_2(tmp_path: Path, rub: str, field: str) -> None:
    """Hostile or impossible friction contacts: exit 2 with file, line and field, never a traceback, nothing
    written."""
    text = ROUGH_WEDGE.replace("rub: {coefficient: mu, normal: [face]}", f"rub: {rub}")
    path = write(tmp_path, "contact.yaml", text)
    result, _ = derive(str(path), "-o", str(tmp_path / "out"))
    assert result.exit_code == 2, result.output
    assert f"error: {path}:" in result.stderr and f": {field}: " in result.stderr, result.stderr
    assert "Traceback" not in result.output and "Traceback" not in result.stderr
    assert not (tmp_path / "out").exists()
