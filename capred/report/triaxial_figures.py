"""Figures of `capred triaxial-bounds`, after Fig. 16-18 of Prunier et al. (2024)."""
from __future__ import annotations

import numpy as np

KPA = 1e-3
BOUND_STYLE = {
    "lower": dict(color="tab:red", marker="v", label="LB (σ1_cap = 0)"),
    "spherical": dict(color="tab:blue", marker="o", label="UB q = q' (spherical)"),
    "edtp": dict(color="tab:green", marker="^", label="UB EDTP"),
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
    for i in np.flatnonzero(uns & np.isfinite(edtp.p_prime)):
        p0e = t["p0"][i] + t["s0"][i]
        ax.plot([p0e * KPA, edtp.p_prime[i] * KPA], [0, edtp.q_prime[i] * KPA], "--", color="tab:green", lw=0.8)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("p, p' [kPa]")
    ax.set_ylabel("q, q' [kPa]")
    ax.set_title("q-p plane: failure points and image points of each bound")
    ax.legend(fontsize=7, loc="upper left")
    return ax


def plot_capillary_ranges(ax, result):
    """sigma1_cap, sigma3_cap and p_cap of every bound, per unsaturated test."""
    t = result.tests
    idx = np.flatnonzero(result.unsaturated)
    width = 0.25
    comps = (("sigma1_cap", "σ1_cap"), ("sigma3_cap", "σ3_cap"), ("p_cap", "p_cap"))
    for k, (name, style) in enumerate(BOUND_STYLE.items()):
        b = result.bounds[name]
        for j, (attr, _) in enumerate(comps):
            x = np.arange(len(idx)) * 4 + j + (k - 1) * width
            ax.bar(x, getattr(b, attr)[idx] * KPA, width, color=style["color"], alpha=0.85,
                   label=style["label"] if j == 0 else None)
    ticks = [4 * n + j for n in range(len(idx)) for j in range(3)]
    ax.set_xticks(ticks, [f"{lab}\n{t['test_id'][i]}" if j == 1 else lab
                          for i in idx for j, (_, lab) in enumerate(comps)], fontsize=7)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_ylabel("capillary stress component [kPa]")
    ax.set_title("Range of capillary stresses at failure")
    ax.legend(fontsize=7, loc="lower right")
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
    ax.set_xlabel("σ, σ' [kPa]")
    ax.set_ylabel("τ [kPa]")
    ax.set_title("Mohr circles at failure")
    ax.legend(fontsize=7, loc="upper left")
    return ax


def figure_triaxial_report(result):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 10))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.08, top=0.93, wspace=0.22, hspace=0.3)
    gs = fig.add_gridspec(2, 2)
    plot_qp_plane(fig.add_subplot(gs[0, :]), result)
    plot_capillary_ranges(fig.add_subplot(gs[1, 0]), result)
    plot_mohr_circles(fig.add_subplot(gs[1, 1]), result)
    fig.suptitle("capred triaxial-bounds — capillary stress tensor at failure (Prunier et al. 2024)")
    return fig
