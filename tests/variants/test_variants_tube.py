"""Issue 34: variants of the rough level tube, each passing its own key, the stick/slip label at t = 0 agreeing
with the closed form mu_s*g >= Omega**2*r (derived for this file: at rest, N = m*g and the force that holds
the particle is m*Omega**2*r), and the key's numbers agreeing with the closed forms of either regime."""

from __future__ import annotations

import math

import pytest
from variants_support import TUBE, TUBE_VARY, answers, check_text, run, spec, tube_sticks

from lagsolve.mechanics.derivation import derive
from lagsolve.problem.load import load_problem


def _variants(count: int, seed: int):
    problem = load_problem(TUBE)
    request = spec.build_request(problem, count=count, vary=TUBE_VARY, seed=seed)
    return run.generate(TUBE, request)


def _assert_tube(made, derivation) -> tuple[int, int]:
    sticks = slips = 0
    for v in made.variants:
        report = check_text(derivation, v.text)
        assert report.passed and all(x.status == "ok" for x in report.verdicts), (v.index, report.verdicts)
        values, initial, key = v.values, v.initial, answers(v)
        held = tube_sticks(values, initial)
        assert v.key.regime == {"wall": "stick" if held else "slip"}, (v.varied, v.key.regime)
        m, g, omega, r = values["m"], values["g"], values["Omega"], initial["r"]
        assert math.isclose(key["N_wall"], m * g, rel_tol=1e-5)
        assert math.isclose(key["least_static_wall"], omega ** 2 * r / g, rel_tol=1e-5)
        if held:
            sticks += 1
            assert math.isclose(key["friction_wall"], -m * omega ** 2 * r, rel_tol=1e-5)
            assert "r_ddot" not in key
        else:
            slips += 1
            assert math.isclose(key["r_ddot"], omega ** 2 * r - values["mu"] * g, rel_tol=1e-5)
    return sticks, slips


def test_a_few_tube_variants_pass_their_keys_and_the_closed_form():
    made = _variants(8, seed=3)
    sticks, slips = _assert_tube(made, derive(load_problem(TUBE)))
    assert sticks + slips == 8 and made.rejections["key"] == 0


@pytest.mark.slow
def test_200_tube_variants_pass_their_keys_and_the_closed_form():
    made = _variants(200, seed=34)
    sticks, slips = _assert_tube(made, derive(load_problem(TUBE)))
    assert sticks > 20 and slips > 20  # both regimes are exercised
    assert made.rejections["key"] == 0 and made.attempts < 260


def test_sphere_variants_release_where_energy_says() -> None:
    """Released from rest at height y0 on a sphere of radius R, the particle leaves it at y = 2*y0/3 (energy and
    N = 0); the key's release place agrees, and every key passes its own check."""
    from pathlib import Path

    sphere = Path(__file__).resolve().parents[2] / "problems" / "sliding_off_sphere.yaml"
    problem = load_problem(sphere)
    request = spec.build_request(problem, count=3, vary=["R=0.5:2", "x=0.001:0.3"], seed=7, require="release")
    made = run.generate(sphere, request)
    derivation = derive(problem)
    for v in made.variants:
        assert check_text(derivation, v.text).passed
        key = answers(v)
        assert math.isclose(key["y_at_release_surface"], 2 * v.initial["y"] / 3, rel_tol=1e-4), (v.varied, key)
        assert key["release_time_surface"] > 0 and v.key.released


def test_hoop_variants_give_the_equilibria_and_frequencies_of_the_closed_form() -> None:
    """The bead on a hoop turning at Omega (Taylor, ch. 7): theta = 0 with omega**2 = g/R - Omega**2 while
    Omega**2 < g/R, else cos(theta) = g/(R*Omega**2) with omega**2 = Omega**2 - g**2/(R**2*Omega**2)."""
    from pathlib import Path

    hoop = Path(__file__).resolve().parents[2] / "problems" / "bead_on_rotating_hoop.yaml"
    problem = load_problem(hoop)
    made = run.generate(hoop, spec.build_request(problem, count=6, vary=["Omega=2:8"], seed=1))
    fast = slow = 0
    for v in made.variants:
        key, g, radius, omega = answers(v), v.values["g"], v.values["R"], v.values["Omega"]
        assert key["equilibrium_1_theta"] == 0 and math.isclose(key["equilibrium_2_theta"], math.pi, rel_tol=1e-6)
        if omega ** 2 < g / radius:
            slow += 1
            assert math.isclose(key["omega_1"], math.sqrt(g / radius - omega ** 2), rel_tol=1e-5)
            assert "equilibrium_4_theta" not in key
        else:
            fast += 1
            assert math.isclose(key["equilibrium_4_theta"], math.acos(g / (radius * omega ** 2)), rel_tol=1e-5)
            assert math.isclose(key["omega_4"], math.sqrt(omega ** 2 - g ** 2 / (radius * omega) ** 2), rel_tol=1e-5)
            assert "omega_1" not in key
    assert fast and slow


def test_inclined_tube_from_rest_sticks_where_the_closed_form_says() -> None:
    """problems/rotating_tube.yaml started at rest in the tube: held at t = 0 iff
    |Omega**2*r*sin(theta)**2 - g*cos(theta)| <= mu*|sin(theta)|*|Omega**2*r*cos(theta) + g| (mu is also the
    static coefficient), the force along the tube against the friction the normal force allows."""
    from pathlib import Path

    tube = Path(__file__).resolve().parents[2] / "problems" / "rotating_tube.yaml"
    problem = load_problem(tube)
    request = spec.build_request(problem, count=8, vary=["mu=0.05:0.9", "Omega=1:4", "r_dot=0:0"], seed=4)
    made = run.generate(tube, request)
    labels = []
    for v in made.variants:
        mu, g, omega = v.values["mu"], v.values["g"], v.values["Omega"]
        r, theta = v.initial["r"], v.initial["theta"]
        along = abs(omega ** 2 * r * math.sin(theta) ** 2 - g * math.cos(theta))
        allowed = mu * abs(math.sin(theta)) * abs(omega ** 2 * r * math.cos(theta) + g)
        labels.append(v.key.regime["wall"])
        assert labels[-1] == ("stick" if along <= allowed else "slip"), (v.varied, along, allowed)
    assert set(labels) == {"stick", "slip"}
