"""The Python API of `capred shear` in the user's units (issue 28.2, 28.8): fit.params, summary(), deprecations,
errors that quote the value as given, and summary.csv / metrics.csv each holding one kind of record."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

import capred
from capred.errors import OptionError


@pytest.fixture(scope="module")
def run():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return capred.run_shear(
            capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, models=("bishop", "chi_power", "khalili_fit"))
        )


def test_envelope_params_equal_the_json_in_kpa_and_degrees(run):
    js = run.to_json()
    for m, fit in run.fits.items():
        p = fit.params
        # the same number written twice: equal to float rounding of the kPa conversion
        assert p["c_kPa"].value == pytest.approx(js["materials"][m]["c_kPa"], rel=1e-12)
        assert p["phi_deg"].value == pytest.approx(js["materials"][m]["phi_deg"], rel=1e-12)
        assert p["c_kPa"].stderr == pytest.approx(js["materials"][m]["c_se_kPa"], rel=1e-12)
        assert p["phi_deg"].unit == "deg" and p["c_kPa"].unit == "kPa"
        # by hand from the SI line: c [Pa] / 1000 and atan(tan phi) in degrees
        assert p["c_kPa"].value == pytest.approx(fit.line.intercept / 1e3, rel=1e-12)
        assert p["phi_deg"].value == pytest.approx(np.degrees(np.arctan(fit.line.slope)), rel=1e-12)
        lo, hi = p["c_kPa"].ci95
        assert lo < p["c_kPa"].value < hi
        text = fit.summary()
        assert "c_kPa" in text and "phi_deg" in text and m in text


def test_old_envelope_attributes_keep_pa_and_warn(run):
    fit = next(iter(run.fits.values()))
    with pytest.warns(DeprecationWarning, match=r'params\["c_kPa"\]'):
        c_pa = fit.intercept
    assert c_pa == fit.line.intercept  # the old value in its old unit (Pa), not kPa
    with pytest.warns(DeprecationWarning, match="tan_phi"):
        assert fit.slope == fit.line.slope


def test_law_params_in_kpa_and_the_old_si_key_warns(run):
    m = next(iter(run.fits))
    law = run.laws["khalili_fit"][m]
    js = run.to_json()["fitted"][m]["khalili_fit"]
    assert law.params["s_b_kPa"].value == pytest.approx(js["params"]["s_b_kPa"], rel=1e-12)
    assert law.params["s_b_kPa"].value == pytest.approx(law.values["s_b"] / 1e3, rel=1e-12)
    assert law.params["eta"].fixed
    with pytest.warns(DeprecationWarning, match="s_b_kPa"):
        assert law.params["s_b"] == law.values["s_b"]  # Pa, as before
    kappa = run.laws["chi_power"][m]
    assert kappa.params["kappa"].value == kappa.values["kappa"]
    assert "kappa" in kappa.summary("chi_power")


def test_api_error_quotes_the_value_as_given():
    with pytest.raises(OptionError) as e:
        capred.ShearOptions(box_area=-3)
    msg = str(e.value)
    assert "box_area=-3" in msg and "m^2" in msg
    with pytest.raises(OptionError, match="air_entry=-5, a plain number read in Pa"):
        capred.ModelParams(air_entry=-5)
    with pytest.raises(OptionError, match="box_area='-3 cm\\^2'"):
        capred.ShearOptions(box_area="-3 cm^2")


def test_summary_and_metrics_tables_hold_one_kind_of_record(run, tmp_path):
    tables = run.csv_tables()
    summary, metrics = tables["summary"], tables["metrics"]
    assert list(summary["material"]) == list(run.fits)  # one row per material, no model rows
    assert "model" not in summary
    for header in list(summary) + list(metrics):
        assert header in ("material", "model", "best", "dry_fit", "errors", "dry_loss") or header.endswith("]")
    assert set(metrics["model"]) == set(run.models)
    from capred.io.writers import write_run

    write_run(run, tmp_path / "out", xlsx=False)
    assert (tmp_path / "out" / "metrics.csv").exists()
    json.loads((tmp_path / "out" / "summary.json").read_text(encoding="utf-8"))


def test_models_all_runs_what_the_inputs_allow_and_names_the_rest():
    opts = capred.ShearOptions(models="all", bootstrap=0)
    # the registry's requirements: vanapalli needs --s-res, khalili --air-entry, lu_likos --vg-alpha and --vg-n
    assert opts.skipped_models == {
        "vanapalli": "--s-res",
        "khalili": "--air-entry",
        "lu_likos": "--vg-alpha and --vg-n",
    }
    assert "vanapalli" not in opts.models and "bishop" in opts.models and "chi_power" in opts.models
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = capred.run_shear(capred.sample_path("shear"), opts)
    notes = r.to_json()["notes"]
    assert any("'vanapalli' skipped" in n and "--s-res" in n for n in notes)
    # given what it needs, the model runs and is no longer skipped
    full = capred.ShearOptions(models="all", bootstrap=0, model_params=capred.ModelParams(s_res=0.05))
    assert "vanapalli" in full.models and "vanapalli" not in full.skipped_models
    # a named model without its inputs still stops with the reason (the user asked for it by name)
    with pytest.raises(OptionError, match="--s-res"):
        capred.ShearOptions(models="bishop,vanapalli")


def test_cli_models_all(tmp_path):
    from typer.testing import CliRunner

    from capred.cli import app

    res = CliRunner().invoke(
        app,
        ["shear", "--sample", "--models", "thesis,all", "--bootstrap", "0", "--no-plots", "--out", str(tmp_path / "o")],
    )
    assert res.exit_code == 0, res.output
    assert "'khalili' skipped" in res.output
    js = json.loads((tmp_path / "o" / "summary.json").read_text(encoding="utf-8"))
    assert "khalili" not in js["models"] and "bishop" in js["models"]
