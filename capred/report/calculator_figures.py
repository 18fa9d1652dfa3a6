"""Figure of `capred skempton-b`: B against S_r and the parameter studies of Morvan et al. (2016), Fig. 1-3, 5."""
from __future__ import annotations

import numpy as np

from ..physics import calculators as calc


def figure_skempton(kappa, e0, p0, u0, pa0, s_e=None, bc_alpha=None, points=None):
    """B(S_r) for the given parameters; kappa, e_0 and s_e studies around them (stresses in Pa)."""
    from matplotlib.figure import Figure

    S = np.linspace(0.5, 1.0, 400)
    fig = Figure(figsize=(11, 8.5))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.07, top=0.92, wspace=0.2, hspace=0.3)
    ax = fig.subplots(2, 2)
    pe = p0 - u0
    a = ax[0, 0]
    a.plot(S, calc.skempton_b(S, pe, e0, kappa, pa0), "k-", label="eq. 10 (no suction)")
    if s_e is not None:
        a.plot(S, calc.skempton_b_suction(S, p0, u0, e0, kappa, pa0, s_e, bc_alpha), "r--",
               label=f"with suction (s_e = {s_e / 1e3:g} kPa, α = {bc_alpha:g})")
    if points is not None:
        a.plot(points[0], points[1], "ko", ms=5, label="computed cases")
    a.set_title(f"κ = {kappa:g}, e0 = {e0:g}, p'0 = {pe / 1e3:g} kPa, P_a0 = {pa0 / 1e3:g} kPa")
    for k in (0.0006, 0.006, 0.06):
        ax[0, 1].plot(S, calc.skempton_b(S, pe, e0, k, pa0), label=f"κ = {k:g}")
    ax[0, 1].set_title("effect of κ (Morvan et al. 2016, Fig. 2)")
    for e in (0.6, 0.8, 1.2):
        ax[1, 0].plot(S, calc.skempton_b(S, pe, e, kappa, pa0), label=f"e0 = {e:g}")
    ax[1, 0].set_title("effect of e0 (Morvan et al. 2016, Fig. 3)")
    alpha = bc_alpha if bc_alpha is not None else 0.8
    for se in (5e3, 20e3, 100e3, 1000e3):
        ax[1, 1].plot(S, calc.skempton_b_suction(S, p0, u0, e0, kappa, pa0, se, alpha), label=f"s_e = {se / 1e3:g} kPa")
    ax[1, 1].set_title(f"suction equilibrium, effect of s_e (α = {alpha:g}; Morvan et al. 2016, Fig. 5)")
    for x in ax.flat:
        x.set_xlabel("S_r [-]")
        x.set_ylabel("B [-]")
        x.set_ylim(0, 1.02)
        x.legend(fontsize=7, loc="upper left")
    fig.suptitle("capred skempton-b — Skempton's B against degree of saturation (Morvan et al.)")
    return fig
