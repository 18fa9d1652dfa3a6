"""Water retention curves: van Genuchten (1980) and Brooks & Corey (1964).

Suction s >= 0 in any pressure unit consistent with the parameters (capred
passes Pa, alpha in 1/Pa, s_e in Pa). The water quantity y is volumetric
water content theta or degree of saturation S_R; y_s, y_r are its saturated
and residual values (theta_s, theta_r or S_s, S_res).

References
----------
[3] M. Th. van Genuchten, "A closed-form equation for predicting the
    hydraulic conductivity of unsaturated soils", SSSA J. 44 (1980) 892-898.
[4] R. H. Brooks, A. T. Corey, "Hydraulic properties of porous media",
    Hydrology Paper 3, Colorado State University (1964); used with air-entry
    suction s_e and index alpha by Morvan et al. (2016, section 3).
"""
from __future__ import annotations

import numpy as np


def vg_effective_saturation(s, alpha, n, m=None):
    """S_e = [1 + (alpha s)^n]^(-m), m = 1 - 1/n unless given [3]."""
    m = 1.0 - 1.0 / n if m is None else m
    return (1.0 + (alpha * np.maximum(np.asarray(s, float), 0.0)) ** n) ** (-m)


def vg_water(s, y_r, y_s, alpha, n, m=None):
    """y(s) = y_r + (y_s - y_r) S_e(s) (van Genuchten [3])."""
    return y_r + (y_s - y_r) * vg_effective_saturation(s, alpha, n, m)


def bc_effective_saturation(s, s_e, lam):
    """S_e = (s_e/s)^lambda for s > s_e, else 1 (Brooks & Corey [4])."""
    s = np.asarray(s, float)
    with np.errstate(divide="ignore"):
        return np.where(s > s_e, (s_e / np.where(s > 0, s, 1.0)) ** lam, 1.0)


def bc_water(s, y_r, y_s, s_e, lam):
    """y(s) = y_r + (y_s - y_r) S_e(s) (Brooks & Corey [4])."""
    return y_r + (y_s - y_r) * bc_effective_saturation(s, s_e, lam)


def bc_suction(S_r, s_e, alpha):
    """Suction from Brooks-Corey as Morvan et al. (2016) use it: S_r = (s_e/s)^alpha -> s = s_e S_r^(-1/alpha).

    Full saturation (S_r = 1) gives s = s_e.
    """
    return s_e * np.asarray(S_r, float) ** (-1.0 / alpha)


def kosugi_effective_saturation(s, s_m, sigma):
    """S_e = Q(ln(s/s_m)/sigma), Q the complementary standard normal distribution (Kosugi 1996).

    Parameters
    ----------
    s : suction (any unit, the same as s_m), >= 0
    s_m : median suction of the pore-size distribution (> 0)
    sigma : standard deviation of ln(pore size) [-], > 0
    """
    from scipy.special import erfc

    s = np.asarray(s, float)
    with np.errstate(divide="ignore"):
        z = np.log(np.where(s > 0, s, 0.0) / s_m) / sigma
    return 0.5 * erfc(z / np.sqrt(2.0))


def fx_correction(s, s_r, s_max=1e9):
    """C(s) = 1 - ln(1 + s/s_r)/ln(1 + s_max/s_r) of Fredlund & Xing (1994); s_max = 10^6 kPa (1e9 Pa):
    the water content reaches zero at that suction."""
    s = np.asarray(s, float)
    return 1.0 - np.log1p(np.maximum(s, 0.0) / s_r) / np.log1p(s_max / s_r)


def fx_shape(s, a, n, m):
    """[ln(e + (s/a)^n)]^-m of Fredlund & Xing (1994) (1 at s = 0)."""
    s = np.maximum(np.asarray(s, float), 0.0)
    return np.log(np.e + (s / a) ** n) ** (-m)


def durner_effective_saturation(s, w1, alpha1, n1, alpha2, n2):
    """S_e = w1 S_e1 + (1 - w1) S_e2, two van Genuchten curves with m_i = 1 - 1/n_i (Durner 1994)."""
    return w1 * vg_effective_saturation(s, alpha1, n1) + (1.0 - w1) * vg_effective_saturation(s, alpha2, n2)
