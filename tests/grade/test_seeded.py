# ruff: noqa: E501 - the seeded answers are long formulas, one a line
"""Seeded submissions over the four seed problems (issue 31): correct answers written in other forms (the other
λ convention where the key accepts it, other coordinates through ``coordinates_map``) earn every point; each known
mistake, made at a known step (in the key's coordinates or the student's), is found at that step and named (a
wrong dimension, a moving constraint taken as still, ...); after one seeded mistake the later steps that follow
from it get follow-through credit (down to H, V_eff, conserved quantities and ω²). The steps past the core
(equilibria, frequencies, hamiltonian, effective_potential, conserved) are seeded where the key has them. The
correct answers are checked against SymPy's LagrangesMethod or by hand with SymPy, never lagsolve."""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

import pytest
import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from lagsolve.grade.grader import GradingKey, grade
from lagsolve.grade.key import Grading
from lagsolve.grade.submission import read_text
from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem

ROOT = Path(__file__).resolve().parents[2]
F1, F2 = "Derivative(f(x), x)", "Derivative(f(x), (x, 2))"
#: the hole table's circular orbit r0³ = p_θ²/(m1 m2 g) (V_eff = m2 g r + p_θ²/(2 m1 r²) at its minimum)
R0_CUBED = "p_theta**2/(m1*m2*g)"
#: a mistake made in the seed's other coordinates (its "mapped" answers and coordinates_map)
MAPPED = {"mapped": True}

#: per problem: the answers as a student writes them, the steps graded, and mistakes (step, name, changes)
SEEDS: dict[str, dict[str, Any]] = {
    "bead": {
        "steps": {
            "kinetic": f"m*x_dot**2*(1 + {F1}**2)/2", "potential": "m*g*f(x)",
            "lagrangian": "m*(x_dot**2 + y_dot**2)/2 - m*g*y",
            "momenta": {"x": "m*x_dot", "y": "m*y_dot"}, "generalized_forces": {"x": "0", "y": "-m*g"},
            "equations": {"x": f"m*x_ddot = -lambda_wire*{F1}", "y": "m*y_ddot + m*g = lambda_wire"},
            "accelerations": {"x": f"-{F1}*({F2}*x_dot**2 + g)/(1 + {F1}**2)",
                              "y": f"({F2}*x_dot**2 - g*{F1}**2)/(1 + {F1}**2)"},
            "multipliers": {"wire": f"m*({F2}*x_dot**2 + g)/(1 + {F1}**2)"},
            "conserved": {"energy": f"m*x_dot**2*(1 + {F1}**2)/2 + m*g*f(x)"},
            "effective_potential": {"coordinate": "x", "expression": "m*g*f(x)"},
            "hamiltonian": f"p_x**2/(2*m*(1 + {F1}**2)) + m*g*f(x)",
        },
        "mapped": ({"v": "-y"}, {
            "potential": "-m*g*v", "lagrangian": "m*(x_dot**2 + v_dot**2)/2 + m*g*v",
            "momenta": {"x": "m*x_dot", "v": "m*v_dot"}, "generalized_forces": {"x": "0", "v": "m*g"},
            "equations": {"x": f"m*x_ddot = -lambda_wire*{F1}", "v": "m*v_ddot - m*g + lambda_wire"},
            "accelerations": {"x": f"-{F1}*({F2}*x_dot**2 + g)/(1 + {F1}**2)",
                              "v": f"-({F2}*x_dot**2 - g*{F1}**2)/(1 + {F1}**2)"},
        }),
        "mistakes": [
            ("kinetic", "wrong_dimension", {"kinetic": f"m*x_dot*(1 + {F1}**2)/2"}),
            ("accelerations", "missing_velocity_squared_terms", {"accelerations": {"x": f"-{F1}*g/(1 + {F1}**2)", "v": f"g*{F1}**2/(1 + {F1}**2)"}}, MAPPED),
            ("potential", "wrong_potential_sign", {"potential": "-m*g*f(x)", "lagrangian": "m*(x_dot**2 + y_dot**2)/2 + m*g*y",
                                                   "equations": {"x": f"m*x_ddot = -lambda_wire*{F1}", "y": "m*y_ddot - m*g = lambda_wire"},
                                                   "hamiltonian": f"p_x**2/(2*m*(1 + {F1}**2)) - m*g*f(x)",
                                                   "effective_potential": {"coordinate": "x", "expression": "-m*g*f(x)"},
                                                   "conserved": {"energy": f"m*x_dot**2*(1 + {F1}**2)/2 - m*g*f(x)"}},
             {"follows": ("lagrangian", "equations", "hamiltonian", "effective_potential", "conserved")}),
            ("hamiltonian", "wrong_potential_sign", {"hamiltonian": f"p_x**2/(2*m*(1 + {F1}**2)) - m*g*f(x)"}),
            ("potential", "wrong_potential_sign", {"potential": "-m*g*f(x)"}),
            ("lagrangian", "wrong_potential_sign", {"lagrangian": "m*(x_dot**2 + y_dot**2)/2 + m*g*y"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m*x_dot**2/2"}),
            ("kinetic", "missing_factor", {"kinetic": f"m*x_dot**2*(1 + {F1}**2)"}),
            ("multipliers", "lambda_sign_convention", {"multipliers": {"wire": f"-m*({F2}*x_dot**2 + g)/(1 + {F1}**2)"}}),
            ("accelerations", "missing_velocity_squared_terms",
             {"accelerations": {"x": f"-{F1}*g/(1 + {F1}**2)", "y": f"-g*{F1}**2/(1 + {F1}**2)"}}),
            ("accelerations", "dropped_constraint", {"accelerations": {"x": "0", "y": "-g"}}),
            ("equations", "lambda_sign_convention",
             {"equations": {"x": f"m*x_ddot = lambda_wire*{F1}", "y": "m*y_ddot + m*g = -lambda_wire"}}),
        ],
    },
    "knife_edge": {
        "steps": {
            "kinetic": "m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2/2 + m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))",
            "potential": "0",
            "momenta": {"x": "2*m*x_dot - m*l*theta_dot*sin(theta)", "y": "2*m*y_dot + m*l*theta_dot*cos(theta)",
                        "theta": "m*l**2*theta_dot + m*l*(y_dot*cos(theta) - x_dot*sin(theta))"},
            "equations": {"x": "2*m*x_ddot - m*l*(theta_ddot*sin(theta) + theta_dot**2*cos(theta)) = -lambda_skate*sin(theta)",
                          "y": "2*m*y_ddot + m*l*(theta_ddot*cos(theta) - theta_dot**2*sin(theta)) = lambda_skate*cos(theta)",
                          "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"},
            "multipliers": {"skate": "m*theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))"},
            "accelerations": {"x": "theta_dot*(l*theta_dot*cos(theta)/2 - sin(theta)*(x_dot*cos(theta) + y_dot*sin(theta)))",
                              "y": "theta_dot*(l*theta_dot*sin(theta)/2 + cos(theta)*(x_dot*cos(theta) + y_dot*sin(theta)))",
                              "theta": "-theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))/l"},
            "conserved": {"energy": "m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2/2 + m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"},
        },
        "weights": {"kinetic": 1, "potential": 1, "momenta": 1, "equations": 2, "accelerations": 2, "multipliers": 1,
                    "conserved": 1},
        "mapped": ({"psi": "theta + pi/2"}, {
            "kinetic": "m*(x_dot**2 + y_dot**2) + m*l**2*psi_dot**2/2 + m*l*psi_dot*(y_dot*sin(psi) + x_dot*cos(psi))",
            "momenta": {"x": "2*m*x_dot + m*l*psi_dot*cos(psi)", "y": "2*m*y_dot + m*l*psi_dot*sin(psi)",
                        "psi": "m*l**2*psi_dot + m*l*(y_dot*sin(psi) + x_dot*cos(psi))"},
            "multipliers": {"skate": "m*psi_dot*(x_dot*sin(psi) - y_dot*cos(psi))"},
            "accelerations": {"x": "psi_dot*(l*psi_dot*sin(psi)/2 + cos(psi)*(x_dot*sin(psi) - y_dot*cos(psi)))",
                              "y": "psi_dot*(-l*psi_dot*cos(psi)/2 + sin(psi)*(x_dot*sin(psi) - y_dot*cos(psi)))",
                              "psi": "-psi_dot*(x_dot*sin(psi) - y_dot*cos(psi))/l"},
        }),
        "mistakes": [
            ("conserved", "missing_factor", {"conserved": {"energy": "2*m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2 + 2*m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"}}),
            ("multipliers", "lambda_sign_convention", {"multipliers": {"skate": "-m*psi_dot*(x_dot*sin(psi) - y_dot*cos(psi))"}}, MAPPED),
            ("kinetic", "missing_kinetic_term",
             {"kinetic": "m*(x_dot**2 + y_dot**2) + m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"}),
            ("kinetic", "missing_factor", {"kinetic": "2*m*(x_dot**2 + y_dot**2) + m*l**2*theta_dot**2 + 2*m*l*theta_dot*(y_dot*cos(theta) - x_dot*sin(theta))"}),
            ("multipliers", "lambda_sign_convention",
             {"multipliers": {"skate": "-m*theta_dot*(x_dot*cos(theta) + y_dot*sin(theta))"}}),
            ("multipliers", "sign_error", {"multipliers": {"skate": "m*theta_dot*(x_dot*cos(theta) - y_dot*sin(theta))"}}),
            ("momenta", "sign_error", {"momenta": {"x": "-2*m*x_dot + m*l*theta_dot*sin(theta)",
                                                   "y": "2*m*y_dot + m*l*theta_dot*cos(theta)",
                                                   "theta": "m*l**2*theta_dot + m*l*(y_dot*cos(theta) - x_dot*sin(theta))"}}),
            ("equations", "lambda_sign_convention",
             {"equations": {"x": "2*m*x_ddot - m*l*(theta_ddot*sin(theta) + theta_dot**2*cos(theta)) = lambda_skate*sin(theta)",
                            "y": "2*m*y_ddot + m*l*(theta_ddot*cos(theta) - theta_dot**2*sin(theta)) = -lambda_skate*cos(theta)",
                            "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"}}),
            ("equations", "missing_velocity_squared_terms",
             {"equations": {"x": "2*m*x_ddot - m*l*theta_ddot*sin(theta) = -lambda_skate*sin(theta)",
                            "y": "2*m*y_ddot + m*l*theta_ddot*cos(theta) = lambda_skate*cos(theta)",
                            "theta": "m*l**2*theta_ddot + m*l*(y_ddot*cos(theta) - x_ddot*sin(theta))"}}),
            ("momenta", "missing_factor", {"momenta": {"x": "4*m*x_dot - 2*m*l*theta_dot*sin(theta)", "y": "4*m*y_dot + 2*m*l*theta_dot*cos(theta)",
                          "theta": "2*m*l**2*theta_dot + 2*m*l*(y_dot*cos(theta) - x_dot*sin(theta))"}}),
        ],
    },
    "hole_table": {
        "steps": {
            "kinetic": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2", "potential": "m2*g*z",
            "lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 - m2*g*z",
            "momenta": {"r": "m1*r_dot", "theta": "m1*r**2*theta_dot", "z": "m2*z_dot"},
            "generalized_forces": {"r": "m1*r*theta_dot**2", "theta": "0", "z": "-m2*g"},
            "equations": {"r": "m1*r_ddot - m1*r*theta_dot**2 = lambda_string", "theta": "m1*r**2*theta_ddot + 2*m1*r*r_dot*theta_dot",
                          "z": "m2*z_ddot + m2*g = -lambda_string"},
            "accelerations": {"r": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r",
                              "z": "(m1*r*theta_dot**2 - m2*g)/(m1 + m2)"},
            "multipliers": {"string": "-m1*m2*(g + r*theta_dot**2)/(m1 + m2)"},
            "constraint_forces": {"string": "m1*m2*(g + r*theta_dot**2)/(m1 + m2)"},
            "conserved": {"p_theta": "m1*r**2*theta_dot", "energy": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 + m2*g*z"},
            "effective_potential": {"coordinate": "r", "expression": "m2*g*r + p_theta**2/(2*m1*r**2)"},
            "equilibria": [f"({R0_CUBED})**(1/3)"],
            "frequencies": [f"3*m2*g/((m1 + m2)*({R0_CUBED})**(1/3))"],
            "hamiltonian": "p_r**2/(2*(m1 + m2)) + p_theta**2/(2*m1*r**2) + m2*g*r",
        },
        "weights": {"kinetic": 1, "potential": 1, "lagrangian": 1, "momenta": 1, "generalized_forces": 1,
                    "equations": 2, "accelerations": 2, "multipliers": 1, "constraint_forces": 1, "conserved": 1,
                    "effective_potential": 1, "equilibria": 1, "frequencies": 1, "hamiltonian": 1},
        "mapped": ({"phi": "theta - pi/2"}, {
            "kinetic": "m1*(r_dot**2 + r**2*phi_dot**2)/2 + m2*z_dot**2/2",
            "momenta": {"r": "m1*r_dot", "phi": "m1*r**2*phi_dot", "z": "m2*z_dot"},
            "equations": {"r": "m1*r_ddot - m1*r*phi_dot**2 = lambda_string", "phi": "m1*r**2*phi_ddot + 2*m1*r*r_dot*phi_dot",
                          "z": "m2*z_ddot + m2*g = -lambda_string"},
            "accelerations": {"r": "(m1*r*phi_dot**2 - m2*g)/(m1 + m2)", "phi": "-2*r_dot*phi_dot/r",
                              "z": "(m1*r*phi_dot**2 - m2*g)/(m1 + m2)"},
            "hamiltonian": "p_r**2/(2*(m1 + m2)) + p_phi**2/(2*m1*r**2) + m2*g*r",
        }),
        "mistakes": [
            ("potential", "wrong_dimension", {"potential": "m2*g*z + m2*z_dot"}),
            ("accelerations", "missing_velocity_squared_terms",
             {"accelerations": {"r": "-m2*g/(m1 + m2)", "phi": "-2*r_dot*phi_dot/r", "z": "-m2*g/(m1 + m2)"}}, MAPPED),
            ("kinetic", "missing_kinetic_term",
             {"kinetic": "m1*(r_dot**2 + r**2*theta_dot**2)/2", "lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 - m2*g*z",
              "frequencies": [f"3*m2*g/(m1*({R0_CUBED})**(1/3))"], "hamiltonian": "p_r**2/(2*m1) + p_theta**2/(2*m1*r**2) + m2*g*r"},
             {"follows": ("lagrangian", "frequencies", "hamiltonian")}),
            ("frequencies", "sign_error", {"frequencies": [f"-3*m2*g/((m1 + m2)*({R0_CUBED})**(1/3))"]}),
            ("hamiltonian", "wrong_potential_sign", {"hamiltonian": "p_r**2/(2*(m1 + m2)) + p_theta**2/(2*m1*r**2) - m2*g*r"}),
            ("frequencies", "missing_factor", {"frequencies": [f"3*g/((m1 + m2)*({R0_CUBED})**(1/3))"]}),
            ("potential", "wrong_potential_sign", {"potential": "-m2*g*z"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m1*r_dot**2/2 + m2*z_dot**2/2"}),
            ("generalized_forces", "sign_error", {"generalized_forces": {"r": "-m1*r*theta_dot**2", "theta": "0", "z": "-m2*g"}}),
            ("accelerations", "missing_velocity_squared_terms",
             {"accelerations": {"r": "-m2*g/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r", "z": "-m2*g/(m1 + m2)"}}),
            ("multipliers", "lambda_sign_convention", {"multipliers": {"string": "m1*m2*(g + r*theta_dot**2)/(m1 + m2)"}}),
            ("constraint_forces", "missing_factor", {"constraint_forces": {"string": "m1*(g + r*theta_dot**2)/(m1 + m2)"}}),
            ("lagrangian", "wrong_potential_sign",
             {"lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 + m2*g*z"}),
            ("momenta", "missing_factor", {"momenta": {"r": "m1*r_dot", "theta": "m1*r**2*theta_dot/2", "z": "m2*z_dot"}}),
        ],
    },
    "rotating_tube": {
        "steps": {
            "kinetic": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2",
            "potential": "m*g*r*cos(theta)",
            "lagrangian": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2 - m*g*r*cos(theta)",
            "momenta": {"r": "m*r_dot", "theta": "m*r**2*theta_dot", "phi": "m*r**2*sin(theta)**2*phi_dot"},
            "accelerations": {"r": "r*Omega**2*sin(theta)**2 - g*cos(theta) - mu*sign(r_dot)*Abs(sin(theta))"
                                   "*sqrt(4*Omega**2*r_dot**2 + (r*Omega**2*cos(theta) + g)**2)", "theta": "0", "phi": "0"},
            "multipliers": {"tilt": "-m*r**2*sin(theta)*cos(theta)*Omega**2 - m*g*r*sin(theta)",
                            "spin": "2*m*r*r_dot*sin(theta)**2*Omega"},
            "constraints": {"tilt": "theta_dot = 0", "spin": "phi_dot = Omega"},
            "hamiltonian": "p_r**2/(2*m) - m*r**2*Omega**2*sin(theta)**2/2 + m*g*r*cos(theta)",
        },
        "weights": {"kinetic": 1, "potential": 1, "lagrangian": 1, "momenta": 1, "accelerations": 2, "multipliers": 1,
                    "constraints": 1, "hamiltonian": 1},
        "mapped": ({"s": "2*r"}, {
            "kinetic": "m*(s_dot**2 + s**2*theta_dot**2 + s**2*sin(theta)**2*phi_dot**2)/8",
            "potential": "m*g*s*cos(theta)/2",
            "momenta": {"s": "m*s_dot/4", "theta": "m*s**2*theta_dot/4", "phi": "m*s**2*sin(theta)**2*phi_dot/4"},
            "hamiltonian": "2*p_s**2/m - m*s**2*Omega**2*sin(theta)**2/8 + m*g*s*cos(theta)/2",
        }),
        "mistakes": [
            ("constraints", "missing_moving_constraint_term", {"constraints": {"tilt": "theta_dot = 0", "spin": "phi_dot = 0"}}),
            ("potential", "wrong_potential_sign", {"potential": "-m*g*s*cos(theta)/2"}, MAPPED),
            ("hamiltonian", "missing_factor", {"hamiltonian": "p_r**2/m - m*r**2*Omega**2*sin(theta)**2/2 + m*g*r*cos(theta)"}),
            ("potential", "wrong_potential_sign", {"potential": "-m*g*r*cos(theta)"}),
            ("kinetic", "missing_kinetic_term", {"kinetic": "m*(r_dot**2 + r**2*theta_dot**2)/2"}),
            ("lagrangian", "wrong_potential_sign",
             {"lagrangian": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)/2 + m*g*r*cos(theta)"}),
            ("multipliers", "lambda_sign_convention",
             {"multipliers": {"tilt": "m*r**2*sin(theta)*cos(theta)*Omega**2 + m*g*r*sin(theta)",
                              "spin": "-2*m*r*r_dot*sin(theta)**2*Omega"}}),
            ("momenta", "missing_factor",
             {"momenta": {"r": "m*r_dot", "theta": "m*r**2*theta_dot", "phi": "m*r**2*sin(theta)**2*phi_dot/2"}}),
            ("multipliers", "sign_error",
             {"multipliers": {"tilt": "-m*r**2*sin(theta)*cos(theta)*Omega**2 + m*g*r*sin(theta)",
                              "spin": "2*m*r*r_dot*sin(theta)**2*Omega"}}),
            ("kinetic", "missing_factor", {"kinetic": "m*(r_dot**2 + r**2*theta_dot**2 + r**2*sin(theta)**2*phi_dot**2)"}),
            ("potential", "missing_factor", {"potential": "2*m*g*r*cos(theta)"}),
        ],
    },
}


def _variant(steps: dict[str, Any], k: int, c: int) -> dict[str, Any]:
    """The same answers written differently: equations times k, the energies shifted by c, sums reordered."""
    out: dict[str, Any] = {}
    for name, value in steps.items():
        if name in ("equations", "constraints"):
            out[name] = {q: " = ".join(f"{k}*({side})" for side in e.split("=")) for q, e in value.items()}
        elif name in ("potential", "lagrangian", "hamiltonian"):
            out[name] = f"{value} + {c}" if name != "lagrangian" else f"{c} + ({value})"
        elif name == "effective_potential":
            out[name] = {"coordinate": value["coordinate"], "expression": f"{value['expression']} - {c}"}
        elif name == "frequencies":
            out[name] = [f"sqrt({w})" for w in reversed(value)]  # ω for ω², in another order
        elif name == "kinetic":
            out[name] = f"({value})*{k}/{k}"
        elif isinstance(value, dict):
            out[name] = {q: f"{k}*({e})/{k}" for q, e in value.items()}
        else:
            out[name] = value
    return out


def _flip_lambda(steps: dict[str, Any], problem: Any) -> dict[str, Any]:
    """The other λ convention: the multipliers negated, and λ → −λ in the equations."""
    out = dict(steps)
    names = [c.name for c in problem.constraints]
    if "multipliers" in steps:
        out["multipliers"] = {n: f"-({e})" for n, e in steps["multipliers"].items()}
    if "equations" in steps:
        flipped = {}
        for q, e in steps["equations"].items():
            for n in names:
                e = e.replace(f"lambda_{n}", f"(-LAMBDA_{n})")
            flipped[q] = e.replace("LAMBDA_", "lambda_")
        out["equations"] = flipped
    return out


@pytest.fixture(scope="module")
def keys() -> dict[str, tuple]:
    out = {}
    for name, seed in SEEDS.items():
        problem = load_problem(ROOT / "problems" / f"{name}.yaml")
        derivation = derive(problem)
        weights = {k: float(v) for k, v in seed.get("weights", dict.fromkeys(seed["steps"], 1)).items()}
        out[name] = (problem, derivation, weights)
    return out


def _grade(keys: dict[str, tuple], name: str, steps: dict[str, Any], sign: str = "strict",
           mapping: dict[str, str] | None = None) -> dict[str, Any]:
    problem, derivation, weights = keys[name]
    if mapping:  # the steps written in the other coordinates only
        weights = {s: w for s, w in weights.items() if s in steps}
    grading = Grading(weights, 1.0, sign)
    data: dict[str, Any] = {"student": "s", "steps": steps}
    if mapping:
        data["coordinates_map"] = mapping
    text = json.dumps(data)
    context = GradingKey(derivation, grading)
    result = grade(derivation, grading, read_text(text, problem, "s.yaml"), key=context)
    return {s.step: s for s in result.steps}


def _seeded() -> list[tuple[str, str, Any]]:
    """(problem, kind, data): per problem as many correct variants as mistakes (every fourth in the other λ
    convention, every fourth in other coordinates), 94 submissions."""
    out: list[tuple[str, str, Any]] = []
    for name, seed in SEEDS.items():
        rng = random.Random(name)
        for i in range(len(seed["mistakes"])):
            out.append((name, "correct", (rng.randint(2, 9) * (-1) ** i, rng.randint(1, 50), i % 4)))
        for mistake in seed["mistakes"]:
            out.append((name, "mistake", mistake))
    return out


SEEDED = _seeded()


def test_at_least_sixty_seeded_submissions_half_correct() -> None:
    assert len(SEEDED) >= 60
    assert sum(kind == "correct" for _, kind, _ in SEEDED) * 2 == len(SEEDED)


@pytest.mark.parametrize(("name", "kind", "data"), SEEDED, ids=[f"{n}-{k}-{i}" for i, (n, k, _) in enumerate(SEEDED)])
def test_seeded_submission(keys: dict[str, tuple], name: str, kind: str, data: Any) -> None:
    problem = keys[name][0]
    steps = SEEDS[name]["steps"]
    if kind == "correct":
        k, c, which = data
        mapping, written = None, _variant(steps, k, c)
        sign = "strict"
        if which == 2:
            mapping, mapped = SEEDS[name]["mapped"]
            written = _variant(_mapped_steps(steps, mapped), k, c)
        if which == 3 and problem.constraints:
            written, sign = _flip_lambda(written, problem), "either"
        graded = _grade(keys, name, written, sign, mapping)
        lost = {s: (g.status, g.message) for s, g in graded.items() if g.points != g.max_points}
        assert not lost
        assert set(graded) == set(written)
        return
    step, mistake, changed, *more = data
    options = more[0] if more else {}
    mapping, base = None, steps
    if options.get("mapped"):
        mapping, mapped = SEEDS[name]["mapped"]
        base = _mapped_steps(steps, mapped)
    graded = _grade(keys, name, {**base, **changed}, mapping=mapping)
    assert graded[step].status == "incorrect"
    assert graded[step].mistake == mistake, graded[step].message
    followed = options.get("follows", ())
    for other in followed:
        assert graded[other].status == "follows", (other, graded[other].message)
        assert graded[other].points == graded[other].max_points
    for other, g in graded.items():
        if other not in changed:
            assert g.status in ("correct", "follows"), (other, g.message)


def _mapped_steps(steps: dict[str, Any], mapped: dict[str, Any]) -> dict[str, Any]:
    """The seed's answers in other coordinates: the mapped ones, and the others that name no coordinate."""
    per_coordinate = ("momenta", "generalized_forces", "equations", "accelerations", "equilibria", "effective_potential")
    return {**{s: v for s, v in steps.items() if s not in per_coordinate}, **mapped}


def test_follow_through_after_a_wrong_potential(keys: dict[str, tuple]) -> None:
    """hole_table with V = −m2 g z (the key's is +m2 g z: z is the height, gravity −g along it): L, the
    z equation and the accelerations that follow get credit. The z equation m2 z̈ − m2 g + λ is not the key's
    m2 z̈ + m2 g + λ up to a constant factor: the accelerations and λ are drawn anew at each state, so a ratio
    that depends on them is no constant (with them drawn per group of states it was, and this step was
    graded correct)."""
    steps = dict(SEEDS["hole_table"]["steps"])
    steps.update({"potential": "-m2*g*z", "lagrangian": "m1*(r_dot**2 + r**2*theta_dot**2)/2 + m2*z_dot**2/2 + m2*g*z",
                  "generalized_forces": {"r": "m1*r*theta_dot**2", "theta": "0", "z": "m2*g"},
                  "equations": {"r": "m1*r_ddot - m1*r*theta_dot**2 = lambda_string",
                                "theta": "m1*r**2*theta_ddot + 2*m1*r*r_dot*theta_dot",
                                "z": "m2*z_ddot - m2*g = -lambda_string"},
                  "accelerations": {"r": "(m1*r*theta_dot**2 + m2*g)/(m1 + m2)", "theta": "-2*r_dot*theta_dot/r",
                                    "z": "(m1*r*theta_dot**2 + m2*g)/(m1 + m2)"},
                  "multipliers": {"string": "-m1*m2*(r*theta_dot**2 - g)/(m1 + m2)"},
                  "constraint_forces": {"string": "m1*m2*Abs(r*theta_dot**2 - g)/(m1 + m2)"}})
    graded = _grade(keys, "hole_table", steps)
    assert graded["potential"].mistake == "wrong_potential_sign"
    for step in ("lagrangian", "generalized_forces", "equations", "accelerations", "multipliers",
                 "constraint_forces"):
        assert graded[step].status == "follows", (step, graded[step].message)
        assert graded[step].points == graded[step].max_points
    assert graded["kinetic"].status == graded["momenta"].status == "correct"


# -- the correct answers, against SymPy's LagrangesMethod -----------------------------------------------


def _numeric_equal(a: Any, b: Any, symbols: list[Any], *, up_to_sign: bool = False) -> bool:
    rng = random.Random(1)
    for _ in range(5):
        point = {s: sympy.Float(rng.uniform(0.4, 1.6)) for s in symbols}
        x, y = complex(a.xreplace(point).evalf()), complex(b.xreplace(point).evalf())
        if abs(x - y) > 1e-9 * max(1, abs(y)) and not (up_to_sign and abs(x + y) <= 1e-9 * max(1, abs(y))):
            return False
    return True


@pytest.mark.parametrize("name", ["hole_table", "knife_edge"])
def test_seeded_answers_agree_with_lagranges_method(keys: dict[str, tuple], name: str) -> None:
    problem = keys[name][0]
    parsed = read_text(json.dumps({"steps": SEEDS[name]["steps"]}), problem, "s.yaml")
    t = dynamicsymbols._t
    names = [q.name for q in problem.coordinates]
    q = dynamicsymbols(" ".join(names))
    syms = problem.symbols
    plain = {**{qi: syms[n] for qi, n in zip(q, names, strict=True)},
             **{qi.diff(t): syms[f"{n}_dot"] for qi, n in zip(q, names, strict=True)}}
    lagrangian = parsed.steps["kinetic"].entries[""] - parsed.steps["potential"].entries[""]
    back = {v: k for k, v in plain.items()}
    lagrangian = lagrangian.xreplace({s: back[s] for s in back if isinstance(s, sympy.Symbol)})
    if name == "knife_edge":
        x, y, th = q
        method = LagrangesMethod(lagrangian, q, nonhol_coneqs=[-sympy.sin(th) * x.diff(t) + sympy.cos(th) * y.diff(t)])
    else:
        r, _, z = q
        method = LagrangesMethod(lagrangian, q, hol_coneqs=[r - z - syms["l"]])
    method.form_lagranges_equations()
    rhs = method.rhs()
    n = len(q)
    accelerations = {nm: rhs[n + i].xreplace({qi.diff(t): plain[qi.diff(t)] for qi in q}).xreplace(plain)
                     for i, nm in enumerate(names)}
    multiplier = rhs[2 * n].xreplace({qi.diff(t): plain[qi.diff(t)] for qi in q}).xreplace(plain)
    symbols = sorted(set().union(*(e.free_symbols for e in accelerations.values())) | multiplier.free_symbols,
                     key=str)
    for coordinate, expr in parsed.steps["accelerations"].entries.items():
        assert _numeric_equal(expr, accelerations[coordinate], symbols), coordinate
    [student_lambda] = parsed.steps["multipliers"].entries.values()
    assert _numeric_equal(student_lambda, multiplier, symbols, up_to_sign=True)


def test_hole_table_orbit_and_frequencies_by_hand() -> None:
    """The seeded circular orbit and ω², from V_eff = m2 g r + p_θ²/(2 m1 r²) with SymPy alone: V_eff'(r0) = 0 and
    ω² = V_eff''(r0)/m_eff, m_eff = m1 + m2 (the seeded follow-through after T without m2 ż²/2: m_eff = m1)."""
    r, m1, m2, g, p = sympy.symbols("r m1 m2 g p_theta", positive=True)
    v_eff = m2 * g * r + p**2 / (2 * m1 * r**2)
    [r0] = sympy.solve(sympy.diff(v_eff, r), r)
    names = {"m1": m1, "m2": m2, "g": g, "p_theta": p}
    seeded = sympy.sympify(SEEDS["hole_table"]["steps"]["equilibria"][0], locals=names)
    assert _numeric_equal(seeded, r0, [m1, m2, g, p])
    curvature = sympy.diff(v_eff, r, 2).subs(r, r0)
    for mass, text in ((m1 + m2, SEEDS["hole_table"]["steps"]["frequencies"][0]),
                       (m1, next(m[2]["frequencies"][0] for m in SEEDS["hole_table"]["mistakes"]
                                 if m[0] == "kinetic" and "frequencies" in m[2]))):
        assert _numeric_equal(sympy.sympify(text, locals=names), curvature / mass, [m1, m2, g, p])
