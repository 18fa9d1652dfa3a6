"""Small closed-form calculators from the source papers: Bernatzik's prism, Skempton's B, Rumpf.

SI in and out (Pa, m, N/m); angles in degrees.

References
----------
[5] W. Bernatzik, "The determination of the capillary rise in sand by means
    of prism pressure tests", Proc. 2nd ICSMFE, Rotterdam (Bernatzik 1948).
[6] M. Morvan, M. Vernay, P. Breul, "Study of the variation of B with Sr"
    (Morvan et al. 2016), eq. (10)-(13).
[7] Prunier et al. (2024), doi:10.1080/19648189.2024.2314099, eq. (19), after Rumpf (1962).
"""
from __future__ import annotations

import numpy as np

from .retention import bc_suction


def prism_capillary_pressure(break_tension, friction_angle_deg):
    """P_kmax = sigma_b (1 - sin rho) / (2 sin rho) [5].

    From the Mohr circle of the prism at break: sin rho = sigma_b / (2 P_kmax + sigma_b).
    Dense sand, rho = 36 deg: P_kmax = 0.35 sigma_b [5].
    """
    s = np.sin(np.radians(friction_angle_deg))
    return np.asarray(break_tension, float) * (1.0 - s) / (2.0 * s)


def capillary_rise(capillary_pressure, gamma_w):
    """h_c = P_kmax / gamma_w [m] [5]."""
    return np.asarray(capillary_pressure, float) / gamma_w


def skempton_b(S_r, p0_eff, e0, kappa, pa0):
    """B = 1 / (1 + p'_0 e_0 (1 - S_r) / (kappa P_a0)) [6, eq. 10].

    p'_0 initial mean effective stress, e_0 void ratio, kappa slope of the
    elastic line in e-ln p, P_a0 absolute initial air pressure (same unit as p'_0).
    Water and grains incompressible, Boyle's law for the air.
    """
    return 1.0 / (1.0 + p0_eff * e0 * (1.0 - np.asarray(S_r, float)) / (kappa * pa0))


def saturation_from_b(B, p0_eff, e0, kappa, pa0):
    """Inverse of eq. (10) of [6]: S_r = 1 - (1/B - 1) kappa P_a0 / (p'_0 e_0)."""
    return 1.0 - (1.0 / np.asarray(B, float) - 1.0) * kappa * pa0 / (p0_eff * e0)


def skempton_b_suction(S_r, p0, ua0, e0, kappa, pa0, s_e, alpha):
    """B with suction equilibrium before the increment [6, section 3].

    Suction from Brooks-Corey, s = s_e S_r^(-1/alpha); initial effective stress
    p'_0 = p0 - u_a0 + s S_r (eq. 13). The undrained increment is small and
    the suction is taken constant during it (du_a = du_w), so eq. (10) applies
    with this stiffer p'_0: B falls as s_e rises.
    """
    S_r = np.asarray(S_r, float)
    p0_eff = p0 - ua0 + bc_suction(S_r, s_e, alpha) * S_r
    return skempton_b(S_r, p0_eff, e0, kappa, pa0)


def rumpf_capillary_pressure(shape_factor, void_ratio, S_r, diameter, surface_tension, contact_angle_deg):
    """p_cap = -(6/phi)(S_r/e)(gamma/d_p) cos(theta) [7, eq. 19] (negative: tension).

    phi particle shape factor, e void ratio, d_p apparent particle diameter [m],
    gamma surface tension [N/m], theta wetting angle.
    """
    return -(6.0 / np.asarray(shape_factor, float)) * (np.asarray(S_r, float) / void_ratio) * (
        surface_tension / np.asarray(diameter, float)) * np.cos(np.radians(contact_angle_deg))
