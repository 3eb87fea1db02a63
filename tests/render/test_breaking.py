"""Breaking long LaTeX formulas into lines that fit a printed page."""

from __future__ import annotations

import sympy

from lagsolve.render.breaking import LINE, boxed, equation, formula, matrix, tex_lines, vector, width
from lagsolve.render.notation import Notation

NOTE = Notation(["theta1", "theta2"])
t1, t2, g, ell, m = sympy.symbols("theta1 theta2 g l m", positive=True)
LONG = sum((sympy.Symbol(f"a{k}") * sympy.sin(t1) * sympy.cos(t2) ** 2 for k in range(30)), sympy.Integer(0))


def test_a_short_formula_is_one_line() -> None:
    """A formula that fits is left as it is."""
    assert tex_lines("a + b") == ["a + b"]


def test_a_long_sum_breaks_between_terms() -> None:
    """Each line of a broken sum fits, and the lines joined give back the sum."""
    tex = NOTE.latex(LONG)
    lines = tex_lines(tex)
    assert len(lines) > 2
    assert all(width(line) <= LINE for line in lines)
    assert " ".join(lines) == tex


def test_a_product_with_a_long_sum_uses_big_parentheses() -> None:
    r"""``c \left(...\right)`` becomes ``c \Bigl(`` ... ``\Bigr)``: no \left/\right pair spans two lines."""
    lines = tex_lines(NOTE.latex(ell * m * LONG))
    assert lines[0].startswith(r"l m \Bigl(") and lines[-1].endswith(r"\Bigr)")
    for line in lines:
        assert line.count(r"\left") == line.count(r"\right")


def test_a_fraction_with_long_parts_is_written_as_a_quotient() -> None:
    """Numerator and denominator both too long: (numerator) / (denominator), each broken."""
    lines = tex_lines(NOTE.latex(-LONG / (LONG + 1)))
    assert lines[0].startswith(r"\Bigl(")
    assert any(line.startswith(r"\Big/ \Bigl(") for line in lines)


def test_equation_rows_align_on_the_relation() -> None:
    """Continuation lines of an equation are indented under its right-hand side."""
    rows = equation(r"\ddot{x}", NOTE.latex(LONG)).split(" \\\\\n")
    assert rows[0].startswith(r"\ddot{x} &= ")
    assert all(r.startswith(r"&\qquad ") for r in rows[1:])


def test_a_wide_matrix_is_written_entry_by_entry() -> None:
    """A 2×2 matrix too wide for the page lists each non-zero entry, and says that the others are zero."""
    tex = NOTE.latex(sympy.Matrix([[LONG, 0], [0, m]]))
    rows = matrix(tex, "M")
    assert "M_{11} &= " in rows and "M_{22} &= m" in rows and "M_{12}" not in rows
    assert "the other entries" in rows
    assert matrix(NOTE.latex(sympy.Matrix([[m, 0], [0, m]])), "M").startswith(r"M &= \left[")


def test_vectors_and_formulas_go_to_a_display_when_long() -> None:
    """A short vector stays in the text, a long one is displayed one component per line."""
    assert vector(["x", "y"], r"\mathbf{r}") == r"$\mathbf{r} = \left(x, y\right)$"
    long = vector([NOTE.latex(LONG), "0"], r"\mathbf{F}")
    assert r"\begin{align*}" in long and r"\mathbf{F}_{x} &= " in long and r"\mathbf{F}_{y} &= 0" in long
    assert formula("h", "m") == "$h = m$"
    assert r"\begin{align*}" in formula("h", NOTE.latex(LONG))


def test_final_answers_are_boxed() -> None:
    """A result is boxed; a long one is broken inside its box."""
    assert boxed("a", "b") == r"a &= \boxed{b}"
    assert r"\boxed{\begin{aligned}[t]" in boxed("a", NOTE.latex(LONG))
