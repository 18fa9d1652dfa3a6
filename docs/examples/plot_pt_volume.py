"""
Void ratio along a stress path with two effective stresses
==========================================================

``capred pt-volume --sample --example-kaolin``: the model of Pedrotti &
Tarantino (submitted) along an illustrative path (compaction end A, unloading
to B, wetting to C, reloading to D). The lines are the illustrative
``EXAMPLE_KAOLIN`` set, not fitted values.
"""

import matplotlib.pyplot as plt

import capred

result = capred.run_pt_volume(capred.sample_path("pt-volume"), capred.PTVolumeOptions(example_kaolin=True))
t = result.table()
print(t[["stage", "sigma [kPa]", "suction [kPa]", "S_r [-]", "e [-]"]].to_string(index=False))

fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
axes[0].plot(t["sigma [kPa]"], t["e [-]"], "k-o", ms=3, label="sample, e")
axes[0].plot(t["sigma_W [kPa]"], t["e_W [-]"], "--", label="water-saturated part, e_W on σ'_W")
axes[0].plot(t["sigma_A [kPa]"], t["e_A [-]"], ":", label="air-saturated part, e_A on σ'_A")
axes[0].set(xscale="log", xlabel="stress [kPa]", ylabel="void ratio [-]")
axes[0].legend(frameon=False, fontsize=7)
axes[1].plot(t["step [-]"], t["S_r [-]"], "k-o", ms=3)
axes[1].set(xlabel="step", ylabel="S_r [-]")
plt.show()
