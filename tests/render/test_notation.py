"""How expressions and user text are printed: dots, primes, Greek, escaping."""

from __future__ import annotations

import sympy

from lagsolve.render.notation import Notation, md_escape, md_prose, tex_escape, to_json

x, theta = sympy.symbols("x theta", real=True)
x_dot, x_ddot, theta_dot = sympy.symbols("x_dot x_ddot theta_dot", real=True)
f = sympy.Function("f", real=True)
note = Notation(["x", "theta"])


def test_latex_uses_dots_for_rates() -> None:
    """Velocities and accelerations of coordinates print as \\dot{x}, \\ddot{x}, \\dot{\\theta}."""
    assert note.latex(x_dot) == r"\dot{x}"
    assert note.latex(x_ddot) == r"\ddot{x}"
    assert note.latex(theta_dot) == r"\dot{\theta}"


def test_latex_leaves_other_dot_names_alone() -> None:
    """A parameter that merely ends in _dot (not a coordinate's rate) keeps a subscript, upright like any word."""
    assert note.latex(sympy.Symbol("w_dot")) == r"w_{\mathrm{dot}}"


def test_latex_primes_for_declared_functions() -> None:
    """Derivatives of a one-argument declared function print as f'(x), f''(x), f^{(4)}(x)."""
    assert note.latex(sympy.diff(f(x), x)) == r"f'\left(x\right)"
    assert note.latex(sympy.diff(f(x), x, 2)) == r"f''\left(x\right)"
    assert note.latex(sympy.diff(f(x), x, 4)) == r"f^{(4)}\left(x\right)"


def test_text_for_terminals() -> None:
    """Terminal text uses combining dots, Greek letters, primes and superscript squares."""
    expr = -x_dot**2 * sympy.diff(f(x), x, 2) + theta_dot
    assert note.text(expr) == "\u03b8\u0307 - x\u0307\u00b2*f''(x)"
    assert note.text(sympy.Symbol("lambda_wire")) == "λ_wire"


def test_json_is_sympy_str_syntax() -> None:
    """JSON expressions are SymPy str() syntax with the input's names, so parse_expr reads them back."""
    assert to_json(sympy.diff(f(x), x, 2) * x_dot) == "x_dot*Derivative(f(x), (x, 2))"


def test_tex_escape_makes_commands_inert() -> None:
    """TeX commands in user text are printed, never executed."""
    assert tex_escape(r"\input{/etc/passwd}") == r"\textbackslash{}input\{/etc/passwd\}"
    assert tex_escape("100% & $5 #1 a_b ^ ~") == r"100\% \& \$5 \#1 a\_b \textasciicircum{} \textasciitilde{}"


def test_tex_escape_handles_unicode_and_control_characters() -> None:
    """Greek letters become math, characters pdflatex cannot set become '?', control characters vanish."""
    assert tex_escape("θ\a漢") == r"$\theta$?"


def test_markdown_escapes() -> None:
    """Names are fully escaped for Markdown; descriptions keep Markdown but lose raw HTML and math."""
    assert md_escape("<b>*x*</b>") == r"&lt;b&gt;\*x\*&lt;/b&gt;"
    expected = "**bold** &lt;script&gt;alert(1)&lt;/script&gt; \\$x\\$"
    assert md_prose("**bold** <script>alert(1)</script> $x$") == expected


def test_ascii_text_spells_out_what_a_terminal_cannot_show() -> None:
    """Dots over names, Greek letters, powers, subscripts and marks become ASCII, in the input's own names."""
    from lagsolve.render.notation import ascii_text

    assert ascii_text("ẍ = -(g + ẋ²*f''(x))") == "x_ddot = -(g + x_dot**2*f''(x))"
    assert ascii_text("θ\u0307 λ_wire Ω r⁻¹⁰ q₀") == "theta_dot lambda_wire Omega r**-10 q0"
    assert ascii_text("✓ ok, ✗ mismatch, – not checked, x ≥ 0 → é") == "+ ok, X mismatch, - not checked, x >= 0 -> e"


def test_word_subscripts_are_upright() -> None:
    """λ_wire, N_rough and m_cart have upright subscripts; indices and Greek subscripts stay as they are."""
    note = Notation(["x"])
    assert note.latex(sympy.Symbol("lambda_wire")) == r"\lambda_{\mathrm{wire}}"
    assert note.latex(sympy.Symbol("N_rough")) == r"N_{\mathrm{rough}}"
    assert note.latex(sympy.Symbol("m_cart")) == r"m_{\mathrm{cart}}"
    assert note.latex(sympy.Symbol("theta_0")) == r"\theta_{0}"
    assert note.latex(sympy.Symbol("p_phi")) == r"p_{\phi}"


def test_no_leading_minus_in_a_denominator() -> None:
    """x/(−M − m sin²θ) is printed −x/(M + m sin²θ)."""
    x, big, m, th = sympy.symbols("x M m theta")
    note = Notation(["x"])
    assert note.latex(x / (-big - m * sympy.sin(th) ** 2)) == r"- \frac{x}{M + m \sin^{2}{\left(\theta \right)}}"
    assert note.text(x / (-big - m)) == "-x/(M + m)"
    # mixed signs: the first printed term decides (the disk rolling inside a cylinder's -2 g sin θ/(3 (R - r)))
    R, r = sympy.symbols("R r", positive=True)
    assert note.latex(x / (-3 * R + 3 * r)) == r"- \frac{x}{3 R - 3 r}"
    assert note.latex(x / (3 * R - 3 * r)) == r"\frac{x}{3 R - 3 r}"


def test_dotted_letters_in_notes_are_math_in_latex() -> None:
    """A note's q̈, ẋ and Aᵀ are set as math in LaTeX, not printed as '?'."""
    from lagsolve.render.notation import tex_escape

    assert tex_escape("M q\u0308 = F + A\u1d40\u03bb, x\u0307") == r"M $\ddot{q}$ = F + A$^{T}$$\lambda$, $\dot{x}$"


def test_inline_reads_as_written_for_figure_text() -> None:
    """Figure text (mathtext): fractions on the line, no `*` or `**`, and in a sum the terms with a minus sign last,
    a coordinate's before a parameter's."""
    k, L0 = sympy.symbols("k L0", positive=True)
    x1, x2 = sympy.symbols("x1 x2", real=True)
    two = Notation(["x1", "x2"])
    assert two.inline(k * (x2 - x1 - L0) ** 2 / 2) == r"k \left(x_{2} - x_{1} - L_{0}\right)^{2} / 2"
    assert note.inline(k * x_dot ** 2 / 2) == r"k \dot{x}^{2} / 2"
