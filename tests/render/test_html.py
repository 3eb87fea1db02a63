"""The HTML report: one self-contained page whose MathML a real browser renders (headless Chromium)."""

from __future__ import annotations

import re
import shutil
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from lagsolve.mechanics.derivation import Derivation, derive
from lagsolve.problem.load import load_text
from lagsolve.render.report import render

ROOT = Path(__file__).resolve().parents[2]

HOSTILE = r"""
name: '<script>alert(1)</script>'
description: 'See <img src=x onerror=alert(1)> and $\theta$ and $\input{x}$'
parameters: {m: mass, k: stiffness}
coordinates: {x: '<b>position</b>'}
particles: {p: {mass: m, position: [x, 0]}}
potential: k*x**2/2
"""


@pytest.fixture(scope="module")
def bead(shipped_derivation: Callable[[str], Derivation]) -> Derivation:
    return shipped_derivation("bead")


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """Headless Chromium driven through chromedriver (both from the distribution's packages)."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if chromium is None or driver_path is None:
        pytest.skip("chromium and chromedriver are not installed (apt-get install chromium chromium-driver)")
    webdriver = pytest.importorskip("selenium.webdriver")
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run", "--window-size=1000,1400"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(driver_path), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def test_the_page_is_self_contained(bead: Derivation) -> None:
    """The page has a table of contents, MathML for every result and nothing that loads from elsewhere."""
    html = render(bead, "html")
    assert html.startswith("<!DOCTYPE html>") and '<nav aria-label="Contents">' in html
    assert '<a href="#results">Results</a>' in html and 'id="results"' in html
    assert html.count('<math display="block" class="answer">') == 3  # two accelerations, one multiplier
    assert "<script" not in html and "http://" not in html and "https://" not in html
    assert not re.search(r"""(src|href)="(?!#|data:)""", html)


def test_figures_are_data_uris(bead: Derivation) -> None:
    """A figure the report shows is embedded as a data: URI."""
    html = render(bead, "html", potential={"file": "p.png", "caption": "V"}, files={"p.png": b"\x89PNG fake"})
    assert 'src="data:image/png;base64,iVBORyBmYWtl"' in html


def test_user_text_is_escaped_in_html() -> None:
    """Names and descriptions cannot inject HTML; safe description math is shown, unsafe stays text."""
    html = render(derive(load_text(HOSTILE, "hostile.yaml")), "html")
    assert "<script>" not in html and "<img src=x" not in html and "<b>position" not in html
    assert "&lt;script&gt;" in html and '<i class="m">θ</i>' in html and r"$\input{x}$" in html


def test_the_browser_renders_the_math(bead: Derivation, browser: Any, tmp_path: Path) -> None:
    """Chromium loads the page without console errors or requests, and every math element has a size."""
    page = tmp_path / "bead.html"
    page.write_text(render(bead, "html"), encoding="utf-8")
    browser.get(page.as_uri())
    sizes = browser.execute_script(
        "return Array.from(document.querySelectorAll('math')).map("
        "m => [m instanceof MathMLElement, m.getBoundingClientRect().width, m.getBoundingClientRect().height]);")
    assert len(sizes) > 40
    assert all(is_mathml and width > 0 and height > 0 for is_mathml, width, height in sizes)
    assert browser.execute_script("return performance.getEntriesByType('resource').length;") == 0
    errors = [entry for entry in browser.get_log("browser") if entry["level"] in ("SEVERE", "ERROR")]
    assert errors == []


def test_the_browser_renders_the_normal_modes(browser: Any, tmp_path: Path,
                                              shipped_derivation: Callable[[str], Derivation]) -> None:
    """The coupled pendulums' page: each equilibrium's ω² and mode shapes are MathML that Chromium lays out,
    and the sentence on how the equilibria were found is there."""
    page = tmp_path / "coupled.html"
    page.write_text(render(shipped_derivation("coupled_pendulums"), "html"), encoding="utf-8")
    browser.get(page.as_uri())
    items = browser.execute_script(
        "const h = document.getElementById('equilibria'); const list = h.nextElementSibling.nextElementSibling;"
        "return [h.nextElementSibling.textContent, Array.from(list.querySelectorAll('li')).map(li => "
        "Array.from(li.querySelectorAll('math')).map(m => m.getBoundingClientRect().width > 0 && "
        "m.getBoundingClientRect().height > 0))];")
    sentence, sizes = items
    assert "Found without a general solve" in sentence
    assert len(sizes) == 4 and all(len(maths) >= 7 and all(maths) for maths in sizes)
    errors = [entry for entry in browser.get_log("browser") if entry["level"] in ("SEVERE", "ERROR")]
    assert errors == []


def test_cli_writes_the_html_report(tmp_path: Path) -> None:
    """`lagsolve derive --format html -o FILE.html` writes the page."""
    from click.testing import CliRunner

    from lagsolve.cli import main

    target = tmp_path / "bead.html"
    result = CliRunner().invoke(main, ["derive", str(ROOT / "problems" / "bead.yaml"), "--format", "html",
                                       "-o", str(target)])
    assert result.exit_code == 0, result.output
    assert target.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


def test_description_math_reads_as_unicode() -> None:
    r"""$\cos\theta = 2/3$ and $\sqrt{1 + f'(x)^2}$ read as cos θ = 2/3 and √(1 + f'(x)²) in the page."""
    from lagsolve.render.notation import html_description

    out = str(html_description(r"at $\cos\theta = 2/3$, $m/\sqrt{1 + \dot x^2}$"))
    assert out == 'at <i class="m">cos θ = 2/3</i>, <i class="m">m/√(1 + x\u0307²)</i>'


def test_the_time_slider_moves_the_particles(bead: Derivation, browser: Any, tmp_path: Path) -> None:
    """With a simulation, the slider moves each particle along its path and the plots' cursors follow."""
    from lagsolve.app.pipeline import derive_file
    from lagsolve.app.simulation import SimulationOptions

    reports = derive_file(ROOT / "problems" / "bead.yaml", ("html",),
                          simulate=SimulationOptions(values={}, initial={}, samples=201))
    html = reports.outputs["html"]
    assert 'id="time"' in html and "application/json" in html
    page = tmp_path / "bead.html"
    page.write_text(html, encoding="utf-8")
    browser.get(page.as_uri())
    before = browser.execute_script("return document.querySelector('#path-view circle').getAttribute('cx');")
    browser.execute_script("var s = document.getElementById('time'); s.value = '100';"
                           "s.dispatchEvent(new Event('input'));")
    after, cursor, label = browser.execute_script(
        "return [document.querySelector('#path-view circle').getAttribute('cx'),"
        " document.querySelector('#series-plots line').getAttribute('x1'),"
        " document.getElementById('time-label').textContent];")
    assert after != before and float(cursor) > 40 and label.startswith("t = 5")
    assert browser.execute_script("return performance.getEntriesByType('resource').length;") == 0
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "ERROR")] == []


def test_the_slider_drawing_moves_the_rods(browser: Any, tmp_path: Path) -> None:
    """The double pendulum's page draws its two rods and the pivot; the slider moves the rods' ends with the
    particles (the lower rod starts where the upper particle is)."""
    from lagsolve.app.pipeline import derive_file
    from lagsolve.app.simulation import SimulationOptions

    reports = derive_file(ROOT / "problems" / "double_pendulum.yaml", ("html",),
                          simulate=SimulationOptions(values={}, initial={}, samples=201))
    page = tmp_path / "double_pendulum.html"
    page.write_text(reports.outputs["html"], encoding="utf-8")
    browser.get(page.as_uri())
    script = ("var r = document.querySelectorAll('#path-view line'),"
              " c = document.querySelectorAll('#path-view circle');"
              "return [Array.from(r).map(function (l) { return [l.getAttribute('x1'), l.getAttribute('y1'),"
              " l.getAttribute('x2'), l.getAttribute('y2')]; }), [c[0].getAttribute('cx'), c[0].getAttribute('cy')],"
              " document.querySelectorAll('#path-view polygon').length];")
    rods, upper, pivots = browser.execute_script(script)
    assert len(rods) == 2 and pivots == 1
    assert rods[0][2:] == upper and rods[1][:2] == upper
    browser.execute_script("var s = document.getElementById('time'); s.value = '100';"
                           "s.dispatchEvent(new Event('input'));")
    moved, upper_then, _ = browser.execute_script(script)
    assert moved[0][2:] == upper_then != upper and moved[1][:2] == upper_then
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "ERROR")] == []
