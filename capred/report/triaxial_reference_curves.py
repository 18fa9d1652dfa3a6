"""The raw curves of `capred triaxial-bounds --curves` that were not used for failure, drawn for reference.

Where the tests table gives a test's failure deviator (q_f or sigma1), it wins over the peak of the test's curve
(``TriaxialResult.reference_curves``). These curves are drawn as Prunier et al. (2024) draw theirs (Fig. 10, 15),
with the curve's peak marked and the table's q_f beside it, so that a user sees whether the two agree.
"""

from __future__ import annotations

import numpy as np

from .sheets import Panel
from .style import OKABE_ITO, literal

#: one colour per curve, markers for a printed page in grey
COLOURS = [OKABE_ITO[k] for k in ("blue", "vermillion", "green", "orange", "sky", "purple", "black", "grey")]
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")


def reference_rows(result) -> list[tuple[int, object]]:
    """(index in the tests, Curve) of the tests whose curve was not used for failure, saturated first, by sigma3.

    Parameters
    ----------
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial-bounds`` run.

    Returns
    -------
    list of (int, Curve)
        The tests in the order drawn.
    """
    t = result.states
    refs = getattr(result, "reference_curves", {}) or {}
    rows = [(i, refs[str(tid)]) for i, tid in enumerate(t.test_id) if str(tid) in refs]
    return sorted(rows, key=lambda ic: (t.condition[ic[0]] != "saturated", t.sigma3[ic[0]]))


def _label(result, i: int) -> str:
    t = result.states
    state = "sat." if t.condition[i] == "saturated" else "unsat."
    return rf"{literal(t.test_id[i])} ({state}, $\sigma_3$ = {t.sigma3[i]:.4g} kPa)"


def plot_reference_q(ax, result):
    """Deviator q against axial strain ε1 of the curves not used for failure.

    Each curve's peak (marker) and the table's q_f (a horizontal bar at the peak's strain) compared (after Prunier et
    al. 2024, Fig. 10 and 15).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial-bounds`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.

    References
    ----------
    Prunier, F., et al. (2024), Fig. 10 (saturated) and 15 (unsaturated tests): q-ε1 with the peak as failure.
    """
    t = result.states
    for k, (i, c) in enumerate(reference_rows(result)):
        colour, marker = COLOURS[k % len(COLOURS)], MARKERS[k % len(MARKERS)]
        ls = "--" if t.condition[i] == "saturated" else "-"
        ax.plot(c.axial_strain * 100, c.q, ls=ls, color=colour, lw=1.0, label=_label(result, i))
        ax.plot(c.axial_strain[c.peak] * 100, c.q[c.peak], marker, color=colour, mec="k", ms=6, ls="none")
        ax.plot(c.axial_strain[c.peak] * 100, t.q[i], "_", color="k", ms=14, mew=1.5, ls="none")
    ax.plot([], [], "o", color="white", mec="k", ls="none", label="peak of the curve")
    ax.plot([], [], "_", color="k", ms=14, mew=1.5, ls="none", label="$q_f$ of the table (used)")
    ax.set_xlim(left=0)
    ax.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax.set_ylabel(r"$q$ [kPa]")
    ax.set_title(r"$q$-$\varepsilon_1$ for reference: peak against $q_f$ (Fig. 10, 15)")
    ax.legend()
    return ax


def plot_reference_volumetric(ax, result):
    """Volumetric strain εv against axial strain ε1 of the curves not used for failure.

    Compression positive, the reading at the curve's peak marked (after Prunier et al. 2024, Fig. 10 and 15).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial-bounds`` run.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.

    References
    ----------
    Prunier, F., et al. (2024), Fig. 10 and 15: εv-ε1 of the triaxial tests.
    """
    drawn = False
    for k, (i, c) in enumerate(reference_rows(result)):
        ok = np.isfinite(c.vol_strain)
        if not ok.any():
            continue
        drawn = True
        colour, marker = COLOURS[k % len(COLOURS)], MARKERS[k % len(MARKERS)]
        ls = "--" if result.states.condition[i] == "saturated" else "-"
        ax.plot(c.axial_strain[ok] * 100, c.vol_strain[ok] * 100, ls=ls, color=colour, lw=1.0, label=_label(result, i))
        if ok[c.peak]:
            ax.plot(c.axial_strain[c.peak] * 100, c.vol_strain[c.peak] * 100, marker, color=colour, mec="k", ms=6)
    if not drawn:
        ax.text(0.5, 0.5, "no volumetric strain in the curves", ha="center", va="center", transform=ax.transAxes)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlim(left=0)
    ax.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax.set_ylabel(r"volumetric strain $\varepsilon_v$ [%] (contraction +)")
    ax.set_title(r"$\varepsilon_v$-$\varepsilon_1$ for reference (Fig. 10, 15)")
    if drawn:
        ax.legend()
    return ax


def reference_panels(result) -> list[Panel]:
    """The two panels of the curves not used for failure; none when every curve gave its test's failure.

    Parameters
    ----------
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial-bounds`` run.

    Returns
    -------
    list of Panel
        ``reference_curves`` (q-ε1) and ``reference_vol_strain`` (εv-ε1), or an empty list.
    """
    if not reference_rows(result):
        return []
    return [
        Panel(
            "reference_curves",
            lambda ax: plot_reference_q(ax, result),
            "Deviator against axial strain of the raw curves of tests whose q_f the table gives (not used for "
            "failure: the table's value wins): the curve's peak marked, the table's q_f as a bar at the peak's "
            "strain (after Prunier et al. 2024, Fig. 10 and 15).",
        ),
        Panel(
            "reference_vol_strain",
            lambda ax: plot_reference_volumetric(ax, result),
            "Volumetric against axial strain of the same curves, the reading at the curve's peak marked (after "
            "Prunier et al. 2024, Fig. 10 and 15).",
        ),
    ]
