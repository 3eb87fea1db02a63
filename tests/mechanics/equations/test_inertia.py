"""Negative masses and coordinates without inertia (lagsolve.mechanics.equations.inertia) are refused with a fix, before
anything is solved; massless parts that leave every coordinate determined pass."""

from __future__ import annotations

import subprocess
import sys

import pytest

from lagsolve.errors import SpecError
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.problem.load import load_text
from mechanics_support import PROBLEMS

BASE = """\
name: Masses
parameters: {m: mass, M: other mass, k: stiffness}
coordinates: [x, y]
particles:
  a: {mass: MASS_A, position: [x, 0]}
  b: {mass: MASS_B, position: [y, 1]}
potential: k*(y - x)**2/2
"""


def refused(text: str) -> tuple:
    with pytest.raises(SpecError) as caught:
        matrix_form(load_text(text, "p.yaml"))
    return caught.value.issues


def test_a_negative_mass_is_refused_at_its_field() -> None:
    (issue,) = refused(BASE.replace("MASS_A", "-m").replace("MASS_B", "M"))
    assert (issue.file, issue.line, issue.where) == ("p.yaml", 5, "particles.a.mass")
    assert "negative" in issue.message and "positive" in issue.hint


def test_a_negative_moment_of_inertia_is_refused() -> None:
    text = """\
name: Wheel
parameters: {m: mass, R: radius}
coordinates: [phi]
bodies:
  wheel: {mass: m, position: [0, 0], inertia: -m*R**2/2, angular_velocity: phi_dot}
"""
    (issue,) = refused(text)
    assert issue.where == "bodies.wheel.inertia" and issue.line == 5


def test_a_coordinate_without_inertia_is_refused_with_a_fix() -> None:
    """Both masses on x: y has no kinetic energy and no constraint, so its acceleration is undetermined (this
    used to exit 1 with 'the augmented system is singular' and no file, line or field)."""
    (issue,) = refused(BASE.replace("MASS_A", "m").replace("MASS_B", "0"))
    assert (issue.where, issue.line) == ("coordinates[1]", 3)
    assert "no inertia" in issue.message and "remove y" in issue.hint


def test_massless_parts_that_leave_every_coordinate_determined_pass() -> None:
    """A massless particle carried by a constraint (an ideal string's end), and a massless particle on a
    coordinate that also carries mass elsewhere, are fine models."""
    text = """\
name: Bead pulled by a massless ring
parameters: {m: mass, g: gravity}
coordinates: [x, s]
particles:
  bead: {mass: m, position: [x, 0]}
  ring: {mass: 0, position: [s, 0]}
gravity: [0, -g]
constraints:
  string: {holonomic: s - x}
"""
    form = matrix_form(load_text(text, "p.yaml"))
    assert form.lagrange.mass_matrix[1, 1] == 0


@pytest.mark.parametrize("name", sorted(p.stem for p in PROBLEMS.glob("*.yaml")))
def test_shipped_problems_pass(name: str) -> None:
    path = PROBLEMS / f"{name}.yaml"
    matrix_form(load_text(path.read_text(), str(path)), display=False)


def test_cli_exit_code_2_with_file_line_and_field(tmp_path) -> None:  # noqa: ANN001
    path = tmp_path / "neg.yaml"
    path.write_text(BASE.replace("MASS_A", "m").replace("MASS_B", "-M"))
    done = subprocess.run([sys.executable, "-m", "lagsolve", "derive", str(path), "-o", str(tmp_path / "out")],
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert f"{path}:6: particles.b.mass: the mass -M is negative" in done.stderr
    assert "Traceback" not in done.stderr
