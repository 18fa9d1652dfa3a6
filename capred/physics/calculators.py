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

from collections.abc import Callable
from dataclasses import dataclass

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


#: compressibility of water [1/Pa] (4.6e-10 at 20 °C; Skempton 1954 and Lade & Hernandez 1977 use 4.6e-7 1/kPa)
WATER_COMPRESSIBILITY = 4.6e-10
#: Henry's volumetric coefficient of solubility of air in water [-] (0.02 at 20 °C; Hilf 1948)
HENRY_COEFFICIENT = 0.02
#: radius of the air bubbles of Schuurman's (1966) mixture [m] unless given (an illustrative 0.05 mm)
BUBBLE_RADIUS = 5e-5


def skeleton_compressibility(p0_eff, e0, kappa_elastic):
    """Volumetric compressibility of an elastic skeleton, C_c = κ/((1 + e0) p'0) [1/Pa] (Morvan et al. 2016, eq. 5).

    Parameters
    ----------
    p0_eff : numeric
        Mean effective stress p'0 [Pa].
    e0 : numeric
        Void ratio [-].
    kappa_elastic : numeric
        Slope of the elastic line in e - ln p' [-].

    Returns
    -------
    numeric
        C_c [1/Pa].

    References
    ----------
    .. [1] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation of B with Sr. E-UNSAT 2016, eq. 5.
    """
    return kappa_elastic / ((1.0 + e0) * p0_eff)


def b_skempton1954(S_R, p0_eff, e0, kappa_elastic, pa0, C_w=WATER_COMPRESSIBILITY):
    r"""Skempton (1954): B = 1/(1 + n C_v/C_c) with the pore fluid a mixture of water and free air (Boyle's law).

    Parameters
    ----------
    S_R : numeric
        Degree of saturation [-].
    p0_eff : numeric
        Mean effective stress p'0 [Pa].
    e0 : numeric
        Void ratio [-].
    kappa_elastic : numeric
        Slope of the elastic line in e - ln p' [-].
    pa0 : numeric
        Absolute pore-air pressure [Pa].
    C_w : numeric, optional
        Compressibility of water [1/Pa].

    Returns
    -------
    numeric
        B [-].

    Notes
    -----
    .. math::

        B = \frac{1}{1 + n C_v / C_c},\quad n = \frac{e_0}{1 + e_0},\quad
        C_v = S_r C_w + \frac{1 - S_r}{P_{a0}},\quad C_c = \frac{\kappa}{(1 + e_0) p'_0};

    with C_w = 0 it is Morvan et al.'s eq. 10.

    References
    ----------
    .. [1] Skempton, A. W. (1954). The pore-pressure coefficients A and B. Géotechnique 4(4), 143-147.
       doi:10.1680/geot.1954.4.4.143
    .. [2] Morvan, M., Vernay, M. & Breul, P. (2016), eq. 3 (the same relation) and eq. 5.
    """
    S = np.asarray(S_R, float)
    n = e0 / (1.0 + e0)
    C_v = S * C_w + (1.0 - S) / pa0
    return 1.0 / (1.0 + n * C_v / skeleton_compressibility(p0_eff, e0, kappa_elastic))


def b_hilf_lade(S_R, p0_eff, e0, kappa_elastic, pa0, C_w=WATER_COMPRESSIBILITY, H=HENRY_COEFFICIENT):
    r"""Hilf (1948) as Lade & Hernandez (1977) use it: Skempton's B with air that dissolves (Henry's law).

    Parameters
    ----------
    S_R : numeric
        Degree of saturation [-].
    p0_eff, e0, kappa_elastic, pa0 : numeric
        As :func:`b_skempton1954` [Pa, -, -, Pa].
    C_w : numeric, optional
        Compressibility of water [1/Pa].
    H : numeric, optional
        Henry's volumetric coefficient of solubility [-] (0.02).

    Returns
    -------
    numeric
        B [-].

    Notes
    -----
    .. math::

        B = \frac{1}{1 + n C_v / C_c},\quad C_v = S_r C_w + \frac{1 - S_r + H S_r}{P_{a0}}

    (the air dissolved in the pore water, H S_r of the voids at P_a0, is compressed with the free air, while free
    air is left: at S_r = 1 the fluid is water alone, so B jumps to 1/(1 + n C_w/C_c) there).

    References
    ----------
    .. [1] Hilf, J. W. (1948). Estimating construction pore pressures in rolled earth dams. Proc. 2nd ICSMFE,
       Rotterdam, 3, 234-240.
    .. [2] Lade, P. V. & Hernandez, S. B. (1977). Membrane penetration effects in undrained tests. J. Geotech.
       Eng. Div. ASCE 103(GT2), 109-125.
    """
    S = np.asarray(S_R, float)
    n = e0 / (1.0 + e0)
    C_v = S * C_w + np.where(S < 1.0, (1.0 - S + H * S) / pa0, 0.0)  # no free air left at S_r = 1
    return 1.0 / (1.0 + n * C_v / skeleton_compressibility(p0_eff, e0, kappa_elastic))


def b_schuurman1966(
    S_R,
    p0_eff,
    e0,
    kappa_elastic,
    pa0,
    C_w=WATER_COMPRESSIBILITY,
    H=HENRY_COEFFICIENT,
    surface_tension=0.0728,
    bubble_radius=BUBBLE_RADIUS,
):
    r"""Schuurman (1966): the air as bubbles of constant number, their pressure raised by surface tension.

    Parameters
    ----------
    S_R : numeric
        Degree of saturation [-] (the bubble model holds above about 0.85).
    p0_eff, e0, kappa_elastic, pa0 : numeric
        As :func:`b_skempton1954`; ``pa0`` is the absolute pore-water pressure here [Pa].
    C_w, H : numeric, optional
        Compressibility of water [1/Pa] and Henry's coefficient [-].
    surface_tension : numeric, optional
        Surface tension of water [N/m].
    bubble_radius : numeric, optional
        Radius r of the bubbles [m].

    Returns
    -------
    numeric
        B [-].

    Notes
    -----
    A bubble's air pressure is P_w + 2 gamma / r; with Boyle's law on a bubble of constant number of molecules
    (r ~ V^(1/3)) its compressibility with respect to the water pressure is 1 / (P_w + 4 gamma / (3 r)), so

    .. math::

        C_v = S_r C_w + \frac{1 - S_r + H S_r}{P_{w0} + 4\gamma/(3r)}

    (capred's reading of Schuurman's bubble model for the instantaneous B; the paper itself was not at hand).
    As r -> infinity it is :func:`b_hilf_lade`.

    References
    ----------
    .. [1] Schuurman, I. E. (1966). The compressibility of an air/water mixture and a theoretical relation
       between the air and water pressures. Géotechnique 16(4), 269-281. doi:10.1680/geot.1966.16.4.269
    """
    S = np.asarray(S_R, float)
    n = e0 / (1.0 + e0)
    C_v = S * C_w + np.where(S < 1.0, (1.0 - S + H * S) / (pa0 + 4.0 * surface_tension / (3.0 * bubble_radius)), 0.0)
    return 1.0 / (1.0 + n * C_v / skeleton_compressibility(p0_eff, e0, kappa_elastic))


@dataclass(frozen=True)
class BRelation:
    """One classical B(S_r) relation: a registry entry of :data:`SKEMPTON_RELATIONS`.

    Attributes
    ----------
    name : str
        Key (``--compare`` spelling, output column ``B_<name>``).
    label : str
        Figure legend.
    reference : str
        Key of capred.references.REFERENCES.
    equation : str
        What it computes.
    b : callable
        ``b(S_R, p0_eff, e0, kappa_elastic, pa0) -> B``.
    """

    name: str
    label: str
    reference: str
    equation: str
    b: Callable


SKEMPTON_RELATIONS: dict[str, BRelation] = {
    r.name: r
    for r in (
        BRelation(
            "skempton1954",
            "Skempton (1954)",
            "skempton1954",
            "B = 1/(1 + n C_v/C_c), C_v = S_r C_w + (1 − S_r)/P_a0, C_c = κ/((1 + e0) p'0) (Morvan et al. eq. 3, 5)",
            b_skempton1954,
        ),
        BRelation(
            "hilf_lade",
            "Hilf (1948) / Lade & Hernandez (1977)",
            "lade_hernandez1977",
            "as Skempton with C_v = S_r C_w + (1 − S_r + H S_r)/P_a0, H = 0.02 (air dissolved by Henry's law)",
            b_hilf_lade,
        ),
        BRelation(
            "schuurman1966",
            "Schuurman (1966)",
            "schuurman1966",
            "bubbles of constant number: C_v = S_r C_w + (1 − S_r + H S_r)/(P_a0 + 4γ/(3r)), r = 0.05 mm",
            b_schuurman1966,
        ),
    )
}


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
