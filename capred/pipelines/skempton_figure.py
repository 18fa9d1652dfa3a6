"""The curves `capred skempton-b`'s figure sheet draws, computed here so that capred.report only draws them.

B against the degree of saturation S_r (Morvan et al. 2016): for each parameter set of the computed cases, B of
eq. 10, with suction equilibrium (section 3) and of the bounding-surface reconstruction (section 4); and the
parameter studies of their Fig. 2 (κ), Fig. 3 (e0) and Fig. 5 (air-entry suction). Computed when a figure is
asked for (``CalcResult.figure_curves``), never by a run without figures.

References
----------
.. [1] Morvan, M., Vernay, M., Breul, P. (2016). Study of the variation of B with Sr. E-UNSAT 2016, E3S Web of
   Conferences; eq. 10, sections 3-4, Fig. 2, 3, 5.
"""

from __future__ import annotations

import numpy as np

from ..physics import calculators as calc

#: the degrees of saturation every curve of the sheet is drawn at [-]
S_GRID = (0.5, 1.0, 400)
#: the values of each parameter study: κ (Fig. 2), e0 (Fig. 3), s_e [Pa] (Fig. 5)
STUDIES = {"kappa": (0.0006, 0.006, 0.06), "e0": (0.6, 0.8, 1.2), "s_e": (5e3, 20e3, 100e3, 1000e3)}
#: Brooks-Corey λ of the s_e study when the run gives none (Morvan et al. 2016, Fig. 5)
STUDY_LAMBDA = 0.8


def bounding_curve(S, params, s_e, bc_lambda, bounding):
    """B(S_r) of the bounding-surface reconstruction along one drying path (Morvan et al. 2016, section 4).

    Parameters
    ----------
    S : ndarray
        Degrees of saturation [-], decreasing from 1 along the path.
    params : tuple of float
        (κ [-], e0 [-], p0 [Pa], u0 [Pa], pa0 [Pa]).
    s_e : float
        Air-entry suction [Pa].
    bc_lambda : float
        Brooks-Corey index λ [-].
    bounding : dict
        ``lambda0``, ``a_ini`` [Pa], ``interpolation_h``, ``air_pressure``.

    Returns
    -------
    ndarray
        B [-] at ``S``.
    """
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


def figure_curves(figure_data: dict) -> dict:
    """Every curve of the skempton-b sheet, for capred.report.calculator_figures.sheet_skempton.

    Parameters
    ----------
    figure_data : dict
        What the run kept for its figure (``CalcResult.figure_data``):

        - ``cases``: (κ, e0, p0 [Pa], u0 [Pa], pa0 [Pa]) -> (S_r values, B values) of the computed cases (absent
          or None with ``curves``);
        - ``kappa``, ``e0``, ``p0``, ``u0``, ``pa0``: the options' values, for the parameter studies (κ of the
          elastic line [-], e0 [-], p0, u0, pa0 [Pa]);
        - ``s_e``: air-entry suction [Pa] or None: each case's curve with suction equilibrium too;
        - ``bc_lambda``: Brooks-Corey index λ [-] of that curve (and of the s_e study; else 0.8) or None;
        - ``bounding``: ``lambda0``, ``a_ini`` [Pa], ``interpolation_h``, ``air_pressure``, or None: each case's
          bounding-surface curve too;
        - ``curves``, ``curve_names`` (``skempton-b --curve``): ``"S_r"`` and each model's B as the run computed
          them, and their names as the caption gives them.

    Returns
    -------
    dict
        ``S_r`` (the grid), ``cases`` (per parameter set: ``params``, ``B_eq10``, ``B_suction``, ``B_bounding``
        (None where not asked) and the ``points`` (S_r, B) of its cases), ``studies`` (``kappa``, ``e0``, ``s_e``:
        value -> B; ``lambda``), and ``s_e``, ``bc_lambda``, ``bounding``, ``curves``, ``curve_names`` as given.
    """
    d = figure_data
    s_e, bc_lambda, bounding = d.get("s_e"), d.get("bc_lambda"), d.get("bounding")
    k0, e0, p0, u0, pa0 = (d[k] for k in ("kappa", "e0", "p0", "u0", "pa0"))
    S = np.linspace(*S_GRID)
    drawn = []
    for params, points in (d.get("cases") or {}).items():
        k, e, p, u, pa = params
        drawn.append(
            {
                "params": params,
                "B_eq10": calc.skempton_b(S, p - u, e, k, pa),
                "B_suction": None if s_e is None else calc.skempton_b_suction(S, p, u, e, k, pa, s_e, bc_lambda),
                "B_bounding": None if bounding is None else bounding_curve(S, params, s_e, bc_lambda, bounding),
                "points": points,
            }
        )
    lam = bc_lambda if bc_lambda is not None else STUDY_LAMBDA
    studies = {
        "kappa": {k: calc.skempton_b(S, p0 - u0, e0, k, pa0) for k in STUDIES["kappa"]},
        "e0": {e: calc.skempton_b(S, p0 - u0, e, k0, pa0) for e in STUDIES["e0"]},
        "s_e": {se: calc.skempton_b_suction(S, p0, u0, e0, k0, pa0, se, lam) for se in STUDIES["s_e"]},
        "lambda": lam,
    }
    return {
        "S_r": S,
        "cases": drawn,
        "studies": studies,
        "s_e": s_e,
        "bc_lambda": bc_lambda,
        "bounding": bounding,
        "curves": d.get("curves"),
        "curve_names": d.get("curve_names"),
    }
