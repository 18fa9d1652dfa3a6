"""`capred history`: the individuals chart (with each run's 95 % interval) and the moving-range chart.

Shewhart individuals and moving-range chart as in Montgomery (2013), Introduction to Statistical Quality
Control, 7th ed., section 6.4, Fig. 6.18 (centre line, 3-sigma limits, out-of-control points marked).
"""

from __future__ import annotations

import numpy as np

from ..table_spec import TableSpec
from .sheets import Panel, Sheet
from .style import OKABE_ITO, legend_outside

_LIMIT = dict(color=OKABE_ITO["vermillion"], ls="--", lw=1.0)
_CENTRE = dict(color=OKABE_ITO["grey"], ls="-", lw=1.0)


def _runs_axis(ax, n: int) -> None:
    from matplotlib.ticker import MaxNLocator

    ax.set_xlim(0.5, n + 0.5)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("run (in test order)")


def _label(result) -> str:
    """The y label: the quantity and unit as a store holds them (another program may have written them)."""
    from .style import literal

    unit = "" if result.unit == "-" else f" [{literal(result.unit)}]"
    return f"{literal(result.quantity)}{unit}"


def _individuals(ax, result):
    r, lim = result.record(), result.limits  # the typed record (HistoryRecord), in the quantity's unit
    k = np.arange(1, len(r.run) + 1)
    x = r.value
    lo, hi = r.ci_low, r.ci_high
    has_ci = np.isfinite(lo) & np.isfinite(hi)
    if has_ci.any():
        ax.errorbar(
            k[has_ci],
            x[has_ci],
            yerr=[x[has_ci] - lo[has_ci], hi[has_ci] - x[has_ci]],
            fmt="none",
            ecolor=OKABE_ITO["sky"],
            elinewidth=0.9,
            capsize=2,
            label="95 % interval of the run",
        )
    ax.plot(k, x, "-o", color=OKABE_ITO["black"], ms=3.5, lw=0.8, label="value per run")
    out = r.beyond_limits
    if out.any():
        ax.plot(k[out], x[out], "s", color=OKABE_ITO["vermillion"], ms=7, mfc="none", mew=1.5, label="beyond limits")
    ax.axhline(lim.centre, **_CENTRE, label="centre line")
    ax.axhline(lim.ucl, **_LIMIT, label=r"$\pm 3\sigma$ limits")
    ax.axhline(lim.lcl, **_LIMIT)
    if result.baseline_runs:
        ax.axvspan(0.5, result.baseline_runs + 0.5, color=OKABE_ITO["grey"], alpha=0.12, lw=0, label="baseline runs")
    _runs_axis(ax, len(k))
    ax.set_ylabel(_label(result))
    ax.set_title("Individuals")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return ax


def _moving_range(ax, result):
    r, lim = result.record(), result.limits
    k = np.arange(1, len(r.run) + 1)
    mr = r.moving_range
    ax.plot(k[1:], mr[1:], "-o", color=OKABE_ITO["black"], ms=3.5, lw=0.8, label="moving range")
    out = r.mr_beyond_limit
    if out.any():
        ax.plot(k[out], mr[out], "s", color=OKABE_ITO["vermillion"], ms=7, mfc="none", mew=1.5, label="beyond limit")
    ax.axhline(lim.mr_centre, **_CENTRE, label=r"$\overline{MR}$")
    ax.axhline(lim.mr_ucl, **_LIMIT, label=r"$D_4\,\overline{MR}$")
    _runs_axis(ax, len(k))
    from .style import literal

    ax.set_ylabel(f"moving range{'' if result.unit == '-' else f' [{literal(result.unit)}]'}")
    ax.set_title("Moving range")
    top = np.nanmax(np.append(mr[1:], lim.mr_ucl)) if len(mr) > 1 else lim.mr_ucl
    ax.set_ylim(0, 1.12 * top if np.isfinite(top) and top > 0 else None)  # room for the marks of the highest
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return ax


#: share of the panel's axes height given to the individuals chart, the gap under it (its tick labels, the moving
#: range's title) and the moving-range chart [-]
_SPLIT = (0.57, 0.14, 0.29)


def plot_control_chart(ax, result):
    """The individuals chart over the moving-range chart, as one panel.

    Two axes laid out as one group, so that both span the same width and run k sits at the same x in both (as Montgomery
    2013 draws them, Fig. 6.18).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel's axes: the individuals chart; the moving-range chart is added below it, on the same figure.
    result : capred.pipelines.history.HistoryResult
        A ``capred history`` run.

    Returns
    -------
    matplotlib.axes.Axes
        The individuals axes.

    References
    ----------
    Montgomery, D. C. (2013). Introduction to Statistical Quality Control, 7th ed., Wiley, section 6.4.
    """
    p = ax.get_position()
    top, gap, low = _SPLIT
    ax.set_position((p.x0, p.y0 + (low + gap) * p.height, p.width, top * p.height))
    mr = ax.figure.add_axes((p.x0, p.y0, p.width, low * p.height))
    _individuals(ax, result)  # its legend is placed by the sheet, beside the axes
    ax.set_xlabel("")  # the runs axis is labelled once, under the moving range
    _moving_range(mr, result)
    legend_outside(mr)  # the house legend, beside the axes like the individuals'
    return ax


def sheet_history(result) -> Sheet:
    """The control chart of a `capred history` result: individuals (with 95 % intervals) over moving range.

    Parameters
    ----------
    result : capred.pipelines.history.HistoryResult
        A ``capred history`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    what = f"{result.quantity}" + (f" of {result.material}" if result.material else "")
    return Sheet(
        f"Control chart: {what}",
        [
            Panel(
                "control_chart",
                lambda ax: plot_control_chart(ax, result),
                f"Individuals chart of {what} per run with each run's 95 % interval (error bars); centre line and "
                f"3σ limits from {result.limits.basis}; below, the moving range of consecutive runs with its centre "
                "line and upper limit D4·MR̄, D4 = 3.267; squares: beyond the limits (after Montgomery 2013, "
                "Fig. 6.18).",
            ),
        ],
        1,
        spans={"control_chart": 2},
        panel_size=(6.0, 5.2),
    )


def history_tables(result) -> list[TableSpec]:
    """The runs with their value, interval, moving range and flag; then the limits.

    Parameters
    ----------
    result : capred.pipelines.history.HistoryResult
        A ``capred history`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    from .render import fmt, row_table

    rows = [
        {**r, "flag": "OUT" if r["beyond_limits"] else ("MR" if r["mr_beyond_limit"] else "")}
        for r in result.record().json_rows()  # the typed record (HistoryRecord)
    ]
    keys = ["run", "test_date", "value", "ci_low", "ci_high", "moving_range", "flag"]
    what = f"{result.quantity}" + (f" of {result.material}" if result.material else "")
    unit = "" if result.unit == "-" else f" [{result.unit}]"
    lim = result.limits
    runs = row_table(f"{what}{unit} per run", rows, keys, "history.csv")
    limits = TableSpec("Control limits (" + lim.basis + ")", [("line", "left"), ("value", "right")])
    for name, v in (
        ("centre", lim.centre),
        ("sigma", lim.sigma),
        ("LCL", lim.lcl),
        ("UCL", lim.ucl),
        ("MR centre", lim.mr_centre),
        ("MR UCL", lim.mr_ucl),
    ):
        limits.rows.append([name, fmt(v)])
    return [runs, limits]
