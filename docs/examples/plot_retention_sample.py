"""
Water retention: drying and wetting branches of the sample column
=================================================================

``capred retention --sample``: van Genuchten (m = 1 − 1/n and m free) and
Brooks-Corey fitted per branch at the global optimum, with model selection by
AICc. A fitted curve is callable: ``fit.S_R(suction_Pa)``.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred

result = capred.run_retention(capred.sample_path("retention"))
for model, row in result.to_json()["model_selection"].items():
    print(f"{model:10s} ΔAICc {row['delta_aicc']:7.2f}   Akaike weight {row['weight']:.3f}")

# %%
# The readings of each branch and the fitted curves:
s = np.geomspace(result.suction.min() / 2, result.suction.max() * 2, 200)  # Pa
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
for k, branch in enumerate(result.fits):
    on = result.branch == branch
    ax.plot(result.suction[on] / 1e3, result.water[on], "o", color=f"C{k}", ms=4, label=f"{branch} readings")
    for style, (model, fit) in zip(("-", "--", ":"), result.fits[branch].items()):
        ax.plot(s / 1e3, fit.S_R(s), style, color=f"C{k}", lw=1, label=f"{branch}: {model}")
ax.set(xscale="log", xlabel="suction [kPa]", ylabel="S_R [-]")
ax.legend(frameon=False, fontsize=7)
plt.show()

# %%
# The parameters of the drying van Genuchten fit, with standard errors and intervals:
print(result.fits["drying"]["vg"].summary())
