"""Figure sheets of `capred shear`: per material, the report, the capillary stress and the raw curves."""
from __future__ import annotations

import numpy as np

from ..physics.effective_stress_models import MODEL_LABELS, REGISTRY
from .sheets import Panel, Sheet
from .style import LABEL, literal
from .style import style as _style

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
    ax.set_xlabel(LABEL["sigma_N"])
    ax.set_ylabel(LABEL["tau_max"])
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
        p = result.predictions[m]
        pred = p.tau[wet] * KPA
        lo_pi, hi_pi = p.tau_prediction_interval
        band = np.abs(np.vstack([pred - lo_pi[wet] * KPA, hi_pi[wet] * KPA - pred]))
        hi = max(hi, np.nanmax(pred, initial=0), meas.max(initial=0))
        met = result.metrics[material].get(m)
        rmse = f" (RMSE {met.rmse * KPA:.3g})" if met else ""
        ax.errorbar(meas, pred, yerr=band, ls="none", ms=4, alpha=0.85, elinewidth=0.8, capsize=1.5,
                    label=MODEL_LABELS[m] + rmse, **_style(m))
    hi = hi * 1.05 or 1.0
    ax.plot([0, hi], [0, hi], "k--", lw=0.8, label="1:1")
    ax.set_xlim(0, hi)
    ax.set_ylim(0, hi)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("measured " + LABEL["tau_max"])
    ax.set_ylabel("predicted " + LABEL["tau_pred"])
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
    relation = result.retention_relation(material)
    if relation is not None:  # model curves along the water-retention relation, one per normal stress
        for k, level in enumerate(levels):
            S, taus = result.model_curves(material, float(level))
            for m, tau in taus.items():
                ax.plot(S, tau * KPA, "-", color=_style(m)["color"], lw=1.0, alpha=0.9,
                        label=MODEL_LABELS[m] if k == 0 else None)
    for m in result.models:
        if relation is not None and REGISTRY[m].along_retention:
            continue
        p = result.predictions[m]
        pred = p.tau[wet] * KPA
        lo_pi, hi_pi = p.tau_prediction_interval
        band = np.abs(np.vstack([pred - lo_pi[wet] * KPA, hi_pi[wet] * KPA - pred]))
        ax.errorbar(t["S_R"][wet], pred, yerr=band, ls="none", ms=4, alpha=0.6, elinewidth=0.8,
                    markerfacecolor="none", label=MODEL_LABELS[m], **_style(m))
    for k, level in enumerate(levels):
        sel = wet & (np.round(t["sigma_N"], 6) == level)
        ax.plot(t["S_R"][sel], t["tau_max"][sel] * KPA, "k" + "ov^sD"[k % 5], ms=4, ls="none",
                label=rf"measured, $\sigma_N$ = {level * KPA:.3g} kPa")
    ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["tau_max"])
    ax.set_title("Strength against saturation")
    ax.legend(fontsize=7, loc="upper right")
    return ax


def plot_residuals(ax, result, material):
    """Residual (predicted - measured) against S_R for each model."""
    t = result.tests
    wet = _wet(result, material)
    for m in result.models:
        ax.plot(t["S_R"][wet], result.predictions[m].residual[wet] * KPA, ls="none", ms=4,
                alpha=0.85, label=MODEL_LABELS[m], **_style(m))
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["residual"])
    ax.set_title("Residuals")
    ax.legend(fontsize=7, loc="lower left")
    return ax


def _strength_caption(result, material) -> str:
    relation = result.retention_relation(material)
    if relation is None:
        return ("Measured strength and each model's prediction per test against S_R, as markers: no "
                "water-retention relation is available to draw model curves.")
    return ("Measured strength against S_R; model curves at each normal stress along the water-retention "
            f"relation: {relation.source}.")


def sheet_shear_report(result, material) -> Sheet:
    """The report sheet of one material: dry envelope, measured vs predicted, strength vs S_R, residuals."""
    best = result.best_model.get(material)
    panels = [Panel("dry_envelope", lambda ax: plot_dry_envelope(ax, result, material),
                    "Dry tests and the fitted envelope with its 95 % confidence band.")]
    if _wet(result, material).any():
        panels += [Panel("measured_vs_predicted", lambda ax: plot_measured_vs_predicted(ax, result, material),
                         "Wet tests: each model's prediction, with the 95 % prediction interval of a new test, against the measured strength."),
                   Panel("strength_vs_saturation", lambda ax: plot_strength_vs_saturation(ax, result, material),
                         _strength_caption(result, material)),
                   Panel("residuals", lambda ax: plot_residuals(ax, result, material),
                         "Residual (predicted − measured) against S_R.")]
    title = f"Direct shear, {material}" + (f": best model {MODEL_LABELS[best]}" if best else "")
    return Sheet(title, panels, 2)


def plot_capillary_stress(ax, result, material, x: str):
    """Back-analysed capillary stress of the wet tests (error bars: standard uncertainty) against S_R or
    suction, with each model's predicted capillary stress per test."""
    t = result.tests
    wet = _wet(result, material)
    xs = t[x][wet] * (1.0 if x == "S_R" else KPA)
    for m in result.models:
        ax.plot(xs, result.predictions[m].sigma_cap[wet] * KPA, ls="none", ms=4, alpha=0.75, markerfacecolor="none",
                label=MODEL_LABELS[m], **_style(m))
    back = result.back
    ax.errorbar(xs, back.sigma_cap[wet] * KPA, yerr=back.sigma_cap_se[wet] * KPA, fmt="ko", ms=4, capsize=2,
                elinewidth=0.8, label="back-analysed (± 1 se)")
    if x == "S_R":
        ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(LABEL[x])
    ax.set_ylabel(LABEL["sigma_cap"])
    ax.set_title("Capillary stress carried, against " + ("saturation" if x == "S_R" else "suction"))
    return ax


def plot_chi_back(ax, result, material):
    """chi_back = sigma_cap / Delta_u of the wet tests against S_R, with the chi(S_R) of every model of the run
    that has one (Bishop's S_R, Own 1's chi1, a fitted S_e^kappa ...)."""
    t = result.tests
    wet = _wet(result, material) & (t["suction"] > 0)
    s = np.linspace(0.0, 1.0, 201)
    params = result.options.model_params
    for m in result.models:
        entry = REGISTRY[m]
        if entry.chi_of_saturation is None:
            continue
        law = result.laws.get(m, {}).get(material)
        chi = entry.chi_of_saturation(s, params, law.params if law is not None else None)
        if np.isfinite(chi).any():
            extra = "".join(f", {k} = {law.params[k]:.3g}" for k in entry.fitted) if law is not None else ""
            ax.plot(s, chi, color=_style(m)["color"], lw=1.2, label=MODEL_LABELS[m] + extra)
    back = result.back
    ax.errorbar(t["S_R"][wet], back.chi_back[wet], yerr=back.chi_back_se[wet], fmt="ko", ms=4, capsize=2,
                elinewidth=0.8, label="χ back-analysed (± 1 se)")
    ax.axvline(result.options.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["chi"])
    ax.set_title("Effective-stress parameter χ")
    return ax


def sheet_capillary_stress(result, material) -> Sheet:
    """What capillary stress each wet test carried and which chi law explains it: 3 panels."""
    return Sheet(f"Back-analysed capillary stress, {material}", [
        Panel("sigma_cap_vs_saturation", lambda ax: plot_capillary_stress(ax, result, material, "S_R"),
              "σ_cap = (τ_max − c)/tan φ − σ_N of each wet test (± 1 standard uncertainty) and each model's "
              "prediction, against S_R."),
        Panel("sigma_cap_vs_suction", lambda ax: plot_capillary_stress(ax, result, material, "suction"),
              "The same against the suction."),
        Panel("chi", lambda ax: plot_chi_back(ax, result, material),
              "χ_back = σ_cap/Δu against S_R with the χ(S_R) of each model of the run that has one."),
    ], 3, panel_size=(4.2, 3.4))


def sheet_curves(result, material) -> Sheet:
    return Sheet(f"Shear curves, {material}", [
        Panel("curves", lambda ax: plot_curves(ax, result, material),
              "Shear stress against horizontal displacement; dots mark the picked peaks.")], 1)


def plot_curves(ax, result, material):
    """The raw shear curves of one material (tau against horizontal displacement) with the picked peaks."""
    t = result.tests
    for k, tid in enumerate(t["test_id"][t["material"] == material]):
        curve = result.curves.curves.get(str(tid))
        if curve is None:
            continue
        d, tau, peak = curve
        line, = ax.plot(d * 1e3, tau * KPA, lw=1.0, label=literal(tid))
        ax.plot(d[peak] * 1e3, tau[peak] * KPA, "o", color=line.get_color(), ms=5)
    ax.set_xlabel(LABEL["displacement"])
    ax.set_ylabel(LABEL["tau"])
    ax.set_title("Shear curves (dots: peaks)")
    ax.legend()
    return ax
