"""Notes of the derivation with their quantities as math; descriptions with safe $...$ math only."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from lagsolve.render.notation import md_description, md_math_prose, tex_description, tex_prose
from lagsolve.render.prose import description_segments, safe_math, segments

SYMBOLS = {"phi": [r"\phi", "φ"], "Q_phi": [r"Q_{\phi}", "Q_φ"], "x": ["x", "x"], "l": ["l", "l"]}


def test_names_rates_and_relations_become_math() -> None:
    """dL/dphi, Q_phi = 0 and the problem's names are set as math, the words stay text."""
    assert tex_prose("phi is cyclic: dL/dphi = 0, Q_phi = 0", SYMBOLS) == (
        r"$\phi$ is cyclic: $\partial L/\partial \phi = 0$, $Q_{\phi} = 0$")


def test_the_work_sentence_has_no_ascii_names() -> None:
    """'sum of Q_i q_i_dot' is written as the sum it is."""
    out = tex_prose("energy: not conserved, friction does work (sum of Q_i q_i_dot is not 0)", SYMBOLS)
    assert r"$\sum_i Q_i\,\dot q_i$ is not 0" in out and "q\\_i\\_dot" not in out


def test_articles_and_numbers_stay_words() -> None:
    """'a' before a word and a count like '2 coordinates' are not math."""
    assert tex_prose("a generalized force acts on x at rest", SYMBOLS) == "a generalized force acts on $x$ at rest"
    assert segments("2 coordinates are left", SYMBOLS) == [("text", "2 coordinates are left",
                                                            "2 coordinates are left")]


def test_an_expression_in_a_note_gets_exponents() -> None:
    """x**2 in a note is printed x^{2}."""
    assert "$-l^{2}/2 + x^{2}/2 = 0$" in tex_prose("constraint 'rod' (-l**2/2 + x**2/2 = 0) is not solved", SYMBOLS)
    assert "$`-l^{2}/2 + x^{2}/2 = 0`$" in md_math_prose("(-l**2/2 + x**2/2 = 0)", SYMBOLS)


def test_description_math_is_kept_when_safe() -> None:
    r"""$\dot\theta^2$ is math; $\input{x}$ and an unpaired $ are literal text."""
    assert description_segments(r"rate $\dot\theta^2$ here") == [("text", "rate "), ("math", r"\dot\theta^2"),
                                                                  ("text", " here")]
    assert tex_description(r"$\input{/etc/passwd}$") == r"\$\textbackslash{}input\{/etc/passwd\}\$"
    assert tex_description("costs $5") == r"costs \$5"
    assert md_description(r"angle $\theta$ | <b>") == r"angle $`\theta`$ \| &lt;b&gt;"
    assert not safe_math(r"\write18{rm}") and not safe_math("a}{") and safe_math(r"\frac{a}{b}")


def test_markdown_descriptions_keep_emphasis_but_no_link() -> None:
    """A description keeps its emphasis and plain brackets; a link, an image, a bare URL and a backslash that would
    re-open a link are made inert, and a heading line is text."""
    from lagsolve.render.notation import md_cell

    assert md_description("*light* rod [[a, b]]") == "*light* rod [[a, b]]"
    assert md_description("[x](javascript:alert(1))") == r"[x\](javascript:alert(1))"
    assert md_description(r"\[x](y)") == r"\\[x\](y)"
    assert md_description("see https://e.example/a.") == "see `https://e.example/a.`"
    assert md_description("(at https://e.example/a)") == "(at `https://e.example/a`)"
    assert md_description("a\n# b") == "a\n\\# b"
    assert md_cell("a\r\n## b | c") == r"a ## b \| c"
    assert md_cell(r"norm $|x|$") == r"norm $`\|x\|`$"


MALFORMED = [r"\frac{a}", r"\dot", r"x_1_2", "x^", "__", r"\left( x", r"x^2'", r"\sqrt[3", "^^41", r"\dot\frac{a}{b}"]
WELL_FORMED = [r"\frac{1}{2}m\dot x^2", r"\left( x \right.", r"\sqrt[3]{x}", "f''(x)", "x'^2", r"\sum_{i=1}^{n} x_i",
               r"|f''(x)\,\dot x^2 + g|\, m/\sqrt{1 + f'(x)^2}"]


def test_description_math_that_tex_would_refuse_stays_text(tmp_path: Path) -> None:
    """Math of safe pieces put together wrong (``$\\frac{a}$``, ``$x_1_2$``) was set as math, and pdflatex stopped
    on the report; it is literal text now, and the rest is math still (each compiled when pdflatex is here)."""
    assert [m for m in MALFORMED if safe_math(m)] == []
    assert [m for m in WELL_FORMED if not safe_math(m)] == []
    if shutil.which("pdflatex") is None:
        return
    body = " ".join(tex_description(f"${m}$") for m in MALFORMED + WELL_FORMED)
    (tmp_path / "d.tex").write_text(f"\\documentclass{{article}}\n\\usepackage{{amsmath}}\n\\begin{{document}}\n"
                                    f"{body}\n\\end{{document}}\n")
    run = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "d.tex"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-1500:]
