"""Figures of `capred triaxial-bounds`, after Fig. 16-18 of Prunier et al. (2024)."""
from __future__ import annotations

import numpy as np

from ..physics import triaxial as tx
from .sheets import Panel, Sheet
from .style import LABEL, literal
from .style import style as model_style

KPA = 1e-3
BOUND_STYLE = {
    "lower": dict(**model_style("lower"), label=r"LB ($\sigma_{1,cap}$ = 0)"),
    "spherical": dict(**model_style("spherical"), label="UB q = q' (spherical)"),
    "edtp": dict(**model_style("edtp"), label="UB EDTP"),
}


def plot_qp_plane(ax, result):
    """Envelope, saturated and unsaturated failure points, image points and assumed paths."""
    t = result.tests
    env = result.envelope
    sat = t["condition"] == "saturated"
    uns = result.unsaturated
    p_all = np.concatenate([t["p"], *(b.p_prime[np.isfinite(b.p_prime)] for b in result.bounds.values())])
    p_max = max(float(np.nanmax(p_all)) * 1.1, 1.0)
    ps = np.linspace(0.0, p_max, 50)
    ax.plot(ps * KPA, (env.M * ps + env.k) * KPA, "k-", lw=1.2,
            label=f"effective envelope (c' = {env.c * KPA:.3g} kPa, φ' = {env.phi:.2f}°)")
    ax.plot(t["p"][sat] * KPA, t["q"][sat] * KPA, "ks", mfc="white", label="saturated failure (p', q)")
    ax.plot(t["p"][uns] * KPA, t["q"][uns] * KPA, "k*", ms=9, label="unsaturated failure (p, q) total")
    for name, style in BOUND_STYLE.items():
        b = result.bounds[name]
        ok = uns & np.isfinite(b.p_prime)
        if not ok.any():
            continue
        ax.plot(b.p_prime[ok] * KPA, b.q_prime[ok] * KPA, ls="none", ms=7, color=style["color"],
                marker=style["marker"], label=style["label"])
        for i in np.flatnonzero(ok):
            ax.annotate("", xy=(b.p_prime[i] * KPA, b.q_prime[i] * KPA), xytext=(t["p"][i] * KPA, t["q"][i] * KPA),
                        arrowprops=dict(arrowstyle="->", color=style["color"], lw=0.8, alpha=0.7))
    edtp = result.bounds["edtp"]
    for k, i in enumerate(np.flatnonzero(uns & np.isfinite(edtp.p_prime))):
        p0e = t["p0"][i] + t["s0"][i]
        ax.plot([p0e * KPA, edtp.p_prime[i] * KPA], [0, edtp.q_prime[i] * KPA], "--", color=model_style("edtp")["color"],
                lw=0.8, label="EDTP stress path (from p0 + s0)" if k == 0 else None)
    for g in result.groups:  # the apparent (total) envelope of each group sharing one capillary tensor
        if "C_apparent_kPa" not in g:
            continue
        M, k_app = tx.envelope_qp(g["C_apparent_kPa"] * 1e3, g["phi_apparent_deg"])
        ax.plot(ps * KPA, (M * ps + k_app) * KPA, ":", color="0.3", lw=1.0,
                label=f"group {literal(g['group'])}: apparent envelope (C = {g['C_apparent_kPa']:.3g} kPa, "
                      f"φ = {g['phi_apparent_deg']:.3g}°)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_xlabel(LABEL["p"])
    ax.set_ylabel(LABEL["q"])
    ax.set_title("q-p plane: failure points and the image points of each bound")
    ax.legend()
    return ax


def plot_capillary_ranges(ax, result):
    """sigma1_cap, sigma3_cap and p_cap of every bound, per unsaturated test: colour = bound, hatch = component."""
    from matplotlib.patches import Patch

    t = result.tests
    idx = np.flatnonzero(result.unsaturated)
    comps = (("sigma1_cap", r"$\sigma_{1,cap}$", ""), ("sigma3_cap", r"$\sigma_{3,cap}$", "///"),
             ("p_cap", r"$p_{cap}$", "..."))
    width = 0.8 / (len(BOUND_STYLE) * len(comps))
    for k, (name, st) in enumerate(BOUND_STYLE.items()):
        b = result.bounds[name]
        for j, (attr, _, hatch) in enumerate(comps):
            x = np.arange(len(idx)) - 0.4 + width * (k * len(comps) + j + 0.5)
            ax.bar(x, getattr(b, attr)[idx] * KPA, width, color=st["color"], alpha=0.85, hatch=hatch,
                   edgecolor="white", lw=0.3)
    ax.set_xticks(np.arange(len(idx)), [literal(t["test_id"][i]) for i in idx], fontsize=7)
    ax.axhline(0, color="k", lw=0.8)
    handles = [Patch(color=st["color"], label=st["label"]) for st in BOUND_STYLE.values()]
    handles += [Patch(facecolor="0.75", hatch=h, edgecolor="white", label=lab) for _, lab, h in comps]
    ax.legend(handles=handles)
    ax.set_ylabel(LABEL["cap_component"])
    ax.set_title("Capillary stresses at failure, per test")
    return ax


def plot_mohr_circles(ax, result):
    """Total failure circles (unsaturated), lower-bound effective circles and the envelope."""
    t = result.tests
    env = result.envelope
    th = np.linspace(0, np.pi, 90)
    hi = 0.0
    for i in range(len(t["test_id"])):
        if result.unsaturated[i]:
            pairs = [(t["sigma3"][i], t["sigma1"][i], "k-", "total")]
            lb = result.bounds["lower"]
            s3e = t["sigma3"][i] - lb.sigma3_cap[i]
            pairs.append((s3e, t["sigma1"][i] - lb.sigma1_cap[i], "r--", "effective (LB)"))
        else:
            pairs = [(t["sigma3"][i], t["sigma1"][i], "0.6", "saturated")]
        for a, b, style, _ in pairs:
            c, r = (a + b) / 2, (b - a) / 2
            ax.plot((c + r * np.cos(th)) * KPA, r * np.sin(th) * KPA, style, lw=0.9)
            hi = max(hi, b)
    s = np.linspace(0, hi, 20)
    ax.plot(s * KPA, (env.c + s * np.tan(np.radians(env.phi))) * KPA, "b-", lw=1.0, label="τ = c' + σ' tan φ'")
    ax.plot([], [], "k-", label="unsaturated, total")
    ax.plot([], [], "r--", label="unsaturated, effective (LB)")
    ax.plot([], [], color="0.6", label="saturated, effective")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(LABEL["sigma"])
    ax.set_ylabel(LABEL["tau"])
    ax.set_title("Mohr circles at failure")
    ax.legend()
    return ax


def sheet_triaxial(result) -> Sheet:
    return Sheet("Capillary stress tensor at failure (after Prunier et al. 2024, Fig. 16-18)", [
        Panel("qp_plane", lambda ax: plot_qp_plane(ax, result),
              "Failure points in the q-p plane, the effective envelope, the image points of each bound and the "
              "EDTP stress paths; groups' apparent envelopes dotted."),
        Panel("capillary_stresses", lambda ax: plot_capillary_ranges(ax, result),
              "σ1,cap, σ3,cap and p_cap of each bound for every unsaturated test."),
        Panel("mohr_circles", lambda ax: plot_mohr_circles(ax, result),
              "Mohr circles at failure: total (unsaturated), effective under the lower bound, and saturated."),
    ], 2, spans={"qp_plane": 2})
