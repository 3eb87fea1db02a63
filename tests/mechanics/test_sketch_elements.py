"""Every shipped problem's sketch lists its elements (``Geometry.elements``): what a student must see to recognise
the system, decided from the problem (issue 29, items 1, 2 and 7). A new problem in problems/ needs its row here."""

from __future__ import annotations

from pathlib import Path

import pytest

from lagsolve.api import load_problem
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.mechanics.geometry.shapes import sketch

ROOT = Path(__file__).resolve().parents[2]

#: (kind, label, members) of each element; arrows are the forces of constraint and friction, one per member
ELEMENTS: dict[str, set[tuple[str, str, tuple[str, ...]]]] = {
    "atwood": {
        ("arrow constraint", "string", ("m1",)),
        ("arrow constraint", "string", ("m2",)),
        ("string", "string", ("m1", "m2")),
    },
    "bead": {
        ("arrow constraint", "wire", ("bead",)),
        ("wire", "wire", ("bead",)),
    },
    "bead_on_rotating_hoop": {
        ("arrow constraint", "drive", ("bead",)),
        ("moving wire", "drive", ("bead",)),
    },
    "block_two_pendulums": {
        ("body bar", "compound", ("block",)),
        ("rod", "", ("block", "bob")),
        ("support", "surface under block", ("block",)),
    },
    "bowl": {
        ("arrow constraint", "bowl", ("particle",)),
        ("revolution", "bowl", ("particle",)),
    },
    "cart_two_wheels": {
        ("body disc", "front", ()),
        ("body disc", "rear", ()),
        ("rod", "axle1", ("front", "cart")),
        ("rod", "axle2", ("rear", "cart")),
        ("surface", "roll1", ("front",)),
        ("surface", "roll2", ("rear",)),
    },
    "central_force": {
        ("centre", "centre (-k/r)", ("fixed", "planet")),
    },
    "charged_ring": {
        ("arrow constraint", "plane", ("bead",)),
        ("arrow constraint", "ring", ("bead",)),
        ("wire", "ring, plane", ("bead",)),
    },
    "cone": {
        ("arrow constraint", "cone", ("p",)),
        ("revolution", "cone", ("p",)),
    },
    "coupled_pendulums": {
        ("pivot", "", ()),
        ("rod", "", ("pivot", "bob1")),
        ("rod", "", ("pivot", "bob2")),
        ("spring", "spring", ("bob1", "bob2")),
    },
    "disc_on_cylinder": {
        ("arrow constraint", "roll", ("disc",)),
        ("arrow constraint", "surface", ("disc",)),
        ("body disc", "disc", ()),
        ("solid", "surface", ("disc",)),
    },
    "differential_drive": {  # seen from above; the axle's no-slip constraint turns with the cart: no line to roll on
        ("body plate", "chassis", ()),
        ("body plate", "left", ()),
        ("body plate", "right", ()),
        # the axle's sideways velocity is each wheel's: both wheels are knife edges along the heading
        ("blade", "lateral", ("left",)),
        ("blade", "lateral", ("right",)),
        # one frame: the axle between the wheels (the spine), the chassis joined at its foot on it (the midpoint)
        ("rod", "", ("right", "left")),
        ("rod", "", ("pivot", "chassis")),
        ("pivot", "", ()),
    },
    "double_pendulum": {
        ("pivot", "", ()),
        ("rod", "", ("pivot", "upper")),
        ("rod", "", ("upper", "lower")),
    },
    "driven_oscillator": {
        ("damper", "damper (b*x_dot**2/2)", ("fixed", "x")),
        ("marker", "x", ()),
        ("spring", "spring (k*x**2/2)", ("fixed", "x")),
    },
    "heavy_top": {
        ("body top", "top", ("pivot",)),
        ("pivot", "", ()),
        ("rod", "", ("pivot", "top")),
    },
    "hole_table": {
        ("arrow constraint", "string", ("m1",)),
        ("arrow constraint", "string", ("m2",)),
        ("string", "string", ("m1", "m2")),
        ("support", "surface under m1", ("m1",)),
    },
    "incline_cartesian": {
        ("arrow constraint", "plane", ("block",)),
        ("arrow friction", "rough", ("block",)),
        ("surface", "plane", ("block",)),
    },
    "incline_pulley": {
        ("arrow constraint", "plane", ("block",)),
        ("arrow constraint", "string", ("block",)),
        ("arrow constraint", "string", ("weight",)),
        ("arrow friction", "rough", ("block",)),
        ("string", "string", ("block", "weight")),
        ("surface", "plane", ("block",)),
    },
    "multidof_holonomic": {  # the bob hangs by its rod from a joint at the bar's lower end
        ("body bar", "pendulum", ("block",)),
        ("pivot", "", ()),
        ("rod", "", ("pivot", "bob")),
        ("damper", "damper (c*q1_dot**2/2)", ("fixed", "block")),
        ("spring", "spring (k*q1**2/2)", ("fixed", "block")),
        ("support", "surface under block", ("block",)),
    },
    "knife_edge": {
        ("arrow constraint", "skate", ("p1",)),
        ("blade", "skate", ("p1",)),
        ("rod", "", ("p1", "p2")),
    },
    "ladder_rough_floor": {
        ("arrow constraint", "floor", ("foot",)),
        ("arrow constraint", "rod", ("foot",)),
        ("arrow constraint", "rod", ("top",)),
        ("arrow constraint", "wall", ("top",)),
        ("arrow friction", "rough", ("foot",)),
        ("rod", "rod", ("top", "foot")),
        ("surface", "floor", ("foot",)),
        ("surface", "wall", ("top",)),
    },
    "moving_support": {
        ("arrow constraint", "drive", ("support",)),
        ("rod", "", ("support", "bob")),
        ("support", "surface under support", ("support",)),
    },
    "pendulum_cartesian": {
        ("arrow constraint", "rod", ("bob",)),
        ("pivot", "", ()),
        ("rod", "rod", ("pivot", "bob")),
    },
    "physical_pendulum": {
        ("arrow constraint", "axle_x", ("body",)),
        ("arrow constraint", "axle_y", ("body",)),
        ("body bar", "body", ("pivot",)),
        ("pivot", "", ()),
    },
    "rolling_coin": {
        ("body disc", "coin", ()),
    },
    "rolling_disc": {
        ("body disc", "disc", ()),
    },
    "rolling_incline": {
        ("arrow constraint", "roll", ("disk",)),
        ("body disc", "disk", ()),
        ("surface", "", ("disk",)),
    },
    "rotating_tube": {
        ("arrow constraint", "spin", ("bead",)),
        ("arrow constraint", "tilt", ("bead",)),
        ("arrow friction", "wall", ("bead",)),
        ("moving wire", "tilt, spin", ("bead",)),
    },
    "rough_circular_wire": {
        ("arrow constraint", "wire", ("bead",)),
        ("arrow friction", "rub", ("bead",)),
        ("wire", "wire", ("bead",)),
    },
    "rough_disc_incline": {
        ("arrow constraint", "surface", ("disc",)),
        ("arrow friction", "grip", ("disc",)),
        ("body disc", "disc", ()),
        ("surface", "surface", ("disc",)),
    },
    "rough_incline": {
        ("arrow constraint", "surface", ("block",)),
        ("arrow friction", "contact", ("block",)),
        ("surface", "surface", ("block",)),
    },
    "rough_wedge": {
        ("arrow constraint", "face", ("block",)),
        ("arrow constraint", "face", ("wedge",)),
        ("arrow friction", "rub", ("block",)),
        ("arrow friction", "rub", ("wedge",)),
        ("support", "surface under wedge", ("wedge",)),
        ("surface", "face", ("block", "wedge")),
    },
    "sliding_off_sphere": {
        ("arrow constraint", "surface", ("p",)),
        ("solid", "surface", ("p",)),
    },
    "spherical_pendulum_cartesian": {
        ("arrow constraint", "rod", ("bob",)),
        ("pivot", "", ()),
        ("rod", "rod", ("pivot", "bob")),
    },
    "spherical_pendulum": {
        ("pivot", "", ()),
        ("rod", "", ("pivot", "bob")),
    },
    "spring_damper": {
        ("arrow constraint", "floor", ("block",)),
        ("damper", "damper (c*x_dot**2/2)", ("fixed", "block")),
        ("spring", "spring (k*x**2/2)", ("fixed", "block")),
        ("surface", "floor", ("block",)),
    },
    "spring_on_rough_floor": {
        ("arrow constraint", "floor", ("block",)),
        ("arrow friction", "rough", ("block",)),
        ("spring", "spring (k*x**2/2)", ("fixed", "block")),
        ("surface", "floor", ("block",)),
    },
    "stacked_blocks": {
        ("arrow constraint", "floor", ("lower",)),
        ("arrow constraint", "top", ("lower",)),
        ("arrow constraint", "top", ("upper",)),
        ("arrow friction", "between", ("lower",)),
        ("arrow friction", "between", ("upper",)),
        ("arrow friction", "ground", ("lower",)),
        ("surface", "floor", ("lower",)),
        ("surface", "top", ("upper", "lower")),
    },
    "triple_pendulum": {
        ("pivot", "", ()),
        ("rod", "", ("middle", "lower")),
        ("rod", "", ("pivot", "upper")),
        ("rod", "", ("upper", "middle")),
    },
    "turntable": {
        ("arrow constraint", "motor", ("bead",)),
        ("moving wire", "motor", ("bead",)),
        ("pivot", "", ()),
        ("spring", "spring (k*(r - r0)**2/2)", ("fixed", "bead")),
    },
    "two_masses_spring": {
        ("spring", "spring (k*(-L0 - x1 + x2)**2/2)", ("m1", "m2")),
    },
    "wedge": {
        ("arrow constraint", "floor", ("wedge",)),
        ("arrow constraint", "incline", ("block",)),
        ("arrow constraint", "incline", ("wedge",)),
        ("surface", "floor", ("wedge",)),
        ("surface", "incline", ("block", "wedge")),
    },
    "wedge_cylinder": {
        ("arrow constraint", "roll", ("cyl",)),
        ("arrow constraint", "roll", ("wedge",)),
        ("body disc", "cyl", ()),
        ("support", "surface under wedge", ("wedge",)),
        ("surface", "", ("cyl", "wedge")),
    },
}


def test_every_shipped_problem_has_its_row() -> None:
    assert sorted(p.stem for p in (ROOT / "problems").glob("*.yaml")) == sorted(ELEMENTS)


@pytest.mark.parametrize("name", sorted(ELEMENTS))
def test_the_sketch_has_the_elements_of_the_problem(name: str) -> None:
    form = matrix_form(load_problem(ROOT / "problems" / f"{name}.yaml"), display=False)
    assert set(sketch(form).elements()) == ELEMENTS[name]

