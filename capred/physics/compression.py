r"""One-dimensional (oedometer) and isotropic compression: lines, indices and the yield stress.

Pure functions on arrays (SI: stresses in Pa). The first loading is described by a smooth bilinear curve in
e - log10 sigma',

.. math::

    e(t) = e_y - C_r\,t - (C_c - C_r)\,w \log_{10}\left(1 + 10^{t/w}\right), \qquad t = \log_{10}(\sigma'/\sigma'_y),

whose asymptotes are the recompression line e_y - C_r t and the normal (virgin) compression line
e_y - C_c t; they meet at sigma'_y (the bilinear yield stress) and w [decades] is the width of the bend. The
fit gives C_c (lambda = C_c / ln 10) and, on its fitted curve, the yield stress by the constructions of
Casagrande (1936) and Pacheco Silva (1970). Unloading (and reloading) stages give C_s (kappa = C_s / ln 10) by a
straight line in e - log10 sigma'. The constructions are made in the plot's own coordinates (decades of stress
across, void ratio up), as drawn on an e - log sigma' chart with one decade as long as a unit of e.

References
----------
.. [1] Casagrande, A. (1936). The determination of the pre-consolidation load and its practical significance.
   Proc. 1st Int. Conf. Soil Mech. Found. Eng., Cambridge MA, vol. 3, 60-64.
.. [2] Pacheco Silva, F. (1970). A new graphical construction for determination of the pre-consolidation stress
   of a soil sample. Proc. 4th Brazilian Conf. Soil Mech. Found. Eng., Rio de Janeiro, vol. 2, 225-232.
.. [3] Roscoe, K. H., Burland, J. B. (1968), and Schofield & Wroth (1968), Critical State Soil Mechanics:
   lambda and kappa as the slopes in e - ln p'.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

LN10 = float(np.log(10.0))
#: bounds of the bend width w of the smooth bilinear curve [decades of stress]
BEND_BOUNDS = (0.01, 2.0)


def smooth_bilinear(t, e_y, C_r, C_c, w):
    """Void ratio of the smooth bilinear first-loading curve at t = log10(sigma'/sigma'_y) [-].

    Parameters
    ----------
    t : array_like
        log10(sigma'/sigma'_y) [-].
    e_y : float
        Void ratio where the two asymptotes meet [-].
    C_r, C_c : float
        Recompression and compression indices, slopes in e - log10 sigma' [-].
    w : float
        Width of the bend [decades].

    Returns
    -------
    numpy.ndarray
        e [-].

    References
    ----------
    .. [1] Casagrande (1936), the bilinear idealisation of the e - log sigma' curve.
    """
    t = np.asarray(t, float)
    return e_y - C_r * t - (C_c - C_r) * w * np.logaddexp(0.0, LN10 * t / w) / LN10


def _slope(t, C_r, C_c, w):
    s = 1.0 / (1.0 + np.exp(-LN10 * np.asarray(t, float) / w))  # logistic: the share of the bend passed
    return -C_r - (C_c - C_r) * s


def _second(t, C_r, C_c, w):
    s = 1.0 / (1.0 + np.exp(-LN10 * np.asarray(t, float) / w))
    return -(C_c - C_r) * s * (1.0 - s) * LN10 / w


def casagrande_construction(e_y, C_r, C_c, w) -> tuple[float, float, float, float]:
    """Casagrande's (1936) construction on the smooth bilinear curve, every point of it (for its figure too).

    Parameters
    ----------
    e_y, C_r, C_c, w : float
        The curve (see :func:`smooth_bilinear`).

    Returns
    -------
    (float, float, float, float)
        t_T, the point of largest curvature as log10(sigma'/sigma'_y) [-]; e_T, the void ratio there [-]; the
        slope de/dlog10 sigma' of the curve there [-]; and t_p = log10(sigma'_p/sigma'_y) [-], where the bisector
        of the horizontal and the tangent at T meets the virgin line e_y - C_c t.

    References
    ----------
    .. [1] Casagrande, A. (1936). Proc. 1st ICSMFE, Cambridge MA, vol. 3, 60-64.
    """
    from scipy.optimize import minimize_scalar

    def minus_curvature(t):
        d1, d2 = _slope(t, C_r, C_c, w), _second(t, C_r, C_c, w)
        return -abs(d2) / (1.0 + d1 * d1) ** 1.5

    grid = np.linspace(-6 * w, 6 * w, 241)
    k = int(np.argmin([minus_curvature(x) for x in grid]))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    tT = float(minimize_scalar(minus_curvature, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12}).x)
    eT = float(smooth_bilinear(tT, e_y, C_r, C_c, w))
    slope = float(_slope(tT, C_r, C_c, w))
    m = np.tan(0.5 * np.arctan(slope))  # the bisector's slope (half the tangent's angle)
    return tT, eT, slope, float((e_y - eT + m * tT) / (m + C_c))


def casagrande_t(e_y, C_r, C_c, w) -> float:
    """Casagrande's (1936) construction on the smooth bilinear curve: t = log10(sigma'_p/sigma'_y).

    The point T of largest curvature; the horizontal and the tangent there; their bisector; its intersection with
    the virgin compression line e_y - C_c t.

    Parameters
    ----------
    e_y, C_r, C_c, w : float
        The curve (see :func:`smooth_bilinear`).

    Returns
    -------
    float
        log10 of the pre-consolidation stress over sigma'_y [-].

    References
    ----------
    .. [1] Casagrande, A. (1936). Proc. 1st ICSMFE, Cambridge MA, vol. 3, 60-64.
    """
    return casagrande_construction(e_y, C_r, C_c, w)[3]


def pacheco_silva_t(e0, e_y, C_r, C_c, w) -> float:
    """Pacheco Silva's (1970) construction on the smooth bilinear curve: t = log10(sigma'_p/sigma'_y).

    The virgin line meets the horizontal e = e0 at A; the vertical through A meets the curve at B; the horizontal
    through B meets the virgin line at C, the pre-consolidation stress.

    Parameters
    ----------
    e0 : float
        Initial void ratio of the specimen [-] (the first reading).
    e_y, C_r, C_c, w : float
        The curve (see :func:`smooth_bilinear`).

    Returns
    -------
    float
        log10 of the pre-consolidation stress over sigma'_y [-].

    References
    ----------
    .. [1] Pacheco Silva, F. (1970). Proc. 4th Brazilian Conf. Soil Mech. Found. Eng., vol. 2, 225-232.
    """
    tA = (e_y - e0) / C_c
    eB = float(smooth_bilinear(tA, e_y, C_r, C_c, w))
    return float((e_y - eB) / C_c)


@dataclass(frozen=True)
class FirstLoadingFit:
    """The smooth bilinear curve fitted to the first loading, with its covariance.

    Attributes
    ----------
    e_y, C_r, C_c, w : float
        The curve's parameters (see :func:`smooth_bilinear`) [-, -, -, decades].
    log_sigma_y : float
        log10 of the bilinear yield stress sigma'_y [log10 Pa].
    cov : numpy.ndarray
        5 x 5 covariance of (e_y, C_r, C_c, log_sigma_y, w) from the Jacobian, scaled by the residual variance.
    n : int
        Readings fitted.
    rss : float
        Residual sum of squares [-].
    w_at_bound : bool
        The bend width ended at a bound of :data:`BEND_BOUNDS` (too few readings in the bend to set it).
    """

    e_y: float
    C_r: float
    C_c: float
    log_sigma_y: float
    w: float
    cov: np.ndarray
    n: int
    rss: float
    w_at_bound: bool

    @property
    def params(self) -> np.ndarray:
        """The fitted parameters as one vector, in the order of ``cov``: (e_y, C_r, C_c, log_sigma_y, w)."""
        return np.array([self.e_y, self.C_r, self.C_c, self.log_sigma_y, self.w])

    def e_at(self, sigma):
        """Void ratio of the fitted curve at an effective vertical stress.

        Parameters
        ----------
        sigma : float or array_like
            Effective vertical stress σ' [Pa].

        Returns
        -------
        numpy.ndarray
            Void ratio e [-] of :func:`smooth_bilinear` with the fitted parameters.
        """
        return smooth_bilinear(np.log10(sigma) - self.log_sigma_y, self.e_y, self.C_r, self.C_c, self.w)


def fit_first_loading(sigma, e) -> FirstLoadingFit:
    """Least-squares fit of :func:`smooth_bilinear` to the readings of the first loading.

    Parameters
    ----------
    sigma : array_like
        Effective stress of each reading (vertical or mean) [Pa], > 0.
    e : array_like
        Void ratio [-].

    Returns
    -------
    FirstLoadingFit

    References
    ----------
    .. [1] Casagrande (1936): the e - log sigma' curve of first loading, bilinear with a bend at the yield stress.
    """
    from scipy.optimize import least_squares

    x, y = np.log10(np.asarray(sigma, float)), np.asarray(e, float)
    n = x.size

    def model(p):
        return smooth_bilinear(x - p[3], p[0], p[1], p[2], p[4])

    # start: the last three readings' slope (virgin), the first three's (recompression), the bend in the middle
    k = max(2, min(3, n // 2))
    cc0 = max(-np.polyfit(x[-k:], y[-k:], 1)[0], 1e-3)
    cr0 = min(max(-np.polyfit(x[:k], y[:k], 1)[0], 0.0), 0.5 * cc0)
    best = None
    for ts in np.quantile(x, [0.3, 0.5, 0.7]):
        e_ys = float(np.interp(ts, x, y))
        p0 = [e_ys, cr0, cc0, ts, 0.1]
        lo = [-np.inf, -np.inf, -np.inf, x.min() - 3, BEND_BOUNDS[0]]
        hi = [np.inf, np.inf, np.inf, x.max() + 3, BEND_BOUNDS[1]]
        r = least_squares(lambda p: model(p) - y, p0, bounds=(lo, hi), x_scale="jac", xtol=1e-14, ftol=1e-14)
        if best is None or r.cost < best.cost:
            best = r
    p = best.x
    J = best.jac
    rss = float(2.0 * best.cost)
    dof = n - 5
    s2 = rss / dof if dof > 0 else np.nan
    try:
        cov = np.linalg.pinv(J.T @ J) * s2
    except np.linalg.LinAlgError:  # pragma: no cover - pinv converges for finite matrices
        cov = np.full((5, 5), np.nan)
    at_bound = bool(np.isclose(p[4], BEND_BOUNDS[0], rtol=1e-3) or np.isclose(p[4], BEND_BOUNDS[1], rtol=1e-3))
    return FirstLoadingFit(float(p[0]), float(p[1]), float(p[2]), float(p[3]), float(p[4]), cov, n, rss, at_bound)


def gradient(f, p, steps=None) -> np.ndarray:
    """Central-difference gradient of a scalar function of the fit's parameters (for the delta method).

    Parameters
    ----------
    f : callable
        ``f(params) -> float``.
    p : numpy.ndarray
        The parameters.
    steps : numpy.ndarray, optional
        Step per parameter; default 1e-6 (1 + |p|).

    Returns
    -------
    numpy.ndarray
        df/dp.

    References
    ----------
    .. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed., Wiley,
       doi:10.1002/9781118625590 (the delta method's gradient).
    """
    p = np.asarray(p, float)
    h = 1e-6 * (1.0 + np.abs(p)) if steps is None else steps
    g = np.empty_like(p)
    for i in range(p.size):
        a, b = p.copy(), p.copy()
        a[i] += h[i]
        b[i] -= h[i]
        g[i] = (f(a) - f(b)) / (2 * h[i])
    return g


@dataclass(frozen=True)
class LineFit:
    """A straight line e = a - C log10 sigma' fitted by ordinary least squares.

    Attributes
    ----------
    index : float
        C, the slope's magnitude in e - log10 sigma' [-] (C_s of an unloading stage).
    se : float
        Its standard error [-] (NaN with two readings).
    intercept : float
        a, e at sigma' = 1 Pa [-].
    n : int
        Readings.
    """

    index: float
    se: float
    intercept: float
    n: int


def fit_line(sigma, e) -> LineFit:
    """Line e = a - C log10 sigma' fitted by least squares (an unloading or reloading stage).

    Parameters
    ----------
    sigma : array_like
        Effective stress [Pa], > 0.
    e : array_like
        Void ratio [-].

    Returns
    -------
    LineFit

    References
    ----------
    .. [1] Schofield, A., Wroth, P. (1968). Critical State Soil Mechanics: unloading-reloading lines straight in
       e - ln p' (kappa = C_s / ln 10).
    """
    x, y = np.log10(np.asarray(sigma, float)), np.asarray(e, float)
    n = x.size
    X = np.column_stack([np.ones(n), x])
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    se = np.nan
    if n > 2:
        r = y - X @ coef
        s2 = float(r @ r) / (n - 2)
        se = float(np.sqrt(s2 / np.sum((x - x.mean()) ** 2)))
    return LineFit(float(-coef[1]), se, float(coef[0]), n)


def stage_labels(sigma) -> list[str]:
    """Loading, unloading and reloading stages from the stress history alone.

    A reading whose stress is above the one before is loading (``reloading`` while below the largest stress
    reached before, ``loading`` at or beyond it); below it, ``unloading``. The first reading takes the label of
    the second.

    Parameters
    ----------
    sigma : array_like
        Effective stress in reading order [Pa].

    Returns
    -------
    list of str
        ``loading``, ``unloading`` or ``reloading`` per reading.

    References
    ----------
    .. [1] ASTM D2435/D2435M-11, Standard test methods for one-dimensional consolidation properties of soils
       using incremental loading (loading, unloading and reloading increments). doi:10.1520/D2435_D2435M-11
    """
    s = np.asarray(sigma, float)
    out: list[str] = []
    peak = s[0] if s.size else 0.0
    for i in range(1, s.size):
        if s[i] < s[i - 1]:
            out.append("unloading")
        elif s[i] > peak:
            out.append("loading")
        else:
            out.append("reloading")
        peak = max(peak, s[i])
    return [out[0] if out else "loading", *out]


__all__ = [
    "smooth_bilinear",
    "casagrande_t",
    "pacheco_silva_t",
    "fit_first_loading",
    "FirstLoadingFit",
    "fit_line",
    "LineFit",
    "stage_labels",
    "gradient",
]
