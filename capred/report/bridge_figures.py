"""Figure sheets of `capred bridge`: Evenepoel's analytical comparison and the micro-test checks."""

from __future__ import annotations

import numpy as np

from ..physics.effective_stress_models import REGISTRY
from .sheets import Panel, Sheet
from .style import LABEL, OKABE_ITO, style, untitled

#: the curves of `bridge curve` that are not effective-stress models (those carry theirs in their registry entry,
#: ``bridge_curve``)
LINES = {
    "exact": dict(lw=2.0, ls="-", label="exact bridge (Young-Laplace)"),
    "israelachvili": dict(lw=1.2, ls="--", label=r"Israelachvili $2\gamma\cos\theta/R$"),
}


def curve_line(name: str) -> dict:
    """Line width, dash and legend label of one curve of `capred bridge curve`.

    No equation: a lookup in :data:`LINES` for the exact bridge and Israelachvili, else in the model's entry of
    ``capred.physics.effective_stress_models.REGISTRY`` (``bridge_curve``).

    Parameters
    ----------
    name : str
        ``exact``, ``israelachvili`` or an effective-stress model drawn on the curve.

    Returns
    -------
    dict
        Matplotlib keywords ``lw``, ``ls`` and ``label``.

    References
    ----------
    .. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular
       materials, master thesis, Vrije Universiteit Brussel (no DOI): the comparison of the approximations.
    """
    if name in LINES:
        return LINES[name]
    curve = REGISTRY[name].bridge_curve
    return {**curve.line, "label": curve.label}


def plot_curve(ax, curve, inside: bool):
    """Effective stress σ' [kPa] of each model against S_R [-] of a pendular bridge between spheres in contact.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    curve : capred.pipelines.bridge.CurveResult
        A ``capred bridge curve`` run (SI units).
    inside : bool
        True: the pendular regime only (S_R below the pendular limit); False: the whole concave range, the limit dotted.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    sel = curve.S_R < curve.pendular_limit if inside else np.ones(curve.S_R.size, bool)
    for name, v in curve.models().items():
        ax.plot(curve.S_R[sel], v[sel] / 1e3, color=style(name)["color"], **curve_line(name))
    if not inside:
        ax.axvline(curve.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["sigma_prime"])
    lim = f"{curve.pendular_limit:g}"
    ax.set_title(f"Pendular regime ($S_R$ < {lim})" if inside else "Whole concave range")
    ax.set_ylim(bottom=0)
    ax.legend()
    return ax


def sheet_curve(curve) -> Sheet:
    """The sheet of ``capred bridge curve``: the pendular regime and the whole concave range, two panels.

    Parameters
    ----------
    curve : capred.pipelines.bridge.CurveResult
        A ``capred bridge curve`` run (SI units).

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        f"Effective stress of a pendular bridge against the degree of saturation, spheres in contact "
        f"(R = {curve.R * 1e3:g} mm, γ = {curve.gamma:g} N/m, θ = {np.degrees(curve.contact_angle_rad):g}°)",
        [
            Panel(
                "pendular",
                lambda ax: plot_curve(ax, curve, True),
                "σ' = F_cap/(πR²) against S_R = 3V_w/(2πR³) inside the pendular regime: the exact "
                "bridge against the approximations.",
            ),
            Panel("concave_range", lambda ax: plot_curve(ax, curve, False), "Over the whole range of concave bridges."),
        ],
        2,
    )


COMPARE_LABEL = {
    "exact": "exact bridge",
    "toroidal": "toroidal",
    "willett": "Willett et al. (2000)",
    "israelachvili": "Israelachvili",
}


def plot_compare(ax, rows):
    """Predicted against measured capillary force [mN] of each sphere pair, with the 1:1 line.

    The exact bridge, the toroidal approximation, Willett et al. (2000) and Israelachvili.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    rows : list of dict
        The JSON rows of a ``capred bridge compare`` run (forces in mN; None where a model has no bridge).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    meas = np.array([r["F_measured_mN"] for r in rows], float)
    hi = 0.0
    for name in ("exact", "toroidal", "willett", "israelachvili"):
        pred = np.array([np.nan if r[f"F_{name}_mN"] is None else r[f"F_{name}_mN"] for r in rows], float)
        ax.plot(meas, pred, ms=4, alpha=0.85, label=COMPARE_LABEL[name], **{**style(name), "ls": "none"})
        hi = max(hi, np.nanmax(pred, initial=0.0), np.nanmax(meas, initial=0.0))
    ax.plot([0, hi * 1.05], [0, hi * 1.05], "k--", lw=0.8, label="1:1")
    ax.set_xlabel(LABEL["F_measured"])
    ax.set_ylabel(LABEL["F_predicted"])
    ax.set_title("Micro-tests against theory")
    ax.legend()
    return ax


def sheet_compare(rows) -> Sheet:
    """The sheet of ``capred bridge compare``: measured against predicted forces, one panel.

    Parameters
    ----------
    rows : list of dict
        The JSON rows of a ``capred bridge compare`` run (forces in mN; None where a model has no bridge).

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        "Measured capillary forces against theory",
        [
            Panel(
                "measured_vs_predicted",
                untitled(lambda ax: plot_compare(ax, rows)),
                "Each sphere pair's measured force against the exact bridge of the same R, gap, contact angle and "
                "volume, the toroidal approximation, Willett et al. (2000) and Israelachvili.",
            )
        ],
        1,
    )


def plot_rupture(ax, rows):
    """Exact rupture distance against V^(1/3), one marker per contact angle, Lian's line for each.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    rows : list of dict
        The JSON rows of a ``capred bridge rupture`` run (volumes in mm³, distances in mm, angles in deg).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    palette = [OKABE_ITO[c] for c in ("black", "blue", "vermillion", "green", "purple", "orange", "sky")]
    ok = [r for r in rows if r["status"] == "ok"]
    angles = sorted({r["contact_angle_deg"] for r in ok})
    x_hi = max((r["V_w_mm3"] ** (1 / 3) for r in ok), default=1.0)
    markers = "osD^v<>ph"
    for k, th in enumerate(angles):
        sel = [r for r in ok if r["contact_angle_deg"] == th]
        colour = palette[k % len(palette)]
        x = np.array([r["V_w_mm3"] for r in sel]) ** (1 / 3)
        ax.plot(
            x,
            [r["D_rupture_mm"] for r in sel],
            ls="none",
            marker=markers[k % len(markers)],
            color=colour,
            ms=5,
            label=rf"exact, $\theta$ = {th:g}°",
        )
        xs = np.linspace(0, x_hi * 1.05, 50)
        ax.plot(
            xs, (1 + np.radians(th) / 2) * xs, color=colour, lw=1.0, ls="--", label=rf"Lian et al., $\theta$ = {th:g}°"
        )
    ax.set_xlabel(LABEL["V13"])
    ax.set_ylabel(LABEL["D_rupture"])
    ax.set_title("Rupture at constant volume")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend()
    return ax


def sheet_rupture(rows) -> Sheet:
    """The sheet of ``capred bridge rupture``: rupture distance against Lian et al. (1993), one panel.

    Parameters
    ----------
    rows : list of dict
        The JSON rows of a ``capred bridge rupture`` run (volumes in mm³, distances in mm, angles in deg).

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        "Rupture distance against Lian et al. (1993)",
        [
            Panel(
                "rupture_vs_lian",
                untitled(lambda ax: plot_rupture(ax, rows)),
                "Exact rupture distance (widest gap spanned at constant volume) against the cube root of the water "
                "volume, with Lian et al.'s estimate D = (1 + θ/2) V_w^(1/3) (θ in rad), one line style each.",
            )
        ],
        1,
    )
