"""Retention data and fitted curves on a log suction axis."""
from __future__ import annotations

import numpy as np

STYLE = {"vg": "-", "vg_m_free": ":", "bc": "--"}
LABEL = {"vg": "van Genuchten (m = 1 − 1/n)", "vg_m_free": "van Genuchten (m free)", "bc": "Brooks-Corey"}
COLOR = {"drying": "tab:red", "wetting": "tab:blue"}


def plot_retention(ax, result):
    pos = result.suction[result.suction > 0]
    lo = pos.min() / 3 if pos.size else 1.0
    hi = result.suction.max() * 3
    grid = np.geomspace(lo, hi, 300)
    for b, fits in result.fits.items():
        sel = result.branch == b
        shown = np.where(result.suction[sel] > 0, result.suction[sel], lo)
        color = COLOR.get(b, "k")
        ax.plot(shown / 1e3, result.water[sel], "o", color=color, ms=4, label=f"{b} data")
        for m in fits:
            r2 = fits[m].r2
            ax.plot(grid / 1e3, result.curve(b, m, grid), STYLE[m], color=color, lw=1.2,
                    label=f"{b}: {LABEL[m]} (R² {r2:.4f})")
    ax.set_xscale("log")
    ax.set_xlabel("suction s [kPa]")
    ax.set_ylabel("θ [-]" if result.quantity == "theta" else "S_R [-]")
    ax.legend(fontsize=7, loc="lower left")
    return ax


def figure_retention(result):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 6))
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.1, top=0.92)
    plot_retention(fig.add_subplot(), result)
    fig.suptitle("capred retention — water retention curves")
    return fig
