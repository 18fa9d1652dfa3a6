"""Compute tests/data/retention/reference_optima.csv: the lowest RSS of a 200-start global search per data set and
retention model, over each model's own domain (its bounds in capred.fitting.retention_models, e.g. Fredlund &
Xing's n > 0).

The search shares nothing with capred's fit: scipy's least_squares (trust-region reflective) on all parameters
(no variable projection, natural coordinates, x_scale='jac', tolerances 1e-13) from 200 starts drawn uniformly
inside the bounds (log-uniformly for the log-scaled parameters), seed 0; the lowest end point is kept. The data
sets: every public set of tests/data/retention (heads in cm, θ; benchmarks/bench_retention.py uses three of
them) and both branches of capred's bundled sample (sample_data/retention.csv, S_R from the burette).
Suction = head x 98.1 Pa/cm.

Run once: python tests/data/retention/make_reference_optima.py [OUT.csv [JOBS]] (about 30 minutes of one core;
the stored file was computed with this search on 16 cores in 3 minutes, at the commit that bounded n > 0).
tests/test_retention_domain.py reads the file (the tests no longer search for their own reference optimum).
"""

from __future__ import annotations

import csv
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(ROOT))
CM = 98.1
N_STARTS = 200

from capred.fitting.retention_models import MODELS, bounds_for  # noqa: E402


def _rows(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def datasets():
    """(name, suction [Pa], water) of every set."""
    for p in sorted(HERE.glob("*.csv")):
        if p.name.startswith("reference_"):  # the reference tables themselves (optima, conversions)
            continue
        rows = _rows(p)
        h, w = list(rows[0])[:2]
        yield p.stem, np.array([float(r[h]) for r in rows]) * CM, np.array([float(r[w]) for r in rows])
    rows = _rows(ROOT / "sample_data" / "retention.csv")
    for b in ("drying", "wetting"):
        x = [r for r in rows if r["branch"] == b]
        vv, z2 = (np.array([float(r[k]) for r in x]) for k in ("V_v [cm^3]", "z2 [cm^3]"))
        yield f"sample_{b}", np.array([float(r["z1 [cm]"]) for r in x]) * CM, (vv - z2) / vv


def global_search(name, s, y, n_starts=N_STARTS, seed=0):
    """Lowest RSS and its parameters over n_starts random starts inside the model's bounds."""
    model = MODELS[name]
    names = model.names
    b = bounds_for(s, y, name)
    lo = np.array([b[k][0] for k in names])
    hi = np.array([b[k][1] for k in names])
    logp = model.log_params
    rng = np.random.default_rng(seed)

    def resid(v):
        with np.errstate(all="ignore"):
            r = model.water(s, **dict(zip(names, v))) - y
        return np.where(np.isfinite(r), r, 1e3)

    best, best_x = np.inf, None
    for _ in range(n_starts):
        x0 = [
            o + np.exp(rng.uniform(np.log(a - o), np.log(c - o)))
            if (o := logp.get(k)) is not None
            else rng.uniform(a, c)
            for k, a, c in zip(names, lo, hi)
        ]
        x0 = np.clip(x0, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo))
        r = least_squares(resid, x0, bounds=(lo, hi), x_scale="jac", ftol=1e-13, xtol=1e-13, gtol=1e-13, max_nfev=3000)
        if 2 * r.cost < best:
            best, best_x = 2 * r.cost, r.x
    return best, dict(zip(names, best_x))


def _case(args):
    data, name, s, y = args
    t = time.process_time()
    rss, x = global_search(name, s, y)
    print(data, name, rss, f"{time.process_time() - t:.1f} s", flush=True)
    return {
        "data": data,
        "model": name,
        "rss": repr(float(rss)),
        "n_starts": N_STARTS,
        "seed": 0,
    }


def main(out=HERE / "reference_optima.csv", jobs=1):
    """Every (data set, model) case, on ``jobs`` processes; the table written to ``out``."""
    from concurrent.futures import ProcessPoolExecutor

    cases = [(data, name, s, y) for data, s, y in datasets() for name in MODELS]
    with ProcessPoolExecutor(jobs) as pool:
        rows = list(pool.map(_case, cases))
    with open(out, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main(
        Path(sys.argv[1]) if len(sys.argv) > 1 else HERE / "reference_optima.csv",
        int(sys.argv[2]) if len(sys.argv) > 2 else 1,
    )
