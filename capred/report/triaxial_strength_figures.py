"""Figures and console tables of `capred triaxial`.

Per material, the failure states on the extended envelope and every model's predicted against measured q_f.
"""

from __future__ import annotations

import numpy as np

from ..io import safe_name
from ..physics import effective_stress_models as esm
from .render import row_table
from .sheets import Panel, Sheet
from .style import OKABE_ITO, legend_outside

KPA = 1e3


#: at most this many suction classes are drawn (one colour, one envelope line and one legend entry each)
MAX_SUCTION_CLASSES = 6


def suction_classes(s) -> list[tuple[np.ndarray, float, str]]:
    """The tests grouped by suction for drawing.

    One group per suction when there are at most `MAX_SUCTION_CLASSES` of them (a lab's controlled suctions), else that
    many ranges of equal counts (a lab's measured, scattered suctions), each drawn with the envelope at its median
    suction.

    Parameters
    ----------
    s : numpy.ndarray
        Suction of every test [Pa].

    Returns
    -------
    list of (numpy.ndarray, float, str)
        Per group: the tests in it (boolean mask), the suction its envelope line is drawn at [Pa], its label.
    """
    levels = np.unique(s)
    if levels.size <= MAX_SUCTION_CLASSES:
        return [(s == v, float(v), f"s = {v / KPA:g} kPa") for v in levels]
    edges = np.quantile(s, np.linspace(0.0, 1.0, MAX_SUCTION_CLASSES + 1))
    out = []
    for k in range(MAX_SUCTION_CLASSES):
        last = k == MAX_SUCTION_CLASSES - 1
        on = (s >= edges[k]) & ((s <= edges[k + 1]) if last else (s < edges[k + 1]))
        if on.any():
            lo, hi = float(s[on].min()), float(s[on].max())
            out.append((on, float(np.median(s[on])), f"s = {lo / KPA:.3g}-{hi / KPA:.3g} kPa"))
    return out


def plot_failure_states(ax, result, material: str):
    """q_f against the net cell pressure, by suction (`suction_classes`).

    With the extended envelope at each suction class and at s -> 0.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    result : capred.pipelines.triaxial_strength.TriaxialStrengthResult
    material : str

    Returns
    -------
    matplotlib.axes.Axes
    """
    r = result.materials[material]
    x, s, y = r.fit.x, r.fit.s, r.fit.y
    grid = np.linspace(0.0, float(np.max(x)) * 1.05, 60)
    colours = list(OKABE_ITO.values())[1:]
    for k, (on, level, label) in enumerate(suction_classes(s)):
        c = colours[k % len(colours)]
        ax.plot(x[on] / KPA, y[on] / KPA, "o", color=c, label=label)
        ax.plot(grid / KPA, r.fit.predict(grid, level) / KPA, "-", color=c, lw=0.8)
    lo, hi = r.fit.mean_band(grid, 0.0)
    ax.plot(grid / KPA, r.fit.predict(grid, 0.0) / KPA, "k--", lw=1.0, label="s → 0 (c', φ')")
    ax.fill_between(grid / KPA, lo / KPA, hi / KPA, color="grey", alpha=0.25, lw=0, label="95 % band, s → 0")
    ax.set_xlabel("net cell pressure σ3 − u_a [kPa]")
    ax.set_ylabel("deviator at failure q_f [kPa]")
    legend_outside(ax)
    return ax


def plot_predicted_measured(ax, result, material: str):
    """Every scored model's predicted q_f against the measured one (tests with suction), with the 1:1 line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    result : capred.pipelines.triaxial_strength.TriaxialStrengthResult
    material : str

    Returns
    -------
    matplotlib.axes.Axes
    """
    r = result.materials[material]
    y = r.fit.y
    wet = r.fit.s > 0
    for mod in r.models:
        st = esm.REGISTRY[mod].style
        rmse = r.metrics[mod].si.rmse / KPA
        ax.plot(
            y[wet] / KPA,
            r.predictions[mod][wet] / KPA,
            st.get("marker", "o"),
            color=OKABE_ITO.get(st.get("color", "black"), "black"),
            mfc="none",
            label=f"{esm.REGISTRY[mod].label} (RMSE {rmse:.3g} kPa)",
        )
    top = float(np.nanmax(y)) / KPA * 1.1
    ax.plot([0, top], [0, top], "k-", lw=0.6)
    ax.set_xlabel("measured q_f [kPa]")
    ax.set_ylabel("predicted q_f [kPa]")
    legend_outside(ax)
    return ax


def triaxial_strength_figures(result) -> dict:
    """The report's figure sheets of a ``capred triaxial`` run, one per material.

    Parameters
    ----------
    result : capred.pipelines.triaxial_strength_records.TriaxialStrengthResult
        The run.

    Returns
    -------
    dict of str to Sheet
        ``{"report_<material>": Sheet}``: the failure states with the extended Mohr-Coulomb envelope, and the
        q_f each effective-stress model predicts against the measured one.
    """
    taken: set[str] = set()
    out = {}
    for m in result.materials:
        r = result.materials[m]
        out[f"report_{safe_name(m, taken)}"] = Sheet(
            f"Triaxial failure states of {m}",
            [
                Panel(
                    "envelope",
                    (lambda mm: lambda ax: plot_failure_states(ax, result, mm))(m),
                    "Failure states and the extended Mohr-Coulomb envelope (Fredlund et al. 1978) at each suction; "
                    f"dashed: the envelope at s → 0 ({r.envelope_source}).",
                ),
                Panel(
                    "models",
                    (lambda mm: lambda ax: plot_predicted_measured(ax, result, mm))(m),
                    "q_f predicted by each effective-stress model on that envelope against the measured q_f.",
                ),
            ],
            2,
        )
    return out


def triaxial_strength_tables(result) -> list:
    """The console tables of a ``capred triaxial`` run.

    Parameters
    ----------
    result : capred.pipelines.triaxial_strength_records.TriaxialStrengthResult
        The run.

    Returns
    -------
    list of capred.result.TableSpec
        Per material the extended Mohr-Coulomb fit and its envelope, then the comparison of the models.
    """
    mats = result.material_rows()
    keys = [
        "material",
        "n",
        "c_eff_kPa",
        "c_eff_se_kPa",
        "phi_eff_deg",
        "phi_eff_se_deg",
        "phi_b_deg",
        "phi_b_se_deg",
        "r2",
        "errors",
        "best_model",
    ]
    metrics = result.metric_rows()
    mkeys = [
        "material",
        "model",
        "n",
        "rmse_kPa",
        "bias_kPa",
        "r2",
        "delta_aicc",
        "akaike_weight",
        "p_best",
        "own_rmse_kPa",
        "own_akaike_weight",
    ]
    env = [{"material": r["material"], "envelope": r["envelope"]} for r in mats]
    return [
        row_table("Extended Mohr-Coulomb (Fredlund et al. 1978), per material", mats, keys, "materials.csv"),
        row_table("Effective envelope used by the models and bounds", env, ["material", "envelope"], "materials.csv"),
        row_table(
            "Models on q_f (tests with suction): on the shared envelope, and on each model's own envelope (own_)",
            metrics,
            mkeys,
            "metrics.csv",
        ),
    ]
