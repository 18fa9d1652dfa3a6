"""Coverage of capred shear's intervals by simulation (issue 30.8), in the slow suite.

Three materials, 6 dry and 10 wet tests each; the wet tests follow Bishop's chi = S_R (so the fitted
chi = S_e^kappa has kappa = 1 with S_res = 0). Each data set goes through `capred.run_shear` whole. Scenarios
(issue 41.6: the DEFAULT options, ``--errors either``, unless a test names another): constant scatter, scatter
proportional to the strength (sd 4 % of tau), 4 dry tests, and one dry outlier (+8 sd).

Binomial tolerance: the intervals of one material share its dry fit, so they are not independent; the
tolerance counts one trial per material and data set (N = 3 x sets, the conservative effective size): with true
coverage 95 % the observed share has sd sqrt(0.95 0.05 / N), and the tests accept 3 sd below the target (a false
alarm about 1 run in 700). The issue's 93 % per third of the stress range (proportional scatter) is checked as
observed >= 93 % - 3 sd.

Run ``python tests/test_shear_coverage.py`` to print the table of the report.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
import pytest

import capred

C_KPA, TAN_PHI, SD_KPA, REL_SD = 0.5, 0.7, 0.3, 0.04
DRY_SIGMA = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
WET_SIGMA = np.linspace(10.0, 60.0, 10)
WET_SUCTION = np.array([20.0, 3.0, 12.0, 6.0, 15.0, 2.0, 9.0, 18.0, 4.0, 8.0])
WET_SR = np.array([0.05, 0.5, 0.1, 0.3, 0.08, 0.6, 0.2, 0.06, 0.4, 0.25])
MATERIALS = ("a", "b", "c")


def _scatter(tau, scenario, rng):
    sd = REL_SD * tau if scenario == "proportional" else np.full(np.shape(tau), SD_KPA)
    return tau + sd * rng.standard_normal(np.shape(tau))


def simulate(
    scenario: str, sets: int, seed: int = 0, errors: str | None = None, loss: str | None = None, n_dry: int = 6
):
    """Coverage shares of one scenario over ``sets`` data sets (3 materials each); ``errors``, ``loss`` None: the
    defaults of `capred.ShearOptions`."""
    rng = np.random.default_rng(seed)
    dry_sigma = DRY_SIGMA if n_dry == 6 else np.linspace(10.0, 60.0, n_dry)
    tau_dry = C_KPA + dry_sigma * TAN_PHI
    cap_true = WET_SR * WET_SUCTION  # Bishop: sigma_cap = S_R s [kPa]
    tau_wet = C_KPA + (WET_SIGMA + cap_true) * TAN_PHI
    thirds = np.digitize(WET_SIGMA, np.quantile(WET_SIGMA, [1 / 3, 2 / 3]), right=True)  # 0, 1, 2 by stress
    hits = {k: [] for k in ("cap", "pred", "mean", "kappa")}
    by_third = {k: [[], [], []] for k in ("cap", "pred")}
    width = []
    kappa, kappa_se, chosen = [], [], []
    for _ in range(sets):
        rows = []
        for m in MATERIALS:
            yd = _scatter(tau_dry, "proportional" if scenario == "proportional" else "constant", rng)
            if scenario == "outlier":
                yd[3] += 8 * SD_KPA
            yw = _scatter(tau_wet, scenario, rng)
            rows += [
                {"test_id": f"{m}D{k}", "material": m, "condition": "dry", "sigma_N [kPa]": s, "tau_max [kPa]": t}
                for k, (s, t) in enumerate(zip(dry_sigma, yd))
            ]
            rows += [
                {
                    "test_id": f"{m}W{k}",
                    "material": m,
                    "condition": "wet",
                    "sigma_N [kPa]": s,
                    "tau_max [kPa]": t,
                    "suction [kPa]": u,
                    "S_R": S,
                    "R [mm]": 1.0,
                }
                for k, (s, t, u, S) in enumerate(zip(WET_SIGMA, yw, WET_SUCTION, WET_SR))
            ]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            chosen_opts = {k: v for k, v in (("errors", errors), ("dry_loss", loss)) if v is not None}
            r = capred.run_shear(
                pd.DataFrame(rows), capred.ShearOptions(models=("bishop", "chi_power"), bootstrap=0, **chosen_opts)
            )
        for m in MATERIALS:
            sel = (r.tests["material"] == m) & (r.tests["condition"] == "wet")
            lo, hi = (v[sel] for v in r.back.sigma_cap_ci_kPa)
            cap_hit = (lo <= cap_true) & (cap_true <= hi)
            plo, phi = (v[sel] for v in r.predictions["bishop"].tau_prediction_interval_kPa)
            new = _scatter(tau_wet, scenario, rng)  # a new test at each state
            pred_hit = (plo <= new) & (new <= phi)
            mlo, mhi = (v[sel] for v in r.predictions["bishop"].tau_mean_ci_kPa)
            width += (phi - plo).tolist()
            hits["cap"] += cap_hit.tolist()
            hits["pred"] += pred_hit.tolist()
            hits["mean"] += ((mlo <= tau_wet) & (tau_wet <= mhi)).tolist()
            for t in range(3):
                by_third["cap"][t] += cap_hit[thirds == t].tolist()
                by_third["pred"][t] += pred_hit[thirds == t].tolist()
            law = r.laws["chi_power"][m]
            klo, khi = law.ci95["kappa"]
            hits["kappa"].append(klo <= 1.0 <= khi)
            kappa.append(law.values["kappa"])
            kappa_se.append(law.se["kappa"])
            chosen.append(r.fits[m].line.errors)
    out = {k: float(np.mean(v)) for k, v in hits.items()}
    out.update({f"{k}_third{t + 1}": float(np.mean(by_third[k][t])) for k in by_third for t in range(3)})
    out["pred_width_kPa"] = float(np.mean(width))  # the interval is in kPa already
    out["n_intervals"] = len(hits["cap"])
    out["n_fits"] = sets * len(MATERIALS)  # independent dry fits: the effective sample size of the tolerance
    out["n_kappa"] = len(kappa)
    out["kappa_se_ratio"] = float(np.mean(kappa_se) / np.std(kappa, ddof=1))
    # the same ratio robust to the few fits where kappa runs off (an unidentified kappa: SE ~1e9, warned about)
    k = np.asarray(kappa)
    out["kappa_se_ratio_median"] = float(np.median(kappa_se) / (1.4826 * np.median(np.abs(k - np.median(k)))))
    out["chose_proportional"] = float(np.mean([c == "proportional" for c in chosen]))
    return out


def _floor(target: float, n: int) -> float:
    """target - 3 binomial sd at n trials."""
    return target - 3 * math.sqrt(target * (1 - target) / n)


def _assert_thirds(res: dict, keys=("cap", "pred")) -> None:
    """The issue's floor: 93 % in each third of the stress range, less 3 binomial sd of the effective sample
    size (one trial per material and data set, the intervals of a material sharing its dry fit)."""
    for key in keys:
        for t in (1, 2, 3):
            assert res[f"{key}_third{t}"] >= 0.93 - 3 * math.sqrt(0.95 * 0.05 / res["n_fits"]), (key, t, res)


def test_defaults_cover_under_both_scatters_cheap():
    """Everyday version (about 2 s): 12 data sets of each scatter with the defaults. Measured at 300 sets
    (docs/user_guide/uncertainty_defaults.md) every third covers >= 94.9 %; with 36 fits the floor is
    93 % - 3 x 3.6 %, so only a real loss (the old ``auto`` gave 83 % at the top third) fails it."""
    for scenario in ("proportional", "constant"):
        res = simulate(scenario, 12, seed=21)
        _assert_thirds(res)
        assert res["kappa"] >= _floor(0.95, res["n_kappa"]), res


@pytest.mark.slow
def test_defaults_proportional_scatter_per_third_of_the_stress_range():
    """Issue 41's criterion: 300 data sets, scatter 4 % of the strength, default options."""
    res = simulate("proportional", 300, seed=2)
    _assert_thirds(res)
    assert res["kappa"] >= _floor(0.95, res["n_kappa"]) - 0.02, res  # 93 %: the floor for kappa
    # the old default (auto: a Breusch-Pagan switch) misses at the high-stress end (what 'either' is for)
    auto = simulate("proportional", 100, seed=2, errors="auto")
    assert auto["pred_third3"] < res["pred_third3"]


@pytest.mark.slow
def test_defaults_constant_scatter_per_third_of_the_stress_range():
    res = simulate("constant", 300, seed=1)
    _assert_thirds(res)
    for key in ("cap", "pred", "mean"):
        assert res[key] >= _floor(0.95, res["n_fits"]), (key, res)
    assert res["kappa"] >= _floor(0.95, res["n_kappa"]), res


@pytest.mark.slow
def test_defaults_four_dry_tests_and_one_outlier():
    for scenario, n_dry in (("constant", 4), ("proportional", 4), ("outlier", 6)):
        res = simulate(scenario, 100, seed=3, n_dry=n_dry)
        _assert_thirds(res, ("cap", "pred"))
        assert res["kappa"] >= 0.93 - 3 * math.sqrt(0.95 * 0.05 / res["n_kappa"]), (scenario, res)


@pytest.mark.slow
def test_proportional_option_keeps_its_meaning():
    res = simulate("proportional", 150, seed=2, errors="proportional")
    _assert_thirds(res)
    # and constant errors on the same data fail at the high-stress end (what the option is for)
    flat = simulate("proportional", 100, seed=2, errors="constant")
    assert flat["pred_third3"] < res["pred_third3"]


@pytest.mark.slow
def test_outlier_with_huber_kappa_se_matches_its_spread():
    # issue 30's criterion on the Huber sandwich, with the constant error model it was stated for: kappa's median
    # SE within 1.3x of its robust spread (either way). Under the default --errors either kappa's SE is
    # conservative (median ratio 1.1-1.6: the wet scatter is not pooled with the dry one, see the docs page)
    res = simulate("outlier", 150, seed=3, loss="huber", errors="constant")
    assert 1 / 1.3 <= res["kappa_se_ratio_median"] <= 1.3, res


if __name__ == "__main__":  # the coverage table of the report (more sets than the tests)
    import sys

    sets = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    rows = {
        "constant, defaults": simulate("constant", sets, seed=11),
        "proportional, defaults": simulate("proportional", sets, seed=12),
        "4 dry tests, defaults": simulate("constant", sets, seed=13, n_dry=4),
        "4 dry tests, proportional, defaults": simulate("proportional", sets, seed=13, n_dry=4),
        "outlier, defaults": simulate("outlier", sets, seed=14),
        "proportional, --errors proportional": simulate("proportional", sets, seed=12, errors="proportional"),
        "proportional, --errors auto": simulate("proportional", sets, seed=12, errors="auto"),
        "proportional, --errors constant": simulate("proportional", sets, seed=12, errors="constant"),
        "outlier, --dry-loss huber": simulate("outlier", sets, seed=14, loss="huber"),
    }
    keys = [
        "cap",
        "pred",
        "mean",
        "kappa",
        "cap_third1",
        "cap_third2",
        "cap_third3",
        "pred_third1",
        "pred_third2",
        "pred_third3",
        "kappa_se_ratio",
        "kappa_se_ratio_median",
        "pred_width_kPa",
    ]
    print(f"{sets} data sets x 3 materials per scenario")
    print("| scenario | n_fits | " + " | ".join(keys) + " |")
    for name, res in rows.items():
        print(f"| {name} | {res['n_fits']} | " + " | ".join(f"{res[k]:.3f}" for k in keys) + " |")
