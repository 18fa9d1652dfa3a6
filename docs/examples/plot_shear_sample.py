"""
Direct shear: which effective-stress model predicts the wet tests?
==================================================================

``capred shear --sample`` from Python. Per material, capred fits the dry envelope
τ = c + σ_N tan φ, predicts every wet test with the four models of Evenepoel's
thesis (no suction, Bishop's χ = S_R, Own 1 and Own 2) and scores them. Here the
ranking bootstrap is off (``bootstrap=0``) to keep the example fast.
"""

import matplotlib.pyplot as plt

import capred

result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
table = result.table()  # one row per test, kPa columns
wet = table[table["condition"] == "wet"]
models = ["no_suction", "bishop", "own1", "own2"]

# %%
# The best model per material (lowest RMSE on the wet tests) and each model's scores:
print(result.to_json()["best_model"])
for material, scores in result.metrics.items():
    for model, m in scores.items():
        print(f"{material:16s} {model:11s} RMSE {m.rmse_kPa:.3f} kPa  bias {m.bias_kPa:+.3f} kPa  n {m.n}")

# %%
# Measured against predicted peak shear stress, one panel per material:
materials = list(result.fits)
fig, axes = plt.subplots(1, len(materials), figsize=(9, 4), layout="constrained")
for ax, material in zip(axes, materials):
    rows = wet[wet["material"] == material]
    for model in models:
        ax.plot(rows["tau_max [kPa]"], rows[f"tau_pred_{model} [kPa]"], "o", ms=4, label=model)
    lo, hi = rows["tau_max [kPa]"].min(), rows["tau_max [kPa]"].max()
    ax.plot([lo, hi], [lo, hi], "k-", lw=0.8)
    ax.set(title=material, xlabel="measured τ_max [kPa]", ylabel="predicted τ [kPa]")
axes[0].legend(frameon=False)
plt.show()
