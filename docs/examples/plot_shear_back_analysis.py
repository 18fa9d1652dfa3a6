"""
Back-analysed capillary stress and χ of every wet test
======================================================

Each wet test's apparent capillary stress σ_cap = (τ_max − c)/tan φ − σ_N, from
its material's dry fit, with its 95 % interval (delta method), against the
degree of saturation; the lines are what each model predicts for that test.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred

result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
table = result.table()
wet = table[table["condition"] == "wet"].sort_values("S_R [-]")

fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
for ax, (material, rows) in zip(axes, wet.groupby("material")):
    err = np.vstack(
        [
            rows["sigma_cap [kPa]"] - rows["sigma_cap_low95 [kPa]"],
            rows["sigma_cap_high95 [kPa]"] - rows["sigma_cap [kPa]"],
        ]
    )
    ax.errorbar(rows["S_R [-]"], rows["sigma_cap [kPa]"], yerr=err, fmt="ko", ms=3, label="back-analysed, 95 %")
    for model in ("bishop", "own1", "own2"):
        ax.plot(rows["S_R [-]"], rows[f"sigma_cap_pred_{model} [kPa]"], "-", label=model)
    ax.set(title=material, xlabel="S_R [-]", ylabel="σ_cap [kPa]")
axes[0].legend(frameon=False, fontsize=8)
plt.show()

# %%
# χ_back = σ_cap/Δu of the first wet tests:
columns = [
    "test_id",
    "material",
    "S_R [-]",
    "suction [kPa]",
    "chi_back [-]",
    "chi_back_low95 [-]",
    "chi_back_high95 [-]",
]
print(wet[columns].head(8).to_string(index=False))
