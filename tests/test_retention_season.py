"""season_retention.csv of a batch speaks the units of fits.csv (issue 34 loose end: it said ``rmse [-]`` and
``theta_r [-]`` for θ data, where fits.csv says m³/m³): one rule, the record's unit in ``name [unit]``."""

from pathlib import Path

import pandas as pd
from typer.testing import CliRunner

import capred
from capred.cli import app

DATA = Path(__file__).parent / "data" / "retention"


def test_season_headers_carry_the_units_of_fits_csv(tmp_path):
    manifest = tmp_path / "runs.csv"
    manifest.write_text(
        "command,input,options\n"
        f"retention,{DATA / 'swrc_toyoura_sand_swrcfit.csv'},--no-plots --no-html\n"
        f"retention,{capred.sample_path('retention')},--no-plots --no-html\n"
    )
    res = CliRunner().invoke(app, ["batch", str(manifest), "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    season = pd.read_csv(tmp_path / "out" / "season_retention.csv", dtype=str, keep_default_na=False)
    # θ data (Toyoura sand, SWRC Fit's sample) in m³/m³, S_R data (capred's sample) dimensionless: both columns
    for head in ("rmse [m³/m³]", "theta_r [m³/m³]", "theta_s [m³/m³]", "rmse [-]", "S_res [-]", "alpha [1/kPa]"):
        assert head in season.columns, (head, list(season.columns))
    assert "theta_r [-]" not in season.columns and "r2 [-]" in season.columns
    toyoura = season[season["theta_r [m³/m³]"] != ""].iloc[0]
    runs = sorted((tmp_path / "out").rglob("fits.csv"))
    fits = next(pd.read_csv(p) for p in runs if "RMSE [m³/m³]" in pd.read_csv(p).columns)
    best = fits.loc[fits["AICc [-]"].idxmin()]  # the season row holds the best model (lowest AICc)
    # the same number under the same unit in both files
    assert abs(float(toyoura["rmse [m³/m³]"]) - best["RMSE [m³/m³]"]) <= 1e-12 * best["RMSE [m³/m³]"]
