"""
Which closed-form capillary force law? Against the exact bridge
===============================================================

``capred bridge laws`` on a small grid: the laws DEM codes use (Willett et al.
2000, Rabinovich et al. 2005, Lambert et al. 2008, Soulié et al. 2006, Weigert &
Ripperger 1999) against the exact Young-Laplace bridge of the same volume, gap
and contact angle, for equal spheres.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred
from capred.pipelines.bridge_laws import LawsOptions

gaps = tuple(np.round(np.linspace(0.0, 0.2, 11), 3))
result = capred.compare_laws(None, LawsOptions(gaps=gaps, volumes=(1e-3,), angles=(0.0,), ratios=(1.0,)))
t = result.table()
laws = [c.removeprefix("error_") for c in t.columns if c.startswith("error_")]

fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
axes[0].plot(t["D_over_R"], t["F_exact"], "k-", lw=2, label="exact")
for law in laws:
    axes[0].plot(t["D_over_R"], t[f"F_{law}"], lw=1, label=law)
    axes[1].plot(t["D_over_R"], 100 * t[f"error_{law}"].abs(), lw=1, label=law)
axes[0].set(xlabel="D/R", ylabel="F / (2πRγ)", title="V = 1e-3 R³, θ = 0")
axes[1].set(xlabel="D/R", ylabel="|error| [%]", yscale="log")
axes[0].legend(frameon=False, fontsize=7)
plt.show()
