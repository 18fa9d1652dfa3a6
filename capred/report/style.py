"""The one look of capred's figures.

Colour-blind-safe colours and markers per model, axis labels with symbols and units, user text drawn literally, and
legends placed where they never cover data.

Colours are the Okabe & Ito (2008) palette; every model keeps its colour and
marker in every figure of every command (``style(name)``: effective-stress
models from their registry entry, retention models from theirs). Curves that
are not models (one per test, one per normal stress) take a line style and a
marker of their own as well as a colour (``series_style``, ``level_style``),
so that 15 curves never repeat a look and a figure printed in grey stays
readable. Every label is mathtext with its unit (``tex`` turns registry text
such as ``S_e^κ`` into mathtext). Panels of large tables draw a stated random
sample of markers (``thin``) so that a figure's cost does not grow with the
number of tests.
"""

from __future__ import annotations

import re

import numpy as np

from ..sampling import MAX_MARKERS, THIN_SEED, sample_rows  # noqa: F401  (re-exported)

OKABE_ITO = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky": "#56B4E9",
    "green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "purple": "#CC79A7",
    "grey": "#7F7F7F",
}
_C = OKABE_ITO

#: curve name -> matplotlib style: one colour and one marker per curve, everywhere (effective-stress
#: models carry their own style in their registry entry)
MODEL_STYLE: dict[str, dict] = {
    # bridges
    "exact": dict(color=_C["black"], marker="o"),
    "israelachvili": dict(color=_C["purple"], marker="d"),
    "toroidal": dict(color=_C["blue"], marker="^"),
    "willett": dict(color=_C["vermillion"], marker="s"),
    # triaxial bounds
    "lower": dict(color=_C["vermillion"], marker="v"),
    "spherical": dict(color=_C["blue"], marker="o"),
    "edtp": dict(color=_C["green"], marker="^"),
    # retention branches (a retention model's style is its registry entry's)
    "drying": dict(color=_C["orange"], marker="o"),
    "wetting": dict(color=_C["blue"], marker="s"),
}

#: axis labels with mathtext symbols and units, by nomenclature name
LABEL = {
    "sigma_N": r"$\sigma_N$ [kPa]",
    "sigma_eff": r"$\sigma'_N$ [kPa]",
    "tau_max": r"$\tau_{max}$ [kPa]",
    "tau_pred": r"$\tau_{pred}$ [kPa]",
    "S_R": r"$S_R$ [–]",
    "suction": r"$\Delta u$ [kPa]",
    "sigma_cap": r"$\sigma_{cap}$ [kPa]",
    "chi": r"$\chi$ [–]",
    "residual": r"$\tau_{pred} - \tau_{max}$ [kPa]",
    "displacement": r"horizontal displacement $\delta$ [mm]",
    "tau": r"$\tau$ [kPa]",
    "p": r"$p$, $p'$ [kPa]",
    "q": r"$q$, $q'$ [kPa]",
    "sigma": r"$\sigma$, $\sigma'$ [kPa]",
    "cap_component": r"capillary stress component [kPa]",
    "sigma_prime": r"$\sigma'$ [kPa]",
    "F_measured": r"measured $F_{cap}$ [mN]",
    "F_predicted": r"predicted $F_{cap}$ [mN]",
    "B": r"$B$ [–]",
    "S_r": r"$S_r$ [–]",
    "theta": r"volumetric water content $\theta$ [–]",
    "vertical_displacement": r"vertical displacement $\delta_v$ [mm]",
    "dilatancy_angle": r"dilatancy angle at the peak $\psi$ [°]",
    "suction_s": r"suction $s$ [kPa]",
    "V13": r"$V_w^{1/3}$ [mm]",
    "D_rupture": r"rupture distance $D_{rupt}$ [mm]",
}

#: colours of series that are not models (tests, groups), in order: Okabe-Ito without yellow and grey,
#: which print too pale on white
SERIES_COLOURS = [OKABE_ITO[k] for k in ("black", "orange", "sky", "green", "blue", "vermillion", "purple")]
#: line styles of series, models and normal-stress levels, in order (solid first): ten dash patterns that
#: differ in what a reader sees, the sequence of dash lengths in one period (dot <= 1.5 pt, dash 3 pt, long
#: dash 7 pt; every gap 2 pt): solid, dots, dashes, long dashes, long-dot, long-dot-dot, long-dash, dash-dot,
#: long-dot-dot-dot, dash-dot-dot. No two share that sequence (``test_figure_output``), so a figure of up
#: to ten curves in one colour never repeats a look.
LINESTYLES = [
    "-",
    (0, (1, 2)),
    (0, (3, 2)),
    (0, (7, 2)),
    (0, (7, 2, 1, 2)),
    (0, (7, 2, 1, 2, 1, 2)),
    (0, (7, 2, 3, 2)),
    (0, (3, 2, 1, 2)),
    (0, (7, 2, 1, 2, 1, 2, 1, 2)),
    (0, (3, 2, 1, 2, 1, 2)),
]
#: the pendular regime (S_R up to the pendular limit) on S_R axes: a shaded band of its own, no line, so it is
#: never taken for a curve; ``pendular_band`` draws it with its legend entry
PENDULAR_STYLE = dict(color=OKABE_ITO["yellow"], alpha=0.35, lw=0, zorder=0)
#: markers of series and of normal-stress levels, in order
MARKERS = ["o", "s", "^", "D", "v", "<", ">", "p", "h", "X", "P", "*"]
#: MAX_MARKERS, THIN_SEED: how many markers a panel draws per series (capred.sampling, shared with the pipelines)

#: a one-column journal figure (89 mm wide)
SINGLE_PANEL_SIZE = (3.5, 2.8)


def literal(text) -> str:
    """User text (a material name, a test id) as drawn.

    '$' is escaped, so no mathtext is read into it; control and bidi characters are shown (capred.text_safety.visible).

    Parameters
    ----------
    text : object
        User text (converted with str).

    Returns
    -------
    str
    """
    from ..text_safety import visible

    return visible(str(text), pictures=False).replace("$", r"\$")


def style(name: str, **over) -> dict:
    """Colour, marker and line style of a model or curve (and any overrides).

    An effective-stress model's come from its entry of
    ``capred.physics.effective_stress_models.REGISTRY``, a retention model's line style from its entry of
    ``capred.fitting.retention_models.MODELS`` (its colour is the branch's), the others' from MODEL_STYLE.
    Colour names of the registries are names of OKABE_ITO.

    Parameters
    ----------
    name : str
        A model's or curve's name.
    **over
        Matplotlib keywords that replace the style's.

    Returns
    -------
    dict
        Matplotlib keywords (color, ls, marker ...).
    """
    from ..fitting.retention_models import MODELS
    from ..physics.effective_stress_models import REGISTRY

    entry = REGISTRY.get(name)
    retention = MODELS.get(name)
    if entry is not None:  # a line style of its own too (by registry order) where the entry names none
        base = {"ls": LINESTYLES[list(REGISTRY).index(name) % len(LINESTYLES)], **entry.style}
    elif retention is not None:
        base = {"color": "black", **retention.style}
    else:
        base = MODEL_STYLE.get(name, dict(color=_C["black"], marker="o"))
    base = {**base, **over}
    if "color" in base:
        base["color"] = _C.get(base["color"], base["color"])
    return base


def series_style(k: int) -> dict:
    """Colour, line style and marker of the k-th of several series that are not models (a test's curve).

    The colour runs through SERIES_COLOURS and the line style changes after each round of colours, so that
    the first ``len(SERIES_COLOURS) * len(LINESTYLES)`` (56) series all differ in colour or line style; the
    marker runs through MARKERS as well.

    Parameters
    ----------
    k : int
        Index of the series, from 0.

    Returns
    -------
    dict
        Matplotlib keywords (color, ls, marker).
    """
    nc = len(SERIES_COLOURS)
    return dict(
        color=SERIES_COLOURS[k % nc], ls=LINESTYLES[(k // nc) % len(LINESTYLES)], marker=MARKERS[k % len(MARKERS)]
    )


def level_style(k: int) -> dict:
    """Line style and marker of the k-th normal-stress level (the colour stays the model's).

    Parameters
    ----------
    k : int
        Index of the normal-stress level, from 0.

    Returns
    -------
    dict
        Matplotlib keywords (ls, marker).
    """
    return dict(ls=LINESTYLES[k % len(LINESTYLES)], marker=MARKERS[k % len(MARKERS)])


_GREEK = {
    "alpha": r"\alpha",
    "beta": r"\beta",
    "gamma": r"\gamma",
    "delta": r"\delta",
    "eta": r"\eta",
    "theta": r"\theta",
    "kappa": r"\kappa",
    "lambda": r"\lambda",
    "lam": r"\lambda",
    "mu": r"\mu",
    "rho": r"\rho",
    "sigma": r"\sigma",
    "tau": r"\tau",
    "phi": r"\phi",
    "chi": r"\chi",
    "psi": r"\psi",
}
_WORD = r"[A-Za-z\u0370-\u03ff]+'*"
_SCRIPT = r"[A-Za-z0-9\u0370-\u03ff,.]+"
_TOKEN = re.compile(rf"({_WORD})(_\{{[^}}]*\}}|_{_SCRIPT})?(\^\([^)]*\)|\^\{{[^}}]*\}}|\^[-+]?{_SCRIPT})?")


def _script(text: str) -> str:
    text = text[1:]
    if text[:1] in "({":
        text = text[1:-1]
    return "{" + text + "}"


def tex(text: str) -> str:
    """Plain text with sub- and superscripts (``S_R``, ``φ_b``, ``S_e^κ``, ``(2π S_R/3)^(2/3)``) as mathtext.

    Only words that carry a ``_`` or ``^`` are set in math (``S_e^κ`` becomes ``$S_{e}^{κ}$``); the rest of
    the text, and any part already between ``$``, is left as it is.

    Parameters
    ----------
    text : str
        Plain text.

    Returns
    -------
    str
    """
    parts = str(text).split("$")
    for j in range(0, len(parts), 2):  # outside existing math only

        def sub(m):
            base, low, high = m.group(1), m.group(2), m.group(3)
            if not low and not high:
                return m.group(0)
            bare = base.rstrip("'")
            base = _GREEK.get(bare, bare) + base[len(bare) :]
            return "$" + base + (("_" + _script(low)) if low else "") + (("^" + _script(high)) if high else "") + "$"

        parts[j] = _TOKEN.sub(sub, parts[j])
        parts[j] = re.sub(r"\)\^\(([^)]*)\)", r")$^{\1}$", parts[j])  # (…)^(2/3)
    return "$".join(parts)


def symbol(name: str) -> str:
    r"""A parameter name (``kappa``, ``s_b``, ``alpha1``) as mathtext (``$\kappa$``, ``$s_{b}$``, ``$\alpha_1$``).

    Parameters
    ----------
    name : str
        A parameter name.

    Returns
    -------
    str
        Mathtext; a name of another form is returned as :func:`literal` text.
    """
    m = re.fullmatch(r"([A-Za-z]+?)(\d*)(?:_(\w+))?", name)
    if not m:
        return literal(name)
    base, digits, low = m.groups()
    base = _GREEK.get(base, base)
    low = digits or low
    return f"${base}" + (f"_{{{low}}}" if low else "") + "$"


def thin(index, limit: int = MAX_MARKERS, seed: int = THIN_SEED):
    """At most ``limit`` of the row indices ``index``, and a note saying so.

    A random sample without replacement, in order; the note is "" when all are kept. Figures of large tables draw this
    sample so that their cost does not grow with the number of tests; statistics in legends and tables use every test.

    Parameters
    ----------
    index : array_like of bool or int
        A boolean mask or row indices.
    limit : int, optional
        Most rows kept (default MAX_MARKERS).
    seed : int, optional
        Seed of the sample (default THIN_SEED).

    Returns
    -------
    tuple
        (kept row indices as a numpy array, note).
    """
    index = np.asarray(index)
    n = int(index.sum()) if index.dtype == bool else index.size
    keep = sample_rows(index, limit, seed)
    return keep, (f"markers: random sample of {limit:,} of {n:,} tests (seed {seed})" if n > limit else "")


def pendular_band(ax, limit: float):
    """Shade the pendular regime, S_R from 0 to ``limit`` [-], with its legend entry (``PENDULAR_STYLE``).

    The chi approximations of Own 1 and Own 2 are derived for that regime (one bridge per contact); the band
    shows where a point or curve leaves it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        An axes whose x axis is S_R [-].
    limit : float
        The pendular limit [-] (``ShearOptions.pendular_limit``).

    Returns
    -------
    matplotlib.patches.Rectangle
        The shaded band (``ax.axvspan``'s artist).
    """
    return ax.axvspan(0.0, limit, label=rf"pendular, $S_R \leq$ {limit:g}", **PENDULAR_STYLE)


def note(ax, text: str) -> None:
    """A small note in the lower right corner of an axes (e.g. which markers a panel shows).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    text : str
        The note ("": nothing drawn).
    """
    if text:
        ax.text(0.99, 0.01, text, transform=ax.transAxes, ha="right", va="bottom", fontsize=6, color="0.3")


def legend_outside(ax, ncol: int = 1, handles=None, labels=None) -> None:
    """Move an axes' legend outside its data area (to the right), so that it never covers a point.

    ``handles`` (and ``labels``, default: the handles' labels): the entries to show, when the legend was not
    built yet; else those of the axes' legend, or its labelled artists.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    ncol : int, optional
        Columns of the legend.
    handles : sequence of matplotlib artists or None, optional
        The entries to show.
    labels : sequence of str or None, optional
        Their labels.
    """
    old = ax.get_legend()
    if handles is not None:
        handles = list(handles)
        labels = list(labels) if labels is not None else [h.get_label() for h in handles]
        if old is not None:
            old.remove()
    elif old is not None:  # keep what the panel put in its legend (also proxy handles)
        handles = list(getattr(old, "legend_handles", None) or old.legendHandles)
        labels = [t.get_text() for t in old.get_texts()]
        artists, own = ax.get_legend_handles_labels()
        if own == labels:  # the axes' own artists (error bars keep their look in the new legend)
            handles = artists
        old.remove()
    else:
        handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(
            handles,
            labels,
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            borderaxespad=0.0,
            fontsize=7,
            frameon=False,
            ncol=ncol,
        )


def untitled(draw):
    """A panel's draw function without its axes title.

    For a sheet of one panel, whose figure title (and the report's caption) already names it, so that no figure carries
    two titles.

    Parameters
    ----------
    draw : callable
        ``draw(ax)``, a panel's draw function.

    Returns
    -------
    callable
        ``draw(ax)`` that clears the axes title after drawing (returns what ``draw`` returns).
    """

    def draw_untitled(ax):
        out = draw(ax)
        ax.set_title("")
        return out

    return draw_untitled
