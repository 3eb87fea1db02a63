"""Issue 34: ``lagsolve variants`` — bad options exit 2 with a message and a fix before any work; the files are
byte-identical for a seed whatever PYTHONHASHSEED; each written problem file passes ``lagsolve check``; the
library function writes the same files."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from variants_support import TUBE, TUBE_VARY

import lagsolve
from lagsolve.cli import main

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"


@pytest.mark.parametrize(("options", "message", "fix"), [
    (["--vary", "nu=0.1:0.6"], "unknown name 'nu'", "known: m, g, Omega, mu, mu_s, r, phi, z"),
    (["--vary", "mu_s=0.6:0.1"], "LOW 0.6 is above HIGH 0.1", "swap them: --vary mu_s=0.1:0.6"),
    (["--vary", "mu_s=0.1:0.6:0"], "STEP must be positive", "e.g. --vary"),
    (["--vary", "mu_s=0.1:x"], "expected two or three finite numbers", "e.g. --vary"),
    (["--vary", "mu_s=0.1:0.6", "--vary", "mu_s=0.2:0.3"], "'mu_s' is varied twice", "give each name once"),
    (["--vary", "mu_s=0.1:0.6", "--require", "release"], "release needs a unilateral constraint",
     "problems/sliding_off_sphere.yaml"),
])
def test_bad_options_exit_2_before_any_work(tmp_path: Path, options: list[str], message: str, fix: str) -> None:
    started = time.process_time()
    result = CliRunner().invoke(main, ["variants", str(TUBE), "--count", "3", *options, "-o", str(tmp_path / "hw")])
    assert result.exit_code == 2, result.output
    assert message in result.output and fix in result.output
    assert time.process_time() - started < 1.5  # refused before the derivation
    assert not (tmp_path / "hw").exists()


def test_stick_on_a_file_without_friction_is_refused(tmp_path: Path) -> None:
    result = CliRunner().invoke(main, ["variants", str(PROBLEMS / "bead.yaml"), "--count", "2", "--vary", "g=1:2",
                                       "--require", "stick", "-o", str(tmp_path)])
    assert result.exit_code == 2 and "stick needs a friction contact" in result.output


def test_an_impossible_regime_runs_out_of_attempts_with_exit_2(tmp_path: Path) -> None:
    # mu_s*g >= 9.81*0.6 > Omega**2*r <= 0.25*1: the particle is always held, so slip never happens
    result = CliRunner().invoke(main, ["variants", str(TUBE), "--count", "2", "--vary", "mu_s=0.6:0.7",
                                       "--vary", "Omega=0.1:0.5", "--require", "slip", "--attempts", "5",
                                       "-o", str(tmp_path / "hw")])
    assert result.exit_code == 2, result.output
    assert "only 0 of 2 variants passed in 5 attempts (rejected: regime 5" in result.output
    assert "widen or move the --vary ranges" in result.output


def _run(folder: Path, hashseed: str) -> dict[str, bytes]:
    env = {**os.environ, "PYTHONHASHSEED": hashseed}
    command = [sys.executable, "-m", "lagsolve", "variants", str(TUBE), "--count", "3", "--seed", "11",
               *(f"--vary={v}" for v in TUBE_VARY), "--to", "prairielearn", "-o", str(folder)]
    subprocess.run(command, check=True, env=env, cwd=ROOT, capture_output=True)
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_same_seed_same_bytes_whatever_the_hash_seed(tmp_path: Path) -> None:
    first, second = _run(tmp_path / "a", "1"), _run(tmp_path / "b", "4242")
    assert first == second and len(first) == 3 * 3 + 3 + 3
    result = subprocess.run([sys.executable, "-m", "lagsolve", "check",
                             *(str(tmp_path / "a" / f"variant-0{i}" / "rough_level_tube.yaml") for i in (1, 2, 3))],
                            cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0 and result.stdout.count("ok (symbolic)") >= 3 * 6, result.stdout
    key, model = tmp_path / "a" / "variant-02" / "rough_level_tube.yaml", tmp_path / "a" / "model_submission.yaml"
    graded = subprocess.run([sys.executable, "-m", "lagsolve", "grade", str(key), str(model), "--format", "json"],
                            cwd=ROOT, capture_output=True, text=True)
    assert graded.returncode == 0, graded.stderr
    (grade,) = json.loads(graded.stdout)["submissions"]
    assert grade["points"] == grade["max_points"] > 10


def test_the_library_function_writes_the_same_files(tmp_path: Path) -> None:
    made = lagsolve.variants(TUBE, count=2, vary={"mu_s": "0.1:0.6", "Omega": "1:4", "r": "0.5:1.5"}, seed=2,
                             output=tmp_path)
    assert [v.index for v in made.variants] == [1, 2]
    assert (tmp_path / "variant-02" / "key.json").is_file() and (tmp_path / "variants.csv").is_file()
    with pytest.raises(lagsolve.SpecError, match="unknown regime"):
        lagsolve.variants(TUBE, count=2, vary=["mu_s=0.1:0.6"], require="sticky")


def test_variants_stays_the_function_after_the_package_is_imported() -> None:
    import importlib

    importlib.import_module("lagsolve.variants.run")
    assert callable(lagsolve.variants) and lagsolve.variants is lagsolve.api.variants


def test_a_link_inside_the_output_folder_is_refused(tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "hw").mkdir()
    (tmp_path / "hw" / "variant-01").symlink_to(elsewhere, target_is_directory=True)
    result = CliRunner().invoke(main, ["variants", str(TUBE), "--count", "1", "--vary", "mu_s=0.1:0.6",
                                       "-o", str(tmp_path / "hw")])
    assert result.exit_code == 2 and "link" in result.output
    assert list(elsewhere.iterdir()) == []


def test_stick_with_a_contact_that_starts_sliding_is_refused_with_the_fix(tmp_path: Path) -> None:
    result = CliRunner().invoke(main, ["variants", str(PROBLEMS / "rotating_tube.yaml"), "--count", "2",
                                       "--vary", "mu=0.1:0.6", "--require", "stick", "-o", str(tmp_path)])
    assert result.exit_code == 2 and "contact wall starts sliding (r_dot = 0.5" in result.output
    assert "--vary r_dot=0:0" in result.output


def test_figures_are_drawn_on_request(tmp_path: Path) -> None:
    lagsolve.variants(TUBE, count=1, vary=["mu_s=0.1:0.6"], figures=True, output=tmp_path)
    for name in ("coordinates", "forces"):
        assert (tmp_path / "variant-01" / f"{name}.png").read_bytes().startswith(b"\x89PNG")
        assert f"![{name}]({name}.png)" in (tmp_path / "variant-01" / "solution.md").read_text(encoding="utf-8")
