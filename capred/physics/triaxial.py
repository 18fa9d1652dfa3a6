"""Triaxial failure states and bounds of the capillary stress tensor (Prunier et al. 2024).

Compression positive; any consistent stress unit (capred passes Pa). sigma1
is the major (axial, in compression) principal stress, sigma3 the minor
(radial). Capillary components are negative (tensile) in the unsaturated state.

References
----------
[2] F. Prunier, D. Branque, J. Duriez, F. Darve, "A method to evaluate the
    capillary stress tensor at failure in unsaturated soils", Eur. J. Environ.
    Civ. Eng. (2024), doi:10.1080/19648189.2024.2314099.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def mean_stress(sigma1, sigma3, sigma2=None):
    """p = (sigma1 + sigma2 + sigma3) / 3; sigma2 = sigma3 for axisymmetric tests."""
    s2 = sigma3 if sigma2 is None else sigma2
    return (np.asarray(sigma1, float) + np.asarray(s2, float) + np.asarray(sigma3, float)) / 3.0


def deviator(sigma1, sigma3):
    """q = sigma1 - sigma3 [2]."""
    return np.asarray(sigma1, float) - np.asarray(sigma3, float)


def lode_angle(sigma1, sigma2, sigma3):
    """Lode angle theta [deg] from cos(3 theta) = sqrt(6) J3 / J2^(3/2) [2, eq. 52-53].

    J2 = tr(s^2), J3 = tr(s^3) of the deviatoric stress s. theta = 0 for
    triaxial compression (sigma2 = sigma3), 60 deg for extension
    (sigma1 = sigma2); NaN for an isotropic state.
    """
    s = np.stack([np.asarray(x, float) for x in (sigma1, sigma2, sigma3)])
    s = s - s.mean(axis=0)
    j2 = np.sum(s**2, axis=0)
    j3 = np.sum(s**3, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        c3 = np.clip(np.sqrt(6.0) * j3 / j2**1.5, -1.0, 1.0)
    return np.degrees(np.arccos(c3) / 3.0)


def lode_ratio(sigma1, sigma2, sigma3):
    """Q = (sigma1 - sigma2)/(sigma1 - sigma3); equal Q <=> equal Lode angle [2, eq. 49, 54]."""
    return (np.asarray(sigma1, float) - sigma2) / (np.asarray(sigma1, float) - sigma3)


def passive_coefficient(phi_deg):
    """K_p = (1 + sin phi)/(1 - sin phi)."""
    s = np.sin(np.radians(phi_deg))
    return (1.0 + s) / (1.0 - s)


def envelope_qp(c, phi_deg):
    """Mohr-Coulomb in the q-p plane for compression: q = M p + k.

    M = 6 sin phi / (3 - sin phi), k = 6 c cos phi / (3 - sin phi).
    """
    s = np.sin(np.radians(phi_deg))
    co = np.cos(np.radians(phi_deg))
    return 6.0 * s / (3.0 - s), 6.0 * c * co / (3.0 - s)


def sigma1_at_failure(sigma3_eff, c, phi_deg):
    """sigma'_1 = K_p sigma'_3 + 2 c' cos phi'/(1 - sin phi') [2, eq. 25]."""
    kp = passive_coefficient(phi_deg)
    return kp * np.asarray(sigma3_eff, float) + 2.0 * c * np.sqrt(kp)


def drained_strength(p0_eff, c, phi_deg):
    """q'_sat: deviator at failure of a drained compression from isotropic p'_0.

    The path keeps sigma'_3 = p'_0 (slope 3 in the q-p plane), so
    q' = (K_p - 1) p'_0 + 2 c' sqrt(K_p) [2, eq. 25].
    """
    return sigma1_at_failure(p0_eff, c, phi_deg) - np.asarray(p0_eff, float)


@dataclass
class Bound:
    """A capillary stress tensor at failure and the effective image point (arrays)."""

    sigma1_cap: np.ndarray
    sigma3_cap: np.ndarray
    p_prime: np.ndarray
    q_prime: np.ndarray

    @property
    def p_cap(self):
        return (self.sigma1_cap + 2.0 * self.sigma3_cap) / 3.0

    @property
    def q_cap(self):
        return self.sigma1_cap - self.sigma3_cap

    @property
    def positive(self):
        """True where a component is > 0, against eq. (18)/(20) of [2] (1e-9 relative slack)."""
        scale = 1e-9 * np.maximum(np.abs(self.p_prime), 1.0)
        return (self.sigma1_cap > scale) | (self.sigma3_cap > scale)


def _from_effective(sigma1, sigma3, s1_eff, s3_eff) -> Bound:
    return Bound(
        sigma1_cap=np.asarray(sigma1, float) - s1_eff,
        sigma3_cap=np.asarray(sigma3, float) - s3_eff,
        p_prime=(s1_eff + 2.0 * s3_eff) / 3.0,
        q_prime=s1_eff - s3_eff,
    )


def spherical_bound(sigma1, sigma3, c, phi_deg) -> Bound:
    """Spherical capillary tensor, the conservative upper bound [2, eq. 15-17].

    q' = q; the image point is the horizontal projection of (p, q) on the
    envelope, p' = (q - k)/M, and sigma_cap = p - p' in every direction.
    """
    q = deviator(sigma1, sigma3)
    M, k = envelope_qp(c, phi_deg)
    p_eff = (q - k) / M
    cap = mean_stress(sigma1, sigma3) - p_eff
    s3_eff = np.asarray(sigma3, float) - cap
    return _from_effective(sigma1, sigma3, s3_eff + q, s3_eff)


def lower_bound(sigma1, sigma3, c, phi_deg) -> Bound:
    """Lower bound: sigma1_cap = 0 [2, eq. 24] and

    sigma3_cap = sigma3 + 2c' cos phi'/(1 + sin phi') - sigma1 (1 - sin phi')/(1 + sin phi')
    [2, eq. 27], i.e. the effective state (sigma1, sigma3 - sigma3_cap) lies on
    the envelope with the smallest q'.
    """
    s = np.sin(np.radians(phi_deg))
    co = np.cos(np.radians(phi_deg))
    s1 = np.asarray(sigma1, float)
    s3_cap = np.asarray(sigma3, float) + 2.0 * c * co / (1.0 + s) - s1 * (1.0 - s) / (1.0 + s)
    return _from_effective(s1, sigma3, s1, np.asarray(sigma3, float) - s3_cap)


def edtp_bound(sigma1, sigma3, p0, s0, c, phi_deg) -> Bound:
    """Upper bound "EDTP": an effective drained triaxial path [2, section 4.2].

    The path starts at p'_0 = p_0 - p0_cap with p0_cap = -s0 (initial suction as
    the bound of the initial capillary pressure) and rises with slope 3 in the
    (p, q) plane (sigma'_3 = p'_0) to the envelope.
    """
    p0_eff = np.asarray(p0, float) + np.asarray(s0, float)
    s1_eff = sigma1_at_failure(p0_eff, c, phi_deg)
    return _from_effective(sigma1, sigma3, s1_eff, p0_eff)


def envelope_from_principal_fit(slope, intercept):
    """c', phi' from a fit sigma'_1 = K_p sigma'_3 + b (eq. 25 of [2]): phi = asin((K_p-1)/(K_p+1)), c = b / (2 sqrt K_p)."""
    phi = np.degrees(np.arcsin((slope - 1.0) / (slope + 1.0)))
    c = intercept / (2.0 * np.sqrt(slope))
    return c, phi


def spherical_group_cap(C_apparent, c_eff, phi_eff_deg):
    """Spherical tensor shared by a group: sigma_cap = -(C - C')/tan phi' [2, eq. 37]."""
    return -(C_apparent - c_eff) / np.tan(np.radians(phi_eff_deg))


def axisymmetric_group_cap(C_apparent, C_fictive, c_eff, phi_eff_deg):
    """Axisymmetric non-spherical tensor shared by a group [2, eq. 48].

    (sigma1_cap + sigma3_cap)/2 = -(C'' - C')/tan phi',
    (sigma1_cap - sigma3_cap)/2 = (C - C'') cos phi'.
    Returns (sigma1_cap, sigma3_cap).
    """
    phi = np.radians(phi_eff_deg)
    mean = -(C_fictive - c_eff) / np.tan(phi)
    half = (C_apparent - C_fictive) * np.cos(phi)
    return mean + half, mean - half


def fictive_cohesion_lower(C_apparent, c_eff, phi_eff_deg):
    """C'' that closes eq. (48) of [2] under the lower-bound hypothesis sigma1_cap = 0.

    From (C'' - C')/tan phi' = (C - C'') cos phi':
    C'' = (C cos phi' + C'/tan phi') / (cos phi' + 1/tan phi').
    """
    phi = np.radians(phi_eff_deg)
    return (C_apparent * np.cos(phi) + c_eff / np.tan(phi)) / (np.cos(phi) + 1.0 / np.tan(phi))


def true_triaxial_group_cap(C_apparent, C_fictive, Ci_apparent, Ci_fictive, c_eff, phi_eff_deg):
    """True-triaxial tensor at constant Lode angle [2, eq. 50]: (sigma1, sigma2, sigma3)_cap.

    Adds (sigma1_cap - sigma2_cap)/2 = (C_i - C_i'') cos phi' to eq. (48).
    """
    s1, s3 = axisymmetric_group_cap(C_apparent, C_fictive, c_eff, phi_eff_deg)
    s2 = s1 - 2.0 * (Ci_apparent - Ci_fictive) * np.cos(np.radians(phi_eff_deg))
    return s1, s2, s3
