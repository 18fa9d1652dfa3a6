r"""Water-retention curves: the effective saturation S_e(s) of each model and its inverse.

Suction ``s`` is in any pressure unit consistent with the parameters (capred
passes Pa: ``vg_alpha`` in 1/Pa, ``s_e``, ``s_m``, ``a``, ``s_r`` in Pa). The water
quantity ``y`` is the volumetric water content θ [m³/m³] or the degree of
saturation S_R [-]; ``y_s`` and ``y_r`` are its saturated and residual values
(θ_s, θ_r or S_s, S_res), and

.. math:: y(s) = y_r + (y_s - y_r)\, S_e(s).

Every function takes scalars or arrays (broadcast together) and returns an
array of the broadcast shape. Suctions below zero are treated as zero.

References
----------
.. [1] van Genuchten, M. Th. (1980). A closed-form equation for predicting the
   hydraulic conductivity of unsaturated soils. Soil Sci. Soc. Am. J. 44:892-898.
   doi:10.2136/sssaj1980.03615995004400050002x (eqs. 3 and 21).
.. [2] Brooks, R. H., Corey, A. T. (1964). Hydraulic properties of porous media.
   Hydrology Paper 3, Colorado State University (no DOI).
.. [3] Kosugi, K. (1996). Lognormal distribution model for unsaturated soil
   hydraulic properties. Water Resour. Res. 32(9):2697-2703. doi:10.1029/96WR01776.
.. [4] Fredlund, D. G., Xing, A. (1994). Equations for the soil-water
   characteristic curve. Can. Geotech. J. 31(4):521-532. doi:10.1139/t94-061
   (eq. 26 and its correction factor C(ψ)).
.. [5] Durner, W. (1994). Hydraulic conductivity estimation for soils with
   heterogeneous pore structure. Water Resour. Res. 30(2):211-223.
   doi:10.1029/93WR02676.
.. [6] Morvan, M., Vernay, M., Breul, P. (2016). Study of the variation of B
   with Sr. E-UNSAT 2016, E3S Web of Conferences (section 3).
"""

from __future__ import annotations

import numpy as np

#: Suction at which Fredlund & Xing's correction factor brings the water content to zero [Pa] (10^6 kPa) [4]
FX_S_MAX = 1e9


def vg_effective_saturation(s, vg_alpha, vg_n, vg_m=None):
    r"""Effective saturation of van Genuchten (1980).

    .. math:: S_e = \left[1 + (\alpha s)^n\right]^{-m}, \qquad m = 1 - 1/n \text{ unless given}

    Parameters
    ----------
    s : array_like
        Suction [Pa] (any unit, the inverse of ``vg_alpha``'s), >= 0.
    vg_alpha : array_like
        :math:`\alpha`, the inverse of a characteristic suction [1/Pa], > 0.
    vg_n : array_like
        Pore-size index :math:`n` [-], > 1 when ``vg_m = 1 - 1/vg_n``.
    vg_m : array_like, optional
        Shape exponent :math:`m` [-], > 0; ``1 - 1/vg_n`` (Mualem's constraint) when None.

    Returns
    -------
    numpy.ndarray
        S_e [-] in [0, 1].

    References
    ----------
    van Genuchten (1980), doi:10.2136/sssaj1980.03615995004400050002x, eq. 3.
    """
    m = 1.0 - 1.0 / np.asarray(vg_n, float) if vg_m is None else vg_m
    x = vg_alpha * np.maximum(np.asarray(s, float), 0.0)
    with np.errstate(over="ignore"):
        p = x**vg_n
        se = (1.0 + p) ** (-m)
    if np.isinf(p).any():  # (αs)^n beyond the float range: S_e = (αs)^(-nm) (1 + (αs)^(-n))^(-m), the last 1
        x, n_, m_, p = np.broadcast_arrays(x, vg_n, m, p)
        big = np.isinf(p)
        se = np.array(np.broadcast_to(se, big.shape), float)
        se[big] = np.exp(-m_[big] * n_[big] * np.log(x[big]))
    return se


def vg_water(s, y_r, y_s, vg_alpha, vg_n, vg_m=None):
    r"""Water content (or S_R) of van Genuchten (1980).

    .. math:: y = y_r + \frac{y_s - y_r}{\left[1 + (\alpha s)^n\right]^{m}}

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    y_r, y_s : array_like
        Residual and saturated water content [m³/m³] or degree of saturation [-].
    vg_alpha : array_like
        :math:`\alpha` [1/Pa].
    vg_n : array_like
        :math:`n` [-].
    vg_m : array_like, optional
        :math:`m` [-]; ``1 - 1/vg_n`` when None.

    Returns
    -------
    numpy.ndarray
        y(s) in the unit of ``y_r`` and ``y_s``.

    References
    ----------
    van Genuchten (1980), doi:10.2136/sssaj1980.03615995004400050002x, eq. 21.
    """
    return y_r + (y_s - y_r) * vg_effective_saturation(s, vg_alpha, vg_n, vg_m)


def vg_suction(S_e, vg_alpha, vg_n, vg_m=None):
    r"""Suction at a given effective saturation, the inverse of :func:`vg_effective_saturation`.

    .. math:: s = \frac{1}{\alpha}\left(S_e^{-1/m} - 1\right)^{1/n}

    Parameters
    ----------
    S_e : array_like
        Effective saturation [-] in (0, 1]; outside, NaN.
    vg_alpha : array_like
        :math:`\alpha` [1/Pa].
    vg_n : array_like
        :math:`n` [-].
    vg_m : array_like, optional
        :math:`m` [-]; ``1 - 1/vg_n`` when None.

    Returns
    -------
    numpy.ndarray
        Suction [Pa] (0 at S_e = 1).

    References
    ----------
    van Genuchten (1980), doi:10.2136/sssaj1980.03615995004400050002x, eq. 3 solved for s.
    """
    S_e = np.asarray(S_e, float)
    m = 1.0 - 1.0 / np.asarray(vg_n, float) if vg_m is None else vg_m
    ok = (S_e > 0) & (S_e <= 1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s = np.maximum(np.where(ok, S_e, 0.5) ** (-1.0 / m) - 1.0, 0.0) ** (1.0 / vg_n) / vg_alpha
    return np.where(ok, s, np.nan)


def bc_effective_saturation(s, s_e, bc_lambda):
    r"""Effective saturation of Brooks & Corey (1964).

    .. math:: S_e = (s_e / s)^{\lambda} \ (s > s_e), \qquad S_e = 1 \ (s \le s_e)

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    s_e : array_like
        Air-entry (bubbling) suction [Pa], > 0.
    bc_lambda : array_like
        Pore-size distribution index λ [-], > 0.

    Returns
    -------
    numpy.ndarray
        S_e [-] in (0, 1].

    References
    ----------
    Brooks & Corey (1964), Hydrology Paper 3 (no DOI).
    """
    s = np.asarray(s, float)
    with np.errstate(divide="ignore"):
        # exp(λ ln min(s_e/s, 1)): exactly 1 up to s_e; the logarithm is taken once per (s, s_e) when λ varies
        # on another broadcast axis
        return np.exp(bc_lambda * np.log(np.minimum(s_e / np.where(s > 0, s, 0.0), 1.0)))


def bc_water(s, y_r, y_s, s_e, bc_lambda):
    """Water content (or S_R) of Brooks & Corey (1964): :math:`y = y_r + (y_s - y_r) S_e(s)`.

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    y_r, y_s : array_like
        Residual and saturated water content [m³/m³] or degree of saturation [-].
    s_e : array_like
        Air-entry suction [Pa].
    bc_lambda : array_like
        Pore-size distribution index λ [-].

    Returns
    -------
    numpy.ndarray
        y(s) in the unit of ``y_r`` and ``y_s``.

    References
    ----------
    Brooks & Corey (1964), Hydrology Paper 3 (no DOI).
    """
    return y_r + (y_s - y_r) * bc_effective_saturation(s, s_e, bc_lambda)


def bc_suction(S_R, s_e, bc_lambda):
    r"""Suction from Brooks-Corey as Morvan et al. (2016) use it, the inverse of :func:`bc_effective_saturation`.

    .. math:: s = s_e\, S_R^{-1/\lambda}

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-] in (0, 1], taken as the effective saturation (no residual saturation, as
        Morvan et al. do); 1 gives ``s = s_e``.
    s_e : array_like
        Air-entry suction [Pa] (any pressure unit; the result has the same).
    bc_lambda : array_like
        Brooks-Corey pore-size index λ [-] (Morvan et al. call it α).

    Returns
    -------
    numpy.ndarray
        Suction [Pa].

    References
    ----------
    Brooks & Corey (1964), Hydrology Paper 3; Morvan et al. (2016), section 3.
    """
    return s_e * np.asarray(S_R, float) ** (-1.0 / bc_lambda)


def kosugi_effective_saturation(s, s_m, sigma):
    r"""Effective saturation of Kosugi's (1996) lognormal model.

    .. math:: S_e = Q\!\left(\frac{\ln(s/s_m)}{\sigma}\right) = \tfrac12\,
              \mathrm{erfc}\!\left(\frac{\ln(s/s_m)}{\sqrt{2}\,\sigma}\right)

    with Q the complementary standard normal distribution function.

    Parameters
    ----------
    s : array_like
        Suction [Pa], >= 0 (S_e = 1 at s = 0).
    s_m : array_like
        Median suction of the pore-size distribution [Pa], > 0.
    sigma : array_like
        Standard deviation of ln(pore radius) [-], > 0.

    Returns
    -------
    numpy.ndarray
        S_e [-] in [0, 1].

    References
    ----------
    Kosugi (1996), doi:10.1029/96WR01776.
    """
    from scipy.special import erfc

    s = np.asarray(s, float)
    with np.errstate(divide="ignore"):
        z = np.log(np.where(s > 0, s, 0.0) / s_m) / sigma
    return 0.5 * erfc(z / np.sqrt(2.0))


def kosugi_suction(S_e, s_m, sigma):
    r"""Suction at a given effective saturation, the inverse of :func:`kosugi_effective_saturation`.

    .. math:: s = s_m \exp\!\left(\sigma\, Q^{-1}(S_e)\right)

    Parameters
    ----------
    S_e : array_like
        Effective saturation [-] in (0, 1]; outside, NaN (1 gives 0).
    s_m : array_like
        [Pa].
    sigma : array_like
        [-].

    Returns
    -------
    numpy.ndarray
        Suction [Pa].

    References
    ----------
    Kosugi (1996), doi:10.1029/96WR01776.
    """
    from scipy.special import ndtri

    S_e = np.asarray(S_e, float)
    ok = (S_e > 0) & (S_e <= 1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s = s_m * np.exp(sigma * -ndtri(np.where(ok, S_e, 0.5)))
    return np.where(ok, np.where(S_e >= 1, 0.0, s), np.nan)


def fx_correction(s, s_r, s_max=FX_S_MAX):
    r"""Correction factor C(s) of Fredlund & Xing (1994): the water content reaches zero at ``s_max``.

    .. math:: C(s) = 1 - \frac{\ln(1 + s/s_r)}{\ln(1 + s_{max}/s_r)}

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    s_r : array_like
        Suction of the residual water content [Pa], > 0.
    s_max : float, optional
        Suction of zero water content [Pa]; 10^6 kPa as in Fredlund & Xing.

    Returns
    -------
    numpy.ndarray
        C [-] (1 at s = 0, 0 at ``s_max``).

    References
    ----------
    Fredlund & Xing (1994), doi:10.1139/t94-061, eq. 26.
    """
    s = np.asarray(s, float)
    return 1.0 - np.log1p(np.maximum(s, 0.0) / s_r) / np.log1p(s_max / s_r)


def fx_shape(s, a, n, m):
    r"""The shape factor of Fredlund & Xing (1994).

    .. math:: S(s) = \left[\ln\!\left(e + (s/a)^n\right)\right]^{-m}

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    a : array_like
        Suction parameter [Pa], > 0 (near the air-entry suction).
    n : array_like
        Steepness [-], > 0.
    m : array_like
        Exponent of the residual range [-], > 0.

    Returns
    -------
    numpy.ndarray
        S [-] in (0, 1] (1 at s = 0).

    References
    ----------
    Fredlund & Xing (1994), doi:10.1139/t94-061, eq. 26 (without C).
    """
    s = np.maximum(np.asarray(s, float), 0.0)
    x = s / a
    with np.errstate(over="ignore"):
        p = x**n
    log_term = np.log(np.e + p)
    if np.isinf(p).any():  # (s/a)^n beyond the float range: ln(e + (s/a)^n) = n ln(s/a), to 1e-308
        x, n_, p = np.broadcast_arrays(x, n, p)
        big = np.isinf(p)
        log_term = np.array(np.broadcast_to(log_term, big.shape), float)
        log_term[big] = n_[big] * np.log(x[big])
    return log_term ** (-m)


def durner_effective_saturation(s, w1, alpha1, n1, alpha2, n2):
    r"""Effective saturation of Durner (1994), two van Genuchten curves (m_i = 1 - 1/n_i) weighted.

    .. math:: S_e = w_1 \left[1 + (\alpha_1 s)^{n_1}\right]^{-m_1}
              + (1 - w_1) \left[1 + (\alpha_2 s)^{n_2}\right]^{-m_2}

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    w1 : array_like
        Weight of the first pore system [-] in [0, 1].
    alpha1, alpha2 : array_like
        [1/Pa].
    n1, n2 : array_like
        [-], > 1.

    Returns
    -------
    numpy.ndarray
        S_e [-] in [0, 1].

    References
    ----------
    Durner (1994), doi:10.1029/93WR02676.
    """
    return w1 * vg_effective_saturation(s, alpha1, n1) + (1.0 - w1) * vg_effective_saturation(s, alpha2, n2)


def monotone_suction(saturation, target, lo=1e-6, hi=FX_S_MAX, iterations=64):
    """Suction at which a decreasing S(s) equals ``target``, by bisection on ln s (vectorised).

    Parameters
    ----------
    saturation : callable
        ``saturation(s) -> S`` [-], non-increasing in s [Pa].
    target : array_like
        Values of S [-] to invert.
    lo, hi : float
        Bracket [Pa]; targets outside [S(hi), S(lo)] give NaN.
    iterations : int
        Halvings of the log bracket (64 reach the float resolution of ln s).

    Returns
    -------
    numpy.ndarray
        Suction [Pa], NaN where ``target`` is out of reach.

    References
    ----------
    Used for the models without a closed-form inverse: Fredlund & Xing (1994), doi:10.1139/t94-061, eq. 26;
    Durner (1994), doi:10.1029/93WR02676.
    """
    target = np.asarray(target, float)
    a = np.full(target.shape, np.log(lo))
    b = np.full(target.shape, np.log(hi))
    inside = (saturation(np.exp(a)) >= target) & (saturation(np.exp(b)) <= target)
    for _ in range(iterations):
        mid = 0.5 * (a + b)
        above = saturation(np.exp(mid)) > target
        a, b = np.where(above, mid, a), np.where(above, b, mid)
    return np.where(inside, np.exp(0.5 * (a + b)), np.nan)


def scanning_water(s, main, s_reversal, y_reversal, s_closure, y_closure):
    r"""A scanning curve by the scaling of a main curve between its reversal and closure points.

    The scanning curve runs from the reversal point (s_Δ, y_Δ) to the point where its loop closes (s_c, y_c) along
    the main curve M of its own direction (main wetting for a wetting scanning curve, main drying for a drying
    one), scaled linearly so that it passes through both:

    .. math:: y(s) = y_c + \left[M(s) - M(s_c)\right] \frac{y_Δ - y_c}{M(s_Δ) - M(s_c)}

    A first-order wetting curve from the main drying curve closes at s_c = 0 (y_c the main wetting curve's
    saturated value), a first-order drying curve from the main wetting curve at s_c → ∞ (y_c its residual
    value); a curve of higher order closes at the previous reversal point of the other kind.

    Parameters
    ----------
    s : array_like
        Suction [Pa].
    main : callable
        ``main(s) -> y``: the main curve of the scanning curve's direction.
    s_reversal, y_reversal : float
        The reversal point: suction [Pa] and water quantity (θ [m³/m³], S_R [-] or w [-]).
    s_closure, y_closure : float
        The closure point (``np.inf`` for the dry end).

    Returns
    -------
    numpy.ndarray
        y(s) on the scanning curve (NaN where M(s_Δ) = M(s_c): the main curve is flat between the two points).

    References
    ----------
    Parker, J. C., Lenhard, R. J. (1987). A model for hysteretic constitutive relations governing multiphase
    flow: 1. Saturation-pressure relations. Water Resour. Res. 23(12):2187-2196, doi:10.1029/WR023i012p02187
    (the main curves scaled through the reversal points; here without air entrapment);
    Kool, J. B., Parker, J. C. (1987). Water Resour. Res. 23(1):105-114, doi:10.1029/WR023i001p00105.
    """
    s = np.asarray(s, float)
    m_c = float(np.asarray(main(np.asarray(min(s_closure, 1e15), float))))
    m_r = float(np.asarray(main(np.asarray(s_reversal, float))))
    if m_r == m_c:
        return np.full(s.shape, np.nan)
    return y_closure + (np.asarray(main(s), float) - m_c) * (y_reversal - y_closure) / (m_r - m_c)
