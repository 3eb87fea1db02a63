"""The format registry (``lagsolve.render.formats``) is what the renderer, the pipeline and the CLI use."""

from __future__ import annotations

from pathlib import Path

import click
import pytest

from lagsolve import cli
from lagsolve.errors import RenderError
from lagsolve.render.formats import DEFAULT_FORMATS, FORMATS, REGISTRY
from lagsolve.render.report import render, template_dirs


def _choices(command: click.Command, option: str) -> list[str]:
    (param,) = [p for p in command.params if p.name == option]
    assert isinstance(param.type, click.Choice)
    return list(param.type.choices)


def test_cli_formats_and_extensions_come_from_the_registry() -> None:
    """``derive --format`` offers the registry's formats (and jsonl); files get the registry's extensions."""
    assert _choices(cli.derive, "fmts") == [*FORMATS, "jsonl"]
    assert cli.EXTENSIONS == {"md": ".md", "tex": ".tex", "html": ".html", "json": ".json"}
    assert DEFAULT_FORMATS == ("md", "tex", "json")


@pytest.mark.parametrize("spec", [f for f in REGISTRY if f.templates is not None], ids=lambda f: f.name)
def test_each_template_format_has_its_packaged_template(spec) -> None:  # noqa: ANN001
    """The entry template of every template format exists in the packaged (or checkout) templates."""
    assert spec.template is not None and spec.templates is not None
    found = [d / spec.template for d in template_dirs(spec.templates) if (d / spec.template).is_file()]
    assert found, f"no {spec.templates}/{spec.template}"
    assert spec.math in ("latex", "mathml") and spec.figures in ("files", "inline")


def test_an_unknown_format_is_refused_with_the_registry(shipped_derivation) -> None:  # noqa: ANN001
    """render() names the formats it knows, from the registry."""
    with pytest.raises(RenderError, match="unknown format 'rtf'; use md, tex, html, json"):
        render(shipped_derivation("bead"), "rtf")


def test_extensions_name_the_written_files(tmp_path: Path) -> None:
    """Every extension starts with a dot and differs from the others (no report overwrites another)."""
    extensions = [f.extension for f in REGISTRY]
    assert all(e.startswith(".") for e in extensions) and len(set(extensions)) == len(extensions)


def test_every_format_has_a_template_or_a_projection() -> None:
    """A format of the registry is either a template or has its text projection of the sections."""
    from lagsolve.render.report import TEXT_PROJECTIONS

    assert {f.name for f in REGISTRY if f.templates is None} == set(TEXT_PROJECTIONS)
