"""capred retention against unsatfit (an optional peer): every shared model, the same data, interleaved.

Data: capred's sample (drying branch, 16 points), SWRC Fit's Toyoura sample
(44 points, tests/data/retention), one of van Genuchten's (1980) soils and
2,000 points drawn around a van Genuchten curve.

Shared models (capred name -> unsatfit call):

- ``vg``        -> ``vg`` with q = 1 (m = 1 - 1/n)
- ``vg_m_free`` -> ``vg`` with q free (n = q/(1 - m): m and n independent)
- ``bc``        -> ``bc``
- ``kosugi``    -> ``ln``
- ``fx_no_c``   -> ``fx`` (unsatfit's Fredlund-Xing has no correction factor)
- ``durner``    -> ``vg2`` with q = 1 (two van Genuchten curves, m_i = 1 - 1/n_i)

Each unsatfit fit is what its documentation shows: ``f.ini = (max θ, 0, *f.get_init())`` then
``f.optimize()`` (get_init runs its own preliminary fits; they are part of its cost, as capred's
start grid is part of capred's).

Timing: one warm-up of each, then ``repeats`` rounds; in each round capred and unsatfit alternate
(the order flips every round), so a change of machine load hits both alike. Per fit the median CPU
time (``time.process_time``) and wall time (``time.perf_counter``) are reported, and the ratio
capred/unsatfit of both. One process, one core each: neither library uses threads here (BLAS is
limited to one thread below).

The RSS of both fits is printed: a faster fit that stops higher is not a win. The bounds differ:
capred keeps n <= 100 (m <= 0.99) where unsatfit lets m -> 1, so on very steep data unsatfit can reach
a lower RSS outside capred's range; the column ``rss capred/unsatfit`` shows it.

Run: python benchmarks/bench_retention.py [repeats]   (needs ``pip install unsatfit``; not a dependency)
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CM = 98.1  # Pa per cm of head (gamma_w = 9.81 kN/m^3)
PAIRS = {
    "vg": ("vg", ["q=1"]),
    "vg_m_free": ("vg", []),
    "bc": ("bc", []),
    "kosugi": ("ln", []),
    "fx_no_c": ("fx", []),
    "durner": ("vg2", ["q=1"]),
}


def datasets():
    import pandas as pd

    sample = pd.read_csv(ROOT / "sample_data" / "retention.csv", comment="#")
    dry = sample[sample["branch"] == "drying"]
    s_r = (dry["V_v [cm^3]"] - dry["z2 [cm^3]"]) / dry["V_v [cm^3]"]
    yield "capred sample, drying (16 points)", dry["z1 [cm]"].to_numpy(float), s_r.to_numpy(float)
    for name, label in (
        ("swrc_toyoura_sand_swrcfit.csv", "Toyoura sand (44 points)"),
        ("swrc_vg1980_silt_loam_ge3.csv", "silt loam G.E. 3, van Genuchten 1980"),
    ):
        d = pd.read_csv(ROOT / "tests" / "data" / "retention" / name)
        yield label, d.iloc[:, 0].to_numpy(float), d.iloc[:, 1].to_numpy(float)
    rng = np.random.default_rng(1)
    h = np.geomspace(1, 1e4, 2_000)
    theta = 0.06 + 0.34 * (1 + (h / 40) ** 4) ** -0.75 + rng.normal(0, 0.005, h.size)
    yield "synthetic van Genuchten (2,000 points)", h, theta


def capred_fit(model, h, theta):
    from capred.fitting.retention_models import fit_model

    return fit_model(model, h * CM, theta).rss


def unsatfit_fit(model, h, theta):
    import unsatfit

    name, const = PAIRS[model]
    f = unsatfit.Fit()
    f.swrc = (h, theta)
    f.set_model(name, const=const)
    init = f.get_init()
    if model == "vg_m_free":
        init = (*init, 1.0)  # q starts at 1 (m = 1 - 1/n)
    f.ini = (max(theta), 0, *init)
    f.optimize()
    if not f.success:
        raise RuntimeError(f.message)
    r = f.f_ht(f.fitted, h) - theta
    return float(r @ r)


def clock(fn):
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn()
    return time.process_time() - c0, time.perf_counter() - w0, out


def compare(model, h, theta, repeats):
    """Interleaved timing of one model: {side: (median cpu, median wall, rss)}."""
    sides = {"capred": lambda: capred_fit(model, h, theta), "unsatfit": lambda: unsatfit_fit(model, h, theta)}
    for fn in sides.values():
        fn()  # warm-up (imports, caches)
    times = {k: ([], []) for k in sides}
    rss = {}
    for i in range(repeats):
        for k in ("capred", "unsatfit") if i % 2 == 0 else ("unsatfit", "capred"):
            cpu, wall, rss[k] = clock(sides[k])
            times[k][0].append(cpu)
            times[k][1].append(wall)
    return {k: (statistics.median(c), statistics.median(w), rss[k]) for k, (c, w) in times.items()}


def main(repeats: int = 7) -> None:
    try:
        import unsatfit  # noqa: F401
    except ImportError:
        raise SystemExit("unsatfit is not installed: pip install unsatfit (the benchmark compares with it)")
    warnings.simplefilter("ignore")
    worst = 0.0
    print(
        f"{'model':10s} {'capred cpu':>10s} {'unsatfit cpu':>12s} {'ratio cpu':>9s} {'ratio wall':>10s}"
        f"  {'rss capred':>12s} {'rss unsatfit':>12s} {'rss c/u':>8s}"
    )
    for label, h, theta in datasets():
        print(label)
        for model in PAIRS:
            try:
                r = compare(model, h, theta, repeats)
            except Exception as exc:  # the peer failing is reported, not fatal
                print(f"  {model:10s} unsatfit failed: {type(exc).__name__}: {exc}")
                continue
            (cc, cw, cr), (uc, uw, ur) = r["capred"], r["unsatfit"]
            worst = max(worst, cc / uc)
            print(
                f"  {model:10s} {cc * 1e3:8.1f}ms {uc * 1e3:10.1f}ms {cc / uc:8.2f}x {cw / uw:9.2f}x"
                f"  {cr:12.6g} {ur:12.6g} {cr / ur:8.4f}"
            )
    print(f"worst CPU ratio capred/unsatfit: {worst:.2f}x (target <= 1.0x)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
