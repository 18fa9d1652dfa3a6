"""Closed-form capillary-force laws that DEM codes use, each one registry entry (:data:`LAWS`).

The registry is declared without numerics in `capred.spec.bridge_laws` (re-exported here); this module holds
the force functions its entries name.

Every law is written in capred's dimensionless variables: lengths in units of the radius R1 of particle 1
(gap* = D / R1, V* = V / R1^3, rho = R2 / R1, ``inf`` for a plane), the contact angle theta [rad] the same on
both solids, and the force returned in units of 2 pi R1 gamma (so that Israelachvili's limit between equal
spheres at contact is cos theta). For unequal spheres and a plane the laws written for equal spheres take
Derjaguin's effective radius R* = 2 R1 R2 / (R1 + R2) (R1 for equal spheres, 2 R1 on a plane), as Willett et
al. (2000) propose and YADE applies them.

Where the formulas come from. Each law's equation is the one its paper prints, with the equation numbers that
YADE's implementation (pkg/dem/ViscoelasticCapillarPM.cpp, Law2_ScGeom_ViscElCapPhys_Basic, the comparison of
yade-dev revision 3871) cites; the papers themselves were not at hand. Each was checked against capred's exact
bridge where the law claims to hold (tests/test_bridge_laws.py): the Derjaguin limit at contact (Willett's
simple form, Rabinovich, Lambert), agreement within a few per cent inside its fitted range (Willett's full
form, Soulié, Mikami). Mikami et al. (1998) is transcribed as the DEM codes that cite it print it (natural
logarithms, F = pi R gamma [exp(A D/R + B) + C], D the full separation): the exact bridge settles the two
readings that a source at hand leaves open. With F = 2 pi R gamma [...] the force at contact would be twice the
Derjaguin limit; with D the half separation the force at D/R = 0.05 would be 40-160 % above the exact one, and
its rupture distance (0.62 theta + 0.99) (V/R^3)^0.34 R matches the exact full-gap rupture (4-7 % at theta = 0).
Its theta^2 term, read with ln, overestimates the force once theta > 0 (+20-40 % at 20 deg); read with log10 it
becomes Soulié et al.'s (2006) regression (their coefficients are Mikami's times log10(e)), offered as ``soulie``.
"""

from __future__ import annotations

import numpy as np

from ..spec.bridge_laws import LAWS, Law  # noqa: F401  (the registry, declared without numerics)


def effective_radius(ratio):
    """Derjaguin's effective radius R* / R1 = 2 rho / (1 + rho) [-]; 2 on a plane (rho = inf), 1 for equal spheres.

    Parameters
    ----------
    ratio : float or array_like
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        R* / R1 [-].

    References
    ----------
    .. [1] Derjaguin, B. (1934). Untersuchungen über die Reibung und Adhäsion, IV. Kolloid-Z. 69, 155-164.
       doi:10.1007/BF01433225
    """
    rho = np.asarray(ratio, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.isinf(rho), 2.0, 2.0 * rho / (1.0 + np.where(np.isinf(rho), 1.0, rho)))


def _args(theta, V, D, rho):
    return [np.asarray(x, dtype=float) for x in np.broadcast_arrays(theta, V, D, rho)]


def willett_simple(contact_angle_rad, V, D, ratio=1.0):
    r"""Willett et al. (2000), the simple closed form (their eqs. 12-13), with Derjaguin's R*.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-] (the full separation of the surfaces).
    ratio : float or array_like, default 1.0
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    .. math::

        \frac{F}{2\pi R^* \gamma} = \frac{\cos\theta}{1 + 2.1 S^+ + 10 S^{+2}}, \qquad S^+ = \frac{D}{2}\sqrt{R^*/V}

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A. & Seville, J. P. K. (2000). Capillary bridges between two
       spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    S = 0.5 * D / np.sqrt(V / Rs)
    return Rs * np.cos(theta) / (1.0 + 2.1 * S + 10.0 * S * S)


def willett_full(contact_angle_rad, V, D, ratio=1.0):
    r"""Willett et al. (2000), the full regression of the exact force (their appendix), with Derjaguin's R*.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad] (fitted for 0-50 deg).
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-], > 0 (the regression is in ln S+).
    ratio : float or array_like, default 1.0
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-]; NaN at D = 0.

    Notes
    -----
    .. math::

        \ln\frac{F}{2\pi R^*\gamma} = f_1 - f_2 \exp\left(f_3 \ln S^+ + f_4 \ln^2 S^+\right),
        \qquad S^+ = \frac{D}{2}\sqrt{R^*/V},

    with f1-f4 polynomials in ln(V / R*^3) (cubic or quadratic) whose coefficients are quadratic in theta
    [rad], as the appendix of [1]_ prints them.

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A. & Seville, J. P. K. (2000). Capillary bridges between two
       spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    t, t2 = theta, theta * theta
    L = np.log(V / Rs**3)
    f1 = (
        (-0.44507 + 0.050832 * t - 1.1466 * t2)
        + (-0.1119 - 0.000411 * t - 0.1490 * t2) * L
        + (-0.012101 - 0.0036456 * t - 0.01255 * t2) * L**2
        + (-0.0005 - 0.0003505 * t - 0.00029076 * t2) * L**3
    )
    f2 = (
        (1.9222 - 0.57473 * t - 1.2918 * t2)
        + (-0.0668 - 0.1201 * t - 0.22574 * t2) * L
        + (-0.0013375 - 0.0068988 * t - 0.01137 * t2) * L**2
    )
    f3 = (
        (1.268 - 0.01396 * t - 0.23566 * t2)
        + (0.198 + 0.092 * t - 0.06418 * t2) * L
        + (0.02232 + 0.02238 * t - 0.009853 * t2) * L**2
        + (0.0008585 + 0.001318 * t - 0.00053 * t2) * L**3
    )
    f4 = (
        (-0.010703 + 0.073776 * t - 0.34742 * t2)
        + (0.03345 + 0.04543 * t - 0.09056 * t2) * L
        + (0.0018574 + 0.004456 * t - 0.006257 * t2) * L**2
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        lS = np.log(0.5 * D / np.sqrt(V / Rs))
        out = Rs * np.exp(f1 - f2 * np.exp(f3 * lS + f4 * lS * lS))
    return np.where(D > 0, out, np.nan)


def _immersion(V, D, Rs):
    """Immersion factor q = sqrt(1 + 2 V / (pi R* D^2)) [-]; inf at D = 0.

    Rabinovich et al. (2005), eq. 20: the immersion depth is d = D/2 (q - 1).
    """
    with np.errstate(divide="ignore"):
        return np.sqrt(1.0 + 2.0 * V / (np.pi * Rs * D * D))


def lambert(contact_angle_rad, V, D, ratio=1.0):
    r"""Lambert et al. (2008), eq. 65 (the first term of Rabinovich et al. 2005), with Derjaguin's R*.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-].
    ratio : float or array_like, default 1.0
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    .. math::

        \frac{F}{2\pi R^*\gamma} = \frac{\cos\theta}{1 + D / (2 d)} = \cos\theta\left(1 - \frac{1}{q}\right),
        \quad d = \frac{D}{2}(q - 1),\quad q = \sqrt{1 + \frac{2V}{\pi R^* D^2}}

    (d: the immersion height); cos theta at D = 0.

    References
    ----------
    .. [1] Lambert, P., Chau, A., Delchambre, A. & Régnier, S. (2008). Comparison between two capillary forces
       models. Langmuir 24, 3157-3163. doi:10.1021/la7036444
    .. [2] Rabinovich, Y. I., Esayanur, M. S. & Moudgil, B. M. (2005). Capillary forces between two spheres with a
       fixed volume liquid bridge: theory and experiment. Langmuir 21, 10992-10997. doi:10.1021/la0517639
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    return Rs * np.cos(theta) * (1.0 - 1.0 / _immersion(V, D, Rs))


def rabinovich(contact_angle_rad, V, D, ratio=1.0):
    r"""Rabinovich et al. (2005), eqs. 19, 20 and A3, with Derjaguin's R*.

    The force at the neck with its surface-tension term.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-].
    ratio : float or array_like, default 1.0
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    .. math::

        \frac{F}{2\pi R^*\gamma} = \frac{\cos\theta}{1 + D/(2d)} + \sin\alpha\,\sin(\theta + \alpha),
        \quad \alpha^2 = \frac{D}{R^*}(q - 1)

    (d and q as in :func:`lambert`; alpha the filling angle of the small-angle approximation). At contact
    (D = 0) alpha takes its limit alpha_0 = (2V/(pi R*^3))^(1/4) (the limit of D (q - 1)/R* as D -> 0), so the
    force at contact is the law's own limit, not cos theta.

    References
    ----------
    .. [1] Rabinovich, Y. I., Esayanur, M. S. & Moudgil, B. M. (2005). Capillary forces between two spheres with a
       fixed volume liquid bridge: theory and experiment. Langmuir 21, 10992-10997. doi:10.1021/la0517639
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    q = _immersion(V, D, Rs)
    with np.errstate(invalid="ignore", divide="ignore"):
        # at contact D (q - 1) / R* -> sqrt(2 V / (pi R*^3)): the filling angle of eq. A3 tends to its own limit
        alpha = np.where(D > 0, np.sqrt(D / Rs * (q - 1.0)), (2.0 * V / (np.pi * Rs**3)) ** 0.25)
    return Rs * (np.cos(theta) * (1.0 - 1.0 / q) + np.sin(alpha) * np.sin(theta + alpha))


#: (b1, b2, c1) of the regression shared by Soulié et al. (2006) and Mikami et al. (1998), see
#: `_exponential_regression`, as YADE cites Soulié et al. and as Mikami et al. print them
SOULIE_COEFFICIENTS = (-0.148, -0.0082, 0.0018)
MIKAMI_COEFFICIENTS = (-0.34, -0.019, 0.0042)


def _exponential_regression(theta, Vp, h, coefficients):
    """exp(A h + B) + C, the form Mikami et al. (1998) fitted and Soulié et al. (2006) refitted.

    A = -1.1 V+^-0.53, B = (b1 ln V+ - 0.96) theta^2 + b2 ln V+ + 0.48, C = c1 ln V+ + 0.078, with V+ the volume and h
    the gap over the radius.
    """
    b1, b2, c1 = coefficients
    L = np.log(Vp)
    A = -1.1 * Vp**-0.53
    B = (b1 * L - 0.96) * theta * theta + b2 * L + 0.48
    return np.exp(A * h + B) + (c1 * L + 0.078)


def soulie(contact_angle_rad, V, D, ratio=1.0):
    r"""Soulié et al. (2006): the regression of the exact force between two spheres of radii R1 and R2.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-].
    ratio : float or array_like, default 1.0
        R2 / R1 [-] (spheres only: NaN on a plane).

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    With R the larger radius, V+ = V / R^3 and ln its natural logarithm,

    .. math::

        F = \pi\gamma\sqrt{R_1 R_2}\left[c + \exp\left(a \frac{D}{R} + b\right)\right],\quad
        a = -1.1\,V_+^{-0.53},\quad b = (-0.148 \ln V_+ - 0.96)\,\theta^2 - 0.0082 \ln V_+ + 0.48,\quad
        c = 0.0018 \ln V_+ + 0.078 .

    References
    ----------
    .. [1] Soulié, F., Cherblanc, F., El Youssoufi, M. S. & Saix, C. (2006). Influence of liquid bridges on the
       mechanical behaviour of polydisperse granular materials. Int. J. Numer. Anal. Methods Geomech. 30,
       213-228. doi:10.1002/nag.476
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    with np.errstate(invalid="ignore", divide="ignore"):
        big = np.where(np.isinf(rho), np.nan, np.maximum(rho, 1.0))  # the larger radius / R1
        return 0.5 * np.sqrt(rho) * _exponential_regression(theta, V / big**3, D / big, SOULIE_COEFFICIENTS)


def mikami(contact_angle_rad, V, D, ratio=1.0):
    r"""Mikami, Kamiya & Horio (1998): the regression of the exact force between two equal spheres.

    With Derjaguin's R* for other pairs.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-] (the full separation of the surfaces).
    ratio : float or array_like, default 1.0
        R2 / R1 [-] (spheres only: NaN on a plane).

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    With V+ = V / R*^3, h = D / R* and ln the natural logarithm,

    .. math::

        F = \pi\gamma R^*\left[\exp(A h + B) + C\right],\quad A = -1.1\,V_+^{-0.53},\quad
        B = (-0.34 \ln V_+ - 0.96)\,\theta^2 - 0.019 \ln V_+ + 0.48,\quad C = 0.0042 \ln V_+ + 0.078,

    fitted for equal spheres; the bridge ruptures at h_c = (0.62 theta + 0.99) V+^0.34
    (:func:`mikami_rupture_gap`). Checked against capred's exact bridge (tests/test_bridge_laws.py): within 4 %
    at theta = 0 for V/R^3 1e-4 to 1e-2 and D/R <= 0.05, 10-12 % at V/R^3 = 0.1; its theta^2 term overestimates
    the force for theta > 0 (see the module's notes).

    References
    ----------
    .. [1] Mikami, T., Kamiya, H. & Horio, M. (1998). Numerical simulation of cohesive powder behavior in a
       fluidized bed. Chem. Eng. Sci. 53(10), 1927-1940. doi:10.1016/S0009-2509(97)00325-4
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    with np.errstate(invalid="ignore", divide="ignore"):
        F = 0.5 * Rs * _exponential_regression(theta, V / Rs**3, D / Rs, MIKAMI_COEFFICIENTS)
    return np.where(np.isinf(rho), np.nan, F)


def mikami_rupture_gap(contact_angle_rad, V, ratio=1.0):
    """Mikami et al. (1998): the gap at which the bridge ruptures, D_c / R1 = (0.62 theta + 0.99) V+^0.34 R*/R1.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    ratio : float or array_like, default 1.0
        R2 / R1 [-].

    Returns
    -------
    numpy.ndarray
        D_c / R1 [-] (the full separation).

    References
    ----------
    .. [1] Mikami, T., Kamiya, H. & Horio, M. (1998). Chem. Eng. Sci. 53(10), 1927-1940.
       doi:10.1016/S0009-2509(97)00325-4
    """
    theta, V, _, rho = _args(contact_angle_rad, V, 0.0, ratio)
    Rs = effective_radius(rho)
    return Rs * (0.62 * theta + 0.99) * (V / Rs**3) ** 0.34


def weigert_ripperger(contact_angle_rad, V, D, ratio=1.0):
    r"""Weigert & Ripperger (1999): the toroidal bridge whose filling angle follows the volume by their fit.

    Eqs. 5, 6, 15-17, 21, 22, with Derjaguin's R* as the sphere radius.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle [rad].
    V : float or array_like
        Bridge volume V / R1^3 [-].
    D : float or array_like
        Gap D / R1 [-].
    ratio : float or array_like, default 1.0
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    Notes
    -----
    With d = 2 R*, C_a = 1 + 6 D / d, C_theta = 1 + 1.1 sin(theta),
    sin(beta) = [V / (0.12 C_a C_theta d^3)]^(1/4); the toroidal radii
    r1 = (d (1 - cos beta) + D) / (2 cos(beta + theta)) and r2 = R* sin(beta) + r1 (sin(beta + theta) - 1),
    Delta p = gamma (1/r1 - 1/r2) and

    .. math::

        F = \frac{\pi}{4} d^2 \sin^2\beta\,\Delta p + \pi\gamma d \sin\beta \sin(\beta + \theta).

    References
    ----------
    .. [1] Weigert, T. & Ripperger, S. (1999). Calculation of the liquid bridge volume and bulk saturation from
       the half-filling angle. Part. Part. Syst. Charact. 16, 238-242.
       doi:10.1002/(SICI)1521-4117(199910)16:5<238::AID-PPSC238>3.0.CO;2-E
    """
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    Rs = effective_radius(rho)
    d = 2.0 * Rs
    Ca = 1.0 + 6.0 * D / d
    Ct = 1.0 + 1.1 * np.sin(theta)
    with np.errstate(invalid="ignore", divide="ignore"):
        beta = np.arcsin((V / (0.12 * Ca * Ct * d**3)) ** 0.25)
        r1 = (d * (1.0 - np.cos(beta)) + D) / (2.0 * np.cos(beta + theta))
        r2 = Rs * np.sin(beta) + r1 * (np.sin(beta + theta) - 1.0)
        dp = 1.0 / r1 - 1.0 / r2
        F = 0.25 * np.pi * d * d * np.sin(beta) ** 2 * dp + np.pi * d * np.sin(beta) * np.sin(beta + theta)
    return F / (2.0 * np.pi)


def geometry_of(ratio) -> np.ndarray:
    """Geometry "equal", "unequal" or "plane" of each pair (the key of :attr:`Law.geometries`).

    Parameters
    ----------
    ratio : array_like
        R2 / R1 [-]; ``np.inf`` for a plane.

    Returns
    -------
    numpy.ndarray of str
        The geometry of each pair.

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A. & Seville, J. P. K. (2000). Capillary bridges between two
       spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y (equal spheres, unequal ones through R*)
    """
    rho = np.asarray(ratio, dtype=float)
    return np.where(np.isinf(rho), "plane", np.where(rho == 1.0, "equal", "unequal"))


def law_force(name: str, contact_angle_rad, V, D, ratio=1.0) -> np.ndarray:
    """The force of a registered law, NaN where the law does not apply to the geometry.

    Parameters
    ----------
    name : str
        A key of :data:`LAWS`.
    contact_angle_rad, V, D, ratio : array_like
        Contact angle [rad], V / R1^3, D / R1, R2 / R1 (``inf``: a plane) [-].

    Returns
    -------
    numpy.ndarray
        F / (2 pi R1 gamma) [-].

    References
    ----------
    .. [1] The law's own paper: ``LAWS[name].citation``, doi ``LAWS[name].doi``.
    """
    law = LAWS[name]
    theta, V, D, rho = _args(contact_angle_rad, V, D, ratio)
    F = law.force(theta, V, D, rho)
    return np.where(np.isin(geometry_of(rho), law.geometries), F, np.nan)
