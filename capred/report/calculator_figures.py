"""Figure sheet of `capred skempton-b`: B against S_r, and the parameter studies of Morvan et al. (2016),
Fig. 2, 3 and 5. Each computed case is drawn on the curve of its own parameters."""

from __future__ import annotations

import numpy as np

from ..physics import calculators as calc
from .sheets import Panel, Sheet
from .style import LABEL, LINESTYLES, OKABE_ITO, SERIES_COLOURS

_COLORS = [OKABE_ITO[k] for k in ("black", "blue", "vermillion", "green", "orange", "purple", "sky")]


def _line(k: int) -> dict:
    """Colour and line style of the k-th curve of a parameter study (no markers: the curves are continuous)."""
    return dict(color=SERIES_COLOURS[k % len(SERIES_COLOURS)], ls=LINESTYLES[k % len(LINESTYLES)], lw=1.2)


def _axes(ax, title):
    ax.set_xlabel(LABEL["S_r"])
    ax.set_ylabel(LABEL["B"])
    ax.set_ylim(0, 1.02)
    ax.set_title(title)
    ax.legend()
    return ax


def _bounding_curve(S, params, s_e, bc_lambda, bounding):
    """B(S_r) of the bounding-surface reconstruction along one drying path (Morvan et al. 2016, section 4)."""
    from ..physics import skempton_elastoplastic as sep

    kappa, e0, p0, u0, pa0 = params
    comp = sep.BoundingSurfaceCompliance(kappa, bounding["lambda0"], bounding["a_ini"], bounding["interpolation_h"])
    return sep.skempton_b_incremental(
        S,
        compliance=comp,
        kappa_elastic=kappa,
        p0=p0,
        u0=u0,
        e0=e0,
        pa0=pa0,
        air_entry=s_e,
        bc_lambda=bc_lambda,
        air_pressure=bounding["air_pressure"],
        S_R_step=2e-3,
    )


def plot_cases(ax, cases, s_e=None, bc_lambda=None, bounding=None):
    """B(S_r) of every distinct parameter set among the cases, with the cases of that set on it."""
    S = np.linspace(0.5, 1.0, 400)
    for k, (params, pts) in enumerate(cases.items()):
        kappa, e0, p0, u0, pa0 = params
        color = _COLORS[k % len(_COLORS)]
        if bounding is not None:
            ax.plot(
                S,
                _bounding_curve(S, params, s_e, bc_lambda, bounding),
                "-.",
                color=color,
                lw=1.2,
                label=rf"  bounding-surface reconstruction ($A_{{ini}}$ = {bounding['a_ini'] / 1e3:g} kPa, "
                f"{bounding['air_pressure']} $P_a$)",
            )
        label = (
            rf"$\kappa$ = {kappa:g}, $e_0$ = {e0:g}, $p'_0$ = {(p0 - u0) / 1e3:g} kPa, "
            rf"$P_{{a0}}$ = {pa0 / 1e3:g} kPa"
        )
        ax.plot(S, calc.skempton_b(S, p0 - u0, e0, kappa, pa0), "-", color=color, lw=1.2, label=label)
        if s_e is not None:
            ax.plot(
                S,
                calc.skempton_b_suction(S, p0, u0, e0, kappa, pa0, s_e, bc_lambda),
                "--",
                color=color,
                lw=1.0,
                label=rf"  with suction ($s_e$ = {s_e / 1e3:g} kPa, $\lambda$ = {bc_lambda:g})",
            )
        ax.plot(pts[0], pts[1], "o", color=color, ms=5, ls="none", label="  computed cases")
    return _axes(ax, "Computed cases on their own curves")


def sheet_skempton(cases: dict, kappa, e0, p0, u0, pa0, s_e=None, bc_lambda=None, bounding=None) -> Sheet:
    """``cases``: (kappa, e0, p0, u0, pa0) -> (S_r values, B values); the studies use the options' parameters."""
    S = np.linspace(0.5, 1.0, 400)
    pe = p0 - u0
    lam = bc_lambda if bc_lambda is not None else 0.8

    def kappa_study(ax):
        for j, k in enumerate((0.0006, 0.006, 0.06)):
            ax.plot(S, calc.skempton_b(S, pe, e0, k, pa0), label=rf"$\kappa$ = {k:g}", **_line(j))
        return _axes(ax, r"Effect of $\kappa$ (Morvan et al. 2016, Fig. 2)")

    def e0_study(ax):
        for j, e in enumerate((0.6, 0.8, 1.2)):
            ax.plot(S, calc.skempton_b(S, pe, e, kappa, pa0), label=f"$e_0$ = {e:g}", **_line(j))
        return _axes(ax, r"Effect of $e_0$ (Morvan et al. 2016, Fig. 3)")

    def se_study(ax):
        for j, se in enumerate((5e3, 20e3, 100e3, 1000e3)):
            ax.plot(
                S,
                calc.skempton_b_suction(S, p0, u0, e0, kappa, pa0, se, lam),
                label=f"$s_e$ = {se / 1e3:g} kPa",
                **_line(j),
            )
        return _axes(ax, rf"Effect of $s_e$, $\lambda$ = {lam:g} (Morvan et al. 2016, Fig. 5)")

    return Sheet(
        "Skempton's B against the degree of saturation",
        [
            Panel(
                "cases",
                lambda ax: plot_cases(ax, cases, s_e, bc_lambda, bounding),
                "B(S_r) of eq. 10 for each parameter set of the computed cases, the cases on their own curve.",
            ),
            Panel("kappa", kappa_study, "Effect of the slope κ of the elastic line."),
            Panel("e0", e0_study, "Effect of the initial void ratio."),
            Panel("air_entry", se_study, "With suction equilibrium: effect of the air-entry suction."),
        ],
        2,
    )
