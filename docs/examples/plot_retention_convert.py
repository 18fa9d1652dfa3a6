"""
A retention fit in another model
================================

``capred retention-convert``: the drying van Genuchten fit of the sample column
expressed as Brooks-Corey and Kosugi curves, each the least-squares match of the
fitted curve over the data's suction range, with its misfit.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred

result = capred.run_retention(capred.sample_path("retention"))
vg = result.fits["drying"]["vg"]
s = np.geomspace(result.suction.min(), result.suction.max(), 200)

fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
ax.plot(s / 1e3, vg.S_R(s), "k-", lw=2, label="van Genuchten (fitted)")
for target in ("bc", "kosugi"):
    conv = capred.convert_retention(result, to=target, model="vg", branch="drying")
    print(target, conv.misfit)
    ax.plot(s / 1e3, conv.converted.S_R(s), "--", label=f"as {target}")
ax.set(xscale="log", xlabel="suction [kPa]", ylabel="S_R [-]")
ax.legend(frameon=False)
plt.show()
