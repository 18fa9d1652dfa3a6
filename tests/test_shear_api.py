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
