"""Figure sheets of `capred shear`: per material, the report, the capillary stress and the raw curves.

Every panel draws from the run's records (``result.tests``, ``result.fits``,
``result.predictions[model]``, ``result.back``, ``result.model_curves``,
``result.curves``) and recomputes no physics. A model keeps its registry
colour and marker everywhere; a normal stress its line style and marker
(``style.level_style``); a test's curve its own colour, line style and marker
(``style.series_style``). Panels of more than ``style.MAX_MARKERS`` tests draw
a stated random sample of markers; fits and metrics in the legends use every
test.
"""

from __future__ import annotations

import numpy as np

from ..physics.effective_stress_models import MODEL_LABELS, REGISTRY
from .sheets import Panel, Sheet
from .style import (
    LABEL,
    MAX_MARKERS,
    OKABE_ITO,
    THIN_SEED,
    level_style,
    literal,
    note,
    pendular_band,
    series_style,
    symbol,
    tex,
    thin,
    untitled,
)
from .style import style as _style

KPA = 1e-3
#: normal-stress levels drawn as their own series (model curves and measured markers); the others are grey
MAX_LEVELS = 5
#: error bars are drawn for at most this many tests per series (more cannot be told apart and cost a segment
#: each); above, markers only, and the caption says so
MAX_ERRORBARS = 300
#: raw curves drawn per panel (a legend of more cannot be read); above it, a stated random sample of them
MAX_CURVES = 16
#: points of each model curve along the retention relation (``result.model_curves``); about half lie within
#: the measured suctions, the part drawn
CURVE_POINTS = 240
#: what the error bars of the report sheet are (their legend entry)
PI_BARS = "bars: 95 %\nprediction interval"  # two lines: the legend stays narrow
#: what the error bars of the capillary sheet are (their legend entry)
SE_BARS = "bars: ± 1\nstandard error"


def _bars_key(ax, text: str) -> None:
    """A legend entry saying what the panel's error bars are: a vertical bar with caps, and ``text``."""
    ax.plot([], [], ls="none", marker="$\u2336$", color="k", ms=6, label=text)


def _label(model: str) -> str:
    return tex(MODEL_LABELS[model])


def _wet(result, material):
    t = result.tests
    return (t["material"] == material) & (t["condition"] == "wet")


def plot_dry_envelope(ax, result, material):
    """Dry tests, the fitted line τ = c + σ_N tan φ and its confidence band of the mean.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    fit = result.fits[material].line
    dry = (t["material"] == material) & (t["condition"] == "dry")
    x = t["sigma_N"][dry]
    xs = np.linspace(0.0, max(x.max(initial=0.0), 1e-9) * 1.1, 100)
    lo, hi = fit.mean_band(xs)
    colour = OKABE_ITO["blue"]
    ax.fill_between(
        xs * KPA, lo * KPA, hi * KPA, color=colour, alpha=0.2, lw=0, label=f"{fit.confidence:.0%} confidence band"
    )
    phi = np.degrees(np.arctan(fit.slope))
    ax.plot(
        xs * KPA,
        fit.predict(xs) * KPA,
        color=colour,
        ls="-",
        label=rf"fit: $c$ = {fit.intercept * KPA:.4g} kPa, $\phi$ = {phi:.2f}°",
    )
    keep, shown = thin(np.flatnonzero(dry))
    ax.plot(
        t["sigma_N"][keep] * KPA,
        t["tau_max"][keep] * KPA,
        ls="none",
        marker="o",
        color="k",
        ms=3.5,
        label=f"dry tests ($n$ = {fit.n})",
    )
    note(ax, shown)
    ax.set_xlabel(LABEL["sigma_N"])
    ax.set_ylabel(LABEL["tau_max"])
    ax.set_title("Dry envelope")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left")
    return ax


def _band(p, keep, pred):
    lo_pi, hi_pi = p.tau_prediction_interval_kPa
    return np.abs(np.vstack([pred - lo_pi[keep], hi_pi[keep] - pred]))


def _points(ax, x, y, yerr, **kw):
    """Markers with error bars, or markers alone above MAX_ERRORBARS points."""
    kw = {**kw, "ls": "none"}
    if np.size(x) <= MAX_ERRORBARS:
        return ax.errorbar(x, y, yerr=yerr, **kw)
    for k in ("elinewidth", "capsize"):
        kw.pop(k, None)
    return ax.plot(x, y, **kw)


def plot_measured_vs_predicted(ax, result, material):
    """Predicted against measured τ of the wet tests, each model with its 95 % prediction interval, and 1:1.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    keep, shown = thin(np.flatnonzero(_wet(result, material)))
    meas = t["tau_max"][keep] * KPA
    hi = float(np.nanmax(meas, initial=0.0))
    for m in result.models:
        p = result.predictions[m]
        pred = p.tau_kPa[keep]
        hi = max(hi, float(np.nanmax(pred, initial=0.0)))
        _points(
            ax,
            meas,
            pred,
            _band(p, keep, pred),
            ms=3.5,
            alpha=0.85,
            elinewidth=0.6,
            capsize=1.2,
            label=_label(m),
            **_style(m),
        )
    hi = hi * 1.05 or 1.0
    ax.plot([0, hi], [0, hi], color="k", ls="--", lw=0.8, label="1:1")
    if result.models and keep.size <= MAX_ERRORBARS:
        _bars_key(ax, PI_BARS)
    note(ax, shown)
    ax.set_xlim(0, hi)
    ax.set_ylim(0, hi)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("measured " + LABEL["tau_max"])
    ax.set_ylabel("predicted " + LABEL["tau_pred"])
    ax.set_title("Measured and predicted strength")
    ax.legend(loc="upper left")
    return ax


def _levels(sigma_N):
    """The normal-stress levels of the wet tests (rounded to 1e-6 Pa) with their test counts.

    Most tests first, at most MAX_LEVELS of them, in increasing order.
    """
    levels, counts = np.unique(np.round(sigma_N, 6), return_counts=True)
    top = np.sort(levels[np.argsort(-counts, kind="stable")[:MAX_LEVELS]])
    return top, levels.size


def plot_strength_vs_saturation(ax, result, material):
    """Measured τ against S_R at each normal stress, with each model's strength.

    Each model's strength along the water-retention relation (one line style per normal stress) or, without a relation,
    each model's prediction per test.

    Colour and marker say which model, line style and marker of the black measured points which normal
    stress; the legend lists both.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    from matplotlib.lines import Line2D

    t = result.tests
    wet = _wet(result, material)
    levels, n_levels = _levels(t["sigma_N"][wet])
    relation = result.retention_relation(material)
    handles = []
    curves_drawn = set()
    if relation is not None:  # model curves along the water-retention relation, one line style per level
        inside = _measured_span(result, material, relation)
        for k, level in enumerate(levels):
            S, taus = result.model_curves(material, float(level), CURVE_POINTS)
            for m, tau in taus.items():
                tau = np.where(inside(S), tau, np.nan)
                ax.plot(S, tau * KPA, color=_style(m)["color"], ls=level_style(k)["ls"], lw=1.0, alpha=0.9)
                curves_drawn.add(m)
    per_test = [m for m in result.models if m not in curves_drawn]
    keep, shown = thin(np.flatnonzero(wet))
    for m in per_test:  # no curve: markers per test with the prediction interval
        p = result.predictions[m]
        pred = p.tau_kPa[keep]
        _points(
            ax,
            t["S_R"][keep],
            pred,
            _band(p, keep, pred),
            ms=3.5,
            alpha=0.6,
            elinewidth=0.6,
            markerfacecolor="none",
            **_style(m),
        )
    for m in result.models:
        st = _style(m)
        handles.append(
            Line2D(
                [],
                [],
                color=st["color"],
                marker=st.get("marker", "o"),
                ms=3.5,
                ls="-" if m in curves_drawn else "none",
                mfc=st["color"] if m in curves_drawn else "none",
                label=_label(m),
            )
        )
    sig = np.round(t["sigma_N"][keep], 6)
    for k, level in enumerate(levels):
        sel = keep[sig == level]
        ls = level_style(k)
        ax.plot(t["S_R"][sel], t["tau_max"][sel] * KPA, ls="none", marker=ls["marker"], color="k", ms=3.5)
        handles.append(
            Line2D(
                [],
                [],
                color="k",
                marker=ls["marker"],
                ms=3.5,
                ls=ls["ls"] if curves_drawn else "none",
                label=rf"$\sigma_N$ = {level * KPA:.3g} kPa",
            )
        )
    other = keep[~np.isin(sig, levels)]
    if other.size:
        ax.plot(t["S_R"][other], t["tau_max"][other] * KPA, ls="none", marker=".", color="0.6", ms=3)
        handles.append(
            Line2D([], [], color="0.6", marker=".", ls="none", label=rf"{n_levels - levels.size} other $\sigma_N$")
        )
    if per_test and keep.size <= MAX_ERRORBARS:
        handles.append(Line2D([], [], ls="none", marker="$\u2336$", color="k", ms=6, label=PI_BARS))
    handles.append(pendular_band(ax, result.options.pendular_limit))
    note(ax, shown)
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["tau_max"])
    ax.set_title("Strength against saturation")
    ax.legend(handles=handles, loc="upper right")
    return ax


def _measured_span(result, material, relation):
    """A test ``inside(S)``: S_R within what the relation gives over the material's measured suctions.

    Model curves are drawn there only. Beyond the measured suctions a fitted relation runs into its
    plateaus: near its residual S_R (e.g. 0.0197 for the sample's steel) the suction, and with it χ Δu,
    grows by orders of magnitude while S_R hardly moves, so a model's strength rose almost vertically at
    S_R ≈ 0.015-0.02: the "jump" of earlier versions (issue 29), an extrapolation no test supports.
    """
    t = result.tests
    s = t["suction"][_wet(result, material)]
    s = s[np.isfinite(s) & (s > 0)]
    if not s.size:
        return lambda S: np.ones(np.shape(S), bool)
    lo, hi = sorted(float(v) for v in relation.S_R(np.array([s.max(), s.min()])))
    pad = 1e-9 + 1e-6 * (hi - lo)
    return lambda S: (S >= lo - pad) & (S <= hi + pad)


def plot_residuals(ax, result, material):
    """Residual (predicted − measured) against S_R for each model.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    keep, shown = thin(np.flatnonzero(_wet(result, material)))
    for m in result.models:
        ax.plot(
            t["S_R"][keep],
            result.predictions[m].residual_kPa[keep],
            ms=3.5,
            alpha=0.85,
            label=_label(m),
            **{**_style(m), "ls": "none"},
        )
    ax.axhline(0.0, color="k", lw=0.8)
    note(ax, shown)
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["residual"])
    ax.set_title("Residuals")
    ax.legend(loc="lower left")
    return ax


def _strength_caption(result, material) -> str:
    relation = result.retention_relation(material)
    if relation is None:
        return (
            "Measured strength and each model's prediction per test against S_R, as markers: no "
            "water-retention relation is available to draw model curves."
        )
    return (
        "Measured strength against S_R (black markers, one marker per normal stress) and each model's "
        "strength (its colour) at each normal stress (the line style of that stress) along the water-retention "
        f"relation: {relation.source}, over the measured suctions. Markers without lines: models predicted per "
        "test, with the 95 % prediction interval of a new test. Shaded: the pendular regime."
    )


def _sample_caption(result, material, condition: str) -> str:
    """The note of a panel of the material's ``condition`` tests (dry or wet) drawn as a random sample."""
    t = result.tests
    n = int(np.sum((t["material"] == material) & (t["condition"] == condition)))
    text = (
        f" Markers: a random sample of {MAX_MARKERS:,} of the {n:,} {condition} tests (seed {THIN_SEED}); fits "
        "and metrics use every test."
        if n > MAX_MARKERS
        else ""
    )
    return text + (f" No error bars above {MAX_ERRORBARS} tests." if n > MAX_ERRORBARS else "")


def sheet_shear_report(result, material) -> Sheet:
    """The report sheet of one material: dry envelope, measured vs predicted, strength vs S_R, residuals.

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    best = result.best_model.get(material)
    more = _sample_caption(result, material, "wet")
    panels = [
        Panel(
            "dry_envelope",
            lambda ax: plot_dry_envelope(ax, result, material),
            "Dry tests and the fitted envelope with its 95 % confidence band."
            + _sample_caption(result, material, "dry"),
        )
    ]
    if _wet(result, material).any():
        panels += [
            Panel(
                "measured_vs_predicted",
                lambda ax: plot_measured_vs_predicted(ax, result, material),
                "Wet tests: each model's prediction, with the 95 % prediction interval of a new test, "
                "against the measured strength." + more,
            ),
            Panel(
                "strength_vs_saturation",
                lambda ax: plot_strength_vs_saturation(ax, result, material),
                _strength_caption(result, material) + more,
            ),
            Panel(
                "residuals",
                lambda ax: plot_residuals(ax, result, material),
                "Residual (predicted − measured) against S_R." + more,
            ),
        ]
    title = f"Direct shear, {material}" + (f": best model {MODEL_LABELS[best]}" if best else "")
    return Sheet(title, panels, 2)


def plot_capillary_stress(ax, result, material, x: str):
    """Back-analysed capillary stress of the wet tests against S_R or suction.

    Error bars: standard uncertainty; with each model's predicted capillary stress per test.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.
    x : {"S_R", "suction"}
        The abscissa: degree of saturation [-] or suction (drawn in kPa).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    keep, shown = thin(np.flatnonzero(_wet(result, material)))
    xs = t[x][keep] * (1.0 if x == "S_R" else KPA)
    for m in result.models:
        ax.plot(
            xs,
            result.predictions[m].sigma_cap_kPa[keep],
            ms=3.5,
            alpha=0.75,
            markerfacecolor="none",
            label=_label(m),
            **{**_style(m), "ls": "none"},
        )
    back = result.back
    _points(
        ax,
        xs,
        back.sigma_cap_kPa[keep],
        back.sigma_cap_se_kPa[keep],
        marker="o",
        color="k",
        ms=3.5,
        capsize=1.5,
        elinewidth=0.6,
        label="back-analysed",
    )
    if keep.size <= MAX_ERRORBARS:
        _bars_key(ax, SE_BARS)
    if x == "S_R":
        pendular_band(ax, result.options.pendular_limit)
    ax.axhline(0.0, color="k", lw=0.5)
    note(ax, shown)
    ax.set_xlabel(LABEL[x])
    ax.set_ylabel(LABEL["sigma_cap"])
    ax.set_title("Against saturation" if x == "S_R" else "Against suction")
    return ax


def plot_chi_back(ax, result, material):
    """χ_back = σ_cap/Δu of the wet tests against S_R, with each model's χ(S_R).

    Every model of the run that has one: Bishop's S_R, Own 1's χ1, a fitted S_e^κ ...

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    keep, shown = thin(np.flatnonzero(_wet(result, material) & (t["suction"] > 0)))
    s = np.linspace(0.0, 1.0, 201)
    params = result.options.model_params
    for m in result.models:
        entry = REGISTRY[m]
        if entry.chi_of_saturation is None:
            continue
        law = result.laws.get(m, {}).get(material)
        chi = entry.chi_of_saturation(s, params, law.values if law is not None else None)
        if np.isfinite(chi).any():
            extra = "".join(f", {symbol(k)} = {law.values[k]:.3g}" for k in entry.fitted) if law is not None else ""
            st = _style(m)
            ax.plot(s, chi, color=st["color"], ls=st.get("ls", "-"), lw=1.2, label=_label(m) + extra)
    back = result.back
    _points(
        ax,
        t["S_R"][keep],
        back.chi_back[keep],
        back.chi_back_se[keep],
        marker="o",
        color="k",
        ms=3.5,
        capsize=1.5,
        elinewidth=0.6,
        label=r"$\chi$ back-analysed",
    )
    if keep.size <= MAX_ERRORBARS:
        _bars_key(ax, SE_BARS)
    pendular_band(ax, result.options.pendular_limit)
    note(ax, shown)
    ax.set_xlabel(LABEL["S_R"])
    ax.set_ylabel(LABEL["chi"])
    ax.set_title(r"Effective-stress parameter $\chi$")
    return ax


def sheet_capillary_stress(result, material) -> Sheet:
    """What capillary stress each wet test carried and which χ law explains it.

    Three panels, drawn on request (``figures="all"``).

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    more = _sample_caption(result, material, "wet")
    return Sheet(
        f"Back-analysed capillary stress, {material}",
        [
            Panel(
                "sigma_cap_vs_saturation",
                lambda ax: plot_capillary_stress(ax, result, material, "S_R"),
                "σ_cap = (τ_max − c)/tan φ − σ_N of each wet test (error bars: ± 1 standard error) and each "
                "model's prediction, against S_R; shaded: the pendular regime." + more,
            ),
            Panel(
                "sigma_cap_vs_suction",
                lambda ax: plot_capillary_stress(ax, result, material, "suction"),
                "The same against the suction (error bars: ± 1 standard error)." + more,
            ),
            Panel(
                "chi",
                lambda ax: plot_chi_back(ax, result, material),
                "χ_back = σ_cap/Δu (error bars: ± 1 standard error) against S_R with the χ(S_R) of each model of "
                "the run that has one; shaded: the pendular regime." + more,
            ),
        ],
        3,
        panel_size=(4.2, 3.4),
        on_request=True,
    )


def _curve_tests(result, material, condition: str):
    """(row indices of the material's tests of ``condition`` that have a curve, drawn sample of them, note)."""
    t = result.tests
    rows = np.flatnonzero((t["material"] == material) & (t["condition"] == condition))
    have = rows[np.isin(t["test_id"][rows].astype(str), np.array(list(result.curves.curves), dtype=str))]
    keep, shown = thin(have, MAX_CURVES)
    return have, keep, shown.replace("tests", "curves")


def _vertical(result, tid):
    """(horizontal, vertical) displacement [m] of one test's readings with both (raw data of the curves file)."""
    table = result.curves.table
    sel = table.columns["test_id"] == tid
    d = table.columns["displacement"][sel]
    v = table.get("vertical_displacement")[sel]
    ok = np.isfinite(d) & np.isfinite(v)
    order = np.argsort(d[ok], kind="stable")
    return d[ok][order], v[ok][order]


def has_vertical(result) -> bool:
    """True when the raw curves of the run give vertical displacements.

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.

    Returns
    -------
    bool
    """
    table = getattr(result.curves, "table", None)
    return (
        table is not None
        and "vertical_displacement" in table.columns
        and bool(np.isfinite(table.columns["vertical_displacement"]).any())
    )


def plot_curves(ax, result, material, condition: str):
    """The raw shear curves (τ against horizontal displacement) of one material's dry or wet tests.

    Each test in its own colour, line style and marker; the marker sits on the picked peak.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.
    condition : {"dry", "wet"}
        Which tests.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    _, keep, shown = _curve_tests(result, material, condition)
    for k, i in enumerate(keep):
        tid = str(t["test_id"][i])
        d, tau, peak = result.curves.curves[tid]
        st = series_style(k)
        ax.plot(
            d * 1e3,
            tau * KPA,
            color=st["color"],
            ls=st["ls"],
            lw=1.0,
            marker=st["marker"],
            ms=3.5,
            markevery=[int(peak)],
            label=literal(tid),
        )
    note(ax, shown)
    ax.set_xlabel(LABEL["displacement"])
    ax.set_ylabel(LABEL["tau"])
    ax.set_title(f"Shear stress, {condition} tests")
    ax.set_xlim(left=0)
    ax.legend()
    return ax


def plot_vertical_displacement(ax, result, material, condition: str):
    """Vertical against horizontal displacement of one material's dry or wet tests (positive: dilation).

    In the tests' styles of ``plot_curves``; the marker is at the peak of shear stress.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.
    condition : {"dry", "wet"}
        Which tests.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    _, keep, shown = _curve_tests(result, material, condition)
    for k, i in enumerate(keep):
        tid = str(t["test_id"][i])
        d, v = _vertical(result, tid)
        if not d.size:
            continue
        st = series_style(k)
        dc, _, peak = result.curves.curves[tid]
        at = [int(np.argmin(np.abs(d - dc[peak])))]
        ax.plot(
            d * 1e3,
            v * 1e3,
            color=st["color"],
            ls=st["ls"],
            lw=1.0,
            marker=st["marker"],
            ms=3.5,
            markevery=at,
            label="_" + literal(tid),
        )  # the key is the shear-stress panel's
    ax.axhline(0.0, color="k", lw=0.5)
    note(ax, shown)
    ax.set_xlabel(LABEL["displacement"])
    ax.set_ylabel(LABEL["vertical_displacement"])
    ax.set_title(f"Vertical displacement, {condition} tests")
    ax.set_xlim(left=0)
    return ax


def plot_dilatancy(ax, result, material):
    """Dilatancy angle at the peak, ψ = atan(dδ_v/dδ_h), of each test against its normal stress (dry and wet).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    t = result.tests
    psi = t.get("dilatancy_angle")
    mat = t["material"] == material
    for cond, mk, colour in (("dry", "s", OKABE_ITO["black"]), ("wet", "o", OKABE_ITO["blue"])):
        keep, _ = thin(np.flatnonzero(mat & (t["condition"] == cond) & np.isfinite(psi)))
        if keep.size:
            ax.plot(
                t["sigma_N"][keep] * KPA,
                psi[keep],
                ls="none",
                marker=mk,
                color=colour,
                ms=3.5,
                mfc="none" if cond == "dry" else colour,
                label=f"{cond} tests",
            )
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(LABEL["sigma_N"])
    ax.set_ylabel(LABEL["dilatancy_angle"])
    ax.set_title("Dilatancy at the peak")
    ax.legend()
    return ax


def sheet_curves(result, material) -> Sheet:
    """Raw curves of one material, dry and wet tests apart.

    τ-δ and, when vertical displacements are given, δ_v-δ of the same tests in the same styles and the dilatancy angle
    at the peak.

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.
    material : str
        The material drawn.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    vertical = has_vertical(result)
    panels = []
    for cond in ("dry", "wet"):
        have, keep, shown = _curve_tests(result, material, cond)
        if not have.size:
            continue
        sampled = f" {shown[0].upper()}{shown[1:]}." if shown else ""
        panels.append(
            Panel(
                f"curves_{cond}",
                lambda ax, c=cond: plot_curves(ax, result, material, c),
                f"Shear stress against horizontal displacement of the {cond} tests, each test in its own "
                "colour, line style and marker; the marker is on the picked peak." + sampled,
            )
        )
        if vertical:
            panels.append(
                Panel(
                    f"vertical_{cond}",
                    lambda ax, c=cond: plot_vertical_displacement(ax, result, material, c),
                    f"Vertical displacement (positive: dilation) against horizontal displacement of the "
                    f"{cond} tests, in the styles of the shear-stress panel; the marker is at the peak "
                    "of shear stress." + sampled,
                )
            )
    if vertical:
        panels.append(
            Panel(
                "dilatancy",
                lambda ax: plot_dilatancy(ax, result, material),
                "Dilatancy angle at the peak, ψ = atan(dδ_v/dδ_h), of each test against its normal stress.",
            )
        )
    if len(panels) == 1:
        panels[0].draw = untitled(panels[0].draw)
    return Sheet(f"Shear curves, {material}", panels, 2)
