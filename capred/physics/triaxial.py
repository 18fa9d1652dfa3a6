r"""Triaxial failure states and the capillary stress tensor at failure (Prunier et al. 2024).

Pure, vectorised formulas (scalar or ndarray in, same shape out). Compression
is positive; stresses in any consistent unit (capred passes Pa). Principal
stresses are ordered :math:`\sigma_1 \ge \sigma_2 \ge \sigma_3`: in triaxial
compression :math:`\sigma_1` is axial and :math:`\sigma_2 = \sigma_3` radial;
in triaxial extension :math:`\sigma_1 = \sigma_2` are radial and
:math:`\sigma_3` is axial. Capillary components are negative (tensile) in the
unsaturated state [1]_ (eq. 20). Angles are in degrees in every public name
and argument; radians stay inside the functions.

The total stress splits into effective and capillary parts,
:math:`\boldsymbol\sigma = \boldsymbol\sigma' + \boldsymbol\sigma^{cap}`
([1]_, eq. 13); the effective failure criterion is Mohr-Coulomb
(:math:`c'`, :math:`\varphi'`) measured on saturated samples.

References
----------
.. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). A method to
   evaluate the capillary stress tensor at failure in unsaturated soils.
   Eur. J. Environ. Civ. Eng., 1-26. doi:10.1080/19648189.2024.2314099
"""

from __future__ import annotations

from dataclasses import dataclass, field
from dataclasses import replace as dataclasses_replace

import numpy as np

#: Tolerance [deg] on "constant Lode angle" (a group for eq. 50 of [1]) and on
#: "sigma2 = sigma3" / "sigma2 = sigma1" (the compression / extension branch).
#: By eq. 49 and 51 of [1] a Lode angle is a Lode ratio Q = (s1 - s2)/(s1 - s3):
#: theta = atan(sqrt(3) (1 - Q)/(1 + Q)), so |d theta/dQ| = sqrt(3)/(2 (1 - Q + Q^2))
#: lies between sqrt(3)/2 rad (Q = 0 or 1) and 2/sqrt(3) rad (Q = 1/2), i.e.
#: 49.6 to 66.2 deg per unit of Q. One degree is therefore at most
#: Delta Q = 0.020: the sigma1 - sigma2 radius Q (s1 - s3)/2 of the tests of a
#: group differs by at most 2 % of their sigma1 - sigma3 radius, the accuracy of
#: the stresses measured at failure in a (true-)triaxial cell. A tighter tolerance
#: rejects real groups for measurement noise; a looser one lets the sigma1 - sigma2
#: circles leave the common line that defines C_i.
LODE_TOL_DEG = 1.0

#: Relative difference of two principal stresses [-] below which they are equal for the Lode angle: the
#: round-off of the reduction that made them (sigma - u, sigma3 + q: a few units of 2.2e-16 of the largest
#: stress; 1e-12 leaves a margin of 4500 ulps), far below any measured difference (a 1 kPa cell read to
#: 0.1 kPa is 1e-4 of it). Exact compression tests then print 0 deg, not 5.69e-07 deg.
LODE_ROUND_OFF = 1e-12

_BRANCHES = ("compression", "extension")


def _axisymmetric_branch(branch):
    """Boolean array (or scalar) 'is extension'; raises on anything but the two axisymmetric branches."""
    b = np.asarray(branch)
    bad = ~np.isin(b, _BRANCHES)
    if np.any(bad):
        raise ValueError(
            f"branch must be 'compression' or 'extension' (the bounds of Prunier et al. 2024, "
            f"section 4, are for axisymmetric tests), got {np.unique(b[bad]).tolist()}"
        )
    return b == "extension"


def mean_stress(sigma1, sigma3, sigma2=None):
    r"""Mean stress :math:`p` of a principal stress state.

    Parameters
    ----------
    sigma1 : numeric
        Major principal stress :math:`\sigma_1` [Pa].
    sigma3 : numeric
        Minor principal stress :math:`\sigma_3` [Pa].
    sigma2 : numeric, optional
        Intermediate principal stress :math:`\sigma_2` [Pa]; ``None`` means
        :math:`\sigma_2 = \sigma_3` (triaxial compression).

    Returns
    -------
    numeric
        Mean stress :math:`p` [Pa].

    Notes
    -----
    .. math::

       p = \frac{\sigma_1 + \sigma_2 + \sigma_3}{3} = \frac{I_1}{3}

    with :math:`I_1 = \mathrm{tr}\,\boldsymbol\sigma` ([1]_, eq. 52).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 18 and 52.
    """
    s2 = sigma3 if sigma2 is None else sigma2
    return (np.asarray(sigma1, float) + np.asarray(s2, float) + np.asarray(sigma3, float)) / 3.0


def deviator(sigma1, sigma3):
    r"""Deviator stress :math:`q = \sigma_1 - \sigma_3`.

    Parameters
    ----------
    sigma1 : numeric
        Major principal stress [Pa].
    sigma3 : numeric
        Minor principal stress [Pa].

    Returns
    -------
    numeric
        Deviator stress :math:`q` [Pa].

    Notes
    -----
    .. math::

       q = \sigma_1 - \sigma_3

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 16.
    """
    return np.asarray(sigma1, float) - np.asarray(sigma3, float)


def lode_angle_deg(sigma1, sigma2, sigma3):
    r"""Lode angle :math:`\theta` of a principal stress state, 0 deg in compression, 60 deg in extension.

    Parameters
    ----------
    sigma1, sigma2, sigma3 : numeric
        Principal stresses [Pa] (any order; the result does not depend on it).

    Returns
    -------
    numeric
        Lode angle :math:`\theta` [deg], in [0, 60]; 0 for triaxial
        compression (:math:`\sigma_2 = \sigma_3`), 60 for triaxial extension
        (:math:`\sigma_2 = \sigma_1`), NaN for an isotropic state. Two
        stresses within ``LODE_ROUND_OFF`` (1e-12) of the largest magnitude
        count as equal: exact compression gives 0 exactly, exact extension 60.

    Notes
    -----
    With the deviatoric stress :math:`\mathbf s = \boldsymbol\sigma - I_1/3\,\mathbf I`,
    :math:`J_2 = \mathrm{tr}(\mathbf s^2)`, :math:`J_3 = \mathrm{tr}(\mathbf s^3)`
    ([1]_, eq. 52-53):

    .. math::

       \cos 3\theta = \frac{\sqrt 6\, J_3}{J_2^{3/2}}
       = \frac{\sqrt 6\,(s_1^3 + s_2^3 + s_3^3)}{(s_1^2 + s_2^2 + s_3^2)^{3/2}}

    For ordered stresses it equals
    :math:`\tan\theta = \sqrt 3 (1 - Q)/(1 + Q)` with the Lode ratio
    :math:`Q = (\sigma_1 - \sigma_2)/(\sigma_1 - \sigma_3)` (eq. 49, 51).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 2,
       eq. 51-53.
    """
    s = np.stack(np.broadcast_arrays(*(np.asarray(x, float) for x in (sigma1, sigma2, sigma3))))
    s1, s2, s3 = -np.sort(-s, axis=0)  # ordered, sigma1 >= sigma2 >= sigma3
    with np.errstate(invalid="ignore", divide="ignore"):
        q = (s1 - s2) / (s1 - s3)  # Lode ratio (eq. 49)
        # the arctan form, not arccos(cos 3 theta): arccos is ill-conditioned at 0 and 60 deg, where a
        # round-off of 1e-16 in cos 3 theta becomes 4e-7 deg
        theta = np.degrees(np.arctan2(np.sqrt(3.0) * (1.0 - q), 1.0 + q))
    # round-off snapped: sigma2 within ROUND_OFF of sigma3 (sigma1) is compression (extension) exactly
    tol = LODE_ROUND_OFF * np.max(np.abs(s), axis=0)
    theta = np.where(s2 - s3 <= tol, 0.0, np.where(s1 - s2 <= tol, 60.0, theta))
    theta = np.where(s1 - s3 > tol, theta, np.nan)  # isotropic: no Lode angle
    return theta[()] if theta.ndim == 0 else theta


#: Former name of :func:`lode_angle_deg` (same function), kept for existing callers.
lode_angle = lode_angle_deg


def lode_ratio(sigma1, sigma2, sigma3):
    r"""Lode ratio :math:`Q = (\sigma_1 - \sigma_2)/(\sigma_1 - \sigma_3)`; equal Q means equal Lode angle.

    Parameters
    ----------
    sigma1, sigma2, sigma3 : numeric
        Ordered principal stresses :math:`\sigma_1 \ge \sigma_2 \ge \sigma_3` [Pa].

    Returns
    -------
    numeric
        Lode ratio :math:`Q` [-], 1 in compression, 0 in extension.

    Notes
    -----
    .. math::

       Q = \frac{\sigma_1 - \sigma_2}{\sigma_1 - \sigma_3}, \qquad
       Q^A = Q^B \Leftrightarrow \theta^A = \theta^B

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 49, 51, 54.
    """
    return (np.asarray(sigma1, float) - sigma2) / (np.asarray(sigma1, float) - sigma3)


def lode_angle_from_ratio_deg(lode_ratio):
    r"""Lode angle of the stress states of Lode ratio :math:`Q` (the map behind eq. 49 of [1]_).

    Parameters
    ----------
    lode_ratio : numeric
        :math:`Q = (\sigma_1 - \sigma_2)/(\sigma_1 - \sigma_3)` [-], in [0, 1].

    Returns
    -------
    numeric
        Lode angle :math:`\theta` [deg], in [0, 60].

    Notes
    -----
    Eq. 56 of [1]_ gives the deviatoric stresses
    :math:`s \propto (1 + Q,\ 1 - 2Q,\ Q - 2)`; put in eq. 53 this is

    .. math::

       \tan\theta = \frac{\sqrt 3\,(1 - Q)}{1 + Q}, \qquad
       \left|\frac{d\theta}{dQ}\right| = \frac{\sqrt 3}{2\,(1 - Q + Q^2)}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 2,
       eq. 53-57.
    """
    Q = np.asarray(lode_ratio, float)
    return np.degrees(np.arctan2(np.sqrt(3.0) * (1.0 - Q), 1.0 + Q))


def lode_branch(sigma1, sigma2, sigma3, tol_deg=LODE_TOL_DEG):
    r"""Branch of a test: ``compression`` (σ2 = σ3), ``extension`` (σ2 = σ1) or ``general``.

    Parameters
    ----------
    sigma1, sigma2, sigma3 : numeric
        Principal stresses at failure [Pa].
    tol_deg : float, default :data:`LODE_TOL_DEG`
        Tolerance on the Lode angle [deg]: compression when
        :math:`\theta \le` ``tol_deg``, extension when
        :math:`\theta \ge 60 -` ``tol_deg`` (see :data:`LODE_TOL_DEG` for
        its justification from eq. 49).

    Returns
    -------
    str or ndarray of str
        ``"compression"``, ``"extension"`` or ``"general"`` per state
        (``"general"`` for an isotropic state too).

    Notes
    -----
    The Lode angle is :func:`lode_angle_deg` ([1]_, eq. 53):

    .. math::

       \text{compression: } \theta \le \Delta\theta, \qquad
       \text{extension: } \theta \ge 60° - \Delta\theta

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 49, 53.
    """
    theta = lode_angle_deg(sigma1, sigma2, sigma3)
    out = np.where(theta <= tol_deg, "compression", np.where(theta >= 60.0 - tol_deg, "extension", "general"))
    return out.item() if out.ndim == 0 else out


def passive_coefficient(phi_deg):
    r"""Passive earth-pressure coefficient :math:`K_p` of a Mohr-Coulomb material.

    Parameters
    ----------
    phi_deg : numeric
        Friction angle :math:`\varphi` [deg].

    Returns
    -------
    numeric
        :math:`K_p` [-].

    Notes
    -----
    .. math::

       K_p = \frac{1 + \sin\varphi}{1 - \sin\varphi}

    the slope of the criterion in the principal-stress plane ([1]_, eq. 25).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    s = np.sin(np.radians(phi_deg))
    return (1.0 + s) / (1.0 - s)


def envelope_qp(c, phi_deg, branch="compression"):
    r"""Mohr-Coulomb criterion in the :math:`(p, q)` plane: :math:`q = M p + k`, compression or extension form.

    Parameters
    ----------
    c : numeric
        Cohesion :math:`c` [Pa].
    phi_deg : numeric
        Friction angle :math:`\varphi` [deg].
    branch : {"compression", "extension"} or array of them, default "compression"
        Triaxial compression (:math:`\sigma_2 = \sigma_3`,
        :math:`p = (\sigma_1 + 2\sigma_3)/3`) or extension
        (:math:`\sigma_2 = \sigma_1`, :math:`p = (2\sigma_1 + \sigma_3)/3`).

    Returns
    -------
    M : numeric
        Slope [-].
    k : numeric
        Intercept at :math:`p = 0` [Pa].

    Notes
    -----
    With :math:`q = \sigma_1 - \sigma_3` the criterion
    :math:`\sigma_1 - \sigma_3 = (\sigma_1 + \sigma_3)\sin\varphi + 2c\cos\varphi`
    ([1]_, eq. 38) reads

    .. math::

       M_c = \frac{6\sin\varphi}{3 - \sin\varphi},\quad
       k_c = \frac{6c\cos\varphi}{3 - \sin\varphi}
       \qquad\text{(compression)}

       M_e = \frac{6\sin\varphi}{3 + \sin\varphi},\quad
       k_e = \frac{6c\cos\varphi}{3 + \sin\varphi}
       \qquad\text{(extension)}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 15-17, 38
       (Fig. 3, 5).
    """
    ext = _axisymmetric_branch(branch)
    s = np.sin(np.radians(phi_deg))
    co = np.cos(np.radians(phi_deg))
    den = np.where(ext, 3.0 + s, 3.0 - s)
    M, k = 6.0 * s / den, 6.0 * np.asarray(c, float) * co / den
    if np.ndim(M) == 0 and np.ndim(k) == 0:
        return float(M), float(k)
    return M, k


def sigma1_at_failure(sigma3_eff, c, phi_deg):
    r"""Major effective principal stress at failure for a given minor one (Mohr-Coulomb).

    Parameters
    ----------
    sigma3_eff : numeric
        Minor effective principal stress :math:`\sigma'_3` [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].

    Returns
    -------
    numeric
        :math:`\sigma'_1` at failure [Pa].

    Notes
    -----
    .. math::

       \sigma'_1 = \frac{1 + \sin\varphi'}{1 - \sin\varphi'}\sigma'_3
       + \frac{2c'\cos\varphi'}{1 - \sin\varphi'}
       = K_p\sigma'_3 + 2c'\sqrt{K_p}

    independent of :math:`\sigma_2` (compression or extension alike).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    kp = passive_coefficient(phi_deg)
    return kp * np.asarray(sigma3_eff, float) + 2.0 * c * np.sqrt(kp)


def sigma3_at_failure(sigma1_eff, c, phi_deg):
    r"""Minor effective principal stress at failure for a given major one (eq. 25 inverted).

    Parameters
    ----------
    sigma1_eff : numeric
        Major effective principal stress :math:`\sigma'_1` [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].

    Returns
    -------
    numeric
        :math:`\sigma'_3` at failure [Pa].

    Notes
    -----
    .. math::

       \sigma'_3 = \frac{\sigma'_1 - 2c'\sqrt{K_p}}{K_p}
       = \sigma'_1\frac{1 - \sin\varphi'}{1 + \sin\varphi'}
       - \frac{2c'\cos\varphi'}{1 + \sin\varphi'}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25, 27.
    """
    kp = passive_coefficient(phi_deg)
    return (np.asarray(sigma1_eff, float) - 2.0 * c * np.sqrt(kp)) / kp


#: Stress paths of a drained extension test from the isotropic state, by their slope dq/dp in the (p, q) plane
#: (q = sigma1 - sigma3 > 0): the axial stress falls at constant cell pressure (slope -3, the default) or the
#: cell pressure rises at constant axial stress (slope 3/2).
from ..spec.triaxial import EXTENSION_PATHS  # noqa: E402, F401 (declared once in spec: the option takes it)


def extension_failure_on_path(p0_eff, c, phi_deg, slope=-3.0):
    r"""Image point :math:`(p', q')` where a drained extension path from :math:`(p'_0, 0)` meets the envelope.

    Parameters
    ----------
    p0_eff : numeric
        Initial isotropic effective stress :math:`p'_0` [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`arphi'` [deg].
    slope : float, default -3
        Slope :math:`\eta = dq/dp` of the path [-]: -3 for axial unloading at constant cell pressure, 3/2
        for radial loading at constant axial stress (:data:`EXTENSION_PATHS`); not 0 and not equal to
        :math:`M_e`.

    Returns
    -------
    p_prime, q_prime : numeric
        Mean effective stress and deviator at failure [Pa].

    Notes
    -----
    The path :math:`p' = p'_0 + q'/\eta` meets the extension envelope :math:`q' = M_e p' + k_e`
    (:func:`envelope_qp`, eq. 25 in extension) at

    .. math::

       q' = rac{M_e p'_0 + k_e}{1 - M_e/\eta}

    With :math:`\eta = -3` it is :math:`q' = p'_0 - (p'_0 - 2c'\sqrt{K_p})/K_p` (:math:`\sigma'_1 =
    \sigma'_2 = p'_0`).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    M, k = envelope_qp(c, phi_deg, "extension")
    if slope == 0 or slope == M:
        raise ValueError(f"an extension path of slope {slope:g} never meets the envelope (slope {M:.4g})")
    p0 = np.asarray(p0_eff, float)
    q = (M * p0 + k) / (1.0 - M / slope)
    return p0 + q / slope, q


def drained_strength(p0_eff, c, phi_deg, branch="compression", extension_slope=-3.0):
    r"""Deviator at failure :math:`q'_{sat}` of a drained test from the isotropic state :math:`p'_0`.

    Parameters
    ----------
    p0_eff : numeric
        Initial isotropic effective stress :math:`p'_0` [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].
    branch : {"compression", "extension"} or array of them, default "compression"
        The cell (radial) pressure is held at :math:`p'_0` in both: in
        compression the axial stress rises (:math:`\sigma'_3 = p'_0`, slope
        3 in the :math:`(p, q)` plane), in extension it falls
        (:math:`\sigma'_1 = \sigma'_2 = p'_0`, slope -3) unless ``extension_slope`` says otherwise.
    extension_slope : float, default -3
        Slope dq/dp of the extension path (:func:`extension_failure_on_path`) [-].

    Returns
    -------
    numeric
        :math:`q'_{sat} = \sigma'_1 - \sigma'_3` at failure [Pa].

    Notes
    -----
    .. math::

       q'_{sat} = (K_p - 1)\,p'_0 + 2c'\sqrt{K_p} \quad\text{(compression)},
       \qquad
       q'_{sat} = p'_0 - \frac{p'_0 - 2c'\sqrt{K_p}}{K_p} \quad\text{(extension)}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25 and
       section 5.4 (Table 3, :math:`q'^{sat}`).
    """
    ext = _axisymmetric_branch(branch)
    p0 = np.asarray(p0_eff, float)
    comp = sigma1_at_failure(p0, c, phi_deg) - p0
    if not np.any(ext):
        return comp
    return np.where(ext, extension_failure_on_path(p0, c, phi_deg, extension_slope)[1], comp)


@dataclass
class Bound:
    r"""A capillary stress tensor at failure and its effective image point (arrays, one value per test).

    Attributes
    ----------
    sigma1_cap : ndarray
        Capillary component along the major principal direction [Pa].
    sigma3_cap : ndarray
        Capillary component along the minor principal direction [Pa].
    p_prime : ndarray
        Mean effective stress of the image point on the envelope [Pa].
    q_prime : ndarray
        Effective deviator of the image point, :math:`\sigma'_1 - \sigma'_3` [Pa].
    sigma2_cap : ndarray or None
        Capillary component along the intermediate direction [Pa]: the
        radial component, equal to ``sigma3_cap`` in compression and to
        ``sigma1_cap`` in extension; ``None`` means ``sigma3_cap``.
    """

    sigma1_cap: np.ndarray
    sigma3_cap: np.ndarray
    p_prime: np.ndarray
    q_prime: np.ndarray
    sigma2_cap: np.ndarray | None = None

    @property
    def p_cap(self):
        """Capillary pressure, the mean of the three components [Pa] (eq. 18 of Prunier et al. 2024)."""
        s2 = self.sigma3_cap if self.sigma2_cap is None else self.sigma2_cap
        return (self.sigma1_cap + s2 + self.sigma3_cap) / 3.0

    @property
    def q_cap(self):
        """Capillary deviator sigma1_cap - sigma3_cap [Pa] (eq. 21 of Prunier et al. 2024)."""
        return self.sigma1_cap - self.sigma3_cap

    @property
    def positive(self):
        """True where a component is > 0, against eq. (18)/(20) of [1] (1e-9 relative slack)."""
        scale = 1e-9 * np.maximum(np.abs(self.p_prime), 1.0)
        return (self.sigma1_cap > scale) | (self.sigma3_cap > scale)


def _from_effective(sigma1, sigma3, s1_eff, s3_eff, ext=False) -> Bound:
    s1_cap = np.asarray(sigma1, float) - s1_eff
    s3_cap = np.asarray(sigma3, float) - s3_eff
    s2_eff = np.where(ext, s1_eff, s3_eff)
    return Bound(
        sigma1_cap=s1_cap,
        sigma3_cap=s3_cap,
        p_prime=(s1_eff + s2_eff + s3_eff) / 3.0,
        q_prime=s1_eff - s3_eff,
        sigma2_cap=np.where(ext, s1_cap, s3_cap),
    )


def spherical_bound(sigma1, sigma3, c, phi_deg, branch="compression") -> Bound:
    r"""Spherical capillary tensor at failure, the conservative upper bound.

    Parameters
    ----------
    sigma1 : numeric
        Major total principal stress at failure [Pa].
    sigma3 : numeric
        Minor total principal stress at failure [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].
    branch : {"compression", "extension"} or array of them, default "compression"
        Triaxial compression (:math:`\sigma_2 = \sigma_3`) or extension
        (:math:`\sigma_2 = \sigma_1`): selects :math:`p` and the form of the
        envelope (:func:`envelope_qp`).

    Returns
    -------
    Bound
        :math:`\sigma^{cap}` in every direction and the image point
        :math:`(p', q')` [Pa].

    Notes
    -----
    :math:`q' = q` (eq. 16) and the image point is the horizontal projection
    of :math:`(p, q)` on the envelope of the test's branch:

    .. math::

       p' = \frac{q - k}{M}, \qquad \sigma^{cap} = p - p'

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 15-17
       (Fig. 3), Table 2.
    """
    ext = _axisymmetric_branch(branch)
    q = deviator(sigma1, sigma3)
    M, k = envelope_qp(c, phi_deg, branch)
    p_eff = (q - k) / M
    p = np.where(ext, mean_stress(sigma1, sigma3, sigma1), mean_stress(sigma1, sigma3))
    cap = p - p_eff
    s3_eff = np.asarray(sigma3, float) - cap
    return _from_effective(sigma1, sigma3, s3_eff + q, s3_eff, ext)


def lower_bound(sigma1, sigma3, c, phi_deg, branch="compression") -> Bound:
    r"""Lower bound of the capillary tensor: :math:`\sigma_1^{cap} = 0`, the smallest :math:`q'`.

    Parameters
    ----------
    sigma1 : numeric
        Major total principal stress at failure [Pa].
    sigma3 : numeric
        Minor total principal stress at failure [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].
    branch : {"compression", "extension"} or array of them, default "compression"
        In extension the major direction is radial, so
        :math:`\sigma_2^{cap} = \sigma_1^{cap} = 0`; the components in the
        principal directions are otherwise the same, only :math:`p'` differs.

    Returns
    -------
    Bound
        Capillary components and the image point :math:`(p', q')` [Pa].

    Notes
    -----
    With every component :math:`\le 0` (eq. 20), :math:`q^{cap}` is largest
    for :math:`\sigma_1^{cap} = 0` (eq. 24), and the effective state
    :math:`(\sigma_1, \sigma_3 - \sigma_3^{cap})` on the envelope gives

    .. math::

       \sigma_{3,LB}^{cap} = \sigma_3 + \frac{2c'\cos\varphi'}{1 + \sin\varphi'}
       - \sigma_1\frac{1 - \sin\varphi'}{1 + \sin\varphi'}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 20-27,
       Table 3 (LB).
    """
    ext = _axisymmetric_branch(branch)
    s = np.sin(np.radians(phi_deg))
    co = np.cos(np.radians(phi_deg))
    s1 = np.asarray(sigma1, float)
    s3_cap = np.asarray(sigma3, float) + 2.0 * c * co / (1.0 + s) - s1 * (1.0 - s) / (1.0 + s)
    return _from_effective(s1, sigma3, s1, np.asarray(sigma3, float) - s3_cap, ext)


def edtp_bound(sigma1, sigma3, p0, s0, c, phi_deg, branch="compression", extension_slope=-3.0) -> Bound:
    r"""Upper bound "EDTP": the effective stress path is a drained triaxial path from :math:`p'_0 = p_0 + s_0`.

    Parameters
    ----------
    sigma1 : numeric
        Major total principal stress at failure [Pa].
    sigma3 : numeric
        Minor total principal stress at failure [Pa].
    p0 : numeric
        Total isotropic stress at the end of the isotropic compression [Pa].
    s0 : numeric
        Initial suction, the bound of :math:`-p_0^{cap}` [Pa].
    c : numeric
        Effective cohesion :math:`c'` [Pa].
    phi_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].
    branch : {"compression", "extension"} or array of them, default "compression"
        The effective cell (radial) stress stays at :math:`p'_0`: in
        compression :math:`\sigma'_3 = p'_0` (slope 3 in :math:`(p, q)`, the
        paper's path); in extension :math:`\sigma'_1 = \sigma'_2 = p'_0` and
        the axial stress falls (slope -3), unless ``extension_slope`` says otherwise.
    extension_slope : float, default -3
        Slope dq/dp of the extension path (:func:`extension_failure_on_path`) [-].

    Returns
    -------
    Bound
        Capillary components and the image point :math:`(p', q')` [Pa].

    Notes
    -----
    .. math::

       p'_0 = p_0 - p_0^{cap} = p_0 + s_0, \qquad
       \sigma'_1 = K_p p'_0 + 2c'\sqrt{K_p}\ \text{(compression)}, \qquad
       \sigma'_3 = \frac{p'_0 - 2c'\sqrt{K_p}}{K_p}\ \text{(extension)}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, section 4.2
       (Fig. 5, 17), eq. 25.
    """
    ext = _axisymmetric_branch(branch)
    p0_eff = np.asarray(p0, float) + np.asarray(s0, float)
    pe, qe = extension_failure_on_path(p0_eff, c, phi_deg, extension_slope)
    s1_eff = np.where(ext, pe + qe / 3.0, sigma1_at_failure(p0_eff, c, phi_deg))  # extension: sigma'1 = sigma'2
    s3_eff = np.where(ext, pe - 2.0 * qe / 3.0, p0_eff)
    return _from_effective(sigma1, sigma3, s1_eff, s3_eff, ext)


def envelope_from_principal_fit(slope, intercept):
    r"""Cohesion and friction angle from a straight line :math:`\sigma_1 = K_p\sigma_3 + b`.

    Parameters
    ----------
    slope : numeric
        :math:`K_p` [-], > 1.
    intercept : numeric
        :math:`b = 2c\sqrt{K_p}` [Pa].

    Returns
    -------
    c : numeric
        Cohesion [Pa].
    phi_deg : numeric
        Friction angle [deg].

    Notes
    -----
    Inverse of eq. 25:

    .. math::

       \varphi = \arcsin\frac{K_p - 1}{K_p + 1}, \qquad c = \frac{b}{2\sqrt{K_p}}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    phi = np.degrees(np.arcsin((slope - 1.0) / (slope + 1.0)))
    c = intercept / (2.0 * np.sqrt(slope))
    return c, phi


def spherical_group_cap(C_apparent, c_eff, phi_eff_deg):
    r"""Spherical capillary tensor shared by a group of tests, from the apparent cohesion.

    Parameters
    ----------
    C_apparent : numeric
        Apparent (total-stress) cohesion :math:`C` of the group [Pa].
    c_eff : numeric
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : numeric
        Effective friction angle :math:`\varphi'` [deg] (= the apparent one, eq. 35).

    Returns
    -------
    numeric
        :math:`\sigma^{cap}` [Pa].

    Notes
    -----
    .. math::

       \sigma^{cap} = -\frac{C - C'}{\tan\varphi'}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       eq. 32-37.
    """
    return -(C_apparent - c_eff) / np.tan(np.radians(phi_eff_deg))


def axisymmetric_group_cap(C_apparent, C_fictive, c_eff, phi_eff_deg):
    r"""Axisymmetric capillary tensor shared by a group, from the apparent, fictive and effective cohesions.

    Parameters
    ----------
    C_apparent : numeric
        Cohesion :math:`C` of the line (slope :math:`\sin\varphi'` in
        :math:`(s, t)`) through the unsaturated Mohr circles [Pa].
    C_fictive : numeric
        Cohesion :math:`C''` of the parallel line through the fictive circles
        (:func:`fictive_state`) [Pa].
    c_eff : numeric
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].

    Returns
    -------
    sigma1_cap : numeric
        Major capillary component [Pa].
    sigma3_cap : numeric
        Minor capillary component [Pa].

    Notes
    -----
    .. math::

       \frac{\sigma_1^{cap} + \sigma_3^{cap}}{2} = -\frac{C'' - C'}{\tan\varphi'},
       \qquad
       \frac{\sigma_1^{cap} - \sigma_3^{cap}}{2} = (C - C'')\cos\varphi'

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       eq. 44-48.
    """
    phi = np.radians(phi_eff_deg)
    mean = -(C_fictive - c_eff) / np.tan(phi)
    half = (C_apparent - C_fictive) * np.cos(phi)
    return mean + half, mean - half


def fictive_cohesion_lower(C_apparent, c_eff, phi_eff_deg):
    r"""Fictive cohesion :math:`C''` that closes eq. 48 under the lower-bound hypothesis :math:`\sigma_1^{cap} = 0`.

    For groups without paired saturated tests, eq. 48 has one equation too
    few; this closure takes the lower bound's :math:`\sigma_1^{cap} = 0` (eq. 24).

    Parameters
    ----------
    C_apparent : numeric
        Apparent cohesion :math:`C` [Pa].
    c_eff : numeric
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].

    Returns
    -------
    numeric
        :math:`C''` [Pa].

    Notes
    -----
    From :math:`(C'' - C')/\tan\varphi' = (C - C'')\cos\varphi'`:

    .. math::

       C'' = \frac{C\cos\varphi' + C'/\tan\varphi'}{\cos\varphi' + 1/\tan\varphi'}

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 24 and 48.
    """
    phi = np.radians(phi_eff_deg)
    return (C_apparent * np.cos(phi) + c_eff / np.tan(phi)) / (np.cos(phi) + 1.0 / np.tan(phi))


def true_triaxial_group_cap(C_apparent, C_fictive, Ci_apparent, Ci_fictive, c_eff, phi_eff_deg, phi_i_deg=None):
    r"""True-triaxial capillary tensor at constant Lode angle, from the cohesions of eq. 50.

    Parameters
    ----------
    C_apparent, C_fictive : numeric
        :math:`C`, :math:`C''` of the :math:`\sigma_1`-:math:`\sigma_3`
        circles (see :func:`axisymmetric_group_cap`) [Pa].
    Ci_apparent, Ci_fictive : numeric
        Intermediate cohesions :math:`C_i`, :math:`C_i''` of the lines through
        the unsaturated and fictive :math:`\sigma_1`-:math:`\sigma_2` circles [Pa].
    c_eff : numeric
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : numeric
        Effective friction angle :math:`\varphi'` [deg].
    phi_i_deg : numeric, optional
        Friction angle :math:`\varphi_i` of those lines [deg]; ``None`` takes
        :math:`\varphi'` as the paper writes it (see Notes).

    Returns
    -------
    sigma1_cap, sigma2_cap, sigma3_cap : numeric
        Capillary components [Pa].

    Notes
    -----
    .. math::

       \frac{\sigma_1^{cap} + \sigma_3^{cap}}{2} = -\frac{C'' - C'}{\tan\varphi'},\quad
       \frac{\sigma_1^{cap} - \sigma_3^{cap}}{2} = (C - C'')\cos\varphi',\quad
       \frac{\sigma_1^{cap} - \sigma_2^{cap}}{2} = (C_i - C_i'')\cos\varphi_i

    The paper writes :math:`\cos\varphi'` in the third line. At a constant
    Lode ratio :math:`Q` the :math:`\sigma_1`-:math:`\sigma_2` circles
    (radius :math:`Q t`, centre :math:`s + (1 - Q)t`) of circles on
    :math:`t = s\sin\varphi' + C\cos\varphi'` lie on a line of slope
    :math:`\sin\varphi_i = Q\sin\varphi'/(1 + (1 - Q)\sin\varphi')`, so the
    third line holds with :math:`\cos\varphi_i` when :math:`C_i` is the
    cohesion of that line (:func:`intermediate_friction_angle_deg`).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       eq. 49-50 (Fig. 22).
    """
    s1, s3 = axisymmetric_group_cap(C_apparent, C_fictive, c_eff, phi_eff_deg)
    phi_i = phi_eff_deg if phi_i_deg is None else phi_i_deg
    s2 = s1 - 2.0 * (Ci_apparent - Ci_fictive) * np.cos(np.radians(phi_i))
    return s1, s2, s3


# --- Appendix 1 on data: the fictive state and the group regressions ---------------------------


def fictive_state(sigma1, sigma3, sigma1_sat, sigma3_sat):
    r"""Fictive state :math:`\sigma''`: the unsaturated Mohr circle's centre with the saturated circle's radius.

    Parameters
    ----------
    sigma1, sigma3 : numeric
        Total principal stresses at failure of the unsaturated test [Pa].
    sigma1_sat, sigma3_sat : numeric
        Effective principal stresses at failure of its paired saturated test
        (the constitutively comparable state) [Pa].

    Returns
    -------
    sigma1_fictive, sigma3_fictive : numeric
        :math:`\sigma''_1`, :math:`\sigma''_3` [Pa].

    Notes
    -----
    With :math:`s = (\sigma_1 + \sigma_3)/2` and
    :math:`t' = (\sigma'_1 - \sigma'_3)/2`:

    .. math::

       \sigma''_1 = s + t', \qquad \sigma''_3 = s - t'

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       section 7.2 (Fig. 21), eq. 44.
    """
    s = (np.asarray(sigma1, float) + np.asarray(sigma3, float)) / 2.0
    t_sat = (np.asarray(sigma1_sat, float) - np.asarray(sigma3_sat, float)) / 2.0
    return s + t_sat, s - t_sat


def circle_cohesion(sigma_major, sigma_minor, phi_deg):
    r"""Cohesion of the line of friction angle :math:`\varphi` through (tangent to) one Mohr circle.

    Parameters
    ----------
    sigma_major, sigma_minor : numeric
        The two principal stresses spanning the circle [Pa].
    phi_deg : numeric
        Friction angle of the line [deg].

    Returns
    -------
    numeric
        Cohesion :math:`C` [Pa].

    Notes
    -----
    With :math:`s = (\sigma_a + \sigma_b)/2`, :math:`t = (\sigma_a - \sigma_b)/2`
    and the criterion in the :math:`(s, t)` plane ([1]_, eq. 38):

    .. math::

       t = s\sin\varphi + C\cos\varphi \;\Rightarrow\;
       C = \frac{t - s\sin\varphi}{\cos\varphi}

    Over a group, the least-squares intercept of lines of fixed slope is the
    mean of these values.

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, eq. 38.
    """
    phi = np.radians(phi_deg)
    a, b = np.asarray(sigma_major, float), np.asarray(sigma_minor, float)
    return ((a - b) / 2.0 - (a + b) / 2.0 * np.sin(phi)) / np.cos(phi)


def intermediate_friction_angle_deg(lode_ratio, phi_deg):
    r"""Friction angle :math:`\varphi_i` of the line through the σ1-σ2 circles at constant Lode ratio.

    Parameters
    ----------
    lode_ratio : numeric
        :math:`Q = (\sigma_1 - \sigma_2)/(\sigma_1 - \sigma_3)` [-], in (0, 1].
    phi_deg : numeric
        Friction angle :math:`\varphi` of the :math:`\sigma_1`-:math:`\sigma_3`
        envelope [deg].

    Returns
    -------
    numeric
        :math:`\varphi_i` [deg]; :math:`\varphi_i = \varphi` only for
        :math:`Q = 1`.

    Notes
    -----
    The :math:`\sigma_1`-:math:`\sigma_2` circle of a circle :math:`(s, t)`
    has radius :math:`t_i = Q t` and centre :math:`s_i = s + (1 - Q)t`; along
    :math:`t = s\sin\varphi + C\cos\varphi` both are linear in :math:`s`:

    .. math::

       \sin\varphi_i = \frac{dt_i}{ds_i} = \frac{Q\sin\varphi}{1 + (1 - Q)\sin\varphi}

    (the envelope "with an expansion factor" of section 7.3 of [1]_).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, section 7.3,
       eq. 49-50 (Fig. 22).
    """
    Q = np.asarray(lode_ratio, float)
    s = np.sin(np.radians(phi_deg))
    return np.degrees(np.arcsin(Q * s / (1.0 + (1.0 - Q) * s)))


@dataclass
class GroupTensor:
    r"""The capillary tensor shared by a group of unsaturated tests (eq. 48 or 50 of Prunier et al. 2024).

    Every stress in Pa, every angle in degrees. Standard errors come from the
    scatter of the tests about the group's lines (least squares with the slope
    fixed by eq. 43); they are 0 for an exact group and NaN when ``dof`` = 0.

    Attributes
    ----------
    n : int
        Number of tests in the group.
    dof : int
        Degrees of freedom of the standard errors, ``n - 1``.
    branch : str
        ``"compression"``, ``"extension"`` or ``"general"`` (eq. 50).
    sigma1_cap, sigma2_cap, sigma3_cap : float
        Capillary components along the major, intermediate and minor
        principal directions [Pa]. In compression ``sigma2_cap`` =
        ``sigma3_cap`` (radial), in extension = ``sigma1_cap``.
    sigma1_cap_se, sigma2_cap_se, sigma3_cap_se : float
        Their standard errors [Pa].
    C_apparent, C_apparent_se : float
        Cohesion :math:`C` of the line of slope :math:`\sin\varphi'` through
        the unsaturated circles, and its standard error [Pa].
    C_fictive, C_fictive_se : float
        Cohesion :math:`C''` of the line through the fictive circles [Pa].
    Ci_apparent, Ci_fictive : float
        Intermediate cohesions :math:`C_i`, :math:`C_i''` of the
        :math:`\sigma_1`-:math:`\sigma_2` circles [Pa]; NaN for eq. 48.
    phi_i_deg : float
        Friction angle of the :math:`\sigma_1`-:math:`\sigma_2` lines [deg];
        NaN for eq. 48.
    phi_apparent_deg, phi_apparent_se_deg : float
        Friction angle of the free least-squares line
        :math:`\sigma_1 = K\sigma_3 + b` through the unsaturated failure
        states, and its standard error [deg]: eq. 48 presumes it equals
        :math:`\varphi'` (eq. 43). NaN when the tests share one
        :math:`\sigma_3` (and the error when ``n`` < 3).
    lode_angle_deg : ndarray
        Lode angle of each test [deg] (eq. 53).
    per_test : ndarray, shape (n, 3)
        Each test's own estimate of (sigma1_cap, sigma2_cap, sigma3_cap) [Pa];
        the group values are their means.
    """

    n: int
    dof: int
    branch: str
    sigma1_cap: float
    sigma2_cap: float
    sigma3_cap: float
    sigma1_cap_se: float
    sigma2_cap_se: float
    sigma3_cap_se: float
    C_apparent: float
    C_apparent_se: float
    C_fictive: float
    C_fictive_se: float
    Ci_apparent: float = np.nan
    Ci_fictive: float = np.nan
    phi_i_deg: float = np.nan
    phi_apparent_deg: float = np.nan
    phi_apparent_se_deg: float = np.nan
    lode_angle_deg: np.ndarray = field(default_factory=lambda: np.empty(0))
    per_test: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))

    @property
    def p_cap(self) -> float:
        """Capillary pressure, the mean of the three components [Pa] (eq. 18)."""
        return (self.sigma1_cap + self.sigma2_cap + self.sigma3_cap) / 3.0

    @property
    def q_cap(self) -> float:
        """Capillary deviator sigma1_cap - sigma3_cap [Pa] (eq. 21)."""
        return self.sigma1_cap - self.sigma3_cap


def _mean_se(x):
    x = np.asarray(x, float)
    n = x.shape[0]
    mean = x.mean(axis=0)
    se = x.std(axis=0, ddof=1) / np.sqrt(n) if n > 1 else np.full_like(mean, np.nan)
    return mean, se


def _apparent_friction(sigma1, sigma3):
    """Friction angle phi and its se [deg] of the least-squares line sigma1 = K sigma3 + b (eq. 25 form)."""
    s1, s3 = np.asarray(sigma1, float), np.asarray(sigma3, float)
    n = s1.size
    if n < 2 or np.ptp(s3) <= 0:
        return np.nan, np.nan
    X = np.column_stack([s3, np.ones(n)])
    (K, b), *_ = np.linalg.lstsq(X, s1, rcond=None)
    if K <= 1.0:
        return np.nan, np.nan
    phi = float(np.degrees(np.arcsin((K - 1.0) / (K + 1.0))))
    if n < 3:
        return phi, np.nan
    res = s1 - X @ np.array([K, b])
    var = res @ res / (n - 2) * np.linalg.inv(X.T @ X)[0, 0]
    return phi, float(np.degrees(np.sqrt(var) / ((K + 1.0) * np.sqrt(K))))


def _check_group(*arrays):
    arrs = [np.atleast_1d(np.asarray(a, float)) for a in arrays]
    n = arrs[0].size
    if any(a.shape != (n,) for a in arrs):
        raise ValueError("every input of a group must be a 1-D array of the same length (one value per test)")
    if n < 2:
        raise ValueError("a group sharing one capillary tensor needs at least two tests")
    return arrs


def axisymmetric_group_tensor(
    sigma1, sigma3, sigma1_sat, sigma3_sat, c_eff, phi_eff_deg, branch="compression"
) -> GroupTensor:
    r"""Capillary tensor shared by a group of axisymmetric unsaturated tests with paired saturated tests (eq. 44-48).

    Parameters
    ----------
    sigma1, sigma3 : array_like, shape (n,)
        Total major and minor principal stresses at failure of the
        unsaturated tests of the group [Pa], n >= 2.
    sigma1_sat, sigma3_sat : array_like, shape (n,)
        Effective major and minor principal stresses at failure of each
        test's paired saturated test [Pa] (only the radius
        :math:`(\sigma'_1 - \sigma'_3)/2` is used, as in the paper).
    c_eff : float
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : float
        Effective friction angle :math:`\varphi'` [deg].
    branch : {"compression", "extension"}, default "compression"
        All tests of the group are compressions (the major direction is
        axial; :math:`\sigma_2^{cap} = \sigma_3^{cap}`) or all are
        extensions (major direction radial; :math:`\sigma_2^{cap} = \sigma_1^{cap}`).
        The Mohr-plane analysis is the same.

    Returns
    -------
    GroupTensor
        :math:`\sigma_1^{cap}`, :math:`\sigma_2^{cap}`, :math:`\sigma_3^{cap}`
        with standard errors (dof = n - 1), :math:`C`, :math:`C''`, the
        apparent friction angle check and each test's own estimate.

    Notes
    -----
    The unsaturated circles :math:`(s_j, t_j)` and the fictive circles
    :math:`(s_j, t'_j)` (:func:`fictive_state`) each lie on a line of slope
    :math:`\sin\varphi'` (eq. 43). The least-squares intercepts of lines of
    fixed slope are the means of the per-test cohesions
    (:func:`circle_cohesion`):

    .. math::

       C = \frac{1}{n}\sum_j \frac{t_j - s_j\sin\varphi'}{\cos\varphi'},\qquad
       C'' = \frac{1}{n}\sum_j \frac{t'_j - s_j\sin\varphi'}{\cos\varphi'}

    and eq. 48 gives the tensor:

    .. math::

       \frac{\sigma_1^{cap} + \sigma_3^{cap}}{2} = -\frac{C'' - C'}{\tan\varphi'},\qquad
       \frac{\sigma_1^{cap} - \sigma_3^{cap}}{2} = (C - C'')\cos\varphi'

    Eq. 48 is linear in :math:`(C, C'')`, so the group tensor is also the
    mean of the per-test tensors; its standard errors are those of that mean
    (sample standard deviation over :math:`\sqrt n`), which carry the
    correlation of :math:`C` and :math:`C''` through the shared :math:`s_j`.

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       section 7.2, eq. 38-48 (Fig. 20-21); "a linear regression ... to
       minimize experimental errors" (section 7.3).
    """
    s1, s3, s1s, s3s = _check_group(sigma1, sigma3, sigma1_sat, sigma3_sat)
    ext = bool(_axisymmetric_branch(branch))
    f1, f3 = fictive_state(s1, s3, s1s, s3s)
    C_j = circle_cohesion(s1, s3, phi_eff_deg)
    Cf_j = circle_cohesion(f1, f3, phi_eff_deg)
    a1, a3 = axisymmetric_group_cap(C_j, Cf_j, c_eff, phi_eff_deg)
    per = np.column_stack([a1, a1 if ext else a3, a3])
    (m1, m2, m3), (e1, e2, e3) = _mean_se(per)
    (C, Cf), (C_se, Cf_se) = _mean_se(np.column_stack([C_j, Cf_j]))
    phi_app, phi_app_se = _apparent_friction(s1, s3)
    n = s1.size
    return GroupTensor(
        n=n,
        dof=n - 1,
        branch="extension" if ext else "compression",
        sigma1_cap=float(m1),
        sigma2_cap=float(m2),
        sigma3_cap=float(m3),
        sigma1_cap_se=float(e1),
        sigma2_cap_se=float(e2),
        sigma3_cap_se=float(e3),
        C_apparent=float(C),
        C_apparent_se=float(C_se),
        C_fictive=float(Cf),
        C_fictive_se=float(Cf_se),
        phi_apparent_deg=phi_app,
        phi_apparent_se_deg=phi_app_se,
        lode_angle_deg=lode_angle_deg(s1, s1 if ext else s3, s3),
        per_test=per,
    )


def true_triaxial_group_tensor(
    sigma1, sigma2, sigma3, sigma1_sat, sigma2_sat, sigma3_sat, c_eff, phi_eff_deg, lode_tol_deg=LODE_TOL_DEG
) -> GroupTensor:
    r"""Capillary tensor shared by a true-triaxial group at constant Lode angle, with paired saturated tests (eq. 50).

    Parameters
    ----------
    sigma1, sigma2, sigma3 : array_like, shape (n,)
        Total principal stresses at failure of the unsaturated tests
        (:math:`\sigma_1 \ge \sigma_2 \ge \sigma_3`) [Pa], n >= 2.
    sigma1_sat, sigma2_sat, sigma3_sat : array_like, shape (n,)
        Effective principal stresses at failure of each test's paired
        saturated test [Pa] (their radii
        :math:`(\sigma'_1 - \sigma'_3)/2` and :math:`(\sigma'_1 - \sigma'_2)/2` are used).
    c_eff : float
        Effective cohesion :math:`C'` [Pa].
    phi_eff_deg : float
        Effective friction angle :math:`\varphi'` [deg].
    lode_tol_deg : float, default :data:`LODE_TOL_DEG`
        Largest spread (max - min) of the Lode angles of the unsaturated
        tests for the group to count as "constant Lode angle" [deg].

    Returns
    -------
    GroupTensor
        The three capillary components with standard errors
        (dof = n - 1), :math:`C, C''` (eq. 48), :math:`C_i, C_i''` and
        :math:`\varphi_i` (eq. 50), the Lode angles.

    Raises
    ------
    ValueError
        If the Lode angles of the group spread over more than ``lode_tol_deg``.

    Notes
    -----
    The first two lines are eq. 48 (:func:`axisymmetric_group_tensor`). The
    :math:`\sigma_1`-:math:`\sigma_2` circles :math:`(s_{i,j}, t_{i,j})`, and the
    fictive ones with the same centres and the saturated radii
    :math:`t'_{i,j} = (\sigma'_1 - \sigma'_2)/2`, lie on parallel lines of slope
    :math:`\sin\varphi_i` (:func:`intermediate_friction_angle_deg`, with the
    group's mean Lode ratio); their least-squares intercepts give
    :math:`C_i`, :math:`C_i''` and

    .. math::

       \frac{\sigma_1^{cap} - \sigma_2^{cap}}{2} = (C_i - C_i'')\cos\varphi_i
       = \frac{1}{n}\sum_j (t_{i,j} - t'_{i,j})

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J.
       Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099, Appendix 1,
       section 7.3, eq. 48-50 (Fig. 22); Appendix 2, eq. 51-59.
    """
    s1, s2, s3, s1s, s2s, s3s = _check_group(sigma1, sigma2, sigma3, sigma1_sat, sigma2_sat, sigma3_sat)
    theta = lode_angle_deg(s1, s2, s3)
    spread = float(np.ptp(theta))
    if not spread <= lode_tol_deg:
        raise ValueError(
            f"the Lode angles of the group spread over {spread:.3g} deg > {lode_tol_deg:g} deg: "
            "eq. 50 needs a constant Lode angle (eq. 49)"
        )
    axi = axisymmetric_group_tensor(s1, s3, s1s, s3s, c_eff, phi_eff_deg)
    Q = float(np.mean(lode_ratio(s1, s2, s3)))
    phi_i = float(intermediate_friction_angle_deg(Q, phi_eff_deg))
    f1, f2 = fictive_state(s1, s2, s1s, s2s)
    Ci_j = circle_cohesion(s1, s2, phi_i)
    Cif_j = circle_cohesion(f1, f2, phi_i)
    a1 = axi.per_test[:, 0]
    per = np.column_stack([a1, a1 - 2.0 * (Ci_j - Cif_j) * np.cos(np.radians(phi_i)), axi.per_test[:, 2]])
    (m1, m2, m3), (e1, e2, e3) = _mean_se(per)
    return dataclasses_replace(
        axi,
        branch="general",
        sigma1_cap=float(m1),
        sigma2_cap=float(m2),
        sigma3_cap=float(m3),
        sigma1_cap_se=float(e1),
        sigma2_cap_se=float(e2),
        sigma3_cap_se=float(e3),
        Ci_apparent=float(np.mean(Ci_j)),
        Ci_fictive=float(np.mean(Cif_j)),
        phi_i_deg=phi_i,
        lode_angle_deg=theta,
        per_test=per,
    )
