"""
Capillary stress bounds at failure (Prunier et al. 2024)
========================================================

The bundled ``triaxial-bounds`` sample reconstructs the Gavet silt tests of
Prunier et al. (2024): saturated tests give the envelope c', φ'; each
unsaturated test gets the spherical (upper) and lower bounds of its capillary
stress tensor. The page "Validated against" compares these numbers with the
paper's Tables 2 and 3.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred

result = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))
doc = result.to_json()
env = doc["envelope"]
print(f"c' = {env['c_kPa']:.3f} kPa, phi' = {env['phi_deg']:.3f} deg")
table = result.table()
columns = [
    "test_id",
    "condition",
    "p0 [kPa]",
    "q [kPa]",
    "spherical_p_cap [kPa]",
    "spherical_gain [-]",
    "lower_gain [-]",
]
print(table[columns].to_string(index=False))

# %%
# The failure states in the q-p plane, the envelope and the image points of the two bounds:
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
p = np.linspace(0, table["p [kPa]"].max() * 1.1, 50)
ax.plot(p, env["M"] * p + env["k_kPa"], "k-", lw=1, label="envelope (compression)")
sat = table[table["condition"] == "saturated"]
uns = table[table["condition"] == "unsaturated"]
ax.plot(sat["p [kPa]"], sat["q [kPa]"], "ks", label="saturated")
ax.plot(uns["p [kPa]"], uns["q [kPa]"], "o", color="C3", label="unsaturated (net stress)")
ax.plot(uns["spherical_p_prime [kPa]"], uns["spherical_q_prime [kPa]"], "^", color="C0", label="spherical bound image")
ax.plot(uns["lower_p_prime [kPa]"], uns["lower_q_prime [kPa]"], "v", color="C2", label="lower bound image")
ax.set(xlabel="p [kPa]", ylabel="q [kPa]")
ax.legend(frameon=False, fontsize=8)
plt.show()
