"""`lagsolve.render.checks`: labels and wording of the check table."""

from __future__ import annotations

import sympy

from lagsolve.check.compare import (
    CONSERVED,
    CONVENTION,
    FACTOR,
    NOT_CONSERVED,
    NOT_DERIVED,
    NUMERIC,
    OFFSET,
    CheckReport,
    Verdict,
    Witness,
)
from lagsolve.render.checks import check_table, describe, label
from lagsolve.render.notation import Notation

NOTE = Notation(["x", "theta"])
m, g = sympy.symbols("m g", positive=True)


def _verdict(**kwargs: object) -> Verdict:
    base: dict = {"quantity": "accelerations", "name": "theta", "status": "ok", "reason": NUMERIC,
                  "expected": (g,), "derived": (g,)}
    base.update(kwargs)
    return Verdict(**base)  # type: ignore[arg-type]


def test_labels_use_the_result_notation() -> None:
    """Quantities are labelled as the summary writes them: θ̈, λ_c, |F_c|, F_c, p_θ, V_eff."""
    assert label(_verdict(), NOTE) == "θ̈"
    assert label(_verdict(quantity="multipliers", name="wire"), NOTE) == "λ_wire"
    assert label(_verdict(quantity="constraint_forces", name="wire"), NOTE) == "|F_wire|"
    assert label(_verdict(quantity="constraint_forces", name="wire.vector"), NOTE) == "F_wire"
    assert label(_verdict(quantity="conserved", name="p_theta"), NOTE, ("x", "theta")) == "p_θ"
    assert label(_verdict(quantity="effective_potential", name="expression"), NOTE) == "V_eff"
    assert label(_verdict(quantity="effective_potential", name="equilibria[1].frequency"), NOTE) == \
        "equilibrium 2: frequency"


def test_factor_wording() -> None:
    """A factor 1/m reads 'a missing factor m'; −1/2 on a multiplier reads as the other convention with factor 1/2."""
    text = describe(_verdict(status="mismatch", reason=FACTOR, factor=1 / m), NOTE)
    assert text == "mismatch: a missing factor m (expected = derived/m)"
    text = describe(_verdict(status="mismatch", reason=CONVENTION, factor=sympy.Rational(-1, 2)), NOTE)
    assert "opposite sign convention and a factor 1/2" in text


def test_offset_wording() -> None:
    """An allowed offset is 'ok up to an additive constant', naming it."""
    text = describe(_verdict(quantity="conserved", name="energy", reason=OFFSET, offset=g * m), NOTE)
    assert text.startswith("ok up to an additive constant (expected = derived + g*m")


def test_table_shows_expressions_and_state_for_a_mismatch() -> None:
    """A mismatch line is followed by the expected and derived expressions and the state where they differ."""
    theta = sympy.Symbol("theta", real=True)
    witness = Witness((("theta", 0.5), ("theta_dot", -1.25), ("g", 9.81)), (), (1.0,), (-1.0,))
    verdicts = (
        _verdict(),
        _verdict(name="x", status="mismatch", reason=FACTOR, factor=sympy.Integer(2),
                 expected=(2 * g * sympy.sin(theta),), derived=(g * sympy.sin(theta),), witness=witness),
        _verdict(quantity="reduced", name="x", status="unchecked", reason=NOT_DERIVED, derived=None,
                 note="not derived yet"),
    )
    table = check_table(CheckReport("Pendulum", "p.yaml", ("x", "theta"), verdicts))
    lines = table.splitlines()
    assert lines[0] == "Pendulum (p.yaml)"
    assert lines[1].startswith("  ✓ θ̈")
    assert "✗ ẍ" in lines[2] and "an extra factor 2 (expected = 2·derived)" in lines[2]
    assert lines[3].strip() == "expected: 2*g*sin(θ)" and lines[4].strip() == "derived:  g*sin(θ)"
    assert lines[5].strip() == "differ at θ = 0.5, θ̇ = -1.25, g = 9.81: expected 1, derived -1"
    assert "– ẍ (reduced)" in lines[6] and "not derived yet" in lines[6]
    assert lines[-1] == "  1 ok, 1 mismatch, 1 not checked"


def test_columns_align_despite_combining_dots() -> None:
    """Labels with combining dots (θ̈) and without (λ_wire) start their verdicts in the same column."""
    table = check_table(CheckReport("P", "p.yaml", ("x", "theta"),
                                    (_verdict(), _verdict(quantity="multipliers", name="wire"))))
    first, second = table.splitlines()[1:3]
    strip = "\u0307\u0308"
    assert first.translate({ord(c): None for c in strip}).index("ok") == second.index("ok")


def test_table_shows_the_rate_of_a_claimed_constant_that_changes() -> None:
    """A claimed conserved quantity that is not conserved shows the claim and dC/dt at a state on the surface."""
    theta, theta_dot = sympy.symbols("theta theta_dot")
    witness = Witness((("theta", 0.5), ("theta_dot", -1.25), ("g", 9.81)), (), (2.5,), (0.0,))
    verdict = _verdict(quantity="conserved", name="spin", status="mismatch", reason=NOT_CONSERVED,
                       expected=(m * theta_dot,), derived=None, states=24, agreeing=0, witness=witness)
    report = CheckReport("Pendulum", "p.yaml", ("x", "theta"), (verdict,))
    lines = check_table(report).splitlines()
    assert "not conserved, dC/dt ≠ 0 along the equations of motion at 24 of 24 states" in lines[1]
    assert lines[2].strip() == "claimed: m*θ̇"
    assert lines[3].strip() == "dC/dt ≠ 0 at θ = 0.5, θ̇ = -1.25, g = 9.81: dC/dt = 2.5"
    ok = _verdict(quantity="conserved", name="spin", reason=CONSERVED, derived=None, states=24, agreeing=24)
    assert describe(ok, NOTE) == "ok (conserved: dC/dt = 0 along the equations of motion, at 24 states on the " \
                                 "constraint surface)"
