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

**Whole processes** (issue 31.5): ``python benchmarks/bench_retention.py --process [rows] [repeats]`` writes
``rows`` (default 10,000) lab-shaped readings (``common.lab_retention_rows``: the sample's columns, scattered
column heights) and times, interleaved, as whole process trees (``common.run``: CPU of the process and its
waited-for children, and wall time):

- ``capred retention FILE --out DIR`` with its default outputs (fits.json, fits/parameters/points.csv, the
  figure retention.png at 300 dpi, report.html, provenance.json);
- the same with ``--no-plots --no-html`` (tables and JSON only);
- unsatfit fitting the same models to the same readings in its own process (``PEER_SCRIPT``: read the CSV
  with numpy, S_R = (V_v - z2)/V_v, van Genuchten with q = 1, with q free, Brooks-Corey, each as its
  documentation shows, the parameters printed): unsatfit's fit, no figure, no file;
- unsatfit's fit and a figure of the readings and the three curves saved as a PNG at 300 dpi with plain
  matplotlib (``PEER_PLOT``): the nearest unsatfit script to capred's default outputs.

It prints the medians (CPU and wall), the ratios and the load average before and after. With
``CAPRED_BASELINE=/path/to/another/checkout`` that checkout's capred is timed in the same rounds (before and
after a change on the same load).
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

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(1, str(ROOT))  # this checkout's capred
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


PEER_SCRIPT = """
import sys
import numpy as np
import unsatfit

d = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1, usecols=(0, 1, 2))
h, s_r = d[:, 0], (d[:, 2] - d[:, 1]) / d[:, 2]
fits = []
for name, const, extra in (("vg", ["q=1"], ()), ("vg", [], (1.0,)), ("bc", [], ())):
    f = unsatfit.Fit()
    f.swrc = (h, s_r)
    f.set_model(name, const=const)
    f.ini = (max(s_r), 0, *f.get_init(), *extra)
    f.optimize()
    print(name, const, f.success, f.fitted)
    fits.append(f)
"""
PEER_PLOT = """
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(180 / 25.4, 120 / 25.4))
ax.semilogx(h, s_r, "o", ms=2)
hh = np.geomspace(h.min(), h.max(), 300)
for f in fits:
    ax.semilogx(hh, f.f_ht(f.fitted, hh))
ax.set_xlabel("head [cm]")
ax.set_ylabel("S_R [-]")
fig.savefig(sys.argv[2], dpi=300)
"""


def process(rows: int = 10_000, repeats: int = 5) -> None:
    """capred retention's whole process with its default outputs against unsatfit's fit as a whole process."""
    import shutil
    import tempfile

    from common import installed_env, interleaved, lab_retention_rows, ratio_line
    from common import run as run_cmd

    try:
        import unsatfit  # noqa: F401
    except ImportError:
        raise SystemExit("unsatfit is not installed: pip install unsatfit (the benchmark compares with it)")
    tmp = Path(tempfile.mkdtemp(prefix="bench_retention_"))
    data = tmp / "readings.csv"
    lab_retention_rows(data, rows)
    env = {
        **installed_env(tmp / "pycache"),
        "PYTHONPATH": os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]),
    }
    py = sys.executable

    def capred(*extra, root=ROOT):
        out = tmp / "out"
        env_r = {**env, "PYTHONPATH": env["PYTHONPATH"].replace(str(ROOT), str(root), 1)}
        cmd = [py, "-m", "capred", "retention", str(data), "--out", str(out), *extra]
        return lambda: run_cmd(cmd, env=env_r, cwd=tmp)  # not from a checkout: python -m imports the cwd's capred

    peer_fit = [py, "-c", PEER_SCRIPT, str(data)]
    peer_plot = [py, "-c", PEER_SCRIPT + PEER_PLOT, str(data), str(tmp / "peer.png")]
    contestants = {
        "capred retention (default outputs)": capred(),
        "capred retention --no-plots --no-html": capred("--no-plots", "--no-html"),
        "unsatfit fit (3 models)": lambda: run_cmd(peer_fit, env=env),
        "unsatfit fit + PNG (plain matplotlib)": lambda: run_cmd(peer_plot, env=env),
    }
    baseline = os.environ.get("CAPRED_BASELINE")  # another checkout (e.g. an earlier commit), timed alongside
    if baseline:
        contestants[f"baseline {Path(baseline).name} (default outputs)"] = capred(root=Path(baseline))
        contestants[f"baseline {Path(baseline).name} --no-plots --no-html"] = capred(
            "--no-plots", "--no-html", root=Path(baseline)
        )
    print(f"{rows:,} lab-shaped readings; {os.cpu_count()} cores; load average {os.getloadavg()} at the start")
    for fn in contestants.values():
        fn()  # warm-up: page cache, .pyc, matplotlib's font cache
    med = interleaved(contestants, repeats)
    for name, m in med.items():
        print(f"  {name:40s} CPU {m.cpu:6.3f} s  wall {m.wall:6.3f} s")
    base = med["unsatfit fit (3 models)"]
    for name in list(contestants)[:2]:
        print("  " + ratio_line(f"{name} / unsatfit fit, CPU", med[name].cpu, base.cpu, "<= 1.0x"))
        print("  " + ratio_line(f"{name} / unsatfit fit, wall", med[name].wall, base.wall))
    both = med["unsatfit fit + PNG (plain matplotlib)"]
    print("  " + ratio_line("default outputs / unsatfit fit + PNG, CPU", med[list(contestants)[0]].cpu, both.cpu))
    for name in list(contestants)[4:]:
        print("  " + ratio_line(f"{name} / unsatfit fit, CPU", med[name].cpu, base.cpu))
    print(f"load average {os.getloadavg()} at the end")
    shutil.rmtree(tmp, ignore_errors=True)


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
    if "--process" in sys.argv:
        args = [int(a) for a in sys.argv[1:] if a != "--process"]
        process(*args)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
