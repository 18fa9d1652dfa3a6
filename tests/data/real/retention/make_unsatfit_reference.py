"""Recompute unsatfit_reference.csv: unsatfit's own optimum on each data set of this folder.

Run with unsatfit installed (``pip install unsatfit==6.3``), from this folder:
``python make_unsatfit_reference.py > unsatfit_reference.csv``. The tests read the CSV; they never
need unsatfit. Settings are those of unsatfit's sample codes (docs/sample-wrc/{VG,BC,KO,FX}.py):
initial values (max(theta), 0, *get_init()), theta_r free, VG with m = 1 - 1/n ('q=1').
The residual sum of squares in theta is (1 - R2) * sum((theta - mean)^2), from unsatfit's own R2.
"""

import sys
from importlib.metadata import version

import numpy as np
import pandas as pd
import unsatfit

VERSION = version("unsatfit")

MODELS = {"VG": ["q=1"], "BC": [], "KO": [], "FX": []}


def data_sets():
    """(name, branch, suction, water content) of every data set: unsatfit's samples, and each branch of the UNSODA files."""
    for name in ["gilat", "clay2362", "IL", "andisol"]:
        table = pd.read_csv(f"unsatfit_{name}.csv")
        yield f"unsatfit_{name}", "", np.asarray(table["h"], float), np.asarray(table["theta"], float)
    for name in ["fx_sand_fig17", "bc_silty_loam"]:
        table = pd.read_csv(f"pmsim_{name}.csv")
        yield f"pmsim_{name}", "", table["s [kPa]"].to_numpy(float), table["S_r"].to_numpy(float)
    for code in ["1410", "1301"]:
        table = pd.read_csv(f"unsoda_{code}.csv", comment="#")
        for branch, rows in table.groupby("branch"):
            yield f"unsoda_{code}", branch, rows["h [cm]"].to_numpy(float), rows["theta [m3/m3]"].to_numpy(float)


print("data,branch,model,rss,r2,n_points,params,unsatfit_version")
for name, branch, h, theta in data_sets():
    sst = float(np.sum((theta - theta.mean()) ** 2))
    for model, const in MODELS.items():
        f = unsatfit.Fit()
        f.set_model(model, const=list(const))
        f.swrc = (h, theta)
        f.ini = (max(theta), 0, *f.get_init())
        f.optimize()
        if not f.success:
            print(f"{name} {model}: {f.message}", file=sys.stderr)
            continue
        params = " ".join(f"{p:.10g}" for p in f.fitted)
        rss = (1.0 - f.r2_ht) * sst
        print(f"{name},{branch},{model},{rss:.10g},{f.r2_ht:.10g},{len(h)},{params},{VERSION}")
