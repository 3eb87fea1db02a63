"""Loading and validating problem files: every section of the format, and every issue at once."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest
import sympy

from lagsolve.errors import Issue, SpecError
from lagsolve.problem.load import load_problem, load_text
from lagsolve.problem.schema import Problem

ROOT = Path(__file__).resolve().parents[2]
SOURCE = "p.yaml"

FULL = """\
name: Everything at once
description: >
  A made-up problem that uses every section of the format.
time: t
parameters:
  m: mass of the bead
  M: {description: mass of the top, positive: true, value: 2.0}
  g: gravitational acceleration
  k: {description: spring constant}
  c: damping coefficient
  F0: {description: force amplitude, positive: false, real: true}
  w: driving frequency
  mu: friction coefficient
  I1: transverse moment of inertia
  I3: axial moment of inertia
functions:
  f: shape of the wire
coordinates:
  x: position along the wire
  y: {description: height, positive: false}
  phi: spin angle of the top
particles:
  bead: {mass: m, position: [x, y, 0]}
bodies:
  top: {mass: M, position: [x, 0, 0], inertia: [I1, I1, I3], angular_velocity: [0, 0, phi_dot]}
gravity: [0, -g, 0]
kinetic: I1*phi_dot^2/2
potential: k*x**2/2
dissipation: c*x_dot**2/2
forces:
  - {coordinate: x, value: -c*x_dot}
  - {on: bead, force: ["F0*cos(w*t)", 0, 0]}
constraints:
  wire: {holonomic: y - f(x), on: bead}
  roll: {nonholonomic: x_dot - phi_dot}
friction:
  wall:
    coefficient: mu
    static: 2*mu
    on: bead
    normal: [wire]
    sliding: [x]
expected:
  accelerations: {x: "-g*Derivative(f(x), x)"}
  multipliers: {wire: "m*g"}
  constraint_forces: {wire: {magnitude: "m*g", vector: [0, "m*g", 0]}, roll: "0"}
  conserved: {energy: "m*x_dot**2/2"}
  reduced: {independent: [x], accelerations: {x: "0"}}
  effective_potential:
    coordinate: x
    expression: k*x**2/2
    equilibria: [{value: 0, stable: true, frequency: "sqrt(k/m)"}]
  normal_modes:
    - at: {x: 0, phi: pi}
      stable: false
      squared_frequencies: [k/m, "-g/M"]
      shapes: [[1, 0, 1], [0, 1, "k/M"]]
simulation:
  values: {m: 1.0, g: 9.81, k: 2, c: 0.1, F0: 1, w: 1, mu: 0.1, I1: 1, I3: 1}
  functions: {"f(u)": "u**2/2"}
  initial: {x: -1.5, x_dot: 0.0}
  t_end: 10.0
  samples: 200
  method: RK45
  rtol: 1e-8
  atol: 1e-10
"""

BEAD = """\
name: Bead
parameters:
  m: mass
  g: gravity
functions:
  f: shape
coordinates: [x, y]
particles:
  bead: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  wire: {holonomic: y - f(x), on: bead}
"""


def load(text: str) -> Problem:
    return load_text(text, SOURCE)


def issues_of(text: str) -> tuple[Issue, ...]:
    start = time.perf_counter()
    with pytest.raises(SpecError) as caught:
        load(text)
    assert time.perf_counter() - start < 2.0
    return caught.value.issues


def bead_with(old: str, new: str) -> str:
    assert old in BEAD, old
    return BEAD.replace(old, new, 1)


# ------------------------------------------------------------------------------------------
# a valid problem using every section


@pytest.fixture(scope="module")
def full() -> Problem:
    return load(FULL)


def test_full_problem_header(full: Problem) -> None:
    """Name, description, time and source are read as written."""
    assert full.name == "Everything at once"
    assert full.description == "A made-up problem that uses every section of the format."
    assert full.time == sympy.Symbol("t", real=True)
    assert full.source == SOURCE and full.slug == "p"


def test_full_problem_parameters(full: Problem) -> None:
    """Parameters in both forms keep their description, assumptions and default value."""
    names = [p.name for p in full.parameters]
    assert names == ["m", "M", "g", "k", "c", "F0", "w", "mu", "I1", "I3"]
    top = full.parameters[1]
    assert (top.description, top.positive, top.value) == ("mass of the top", True, 2.0)
    assert top.symbol.is_positive
    force = full.parameters[5]
    assert (force.positive, force.real, force.value) == (False, True, None)
    assert force.symbol.is_real and force.symbol.is_positive is None
    assert full.parameters[0].description == "mass of the bead"


def test_full_problem_functions_and_coordinates(full: Problem) -> None:
    """Functions become SymPy functions; coordinates get velocity and acceleration symbols."""
    assert [(fn.name, fn.description) for fn in full.functions] == [("f", "shape of the wire")]
    assert [c.name for c in full.coordinates] == ["x", "y", "phi"]
    x = full.coordinates[0]
    assert (str(x.velocity), str(x.acceleration)) == ("x_dot", "x_ddot")
    assert x.description == "position along the wire"
    assert full.coordinates[1].description == "height"
    assert set(full.symbols) == {"t", "m", "M", "g", "k", "c", "F0", "w", "mu", "I1", "I3",
                                 "x", "x_dot", "y", "y_dot", "phi", "phi_dot"}


def test_full_problem_particles_bodies_gravity(full: Problem) -> None:
    """Particles and 3-D bodies carry parsed masses, positions, inertias and rates."""
    s = full.symbols
    (bead,) = full.particles
    assert (bead.name, bead.mass, bead.position) == ("bead", s["m"], (s["x"], s["y"], 0))
    (top,) = full.bodies
    assert not top.planar
    assert top.inertia == (s["I1"], s["I1"], s["I3"])
    assert top.angular_velocity == (0, 0, s["phi_dot"])
    assert full.gravity == (0, -s["g"], 0)


def test_full_problem_energies_and_forces(full: Problem) -> None:
    """Kinetic, potential and dissipation expressions and both kinds of force are parsed."""
    s = full.symbols
    assert full.kinetic == s["I1"] * s["phi_dot"] ** 2 / 2
    assert full.potential == s["k"] * s["x"] ** 2 / 2
    assert full.dissipation == s["c"] * s["x_dot"] ** 2 / 2
    generalized, physical = full.forces
    assert (generalized.coordinate, generalized.on, generalized.value) == (
        "x", None, (-s["c"] * s["x_dot"],))
    assert (physical.coordinate, physical.on) == (None, "bead")
    assert physical.value == (s["F0"] * sympy.cos(s["w"] * s["t"]), 0, 0)


def test_full_problem_constraints_and_friction(full: Problem) -> None:
    """Both kinds of constraint load with their particle and line; friction names its parts."""
    s = full.symbols
    f = full.functions[0].function
    wire, roll = full.constraints
    assert (wire.kind, wire.expression, wire.on, wire.line) == (
        "holonomic", s["y"] - f(s["x"]), ("bead",), 34)
    # `on` defaults to the only particle
    assert (roll.kind, roll.expression, roll.on) == (
        "nonholonomic", s["x_dot"] - s["phi_dot"], ("bead",))
    (wall,) = full.friction
    assert (wall.coefficient, wall.static, wall.on, wall.normal, wall.sliding) == (
        s["mu"], 2 * s["mu"], "bead", ("wire",), ("x",))


def test_full_problem_expected_answers(full: Problem) -> None:
    """Every kind of expected answer is parsed with the names the results use."""
    s = full.symbols
    f = full.functions[0].function
    expected = full.expected
    assert expected.accelerations == {"x": -s["g"] * sympy.Derivative(f(s["x"]), s["x"])}
    assert expected.multipliers == {"wire": s["m"] * s["g"]}
    assert expected.constraint_forces["wire"]["vector"] == (0, s["m"] * s["g"], 0)
    assert expected.constraint_forces["roll"] == {"magnitude": 0}
    assert expected.conserved == {"energy": s["m"] * s["x_dot"] ** 2 / 2}
    assert expected.reduced == {"x": 0}
    potential = expected.effective_potential
    assert potential is not None and potential["coordinate"] == "x"
    assert potential["equilibria"] == (
        {"value": 0, "stable": True, "frequency": sympy.sqrt(s["k"] / s["m"])},)
    (modes,) = expected.normal_modes
    assert modes["at"] == {"x": 0, "phi": sympy.pi} and modes["stable"] is False
    assert modes["squared_frequencies"] == (s["k"] / s["m"], -s["g"] / s["M"])
    assert modes["shapes"] == ((1, 0, 1), (0, 1, s["k"] / s["M"]))
    assert not expected.is_empty()


def test_full_problem_simulation(full: Problem) -> None:
    """Simulation defaults are numbers; concrete functions keep their placeholder."""
    sim = full.simulation
    assert sim is not None
    assert sim.values["g"] == 9.81 and sim.values["k"] == 2.0
    assert sim.initial == {"x": -1.5, "x_dot": 0.0}
    (t_end, samples, method, rtol, atol) = (sim.t_end, sim.samples, sim.method, sim.rtol, sim.atol)
    assert (t_end, samples, method, rtol, atol) == (10.0, 200, "RK45", 1e-8, 1e-10)
    shape = sim.functions["f"]
    (u,) = shape.arguments
    assert shape.expression == u**2 / 2


def test_full_problem_lines(full: Problem) -> None:
    """The problem keeps the line of every field for later messages."""
    assert full.lines["name"] == 1
    assert full.lines["constraints.wire.holonomic"] == 34
    assert full.lines["friction.wall.normal"] == 41
    assert full.lines["simulation.atol"] == 66


def test_planar_body() -> None:
    """A body with scalar inertia and angular velocity is planar."""
    problem = load("""\
name: Rolling disk
parameters: [M, R, J, g]
coordinates: [X, phi]
bodies:
  disk: {mass: M, position: [X, R], inertia: J, angular_velocity: phi_dot}
gravity: [0, -g]
constraints:
  rolling: {nonholonomic: X_dot - R*phi_dot}
""")
    (disk,) = problem.bodies
    s = problem.symbols
    assert disk.planar and disk.inertia == (s["J"],) and disk.angular_velocity == (s["phi_dot"],)
    assert problem.constraints[0].on == ()


DISK = """\
name: Rolling disk
parameters: [M, R, J, g]
coordinates: [X, Y, phi]
bodies:
  disk: {mass: M, position: [X, Y], inertia: J, angular_velocity: -phi_dot}
gravity: [0, -g]
constraints:
  rolling: CONSTRAINT
"""


def test_constraint_on_a_body_at_a_point() -> None:
    """'on: disk' with 'at: [X, Y - R]' names the point of the body where the constraint acts."""
    problem = load(DISK.replace("CONSTRAINT", "{holonomic: X - R*phi, on: disk, at: [X, Y - R]}"))
    (c,) = problem.constraints
    s = problem.symbols
    assert c.on == ("disk",) and c.at == (s["X"], s["Y"] - s["R"])


@pytest.mark.parametrize(("constraint", "field", "words"), [
    ("{holonomic: X - R*phi, on: disk}", "constraints.rolling.on", "needs the point where it acts"),
    ("{holonomic: X - R*phi, at: [X, Y - R]}", "constraints.rolling.on", "'on:' must name that body"),
    ("{holonomic: X - R*phi, on: disk, at: [X, Y, 0]}", "constraints.rolling.at", "has 3 components"),
    ("{holonomic: X - R*phi, on: disk, at: [X, Y - X_dot]}", "constraints.rolling.at[1]", "velocities"),
])
def test_bad_contact_points_are_refused(constraint: str, field: str, words: str) -> None:
    """A point without its body, a body without its point, a point of the wrong size or one that moves with the
    velocities: each is refused with the field and a fix."""
    issues = issues_of(DISK.replace("CONSTRAINT", constraint))
    assert any(i.where == field and words in i.message for i in issues), issues
    assert all(i.line > 0 for i in issues)


WEDGE_AND_CYLINDER = """\
name: Cylinder on a wedge
parameters: [M, m, R, g, alpha]
coordinates: [X, s, phi]
particles:
  wedge: {mass: M, position: [X, 0]}
bodies:
  cyl: {mass: m, position: [X + s*cos(alpha), -s*sin(alpha)], inertia: m*R**2/2, angular_velocity: -phi_dot}
gravity: [0, -g]
constraints:
  roll: {holonomic: s - R*phi, on: ON, at: [X + s*cos(alpha) - R*sin(alpha), -s*sin(alpha) - R*cos(alpha)]}
"""


def test_a_body_pressing_on_a_second_one_is_named_after_it() -> None:
    """'on: [cyl, wedge]' with 'at:': the body the point belongs to, then the particle (or planar body) it
    presses on; a one-name list is the body alone."""
    assert load(WEDGE_AND_CYLINDER.replace("ON", "[cyl, wedge]")).constraints[0].on == ("cyl", "wedge")
    assert load(WEDGE_AND_CYLINDER.replace("ON", "[cyl]")).constraints[0].on == ("cyl",)


@pytest.mark.parametrize(("on", "words", "field"), [
    ("[cyl, table]", "'table'", "on"), ("[cyl, wedge, wedge]", "at most one", "on"),
    ("[cyl, cyl]", "'cyl', 'cyl'", "on"), ("[wedge, cyl]", "'wedge' is a particle, a point", "at"),
    ("[cyl, 3]", "write on: [cyl, OTHER]", "on"), ("[ghost, cyl]", "must name that body or particle", "on"),
])
def test_bad_pairs_of_a_contact_are_refused(on: str, words: str, field: str) -> None:
    """An unknown second name, three names, the body twice, a particle first whose position is not the point, a
    number or an unknown first name: exit 2, field, fix."""
    issues = issues_of(WEDGE_AND_CYLINDER.replace("ON", on))
    assert any(i.where == f"constraints.roll.{field}" and words in i.message + i.hint for i in issues), issues
    assert all(i.line > 0 for i in issues)


def test_a_point_of_a_3d_body_is_refused_with_the_alternative() -> None:
    """'at:' is for planar bodies: a 3-D body's point is refused, and the fix says what is reported without it."""
    text = """\
name: Top
parameters: [M, I1, I3, g, l]
coordinates: [theta, phi, psi]
bodies:
  top: {mass: M, position: [0, 0, l*cos(theta)], inertia: [I1, I1, I3], angular_velocity: [theta_dot, phi_dot, psi_dot]}
constraints:
  tip: {holonomic: theta - 1, on: top, at: [0, 0, 0]}
"""
    issues = issues_of(text)
    assert any(i.where == "constraints.tip.at" and "3-D body" in i.message and "generalized" in i.hint
               for i in issues), issues


def test_seed_problems_load() -> None:
    """Every problem shipped in problems/ is valid."""
    paths = sorted((ROOT / "problems").glob("*.yaml"))
    assert paths
    for path in paths:
        assert load_problem(path).name


def test_load_text_accepts_text_and_bytes() -> None:
    """load_text takes the YAML as str or as UTF-8 bytes."""
    assert load_text(BEAD, SOURCE).name == load_text(BEAD.encode(), SOURCE).name == "Bead"


# ------------------------------------------------------------------------------------------
# invalid problems: (text, number of issues, line, field path, message fragment)

INVALID = [
    ("missing-name", BEAD.replace("name: Bead\n", ""), 1, 1, "",
     "missing required key 'name'; add 'name: ...'"),
    ("missing-coordinates", BEAD.replace("coordinates: [x, y]\n", "", 1), 4, 1, "",
     "missing required key 'coordinates'; add 'coordinates: ...'"),
    ("empty-coordinates", bead_with("coordinates: [x, y]", "coordinates: []"), 4, 7, "coordinates",
     "no coordinates given; list at least one, e.g. [x, y]"),
    ("name-is-a-list", bead_with("name: Bead", "name: [a, b]"), 1, 1, "name",
     "expected text, found a list"),
    ("name-two-lines", bead_with("name: Bead", 'name: "a\\nb"'), 1, 1, "name",
     "expected one non-empty line of text"),
    ("name-empty", bead_with("name: Bead", "name:"), 1, 1, "name", "expected text, found nothing"),
    ("mass-is-a-list", bead_with("mass: m", "mass: [m]"), 1, 9, "particles.bead.mass",
     "expected an expression (text or number), found list"),
    ("gravity-is-text", bead_with("[0, -g]", "down"), 1, 10, "gravity",
     "expected a list of 2 or 3 components, found text 'down'"),
    ("unknown-top-key", BEAD + "gravty: [0, -g]\n", 1, 13, "gravty",
     "unknown key 'gravty'; did you mean 'gravity'?"),
    ("unknown-particle-key", bead_with("mass: m,", "mas: m,"), 2, 9, "particles.bead.mas",
     "unknown key 'mas'; did you mean 'mass'?"),
    ("unknown-parameter-key", bead_with("m: mass", "m: {descripton: mass}"), 1, 3,
     "parameters.m.descripton", "unknown key 'descripton'; did you mean 'description'?"),
    ("duplicate-coordinate", bead_with("coordinates: [x, y]", "coordinates: [x, y, x]"), 1, 7,
     "coordinates[2]", "'x' is already declared as a coordinate; give each name once"),
    ("coordinate-clashes-with-parameter", bead_with("m: mass", "m: mass\n  x: oops"), 1, 8,
     "coordinates[0]", "'x' is already declared as a parameter"),
    ("shadows-sin", bead_with("m: mass", "m: mass\n  sin: oops"), 1, 4, "parameters.sin",
     "'sin' is the name of a built-in function or constant; choose another name"),
    ("shadows-pi", bead_with("coordinates: [x, y]", "coordinates: [x, y, pi]"), 1, 7,
     "coordinates[2]", "'pi' is the name of a built-in function or constant"),
    ("shadows-E", bead_with("m: mass", "m: mass\n  E: energy"), 1, 4, "parameters.E",
     "'E' is the name of a built-in function or constant"),
    ("shadows-time", bead_with("m: mass", "m: mass\n  t: time"), 1, 4, "parameters.t",
     "'t' is already declared as the time"),
    ("parameter-x_dot", bead_with("m: mass", "m: mass\n  x_dot: oops"), 1, 8, "coordinates[0]",
     "'x_dot' (derived from coordinate 'x') is already declared as a parameter; "
     "rename one of them"),
    ("multiplier-name", bead_with("m: mass", "m: mass\n  lambda_wire: oops"), 1, 4,
     "parameters.lambda_wire", "'lambda_wire' is reserved for Lagrange multipliers"),
    ("momentum-name", bead_with("m: mass", "m: mass\n  p_x: oops"), 1, 4,
     "parameters.p_x", "'p_x' is the name lagsolve gives the momentum conjugate to coordinate 'x'"),
    ("keyword-coordinate", bead_with("[x, y]", "[x, lambda]"), 3, 7, "coordinates[1]",
     "'lambda' is a Python keyword"),
    ("cyrillic-coordinate", bead_with("[x, y]", "[x, \u0443]"), 3, 7, "coordinates[1]",
     "non-ASCII character '\u0443' (U+0443 CYRILLIC SMALL LETTER U) in name"),
    ("cyrillic-in-expression", bead_with("mass: m", "mass: \u0430"), 1, 9, "particles.bead.mass",
     "non-ASCII character '\u0430' (U+0430 CYRILLIC SMALL LETTER A) at column 1"),
    ("unknown-name", BEAD + "potential: k*x**2/2\n", 1, 13, "potential",
     "unknown name 'k' at column 1 (known: g, m, t, x, x_dot, y, y_dot)"),
    ("undeclared-function", bead_with("y - f(x)", "y - h(x)"), 1, 12,
     "constraints.wire.holonomic", "unknown function 'h' at column 5; declare it under functions"),
    ("function-without-call", BEAD + "potential: f\n", 1, 13, "potential",
     "function 'f' at column 1 is used without arguments"),
    ("attribute-access", BEAD + "potential: m.__class__\n", 1, 13, "potential",
     "'.' at column 2 is not allowed (attribute access)"),
    ("dunder-import", BEAD + "potential: __import__(x)\n", 1, 13, "potential",
     "name '__import__' at column 1 is not allowed"),
    ("huge-exponent", BEAD + "potential: 9**9**9**9\n", 1, 13, "potential",
     "exponent 3.8742e+08 of '**' at column 5 is too large"),
    ("exp-tower", BEAD + "potential: sin(exp(exp(exp(3))))\n", 1, 13, "potential",
     "a constant in exp(...) at column 5 is too large to evaluate"),
    ("power-tower", BEAD + "potential: x**x**x**x**x\n", 1, 13, "potential",
     "a tower of powers 4 high ('**' at column 2)"),
    ("velocity-constraint-squared", bead_with("holonomic: y - f(x)",
                                              "nonholonomic: x_dot**2 + y_dot"), 1, 12,
     "constraints.wire.nonholonomic",
     "velocity constraint is not linear in the velocities (x_dot); write it as a_1*q1_dot"),
    ("velocity-constraint-product", bead_with("holonomic: y - f(x)", "nonholonomic: x_dot*y_dot"),
     1, 12, "constraints.wire.nonholonomic", "not linear in the velocities (x_dot, y_dot)"),
    ("velocity-constraint-abs", bead_with("holonomic: y - f(x)", "nonholonomic: Abs(x_dot)"),
     1, 12, "constraints.wire.nonholonomic", "not linear in the velocities (x_dot)"),
    ("velocity-constraint-without-velocity", bead_with("holonomic: y - f(x)", "nonholonomic: y"),
     1, 12, "constraints.wire.nonholonomic", "this velocity constraint contains no velocity"),
    ("holonomic-with-velocity", bead_with("y - f(x)", "y - x_dot"), 1, 12,
     "constraints.wire.holonomic",
     "a holonomic constraint cannot contain velocities (found x_dot); write it under "
     "'nonholonomic:' instead"),
    ("constraint-without-coordinate", bead_with("y - f(x)", "t - 1"), 1, 12,
     "constraints.wire.holonomic",
     "this constraint contains no coordinate, so it cannot restrict the motion"),
    ("acceleration-in-constraint", bead_with("y - f(x)", "y - x_ddot"), 1, 12,
     "constraints.wire.holonomic",
     "'x_ddot' at column 5: accelerations may not appear in problem expressions"),
    ("both-constraint-kinds", bead_with("{holonomic: y - f(x), on: bead}",
                                        "{holonomic: y, nonholonomic: x_dot}"), 1, 12,
     "constraints.wire", "give exactly one of 'holonomic: psi(q, t)' or 'nonholonomic"),
    ("constraints-as-list", bead_with("  wire: {holonomic: y - f(x), on: bead}",
                                      "  - {holonomic: y - f(x), on: bead}"), 1, 12, "constraints",
     "expected a mapping name: constraint, found a list"),
    ("on-unknown-particle", bead_with("on: bead", "on: ball"), 1, 12, "constraints.wire.on",
     "unknown particle 'ball'; known particles: bead"),
    ("on-list-with-unknown", bead_with("on: bead", "on: [bead, ball]"), 1, 12,
     "constraints.wire.on", "unknown particle 'ball'"),
    ("on-a-mapping", bead_with("on: bead", "on: {a: 1}"), 1, 12, "constraints.wire.on",
     "unknown particle (a mapping); known particles: bead"),
    ("position-1-component", bead_with("position: [x, y]", "position: [x]"), 1, 9,
     "particles.bead.position", "expected a list of 2 or 3 components, found 1 components; "
     "write [x, y] in the plane or [x, y, z] in space"),
    ("position-4-components", bead_with("position: [x, y]", "position: [x, y, 0, 0]"), 1, 9,
     "particles.bead.position", "expected a list of 2 or 3 components, found 4 components"),
    ("velocity-in-position", bead_with("position: [x, y]", "position: [x_dot, y]"), 1, 9,
     "particles.bead.position[0]",
     "'x_dot' at column 1: positions, masses and inertias cannot depend on velocities"),
    ("gravity-1-component", bead_with("[0, -g]", "[-g]"), 1, 10, "gravity",
     "expected a list of 2 or 3 components, found 1 components"),
    ("gravity-3-components", bead_with("[0, -g]", "[0, -g, 0]"), 1, 10, "gravity",
     "gravity has 3 components but positions have 2"),
    ("gravity-uses-coordinate", bead_with("[0, -g]", "[0, -x]"), 1, 10, "gravity[1]",
     "'x' at column 2: a coordinate cannot appear here (only parameters and the time)"),
    ("force-3-components", BEAD + "forces:\n  - {on: bead, force: [1, 2, 3]}\n", 1, 14,
     "forces[0].force", "the force has 3 components but particle 'bead' has 2"),
    ("force-1-component", BEAD + "forces:\n  - {on: bead, force: [1]}\n", 1, 14, "forces[0].force",
     "expected a list of 2 or 3 components, found 1 components"),
    ("force-on-unknown", BEAD + "forces:\n  - {on: ball, force: [1, 2]}\n", 1, 14, "forces[0].on",
     "unknown particle 'ball'; known particles: bead"),
    ("force-on-a-list", BEAD + "forces:\n  - {on: [bead], force: [1, 2]}\n", 1, 14,
     "forces[0].on", "unknown particle (a list)"),
    ("force-unknown-coordinate", BEAD + "forces:\n  - {coordinate: z, value: 1}\n", 1, 14,
     "forces[0].coordinate", "unknown coordinate 'z'; known: x, y"),
    ("force-of-no-kind", BEAD + "forces:\n  - {value: 1}\n", 1, 14, "forces[0]",
     "a force needs 'coordinate' (a generalized force) or 'on' (a force on a particle)"),
    ("forces-as-mapping", BEAD + "forces: {a: 1}\n", 1, 13, "forces",
     "expected a list, found a mapping"),
    ("particles-as-list", bead_with("  bead: {mass: m, position: [x, y]}", "  - bead"), 1, 9,
     "particles", "expected a mapping, found a list"),
    ("friction-unknown-names", bead_with("g: gravity", "g: gravity\n  mu: mu")
     + "friction:\n  wall: {coefficient: mu, normal: [rope], sliding: [z]}\n", 2, 15,
     "friction.wall.normal[0]", "unknown constraint 'rope'; known constraints: wire"),
    ("friction-without-normal", bead_with("g: gravity", "g: gravity\n  mu: mu")
     + "friction:\n  wall: {coefficient: mu}\n", 1, 15, "friction.wall",
     "missing required key 'normal'"),
    ("equilibria-not-a-list", BEAD + "expected:\n  effective_potential: {coordinate: x, "
     "equilibria: 3}\n", 1, 14, "expected.effective_potential.equilibria",
     "expected a list, found a number (3)"),
    ("normal-modes-not-a-list", BEAD + "expected:\n  normal_modes: {at: {x: 0}}\n", 1, 14,
     "expected.normal_modes", "expected a list, found a mapping"),
    ("normal-modes-without-at", BEAD + "expected:\n  normal_modes: [{stable: true}]\n", 1, 14,
     "expected.normal_modes[0]", "missing required key 'at'"),
    ("normal-modes-unknown-coordinate", BEAD + "expected:\n  normal_modes: [{at: {z: 0}}]\n", 1, 14,
     "expected.normal_modes[0].at.z", "unknown coordinate 'z'; known coordinates: x, y"),
    ("normal-modes-shape-size", BEAD + "expected:\n  normal_modes: [{at: {x: 0, y: 0}, squared_frequencies: [g], "
     "shapes: [[1, 0, 0]]}]\n", 1, 14, "expected.normal_modes[0].shapes[0]",
     "expected a list of 2 components (one per coordinate), found 3 components"),
    ("normal-modes-shape-count", BEAD + "expected:\n  normal_modes: [{at: {x: 0, y: 0}, squared_frequencies: [g], "
     "shapes: [[1, 0], [0, 1]]}]\n", 1, 14, "expected.normal_modes[0].shapes",
     "expected one shape per squared frequency (1), found 2"),
    ("normal-modes-empty-frequencies", BEAD + "expected:\n  normal_modes: [{at: {x: 0}, squared_frequencies: []}]"
     "\n", 1, 14, "expected.normal_modes[0].squared_frequencies", "expected a non-empty list, found an empty list"),
    ("steady-unknown-rate", BEAD + "expected:\n  steady_motions: {coordinate: x, rate: z, values: [1]}\n", 1, 14,
     "expected.steady_motions.rate", "unknown coordinate 'z'; known coordinates: x, y"),
    ("steady-values-not-a-list", BEAD + "expected:\n  steady_motions: {coordinate: x, rate: y, values: 3}\n", 1,
     14, "expected.steady_motions.values", "expected a list of expressions, found a number (3)"),
    ("steady-without-rate", BEAD + "expected:\n  steady_motions: {coordinate: x, values: [1]}\n", 1, 14,
     "expected.steady_motions", "missing required key 'rate'"),
    ("expected-unknown-coordinate", BEAD + "expected:\n  accelerations: {z: 1}\n", 1, 14,
     "expected.accelerations.z", "unknown coordinate 'z'; known coordinates: x, y"),
    ("three-d-body-with-2-moments", BEAD + "bodies:\n  disk: {mass: m, position: [x, y], "
     "inertia: [1, 2], angular_velocity: [1, 2, 3]}\n", 1, 14, "bodies.disk",
     "a 3-D body needs 3 principal moments and 3 body-frame angular velocity components"),
    ("simulation-unknown-parameter", BEAD + "simulation:\n  values: {m: 1, q: 2}\n", 1, 14,
     "simulation.values.q", "unknown parameter 'q'; known parameters: m, g"),
    ("simulation-bad-method", BEAD + "simulation:\n  method: Euler\n", 1, 14, "simulation.method",
     "unknown method 'Euler'; use one of: DOP853, RK45, RK23, Radau, BDF, LSODA"),
    ("simulation-bad-samples", BEAD + "simulation:\n  samples: 1.5\n", 1, 14,
     "simulation.samples", "expected a whole number from 2 to 1000000"),
    ("simulation-negative-t_end", BEAD + "simulation:\n  t_end: -1\n", 1, 14, "simulation.t_end",
     "expected a positive number, found -1"),
    ("simulation-text-value", BEAD + "simulation:\n  values: {m: heavy}\n", 1, 14,
     "simulation.values.m", "expected a number, found text 'heavy'"),
    ("simulation-unknown-initial", BEAD + "simulation:\n  initial: {z: 1}\n", 1, 14,
     "simulation.initial.z", "unknown coordinate or velocity 'z'; known names: x, y, x_dot"),
    ("simulation-undeclared-function", BEAD + "simulation:\n  functions: {\"g(u)\": u}\n", 1, 14,
     "simulation.functions.g(u)", "'g' is not a declared function; known functions: f"),
    ("simulation-repeated-placeholder", BEAD + "simulation:\n  functions: {\"f(u, u)\": u}\n",
     1, 14, "simulation.functions.f(u, u)",
     "write the function with placeholder arguments, like \"f(u)\""),
    ("time-is-a-number", BEAD + "time: 3\n", 1, 13, "time", "expected a name, found a number (3)"),
    ("potential-is-true", BEAD + "potential: true\n", 1, 13, "potential",
     "expected an expression (text or number), found bool"),
    ("potential-huge-number", BEAD + "potential: 1e200\n", 1, 13, "potential",
     "number is out of range"),
]


@pytest.mark.parametrize(("text", "count", "line", "where", "fragment"),
                         [c[1:] for c in INVALID], ids=[c[0] for c in INVALID])
def test_invalid_problems_are_explained(text: str, count: int, line: int, where: str,
                                        fragment: str) -> None:
    """Each mistake is reported with file, line, field path and a message saying what to do."""
    issues = issues_of(text)
    place = f"{SOURCE}:{line}: " + (f"{where}: " if where else "")
    matching = [str(i) for i in issues if str(i).startswith(place) and fragment in str(i)]
    assert matching, "\n".join(str(i) for i in issues)
    assert len(issues) == count, "\n".join(str(i) for i in issues)


def test_several_errors_are_reported_at_once() -> None:
    """All mistakes in a file come back in one SpecError, ordered by line, without follow-ups."""
    text = (BEAD.replace("name: Bead\n", "")
            .replace("y - f(x)", "y - h(x)")
            .replace("position: [x, y]", "position: [x]")
            + "gravty: 1\nsimulation:\n  method: Euler\n")
    issues = issues_of(text)
    assert len(issues) == 5
    assert [str(i) for i in issues] == [
        "p.yaml:1: missing required key 'name'; add 'name: ...'",
        "p.yaml:8: particles.bead.position: expected a list of 2 or 3 components, found 1 "
        "components; write [x, y] in the plane or [x, y, z] in space",
        "p.yaml:11: constraints.wire.holonomic: unknown function 'h' at column 5; declare it "
        "under functions, or use one of: Abs, acos, asin, atan, atan2, cos, cosh, cot, csc, exp, "
        "log, sec, sign, sin, sinh, sqrt, tan, tanh, f",
        "p.yaml:12: gravty: unknown key 'gravty'; did you mean 'gravity'?",
        "p.yaml:14: simulation.method: unknown method 'Euler'; use one of: DOP853, RK45, RK23, "
        "Radau, BDF, LSODA",
    ]


def test_a_particle_that_failed_is_not_unknown_later() -> None:
    """A constraint or force on a particle with its own error does not add 'unknown particle'."""
    text = (bead_with("mass: m", "mass: [m]")
            + "forces:\n  - {on: bead, force: [1, 2]}\n")
    issues = issues_of(text)
    assert [i.where for i in issues] == ["particles.bead.mass"]


def test_unknown_name_message_is_complete() -> None:
    """The whole message of an unknown name: place, field, symbol, column, known names, fix."""
    (issue,) = issues_of(BEAD + "potential: m*gg*y\n")
    assert str(issue) == (
        "p.yaml:13: potential: unknown name 'gg' at column 3 (known: g, m, t, x, x_dot, y, "
        "y_dot); did you mean 'g'? declare it under parameters, coordinates or functions"
    )


def test_yaml_errors_pass_through() -> None:
    """A YAML-level problem (here a duplicate key) reaches the caller as one issue."""
    (issue,) = issues_of(BEAD + "name: Again\n")
    assert str(issue) == ("p.yaml:13: name: duplicate key 'name' (first given on line 1); "
                          "give each key once")


# ------------------------------------------------------------------------------------------
# files


def test_load_problem_reads_a_file(tmp_path: Path) -> None:
    """load_problem reads the file and records its path as the source."""
    path = tmp_path / "my bead.yaml"
    path.write_text(BEAD, encoding="utf-8")
    problem = load_problem(path)
    assert problem.source == str(path) and problem.name == "Bead"


def test_file_not_found(tmp_path: Path) -> None:
    """A missing file is a SpecError naming the path, not a FileNotFoundError."""
    path = tmp_path / "nothere.yaml"
    with pytest.raises(SpecError) as caught:
        load_problem(path)
    assert str(caught.value) == f"{path}: file not found; check the path"


def test_folder_instead_of_file(tmp_path: Path) -> None:
    """A folder is a SpecError saying so."""
    with pytest.raises(SpecError) as caught:
        load_problem(tmp_path)
    assert str(caught.value) == f"{tmp_path}: is a folder, not a problem file"


def test_errors_name_the_file_path(tmp_path: Path) -> None:
    """Issues from a file carry its path, so the message reads path:line: field: ..."""
    path = tmp_path / "bad.yaml"
    path.write_text(bead_with("on: bead", "on: ball"), encoding="utf-8")
    with pytest.raises(SpecError) as caught:
        load_problem(path)
    assert str(caught.value).startswith(f"{path}:12: constraints.wire.on: unknown particle 'ball'")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_endless_file_is_refused_quickly() -> None:
    """An endless input such as /dev/zero is read only up to the size limit, then refused."""
    start = time.perf_counter()
    with pytest.raises(SpecError) as caught:
        load_problem("/dev/zero")
    assert time.perf_counter() - start < 2.0
    assert "bytes; the limit is 262144" in str(caught.value)


def test_values_contradicting_a_positive_assumption_are_refused() -> None:
    """A negative simulation value or default for a positive parameter, or a negative initial value for a
    positive coordinate, is refused with its line, field and the fix: the derivation assumed the opposite.
    Zero, the limit case (mu = 0: no friction), is allowed."""
    text = """\
name: Spring
parameters:
  m: mass
  k: {description: stiffness, positive: true, value: -2}
  F: {description: force, positive: false}
coordinates: {r: {description: distance, positive: true}, z: height}
kinetic: m*(r_dot**2 + z_dot**2)/2
potential: k*r**2/2 - F*z
simulation:
  values: {m: -0.5, F: -3, k: 0}
  initial: {r: -0.5, z: -1}
"""
    issues = [str(i) for i in issues_of(text)]
    assert issues == [
        "p.yaml:4: parameters.k.value: -2 contradicts the assumption that parameter 'k' is positive (parameters "
        "are, unless declared with positive: false), which the derivation relies on; give a value >= 0, or "
        "declare it as k: {description: ..., positive: false} under parameters",
        "p.yaml:10: simulation.values.m: -0.5 contradicts the assumption that parameter 'm' is positive (parameters "
        "are, unless declared with positive: false), which the derivation relies on; give a value >= 0, or "
        "declare it as m: {description: ..., positive: false} under parameters",
        "p.yaml:11: simulation.initial.r: -0.5 contradicts the assumption that coordinate 'r' is positive "
        "(declared positive: true), which the derivation relies on; give a value >= 0, or remove "
        "positive: true from coordinate 'r'",
    ]


def test_free_text_and_names_are_bounded() -> None:
    """A 200,000-character name, over-long descriptions and names are refused at once with the limit,
    instead of slowing every figure and report down."""
    text = BEAD.replace("name: Bead", "name: " + "A" * 200_000).replace(
        "m: mass", "m: " + "b" * 1001 + "\n  k: {description: " + "c" * 1001 + "}\n  " + "q" * 65 + ": long")
    issues = [str(i) for i in issues_of(text + "description: " + "d" * 20_001 + "\n")]
    assert issues == [
        "p.yaml:1: name: text of 200000 characters is too long; the limit here is 200; shorten it; "
        "put details in description",
        "p.yaml:3: parameters.m: text of 1001 characters is too long; the limit here is 1000; shorten it",
        "p.yaml:4: parameters.k.description: text of 1001 characters is too long; the limit here is 1000; "
        "shorten it",
        f"p.yaml:5: parameters.{'q' * 65}: a name of 65 characters ('qqqqqqqqqqqqqqqqqqqq'...) is too long; "
        "names are limited to 64 characters",
        "p.yaml:15: description: text of 20001 characters is too long; the limit here is 20000; shorten it",
    ]
    assert load(BEAD.replace("name: Bead", "name: " + "A" * 200)).name == "A" * 200


@pytest.mark.parametrize(("misspelt", "meant"), [("particle", "particles"), ("constraint", "constraints"),
                                                ("paramters", "parameters"), ("coordinate", "coordinates")])
def test_a_misspelt_section_is_one_error(misspelt: str, meant: str) -> None:
    """A misspelt top-level key is reported once, with the fix; what follows from the section it was meant to be
    (an unknown particle, no kinetic energy, an unknown name) is not reported again."""
    text = """\
name: Bead
parameters: {m: mass, g: gravity}
coordinates: [x, y]
particles:
  bead: {mass: m, position: [x, y]}
gravity: [0, -g]
constraints:
  wire: {holonomic: y - x**2, on: bead}
friction:
  rub: {coefficient: 0.1, on: bead, normal: [wire]}
""".replace(f"{meant}:", f"{misspelt}:")
    issues = issues_of(text)
    assert [i.where for i in issues] == [misspelt], issues
    assert f"did you mean '{meant}'?" in issues[0].hint


def test_expected_steady_motions_are_read() -> None:
    """The heavy top's expected steady precession: the coordinate, the rate, two values, stability, frequency."""
    expected = load_problem(Path(__file__).resolve().parents[2] / "problems" / "heavy_top.yaml").expected
    steady = expected.steady_motions
    assert steady is not None and (steady.coordinate, steady.rate, steady.stable) == ("theta", "phi", True)
    assert len(steady.roots) == 2 and steady.frequency.has(sympy.Symbol("p_psi", real=True))
    assert not expected.is_empty()


def test_a_name_lagsolve_gives_a_normal_force_is_refused() -> None:
    """A parameter N_<contact> would print as the contact's normal force in its equation (Eq(N_rub, N_rub + g*m),
    false as written): refused with its line and field, as p_<coordinate> is (the momentum)."""
    text = bead_with("g: gravity", "g: gravity\n  mu: friction coefficient\n  N_wall: a push") + \
        "friction:\n  wall: {coefficient: mu, normal: [wire]}\n"
    with pytest.raises(SpecError) as caught:
        load_text(text, "clash.yaml")
    message = str(caught.value)
    assert "clash.yaml:" in message and "parameters.N_wall" in message
    assert "'N_wall' is the name lagsolve gives the normal force of friction contact 'wall'" in message


@pytest.mark.parametrize(("answer", "message"), [
    ("multipliers: {wire: lambda_wire}", "expected.multipliers.wire: 'lambda_wire' at column 1: a multiplier is "
     "allowed only in constraint_forces"),
    ("accelerations: {x: 2*lambda_wire*x/m}", "expected.accelerations.x: 'lambda_wire' at column 3"),
    ("conserved: {c: lambda_wire}", "expected.conserved.c: 'lambda_wire'"),
    ("conserved: {d: p_x}", "expected.conserved.d: 'p_x' at column 1: a momentum is allowed only in"),
])
def test_an_answer_may_not_restate_a_multiplier_or_use_a_momentum(answer: str, message: str) -> None:
    """An expected answer in terms of the multiplier restates it (multipliers: {wire: lambda_wire} was "ok"; a
    conserved lambda_wire was read as a constant), and a momentum outside the effective potential and steady motions
    was read as a constant (a conserved p_x "ok" for a particle under gravity): both are refused with the field. A
    force of constraint may still be written with λ (λ∇ψ, compared with the derived λ put in: test_check)."""
    with pytest.raises(SpecError) as caught:
        load_text(BEAD + "expected:\n  " + answer + "\n", "answers.yaml")
    assert message in str(caught.value)
