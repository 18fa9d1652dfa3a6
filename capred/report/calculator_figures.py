"""Figure sheet of `capred skempton-b`: B against S_r, and the parameter studies of Morvan et al. (2016).

The studies are their Fig. 2, 3 and 5. Each computed case is drawn on the curve of its own parameters.
"""

from __future__ import annotations

import numpy as np

from .sheets import Panel, Sheet
from .style import LABEL, LINESTYLES, OKABE_ITO, SERIES_COLOURS

_COLORS = [OKABE_ITO[k] for k in ("black", "blue", "vermillion", "green", "orange", "purple", "sky")]


def _line(k: int) -> dict:
    """Colour and line style of the k-th curve of a parameter study (no markers: the curves are continuous)."""
    return dict(color=SERIES_COLOURS[k % len(SERIES_COLOURS)], ls=LINESTYLES[k % len(LINESTYLES)], lw=1.2)


def _axes(ax, title):
    ax.set_xlabel(LABEL["S_r"])
    ax.set_ylabel(LABEL["B"])
    ax.set_ylim(0, 1.02)
    ax.set_title(title)
    ax.legend()
    return ax


def plot_cases(ax, S, cases: list[dict], s_e=None, bc_lambda=None, bounding=None):
    """B(S_r) of every distinct parameter set among the cases, with the cases of that set on it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    S : ndarray
        Degrees of saturation of the curves [-].
    cases : list of dict
        Per parameter set (capred.pipelines.skempton_figure.figure_curves): ``params`` (κ [-], e0 [-], p0, u0,
        pa0 [Pa]), ``B_eq10``, ``B_suction`` and ``B_bounding`` (None where not computed) at ``S``, and the
        ``points`` (S_r values, B values) of its cases.
    s_e : float or None, optional
        Air-entry suction [Pa] of the suction-equilibrium curves, for their label.
    bc_lambda : float or None, optional
        Brooks-Corey index λ [-] of those curves, for their label.
    bounding : dict or None, optional
        ``a_ini`` [Pa] and ``air_pressure`` of the bounding-surface curves, for their label.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    for k, case in enumerate(cases):
        kappa, e0, p0, u0, pa0 = case["params"]
        color = _COLORS[k % len(_COLORS)]
        if case["B_bounding"] is not None:
            ax.plot(
                S,
                case["B_bounding"],
                "-.",
                color=color,
                lw=1.2,
                label=rf"  bounding-surface reconstruction ($A_{{ini}}$ = {bounding['a_ini'] / 1e3:g} kPa, "
                f"{bounding['air_pressure']} $P_a$)",
            )
        label = (
            rf"$\kappa$ = {kappa:g}, $e_0$ = {e0:g}, $p'_0$ = {(p0 - u0) / 1e3:g} kPa, "
            rf"$P_{{a0}}$ = {pa0 / 1e3:g} kPa"
        )
        ax.plot(S, case["B_eq10"], "-", color=color, lw=1.2, label=label)
        if case["B_suction"] is not None:
            ax.plot(
                S,
                case["B_suction"],
                "--",
                color=color,
                lw=1.0,
                label=rf"  with suction ($s_e$ = {s_e / 1e3:g} kPa, $\lambda$ = {bc_lambda:g})",
            )
        ax.plot(*case["points"], "o", color=color, ms=5, ls="none", label="  computed cases")
    return _axes(ax, "Computed cases on their own curves")


_CURVE_STYLE = {
    "B_eq10": dict(color=OKABE_ITO["black"], ls="-"),
    "B_suction": dict(color=OKABE_ITO["blue"], ls="--"),
    "B_bounding_NC": dict(color=OKABE_ITO["vermillion"], ls="-."),
    "B_bounding_OC": dict(color=OKABE_ITO["green"], ls=":"),
    "B_skempton1954": dict(color=OKABE_ITO["sky"], ls=(0, (1, 1)), lw=2.0),
    "B_hilf_lade": dict(color=OKABE_ITO["orange"], ls="--"),
    "B_schuurman1966": dict(color=OKABE_ITO["purple"], ls="-."),
}
_CURVE_LABEL = {
    "B_eq10": "eq. 10, elastic (Fig. 1)",
    "B_suction": "suction equilibrium (Fig. 5)",
    "B_bounding_NC": "bounding-surface reconstr., NC (Fig. 6)",
    "B_bounding_OC": "bounding-surface reconstr., OC (Fig. 6)",
    "B_skempton1954": "Skempton (1954), eq. 3",
    "B_hilf_lade": "Hilf (1948) / Lade & Hernandez (1977)",
    "B_schuurman1966": "Schuurman (1966), bubbles",
}


def plot_curves(ax, curves: dict):
    """B(S_r) of each model of `skempton-b --curve`, as Morvan et al. (2016) Fig. 1, 5 and 6 draw it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    curves : dict
        ``"S_r"`` -> degrees of saturation [-], and each model's key -> its B values [-].

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    S = curves["S_r"]
    for key, B in curves.items():
        if key != "S_r":
            style = {"lw": 1.3, **_CURVE_STYLE.get(key, {})}
            ax.plot(S, B, label=_CURVE_LABEL.get(key, key), **style)
    ax.set_xlim(0.5, 1.0)
    return _axes(ax, r"B against $S_r$ by model (Morvan et al. 2016, Fig. 1, 5, 6)")


def sheet_skempton(
    S_r,
    cases: list[dict],
    studies: dict,
    s_e=None,
    bc_lambda=None,
    bounding=None,
    curves: dict | None = None,
    curve_names: list[str] | None = None,
) -> Sheet:
    """The skempton-b sheet, drawn from the curves the pipeline computed.

    The curves come from capred.pipelines.skempton_figure.figure_curves: the cases on their own curves (or the models
    of ``skempton-b --curve``) and the parameter studies of Morvan et al. (2016), Fig. 2, 3, 5.

    Parameters
    ----------
    S_r : ndarray
        Degrees of saturation of the curves [-].
    cases : list of dict
        See :func:`plot_cases` (drawn when ``curves`` is None).
    studies : dict
        ``kappa``, ``e0``, ``s_e`` [Pa]: each value -> B at ``S_r``; ``lambda``: λ [-] of the s_e study.
    s_e, bc_lambda, bounding : optional
        See :func:`plot_cases`.
    curves : dict or None, optional
        See :func:`plot_curves`.
    curve_names : list of str or None, optional
        The models of ``curves`` as the caption names them.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    S = S_r

    def kappa_study(ax):
        for j, (k, B) in enumerate(studies["kappa"].items()):
            ax.plot(S, B, label=rf"$\kappa$ = {k:g}", **_line(j))
        return _axes(ax, r"Effect of $\kappa$ (Morvan et al. 2016, Fig. 2)")

    def e0_study(ax):
        for j, (e, B) in enumerate(studies["e0"].items()):
            ax.plot(S, B, label=f"$e_0$ = {e:g}", **_line(j))
        return _axes(ax, r"Effect of $e_0$ (Morvan et al. 2016, Fig. 3)")

    def se_study(ax):
        for j, (se, B) in enumerate(studies["s_e"].items()):
            ax.plot(S, B, label=f"$s_e$ = {se / 1e3:g} kPa", **_line(j))
        return _axes(ax, rf"Effect of $s_e$, $\lambda$ = {studies['lambda']:g} (Morvan et al. 2016, Fig. 5)")

    if curves is not None:
        first = Panel(
            "models",
            lambda ax: plot_curves(ax, curves),
            "B against S_r for each model asked: " + "; ".join(curve_names or []) + ". After Morvan et al. (2016), "
            "Fig. 1 (eq. 10), Fig. 5 (suction equilibrium) and Fig. 6 (elasto-plastic; here capred's Cam-clay "
            "bounding-surface reconstruction, not the BDNS model of their ref. [16]).",
        )
    else:
        first = Panel(
            "cases",
            lambda ax: plot_cases(ax, S, cases, s_e, bc_lambda, bounding),
            "B(S_r) of eq. 10 for each parameter set of the computed cases, the cases on their own curve.",
        )
    return Sheet(
        "Skempton's B against the degree of saturation",
        [
            first,
            Panel("kappa", kappa_study, "Effect of the slope κ of the elastic line."),
            Panel("e0", e0_study, "Effect of the initial void ratio."),
            Panel("air_entry", se_study, "With suction equilibrium: effect of the air-entry suction."),
        ],
        2,
    )


def plot_prism_mohr(ax, break_tension_kPa, friction_angle_deg, P_kmax_kPa, labels=None):
    """Mohr's diagram of the prism break (Bernatzik 1948).

    The circle from P_kmax to P_kmax + sigma_b touches the envelope tau = sigma tan rho; the isotropic capillary
    pressure P_kmax is where the circle starts.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    break_tension_kPa : array_like
        Break tension σ_b of each case [kPa].
    friction_angle_deg : array_like
        Friction angle ρ of each case [deg].
    P_kmax_kPa : array_like
        Isotropic capillary pressure P_kmax of each case [kPa].
    labels : list of str or None, optional
        Legend name of each case (default "case 1", ...).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    sb = np.asarray(break_tension_kPa, float)
    rho = np.asarray(friction_angle_deg, float)
    P = np.asarray(P_kmax_kPa, float)
    t = np.linspace(0.0, np.pi, 181)
    right = float(np.max(P + sb)) * 1.1
    for i in range(sb.size):
        color = _COLORS[i % len(_COLORS)]
        name = labels[i] if labels else f"case {i + 1}"
        c, r = P[i] + sb[i] / 2, sb[i] / 2
        ax.plot(
            c + r * np.cos(t),
            r * np.sin(t),
            "-",
            color=color,
            lw=1.3,
            label=rf"{name}: $\sigma_b$ = {sb[i]:.3g} kPa, $\rho$ = {rho[i]:g}°, $P_{{k,max}}$ = {P[i]:.3g} kPa",
        )
        s = np.array([0.0, right])
        ax.plot(s, s * np.tan(np.radians(rho[i])), "--", color=color, lw=0.9)
        ax.plot([P[i]], [0.0], "o", color=color, ms=5, clip_on=False)
        a = np.radians(rho[i])  # the tangent point: the radius to it is normal to the envelope
        ax.plot([c - r * np.sin(a)], [r * np.cos(a)], "x", color=color, ms=6)
    ax.plot([], [], "k--", lw=0.9, label=r"envelope $\tau = \sigma' \tan\rho$")
    ax.plot([], [], "ko", ms=5, label=r"$P_{k,max}$ (isotropic, $\sigma'_3$)")
    ax.plot([], [], "kx", ms=6, label="tangent point")
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, right / 2)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(r"$\sigma'$ [kPa]")
    ax.set_ylabel(r"$\tau$ [kPa]")
    ax.set_title("Mohr's diagram of the prism break (Bernatzik 1948)")
    ax.legend(loc="upper left", fontsize="x-small", frameon=False)
    return ax


def sheet_prism(break_tension_kPa, friction_angle_deg, P_kmax_kPa, labels=None) -> Sheet:
    """The figure of `capred prism`: Mohr's diagram of each case at break (Bernatzik 1948, the text's figure).

    Parameters
    ----------
    break_tension_kPa : array_like
        Break tension σ_b of each case [kPa].
    friction_angle_deg : array_like
        Friction angle ρ of each case [deg].
    P_kmax_kPa : array_like
        Isotropic capillary pressure P_kmax of each case [kPa].
    labels : list of str or None, optional
        Legend name of each case (default "case 1", ...).

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        "Prism test: Mohr's diagram at break",
        [
            Panel(
                "mohr",
                lambda ax: plot_prism_mohr(ax, break_tension_kPa, friction_angle_deg, P_kmax_kPa, labels),
                "At break the prism's effective stresses are the isotropic capillary pressure P_k,max (σ'_3) and "
                "P_k,max + σ_b (σ'_1); their Mohr circle touches the envelope τ = σ' tan ρ (× marks the "
                "tangent point), so sin ρ = σ_b/(2 P_k,max + σ_b). After Bernatzik (1948), Mohr's diagram of the "
                "text ('see fig.').",
            )
        ],
        1,
        spans={"mohr": 2},
        panel_size=(6.0, 3.0),
    )
