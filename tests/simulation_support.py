"""Shared helpers for simulation tests: derive and bind a problem written inline."""

from __future__ import annotations

from lagsolve.mechanics.analysis.analyse import monitored
from lagsolve.mechanics.equations.matrix_form import matrix_form
from lagsolve.numeric.initial import complete_initial
from lagsolve.numeric.integrate import Trajectory, integrate_motion
from lagsolve.numeric.system import NumericSystem, bind
from lagsolve.problem.load import load_text

CARTESIAN_PENDULUM = """
name: Pendulum in Cartesian coordinates
parameters: {m: mass, g: gravity, l: rod length}
coordinates: [x, y]
particles: {bob: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints:
  rod: {holonomic: x**2 + y**2 - l**2}
simulation:
  values: {m: 1.0, g: 9.81, l: 1.0}
  initial: {x: 0.5, x_dot: 0.0, y_dot: 0.0}
  t_end: 10.0
"""

SPHERE = """
name: Particle sliding off a sphere
parameters: {m: mass, g: gravity, R: radius}
coordinates: [x, y]
particles: {p: {mass: m, position: [x, y]}}
gravity: [0, -g]
constraints:
  sphere: {holonomic: x**2 + y**2 - R**2, unilateral: true}
simulation:
  values: {m: 1.0, g: 9.81, R: 1.0}
  initial: {x: 1.0e-6, y: 1.0, x_dot: 0.0}
  t_end: 5.0
"""

FREE_FALL = """
name: Free fall
parameters: {m: mass, g: gravity}
coordinates: [x, z]
particles: {p: {mass: m, position: [x, z]}}
gravity: [0, -g]
simulation:
  values: {m: 2.0, g: 9.81}
  initial: {x: 0.0, z: 10.0, x_dot: 1.5, z_dot: 3.0}
  t_end: 2.0
"""


PUCK = """
name: Puck sliding to rest on a rough floor
parameters: {m: mass, g: gravity, mu: kinetic coefficient}
coordinates: [x, y, z]
particles: {puck: {mass: m, position: [x, y, z]}}
gravity: [0, 0, -g]
constraints:
  floor: {holonomic: z, on: puck}
friction:
  rub: {coefficient: mu, normal: [floor]}
simulation:
  values: {m: 0.2, g: 9.81, mu: 0.1}
  initial: {x: 0, y: 0, z: 0, x_dot: 1.2, y_dot: 0.5}
  t_end: 3.0
"""


def system_of(text: str, values: dict[str, float] | None = None) -> tuple[NumericSystem, dict]:
    problem = load_text(text, "inline.yaml")
    form = matrix_form(problem, display=False)
    conserved, _, _, energy_note = monitored(form)  # what a simulation monitors, decided by the mechanics
    system = bind(form, values or {}, conserved, energy_note=energy_note)
    assert problem.simulation is not None
    return system, dict(problem.simulation.initial)


def run(text: str, t_end: float, *, initial: dict[str, float] | None = None, **options: object) -> Trajectory:
    system, given = system_of(text)
    given.update(initial or {})
    q0, qd0 = complete_initial(system, given)
    return integrate_motion(system, q0, qd0, t_end, **options)  # type: ignore[arg-type]
