"""Figure sheet of `capred bridge laws`: each closed-form law's error map against gap and volume."""

from __future__ import annotations

import numpy as np

from .sheets import Panel, Sheet

#: colour scale of the maps: |relative error| from 0.1 % to 100 % (log), 5 % marked on the colour bar
ERROR_RANGE = (1e-3, 1.0)


def error_map(result, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per (D/R, V/R^3) node of the grid: the largest |relative error| of law ``name``.

    Over the contact angles and geometries there (NaN where no point has both forces).

    Parameters
    ----------
    result : LawsResult
        A `bridge laws` result.
    name : str
        A registered law.

    Returns
    -------
    gaps, volumes, worst : numpy.ndarray
        The distinct D/R and V/R^3 [-] and the worst |error| [-] at each (one per pair present).
    """
    e = np.abs(result.errors()[name])
    pairs = {}
    for g, v, x in zip(result.gap.tolist(), result.volume.tolist(), e.tolist()):
        if np.isfinite(x):
            pairs[(g, v)] = max(pairs.get((g, v), 0.0), x)
    if not pairs:
        return np.array([]), np.array([]), np.array([])
    keys = list(pairs)
    return np.array([k[0] for k in keys]), np.array([k[1] for k in keys]), np.array([pairs[k] for k in keys])


def plot_error_map(ax, result, name: str):
    """Squares at the grid's (D/R, V/R^3) coloured by the law's worst |error| there.

    Open circles: within the tolerance at every angle and geometry.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel to draw on.
    result : capred.pipelines.bridge_laws.LawsResult
        A ``capred bridge laws`` run.
    name : str
        A key of ``capred.physics.bridge_laws.LAWS``.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, drawn on.
    """
    from matplotlib.colors import LogNorm

    from ..physics.bridge_laws import LAWS

    g, v, worst = error_map(result, name)
    norm = LogNorm(*ERROR_RANGE)
    if g.size:
        sc = ax.scatter(
            g, v, c=np.clip(worst, *ERROR_RANGE), cmap="viridis", norm=norm, marker="s", s=40, edgecolors="none"
        )
        good = worst <= result.tolerance
        ax.scatter(g[good], v[good], marker="o", s=12, facecolors="none", edgecolors="white", linewidths=0.8)
        bar = ax.figure.colorbar(sc, ax=ax, pad=0.02)
        bar.set_label("largest |F_law/F_exact − 1|")
        bar.ax.axhline(result.tolerance, color="white", lw=1.0)
    ax.set_yscale("log")
    ax.set_xscale("symlog", linthresh=1e-3, linscale=0.5)  # contact (D = 0) and gaps from 0.1 % of R
    ax.set_xlim(-4e-4, 1.6 * max(float(np.max(result.gap)), 1e-3))
    ax.set_xlabel("gap D/R [-]")
    ax.set_ylabel("volume V/R³ [-]")
    ax.set_title(LAWS[name].label)
    return ax


def sheet_laws(result) -> Sheet:
    """One error map per registered law, two per row.

    Parameters
    ----------
    result : capred.pipelines.bridge_laws.LawsResult
        A ``capred bridge laws`` run.

    Returns
    -------
    capred.report.sheets.Sheet
    """
    from ..physics.bridge_laws import LAWS

    tol = f"{result.tolerance:.0%}"
    return Sheet(
        "Closed-form capillary laws against the exact bridge",
        [
            Panel(
                f"error_{name}",
                lambda ax, name=name: plot_error_map(ax, result, name),  # titled: the law's name on the panel
                f"{law.citation} ({law.equation}): the largest relative error of its force against the exact "
                f"Young-Laplace bridge at each gap and volume of the grid, over its contact angles and geometries "
                f"(colour, log scale; white line on the bar and open circles: within {tol}).",
            )
            for name, law in LAWS.items()
        ],
        2,
    )
