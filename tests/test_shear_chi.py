"""capred shear answers "chi = ?" (issue 11): back-analysis, pendular scores, bootstrap ranking, bands,
fitted chi laws, the exact-bridge model and the cohesionless envelope."""

import json

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.fitting.chi_laws import akaike_weights, fit_chi_power, information_criteria
from capred.physics import effective_stress_models as esm
from capred.physics import shear as ph
from capred.pipelines.shear_analysis import back_analysis
from capred.report.shear_tables import shear_tables

runner = CliRunner()


def _table(wet_chi, sigma_levels=(1.0, 2.0, 3.0), c=0.2, tan_phi=0.7, R_mm=1.0, noise=None, seed=1):
    """A noise-free (or noisy) shear table in kPa: dry tests on the line, wet tests from a chi law.

    ``wet_chi(S_R, suction_kPa)`` gives chi; sigma'_N = sigma_N + chi Delta_u.
    """
    rng = np.random.default_rng(seed)
    rows = []
    for k, s in enumerate(sigma_levels * 2):
        rows.append(dict(test_id=f"D{k}", condition="dry", sigma_N=s, tau_max=c + s * tan_phi))
    states = [(0.01, 4.0), (0.02, 3.0), (0.04, 2.5), (0.1, 2.0), (0.3, 1.5), (0.6, 1.0), (0.9, 0.5)]
    k = 0
    for s_n in sigma_levels:
        for S, u in states:
            chi = wet_chi(S, u)
            tau = c + (s_n + chi * u) * tan_phi
            if noise:
                tau += rng.normal(0, noise)
            rows.append(dict(test_id=f"W{k}", condition="wet", sigma_N=s_n, tau_max=tau, suction=u, S_R=S, R=R_mm))
            k += 1
    frame = pd.DataFrame(rows)
    return frame.rename(
        columns={"sigma_N": "sigma_N [kPa]", "tau_max": "tau_max [kPa]", "suction": "suction [kPa]", "R": "R [mm]"}
    )


def test_back_analysis_hand_worked():
    # c = 1 kPa, tan phi = 0.5, tau = 3 kPa, sigma_N = 2 kPa, suction 4 kPa:
    # sigma_cap = (3 - 1)/0.5 - 2 = 2 kPa; chi_back = 0.5.
    # var = (1/b)^2 var_c + ((tau-c)/b^2)^2 var_b + 2 (1/b)((tau-c)/b^2) cov + s2/b^2
    #     = 4*0.01 + 64*0.0004 + 2*2*8*(-0.001) + 0.04*4 = 0.04 + 0.0256 - 0.032 + 0.16 = 0.1936 -> se 0.44
    cov = np.array([[[0.01, -0.001], [-0.001, 0.0004]]])
    cap, se, chi, chi_se = back_analysis(
        np.array([3.0]), np.array([2.0]), np.array([4.0]), np.array([1.0]), np.array([0.5]), cov, np.array([0.04])
    )
    assert cap[0] == pytest.approx(2.0, rel=1e-12)
    assert se[0] == pytest.approx(0.44, rel=1e-12)
    assert chi[0] == pytest.approx(0.5, rel=1e-12) and chi_se[0] == pytest.approx(0.11, rel=1e-12)


def test_back_analysis_recovers_the_generating_chi():
    """Noise-free data from chi = S_R: chi_back equals S_R to rounding, sigma_cap = S_R * suction."""
    res = capred.run_shear(_table(lambda S, u: S), capred.ShearOptions(bootstrap=0))
    tests = [t for t in res.to_json()["tests"] if t["condition"] == "wet"]
    for t in tests:
        assert t["chi_back"] == pytest.approx(t["S_R"], abs=1e-9)  # exact data: float rounding only
        assert t["sigma_cap_kPa"] == pytest.approx(t["S_R"] * t["suction_kPa"], abs=1e-9)
        assert t["sigma_cap_pred_kPa"]["bishop"] == pytest.approx(t["sigma_cap_kPa"], abs=1e-9)
        assert set(t) >= {"sigma_cap_se_kPa", "chi_back_se", "sigma_cap_pred_kPa"}


def test_pendular_metrics_use_only_pendular_tests():
    res = capred.run_shear(_table(lambda S, u: S), capred.ShearOptions(bootstrap=0))
    js = res.to_json()
    mat = next(iter(js["metrics"]))
    # 3 normal stresses x 3 states with S_R <= 0.05 (0.01, 0.02, 0.04)
    assert js["metrics_pendular"][mat]["bishop"]["n"] == 9
    assert js["metrics"][mat]["bishop"]["n"] == 21
    assert js["best_model_pendular"][mat] == "bishop"  # the generating model fits exactly
    assert js["metrics_pendular"][mat]["bishop"]["rmse_kPa"] < 1e-9


def test_bootstrap_probabilities_sum_to_one_and_are_deterministic():
    frame = _table(lambda S, u: ph.chi1(S), noise=0.05)
    a = capred.run_shear(frame, capred.ShearOptions(bootstrap=300, seed=7)).to_json()
    b = capred.run_shear(frame, capred.ShearOptions(bootstrap=300, seed=7)).to_json()
    c = capred.run_shear(frame, capred.ShearOptions(bootstrap=300, seed=8)).to_json()
    mat = next(iter(a["best_model_probability"]))
    p = a["best_model_probability"][mat]
    assert sum(p.values()) == pytest.approx(1.0, abs=1e-12)
    assert a["bootstrap"] == b["bootstrap"]
    assert a["bootstrap"][mat]["replicates"] == 300 and c["bootstrap"] != a["bootstrap"]
    lo, hi = a["bootstrap"][mat]["rmse_difference_ci95_kPa"]
    assert lo <= hi


def test_bootstrap_goes_to_one_for_the_generating_model():
    """Noise-free data from Own 1: every resample ranks Own 1 first."""
    res = capred.run_shear(_table(lambda S, u: ph.chi1(S)), capred.ShearOptions(bootstrap=200))
    js = res.to_json()
    mat = next(iter(js["best_model_probability"]))
    assert js["best_model_probability"][mat]["own1"] == 1.0
    assert js["best_model"][mat] == "own1"


def test_chi_power_recovers_kappa_of_noise_free_data():
    """Closed form: data made with chi = S_R^1.7 exactly give kappa = 1.7 and RSS = 0."""
    res = capred.run_shear(
        _table(lambda S, u: S**1.7), capred.ShearOptions(models=("bishop", "chi_power"), bootstrap=0)
    )
    js = res.to_json()
    mat = next(iter(js["fitted"]))
    law = js["fitted"][mat]["chi_power"]
    assert law["params"]["kappa"] == pytest.approx(1.7, rel=1e-7)  # least squares tolerance 1e-14
    assert law["n"] == 21 and law["rss_kPa2"] < 1e-16


def test_chi_power_single_test_closed_form():
    """One wet test: kappa = ln(chi_back)/ln(S_R) exactly."""
    S, u, c, b, s_n = 0.3, 2.0, 0.2, 0.7, 1.0
    chi = 0.45
    tau = c + (s_n + chi * u) * b
    law = fit_chi_power(np.array([s_n]), np.array([u]), np.array([S]), np.array([tau]), c, b)
    assert law.values["kappa"] == pytest.approx(np.log(chi) / np.log(S), rel=1e-8)


def test_khalili_fit_recovers_air_entry():
    res = capred.run_shear(
        _table(lambda S, u: 1.0 if u <= 1.2 else (u / 1.2) ** -0.55),
        capred.ShearOptions(models=("bishop", "khalili_fit"), bootstrap=0),
    )
    law = next(iter(res.to_json()["fitted"].values()))["khalili_fit"]
    # s_b is identified only between the measured suctions that bracket it (1.0 and 1.5 kPa); noise-free
    # data make the RSS zero for s_b = 1.2 exactly
    assert law["params"]["s_b_kPa"] == pytest.approx(1.2, rel=1e-6)
    assert law["params"]["eta"] == 0.55 and law["fixed"] == ["eta"]


def test_aicc_by_hand():
    # RSS = 2, n = 10, one fitted parameter: k = 2; AIC = 10 ln(0.2) + 4 = -12.0944;
    # AICc = AIC + 2*2*3/(10 - 3) = AIC + 1.7143; BIC = 10 ln(0.2) + 2 ln 10 = -11.4892
    ic = information_criteria(2.0, 10, 1)
    assert ic["aic"] == pytest.approx(10 * np.log(0.2) + 4, rel=1e-12)
    assert ic["aicc"] == pytest.approx(10 * np.log(0.2) + 4 + 12 / 7, rel=1e-12)
    assert ic["bic"] == pytest.approx(10 * np.log(0.2) + 2 * np.log(10), rel=1e-12)
    w = akaike_weights({"a": 0.0, "b": 2.0, "c": None})
    # weights exp(0) : exp(-1) normalised
    assert w["a"][1] == pytest.approx(1 / (1 + np.exp(-1))) and w["c"] == (None, None)


def test_model_selection_table_in_json():
    res = capred.run_shear(
        _table(lambda S, u: S**1.7, noise=0.01),
        capred.ShearOptions(models=("bishop", "own1", "chi_power"), bootstrap=0),
    )
    sel = next(iter(res.to_json()["model_selection"].values()))
    assert sel["chi_power"]["k"] == 2 and sel["bishop"]["k"] == 1
    assert sum(v["weight"] for v in sel.values()) == pytest.approx(1.0)
    assert min(v["delta_aicc"] for v in sel.values()) == 0.0


def test_exact_neck_against_the_bridge_solver():
    from capred.physics import bridge as br

    R, gamma, S, u = 1e-3, 0.0728, 0.02, 500.0
    cap, ok = esm.exact_neck_capillary_stress(np.array([S]), np.array([u]), R, gamma, 0.0)
    beta, s_star, status = br.solve_for_volume(0.0, 2 * np.pi * S / 3, 0.0)
    gap, vol, force, y0 = br.geometry(beta, 0.0, s_star)
    assert ok[0] and status[0] == 0
    assert vol[0] == pytest.approx(2 * np.pi * S / 3, rel=1e-9)  # the bridge holds the unit-cell water
    r0 = y0[0] * R
    assert cap[0] == pytest.approx((np.pi * r0**2 * u + 2 * np.pi * r0 * gamma) / (np.pi * R**2), rel=1e-12)


def test_exact_neck_tends_to_israelachvili():
    """S_R -> 0: r0 -> 0 with r0^2 ~ S_R^(1/2) ... and the bridge's own force -> 2 pi R gamma; with the
    bridge's own suction the capillary stress tends to 2 gamma cos(theta)/R (Israelachvili)."""
    from capred.physics import bridge as br

    R, gamma = 1e-3, 0.0728
    for theta in (0.0, 20.0):
        limit = 2 * gamma * np.cos(np.radians(theta)) / R
        errors = []
        for S in (1e-7, 1e-9, 1e-11):
            beta, s_star, status = br.solve_for_volume(np.radians(theta), 2 * np.pi * S / 3, 0.0)
            u = s_star[0] * gamma / R  # the suction this bridge carries
            cap, ok = esm.exact_neck_capillary_stress(np.array([S]), np.array([u]), R, gamma, theta)
            errors.append(abs(cap[0] / limit - 1))
        # the deviation falls like S_R^(1/4) (V^(1/4)): a factor sqrt(10) per two decades, 1e-3 at 1e-11
        assert errors[-1] < 1e-3
        assert errors[0] / errors[1] == pytest.approx(10**0.5, rel=0.05)
        assert errors[1] / errors[2] == pytest.approx(10**0.5, rel=0.05)


def test_exact_neck_flags_tests_without_concave_bridge():
    res = capred.run_shear(_table(lambda S, u: S), capred.ShearOptions(models=("bishop", "exact_neck"), bootstrap=0))
    js = res.to_json()
    wet = [t for t in js["tests"] if t["condition"] == "wet"]
    flagged = [t for t in wet if "no_concave_bridge" in t["flags"]]
    assert flagged and all(t["tau_pred_kPa"]["exact_neck"] is None for t in flagged)
    mat = next(iter(js["metrics"]))
    assert js["metrics"][mat]["exact_neck"]["n"] == len(wet) - len(flagged)
    assert any("exact_neck" in w for w in js["warnings"])


def test_mean_band_and_prediction_interval_match_the_delta_method():
    res = capred.run_shear(_table(lambda S, u: S, noise=0.02), capred.ShearOptions(bootstrap=0))
    t = res.tests
    fit = next(iter(res.fits.values())).line
    i = int(np.flatnonzero(t["condition"] == "wet")[0])
    p = res.predictions["bishop"]
    sig = p.si.sigma_eff[i]
    cov = fit.covariance
    var_mean = cov[0, 0] + 2 * sig * cov[0, 1] + sig**2 * cov[1, 1]
    half = fit.t * np.sqrt(var_mean)
    # the band of the mean: t times the delta-method SE of c + sigma' tan(phi) (numerical derivatives: 1e-6)
    assert p.si.tau_mean_ci[1][i] - p.si.tau[i] == pytest.approx(half, rel=1e-6)
    assert p.si.tau[i] - p.si.tau_mean_ci[0][i] == pytest.approx(half, rel=1e-6)
    # a new test adds the scatter of one test at its strength (the default errors='either': max of s^2 and the
    # proportional model's s_p^2 (tau/ref)^2)
    half_new = fit.t * np.sqrt(var_mean + fit.scatter_variance(p.si.tau[i]))
    assert p.si.tau_prediction_interval[1][i] - p.si.tau[i] == pytest.approx(half_new, rel=1e-6)


def test_dry_fit_through_origin():
    frame = _table(lambda S, u: S, c=0.0)
    js = capred.run_shear(frame, capred.ShearOptions(dry_fit="origin", bootstrap=0)).to_json()
    f = next(iter(js["materials"].values()))
    assert f["c_kPa"] == 0.0 and f["c_se_kPa"] == 0.0
    assert f["tan_phi"] == pytest.approx(0.7, rel=1e-12)
    # noisy: se of the slope = sqrt(s^2 / sum x^2), s^2 = RSS/(n - 1)
    x = np.array([1.0, 2.0, 3.0, 1.0, 2.0, 3.0])
    y = 0.7 * x + np.array([0.01, -0.02, 0.015, -0.005, 0.01, -0.01])
    from capred.fitting.linear import fit_line_origin

    fl = fit_line_origin(x * 1e3, y * 1e3)
    b = float(x @ y / (x @ x))
    s2 = float(np.sum((y - b * x) ** 2)) / 5
    assert fl.slope == pytest.approx(b, rel=1e-12)
    assert fl.slope_se == pytest.approx(np.sqrt(s2 / (x @ x)), rel=1e-12)


def test_cli_options_and_console(tmp_path):
    res = runner.invoke(
        app,
        [
            "shear",
            "--sample",
            "--no-plots",
            "--bootstrap",
            "200",
            "--seed",
            "3",
            "--models",
            "thesis,chi_power",
            "--out",
            str(tmp_path / "o"),
        ],
    )
    assert res.exit_code == 0, res.output
    assert "of resamples" in res.stdout and "Pendular wet tests only" in res.stdout
    assert "ΔAICc" in res.stdout and "Capillary stress carried" in res.stdout
    js = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert js["options"]["bootstrap"] == 200 and js["options"]["seed"] == 3
    assert "kappa" in next(iter(js["fitted"].values()))["chi_power"]["params"]
    bad = runner.invoke(app, ["shear", "--sample", "--dry-fit", "zero"])
    assert bad.exit_code == 1 and "--dry-fit" in bad.stderr


def test_models_are_ranked_on_the_same_wet_tests():
    """Issue 41.2: the exact bridge predicts only the wet tests holding little water. Where it predicts, the table
    is made to match it (so on its own subset it has RMSE ~0 and, before, won with AICc weight 1); it must be
    listed apart with the count it lacks, and Bishop/Own 1 ranked on every wet test."""
    frame = _table(lambda S, u: S, noise=0.02, seed=3)
    first = capred.run_shear(frame, capred.ShearOptions(models=("exact_neck",), bootstrap=0))
    wet = np.flatnonzero(first.tests["condition"] == "wet")
    tau_neck = first.predictions["exact_neck"].si.tau[wet] / 1e3
    has = np.isfinite(tau_neck)
    assert 0 < has.sum() < wet.size  # some tests without a concave bridge
    # its own prediction to 0.001 kPa (an RSS > 0, so that its AICc is defined and would have taken weight 1)
    frame.loc[wet[has], "tau_max [kPa]"] = tau_neck[has] + 0.001 * np.random.default_rng(4).standard_normal(has.sum())
    r = capred.run_shear(frame, capred.ShearOptions(models=("bishop", "own1", "exact_neck"), bootstrap=200, seed=1))
    mat = r.materials[0]
    lack = int(wet.size - has.sum())
    assert r.metrics[mat]["exact_neck"].n == has.sum() and r.metrics[mat]["exact_neck"].rmse_kPa < 0.003
    assert r.best_model[mat] in ("bishop", "own1")
    sel = r.model_selection()[mat]
    assert sel["exact_neck"]["weight"] is None and sel["exact_neck"]["missing"] == lack
    assert sel["bishop"]["weight"] + sel["own1"]["weight"] == pytest.approx(1.0, abs=1e-9)
    assert set(r.ranking[mat].probability) == {"bishop", "own1"}
    js = r.to_json()
    assert js["not_compared"] == {mat: {"exact_neck": lack}}
    table = next(t for t in shear_tables(r) if t.title.startswith("Wet tests: model comparison"))
    assert any(row[-1] == f"not ranked: lacks {lack}" for row in table.rows)
