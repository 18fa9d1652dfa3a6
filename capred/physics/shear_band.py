"""Orientation of a shear band in a triaxial (or biaxial) compression test: the classical angles.

Angles in degrees, measured between the band and the plane on which the major principal stress acts (the
horizontal in a triaxial compression test), as the photographs of Prunier et al. (2024), Fig. 14, read them.

References
----------
.. [1] Coulomb's orientation: 45 + phi'/2, the plane of the Mohr-Coulomb criterion's tangency (e.g. Vardoulakis,
   I. & Sulem, J. (1995), Bifurcation Analysis in Geomechanics, Blackie).
.. [2] Roscoe, K. H. (1970). The influence of strains in soil mechanics. Géotechnique 20(2), 129-170.
   doi:10.1680/geot.1970.20.2.129 (45 + psi/2, a direction of zero extension).
.. [3] Arthur, J. R. F., Dunstan, T., Al-Ani, Q. A. J. L. & Assadi, A. (1977). Plastic deformation and failure
   in granular media. Géotechnique 27(1), 53-74. doi:10.1680/geot.1977.27.1.53 (45 + (phi' + psi)/4).
"""

from __future__ import annotations

import numpy as np


def coulomb_angle(friction_angle_deg):
    """Coulomb's shear-band angle 45 + phi'/2 [deg].

    Parameters
    ----------
    friction_angle_deg : array_like
        Effective friction angle phi' [deg].

    Returns
    -------
    numpy.ndarray
        Angle between the band and the major principal plane [deg].

    References
    ----------
    .. [1] Vardoulakis & Sulem (1995), Bifurcation Analysis in Geomechanics: the Coulomb orientation.
    """
    return 45.0 + 0.5 * np.asarray(friction_angle_deg, float)


def roscoe_angle(dilatancy_angle_deg):
    """Roscoe's (1970) shear-band angle 45 + psi/2 [deg].

    Parameters
    ----------
    dilatancy_angle_deg : array_like
        Dilatancy angle psi [deg].

    Returns
    -------
    numpy.ndarray
        [deg].

    References
    ----------
    .. [1] Roscoe, K. H. (1970). Géotechnique 20(2), 129-170. doi:10.1680/geot.1970.20.2.129
    """
    return 45.0 + 0.5 * np.asarray(dilatancy_angle_deg, float)


def arthur_angle(friction_angle_deg, dilatancy_angle_deg):
    """Arthur et al.'s (1977) shear-band angle, the mean of Coulomb's and Roscoe's: 45 + (phi' + psi)/4 [deg].

    Parameters
    ----------
    friction_angle_deg, dilatancy_angle_deg : array_like
        phi' and psi [deg].

    Returns
    -------
    numpy.ndarray
        [deg].

    References
    ----------
    .. [1] Arthur, J. R. F., Dunstan, T., Al-Ani, Q. A. J. L. & Assadi, A. (1977). Géotechnique 27(1), 53-74.
       doi:10.1680/geot.1977.27.1.53
    """
    return 45.0 + 0.25 * (np.asarray(friction_angle_deg, float) + np.asarray(dilatancy_angle_deg, float))


def dilatancy_angle_triaxial(dilatancy_rate):
    """Dilatancy angle from the rate of volume change in triaxial compression [deg].

    Parameters
    ----------
    dilatancy_rate : array_like
        -d eps_v / d eps_1 at failure [-] (compression positive: > 0 when the sample dilates).

    Returns
    -------
    numpy.ndarray
        psi [deg], from sin psi = d / (2 + d) with d = -d eps_v / d eps_1 (axisymmetric compression,
        eps_v = eps_1 + 2 eps_3).

    References
    ----------
    .. [1] Vermeer, P. A. & de Borst, R. (1984). Non-associated plasticity for soils, concrete and rock. Heron
       29(3), 3-64: sin psi = (d eps_v / d gamma) with the triaxial rates.
    """
    d = np.asarray(dilatancy_rate, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.degrees(np.arcsin(d / (2.0 + d)))
