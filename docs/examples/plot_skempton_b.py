"""
Skempton's B against the degree of saturation (Morvan et al. 2016)
===================================================================

``capred skempton-b``: B from S_r by eq. 10 of Morvan et al. (2016) for three
slopes κ of the elastic line, the other parameters at their Table 1 values.
"""

import matplotlib.pyplot as plt
import numpy as np

import capred

S_R = np.linspace(0.80, 0.999, 40)
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
for kappa in (0.006, 0.02, 0.06):
    B = [capred.run_skempton_b(S_R=float(s), kappa_elastic=kappa).to_json()["B"] for s in S_R]
    ax.plot(S_R, B, label=f"κ = {kappa}")
ax.set(xlabel="S_r [-]", ylabel="B [-]")
ax.legend(frameon=False)
plt.show()

# %%
# The inverse: the degree of saturation a measured B implies.
print(capred.run_skempton_b(b=0.2).to_json()["S_r"])
