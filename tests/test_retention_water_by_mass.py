"""Water content by mass alone (issue 39, item 4): `w` without rho_d fits w(s) with the same models and outputs
(w_s, w_r); with rho_d it is still converted to θ = w ρ_d/ρ_w."""

import json

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.physics import retention as rp
from capred.pipelines.retention import RetentionOptions, run_retention

runner = CliRunner()
S_KPA = np.geomspace(1, 1000, 25)
#: w(s) of van Genuchten with w_r 0.04, w_s 0.30, α 0.05 1/kPa, n 1.7 (no scatter: the fit returns them)
W = rp.vg_water(S_KPA * 1e3, 0.04, 0.30, 5e-5, 1.7)


def test_w_alone_fits_w_s_and_w_r(tmp_path):
    """A w [%] column without rho_d: exit 0, the parameters named w_s, w_r in [-] (percent read as 0.01), equal to
    the generating ones to the optimiser's tolerance (1e-6 relative: exact data)."""
    src = tmp_path / "w.csv"
    pd.DataFrame({"suction [kPa]": S_KPA, "w [%]": 100 * W}).to_csv(src, index=False)
    out = tmp_path / "o"
    res = runner.invoke(app, ["retention", str(src), "--model", "vg,bc", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "fits.json").read_text(encoding="utf-8"))
    assert doc["quantity"] == "w"
    vg = doc["fits"]["vg"]
    assert vg["w_s"] == pytest.approx(0.30, rel=1e-6) and vg["w_r"] == pytest.approx(0.04, rel=1e-6)
    assert vg["units"]["w_s"] == "-" and vg["n"] == pytest.approx(1.7, rel=1e-6)
    assert "w [-]" in pd.read_csv(out / "points.csv").columns
    assert set(pd.read_csv(out / "parameters.csv")["parameter"]) >= {"w_s", "w_r"}
    assert any("without dry density" in n for n in doc["notes"])


def test_w_with_rho_d_is_still_theta():
    """θ = w ρ_d/ρ_w: with ρ_d 1500 kg/m³, θ_s = 0.30 x 1.5 = 0.45 and θ_r = 0.06."""
    res = run_retention(
        pd.DataFrame({"suction [kPa]": S_KPA, "w": W, "rho_d": 1500.0}), RetentionOptions(models=("vg",))
    )
    assert res.quantity == "theta"
    p = res.fits["drying"]["vg"].params
    assert p["theta_s"].value == pytest.approx(0.45, rel=1e-6) and p["theta_r"].value == pytest.approx(0.06, rel=1e-6)


def test_a_w_fit_converts_and_keeps_its_names(tmp_path):
    res = run_retention(pd.DataFrame({"suction [kPa]": S_KPA, "w": W}), RetentionOptions(models=("vg",)))
    import capred

    conv = capred.convert_retention(res, to="kosugi")
    assert conv.quantity == "w" and "w_s" in conv.converted.params
