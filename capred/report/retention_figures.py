"""Figure sheet of `capred retention`: readings and fitted curves on a logarithmic suction axis.

Readings at zero suction cannot sit on a log axis; they are drawn in a grey
strip at the left edge of the axes marked "s = 0" (placed in axes
coordinates, outside the suction scale), never at an invented suction.
Fitted parameters are in the tables, not in the legend.
"""
from __future__ import annotations

import numpy as np

from .sheets import Panel, Sheet
from .style import LABEL, style

MODEL = {"vg": "van Genuchten (m = 1 − 1/n)", "vg_m_free": "van Genuchten (m free)", "bc": "Brooks-Corey",
         "kosugi": "Kosugi", "fx": "Fredlund-Xing", "fx_no_c": "Fredlund-Xing without C", "durner": "Durner"}
LINESTYLE = {"vg": "-", "vg_m_free": "--", "bc": "-.", "kosugi": ":", "fx": (0, (5, 1)), "fx_no_c": (0, (3, 1, 1, 1)),
             "durner": (0, (1, 1))}


STRIP = 0.07  # width of the zero-suction strip, as a fraction of the axes


def plot_retention(ax, result):
    from matplotlib.patches import Rectangle
    from matplotlib.transforms import blended_transform_factory

    pos = result.suction[result.suction > 0]
    lo = pos.min() / 2 if pos.size else 1.0
    hi = (pos.max() if pos.size else 10.0) * 2
    grid = np.geomspace(lo, hi, 300)
    zero = result.suction <= 0
    in_strip = blended_transform_factory(ax.transAxes, ax.transData)
    for b, fits in result.fits.items():
        sel = result.branch == b
        st = style(b)
        ax.plot(result.suction[sel & ~zero] / 1e3, result.water[sel & ~zero], ls="none", ms=4, color=st["color"],
                marker=st["marker"], label=f"{b}: readings")
        if (sel & zero).any():
            ax.plot(np.full(int((sel & zero).sum()), STRIP / 2), result.water[sel & zero], ls="none", ms=4,
                    color=st["color"], marker=st["marker"], transform=in_strip, clip_on=False)
        best = min(fits, key=lambda m: fits[m].aicc if np.isfinite(fits[m].aicc) else np.inf)
        lo_b, hi_b = result.band(b, best, grid)
        ax.fill_between(grid / 1e3, lo_b, hi_b, color=st["color"], alpha=0.18, lw=0,
                        label=f"{b}: 95 % confidence band ({MODEL[best]})")
        for m in fits:
            ax.plot(grid / 1e3, result.curve(b, m, grid), ls=LINESTYLE.get(m, "-"), color=st["color"], lw=1.2,
                    label=f"{b}: {MODEL[m]}")
    ax.set_xscale("log")
    if zero.any():  # leave the strip free of the suction scale
        ax.set_xlim(lo / 1e3 / (hi / lo) ** (STRIP / (1 - STRIP)), hi / 1e3)
        ax.add_patch(Rectangle((0, 0), STRIP, 1, transform=ax.transAxes, color="#e6e6e6", zorder=0, lw=0))
        ax.text(STRIP / 2, 0.02, "s = 0", transform=ax.transAxes, ha="center", va="bottom", fontsize=6, rotation=90)
    ax.set_xlabel(r"suction $s$ [kPa]")
    ax.set_ylabel(LABEL["theta"] if result.quantity == "theta" else LABEL["S_R"])
    ax.set_title("Water retention")
    ax.legend()
    return ax


def sheet_retention(result) -> Sheet:
    return Sheet("Water retention curves", [
        Panel("curves", lambda ax: plot_retention(ax, result),
              "Readings and fitted curves per branch on a logarithmic suction axis; readings at zero suction are "
              "in the grey strip marked s = 0. The fitted parameters are in the tables.")], 1,
        panel_size=(5.5, 4.0))
