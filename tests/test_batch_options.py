"""season.csv and season.html show each run's options that differ from the command's defaults (issue 44, item 5):
the same tests give another cohesion with --dry-loss huber, and the season table says why."""

from __future__ import annotations

import shutil

import pandas as pd
from typer.testing import CliRunner

import capred
from capred.batch import changed_options
from capred.cli import app
from capred.pipelines.shear import ShearOptions


def test_default_options_show_nothing():
    assert changed_options(ShearOptions()) == ""
    assert changed_options(None) == ""


def test_changed_options_in_the_units_a_user_types():
    """gamma_w is held in N/m³ and shown in kN/m³ (its glossary unit); 9.81 kN/m³ typed in another unit that
    converts back to the default is no change."""
    text = changed_options(ShearOptions(dry_loss="huber", bootstrap=0, gamma_w=10_000.0))
    assert text == "gamma_w 10 kN/m³; dry_loss huber; bootstrap 0"
    assert changed_options(ShearOptions(gamma_w="9.81 kN/m^3")) == ""


def test_season_shows_each_runs_options(tmp_path):
    shutil.copy(capred.sample_path("shear"), tmp_path / "a.csv")
    manifest = tmp_path / "m.csv"
    manifest.write_text(
        "command,input,options\n"
        "shear,a.csv,--no-plots --no-html --bootstrap 0\n"
        "shear,a.csv,--no-plots --no-html --bootstrap 0 --dry-loss huber\n"
    )
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["batch", str(manifest), "--out", str(out), "--workers", "1"])
    assert res.exit_code == 0, res.output
    table = pd.read_csv(out / "season.csv", dtype=str, keep_default_na=False)
    assert list(table["options"]) == ["bootstrap 0", "dry_loss huber; bootstrap 0"]
    page = (out / "season.html").read_text(encoding="utf-8")
    assert '<th class="l">options</th>' in page and "dry_loss huber; bootstrap 0" in page
