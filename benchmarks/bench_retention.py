"""capred retention against unsatfit (an optional peer), the same models on the same data, in one run.

Data: SWRC Fit's Toyoura sample (44 points, tests/data/retention) and 10,000
points drawn around a van Genuchten curve. Models with a counterpart in
unsatfit: Brooks-Corey (``bc``), Kosugi (``ln``), Fredlund-Xing without C
(``fx``). Each fit is timed as the median of repeats after one warm-up, both
libraries in this process; the RSS of both fits is printed too (a faster fit
that stops higher is not a win).

Run: python benchmarks/bench_retention.py [repeats]   (pip install unsatfit to include the peer)
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CM = 98.1  # Pa per cm of head (gamma_w = 9.81 kN/m^3)
PAIRS = {"bc": "bc", "kosugi": "ln", "fx_no_c": "fx"}


def timed(fn, repeats):
    fn()  # warm-up (imports, caches)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def datasets():
    import pandas as pd

    sample = pd.read_csv(ROOT / "sample_data" / "retention.csv", comment="#")
    dry = sample[sample["branch"] == "drying"]
    s_r = (dry["V_v [cm^3]"] - dry["z2 [cm^3]"]) / dry["V_v [cm^3]"]
    yield "capred sample, drying (16 points)", dry["z1 [cm]"].to_numpy(float), s_r.to_numpy(float)
    d = pd.read_csv(ROOT / "tests" / "data" / "retention" / "swrc_toyoura_sand_swrcfit.csv")
    yield "Toyoura (44 points)", d.iloc[:, 0].to_numpy(float), d.iloc[:, 1].to_numpy(float)
    rng = np.random.default_rng(1)
    h = np.geomspace(1, 1e4, 10_000)
    theta = 0.06 + 0.34 * (1 + (h / 40) ** 4) ** -0.75 + rng.normal(0, 0.005, h.size)
    yield "synthetic (10,000 points)", h, theta


def capred_fit(model, h, theta):
    from capred.fitting.retention_models import fit_model

    return fit_model(model, h * CM, theta).rss


def unsatfit_fit(model, h, theta):
    import unsatfit

    f = unsatfit.Fit()
    f.swrc = (h, theta)
    f.set_model(model, const=[])
    f.ini = (max(theta), 0, *f.get_init())
    f.optimize()
    p = f.fitted
    r = f.f_ht(p, h) - theta
    return float(r @ r)


def main(repeats: int = 5) -> None:
    try:
        import unsatfit  # noqa: F401
        peer = True
    except ImportError:
        peer = False
        print("unsatfit is not installed: capred timings only (pip install unsatfit)")
    for label, h, theta in datasets():
        print(label)
        for ours, theirs in PAIRS.items():
            t_c, rss_c = timed(lambda: capred_fit(ours, h, theta), repeats)
            line = f"  {ours:8s} capred {t_c * 1e3:8.1f} ms  RSS {rss_c:.6g}"
            if peer:
                try:
                    t_u, rss_u = timed(lambda: unsatfit_fit(theirs, h, theta), repeats)
                    line += f" | unsatfit {t_u * 1e3:8.1f} ms  RSS {rss_u:.6g} | capred/unsatfit {t_c / t_u:.2f}"
                except Exception as exc:  # the peer failing is reported, not fatal
                    line += f" | unsatfit failed: {type(exc).__name__}: {exc}"
            print(line)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
