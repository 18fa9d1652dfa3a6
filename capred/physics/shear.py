"""Direct shear with hanging-column suction: the formulas of Evenepoel's thesis.

All functions are vectorised (scalar or ndarray in, same shape out) and work
in SI: Pa, m, kg, m^3, N/m. Compression is positive; suction u_a - u_w >= 0.

References
----------
[1] R. Evenepoel, "Micro-mechanical characterization of the capillary
    effective stress in granular materials", master thesis, Vrije
    Universiteit Brussel: sections "Apply suction", "Own approximation",
    "Shear strength".
"""
from __future__ import annotations

import numpy as np

#: Unit weight of water [N/m^3] used by default; the thesis uses 10 kN/m^3 [1].
GAMMA_W = 9810.0
#: Surface tension of water at 20 C [N/m].
SURFACE_TENSION = 0.0728
#: Gravitational acceleration [m/s^2].
G = 9.81
#: Upper S_R of the pendular regime used in the thesis [1] ("S_R < 5 %").
PENDULAR_LIMIT = 0.05
#: S_R above which chi1 = (2 pi S_R / 3)^(2/3) exceeds 1: 3 / (2 pi).
CHI1_UNITY_SR = 3.0 / (2.0 * np.pi)

#: The four effective-stress models of the thesis [1], in display order (the registry of every
#: model is capred.physics.effective_stress_models.REGISTRY).
MODELS = ("no_suction", "bishop", "own1", "own2")


def suction_from_head(z1, gamma_w=GAMMA_W):
    """Matric suction from the hanging-column head: Delta_u = gamma_w z1 [1].

    Parameters
    ----------
    z1 : height of the sample above the water level [m], >= 0
    gamma_w : unit weight of water [N/m^3]

    Returns
    -------
    Delta_u = u_a - u_w [Pa]
    """
    return gamma_w * np.asarray(z1, dtype=float)


#: Vapour pressure of water at 20 °C [Pa].
VAPOUR_PRESSURE_20C = 2339.0


def cavitation_head(gamma_w=GAMMA_W, ambient_pressure=101325.0, vapour_pressure=VAPOUR_PRESSURE_20C):
    """Largest hanging-column head before the water at the sample cavitates [m].

    The water pressure at the sample is p_a - gamma_w z1 (absolute); below the
    vapour pressure p_v it boils: z1_max = (p_a - p_v) / gamma_w, about 10.1 m
    of water at 20 °C and 1 atm.

    Parameters
    ----------
    gamma_w : unit weight of water [N/m^3]
    ambient_pressure : absolute air pressure p_a [Pa]
    vapour_pressure : vapour pressure of water p_v [Pa] (2339 Pa at 20 °C)
    """
    return (ambient_pressure - vapour_pressure) / gamma_w


def degree_of_saturation(z2, void_volume):
    """S_R = (V_v - z2) / V_v, with z2 the air volume read on the burette [1].

    Parameters
    ----------
    z2 : air volume that has entered the sample [m^3], 0 <= z2 <= V_v
    void_volume : void volume V_v of the sample [m^3], > 0

    Returns
    -------
    S_R [-], in [0, 1] for valid input
    """
    v = np.asarray(void_volume, dtype=float)
    return (v - np.asarray(z2, dtype=float)) / v


def normal_stress(mass, box_area, g=G):
    """Total normal stress of dead loads on the shear box: sigma_N = m g / A [Pa].

    ``mass`` is the top cap plus added weights [kg]; ``box_area`` [m^2].
    """
    return np.asarray(mass, dtype=float) * g / np.asarray(box_area, dtype=float)


def chi1(S_R):
    """Own approximation 1: chi1 = (2 pi S_R / 3)^(2/3) [-] [1].

    From a two-sphere unit cell with one bridge, V_w ~ r0^3 and
    S_R = 3 V_w / (2 pi R^3), so (r0/R)^2 = (2 pi S_R / 3)^(2/3). Derived for
    the pendular regime (S_R below about 5 %); exceeds 1 for S_R > 3/(2 pi).
    """
    return np.cbrt(2.0 * np.pi * np.asarray(S_R, dtype=float) / 3.0) ** 2


def chi2(S_R, R, surface_tension=SURFACE_TENSION):
    """Own approximation 2 surface-tension term: chi2 = (2 gamma / R)(2 pi S_R/3)^(1/3) [Pa] [1].

    Parameters
    ----------
    S_R : degree of saturation [-]
    R : particle radius [m], > 0
    surface_tension : gamma [N/m]
    """
    return 2.0 * surface_tension / np.asarray(R, dtype=float) * np.cbrt(
        2.0 * np.pi * np.asarray(S_R, dtype=float) / 3.0
    )


def effective_normal_stress(model, sigma_N, suction, S_R, R=np.nan, surface_tension=SURFACE_TENSION):
    """sigma'_N under one of the thesis's four models [1] [Pa].

    ========== =========================================
    model      sigma'_N
    ========== =========================================
    no_suction sigma_N
    bishop     sigma_N + S_R Delta_u
    own1       sigma_N + chi1 Delta_u
    own2       sigma_N + chi1 Delta_u + chi2
    ========== =========================================
    """
    sigma_N = np.asarray(sigma_N, dtype=float)
    suction = np.asarray(suction, dtype=float)
    if model == "no_suction":
        return sigma_N + 0.0 * suction
    if model == "bishop":
        return sigma_N + np.asarray(S_R, dtype=float) * suction
    if model == "own1":
        return sigma_N + chi1(S_R) * suction
    if model == "own2":
        return sigma_N + chi1(S_R) * suction + chi2(S_R, R, surface_tension)
    raise ValueError(f"unknown model '{model}'; choose from {', '.join(MODELS)}")


def mohr_coulomb_strength(c, tan_phi, sigma_eff):
    """Shear strength tau = c + sigma' tan(phi) [Pa] [1]."""
    return c + np.asarray(sigma_eff, dtype=float) * tan_phi
