"""
Every effective-stress model the inputs allow
=============================================

``--models all`` runs every registered model whose parameters are given
(here retention parameters for Vanapalli, Khalili-Khabbaz and Lu-Likos) and the
fitted χ laws; the skipped ones are named with what they need.
"""

import matplotlib.pyplot as plt

import capred

params = capred.ModelParams(s_res=0.05, air_entry="1 kPa", vg_alpha="0.5 1/kPa", vg_n=3)
result = capred.run_shear(
    capred.sample_path("shear"), capred.ShearOptions(models="all", bootstrap=0, model_params=params)
)
for note in result.notes:
    print(note)

# %%
# RMSE of every model on the wet tests of each material:
fig, ax = plt.subplots(figsize=(9, 4), layout="constrained")
materials = list(result.metrics)
models = list(next(iter(result.metrics.values())))
width = 0.8 / len(materials)
for i, material in enumerate(materials):
    rmse = [result.metrics[material][m].rmse_kPa for m in models]
    ax.bar([k + i * width for k in range(len(models))], rmse, width, label=material)
ax.set_xticks([k + 0.4 - width / 2 for k in range(len(models))], models, rotation=45, ha="right")
ax.set(ylabel="RMSE [kPa]", yscale="log")
ax.legend(frameon=False)
plt.show()

# %%
# The fitted χ law χ = S_e^κ per material, with its standard error and interval:
for material, law in result.laws.get("chi_power", {}).items():
    print(material, law.summary())
