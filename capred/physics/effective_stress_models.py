"""Effective-stress and strength models beyond the thesis's four (SI units).

References
----------
[8] S. K. Vanapalli, D. G. Fredlund, D. E. Pufahl, A. W. Clifton, "Model for
    the prediction of shear strength with respect to soil suction", Can.
    Geotech. J. 33 (1996) 379-392.
[9] N. Khalili, M. H. Khabbaz, "A unique relationship for chi for the
    determination of the shear strength of unsaturated soils", Geotechnique
    48 (1998) 681-687.
[10] N. Lu, W. J. Likos, "Suction stress characteristic curve for unsaturated
    soil", J. Geotech. Geoenviron. Eng. 132 (2006) 131-142.
[11] D. G. Fredlund, N. R. Morgenstern, R. A. Widger, "The shear strength of
    unsaturated soils", Can. Geotech. J. 15 (1978) 313-321.
[12] M. Pedrotti, A. Tarantino, "Effective stresses for unsaturated states
    stemming from clay microstructure" (seed 003), eq. [1], [2], [14].
"""
from __future__ import annotations

import numpy as np

from .retention import vg_effective_saturation


def chi_vanapalli(S_R, S_res=0.0, kappa=1.0):
    """chi = Theta^kappa, Theta = (S_R - S_res)/(1 - S_res) clipped to [0, 1] [8].

    Vanapalli et al. write tau = c' + (sigma - u_a) tan phi' + s Theta^kappa tan phi';
    kappa = 1 with the normalised water content is their second form.
    """
    theta = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 0.0, 1.0)
    return theta**kappa


def chi_khalili(suction, air_entry):
    """chi = (s / s_e)^-0.55 above the air-entry suction, 1 below [9]."""
    s = np.asarray(suction, float)
    with np.errstate(divide="ignore"):
        return np.where(s > air_entry, (np.where(s > 0, s, 1.0) / air_entry) ** -0.55, 1.0)


def chi_lu_likos(suction, alpha, n, m=None):
    """chi = S_e(s) of the van Genuchten curve: suction stress -sigma^s = S_e s [10]."""
    return vg_effective_saturation(suction, alpha, n, m)


def fit_tan_phi_b(suction, excess_strength):
    """tan phi_b of tau = c' + sigma_N tan phi' + s tan phi_b [11], least squares through the origin.

    ``excess_strength`` is tau_measured - (c' + sigma_N tan phi') of the wet tests.
    """
    s = np.asarray(suction, float)
    r = np.asarray(excess_strength, float)
    ss = float(s @ s)
    return float(s @ r) / ss if ss > 0 else float("nan")


def pedrotti_tarantino_strength(sigma_N, suction, S_R, c_w, tan_phi_w, c_a, tan_phi_a):
    """tau = S_R tau_W + (1 - S_R) tau_A [12, eq. 14].

    tau_W = c_W + sigma'_W tan phi_W with sigma'_W = (sigma - u_w) S_R [12, eq. 1]
    (sigma - u_w = sigma_N + s when the air is at atmospheric pressure), and
    tau_A = c_A + sigma'_A tan phi_A with sigma'_A = (sigma - u_a)(1 - S_R) [12, eq. 2].
    The W envelope is that of the water-saturated (reconstituted) soil, the A
    envelope that of the dry one.
    """
    S_R = np.asarray(S_R, float)
    sigma_N = np.asarray(sigma_N, float)
    tau_w = c_w + (sigma_N + np.asarray(suction, float)) * S_R * tan_phi_w
    tau_a = c_a + sigma_N * (1.0 - S_R) * tan_phi_a
    return S_R * tau_w + (1.0 - S_R) * tau_a
