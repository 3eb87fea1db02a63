"""The compiled templates kept with the install (render/template_cache.py): read, never written, at run time;
the same reports with and without them; a stale or planted entry is not used."""

from __future__ import annotations

import os
from pathlib import Path

import jinja2
import pytest

from lagsolve.render import precompile, template_cache
from lagsolve.render.report import render_sections, sections_summary
from lagsolve.render.sections import build
from mechanics_support import derived_file


def _env(templates: Path, cache: jinja2.BytecodeCache | None) -> jinja2.Environment:
    return jinja2.Environment(loader=jinja2.FileSystemLoader(str(templates)), bytecode_cache=cache,
                              autoescape=False)


def test_build_compiles_every_packaged_template(tmp_path: Path) -> None:
    count = precompile.build(tmp_path)
    entries = sorted((tmp_path / "ImmutableSandboxedEnvironment").iterdir())
    assert count == len(entries) > 30
    assert all(e.suffix == ".cache" and e.stat().st_size > 0 for e in entries)


def test_reports_are_the_same_with_the_compiled_templates(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every format and the terminal summary of a shipped problem, byte for byte, rendered from the cache and
    compiled from the sources (fresh environments each way)."""
    from lagsolve.render import report

    sections = build(derived_file("rotating_tube"))

    def outputs() -> list[str]:
        report._environment.cache_clear()
        return [sections_summary(sections)] + [render_sections(sections, f) for f in ("md", "tex", "html", "json")]

    monkeypatch.setattr(template_cache, "CACHE", tmp_path / "none")
    plain = outputs()
    precompile.build(tmp_path / "cache")
    monkeypatch.setattr(template_cache, "CACHE", tmp_path / "cache")
    cached = outputs()
    report._environment.cache_clear()
    assert cached == plain


def test_the_cache_is_read_only_and_a_stale_entry_is_compiled_again(tmp_path: Path) -> None:
    templates, folder = tmp_path / "templates", tmp_path / "cache"
    templates.mkdir()
    (templates / "page.j2").write_text("one {{ x }}")
    writer = _env(templates, template_cache.Writer(folder))
    folder.mkdir()
    assert writer.get_template("page.j2").render(x=1) == "one 1"
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    (templates / "page.j2").write_text("two {{ x }}")  # edited after the cache was built
    (templates / "other.j2").write_text("three")  # not in the cache
    reader = _env(templates, template_cache.InstalledCache(folder))
    assert reader.get_template("page.j2").render(x=1) == "two 1"
    assert reader.get_template("other.j2").render() == "three"
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before  # nothing written


@pytest.mark.skipif(not hasattr(os, "O_NOFOLLOW"), reason="no O_NOFOLLOW on this platform")
def test_a_symbolic_link_in_the_cache_is_not_followed(tmp_path: Path) -> None:
    templates, folder, elsewhere = tmp_path / "templates", tmp_path / "cache", tmp_path / "elsewhere"
    templates.mkdir()
    (templates / "page.j2").write_text("real {{ x }}")
    folder.mkdir()
    elsewhere.mkdir()
    _env(templates, template_cache.Writer(elsewhere)).get_template("page.j2")
    (entry,) = elsewhere.iterdir()
    cache = template_cache.InstalledCache(folder)
    env, source = _env(templates, cache), "real {{ x }}"
    filename = str(templates / "page.j2")
    (folder / entry.name).write_bytes(entry.read_bytes())  # a plain copy is read (the control)
    assert cache.get_bucket(env, "page.j2", filename, source).code is not None
    (folder / entry.name).unlink()
    (folder / entry.name).symlink_to(entry)
    assert cache.get_bucket(env, "page.j2", filename, source).code is None
