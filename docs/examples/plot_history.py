"""
A lab's history: the friction angle of one sand run after run
=============================================================

``capred history --sample --quantity phi_deg``: the runs recorded in a lab store
(``--store`` on any command) on an individuals chart with moving range
(Montgomery 2013, section 6.4); runs beyond the 3σ limits are flagged.
"""

import matplotlib.pyplot as plt

import capred

result = capred.run_history(capred.sample_path("history"), quantity="phi_deg")
t = result.table()
lim = result.limits
print(f"centre {lim.centre:.2f} deg, limits {lim.lcl:.2f} to {lim.ucl:.2f} deg ({lim.basis})")
print(t[t["beyond_limits"]][["run", "test_date", "value"]])

fig, axes = plt.subplots(2, 1, figsize=(8, 5), sharex=True, layout="constrained")
axes[0].errorbar(t["run"], t["value"], yerr=[t["value"] - t["ci_low"], t["ci_high"] - t["value"]], fmt="ko", ms=3)
flag = t["beyond_limits"]
axes[0].plot(t["run"][flag], t["value"][flag], "o", color="C3", ms=8, mfc="none", label="beyond the limits")
for y, style in ((lim.centre, "-"), (lim.lcl, "--"), (lim.ucl, "--")):
    axes[0].axhline(y, color="C0", ls=style, lw=1)
axes[0].set(ylabel="φ [deg]")
axes[0].legend(frameon=False)
axes[1].plot(t["run"], t["moving_range"], "k-o", ms=3)
axes[1].axhline(lim.mr_ucl, color="C0", ls="--", lw=1)
axes[1].set(xlabel="run", ylabel="moving range [deg]")
plt.show()
