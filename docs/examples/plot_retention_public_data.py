"""
Retention models on public data: Toyoura sand and the soils of van Genuchten (1980)
===================================================================================

Public data sets of the test corpus (``tests/data/retention``; sources in its
README): Toyoura sand, the sample of SWRC Fit (Seki 2007), and Guelph loam
from van Genuchten (1980, Table 1). Five models each, compared by AICc.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import capred

DATA = Path("../../tests/data/retention")  # from docs/examples/, where the gallery runs this script
files = {
    "Toyoura sand (SWRC Fit)": "swrc_toyoura_sand_swrcfit.csv",
    "Guelph loam (van Genuchten 1980)": "swrc_vg1980_guelph_loam_drying.csv",
}
models = ("vg", "vg_m_free", "bc", "kosugi", "fx")

fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
for ax, (title, name) in zip(axes, files.items()):
    result = capred.run_retention(DATA / name, capred.RetentionOptions(models=models))
    branch = next(iter(result.fits))
    ax.plot(result.suction / 1e3, result.water, "ko", ms=3, label="data")
    s = np.geomspace(result.suction.min(), result.suction.max(), 200)
    selection = result.to_json()["model_selection"]
    for model, fit in result.fits[branch].items():
        ax.plot(s / 1e3, fit(s), lw=1, label=f"{model} (ΔAICc {selection[model]['delta_aicc']:.1f})")
    ax.set(title=title, xscale="log", xlabel="suction [kPa]", ylabel="θ [m³/m³]")
    ax.legend(frameon=False, fontsize=7)
plt.show()
