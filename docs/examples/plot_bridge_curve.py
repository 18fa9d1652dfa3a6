"""
Capillary bridges: σ' of two spheres in contact against S_R
===========================================================

``capred bridge curve``: the effective stress carried by an exact
Young-Laplace bridge between 2 mm steel spheres in contact (water, θ = 0),
beside Israelachvili's, Bishop's and the thesis's approximations.
"""

import matplotlib.pyplot as plt

import capred

curve = capred.bridge_curve()
t = curve.table()
fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
for ax, limit in zip(axes, (0.05, t["S_R"].max())):
    rows = t[t["S_R"] <= limit]
    for col, label in (
        ("sigma_prime_exact_kPa", "exact bridge"),
        ("sigma_prime_israelachvili_kPa", "Israelachvili"),
        ("sigma_prime_bishop_kPa", "Bishop"),
        ("sigma_prime_own1_kPa", "Own 1"),
        ("sigma_prime_own2_kPa", "Own 2"),
    ):
        ax.plot(rows["S_R"], rows[col], lw=2 if col.endswith("exact_kPa") else 1, label=label)
    ax.set(xlabel="S_R [-]", ylabel="σ' [kPa]", title="pendular regime" if limit == 0.05 else "whole concave range")
axes[0].legend(frameon=False, fontsize=8)
plt.show()
