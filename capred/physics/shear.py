r"""Direct shear with hanging-column suction: the formulas of Evenepoel's thesis.

All functions are vectorised (scalar or ndarray in, same shape out) and work
in SI: Pa, m, kg, m^3, N/m. Compression is positive; suction
:math:`\Delta u = u_a - u_w \ge 0`.

References
----------
.. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
   capillary effective stress in granular materials. Master thesis, Vrije
   Universiteit Brussel (no DOI): sections "Apply suction", "Own
   approximation", "Shear strength".
"""

from __future__ import annotations

import numpy as np

from ..spec.constants import GAMMA_W, PENDULAR_LIMIT, SURFACE_TENSION, G  # noqa: F401 (declared once in spec)

#: S_R above which chi1 = (2 pi S_R / 3)^(2/3) exceeds 1: 3 / (2 pi).
CHI1_UNITY_SR = 3.0 / (2.0 * np.pi)


def suction_from_head(z1, gamma_w=GAMMA_W):
    r"""Matric suction applied by a hanging water column.

    Parameters
    ----------
    z1 : numeric
        Height of the sample above the water level [m], >= 0.
    gamma_w : float, default :data:`GAMMA_W`
        Unit weight of water [N/m^3].

    Returns
    -------
    numeric
        Suction :math:`\Delta u = u_a - u_w` [Pa].

    Notes
    -----
    .. math::

       \Delta u = \gamma_w z_1

    The thesis writes :math:`\Delta u = z_1 \cdot 0.1` kPa/cm
    (:math:`\gamma_w` = 10 kN/m^3).

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Apply suction".
    """
    return gamma_w * np.asarray(z1, dtype=float)


#: Vapour pressure of water at 20 °C [Pa].
VAPOUR_PRESSURE_20C = 2339.0


def cavitation_head(gamma_w=GAMMA_W, ambient_pressure=101325.0, vapour_pressure=VAPOUR_PRESSURE_20C):
    r"""Largest hanging-column head before the water at the sample cavitates.

    Parameters
    ----------
    gamma_w : float, default :data:`GAMMA_W`
        Unit weight of water [N/m^3].
    ambient_pressure : float, default 101325
        Absolute air pressure :math:`p_a` [Pa].
    vapour_pressure : float, default :data:`VAPOUR_PRESSURE_20C`
        Vapour pressure of water :math:`p_v` [Pa] (2339 Pa at 20 °C).

    Returns
    -------
    float
        :math:`z_{1,max}` [m]; about 10.1 m of water at 20 °C and 1 atm.

    Notes
    -----
    The absolute water pressure at the sample is :math:`p_a - \gamma_w z_1`
    (the column of [1]_); below :math:`p_v` the water boils:

    .. math::

       z_{1,max} = \frac{p_a - p_v}{\gamma_w}

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Apply suction" (the head
       :math:`z_1`; the cavitation limit is capred's, from hydrostatics).
    """
    return (ambient_pressure - vapour_pressure) / gamma_w


def degree_of_saturation(z2, void_volume):
    r"""Degree of saturation from the air volume read on the burette.

    Parameters
    ----------
    z2 : numeric
        Air volume that has entered the sample [m^3], 0 <= z2 <= V_v.
    void_volume : numeric
        Void volume :math:`V_v` of the sample [m^3], > 0.

    Returns
    -------
    numeric
        :math:`S_R` [-], in [0, 1] for valid input.

    Notes
    -----
    .. math::

       S_R = \frac{V_w}{V_v} = \frac{V_v - V_a}{V_v} = \frac{V_v - z_2}{V_v}

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Apply suction".
    """
    v = np.asarray(void_volume, dtype=float)
    return (v - np.asarray(z2, dtype=float)) / v


def normal_stress(mass, box_area, g=G):
    r"""Total normal stress of dead loads on the shear box.

    Parameters
    ----------
    mass : numeric
        Top cap plus added weights [kg].
    box_area : numeric
        Plan area of the shear box [m^2], > 0.
    g : float, default :data:`G`
        Gravitational acceleration [m/s^2].

    Returns
    -------
    numeric
        :math:`\sigma_N` [Pa].

    Notes
    -----
    .. math::

       \sigma_N = \frac{m g}{A}

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Shear strength" (added
       weights on the top cap).
    """
    return np.asarray(mass, dtype=float) * g / np.asarray(box_area, dtype=float)


def chi1(S_R):
    r"""Own approximation 1 of the effective-stress parameter, :math:`\chi_1 = (2\pi S_R/3)^{2/3}`.

    Parameters
    ----------
    S_R : numeric
        Degree of saturation [-].

    Returns
    -------
    numeric
        :math:`\chi_1` [-]; exceeds 1 for :math:`S_R > 3/(2\pi)`.

    Notes
    -----
    A two-sphere unit cell with one bridge has
    :math:`S_R = 3V_w/(2\pi R^3) \approx 3r_0^3/(2\pi R^3)`, so

    .. math::

       \chi_1 = \left(\frac{r_0}{R}\right)^2 = \left(\frac{2\pi}{3} S_R\right)^{2/3}

    derived for the pendular regime (:math:`S_R` below about 5 %).

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Own approximation".
    """
    return np.cbrt(2.0 * np.pi * np.asarray(S_R, dtype=float) / 3.0) ** 2


def chi2(S_R, R, surface_tension=SURFACE_TENSION):
    r"""Own approximation 2, the surface-tension term :math:`\chi_2 = (2\gamma/R)(2\pi S_R/3)^{1/3}`.

    Parameters
    ----------
    S_R : numeric
        Degree of saturation [-].
    R : numeric
        Particle radius [m], > 0.
    surface_tension : float, default :data:`SURFACE_TENSION`
        Surface tension of water :math:`\gamma` [N/m].

    Returns
    -------
    numeric
        :math:`\chi_2` [Pa].

    Notes
    -----
    The tension force :math:`2\pi r_0\gamma` on the cell's area
    :math:`\pi R^2`, with :math:`r_0/R = (2\pi S_R/3)^{1/3}`:

    .. math::

       \chi_2 = \frac{2\gamma}{R}\left(\frac{2\pi}{3} S_R\right)^{1/3}

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Own approximation".
    """
    return (
        2.0 * surface_tension / np.asarray(R, dtype=float) * np.cbrt(2.0 * np.pi * np.asarray(S_R, dtype=float) / 3.0)
    )


def mohr_coulomb_strength(c, tan_phi, sigma_eff):
    r"""Shear strength on the shear plane, Mohr-Coulomb in effective stress.

    Parameters
    ----------
    c : numeric
        Cohesion [Pa].
    tan_phi : numeric
        Tangent of the friction angle [-].
    sigma_eff : numeric
        Effective normal stress :math:`\sigma'_N` [Pa].

    Returns
    -------
    numeric
        :math:`\tau_{max}` [Pa].

    Notes
    -----
    .. math::

       \tau_{max} = c + \sigma'_N \tan\varphi

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Shear strength".
    """
    return c + np.asarray(sigma_eff, dtype=float) * tan_phi
