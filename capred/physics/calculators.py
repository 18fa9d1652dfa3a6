r"""Small closed-form calculators from the source papers: Bernatzik's prism, Skempton's B, Rumpf.

SI in and out (Pa, m, N/m); angles in degrees. Vectorised: scalar or ndarray
in, same shape out.

References
----------
.. [1] Bernatzik, W. (1948). The determination of the capillary rise in sand
   by means of prism pressure tests. Proc. 2nd Int. Conf. Soil Mech. Found.
   Eng., Rotterdam, paper II b 6 (no DOI).
.. [2] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation of B
   with Sr. E-UNSAT 2016, E3S Web of Conferences (DOI not given in the
   source), eq. 8-13.
.. [3] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). A method to
   evaluate the capillary stress tensor at failure in unsaturated soils. Eur.
   J. Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 19, after
   Rumpf (1962).
"""

from __future__ import annotations

import numpy as np

from .retention import bc_suction


def prism_capillary_pressure(break_tension, friction_angle_deg):
    r"""Largest capillary pressure of a sand prism from its break tension (Bernatzik's prism test).

    Parameters
    ----------
    break_tension : numeric
        Break tension :math:`\sigma_b` of the prism [Pa].
    friction_angle_deg : numeric
        Friction angle :math:`\rho` of the sand [deg].

    Returns
    -------
    numeric
        :math:`P_{k,max}` [Pa]; :math:`0.35\,\sigma_b` for dense sand
        (:math:`\rho` = 36 deg).

    Notes
    -----
    From the Mohr circle of the prism at break,
    :math:`\sin\rho = \sigma_b/(2P_{k,max} + \sigma_b)`:

    .. math::

       P_{k,max} = \frac{\sigma_b\,(1 - \sin\rho)}{2\sin\rho}

    References
    ----------
    .. [1] Bernatzik, W. (1948). The determination of the capillary rise in
       sand by means of prism pressure tests. Proc. 2nd ICSMFE, Rotterdam,
       paper II b 6 (no DOI; the two unnumbered equations of the paper).
    """
    s = np.sin(np.radians(friction_angle_deg))
    return np.asarray(break_tension, float) * (1.0 - s) / (2.0 * s)


def capillary_rise(capillary_pressure, gamma_w):
    r"""Capillary rise equivalent to a capillary pressure.

    Parameters
    ----------
    capillary_pressure : numeric
        :math:`P_{k,max}` [Pa].
    gamma_w : numeric
        Unit weight of water [N/m^3].

    Returns
    -------
    numeric
        Capillary rise :math:`h_c` [m].

    Notes
    -----
    .. math::

       h_c = \frac{P_{k,max}}{\gamma_w}

    References
    ----------
    .. [1] Bernatzik, W. (1948). The determination of the capillary rise in
       sand by means of prism pressure tests. Proc. 2nd ICSMFE, Rotterdam,
       paper II b 6 (no DOI): 40.2 g/cm^2 -> 40.2 cm.
    """
    return np.asarray(capillary_pressure, float) / gamma_w


def skempton_b(S_R, p0_eff, e0, kappa_elastic, pa0):
    r"""Skempton's B of an unsaturated elastic soil with compressible air (Boyle's law).

    Parameters
    ----------
    S_R : numeric
        Degree of saturation :math:`S_r` [-].
    p0_eff : numeric
        Initial mean effective stress :math:`p'_0` [Pa].
    e0 : numeric
        Initial void ratio [-].
    kappa_elastic : numeric
        Slope :math:`\kappa` of the elastic line in :math:`e`-:math:`\ln p` [-].
    pa0 : numeric
        Absolute initial air pressure :math:`P_{a0}` [Pa].

    Returns
    -------
    numeric
        :math:`B = du_w/dp` [-], in (0, 1].

    Notes
    -----
    Water and grains incompressible, :math:`du_w = du_a` (eq. 9):

    .. math::

       B = \frac{1}{1 + \dfrac{p'_0 e_0 (1 - S_r)}{\kappa P_{a0}}}

    References
    ----------
    .. [1] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation
       of B with Sr. E-UNSAT 2016, E3S Web of Conferences (DOI not given in
       the source), eq. 8-10.
    """
    return 1.0 / (1.0 + p0_eff * e0 * (1.0 - np.asarray(S_R, float)) / (kappa_elastic * pa0))


def saturation_from_b(B, p0_eff, e0, kappa_elastic, pa0):
    r"""Degree of saturation from a measured B (eq. 10 of Morvan et al. inverted).

    Parameters
    ----------
    B : numeric
        Skempton's coefficient [-], in (0, 1].
    p0_eff : numeric
        Initial mean effective stress :math:`p'_0` [Pa].
    e0 : numeric
        Initial void ratio [-].
    kappa_elastic : numeric
        Slope :math:`\kappa` of the elastic line in :math:`e`-:math:`\ln p` [-].
    pa0 : numeric
        Absolute initial air pressure :math:`P_{a0}` [Pa].

    Returns
    -------
    numeric
        Degree of saturation :math:`S_r` [-]; B = 0 gives its limit, -inf (no S_r in [0, 1] gives a B below
        the dry soil's, and a caller reports such values as outside [0, 1]).

    Notes
    -----
    .. math::

       S_r = 1 - \left(\frac{1}{B} - 1\right)\frac{\kappa P_{a0}}{p'_0 e_0}

    References
    ----------
    .. [1] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation
       of B with Sr. E-UNSAT 2016, E3S Web of Conferences (DOI not given in
       the source), eq. 10.
    """
    with np.errstate(divide="ignore"):  # 1/0 = inf: the limit B -> 0+, S_r -> -inf
        inv = 1.0 / np.asarray(B, float)
    return 1.0 - (inv - 1.0) * kappa_elastic * pa0 / (p0_eff * e0)


def skempton_b_suction(S_R, p0, ua0, e0, kappa_elastic, pa0, s_e, bc_lambda):
    r"""Skempton's B with suction equilibrium before the increment (Brooks-Corey retention).

    Parameters
    ----------
    S_R : numeric
        Degree of saturation :math:`S_r` [-].
    p0 : numeric
        Initial mean total stress [Pa].
    ua0 : numeric
        Initial air pressure (gauge) [Pa].
    e0 : numeric
        Initial void ratio [-].
    kappa_elastic : numeric
        Slope :math:`\kappa` of the elastic line in :math:`e`-:math:`\ln p` [-].
    pa0 : numeric
        Absolute initial air pressure :math:`P_{a0}` [Pa].
    s_e : numeric
        Air-entry suction of Brooks-Corey [Pa].
    bc_lambda : numeric
        Brooks-Corey pore-size index (:math:`\alpha` of Morvan et al.,
        :math:`\lambda` of Brooks & Corey) [-].

    Returns
    -------
    numeric
        :math:`B` [-]; falls as :math:`s_e` rises. At :math:`S_r = 0` the limit of :math:`s S_r =
        s_e S_r^{1 - 1/\alpha}`: B = 0 for :math:`\alpha < 1` (infinite suction stiffening).

    Notes
    -----
    Suction from Brooks-Corey and the initial effective stress of eq. 13:

    .. math::

       s = s_e S_r^{-1/\alpha}, \qquad p'_0 = p_0 - u_{a0} + s S_r

    The undrained increment is small and the suction is taken constant during
    it (:math:`du_a = du_w`), so eq. 10 applies with this stiffer
    :math:`p'_0` (:func:`skempton_b`).

    References
    ----------
    .. [1] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation
       of B with Sr. E-UNSAT 2016, E3S Web of Conferences (DOI not given in
       the source), section 3, eq. 10-13.
    .. [2] Brooks, R. H. & Corey, A. T. (1964). Hydraulic properties of porous
       media. Hydrology Paper 3, Colorado State University (no DOI).
    """
    S_R = np.asarray(S_R, float)
    wet = S_R > 0
    with np.errstate(divide="ignore"):  # s S_r = s_e S_r^(1 - 1/α) at S_r = 0: inf (α < 1), s_e (α = 1), 0 (α > 1)
        dry = s_e * np.zeros_like(S_R) ** (1.0 - 1.0 / np.asarray(bc_lambda, float))
    p0_eff = p0 - ua0 + np.where(wet, bc_suction(np.where(wet, S_R, 1.0), s_e, bc_lambda) * S_R, dry)
    return skempton_b(S_R, p0_eff, e0, kappa_elastic, pa0)


def rumpf_capillary_pressure(shape_factor, void_ratio, S_R, diameter, surface_tension, contact_angle_deg):
    r"""Capillary pressure of a moist granular medium after Rumpf (negative: tension).

    Parameters
    ----------
    shape_factor : numeric
        Particle shape factor :math:`\phi` [-].
    void_ratio : numeric
        Void ratio :math:`e` [-].
    S_R : numeric
        Degree of saturation :math:`S_r` [-].
    diameter : numeric
        Apparent particle diameter :math:`d_p` [m].
    surface_tension : numeric
        Surface tension :math:`\gamma_{aw}` [N/m].
    contact_angle_deg : numeric
        Wetting (contact) angle :math:`\theta` [deg].

    Returns
    -------
    numeric
        :math:`p^{cap}` [Pa], <= 0 for contact angles below 90 deg.

    Notes
    -----
    .. math::

       p^{cap} = -\frac{6}{\phi}\,\frac{S_r}{e}\,\frac{\gamma_{aw}}{d_p}\cos\theta

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). A method to
       evaluate the capillary stress tensor at failure in unsaturated soils.
       Eur. J. Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 19,
       after Rumpf, H. (1962).
    """
    return (
        -(6.0 / np.asarray(shape_factor, float))
        * (np.asarray(S_R, float) / void_ratio)
        * (surface_tension / np.asarray(diameter, float))
        * np.cos(np.radians(contact_angle_deg))
    )
