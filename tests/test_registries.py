"""A model is one registry entry: a toy model of each family, added as one entry, runs end to end
(API, CLI, JSON, results table, figure, report.html) with no other change."""

import json
from html import unescape

import numpy as np
import pytest
from numpy.testing import assert_allclose
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.fitting import retention_models as rm
from capred.physics import effective_stress_models as esm

runner = CliRunner()


@pytest.fixture
def toy_stress_model(monkeypatch):
    """chi = S_R / 2: half of Bishop's capillary stress, registered as one entry."""
    entry = esm.EffectiveStressModel(
        "toy_half",
        "Half Bishop",
        (),
        "bishop1959",
        lambda d: d.sigma_N + 0.5 * d.S_R * d.suction,
        style={"color": "yellow", "marker": "x"},
        method="Toy: σ'_N = σ_N + S_R Δu/2.",
        chi_of_saturation=lambda S, p, f: 0.5 * np.asarray(S, float),
    )
    monkeypatch.setitem(esm.REGISTRY, "toy_half", entry)
    return entry


def test_toy_effective_stress_model_runs_end_to_end(toy_stress_model, tmp_path):
    opts = capred.ShearOptions(models=("bishop", "toy_half"), bootstrap=0)
    r = capred.run_shear(capred.sample_path("shear"), opts)
    fit = r.fits[r.tests["material"][-1]]
    i = len(r.tests["test_id"]) - 1  # a wet test of the sample
    sig = r.tests["sigma_N"][i] + 0.5 * r.tests["S_R"][i] * r.tests["suction"][i]
    # by hand: tau = c + sigma' tan(phi); float rounding only
    assert_allclose(r.predictions["toy_half"].tau[i], fit.intercept + sig * fit.slope, rtol=1e-12)
    row = r.to_json()["tests"][i]
    assert_allclose(row["tau_pred_kPa"]["toy_half"], (fit.intercept + sig * fit.slope) / 1e3, rtol=1e-12)
    assert "tau_pred_toy_half [kPa]" in r.table().columns
    assert "toy_half" in r.to_json()["metrics"][r.tests["material"][-1]]

    res = runner.invoke(
        app, ["shear", "--sample", "--models", "bishop,toy_half", "--bootstrap", "0", "--out", str(tmp_path / "o")]
    )
    assert res.exit_code == 0, res.output
    html = unescape((tmp_path / "o" / "report.html").read_text(encoding="utf-8"))
    assert "Toy: σ'_N = σ_N + S_R Δu/2." in html and "Half Bishop" in html
    doc = json.loads((tmp_path / "o" / "summary.json").read_text(encoding="utf-8"))
    assert doc["models"] == ["bishop", "toy_half"]
    assert any(p.suffix == ".png" for p in (tmp_path / "o").iterdir())


@pytest.fixture
def toy_retention_model(monkeypatch):
    """S_e = exp(-a s): one parameter a [1/Pa], registered as one entry."""
    a = rm._p("a_exp", "$a$", "1/Pa", "decay rate", "inverse_suction", 1e-3, 1e3, 0.0, 6)
    entry = rm.RetentionModel(
        "toy_exp",
        "Exponential",
        r"$S_e = e^{-a s}$",
        (rm.Y_R, rm.Y_S, a),
        lambda s, a_exp: np.exp(-a_exp * s),
        ("vangenuchten1980",),
        "Toy: θ = θ_r + (θ_s − θ_r) exp(−a s).",
        "toy_exp: exponential toy",
        dict(ls="-"),
        inverse=lambda S, a_exp: -np.log(S) / a_exp,
    )
    monkeypatch.setitem(rm.MODELS, "toy_exp", entry)
    return entry


def test_toy_retention_model_recovers_its_parameter(toy_retention_model, tmp_path):
    s = np.geomspace(100.0, 50e3, 15)  # Pa
    y = 0.05 + (0.40 - 0.05) * np.exp(-2e-4 * s)  # exact data: a = 2e-4 1/Pa = 0.2 1/kPa
    path = tmp_path / "toy.csv"
    path.write_text("suction [kPa],theta\n" + "".join(f"{float(a) / 1e3!r},{float(b)!r}\n" for a, b in zip(s, y)))
    r = capred.run_retention(path, capred.RetentionOptions(models=("toy_exp",)))
    fit = r.fits["drying"]["toy_exp"]
    # exact data: the optimum is the generating parameter to the solver's tolerance
    assert_allclose(fit.params["a_exp"], 2e-4, rtol=1e-6)
    assert_allclose(fit.suction(0.05 + 0.35 * np.exp(-1.0)), 1 / 2e-4, rtol=1e-6)  # S_e = 1/e at s = 1/a
    js = r.to_json()["branches"]["drying"]["fits"]["toy_exp"]
    assert_allclose(js["a_exp_per_kPa"], 0.2, rtol=1e-6)

    res = runner.invoke(app, ["retention", str(path), "--model", "toy_exp", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    html = unescape((tmp_path / "o" / "report.html").read_text(encoding="utf-8"))
    assert "Exponential" in html
    assert (tmp_path / "o" / "retention.png").is_file()
