"""render/mathml.py: MathML set as a textbook sets it (minus signs, function spacing, parentheses)."""

from __future__ import annotations

from lagsolve.render.mathml import typeset
from lagsolve.render.report import render
from mechanics_support import derived_file


def test_a_minus_is_the_minus_sign_and_a_function_is_spaced() -> None:
    """-g r cos(θ): U+2212 for the minus, a thin space before cos and ⁡ after it, text parentheses."""
    math = ("<math><mrow><mo>-</mo><mi>g</mi><mo>&InvisibleTimes;</mo><mi>r</mi><mo>&InvisibleTimes;</mo>"
            "<mrow><mi>cos</mi><mrow><mo>(</mo><mi>&#952;</mi><mo>)</mo></mrow></mrow></mrow></math>")
    out = typeset(f"<p>a - b</p>{math}")
    assert out.startswith("<p>a - b</p>")  # text outside math is left alone
    assert "<mo>&#8722;</mo>" in out and "<mo>-</mo>" not in out
    assert '<mo rspace="0.1667em">&#8290;</mo><mrow><mi>cos</mi><mo>&#8289;</mo>' in out
    assert out.count('<mo stretchy="false">') == 2


def test_parentheses_around_something_tall_still_stretch() -> None:
    """(a/b)^2 keeps its stretchy parentheses; the inner (x) of sin(x) inside the fraction does not."""
    math = ("<math><msup><mrow><mo>(</mo><mfrac><mi>a</mi><mrow><mi>sin</mi><mrow><mo>(</mo><mi>x</mi><mo>)</mo>"
            "</mrow></mrow></mfrac><mo>)</mo></mrow><mn>2</mn></msup></math>")
    out = typeset(math)
    assert out.count('<mo stretchy="false">') == 2 and out.count("<mo>(</mo>") == 1 and out.count("<mo>)</mo>") == 1


def test_the_html_report_has_no_ascii_minus_in_its_math() -> None:
    """Every minus of the HTML report's math is U+2212 (hole table: V = -g m2 z, the string's multiplier)."""
    page = render(derived_file("hole_table"), "html")
    assert "<mo>-</mo>" not in page and page.count("&#8722;") >= 10


def test_a_negative_number_gets_the_minus_sign() -> None:
    """The mode shape (1, -1): SymPy writes <mn>-1</mn>; it is set as the minus sign and the number 1."""
    out = typeset("<math><mn>-1</mn><mo>,</mo><mn>-0.5</mn><mo>,</mo><mn>2</mn></math>")
    assert "<mn>-" not in out and out.count("<mrow><mo>&#8722;</mo><mn>") == 2 and "<mn>0.5</mn>" in out
