"""One language for retention from Python to the page (issue 28, items 1, 2, 8): fit.params by JSON name in the
JSON's units, fit.summary(), the old names deprecated with their old values, typed records, CSV headers."""

import json
import warnings

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.parameters import Parameters

runner = CliRunner()


@pytest.fixture(scope="module")
def result():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        return capred.run_retention(capred.sample_path("retention"), capred.RetentionOptions(hysteresis="kool-parker"))


def test_params_equal_the_json(result):
    """The issue's done-when: params["alpha_per_kPa"].value equals the JSON value (the same float, no rounding)."""
    js = result.to_json()
    fit = result.fits["drying"]["vg"]
    assert isinstance(fit.params, Parameters)
    assert fit.params["alpha_per_kPa"].value == js["fits"]["vg"]["alpha_per_kPa"]
    assert fit.params["alpha_per_kPa"].unit == "1/kPa"
    for model, f in result.fits["drying"].items():
        jf = js["branches"]["drying"]["fits"][model]
        assert list(f.params) == jf["parameters"]
        for p in f.params.values():
            assert p.value == jf[p.name]
            if jf[f"{p.name}_se"] is not None:
                assert p.stderr == jf[f"{p.name}_se"] and list(p.ci95) == jf[f"{p.name}_ci95"]


def test_units_are_the_json_units(result):
    """alpha in 1/kPa is 1000 x alpha in 1/Pa; s_e in kPa is s_e in Pa / 1000; the interval is value ± t se."""
    f = result.fits["drying"]["vg"]
    assert f.params["alpha_per_kPa"].value == pytest.approx(f.params_si["alpha"] * 1e3, rel=1e-15)
    bc = result.fits["drying"]["bc"]
    assert bc.params["s_e_kPa"].value == pytest.approx(bc.params_si["s_e"] * 1e-3, rel=1e-15)
    assert bc.params["s_e_kPa"].unit == "kPa" and bc.params["S_s"].unit == "-"
    p = f.params["n"]
    assert p.ci95[1] - p.value == pytest.approx(f.t * p.stderr, rel=1e-12)


def test_old_names_keep_their_old_value_and_unit_with_a_deprecation_warning(result):
    f = result.fits["drying"]["vg"]
    with pytest.warns(DeprecationWarning, match=r"params\['alpha_per_kPa'\]"):
        old = f.params["alpha"]
    assert old == f.params_si["alpha"] and old == pytest.approx(f.params["alpha_per_kPa"].value / 1e3, rel=1e-15)
    with pytest.warns(DeprecationWarning, match=r"S_res"):
        assert f.params["y_r"] == f.params["S_res"].value
    # a name that did not change (n) computes like a number as before
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=DeprecationWarning, module=r"capred(\.|$)")
        assert f.params["n"] * 2 == pytest.approx(2 * f.params_si["n"]) and f"{f.params['n']:.2f}"


def test_summary_is_a_fit_report(result):
    text = result.fits["drying"]["vg"].summary()
    assert "alpha_per_kPa" in text and "1/kPa" in text and "AICc" in text and "R²" in text
    h = result.hysteresis
    assert set(h.params) == {"S_res", "S_s", "n", "alpha_d_per_kPa", "alpha_w_per_kPa"}
    assert "alpha_w_per_kPa" in h.summary()


def test_records_and_tables(result):
    recs = result.fit_records("drying")
    assert [r.model for r in recs] == list(result.fits["drying"])
    assert sum(r.weight for r in recs) == pytest.approx(1.0, rel=1e-12)  # Akaike weights sum to 1
    t = result.tables()
    assert list(t) == ["fits", "parameters", "points"]
    for name, df in t.items():
        for c in df.columns:  # name [unit] form, or a text column
            assert c.endswith("]") or c in (
                "branch",
                "model",
                "parameter",
                "unit",
                "fixed",
                "converged",
                "value",
                "standard error",
                "95 % CI low",
                "95 % CI high",
            ), (name, c)
    assert "AICc [-]" in t["fits"].columns and "suction [kPa]" in t["points"].columns
    # the points table holds the fitted curve at each reading, by hand for one reading
    pts = t["points"]
    f = result.fits["drying"]["vg"]
    row = pts[pts["branch"] == "drying"].iloc[3]
    assert row["S_R_vg [-]"] == pytest.approx(float(f(row["suction [kPa]"] * 1e3)), rel=1e-12)


def test_cli_writes_name_unit_headers(tmp_path):
    out = tmp_path / "o"
    res = runner.invoke(app, ["retention", "--sample", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    fits = pd.read_csv(out / "fits.csv")
    assert "R² [-]" in fits.columns and "RMSE [-]" in fits.columns
    js = json.loads((out / "fits.json").read_text(encoding="utf-8"))
    assert js["fits"]["vg"]["units"]["alpha_per_kPa"] == "1/kPa"
    params = pd.read_csv(out / "parameters.csv")
    vg_alpha = params[(params["model"] == "vg") & (params["parameter"] == "alpha_per_kPa")]
    assert vg_alpha["branch"].tolist()[0] == "drying"
    assert vg_alpha["value"].tolist()[0] == pytest.approx(js["fits"]["vg"]["alpha_per_kPa"], rel=1e-12)
    assert np.isfinite(params["value"]).all()


def test_stderr_by_json_name_and_the_old_names_deprecated():
    """fit.stderr speaks the JSON's names and units, as fit.params does (issue 28.2; issue 34: the converted
    fit's used internal names): alpha_per_kPa [1/kPa] is 1000 x the SI value [1/Pa]; an old internal name
    returns the OLD SI value with a DeprecationWarning naming the new key; a converted fit has None for each."""
    r = capred.run_retention(capred.sample_path("retention"))
    f = r.fits["drying"]["vg"]
    assert set(f.stderr) == {"S_res", "S_s", "alpha_per_kPa", "n"}
    assert f.stderr["alpha_per_kPa"] == pytest.approx(1e3 * f.stderr_si["alpha"], rel=1e-15)
    assert f.stderr["alpha_per_kPa"] == f.params["alpha_per_kPa"].stderr  # the same number as the record's
    with pytest.warns(DeprecationWarning, match=r"fit.stderr\['alpha_per_kPa'\]"):
        assert f.stderr["alpha"] == f.stderr_si["alpha"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)  # BC cannot follow the VG curve closely
        c = capred.convert_retention(f, to="bc").converted
    assert dict(c.stderr) == {"S_res": None, "S_s": None, "s_e_kPa": None, "lambda": None}
