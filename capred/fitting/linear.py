"""Ordinary least-squares straight line with standard errors and intervals.

The dry envelope of `capred shear` is such a line, tau = c + sigma_N tan(phi)
(intercept c [Pa], slope tan(phi) [-]); its covariance feeds every interval
downstream (back-analysed capillary stress, fitted chi laws, bands).

References
----------
.. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed.
   Wiley, doi:10.1002/9781118625590, ch. 1 (the straight line: its
   estimates, their variances, the confidence band of the mean line and the
   prediction interval of a new observation, and the line through the origin).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from statistics import NormalDist

import numpy as np

from ..errors import FitError


def t_quantile(p, dof):
    """Student-t quantile t_{p, dof}.

    Parameters
    ----------
    p : float or array_like
        Lower-tail probability [-], e.g. 0.975 for a two-sided 95 % interval.
    dof : int or array_like
        Degrees of freedom [-], > 0 (NaN is returned where dof <= 0).

    Returns
    -------
    float or ndarray
        The quantile t with P(T <= t) = p [-]; a float for scalar input.

    Notes
    -----
    The inverse in t of Student's distribution function,

    .. math:: p = \\int_{-\\infty}^{t} \\frac{\\Gamma((\\nu + 1)/2)}{\\sqrt{\\nu\\pi}\\,\\Gamma(\\nu/2)}
              \\left(1 + \\frac{u^2}{\\nu}\\right)^{-(\\nu + 1)/2} du, \\qquad \\nu = \\text{dof}.

    For whole ν up to ``_CLOSED_FORM_DOF`` (the fits of a lab table) it is solved here from the closed form
    of P(|T| <= t) in θ = arctan(t / sqrt(ν)) (Abramowitz & Stegun 1964, eq. 26.7.3 and 26.7.4: a finite sum
    of powers of cos θ), by Newton's method in θ: P(|T| <= t) is increasing and concave in θ (its derivative
    2 c_ν cos^(ν-1) θ falls), so from a start below the root (that of the normal quantile, which lies below
    Student's) the iterates rise monotonically to it and never leave [0, π/2). Against a 40-digit solution
    (mpmath) its relative error was at most 1e-15 at p = 0.975 and 6e-13 at p = 0.9999 (scipy's Cephes
    stdtrit: 2e-16); it spares every command the ~0.25 s import of scipy.special. Other ν (a fraction, or
    above the limit) go to ``scipy.special.stdtrit``.

    References
    ----------
    .. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley,
       doi:10.1002/9781118625590, ch. 1 (the t quantiles of the confidence intervals of a fitted line).
    .. [2] Abramowitz, M. & Stegun, I. A. (1964). Handbook of Mathematical Functions. NBS Applied
       Mathematics Series 55 (no DOI), eq. 26.7.3-26.7.4 (Student's distribution for whole ν).
    """
    if np.ndim(p) == 0 and np.ndim(dof) == 0:
        return _t_quantile_one(float(p), float(dof))
    dof_a = np.asarray(dof, dtype=float)
    if np.ndim(p) == 0:  # one level for many fits: each distinct ν once (a table's tests share a handful)
        distinct = np.unique(dof_a)
        values = np.array([_t_quantile_one(float(p), nu) for nu in distinct.tolist()])
        return values[np.searchsorted(distinct, dof_a)] if distinct.size else np.full(dof_a.shape, np.nan)
    p_a, dof_a = np.broadcast_arrays(np.asarray(p, dtype=float), dof_a)
    return np.array(
        [_t_quantile_one(q, nu) for q, nu in zip(p_a.ravel().tolist(), dof_a.ravel().tolist())], dtype=float
    ).reshape(p_a.shape)


def _t_quantile_one(p: float, nu: float) -> float:
    """t_{p, ν} of one pair: the closed form for whole ν (see t_quantile), scipy otherwise, NaN for ν <= 0."""
    if not nu > 0:
        return math.nan
    if nu <= _CLOSED_FORM_DOF and nu == int(nu):
        return _t_quantile_whole(p, int(nu))
    from scipy.special import stdtrit

    return float(stdtrit(nu, p))


#: Degrees of freedom up to which ``t_quantile`` sums the closed form (ν/2 terms) instead of calling scipy.
_CLOSED_FORM_DOF = 200


@lru_cache(maxsize=4096)
def _t_quantile_whole(p: float, nu: int) -> float:
    """t_{p, ν} for one whole ν >= 1 by Newton's method on A(θ) = P(|T| <= sqrt(ν) tan θ) (see t_quantile)."""
    if not 0.0 <= p <= 1.0:
        return math.nan
    target = abs(2.0 * p - 1.0)  # A(|t|): the two-sided probability inside |t|
    sign = 1.0 if p >= 0.5 else -1.0
    if target >= 1.0:
        return sign * math.inf
    if target == 0.0:
        return 0.0
    # c_ν of the derivative dA/dθ = 2 c_ν cos^(ν-1) θ, with c_ν = Γ((ν+1)/2) / (sqrt(π) Γ(ν/2))
    c_nu = math.exp(math.lgamma((nu + 1) / 2.0) - math.lgamma(nu / 2.0)) / math.sqrt(math.pi)
    # start at the normal quantile: |t_p| > |z_p| (Student's tails are heavier), so θ starts below its root
    theta = math.atan(NormalDist().inv_cdf(0.5 + 0.5 * target) / math.sqrt(nu))
    top = math.nextafter(math.pi / 2, 0.0)
    for _ in range(100):  # quadratic convergence: ~4 steps from the normal start; the cap is a guard
        step = (target - _t_two_sided(theta, nu)) / (2.0 * c_nu * math.cos(theta) ** (nu - 1))
        if step <= 4e-16 * theta:  # no step above rounding: converged
            break
        theta = min(theta + step, top)
    return sign * math.sqrt(nu) * math.tan(theta)


def _t_two_sided(theta: float, nu: int) -> float:
    """A(θ) = P(|T| <= sqrt(ν) tan θ) for whole ν (Abramowitz & Stegun 1964, eq. 26.7.3-26.7.4)."""
    c, s = math.cos(theta), math.sin(theta)
    c2 = c * c
    if nu % 2 == 0:  # sin θ [1 + (1/2) cos²θ + (1·3)/(2·4) cos⁴θ + ... + (1·3···(ν-3))/(2·4···(ν-2)) cos^(ν-2)θ]
        term = total = 1.0
        for k in range(1, nu // 2):
            term *= c2 * (2 * k - 1) / (2 * k)
            total += term
        return s * total
    # (2/π) {θ + sin θ [cos θ + (2/3) cos³θ + ... + (2·4···(ν-3))/(1·3···(ν-2)) cos^(ν-2)θ]}; ν = 1: 2θ/π
    total = 0.0
    if nu > 1:
        term = total = c
        for k in range(1, (nu - 1) // 2):
            term *= c2 * (2 * k) / (2 * k + 1)
            total += term
    return (2.0 / math.pi) * (theta + s * total)


@dataclass(frozen=True)
class LineFit:
    """y = intercept + slope x fitted by ordinary least squares.

    Standard errors come from the residual variance s^2 = RSS / (n - 2) and
    (X^T X)^-1; intervals use Student's t with n - 2 degrees of freedom
    (n - 1 through the origin) [1].

    Attributes
    ----------
    intercept, slope : a [unit of y], b [unit of y / unit of x]
    intercept_se, slope_se : their standard errors [same units]
    covariance : (2, 2) covariance s^2 (X^T X)^-1 of (a, b); row and column of a are 0 through the origin
    n : number of points [-]
    rss : residual sum of squares [unit of y squared]
    r2 : coefficient of determination [-]
    confidence : level of ``t`` and of the ``*_ci`` intervals [-]
    t : Student-t quantile at ``confidence`` with ``dof`` degrees of freedom [-]
    x_mean, sxx : mean of x and sum of (x - x_mean)^2 [unit of x, its square]
    through_origin : True when a = 0 was imposed
    """

    intercept: float
    slope: float
    intercept_se: float
    slope_se: float
    covariance: np.ndarray
    n: int
    rss: float
    r2: float
    confidence: float
    t: float
    x_mean: float
    sxx: float
    through_origin: bool = False  # True: intercept fixed at 0 (cohesionless soil)

    @property
    def dof(self) -> int:
        """Residual degrees of freedom: n - 2, or n - 1 through the origin."""
        return self.n - (1 if self.through_origin else 2)

    @property
    def residual_variance(self) -> float:
        """s^2 = RSS / dof, the variance of one measurement about the line."""
        return self.rss / self.dof

    @property
    def unscaled_covariance(self) -> np.ndarray:
        """(X^T X)^-1 of (a, b): the covariance per unit residual variance [1, 1/x, 1/x^2].

        Free line: [[1/n + xbar^2/Sxx, -xbar/Sxx], [-xbar/Sxx, 1/Sxx]]; through the origin
        [[0, 0], [0, 1/sum x^2]] with sum x^2 = Sxx + n xbar^2. Defined even when RSS = 0.
        """
        if self.through_origin:
            return np.array([[0.0, 0.0], [0.0, 1.0 / (self.sxx + self.n * self.x_mean**2)]])
        xm, sxx = self.x_mean, self.sxx
        return np.array([[1.0 / self.n + xm**2 / sxx, -xm / sxx], [-xm / sxx, 1.0 / sxx]])

    @property
    def intercept_ci(self) -> tuple[float, float]:
        """a -/+ t se(a) at ``confidence`` [unit of y]."""
        h = self.t * self.intercept_se
        return self.intercept - h, self.intercept + h

    @property
    def slope_ci(self) -> tuple[float, float]:
        """b -/+ t se(b) at ``confidence`` [unit of y / unit of x]."""
        h = self.t * self.slope_se
        return self.slope - h, self.slope + h

    def predict(self, x):
        """a + b x [unit of y] at ``x`` [unit of x]."""
        return self.intercept + self.slope * np.asarray(x, dtype=float)

    def mean_band(self, x):
        """Lower and upper confidence band of the fitted mean line at ``x`` [unit of y], at ``confidence``.

        .. math:: \\hat y(x) \\mp t_{1-\\alpha/2,\\,\\nu}\\sqrt{V_{aa} + 2xV_{ab} + x^2V_{bb}}

        with V the covariance of (a, b) and nu = ``dof`` [1]. It covers the true mean line, not a new point:
        see :meth:`prediction_interval`.
        """
        x = np.asarray(x, dtype=float)
        cov = self.covariance
        se = np.sqrt(np.maximum(cov[0, 0] + 2 * x * cov[0, 1] + x**2 * cov[1, 1], 0.0))
        y = self.predict(x)
        return y - self.t * se, y + self.t * se

    def prediction_interval(self, x, confidence: float | None = None):
        """Lower and upper limit [unit of y] of a NEW observation at ``x`` (default level ``confidence``).

        .. math:: \\hat y(x) \\mp t_{1-\\alpha/2,\\,\\nu}\\sqrt{s^2 + V_{aa} + 2xV_{ab} + x^2V_{bb}}

        The new observation's own scatter s^2 = RSS/nu is added to the variance of the fitted mean [1].
        """
        x = np.asarray(x, dtype=float)
        cov = self.covariance
        var = self.residual_variance + cov[0, 0] + 2 * x * cov[0, 1] + x**2 * cov[1, 1]
        level = self.confidence if confidence is None else confidence
        t = t_quantile(0.5 + level / 2.0, self.dof)
        y = self.predict(x)
        half = t * np.sqrt(np.maximum(var, 0.0))
        return y - half, y + half


def fit_line(x, y, confidence: float = 0.95) -> LineFit:
    """Fit y = a + b x by ordinary least squares; needs >= 3 points and two distinct x.

    .. math:: b = S_{xy}/S_{xx}, \\quad a = \\bar y - b\\bar x, \\quad
              \\mathrm{Cov}(a, b) = s^2 (X^T X)^{-1}, \\quad s^2 = \\mathrm{RSS}/(n - 2)

    (centred two-pass sums, [1] ch. 1).

    Parameters
    ----------
    x, y : array_like
        Abscissae and ordinates (any consistent units; SI in capred: sigma_N, tau [Pa]).
    confidence : float
        Level of the intervals [-], in (0, 1).

    Returns
    -------
    LineFit
        Intercept a [unit of y], slope b [unit of y / unit of x], their standard errors and covariance,
        RSS, R² and the t quantile of the intervals with n - 2 degrees of freedom.

    Raises
    ------
    FitError
        Fewer than 3 points, non-finite values, or a single abscissa.

    References
    ----------
    .. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley,
       doi:10.1002/9781118625590, ch. 1 (the least-squares straight line, the variances of a and b and
       their t intervals).
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise FitError("the data to fit contain NaN or infinite values")
    n = x.size
    if n < 3:
        raise FitError(f"{n} points: at least 3 are needed to fit a line with standard errors")
    x_mean = x.mean()
    sxx = float(np.sum((x - x_mean) ** 2))
    if sxx <= 1e-12 * max(1.0, float(np.sum(x**2))):
        raise FitError("all points have the same abscissa: the slope cannot be fitted")
    slope = float(np.sum((x - x_mean) * (y - y.mean())) / sxx)
    intercept = float(y.mean() - slope * x_mean)
    resid = y - (intercept + slope * x)
    rss = float(resid @ resid)
    s2 = rss / (n - 2)
    cov = s2 * np.array([[1.0 / n + x_mean**2 / sxx, -x_mean / sxx], [-x_mean / sxx, 1.0 / sxx]])
    tss = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - rss / tss if tss > 0 else 1.0
    t = t_quantile(0.5 + confidence / 2.0, n - 2)
    return LineFit(
        intercept,
        slope,
        float(np.sqrt(cov[0, 0])),
        float(np.sqrt(cov[1, 1])),
        cov,
        n,
        rss,
        r2,
        confidence,
        t,
        float(x_mean),
        sxx,
    )


def fit_line_origin(x, y, confidence: float = 0.95) -> LineFit:
    """Fit y = b x through the origin by least squares (cohesionless soil, c = 0); needs >= 2 points.

    .. math:: b = \\sum xy / \\sum x^2, \\quad \\mathrm{se}(b) = \\sqrt{s^2/\\sum x^2}, \\quad
              s^2 = \\mathrm{RSS}/(n - 1)

    R^2 is 1 - RSS/TSS about the mean of y, as for the free fit, so both compare ([1] ch. 1,
    the line through the origin).

    Parameters
    ----------
    x, y : array_like
        Abscissae and ordinates (SI in capred: sigma_N, tau [Pa]).
    confidence : float
        Level of the intervals [-], in (0, 1).

    Returns
    -------
    LineFit
        With ``through_origin=True``, intercept 0 and its variance 0; slope b [unit of y / unit of x],
        its standard error, RSS, R² and the t quantile with n - 1 degrees of freedom.

    Raises
    ------
    FitError
        Fewer than 2 points, non-finite values, or every x = 0.

    References
    ----------
    .. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley,
       doi:10.1002/9781118625590, ch. 1 (the straight line through the origin, b = Σxy/Σx²,
       s² = RSS/(n − 1)).
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise FitError("the data to fit contain NaN or infinite values")
    n = x.size
    if n < 2:
        raise FitError(f"{n} points: at least 2 are needed to fit a line through the origin with a standard error")
    sxx0 = float(x @ x)
    if sxx0 <= 0:
        raise FitError("all points lie at x = 0: the slope cannot be fitted")
    slope = float(x @ y) / sxx0
    resid = y - slope * x
    rss = float(resid @ resid)
    cov = np.array([[0.0, 0.0], [0.0, rss / (n - 1) / sxx0]])
    tss = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - rss / tss if tss > 0 else 1.0
    t = t_quantile(0.5 + confidence / 2.0, n - 1)
    return LineFit(
        0.0,
        slope,
        0.0,
        float(np.sqrt(cov[1, 1])),
        cov,
        n,
        rss,
        r2,
        confidence,
        t,
        float(x.mean()),
        float(np.sum((x - x.mean()) ** 2)),
        True,
    )
