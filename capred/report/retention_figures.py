"""Figure sheet of `capred retention`: readings and fitted curves on a logarithmic suction axis.

Colour and marker say which branch (drying, wetting), the line style which
model: each model's label, equation and line style come from its entry of
``capred.fitting.retention_models.MODELS``. Readings at zero suction cannot sit
on a log axis; they are drawn in a grey strip at the left edge of the axes
marked "s = 0" (placed in axes coordinates, outside the suction scale), never
at an invented suction. Fitted parameters are in the tables, not in the legend.
"""

from __future__ import annotations

import numpy as np

from ..fitting.retention_models import MODELS
from .sheets import Panel, Sheet
from .style import OKABE_ITO, literal, note, thin, untitled

STRIP = 0.07  # width of the zero-suction strip, as a fraction of the axes
#: colour and marker of the readings and curves of each branch (a model's line style comes from its registry entry)
BRANCH_STYLES = {
    "drying": dict(color=OKABE_ITO["orange"], marker="o"),
    "wetting": dict(color=OKABE_ITO["blue"], marker="s"),
    "scanning": dict(color=OKABE_ITO["green"], marker="^"),
}


#: axis labels in plain text (no mathtext: the figure then never builds matplotlib's mathtext parser, a tenth
#: of a second of every run); tick labels are plain numbers for the same reason (and read as kPa directly)
AXIS_LABELS = {
    "suction": "suction s [kPa]",
    "S_R": "degree of saturation [–]",  # S_R would need mathtext (a raw "S_R" is no journal label)
    "theta": "volumetric water content θ [m³/m³]",
    "w": "water content by mass w [–]",
}


def model_key(name: str) -> str:
    """Legend text of a retention model: its registry label and equation (plain text).

    Parameters
    ----------
    name : str
        A key of ``capred.fitting.retention_models.MODELS`` (another name: shown as text).

    Returns
    -------
    str
    """
    entry = MODELS.get(name)
    if entry is None:
        return literal(name)
    return f"{literal(entry.label)}\n{entry.equation}"


def plot_retention(ax, result):
    """Readings of every branch and each fitted model's curve, with the best model's 95 % confidence band.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.retention.RetentionResult
        A ``capred retention`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Rectangle
    from matplotlib.transforms import blended_transform_factory

    pos = result.suction[result.suction > 0]
    lo = pos.min() / 2 if pos.size else 1.0
    hi = (pos.max() if pos.size else 10.0) * 2
    grid = np.geomspace(lo, hi, 300)
    zero = result.suction <= 0
    in_strip = blended_transform_factory(ax.transAxes, ax.transData)
    handles, models = [], []
    shown = ""
    for b, fits in result.fits.items():
        sel = result.branch == b
        st = BRANCH_STYLES.get(b, dict(color=OKABE_ITO["black"], marker="o"))
        keep, shown = thin(np.flatnonzero(sel & ~zero))
        ax.plot(
            result.suction[keep] / 1e3, result.water[keep], ls="none", ms=3.5, color=st["color"], marker=st["marker"]
        )
        if (sel & zero).any():
            z, _ = thin(np.flatnonzero(sel & zero))
            ax.plot(
                np.full(z.size, STRIP / 2),
                result.water[z],
                ls="none",
                ms=3.5,
                color=st["color"],
                marker=st["marker"],
                transform=in_strip,
                clip_on=False,
            )
        best = min(fits, key=lambda m: fits[m].aicc if np.isfinite(fits[m].aicc) else np.inf)
        lo_b, hi_b = result.band(b, best, grid)
        ax.fill_between(grid / 1e3, lo_b, hi_b, color=st["color"], alpha=0.18, lw=0)
        for m in fits:
            ax.plot(grid / 1e3, result.curve(b, m, grid), color=st["color"], lw=1.1, **_curve_style(m))
            if m not in models:
                models.append(m)
        handles.append(
            Line2D([], [], ls="none", marker=st["marker"], color=st["color"], ms=3.5, label=f"{literal(b)}: readings")
        )
    for b in dict.fromkeys(result.branch):  # readings of branches without a fit (scanning, too few readings)
        if b in result.fits:
            continue
        sel = result.branch == b
        st = BRANCH_STYLES.get(b, dict(color=OKABE_ITO["black"], marker="x"))
        keep, _ = thin(np.flatnonzero(sel & ~zero))
        ax.plot(
            result.suction[keep] / 1e3,
            result.water[keep],
            ls="none",
            ms=3.5,
            mfc="none",
            color=st["color"],
            marker=st["marker"],
        )
        handles.append(
            Line2D(
                [], [], ls="none", marker=st["marker"], mfc="none", color=st["color"], ms=3.5,
                label=f"{literal(b)}: readings (not in the main fits)",
            )
        )  # fmt: skip
    for c in getattr(result, "scanning", []):
        ends = [c.s_reversal, c.s_closure if np.isfinite(c.s_closure) and c.s_closure > 0 else None]
        a = min(x for x in ends if x is not None)
        z = max(x for x in ends if x is not None)
        if ends[1] is None:  # open towards the wet or dry end: drawn over the readings and to the axis' end
            a, z = (min(a, lo), z) if c.direction == "wetting" else (a, max(z, hi))
        span = np.geomspace(max(a, lo), min(z, hi), 120)
        ax.plot(span / 1e3, c.curve(span), color=BRANCH_STYLES["scanning"]["color"], lw=1.0, ls="--")
    if getattr(result, "scanning", []):
        handles.append(
            Line2D(
                [], [], color=BRANCH_STYLES["scanning"]["color"], lw=1.0, ls="--",
                label="scanning curves (Parker & Lenhard 1987 scaling)",
            )
        )  # fmt: skip
    for m in models:
        handles.append(Line2D([], [], color="k", lw=1.1, **_curve_style(m, legend=True), label=model_key(m)))
    _log_suction_axis(ax, lo / 1e3, hi / 1e3)
    if zero.any():  # leave the strip free of the suction scale
        ax.set_xlim(lo / 1e3 / (hi / lo) ** (STRIP / (1 - STRIP)), hi / 1e3)
        ax.add_patch(Rectangle((0, 0), STRIP, 1, transform=ax.transAxes, color="#e6e6e6", zorder=0, lw=0))
        ax.text(STRIP / 2, 0.02, "s = 0", transform=ax.transAxes, ha="center", va="bottom", fontsize=6, rotation=90)
    note(ax, shown)
    ax.set_xlabel(AXIS_LABELS["suction"])
    ax.set_ylabel(AXIS_LABELS.get(result.quantity, AXIS_LABELS["S_R"]))
    ax.set_title("Water retention")
    ax.legend(handles=handles, ncol=2 if len(models) > 3 else 1)
    return ax


def _log_suction_axis(ax, lo: float, hi: float) -> None:
    """A logarithmic suction axis from ``lo`` to ``hi`` [kPa] with plain-number tick labels.

    0.1, 1, 10; and 2, 5 between the decades when the axis spans less than two decades; without mathtext.
    """
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    ax.set_xscale("log")
    if hi / lo < 100:
        ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())


def _curve_style(model: str, legend: bool = False) -> dict:
    """Line style and marker of a retention model's curve.

    Its registry entry's, else the next free pair of RETENTION_STYLES (markers every 60 of 300 grid points on the curve,
    offset per model; one in the legend).
    """
    st = MODELS[model].style if model in MODELS else RETENTION_STYLES[hash(model) % len(RETENTION_STYLES)]
    out = {"ls": st.get("ls", "-")}
    if st.get("marker"):
        out.update(marker=st["marker"], ms=3.0, mfc="white", mew=0.8)
        if not legend:
            k = list(MODELS).index(model) if model in MODELS else 0
            out["markevery"] = (12 + 9 * k % 48, 60)  # each model's markers at their own suctions
    return out


#: distinguishable styles of retention curves (line style, marker), the registry's first: every pair differs in its
#: marker or in a dash pattern of another kind (solid, dashed, dash-dot, dotted, dash-dot-dot)
RETENTION_STYLES = [
    dict(ls="-"),
    dict(ls="--"),
    dict(ls="-."),
    dict(ls=":", marker="o"),
    dict(ls=(0, (5, 1)), marker="s"),
    dict(ls=(0, (3, 1, 1, 1)), marker="^"),
    dict(ls=(0, (3, 1, 1, 1, 1, 1)), marker="D"),
    dict(ls="-", marker="v"),
    dict(ls="--", marker="x"),
    dict(ls="-.", marker="P"),
]


def sheet_retention(result) -> Sheet:
    """One panel, two columns wide, whose height grows with the legend.

    The legend shows each model's name and equation, two lines, two entries a row, below the axes, so that the axes keep
    their height however many models.

    Parameters
    ----------
    result : capred.pipelines.retention.RetentionResult
        A ``capred retention`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    models = list(dict.fromkeys(m for fits in result.fits.values() for m in fits))
    rows = -(-(len(models) + len(result.fits)) // 2)  # legend entries, two a row
    name = literal(str(result.source).replace("\\", "/").rsplit("/", 1)[-1])
    return Sheet(
        f"Water retention curves ({name})",
        [
            Panel(
                "curves",
                untitled(lambda ax: plot_retention(ax, result)),
                "Readings and fitted curves per branch (colour and marker) and model (line style, with its "
                "equation in the legend) on a logarithmic suction axis, with the 95 % confidence band of the best "
                "model (lowest AICc) of each branch; readings at zero suction are in the grey strip marked s = 0. "
                "The fitted parameters are in the tables.",
            )
        ],
        1,
        spans={"curves": 2},
        panel_size=(5.5, 3.2 + (0.5 * rows if len(models) > 3 else 0.0)),
    )


def plot_conversion(ax, result):
    """The source curve and the converted one over the data's suction range (and a decade beyond, dotted).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.retention_convert.RetentionConvertResult
        A ``capred retention-convert`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    src, new = result.source_fit, result.converted
    lo, hi = src.suction_range
    inside = np.geomspace(lo, hi, 300)
    beyond_lo, beyond_hi = np.geomspace(lo / 10, lo, 60), np.geomspace(hi, hi * 10, 60)
    for s, ls_src, ls_new, lab in (
        (inside, "-", "--", True),
        (beyond_lo, ":", ":", False),
        (beyond_hi, ":", ":", False),
    ):
        ax.plot(
            s / 1e3,
            src.water(s),
            color=OKABE_ITO["black"],
            lw=1.4,
            ls=ls_src,
            label=f"{literal(src.label)} (source)" if lab else None,
        )
        ax.plot(
            s / 1e3,
            new.water(s),
            color=OKABE_ITO["vermillion"],
            lw=1.2,
            ls=ls_new,
            label=f"{literal(new.label)} (converted)" if lab else None,
        )
    pts = np.asarray(src.suction_points, float)
    ax.plot(pts / 1e3, src.water(pts), ls="none", marker="|", ms=5, color="0.4", label="suctions of the data")
    ax.axvspan(lo / 1e3, hi / 1e3, color="0.92", lw=0, zorder=0)
    _log_suction_axis(ax, lo / 1e4, hi / 1e2)
    ax.set_xlabel(AXIS_LABELS["suction"])
    ax.set_ylabel(AXIS_LABELS.get(result.quantity, AXIS_LABELS["S_R"]))
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2, fontsize=7, frameon=False)
    return ax


def plot_conversion_misfit(ax, result):
    """Converted minus source curve over the data's suction range.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.retention_convert.RetentionConvertResult
        A ``capred retention-convert`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    src, new = result.source_fit, result.converted
    lo, hi = src.suction_range
    s = np.geomspace(lo, hi, 400)
    ax.plot(s / 1e3, new.water(s) - src.water(s), color=OKABE_ITO["vermillion"], lw=1.2)
    ax.axhline(0.0, color="0.5", lw=0.6)
    _log_suction_axis(ax, lo / 1e3, hi / 1e3)
    ax.set_xlabel(AXIS_LABELS["suction"])
    unit = "m³/m³" if result.quantity == "theta" else "-"  # S_R and w are both [-]
    ax.set_ylabel(f"converted − source [{unit}]")
    m = result.misfit
    note(ax, f"RMSE {m['rmse']:.3g}, largest |deviation| {m['max_deviation']:.3g}")
    return ax


def sheet_convert(result) -> Sheet:
    """Two panels: both curves, and their difference over the data's suction range.

    Parameters
    ----------
    result : capred.pipelines.retention_convert.RetentionConvertResult
        A ``capred retention-convert`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    src, new = result.source_fit, result.converted
    name = literal(str(result.source).replace("\\", "/").rsplit("/", 1)[-1])
    return Sheet(
        f"{literal(src.label)} converted to {literal(new.label)} ({name})",
        [
            Panel(
                "curves",
                lambda ax: plot_conversion(ax, result),
                "The source fit (solid) and the converted curve (dashed) over the suctions of the data (grey band, "
                "ticks: the data's suctions), dotted a decade beyond, where the conversion was not fitted.",
            ),
            Panel("misfit", lambda ax: plot_conversion_misfit(ax, result), "Converted minus source curve."),
        ],
        2,
        panel_size=(4.6, 3.6),
    )
