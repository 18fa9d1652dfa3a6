"""Figures of `capred bridge`: the thesis's analytical comparison and micro-test checks."""
from __future__ import annotations

import numpy as np

STYLE = {
    "exact": dict(color="k", lw=2.0, ls="-", label="Shape (exact Young-Laplace)"),
    "israelachvili": dict(color="tab:purple", lw=1.2, ls="--", label="Israelachvili 2γcosθ/R"),
    "bishop": dict(color="tab:blue", lw=1.2, ls="-.", label="Bishop S_R Δu"),
    "own1": dict(color="tab:orange", lw=1.2, ls=":", label="Own 1 χ1 Δu"),
    "own2": dict(color="tab:green", lw=1.4, ls="-", label="Own 2 χ1 Δu + χ2"),
}


def plot_curve(ax, curve, inside: bool):
    sel = curve.S_R < curve.pendular_limit if inside else np.ones(curve.S_R.size, bool)
    for name, v in curve.models().items():
        ax.plot(curve.S_R[sel], v[sel] / 1e3, **STYLE[name])
    if not inside:
        ax.axvline(curve.pendular_limit, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("S_R [-]")
    ax.set_ylabel("σ' [kPa]")
    ax.set_title("inside the pendular regime (S_R < 5 %)" if inside else "whole concave range (outside: S_R > 5 %)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper right")
    return ax


def figure_curve(curve):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 5))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.12, top=0.86, wspace=0.22)
    a, b = fig.subplots(1, 2)
    plot_curve(a, curve, True)
    plot_curve(b, curve, False)
    fig.suptitle(f"capred bridge curve — σ' = F_cap/(πR²) against S_R = 3V_w/(2πR³); R = {curve.R * 1e3:g} mm, "
                 f"γ = {curve.gamma:g} N/m, θ = {np.degrees(curve.theta):g}°, spheres in contact")
    return fig


def figure_compare(rows):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 6))
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.1, top=0.9)
    ax = fig.add_subplot()
    meas = np.array([r["F_measured_mN"] for r in rows], float)
    hi = 0.0
    for name, style in (("exact", "ko"), ("toroidal", "b^"), ("willett", "gs"), ("israelachvili", "mD")):
        pred = np.array([np.nan if r[f"F_{name}_mN"] is None else r[f"F_{name}_mN"] for r in rows], float)
        ax.plot(meas, pred, style, ms=5, alpha=0.8, label=name)
        hi = max(hi, np.nanmax(pred), np.nanmax(meas))
    ax.plot([0, hi * 1.05], [0, hi * 1.05], "k--", lw=0.8, label="1:1")
    ax.set_xlabel("measured F_cap [mN]")
    ax.set_ylabel("predicted F_cap [mN]")
    ax.legend(fontsize=8)
    fig.suptitle("capred bridge compare — microscopic tests against theory")
    return fig
