"""`capred shear` with scatter growing with stress and a dry outlier (issue 30.1-30.2): the run names both in the
JSON (heteroscedasticity, flags, outliers), the warnings and the methods text, and --errors / --dry-loss change
the envelope as documented."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

import capred
from capred.errors import OptionError


def _frame(outlier: float = 0.0, seed: int = 2):
    rng = np.random.default_rng(seed)
    rows = []
    sig = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])  # kPa
    tau = 0.5 + 0.7 * sig + 0.3 * rng.standard_normal(6)
    tau[3] += outlier
    for k, (s, t) in enumerate(zip(sig, tau)):
        rows.append(
            {"test_id": f"D{k}", "material": "sand", "condition": "dry", "sigma_N [kPa]": s, "tau_max [kPa]": t}
        )
    for k, (S, u) in enumerate([(0.02, 4.0), (0.05, 3.0), (0.1, 2.0), (0.2, 1.5)] * 2):
        s = 15.0 + 10 * k
        t = 0.5 + (s + S * u) * 0.7 + 0.3 * rng.standard_normal()
        rows.append(
            {
                "test_id": f"W{k}",
                "material": "sand",
                "condition": "wet",
                "sigma_N [kPa]": s,
                "tau_max [kPa]": t,
                "suction [kPa]": u,
                "S_R": S,
                "R [mm]": 1.0,
            }
        )
    return pd.DataFrame(rows)


def _run(frame, **opts):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = capred.run_shear(frame, capred.ShearOptions(bootstrap=0, models=("bishop",), **opts))
    return r, [str(w.message) for w in caught]


def test_dry_outlier_is_flagged_everywhere():
    r, caught = _run(_frame(outlier=8 * 0.3 * 3), errors="constant")  # +7.2 kPa, 24 standard deviations
    js = r.to_json()
    row = js["tests"][3]
    assert row["test_id"] == "D3" and "dry_outlier" in row["flags"]
    assert all("dry_outlier" not in t["flags"] for i, t in enumerate(js["tests"]) if i != 3)
    out = js["materials"]["sand"]["outliers"]
    assert len(out) == 1 and out[0]["line"] == 5  # header line 1, D0 on line 2: D3 on line 5
    assert abs(out[0]["studentized_residual"]) > out[0]["threshold"]
    assert any("outlier of the dry envelope" in w and "line 5" in w for w in r.warnings)
    assert any("outlier of the dry envelope" in w for w in caught)  # Python's warnings too
    assert "dry_outlier" in set(r.table()["flags"].iloc[3].split(";"))


def test_huber_limits_the_outlier_and_its_intervals():
    frame = _frame(outlier=7.2)
    ols, _ = _run(frame, errors="constant")
    hub, _ = _run(frame, errors="constant", dry_loss="huber")
    clean, _ = _run(_frame(outlier=0.0), errors="constant")
    o, h, c = (x.fits["sand"].params["phi_deg"] for x in (ols, hub, clean))
    assert abs(h.value - c.value) < abs(o.value - c.value)  # pulled back towards the clean envelope
    assert h.stderr < o.stderr  # the outlier no longer inflates the scatter
    assert hub.to_json()["materials"]["sand"]["dry_loss"] == "huber"
    assert "Huber" in " ".join(hub.method_notes()[0])


def test_heteroscedasticity_reported_and_errors_option_used():
    r, _ = _run(_frame(), errors="proportional")
    js = r.to_json()
    h = js["heteroscedasticity"]["sand"]
    for key in ("statistic", "p_value", "decision"):
        assert key in h["dry_fit"] and key in h["models"]["bishop"]
    assert h["errors"] == "proportional" and js["materials"]["sand"]["errors"] == "proportional"
    assert "proportional to the strength" in " ".join(r.method_notes()[0])
    auto, _ = _run(_frame(), errors="auto")
    p = auto.to_json()["heteroscedasticity"]["sand"]["dry_fit"]["p_value"]
    assert auto.fits["sand"].line.errors == ("proportional" if p < 0.05 else "constant")  # the written rule
    with pytest.raises(OptionError, match="errors"):
        capred.ShearOptions(errors="log")
    with pytest.raises(OptionError, match="dry_loss"):
        capred.ShearOptions(dry_loss="cauchy")


def test_proportional_intervals_widen_with_stress():
    r, _ = _run(_frame(), errors="proportional")
    pred = r.predictions["bishop"]
    wet = np.flatnonzero(r.tests["condition"] == "wet")
    lo, hi = pred.si.tau_prediction_interval
    width = (hi - lo)[wet]
    s = r.tests["sigma_N"][wet]
    assert width[np.argmax(s)] > 2 * width[np.argmin(s)]  # 85 kPa against 15 kPa: the scatter grows with tau
    const, _ = _run(_frame(), errors="constant")
    lo_c, hi_c = const.predictions["bishop"].si.tau_prediction_interval
    wc = (hi_c - lo_c)[wet]
    assert wc.max() < 1.5 * wc.min()  # constant scatter: nearly equal widths
