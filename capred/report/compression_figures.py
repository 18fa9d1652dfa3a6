"""Figure and console tables of `capred compression`: e - log sigma' with the constructions drawn.

Everything drawn comes from the run's records (readings, the fitted first-loading curve, the estimates); the
constructions of Casagrande (1936) and Pacheco Silva (1970) are redrawn from the fitted curve's parameters by the
same functions that computed them (capred.physics.compression).
"""

from __future__ import annotations

import numpy as np

from ..physics import compression as cp
from ..table_spec import TableSpec
from .render import fmt, spec
from .sheets import Panel, Sheet
from .style import OKABE_ITO

STAGE_STYLE = {
    "loading": dict(color=OKABE_ITO["black"], marker="o"),
    "unloading": dict(color=OKABE_ITO["blue"], marker="v"),
    "reloading": dict(color=OKABE_ITO["orange"], marker="^"),
}


def _log_axis(ax) -> None:
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    ax.set_xscale("log")
    f = ScalarFormatter()
    f.set_scientific(False)
    ax.xaxis.set_major_formatter(f)
    ax.xaxis.set_minor_formatter(NullFormatter())


def plot_compression(ax, result, construction: str = "both"):
    """Void ratio e against log σ' by stage, the fitted first-loading curve, its virgin line and the constructions.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    result : capred.pipelines.compression.CompressionResult
        A run.
    construction : str
        ``casagrande``, ``pacheco`` or ``both``.

    Returns
    -------
    matplotlib.axes.Axes
    """
    r = result.readings
    st = np.asarray(r.stage)
    for stage, style in STAGE_STYLE.items():
        m = st == stage
        if m.any():
            ax.plot(r.sigma[m], r.e[m], ls="none", ms=4, label=stage, **style)
    f = result.fit
    sy = 10**f.log_sigma_y / 1e3  # kPa
    lo, hi = np.nanmin(r.sigma), np.nanmax(r.sigma)
    s = np.geomspace(lo, hi, 300)
    ax.plot(s, f.e_at(s * 1e3), "-", color=OKABE_ITO["grey"], lw=1.0, label="fitted first loading")
    ax.plot(s, f.e_y - f.C_c * np.log10(s / sy), "--", color=OKABE_ITO["vermillion"], lw=0.9, label="virgin line (C_c)")
    if construction in ("casagrande", "both"):
        tT, eT, slope, tp = cp.casagrande_construction(f.e_y, f.C_r, f.C_c, f.w)
        m = np.tan(0.5 * np.arctan(slope))
        tt = np.linspace(tT, tT + 0.8, 20)
        c = OKABE_ITO["green"]
        ax.plot(sy * 10**tt, np.full(tt.size, eT), ":", color=c, lw=0.8)
        ax.plot(sy * 10**tt, eT + slope * (tt - tT), ":", color=c, lw=0.8)
        tb = np.linspace(tT, max(tp, tT) + 0.05, 20)
        ax.plot(sy * 10**tb, eT + m * (tb - tT), "-.", color=c, lw=0.8)
        ax.plot([sy * 10**tT], [eT], "s", color=c, ms=4)
        ax.axvline(sy * 10**tp, color=c, lw=0.8, label=f"σ'_p Casagrande {sy * 10**tp:.4g} kPa")
    if construction in ("pacheco", "both"):
        e0 = result.e0
        tA = (f.e_y - e0) / f.C_c
        eB = float(cp.smooth_bilinear(tA, f.e_y, f.C_r, f.C_c, f.w))
        tC = (f.e_y - eB) / f.C_c
        c = OKABE_ITO["purple"]
        ax.plot([lo, sy * 10**tA], [e0, e0], ":", color=c, lw=0.8)
        ax.plot([sy * 10**tA, sy * 10**tA], [e0, eB], ":", color=c, lw=0.8)
        ax.plot([sy * 10**tA, sy * 10**tC], [eB, eB], ":", color=c, lw=0.8)
        ax.axvline(sy * 10**tC, color=c, lw=0.8, ls="--", label=f"σ'_p Pacheco Silva {sy * 10**tC:.4g} kPa")
    _log_axis(ax)
    ax.set_xlabel(f"{result.stress_symbol} [kPa] (log scale)")
    ax.set_ylabel("void ratio e [–]")
    ax.set_title(f"{result.options.test.capitalize()} compression")
    ax.legend(fontsize=6)
    return ax


def sheet_compression(result) -> Sheet:
    """The sheet of a run: e - log σ' with both constructions, and each construction on its own panel.

    Parameters
    ----------
    result : capred.pipelines.compression.CompressionResult

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        "Compression test: lines and pre-consolidation stress",
        [
            Panel(
                "e_log_sigma",
                lambda ax: plot_compression(ax, result, "both"),
                "Readings by stage, the smooth bilinear curve fitted to the first loading, its virgin line, and "
                "the pre-consolidation stress by Casagrande (1936) and Pacheco Silva (1970).",
            ),
            Panel(
                "casagrande",
                lambda ax: plot_compression(ax, result, "casagrande"),
                "Casagrande (1936): the point of largest curvature (square), the horizontal and the tangent there, "
                "their bisector (dash-dot) meeting the virgin line.",
            ),
            Panel(
                "pacheco_silva",
                lambda ax: plot_compression(ax, result, "pacheco"),
                "Pacheco Silva (1970): the virgin line at e0, down to the curve, across to the virgin line.",
            ),
        ],
        2,
        spans={"e_log_sigma": 2},
        caption="Casagrande (1936); Pacheco Silva (1970); λ = C_c/ln 10, κ = C_s/ln 10.",
    )


def compression_tables(result) -> list[TableSpec]:
    """The estimates (value, SE, 95 % interval, method) and the readings.

    Parameters
    ----------
    result : capred.pipelines.compression.CompressionResult

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    t = spec(
        f"Compression ({result.options.test}, {result.stress_symbol}): lines and yield stress",
        ["quantity", "value", "SE", "95 % CI", "unit", "method"],
    )
    t.columns[-1] = ("method", "left")
    for x in result.estimates:
        t.rows.append([x.symbol, fmt(x.value), fmt(x.se), f"{fmt(x.low)} – {fmt(x.high)}", x.unit or "-", x.method])
    r = result.readings
    rd = spec("Readings", ["line", "stage", f"{result.stress_symbol} [kPa]", "e", "e fitted"], left=2)
    for i in range(len(r.stage)):
        rd.rows.append([str(int(r.line[i])), r.stage[i], fmt(r.sigma[i]), fmt(r.e[i]), fmt(r.e_fitted[i])])
    return [t, rd]
