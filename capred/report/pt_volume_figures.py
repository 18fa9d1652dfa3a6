"""Figure sheet of `capred pt-volume`, after Fig. 14-17 of Pedrotti & Tarantino (submitted).

The water-saturated part (W) is drawn in blue with the ncl of the clay
reconstituted from slurry, the air-saturated part (A) in orange with the ncl
of the clay compressed from dry powder, the whole sample in black; every
curve comes from the run's records (nothing is recomputed but the straight
ncl reference lines, from the run's own line parameters).
"""

from __future__ import annotations

import numpy as np

from .sheets import Panel, Sheet
from .style import OKABE_ITO, literal

KPA = 1e-3
PART = {
    "W": dict(color=OKABE_ITO["blue"], marker="o", name="water-sat. part W", ncl="slurry ncl"),
    "A": dict(color=OKABE_ITO["orange"], marker="s", name="air-sat. part A", ncl="dry-powder ncl"),
}
SAMPLE = dict(color=OKABE_ITO["black"], marker="D")
LABEL = {
    "e": r"void ratio $e$ [–]",
    "sigma_parts": r"$\sigma'_W$, $\sigma'_A$ [kPa] (log scale)",
    "net": r"net stress $\sigma - u_a$ [kPa] (log scale)",
    "step": r"step [–]",
}


def stage_marks(result) -> list[tuple[str, int]]:
    """(label, point index) to annotate.

    Points with a label of their own (A, B, C, D), else the first point of every run of labels.

    Parameters
    ----------
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    list of tuple of (str, int)
    """
    runs = result.stages
    single = [(s.label, s.first) for s in runs if s.first == s.last]
    return single or [(s.label, s.first) for s in runs]


def _log_axis(ax, values) -> None:
    """A logarithmic x axis in plain numbers.

    Labels at 1, 2, 5 x 10^k over at most two decades of ``values``, at the decades otherwise (never crowded, also in a
    one-column panel).
    """
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    v = np.asarray(values, float)
    v = v[np.isfinite(v) & (v > 0)]
    decades = np.log10(v.max() / v.min()) if v.size else 0.0
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0) if decades <= 2 else (1.0,)))
    fmt = ScalarFormatter()
    fmt.set_scientific(False)
    ax.xaxis.set_major_formatter(fmt)
    ax.xaxis.set_minor_formatter(NullFormatter())


def _annotate(ax, result, x, y, color) -> None:
    for label, i in stage_marks(result):
        if np.isfinite(x[i]) and np.isfinite(y[i]) and x[i] > 0:
            ax.annotate(
                literal(label), (x[i], y[i]), xytext=(4, 4), textcoords="offset points", fontsize=7, color=color
            )


def plot_e_ln_sigma(ax, result):
    """e^W against σ'_W and e^A against σ'_A (log axis), each with the ncl of its clay (Fig. 14-15).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    pts, p = result.points, result.params
    positive = [v[np.isfinite(v) & (v > 0)] for v in (pts.sigma_W, pts.sigma_A, pts.sigma_star_W, pts.sigma_star_A)]
    allv = np.concatenate(positive)
    lo, hi = (allv.min() / 2, allv.max() * 2) if allv.size else (1e3, 1e6)
    grid = np.geomspace(lo, hi, 100)
    for part in ("W", "A"):
        st = PART[part]
        s, e = getattr(pts, f"sigma_{part}"), getattr(pts, f"e_{part}")
        ok = np.isfinite(e) & (s > 0)
        ax.plot(grid * KPA, p.ncl(part, grid), "--", color=st["color"], lw=1.0, label=st["ncl"])
        ax.plot(s[ok] * KPA, e[ok], "-", color=st["color"], marker=st["marker"], ms=3, lw=1.0, label=st["name"])
        if ok.any():
            _annotate(ax, result, np.where(ok, s * KPA, np.nan), e, st["color"])
    _log_axis(ax, grid * KPA)
    ax.set_xlabel(LABEL["sigma_parts"])
    ax.set_ylabel(LABEL["e"])
    ax.set_title("The two parts in the e–ln σ' plane (after Fig. 14-15)")
    ax.legend()
    return ax


def plot_e_step(ax, result):
    """e, e^W and e^A against the step, stage labels on top.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    pts = result.points
    x = result.step
    ax.plot(x, pts.e, "-", color=SAMPLE["color"], marker=SAMPLE["marker"], ms=3, lw=1.2, label="sample $e$")
    for part in ("W", "A"):
        st = PART[part]
        ax.plot(
            x, getattr(pts, f"e_{part}"), "-", color=st["color"], marker=st["marker"], ms=3, lw=1.0, label=f"$e^{part}$"
        )
    for label, i in stage_marks(result):
        ax.axvline(x[i], color=OKABE_ITO["grey"], lw=0.6, ls=":")
        ax.annotate(
            literal(label),
            (x[i], 1.0),
            xycoords=("data", "axes fraction"),
            xytext=(2, -10),
            textcoords="offset points",
            fontsize=7,
            color=OKABE_ITO["grey"],
        )
    ax.set_xlabel(LABEL["step"])
    ax.set_ylabel(LABEL["e"])
    ax.set_title("Void ratio along the path")
    ax.legend()
    return ax


def plot_e_net_stress(ax, result):
    """Void ratio e of the sample against the net stress σ − u_a (log axis), as the paper's Fig. 17 compares with tests.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    pts = result.points
    net = pts.sigma - pts.u_a
    ok = net > 0
    ax.plot(net[ok] * KPA, pts.e[ok], "-", color=SAMPLE["color"], marker=SAMPLE["marker"], ms=3, lw=1.2)
    _annotate(ax, result, np.where(ok, net * KPA, np.nan), pts.e, SAMPLE["color"])
    _log_axis(ax, net[ok] * KPA)
    ax.set_xlabel(LABEL["net"])
    ax.set_ylabel(LABEL["e"])
    ax.set_title("Sample e against net stress (after Fig. 17)")
    return ax


def sheet_pt_volume(result) -> Sheet:
    """The sheet of a run: the two parts in e–ln σ', e along the path, e against net stress.

    Parameters
    ----------
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    illustrative = " Lines: EXAMPLE_KAOLIN, illustrative values." if result.options.illustrative() else ""
    return Sheet(
        "Volume change with two effective stresses (Pedrotti & Tarantino)",
        [
            Panel(
                "e_ln_sigma",
                lambda ax: plot_e_ln_sigma(ax, result),
                "Void ratio of the water-saturated pores against σ'_W = (σ − u_w) S_r and of the air-saturated pores "
                "against σ'_A = (σ − u_a)(1 − S_r) (eq. 1-2), with the ncl of clay reconstituted from slurry and "
                "compressed from dry powder as reference lines, as in Fig. 14-15 of Pedrotti & Tarantino."
                + illustrative,
            ),
            Panel(
                "e_step",
                lambda ax: plot_e_step(ax, result),
                "Void ratio of the sample (eq. 5) and of its two parts at every point of the path." + illustrative,
            ),
            Panel(
                "e_net_stress",
                lambda ax: plot_e_net_stress(ax, result),
                "Void ratio of the sample against the net stress σ − u_a." + illustrative,
            ),
        ],
        2,
        spans={"e_ln_sigma": 2},
        caption="Pedrotti & Tarantino (submitted), eq. 1-10; stage labels from the path file." + illustrative,
    )
