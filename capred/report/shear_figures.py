"""Report sheet of `capred shear`: one figure per material."""
from __future__ import annotations

import numpy as np

from .. import nomenclature as nom
from ..physics.effective_stress_models import MODEL_LABELS

MODEL_STYLE = {
    "no_suction": dict(color="0.45", marker="s"),
    "bishop": dict(color="tab:blue", marker="o"),
    "own1": dict(color="tab:orange", marker="^"),
    "own2": dict(color="tab:green", marker="D"),
    "vanapalli": dict(color="tab:purple", marker="v"),
    "khalili": dict(color="tab:brown", marker="<"),
    "lu_likos": dict(color="tab:pink", marker=">"),
    "fredlund": dict(color="tab:olive", marker="p"),
    "pedrotti_tarantino": dict(color="tab:cyan", marker="h"),
    "chi_power": dict(color="#CC79A7", marker="P"),
    "khalili_fit": dict(color="#D55E00", marker="X"),
    "exact_neck": dict(color="#0072B2", marker="*"),
}


def literal(text: str) -> str:
    """User text (a material name) drawn as written: no mathtext."""
    return str(text).replace("$", r"\$")
KPA = 1e-3


def plot_dry_envelope(ax, result, material):
    """Dry tests, fitted line tau = c + sigma_N tan(phi) and its confidence band."""
    t = result.tests
    fit = result.fits[material]
    dry = (t["material"] == material) & (t["condition"] == "dry")
    x = t["sigma_N"][dry]
    xs = np.linspace(0.0, max(x.max(), 1e-9) * 1.1, 100)
    lo, hi = fit.mean_band(xs)
    ax.fill_between(xs * KPA, lo * KPA, hi * KPA, color="tab:blue", alpha=0.2,
                    label=f"{fit.confidence:.0%} confidence band")
    phi = np.degrees(np.arctan(fit.slope))
    ax.plot(xs * KPA, fit.predict(xs) * KPA, color="tab:blue",
            label=f"c = {fit.intercept * KPA:.4g} kPa, φ = {phi:.2f}°")
    ax.plot(x * KPA, t["tau_max"][dry] * KPA, "ko", ms=4, label=f"dry tests (n = {fit.n})")
    ax.set_xlabel(nom.label("sigma_N"))
    ax.set_ylabel(nom.label("tau_max"))
    ax.set_title("Dry envelope")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    return ax


def _wet(result, material):
    t = result.tests
    return (t["material"] == material) & (t["condition"] == "wet")


def plot_measured_vs_predicted(ax, result, material):
    """Predicted against measured tau for the wet tests, each model, with the 1:1 line."""
    t = result.tests
    wet = _wet(result, material)
    meas = t["tau_max"][wet] * KPA
    hi = 0.0
    for m in result.models:
        pred = t[f"tau_pred_{m}"][wet] * KPA
        band = np.abs(np.vstack([pred - t[f"tau_pred_lo_{m}"][wet] * KPA, t[f"tau_pred_hi_{m}"][wet] * KPA - pred]))
        hi = max(hi, np.nanmax(pred, initial=0), meas.max(initial=0))
        met = result.metrics[material].get(m)
        rmse = f" (RMSE {met.rmse * KPA:.3g})" if met else ""
        ax.errorbar(meas, pred, yerr=band, ls="none", ms=4, alpha=0.85, elinewidth=0.8, capsize=1.5,
                    label=MODEL_LABELS[m] + rmse, **MODEL_STYLE[m])
    hi = hi * 1.05 or 1.0
    ax.plot([0, hi], [0, hi], "k--", lw=0.8, label="1:1")
    ax.set_xlim(0, hi)
    ax.set_ylim(0, hi)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("measured " + nom.label("tau_max"))
    ax.set_ylabel("predicted " + nom.label("tau_pred"))
    ax.set_title("Wet tests: measured vs predicted")
    ax.legend(fontsize=7, loc="upper left")
    return ax


def plot_strength_vs_saturation(ax, result, material):
    """Measured tau against S_R with each model's prediction and its band, as markers per test.

    No lines join the tests: a model defines tau along the water-retention
    relation, which the tests sample at their own (S_R, suction) pairs only.
    """
    t = result.tests
    wet = _wet(result, material)
    levels = np.unique(np.round(t["sigma_N"][wet], 6))
    for m in result.models:
        pred = t[f"tau_pred_{m}"][wet] * KPA
        band = np.abs(np.vstack([pred - t[f"tau_pred_lo_{m}"][wet] * KPA, t[f"tau_pred_hi_{m}"][wet] * KPA - pred]))
        ax.errorbar(t["S_R"][wet], pred, yerr=band, ls="none", ms=4, alpha=0.6, elinewidth=0.8,
                    markerfacecolor="none", label=MODEL_LABELS[m], **MODEL_STYLE[m])
    for k, level in enumerate(levels):
        sel = wet & (np.round(t["sigma_N"], 6) == level)
        ax.plot(t["S_R"][sel], t["tau_max"][sel] * KPA, "k" + "ov^sD"[k % 5], ms=4, ls="none",
                label=f"measured, σ_N = {level * KPA:.3g} kPa")
    ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(nom.label("S_R"))
    ax.set_ylabel(nom.label("tau_max"))
    ax.set_title("Strength against saturation")
    ax.legend(fontsize=7, loc="upper right")
    return ax


def plot_residuals(ax, result, material):
    """Residual (predicted - measured) against S_R for each model."""
    t = result.tests
    wet = _wet(result, material)
    for m in result.models:
        ax.plot(t["S_R"][wet], (t[f"tau_pred_{m}"][wet] - t["tau_max"][wet]) * KPA, ls="none", ms=4,
                alpha=0.85, label=MODEL_LABELS[m], **MODEL_STYLE[m])
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(nom.label("S_R"))
    ax.set_ylabel("τ_pred − τ_max [kPa]")
    ax.set_title("Residuals")
    ax.legend(fontsize=7, loc="lower left")
    return ax


def figure_shear_report(result, material):
    """2 x 2 report sheet for one material."""
    from matplotlib.figure import Figure

    # fixed margins: constrained layout would double the drawing time of a sheet
    fig = Figure(figsize=(11, 9))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.06, top=0.92, wspace=0.22, hspace=0.28)
    axes = fig.subplots(2, 2)
    plot_dry_envelope(axes[0, 0], result, material)
    if _wet(result, material).any():
        plot_measured_vs_predicted(axes[0, 1], result, material)
        plot_strength_vs_saturation(axes[1, 0], result, material)
        plot_residuals(axes[1, 1], result, material)
    else:
        for ax in (axes[0, 1], axes[1, 0], axes[1, 1]):
            ax.text(0.5, 0.5, "no wet tests", ha="center", va="center", transform=ax.transAxes)
            ax.set_axis_off()
    best = result.best_model.get(material)
    fig.suptitle(f"Direct shear, {literal(material)}" + (f": best model {MODEL_LABELS[best]}" if best else ""))
    return fig


def plot_capillary_stress(ax, result, material, x: str):
    """Back-analysed capillary stress of the wet tests (error bars: standard uncertainty) against S_R or
    suction, with each model's predicted capillary stress per test."""
    t = result.tests
    wet = _wet(result, material)
    xs = t[x][wet] * (1.0 if x == "S_R" else KPA)
    for m in result.models:
        ax.plot(xs, t[f"sigma_cap_pred_{m}"][wet] * KPA, ls="none", ms=4, alpha=0.75, markerfacecolor="none",
                label=MODEL_LABELS[m], **MODEL_STYLE[m])
    ax.errorbar(xs, t["sigma_cap"][wet] * KPA, yerr=t["sigma_cap_se"][wet] * KPA, fmt="ko", ms=4, capsize=2,
                elinewidth=0.8, label="back-analysed (± 1 se)")
    if x == "S_R":
        ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(nom.label(x))
    ax.set_ylabel("σ_cap [kPa]")
    ax.set_title("Capillary stress carried, against " + ("saturation" if x == "S_R" else "suction"))
    return ax


def plot_chi_back(ax, result, material):
    """chi_back = sigma_cap / Delta_u of the wet tests against S_R, with chi = S_R, chi1 and the fitted chi = S_e^kappa."""
    from ..physics import shear as ph

    t = result.tests
    wet = _wet(result, material) & (t["suction"] > 0)
    s = np.linspace(0.0, 1.0, 201)
    ax.plot(s, s, color=MODEL_STYLE["bishop"]["color"], lw=1.2, label="χ = S_R (Bishop)")
    ax.plot(s, ph.chi1(s), color=MODEL_STYLE["own1"]["color"], lw=1.2, label="χ1 = (2π S_R/3)^(2/3)")
    law = result.laws.get("chi_power", {}).get(material)
    if law is not None:
        s_res = result.options.model_params.s_res or 0.0
        se = np.clip((s - s_res) / (1 - s_res), 0, 1)
        ax.plot(s, se ** law.params["kappa"], color=MODEL_STYLE["chi_power"]["color"], lw=1.2,
                label=f"χ = S_e^κ, κ = {law.params['kappa']:.3g} (fitted)")
    ax.errorbar(t["S_R"][wet], t["chi_back"][wet], yerr=t["chi_back_se"][wet], fmt="ko", ms=4, capsize=2,
                elinewidth=0.8, label="χ back-analysed (± 1 se)")
    ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(nom.label("S_R"))
    ax.set_ylabel("χ [–]")
    ax.set_title("Effective-stress parameter χ")
    return ax


def figure_capillary_stress(result, material):
    """What capillary stress each wet test carried and which chi law explains it: 3 panels."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(15, 5.6))
    fig.subplots_adjust(left=0.05, right=0.99, bottom=0.27, top=0.88, wspace=0.22)
    axes = fig.subplots(1, 3)
    plot_capillary_stress(axes[0], result, material, "S_R")
    plot_capillary_stress(axes[1], result, material, "suction")
    plot_chi_back(axes[2], result, material)
    # legends below the panels, never over the data
    for ax, anchor in ((axes[0], (0.36, 0.0)), (axes[2], (0.84, 0.0))):
        handles, labels = ax.get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", bbox_to_anchor=anchor, ncol=2, fontsize=8, frameon=False)
    fig.suptitle(f"Back-analysed capillary stress, {literal(material)}")
    return fig


def figure_curves(result, material):
    """The raw shear curves of one material (tau against horizontal displacement) with the picked peaks."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 5.5))
    fig.subplots_adjust(left=0.1, right=0.72, bottom=0.1, top=0.9)
    ax = fig.subplots()
    t = result.tests
    for k, tid in enumerate(t["test_id"][t["material"] == material]):
        curve = result.curves.curves.get(str(tid))
        if curve is None:
            continue
        d, tau, peak = curve
        line, = ax.plot(d * 1e3, tau * KPA, lw=1.0, label=literal(tid))
        ax.plot(d[peak] * 1e3, tau[peak] * KPA, "o", color=line.get_color(), ms=5)
    ax.set_xlabel("horizontal displacement δ [mm]")
    ax.set_ylabel("τ [kPa]")
    ax.set_title(f"Shear curves, {literal(material)} (dots: peaks)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), ncol=1 if k < 25 else 2, frameon=False)
    return fig
