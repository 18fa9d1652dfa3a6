"""`capred retention-convert` and `capred.convert_retention` (issue 34, item 1): a fitted retention curve in
another model, over the suction range of its data; `skempton-b --retention FIT.json` from any fit."""

import json
import warnings

import numpy as np
import pandas as pd
import pytest
from numpy.testing import assert_allclose
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import FitError
from capred.fitting.retention_models import fit_model
from capred.physics import retention as rp

runner = CliRunner()


def _lenhard(n, alpha):
    """Lenhard, Parker & Mishra (1989): λ = m/(1 − m) (1 − 0.5^(1/m)) and the air-entry suction
    s_e = S_x^(−1/λ) (S_x^(−1/m) − 1)^(1−m) / α with S_x = 0.72 − 0.35 exp(−n⁴), m = 1 − 1/n."""
    m = 1 - 1 / n
    lam = m / (1 - m) * (1 - 0.5 ** (1 / m))
    sx = 0.72 - 0.35 * np.exp(-(n**4))
    return lam, sx ** (-1 / lam) * (sx ** (-1 / m) - 1) ** (1 - m) / alpha


@pytest.fixture(scope="module")
def sample(tmp_path_factory):
    out = tmp_path_factory.mktemp("ret") / "r"
    res = runner.invoke(app, ["retention", "--sample", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    return out / "fits.json"


def test_vg_converted_to_vg_is_itself():
    s = np.geomspace(500, 5e5, 25)
    f = fit_model("vg", s, rp.vg_water(s, 0.05, 0.42, 1 / 8000, 2.2))
    c = capred.convert_retention(f, to="vg")
    # the same curve: the parameters to the fit's convergence (~1e-7 relative) and a misfit at rounding level
    for k, v in f.params_si.items():
        assert c.converted.params_si[k] == pytest.approx(v, rel=1e-5, abs=1e-9), k
    assert c.misfit["rmse"] < 1e-8 and c.misfit["max_deviation"] < 1e-7


@pytest.mark.parametrize("n", [2.0, 3.0, 5.0])
def test_brooks_corey_and_van_genuchten_agree_with_lenhard_1989_in_order_of_magnitude(n):
    """Lenhard et al. (1989) match the curves at one point (S_e = S_x); capred fits them over the data's range,
    so the two agree only roughly: λ within 10 %, the air entry within a factor 3 (measured: λ 3-6 %, s_e a
    factor 1.3-2.2 for n = 2-5), in both directions."""
    alpha = 1e-4  # 1/Pa: a characteristic suction of 10 kPa
    s = np.geomspace(1e3, 1e6, 30)
    lam, s_e = _lenhard(n, alpha)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)  # BC cannot follow a smooth VG curve closely
        bc = capred.convert_retention(fit_model("vg", s, rp.vg_water(s, 0.0, 1.0, alpha, n)), to="bc").converted
    assert bc.params_si["lam"] == pytest.approx(lam, rel=0.10)
    assert 1 / 3 < bc.params_si["s_e"] / s_e < 3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        vg = capred.convert_retention(fit_model("bc", s, rp.bc_water(s, 0.0, 1.0, 1e4, lam)), to="vg").converted
    lam_back, s_e_back = _lenhard(vg.params_si["n"], vg.params_si["alpha"])
    assert lam_back == pytest.approx(lam, rel=0.35) and 1 / 3 < s_e_back / 1e4 < 3


def test_a_fit_without_its_suction_range_is_a_clear_error(sample, tmp_path):
    doc = json.loads(sample.read_text(encoding="utf-8"))
    for b in doc["branches"].values():
        for f in b["fits"].values():
            f.pop("suction_range_kPa"), f.pop("suction_points_kPa")
    doc["fits"] = doc["branches"][doc["main_branch"]]["fits"]
    old = tmp_path / "old_fits.json"
    old.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(FitError, match="no suction range"):
        capred.convert_retention(old, to="bc")
    res = runner.invoke(app, ["retention-convert", str(old), "--to", "bc", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "no suction range" in res.stderr and "Traceback" not in res.output
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())
    f = fit_model("vg", np.geomspace(1e3, 1e5, 10), rp.vg_water(np.geomspace(1e3, 1e5, 10), 0, 1, 1e-4, 2))
    f.suction_points = ()
    with pytest.raises(FitError, match="no suction range"):
        capred.convert_retention(f, to="bc")


def test_cli_writes_a_fit_of_the_same_shape(sample, tmp_path):
    out = tmp_path / "c"
    res = runner.invoke(app, ["retention-convert", str(sample), "--to", "kosugi", "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert {"fits.json", "fits.csv", "parameters.csv", "points.csv", "retention_convert.png"} <= {
        p.name for p in out.iterdir()
    }
    js = json.loads((out / "fits.json").read_text(encoding="utf-8"))
    orig = json.loads(sample.read_text(encoding="utf-8"))
    conv = js["fits"]["kosugi"]
    assert {"params_si", "s_m_kPa", "sigma", "suction_range_kPa", "parameters"} <= set(conv)
    assert conv["suction_range_kPa"] == orig["fits"]["vg"]["suction_range_kPa"]
    assert js["conversion"]["from_model"] == "vg" and js["conversion"]["rmse"] < 0.01  # the sample's curve is smooth
    # the converted curve at the data's own points, by hand (Kosugi 1996: S_e = Q(ln(s/s_m)/σ))
    from scipy.stats import norm

    p = conv["params_si"]
    pts = pd.read_csv(out / "points.csv")
    s = pts["suction [kPa]"].to_numpy() * 1e3
    by_hand = p["y_r"] + (p["y_s"] - p["y_r"]) * norm.sf(np.log(s / p["s_m"]) / p["sigma"])
    assert_allclose(pts["S_R_converted [-]"], by_hand, rtol=1e-9)
    # and it is a fit capred's own readers take: shear --retention, where Lu & Likos need van Genuchten and
    # Khalili the air entry of Brooks-Corey, converts the Kosugi fit to both
    res = runner.invoke(
        app,
        ["shear", "--sample", "--models", "lu_likos,khalili", "--retention", str(out / "fits.json"), "--json"],
    )
    assert res.exit_code == 0, res.output


def test_skempton_b_from_a_van_genuchten_fit(sample, tmp_path):
    """--retention with a van Genuchten fit: converted to Brooks-Corey (S_res = 0, S_s = 1) with the misfit in the
    notes; B equals the run with those s_e and λ given by hand."""
    out = tmp_path / "sk"
    res = runner.invoke(app, ["skempton-b", "--S-R", "0.9", "--retention", str(sample), "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    assert (out / "results.csv").exists()
    js = json.loads(res.stdout)
    note = next(n for n in js["notes"] if "converted to Brooks-Corey" in n)
    assert "RMSE" in note
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        api = capred.run_skempton_b(S_R=0.9, retention=str(sample))
        from capred.pipelines.retention_convert import brooks_corey_for_skempton

        s_e, lam, _, _ = brooks_corey_for_skempton(sample)
        by_hand = capred.run_skempton_b(S_R=0.9, s_e=s_e, bc_lambda=lam)
    assert float(api.outputs["B"][0]) == pytest.approx(float(by_hand.outputs["B"][0]), rel=1e-12)
    assert float(api.outputs["B"][0]) == pytest.approx(js["rows"][0]["B"] if "rows" in js else api.outputs["B"][0])
    # a Brooks-Corey fit is taken as it is
    s_e_bc, lam_bc, notes, _ = brooks_corey_for_skempton(_bc_file(sample, tmp_path))
    doc = json.loads(sample.read_text(encoding="utf-8"))
    assert s_e_bc == doc["fits"]["bc"]["params_si"]["s_e"] and lam_bc == doc["fits"]["bc"]["params_si"]["lam"]
    assert "as it is" in notes[0]


def _bc_file(sample, tmp_path):
    doc = json.loads(sample.read_text(encoding="utf-8"))
    for b in doc["branches"].values():
        b["fits"] = {"bc": b["fits"]["bc"]}
    doc["fits"] = {"bc": doc["fits"]["bc"]}
    p = tmp_path / "bc.json"
    p.write_text(json.dumps(doc), encoding="utf-8")
    return p


def test_readings_are_fitted_first_and_the_sample_runs(tmp_path):
    """`retention-convert --sample`: the sample's readings fitted with capred retention's defaults, the best fit of
    the drying branch converted; the same as converting that fit."""
    res = runner.invoke(app, ["retention-convert", "--sample", "--to", "bc", "--out", str(tmp_path / "o"), "--json"])
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        r = capred.run_retention(capred.sample_path("retention"))
        direct = capred.convert_retention(r, to="bc")
    assert js["conversion"]["from_model"] == direct.source_fit.model
    # the same optimum, reached through the CLI (one BLAS thread) and the API (the process's BLAS threads), whose
    # sums differ in their last bits on some CPUs: the optimum is asserted by its objective (1e-8; 1.2e-9 measured
    # between AVX2 and AVX-512 BLAS kernels) and the parameters, near a minimum where the objective is flat to
    # second order, to 1e-6 (5e-9 measured)
    assert js["fits"]["bc"]["rss"] == pytest.approx(direct.converted.rss, rel=1e-8)
    assert js["fits"]["bc"]["params_si"] == pytest.approx(direct.converted.params_si, rel=1e-6)


def test_the_air_entry_of_a_conversion_is_continuous_not_a_node_of_the_grid():
    """Issue 34 loose end: the discrete least squares put Brooks-Corey's s_e on a suction of the dense grid (its
    objective has a kink at each). Least squares over ln s, split at s_e, is smooth in s_e: (1) the air entry
    does not depend on the number of nodes (on the sample before: 2.703, 2.689, 2.650, 2.653 kPa for 50, 100,
    400, 1000 grid points);
    (2) it follows the source curve continuously: a VG curve and its data range both stretched by 1.0001 along
    s give s_e stretched by 1.0001 (the problem is scale-invariant in s; a grid-bound s_e would either stay or
    jump by a grid step of ~4 %). Tolerances: the optimiser's xtol 1e-12 and the fit's convergence, ~1e-8."""
    s = np.geomspace(500, 5e4, 20)
    f = fit_model("vg", s, rp.vg_water(s, 0.05, 0.42, 1 / 3000, 3.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        se = [capred.convert_retention(f, to="bc", points=k).converted.params_si["s_e"] for k in (50, 100, 101, 150)]
        assert_allclose(se, se[0], rtol=1e-7)
        c = 1.0001
        g = fit_model("vg", s * c, rp.vg_water(s * c, 0.05, 0.42, 1 / (3000 * c), 3.0))
        se_stretched = capred.convert_retention(g, to="bc").converted.params_si["s_e"]
    assert se_stretched / se[1] == pytest.approx(c, rel=1e-7)


def test_a_converted_parameter_at_its_bound_is_a_warning(sample):
    """Brooks-Corey fitted to the sample's van Genuchten curve wants S_res < 0: it stops at 0, and says so (as
    capred retention says of a fitted parameter at its bound) in the result, the JSON and as a CapredWarning."""
    with pytest.warns(capred.CapredWarning, match=r"S_res = 0 lies at its bound"):
        c = capred.convert_retention(sample, to="bc")
    assert c.converted.params_si["y_r"] == 0.0 and c.converted.at_bounds() == ["y_r"]
    assert any("S_res = 0 lies at its bound" in w for w in c.warnings)
    assert any("S_res = 0 lies at its bound" in w for w in c.to_json()["fits"]["bc"]["warnings"])


def test_skempton_b_retention_note_names_the_branch_and_the_fit_taken(tmp_path):
    """`skempton-b --retention fits.json` says which fit of the file it took: the main branch's lowest AICc."""
    from typer.testing import CliRunner

    from capred.cli import app
    from capred.pipelines.retention_convert import brooks_corey_for_skempton

    out = tmp_path / "r"
    res = CliRunner().invoke(app, ["retention", "--sample", "--out", str(out), "--no-plots", "--no-html"])
    assert res.exit_code == 0, res.output
    _, _, notes, _ = brooks_corey_for_skempton(out / "fits.json")
    assert "(branch 'drying', its lowest-AICc fit of 3: vg)" in notes[0]
