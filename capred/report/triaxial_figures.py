"""Figures of `capred triaxial-bounds`, after Fig. 16-18 of Prunier et al. (2024)."""

from __future__ import annotations

import numpy as np

from .sheets import Panel, Sheet
from .style import LABEL, OKABE_ITO, literal
from .style import style as model_style
from .triaxial_reference_curves import reference_panels

#: one colour per group (Okabe-Ito, the bounds' vermillion, blue and green left to the bounds)
GROUP_COLOURS = [OKABE_ITO[k] for k in ("orange", "sky", "purple", "yellow", "black", "grey")]
#: Mohr circles: unsaturated total, unsaturated effective under the lower bound (the bound's colour), saturated
MOHR = {
    "total": dict(color=OKABE_ITO["black"], ls="-", label="unsaturated, total"),
    "effective": dict(color=OKABE_ITO["vermillion"], ls="--", label="unsaturated, effective (LB)"),
    "saturated": dict(color=OKABE_ITO["grey"], ls=":", label="saturated, effective"),
}
BOUND_STYLE = {
    "lower": dict(**model_style("lower"), label=r"LB ($\sigma_{1,cap}$ = 0)"),
    "spherical": dict(**model_style("spherical"), label=r"UB $q = q'$ (spherical)"),
    "edtp": dict(**model_style("edtp"), label="UB EDTP"),
}


def plot_qp_plane(ax, result):
    """Envelope, saturated and unsaturated failure points, image points and assumed paths.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.states  # kPa
    env = result.envelope
    sat = t.condition == "saturated"
    uns = result.unsaturated
    p_all = np.concatenate([t.p, *(b.p_prime[np.isfinite(b.p_prime)] for b in result.bound_states.values())])
    p_max = max(float(np.nanmax(p_all)) * 1.1, 1e-3)
    ps = np.linspace(0.0, p_max, 50)
    ax.plot(
        ps,
        env.M * ps + env.k_kPa,
        "k-",
        lw=1.2,
        label=rf"effective envelope ($c'$ = {env.c_kPa:.3g} kPa, $\phi'$ = {env.phi_deg:.2f}°)",
    )
    ext = t.branch == "extension"
    if ext.any():  # extension: M = 6 sin phi'/(3 + sin phi')
        ax.plot(
            ps,
            env.M_extension * ps + env.k_extension_kPa,
            "k--",
            lw=1.0,
            label=r"effective envelope, extension ($M = 6\sin\phi'/(3 + \sin\phi')$)",
        )
    ax.plot(t.p[sat & ~ext], t.q[sat & ~ext], "ks", mfc="white", label=r"saturated failure ($p'$, $q$)")
    if (uns & ~ext).any():  # a legend entry only for what is drawn
        ax.plot(t.p[uns & ~ext], t.q[uns & ~ext], "k*", ms=9, label=r"unsaturated failure ($p$, $q$), total")
    if ext.any():
        ax.plot(
            t.p[sat & ext],
            t.q[sat & ext],
            "kD",
            mfc="white",
            ms=5,
            label="saturated failure, extension",
        )
        ax.plot(t.p[uns & ext], t.q[uns & ext], "kP", ms=7, label="unsaturated failure, extension")
    for name, style in BOUND_STYLE.items():
        b = result.bound_states[name]
        ok = uns & np.isfinite(b.p_prime)
        if not ok.any():
            continue
        ax.plot(
            b.p_prime[ok],
            b.q_prime[ok],
            ls="none",
            ms=7,
            color=style["color"],
            marker=style["marker"],
            label=style["label"],
        )
        for i in np.flatnonzero(ok):
            ax.annotate(
                "",
                xy=(b.p_prime[i], b.q_prime[i]),
                xytext=(t.p[i], t.q[i]),
                arrowprops=dict(arrowstyle="->", color=style["color"], lw=0.8, alpha=0.7),
            )
    edtp = result.bound_states["edtp"]
    for k, i in enumerate(np.flatnonzero(uns & np.isfinite(edtp.p_prime))):
        p0e = t.p0[i] + t.s0[i]
        ax.plot(
            [p0e, edtp.p_prime[i]],
            [0, edtp.q_prime[i]],
            "--",
            color=model_style("edtp")["color"],
            lw=0.8,
            label=r"EDTP stress path (from $p_0 + s_0$)" if k == 0 else None,
        )
    for j, g in enumerate(result.groups):  # the apparent (total) envelope of each group sharing one tensor
        if g.apparent_M is None:
            continue
        ax.plot(
            ps,
            g.apparent_M * ps + g.apparent_k,
            ":",
            color=GROUP_COLOURS[j % len(GROUP_COLOURS)],
            lw=1.0,
            label=f"group {literal(g.group)}: apparent envelope ($C$ = {g.C_apparent:.3g} kPa, "
            rf"$\phi$ = {g.phi_apparent:.3g}°)",
        )
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_xlabel(LABEL["p"])
    ax.set_ylabel(LABEL["q"])
    ax.set_title(r"$q$-$p$ plane: failure and image points (Fig. 16-17)")
    ax.legend()
    return ax


def plot_capillary_ranges(ax, result):
    """sigma1_cap, sigma3_cap and p_cap of every bound, per unsaturated test: colour = bound, hatch = component.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    from matplotlib.patches import Patch

    t = result.states
    idx = np.flatnonzero(result.unsaturated)
    ax.set_ylabel(LABEL["cap_component"])
    ax.set_title("Capillary stresses per test (Fig. 18)")
    if not idx.size:  # an all-saturated run has no capillary stress to show
        ax.text(0.5, 0.5, "no unsaturated test", ha="center", va="center", transform=ax.transAxes)
        ax.set_xticks([])
        return ax
    comps = (
        ("sigma1_cap", r"$\sigma_{1,cap}$", ""),
        ("sigma3_cap", r"$\sigma_{3,cap}$", "///"),
        ("p_cap", r"$p_{cap}$", "..."),
    )
    width = 0.8 / (len(BOUND_STYLE) * len(comps))
    for k, (name, st) in enumerate(BOUND_STYLE.items()):
        b = result.bound_states[name]
        for j, (attr, _, hatch) in enumerate(comps):
            x = np.arange(len(idx)) - 0.4 + width * (k * len(comps) + j + 0.5)
            ax.bar(
                x,
                getattr(b, attr)[idx],
                width,
                color=st["color"],
                alpha=0.85,
                hatch=hatch,
                edgecolor="white",
                lw=0.3,
            )
    ax.set_xticks(np.arange(len(idx)), [literal(t.test_id[i]) for i in idx], fontsize=7)
    ax.axhline(0, color="k", lw=0.8)
    handles = [Patch(color=st["color"], label=st["label"]) for st in BOUND_STYLE.values()]
    handles += [Patch(facecolor="0.75", hatch=h, edgecolor="white", label=lab) for _, lab, h in comps]
    ax.legend(handles=handles)
    return ax


def plot_mohr_circles(ax, result):
    """Total failure circles (unsaturated), lower-bound effective circles and the envelope.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.states  # kPa
    env = result.envelope
    th = np.linspace(0, np.pi, 90)
    hi = 0.0
    lb = result.bound_states["lower"]
    for i in range(len(t)):
        if result.unsaturated[i]:
            pairs = [(t.sigma3[i], t.sigma1[i], MOHR["total"])]
            pairs.append((t.sigma3[i] - lb.sigma3_cap[i], t.sigma1[i] - lb.sigma1_cap[i], MOHR["effective"]))
        else:
            pairs = [(t.sigma3[i], t.sigma1[i], MOHR["saturated"])]
        for a, b, st in pairs:
            c, r = (a + b) / 2, (b - a) / 2
            ax.plot(c + r * np.cos(th), r * np.sin(th), color=st["color"], ls=st["ls"], lw=0.9)
            hi = max(hi, b)
    s = np.linspace(0, hi, 20)
    ax.plot(
        s,
        env.c_kPa + s * np.tan(np.radians(env.phi_deg)),
        color=OKABE_ITO["blue"],
        ls="-",
        lw=1.0,
        label=r"$\tau = c' + \sigma' \tan\phi'$",
    )
    drawn = {"saturated"} if (~np.asarray(result.unsaturated, bool)).any() else set()
    if np.any(result.unsaturated):
        drawn |= {"total", "effective"}
    for key, st in MOHR.items():
        if key in drawn:  # a legend entry only for circles drawn
            ax.plot([], [], color=st["color"], ls=st["ls"], label=st["label"])
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(LABEL["sigma"])
    ax.set_ylabel(LABEL["tau"])
    ax.set_title("Mohr circles at failure (Fig. 19-20)")
    ax.legend()
    return ax


def plot_group_circles(ax, result):
    """Each group's unsaturated Mohr circles (solid) and fictive circles sigma'' (dashed, eq. 44).

    With the lines of cohesion C and C'' at the effective friction angle (eq. 43, 48).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.states  # kPa
    env = result.envelope
    th = np.linspace(0, np.pi, 90)
    tan_phi = np.tan(np.radians(env.phi_deg))
    hi = 0.0
    for j, g in enumerate(result.groups):
        colour = GROUP_COLOURS[j % len(GROUP_COLOURS)]
        sel = np.isin(t.test_id, g.tests)
        pairs = [(a, b, "-") for a, b in zip(t.sigma3[sel], t.sigma1[sel])]
        if g.fictive_sigma1:
            pairs += [(a, b, "--") for a, b in zip(g.fictive_sigma3, g.fictive_sigma1)]
        for a, b, ls in pairs:
            c, r = (a + b) / 2, (b - a) / 2
            ax.plot(c + r * np.cos(th), r * np.sin(th), ls=ls, color=colour, lw=0.9)
            hi = max(hi, b)
        s_line = np.linspace(0.0, hi, 20)
        for key, ls, what in (("C", "-", "C"), ("C_fictive", "--", "C''")):
            value = getattr(g, key)
            if value is not None:
                ax.plot(
                    s_line,
                    value + s_line * tan_phi,
                    ls=ls,
                    color=colour,
                    lw=1.4,
                    label=f"group {literal(g.group)}: ${what}$ = {value:.3g} kPa",
                )
    s_line = np.linspace(0.0, max(hi, 1.0), 20)
    ax.plot(s_line, env.c_kPa + s_line * tan_phi, "k-", lw=1.0, label=f"effective envelope, $C'$ = {env.c_kPa:.3g} kPa")
    ax.plot([], [], "k-", lw=0.9, label="unsaturated circles (total)")
    ax.plot([], [], "k--", lw=0.9, label=r"fictive circles $\sigma''$ (saturated radius)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    # equal scales by the panel's box: with the limits fixed at 0, "datalim" made matplotlib log "Ignoring fixed
    # x limits ..." on the console of every run with groups
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(LABEL["sigma"])
    ax.set_ylabel(LABEL["tau"])
    ax.set_title(r"Groups: circles, lines $C$ and $C''$ (Fig. 21)")
    ax.legend()
    return ax


def plot_group_tensors(ax, result):
    """sigma1_cap, sigma2_cap, sigma3_cap of each group.

    Eq. 48 or 50 with standard errors, or, for a group without paired saturated tests, the admissible range of each
    component between the closures (eq. 37) with the chosen closure marked.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    groups = [g for g in result.groups if g.determined or g.admissible is not None]
    comps = ((1, r"$\sigma_{1,cap}$", ""), (2, r"$\sigma_{2,cap}$", "///"), (3, r"$\sigma_{3,cap}$", "..."))
    width = 0.8 / len(comps)
    ranged = False
    for k, (n, label, hatch) in enumerate(comps):
        x = np.arange(len(groups)) - 0.4 + width * (k + 0.5)
        for xi, g in zip(x, groups):
            colour = GROUP_COLOURS[result.groups.index(g) % len(GROUP_COLOURS)]
            if g.determined:
                value, se = getattr(g, f"sigma{n}_cap"), getattr(g, f"sigma{n}_cap_se") or 0.0
                ax.bar(xi, value, width, yerr=se, capsize=3, hatch=hatch, edgecolor="white", lw=0.3, color=colour)
                continue
            ranged = True
            r = getattr(g.admissible, f"sigma{n}_cap")
            ax.bar(
                xi,
                r.upper - r.lower,
                width,
                bottom=r.lower,
                hatch=hatch,
                color=colour,
                alpha=0.35,
                lw=0.8,
                edgecolor=colour,
            )
            chosen = next(c for c in g.closures if c.chosen)
            ax.plot([xi], [getattr(chosen, f"sigma{n}_cap")], marker="_", ms=12, mew=2, color="k")

    def short(g):
        if not g.determined:
            return "eq. 37: range"
        return (g.method or "").split(" (")[0]

    ax.set_xticks(np.arange(len(groups)), [f"{literal(g.group)}\n{short(g)}" for g in groups], fontsize=7)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_ylabel(LABEL["cap_component"])
    ax.set_title(r"Tensor of each group ($\pm$ se; range without pairs)")
    handles = [Patch(facecolor="0.75", hatch=h, edgecolor="white", label=lab) for _, lab, h in comps]
    if ranged:
        handles += [
            Patch(facecolor="0.75", alpha=0.35, edgecolor="0.3", label="admissible range (no pairs)"),
            Line2D(
                [], [], marker="_", ms=12, mew=2, color="k", ls="none", label=r"chosen closure $\sigma_{1,cap}$ = 0"
            ),
        ]
    ax.legend(handles=handles)
    return ax


#: one colour per test of the curves, markers for a printed page in grey
CURVE_COLOURS = [OKABE_ITO[k] for k in ("blue", "vermillion", "green", "orange", "sky", "purple", "black", "grey")]
CURVE_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")


def _curves_in_order(result):
    """(index in the tests, Curve) of the tests whose failure came from a curve, saturated first, by sigma3."""
    t = result.states
    rows = [(i, result.curves[str(tid)]) for i, tid in enumerate(t.test_id) if str(tid) in result.curves]
    return sorted(rows, key=lambda ic: (t.condition[ic[0]] != "saturated", t.sigma3[ic[0]]))


def _curve_label(result, i: int) -> str:
    t = result.states
    state = "sat." if t.condition[i] == "saturated" else "unsat."
    return rf"{literal(t.test_id[i])} ({state}, $\sigma_3$ = {t.sigma3[i]:.4g} kPa)"


def plot_q_axial_strain(ax, result):
    """Deviator q against axial strain ε1 of every curve, its picked peak marked.

    After Prunier et al. 2024, Fig. 10 and 15: saturated tests dashed, unsaturated solid.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    for k, (i, c) in enumerate(_curves_in_order(result)):
        colour, marker = CURVE_COLOURS[k % len(CURVE_COLOURS)], CURVE_MARKERS[k % len(CURVE_MARKERS)]
        ls = "--" if result.states.condition[i] == "saturated" else "-"
        ax.plot(c.axial_strain * 100, c.q, ls=ls, color=colour, lw=1.0, label=_curve_label(result, i))
        ax.plot(c.axial_strain[c.peak] * 100, c.q[c.peak], marker, color=colour, mec="k", ms=6, ls="none")
    ax.plot([], [], "o", color="white", mec="k", ls="none", label="peak taken as failure ($q_f$)")
    ax.set_xlim(left=0)
    ax.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax.set_ylabel(r"$q$ [kPa]")
    ax.set_title(r"$q$-$\varepsilon_1$, picked peaks (Fig. 10, 15)")
    ax.legend()
    return ax


def plot_volumetric_strain(ax, result):
    """Volumetric strain εv against axial strain ε1 of every curve, the reading at the picked peak marked.

    Compression positive (the paper plots contraction up); after Prunier et al. 2024, Fig. 10 and 15.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    drawn = False
    for k, (i, c) in enumerate(_curves_in_order(result)):
        if not np.isfinite(c.vol_strain).any():
            continue
        drawn = True
        colour, marker = CURVE_COLOURS[k % len(CURVE_COLOURS)], CURVE_MARKERS[k % len(CURVE_MARKERS)]
        ls = "--" if result.states.condition[i] == "saturated" else "-"
        ok = np.isfinite(c.vol_strain)
        ax.plot(
            c.axial_strain[ok] * 100, c.vol_strain[ok] * 100, ls=ls, color=colour, lw=1.0, label=_curve_label(result, i)
        )
        if np.isfinite(c.vol_strain[c.peak]):
            ax.plot(c.axial_strain[c.peak] * 100, c.vol_strain[c.peak] * 100, marker, color=colour, mec="k", ms=6)
    if not drawn:
        ax.text(0.5, 0.5, "no volumetric strain in the curves", ha="center", va="center", transform=ax.transAxes)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlim(left=0)
    ax.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax.set_ylabel(r"volumetric strain $\varepsilon_v$ [%] (contraction +)")
    ax.set_title(r"$\varepsilon_v$-$\varepsilon_1$ at the peaks (Fig. 10, 15)")
    if drawn:
        ax.legend()
    return ax


def sheet_triaxial(result) -> Sheet:
    """The sheet of ``capred triaxial``: q-p plane, capillary stresses, Mohr circles.

    The groups' circles and tensors when a group's tensor is determined or bounded; the q-ε1 and εv-ε1 curves when it
    has curves (after Prunier et al. 2024, Fig. 10, 15-21).

    Parameters
    ----------
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    return Sheet(
        "Capillary stress tensor at failure (after Prunier et al. 2024, Fig. 10, 15-21)"
        if result.curves
        else "Capillary stress tensor at failure (after Prunier et al. 2024, Fig. 16-21)",
        [
            Panel(
                "qp_plane",
                lambda ax: plot_qp_plane(ax, result),
                "Failure points in the q-p plane, the effective envelope, the image points of each bound and the "
                "EDTP stress paths; groups' apparent envelopes dotted (after Prunier et al. 2024, Fig. 16-17).",
            ),
            Panel(
                "capillary_stresses",
                lambda ax: plot_capillary_ranges(ax, result),
                "σ1,cap, σ3,cap and p_cap of each bound for every unsaturated test (after Prunier et al. 2024, "
                "Fig. 18).",
            ),
            Panel(
                "mohr_circles",
                lambda ax: plot_mohr_circles(ax, result),
                "Mohr circles at failure: total (unsaturated), effective under the lower bound, and saturated "
                "(after Prunier et al. 2024, Fig. 19-20).",
            ),
        ]
        + (
            [
                Panel(
                    "group_circles",
                    lambda ax: plot_group_circles(ax, result),
                    "Groups sharing one tensor (Prunier et al. 2024, Appendix 1): unsaturated Mohr circles, fictive "
                    "circles σ'' with the paired saturated radius (eq. 44) and the lines of cohesion C and C'' (eq. 48; "
                    "after Fig. 21).",
                ),
                Panel(
                    "group_tensors",
                    lambda ax: plot_group_tensors(ax, result),
                    "σ1,cap, σ2,cap, σ3,cap of each group by eq. 48 or 50, with standard errors from the regression; "
                    "without paired saturated tests the admissible range of eq. 37 between the closures σ1,cap = 0 "
                    "(marked, the chosen one) and spherical (Prunier et al. 2024, Appendix 1; the paper has no "
                    "such figure).",
                ),
            ]
            if any(g.determined or g.admissible is not None for g in result.groups)
            else []
        )
        + (
            [
                Panel(
                    "q_axial_strain",
                    lambda ax: plot_q_axial_strain(ax, result),
                    "Deviator against axial strain of the raw curves, the peak taken as failure marked (after "
                    "Prunier et al. 2024, Fig. 10 for saturated and Fig. 15 for unsaturated tests).",
                ),
                Panel(
                    "vol_strain",
                    lambda ax: plot_volumetric_strain(ax, result),
                    "Volumetric against axial strain of the raw curves, the reading at the peak marked (after "
                    "Prunier et al. 2024, Fig. 10 and 15).",
                ),
            ]
            if result.curves
            else []
        )
        + reference_panels(result),  # curves given for tests whose q_f the table gives: drawn for reference
        2,
        spans={"qp_plane": 2},
    )
