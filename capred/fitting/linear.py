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

import dataclasses
import math
from dataclasses import dataclass
from functools import lru_cache
from statistics import NormalDist

import numpy as np

from ..errors import FitError


def t_quantile(p, dof):
    r"""Student-t quantile t_{p, dof}.

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

    .. math:: p = \int_{-\infty}^{t} \frac{\Gamma((\nu + 1)/2)}{\sqrt{\nu\pi}\,\Gamma(\nu/2)}
              \left(1 + \frac{u^2}{\nu}\right)^{-(\nu + 1)/2} du, \qquad \nu = \text{dof}.

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
    errors : "constant" (one scatter s for every point) or "proportional" (standard deviation proportional to
        the fitted strength, s being its value at ``ref``; weighted least squares, `fit_envelope`)
    loss : "ols" (least squares), "huber" or "tukey" (robust M-estimate with sandwich covariance, `fit_envelope`)
    scale : the scatter s behind the intervals [unit of y] when it is not sqrt(RSS/dof) (weighted or robust fits)
    ref : level of y at which ``scale`` holds for ``errors="proportional"`` [unit of y]
    heteroscedasticity : Breusch-Pagan test of the least-squares residuals against x (`breusch_pagan`)
    scale_proportional : with ``errors="either"``, the scatter at ``ref`` of the proportional model [unit of y]
    diagnostics : per point ``studentized`` (externally studentized residual), ``cooks``, ``outlier`` (bool),
        ``threshold`` (`outlier_diagnostics`)
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
    errors: str = "constant"
    loss: str = "ols"
    scale: float | None = None
    ref: float = 1.0
    heteroscedasticity: dict | None = None
    diagnostics: dict | None = None
    #: ``errors="either"``: the scatter s_p at ``ref`` of the proportional model [unit of y]
    scale_proportional: float | None = None

    @property
    def dof(self) -> int:
        """Residual degrees of freedom: n - 2, or n - 1 through the origin."""
        return self.n - (1 if self.through_origin else 2)

    @property
    def residual_variance(self) -> float:
        """s^2 = RSS / dof, the variance of one measurement about the line.

        At ``ref`` for proportional errors; the robust scale squared for a robust fit.
        """
        if self.scale is not None:
            return self.scale**2
        return self.rss / self.dof

    def variance_factor(self, y):
        """v(y) [-]: the variance of one measurement of level y is s^2 v(y).

        1, or (y/ref)^2 for proportional errors, or max(1, (s_p/s)^2 (y/ref)^2) for ``errors="either"`` (the larger of
        the two models' variances).

        Parameters
        ----------
        y : array_like
            Level of the measurement (its expected value) [unit of y].

        Returns
        -------
        ndarray
        """
        y = np.asarray(y, dtype=float)
        if self.errors == "proportional":
            return (y / self.ref) ** 2
        if self.errors == "either" and self.scale_proportional is not None:
            s2 = self.residual_variance
            if not s2 > 0:
                return np.ones(y.shape)
            return np.maximum(1.0, self.scale_proportional**2 / s2 * (y / self.ref) ** 2)
        return np.ones(y.shape)

    def scatter_variance(self, y):
        """s^2 v(y): the variance of one new measurement of expected level y [unit of y squared].

        Parameters
        ----------
        y : float or array_like
            Expected level [unit of y] (matters only with proportional errors).

        Returns
        -------
        float or numpy.ndarray
            ``residual_variance * variance_factor(y)`` [unit of y squared].
        """
        return self.residual_variance * self.variance_factor(y)

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
        """Interval of the intercept, a -/+ t se(a) at ``confidence`` [unit of y]."""
        h = self.t * self.intercept_se
        return self.intercept - h, self.intercept + h

    @property
    def slope_ci(self) -> tuple[float, float]:
        """Interval of the slope, b -/+ t se(b) at ``confidence`` [unit of y / unit of x]."""
        h = self.t * self.slope_se
        return self.slope - h, self.slope + h

    def predict(self, x):
        """The line a + b x [unit of y] at ``x`` [unit of x].

        Parameters
        ----------
        x : float or array_like
            Abscissa [unit of x].

        Returns
        -------
        numpy.ndarray
            The fitted line [unit of y].
        """
        return self.intercept + self.slope * np.asarray(x, dtype=float)

    def mean_band(self, x):
        r"""Lower and upper confidence band of the fitted mean line at ``x`` [unit of y], at ``confidence``.

        .. math:: \hat y(x) \mp t_{1-\alpha/2,\,\nu}\sqrt{V_{aa} + 2xV_{ab} + x^2V_{bb}}

        with V the covariance of (a, b) and nu = ``dof`` [1]. It covers the true mean line, not a new point:
        see :meth:`prediction_interval`.

        Parameters
        ----------
        x : float or array_like
            Abscissa [unit of x].

        Returns
        -------
        tuple of numpy.ndarray
            (lower, upper) [unit of y].
        """
        x = np.asarray(x, dtype=float)
        cov = self.covariance
        se = np.sqrt(np.maximum(cov[0, 0] + 2 * x * cov[0, 1] + x**2 * cov[1, 1], 0.0))
        y = self.predict(x)
        return y - self.t * se, y + self.t * se

    def prediction_interval(self, x, confidence: float | None = None):
        r"""Lower and upper limit [unit of y] of a NEW observation at ``x`` (default level ``confidence``).

        .. math:: \hat y(x) \mp t_{1-\alpha/2,\,\nu}\sqrt{s^2 + V_{aa} + 2xV_{ab} + x^2V_{bb}}

        The new observation's own scatter s^2 = RSS/nu is added to the variance of the fitted mean [1]; with
        proportional errors it is s^2 (y_hat(x)/ref)^2, growing with the strength (`fit_envelope`).

        Parameters
        ----------
        x : float or array_like
            Abscissa [unit of x].
        confidence : float or None, optional
            Level in (0, 1) (default: the fit's ``confidence``).

        Returns
        -------
        tuple of numpy.ndarray
            (lower, upper) [unit of y].
        """
        x = np.asarray(x, dtype=float)
        cov = self.covariance
        var = self.scatter_variance(self.predict(x)) + cov[0, 0] + 2 * x * cov[0, 1] + x**2 * cov[1, 1]
        level = self.confidence if confidence is None else confidence
        t = t_quantile(0.5 + level / 2.0, self.dof)
        y = self.predict(x)
        half = t * np.sqrt(np.maximum(var, 0.0))
        return y - half, y + half


def fit_line(x, y, confidence: float = 0.95) -> LineFit:
    r"""Fit y = a + b x by ordinary least squares; needs >= 3 points and two distinct x.

    .. math:: b = S_{xy}/S_{xx}, \quad a = \bar y - b\bar x, \quad
              \mathrm{Cov}(a, b) = s^2 (X^T X)^{-1}, \quad s^2 = \mathrm{RSS}/(n - 2)

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
        raise FitError(f"{n} point{'' if n == 1 else 's'}: at least 3 are needed to fit a line with standard errors")
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
    r"""Fit y = b x through the origin by least squares (cohesionless soil, c = 0); needs >= 2 points.

    .. math:: b = \sum xy / \sum x^2, \quad \mathrm{se}(b) = \sqrt{s^2/\sum x^2}, \quad
              s^2 = \mathrm{RSS}/(n - 1)

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
        raise FitError(
            f"{n} point{'' if n == 1 else 's'}: at least 2 are needed to fit a line through the origin with a standard error"
        )
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


# ---------------------------------------------------------------------------------------------------------------
# Scatter that grows with stress, outliers and robust losses (capred issue 30)

from ..spec.constants import ERROR_MODELS, LOSSES  # noqa: E402 (declared once in spec: the options take them)

#: tuning constants (in units of the scale s) giving 95 % efficiency at normal errors (Huber 1981; Beaton & Tukey 1974)
HUBER_K = 1.345
TUKEY_C = 4.685
#: level of the Breusch-Pagan test behind ``errors="auto"`` and the heteroscedasticity warning
BP_LEVEL = 0.05
#: family-wise level of the outlier test (Bonferroni over the points of one fit)
OUTLIER_LEVEL = 0.05


def _exact(resid, y_scale) -> bool:
    """The residuals are rounding noise (< 1e-9 of the data's scale): nothing to test."""
    r = np.asarray(resid, dtype=float)
    return y_scale is not None and r.size > 0 and float(np.max(np.abs(r))) <= 1e-9 * y_scale


def breusch_pagan(x, resid, y_scale: float | None = None) -> dict:
    r"""Breusch-Pagan test (Koenker's studentized form) of residuals whose variance grows with x.

    .. math:: LM = n R^2_{e^2 \sim x}, \qquad p = P(\chi^2_1 > LM) = \mathrm{erfc}\sqrt{LM/2}

    with R² that of the least-squares regression of the squared residuals on (1, x). Koenker's form does not
    assume normal errors (the original LM = ESS/(2 σ⁴) does).

    Parameters
    ----------
    x : array_like
        The regressor the variance may grow with (σ_N) [any unit].
    resid : array_like
        Least-squares residuals [unit of y].
    y_scale : float, optional
        Scale of the data [unit of y]: residuals below 1e-9 of it are rounding noise of an exact fit (not tested).

    Returns
    -------
    dict
        ``statistic`` LM [-], ``p_value`` [-], ``dof`` (1), ``n``, ``significant`` (p < ``BP_LEVEL``),
        ``decision`` (text); statistic and p NaN with fewer than 3 points, a single x or an exact fit.

    References
    ----------
    .. [1] Breusch, T. S. & Pagan, A. R. (1979). A simple test for heteroscedasticity and random coefficient
       variation. Econometrica 47(5):1287-1294, doi:10.2307/1911963.
    .. [2] Koenker, R. (1981). A note on studentizing a test for heteroscedasticity. J. Econometrics
       17(1):107-112, doi:10.1016/0304-4076(81)90062-2.
    """
    x = np.asarray(x, dtype=float)
    e2 = np.asarray(resid, dtype=float) ** 2
    n = x.size
    sxx = float(np.sum((x - x.mean()) ** 2)) if n else 0.0
    tss = float(np.sum((e2 - e2.mean()) ** 2)) if n else 0.0
    if n < 3 or sxx <= 0 or tss <= 0:
        return {
            "statistic": math.nan,
            "p_value": math.nan,
            "dof": 1,
            "n": int(n),
            "significant": False,
            "decision": "not testable (fewer than 3 points, one normal stress, or no scatter)",
        }
    b = float(np.sum((x - x.mean()) * (e2 - e2.mean())) / sxx)
    r2 = b * b * sxx / tss
    lm = n * r2
    p = math.erfc(math.sqrt(lm / 2.0))
    sig = bool(p < BP_LEVEL and b > 0)
    return {
        "statistic": float(lm),
        "p_value": float(p),
        "dof": 1,
        "n": int(n),
        "significant": sig,
        "decision": (
            f"scatter grows with stress (p = {p:.3g} < {BP_LEVEL:g})" if sig else f"no significant trend (p = {p:.3g})"
        ),
    }


def choose_errors(x, y, through_origin: bool = False) -> tuple[str, dict]:
    """The rule of ``errors="auto"``: "proportional" or "constant".

    "proportional" when the Breusch-Pagan test of the least-squares residuals against x is significant at ``BP_LEVEL``
    with a variance that grows with x, else "constant".

    Parameters
    ----------
    x, y : array_like
        The points of the envelope [any consistent units].
    through_origin : bool
        Least squares through the origin.

    Returns
    -------
    (str, dict)
        The error model and the test (`breusch_pagan`).

    References
    ----------
    Koenker (1981), doi:10.1016/0304-4076(81)90062-2 (the test).
    """
    ols = (fit_line_origin if through_origin else fit_line)(x, y)
    y = np.asarray(y, float)
    test = breusch_pagan(x, y - ols.predict(x), float(np.max(np.abs(y))))
    return ("proportional" if test["significant"] else "constant"), test


def outlier_diagnostics(x, y, weights=None, through_origin: bool = False, level: float = OUTLIER_LEVEL) -> dict:
    r"""Externally studentized residuals, leverages and Cook's distances of a (weighted) least-squares line.

    .. math:: t_i = \frac{e_i}{s_{(i)}\sqrt{1 - h_{ii}}}, \quad
              s_{(i)}^2 = \frac{(n-p)s^2 - e_i^2/(1-h_{ii})}{n - p - 1}, \quad
              D_i = \frac{e_i^2}{p s^2}\frac{h_{ii}}{(1-h_{ii})^2}

    (weighted residuals e_i = sqrt(w_i) r_i). Under normal errors t_i follows Student's t with n - p - 1 dof, so
    a point is flagged when |t_i| exceeds the Bonferroni quantile t_{1 - level/(2n), n-p-1}: the chance that a fit
    without an outlier flags any of its points is at most ``level`` (5 %), and an outlier of 8 standard
    deviations among 6 tests is flagged (its t_i is far beyond the quantile, about 6.1 for n = 6).

    Parameters
    ----------
    x, y : array_like
        Points [any consistent units].
    weights : array_like, optional
        Weights w_i = 1/v_i of the fit (proportional errors).
    through_origin : bool
        Line through the origin (p = 1).
    level : float
        Family-wise level of the flags [-].

    Returns
    -------
    dict
        ``studentized``, ``leverage``, ``cooks`` (arrays), ``outlier`` (bool array), ``threshold`` [-].

    References
    ----------
    .. [1] Cook, R. D. & Weisberg, S. (1982). Residuals and Influence in Regression. Chapman & Hall
       (no DOI), ch. 2 (studentized residuals, the Bonferroni outlier test, Cook's distance).
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = x.size
    w = np.ones(n) if weights is None else np.asarray(weights, dtype=float)
    sw = np.sqrt(w)
    X = (x[:, None] if through_origin else np.column_stack([np.ones(n), x])) * sw[:, None]
    p = X.shape[1]
    nan = np.full(n, np.nan)
    out = {"studentized": nan, "leverage": nan, "cooks": nan, "outlier": np.zeros(n, bool), "threshold": math.nan}
    if n - p - 1 < 1:
        return out
    XtX_inv = np.linalg.pinv(X.T @ X)
    beta = XtX_inv @ X.T @ (y * sw)
    e = y * sw - X @ beta
    h = np.einsum("ij,jk,ik->i", X, XtX_inv, X)
    if _exact(e, float(np.max(np.abs(y * sw)))):  # an exact fit: its rounding noise is no outlier
        return {**out, "leverage": h}
    s2 = float(e @ e) / (n - p)
    one_minus_h = np.maximum(1.0 - h, 1e-12)
    s2_i = np.maximum(((n - p) * s2 - e**2 / one_minus_h) / (n - p - 1), 1e-300)
    t = e / np.sqrt(s2_i * one_minus_h)
    cooks = e**2 / (p * s2) * h / one_minus_h**2 if s2 > 0 else nan
    threshold = float(t_quantile(1.0 - level / (2.0 * n), n - p - 1))
    return {"studentized": t, "leverage": h, "cooks": cooks, "outlier": np.abs(t) > threshold, "threshold": threshold}


def _design(x, through_origin):
    return x[:, None] if through_origin else np.column_stack([np.ones(x.size), x])


def _wls(x, y, w, through_origin, X=None):
    """(beta, (X^T W X)^-1) of weighted least squares (``X``: the design `_design` gives, when built already)."""
    if X is None:
        X = _design(x, through_origin)
    XtW = X.T * w
    inv = np.linalg.inv(XtW @ X)
    return inv @ (XtW @ y), inv


def _psi(u, loss):
    """psi(u) and psi'(u) of the loss at standardised residuals u."""
    if loss == "huber":
        return np.clip(u, -HUBER_K, HUBER_K), (np.abs(u) <= HUBER_K).astype(float)
    z = u / TUKEY_C
    inside = np.abs(z) < 1
    psi = np.where(inside, u * (1 - z * z) ** 2, 0.0)
    dpsi = np.where(inside, (1 - z * z) * (1 - 5 * z * z), 0.0)
    return psi, dpsi


def _tukey_rho(z):
    """The scipy least_squares loss of Tukey's biweight: rho(z), rho'(z), rho''(z) with z = (f/f_scale)^2."""
    inside = z < 1
    zz = np.minimum(z, 1.0)
    return np.vstack(
        [
            np.where(inside, (1 - (1 - zz) ** 3) / 3.0, 1 / 3.0),
            np.where(inside, (1 - zz) ** 2, 0.0),
            np.where(inside, -2 * (1 - zz), 0.0),
        ]
    )


def _mad_scale(e, n, p):
    """1.4826 median|e| with a small-sample factor sqrt(n/(n - p)) (the fit has used p degrees of freedom)."""
    return 1.4826 * float(np.median(np.abs(e))) * math.sqrt(n / max(n - p, 1))


def fit_envelope(
    x, y, confidence: float = 0.95, through_origin: bool = False, errors: str = "constant", loss: str = "ols"
) -> LineFit:
    r"""The envelope y = a + b x under the chosen error model and loss, with intervals that hold under it.

    **Error models.** ``constant``: ordinary least squares (`fit_line`, `fit_line_origin`). ``proportional``:
    the standard deviation of a test is proportional to its expected strength, Var(y_i) = s² (ŷ_i/ref)²
    (ref the mean of y): iteratively reweighted least squares with w_i = (ref/ŷ_i)² (a fitted variance
    function, Carroll & Ruppert 1988, ch. 2), Cov(a, b) = s² (XᵀWX)⁻¹, s² = Σ w_i r_i²/(n - p), Student's t
    with n - p dof. Chosen over HC3 sandwich errors because the prediction interval of a NEW test needs its
    variance at that test's strength, which a variance function gives and HC3 does not, and because HC3 with 6
    dry tests is itself very noisy. ``auto``: `choose_errors`. ``either``: valid under both models (`_either`).

    **Losses.** ``huber`` / ``tukey``: the M-estimate minimising Σ ρ(√w_i r_i / s) (scipy.optimize.least_squares
    with Huber's loss, k = 1.345 s, or Tukey's biweight, c = 4.685 s, started from the Huber fit), s the MAD
    scale (1.4826 median |e|, re-estimated twice from the robust residuals, times sqrt(n/(n-p))); covariance by
    the sandwich

    .. math:: V = s^2 \frac{n}{n-p} A^{-1} B A^{-1}, \quad A = \sum \psi'(u_i) x_i x_i^T,
              \quad B = \sum \psi(u_i)^2 x_i x_i^T

    (Huber 1981, ch. 7), and the scatter of a new test is s² (an outlier does not widen the intervals of
    the regular tests). Student's t with n - p dof.

    Parameters
    ----------
    x, y : array_like
        σ_N and τ of the dry tests [Pa] (any consistent units).
    confidence : float
        Level of the intervals [-].
    through_origin : bool
        c = 0 imposed (``--dry-fit origin``).
    errors : {"either", "constant", "proportional", "auto"}
        Error model (``--errors``); ``either`` (`_either`): intervals at least as wide as each of the constant
        and proportional models' (valid under both, no choice made).
    loss : {"ols", "huber", "tukey"}
        Loss (``--dry-loss``).

    Returns
    -------
    LineFit
        With ``errors``, ``loss``, ``scale``, ``ref``, ``heteroscedasticity`` (`breusch_pagan` of the
        least-squares residuals) and ``diagnostics`` (`outlier_diagnostics`) filled.

    Raises
    ------
    FitError
        As `fit_line`; an unknown error model or loss.

    References
    ----------
    .. [1] Carroll, R. J. & Ruppert, D. (1988). Transformation and Weighting in Regression. Chapman & Hall,
       doi:10.1201/9780203735268, ch. 2 (variance functions, iteratively reweighted least squares).
    .. [2] Huber, P. J. (1981). Robust Statistics. Wiley, doi:10.1002/0471725250, ch. 7 (regression
       M-estimates and their asymptotic covariance).
    .. [3] Beaton, A. E. & Tukey, J. W. (1974). The fitting of power series, meaning polynomials, illustrated
       on band-spectroscopic data. Technometrics 16(2):147-185, doi:10.1080/00401706.1974.10489171 (biweight).
    .. [4] Draper & Smith (1998), doi:10.1002/9781118625590, ch. 1 and 9 (weighted least squares).
    """
    if errors not in ERROR_MODELS:
        raise FitError(f"errors must be one of {', '.join(ERROR_MODELS)} (got {errors!r})")
    if loss not in LOSSES:
        raise FitError(f"loss must be one of {', '.join(LOSSES)} (got {loss!r})")
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    ols = (fit_line_origin if through_origin else fit_line)(x, y, confidence)
    bp = breusch_pagan(x, y - ols.predict(x), float(np.max(np.abs(y))))
    if errors == "auto":
        errors = "proportional" if bp["significant"] else "constant"
    if errors == "either":
        return _either(x, y, confidence, through_origin, loss, ols, bp)
    return _fit_model(x, y, confidence, through_origin, errors, loss, ols, bp)


def _fit_model(x, y, confidence, through_origin, errors, loss, ols: LineFit, bp: dict) -> LineFit:
    """`fit_envelope` under one error model ("constant" or "proportional") and loss.

    Given the least-squares line ``ols`` of the same points and the Breusch-Pagan test ``bp`` of its residuals (computed
    once by the caller: `_either` fits both models on the same least-squares line).
    """
    n, p = x.size, 1 if through_origin else 2
    w = np.ones(n)
    ref = float(np.mean(np.abs(y))) or 1.0
    X = _design(x, through_origin)  # built once: every weighted fit below uses it
    if errors == "proportional":
        yhat = ols.predict(x)
        for _ in range(50):  # IRLS on the variance function (ŷ/ref)²: converges in a handful of steps
            level = np.maximum(np.abs(yhat), 1e-3 * ref)
            w = (ref / level) ** 2
            beta, _ = _wls(x, y, w, through_origin, X)
            new = X @ beta
            if np.max(np.abs(new - yhat)) <= 1e-12 * ref:
                yhat = new
                break
            yhat = new
        level = np.maximum(np.abs(yhat), 1e-3 * ref)
        w = (ref / level) ** 2
    diagnostics = outlier_diagnostics(x, y, w, through_origin)
    if errors == "constant" and loss == "ols":
        return dataclasses.replace(ols, heteroscedasticity=bp, diagnostics=diagnostics)
    beta, inv = _wls(x, y, w, through_origin, X)
    sw = np.sqrt(w)
    if loss == "ols":
        e = (y - X @ beta) * sw
        scale = math.sqrt(float(e @ e) / (n - p)) if n > p else math.nan
        V = scale**2 * inv
    else:
        beta, scale, V = _robust(X * sw[:, None], y * sw, beta, loss, n, p)
    cov = np.zeros((2, 2))
    if through_origin:
        cov[1, 1] = V[0, 0]
        a, b = 0.0, float(beta[0])
    else:
        cov[:, :] = V
        a, b = float(beta[0]), float(beta[1])
    resid = y - (a + b * x)
    rss = float(resid @ resid)
    tss = float(np.sum((y - y.mean()) ** 2))
    dof = n - p
    return LineFit(
        a,
        b,
        float(np.sqrt(max(cov[0, 0], 0.0))),
        float(np.sqrt(max(cov[1, 1], 0.0))),
        cov,
        n,
        rss,
        1.0 - rss / tss if tss > 0 else 1.0,
        confidence,
        t_quantile(0.5 + confidence / 2.0, dof),
        float(x.mean()),
        float(np.sum((x - x.mean()) ** 2)),
        through_origin,
        errors,
        loss,
        scale,
        ref,
        bp,
        diagnostics,
    )


def loewner_max(A, B) -> np.ndarray:
    """The covariance M >= A and M >= B (positive semi-definite order) smallest along the joint eigen-directions.

    With A = L L^T and L^-1 B L^-T = Q diag(w) Q^T, M = L Q diag(max(w, 1)) Q^T L^T.

    Every linear combination c^T theta then has c^T M c >= max(c^T A c, c^T B c), so an interval built on M
    holds under either covariance; along the directions where one dominates, M equals it.

    Parameters
    ----------
    A, B : (p, p) array_like
        Symmetric positive semi-definite covariances (rows and columns of zeros are kept at zero).

    Returns
    -------
    numpy.ndarray
        (p, p) covariance.

    References
    ----------
    Horn, R. A. & Johnson, C. R. (2013). Matrix Analysis, 2nd ed. Cambridge University Press,
    doi:10.1017/CBO9781139020411, section 7.6 (simultaneous diagonalisation of two quadratic forms).
    """
    A = np.asarray(A, dtype=float)
    B = np.asarray(B, dtype=float)
    free = np.flatnonzero((np.abs(np.diag(A)) > 0) | (np.abs(np.diag(B)) > 0))
    out = np.zeros_like(A)
    if free.size == 0:
        return out
    a, b = A[np.ix_(free, free)], B[np.ix_(free, free)]
    try:
        L = np.linalg.cholesky(a)
    except np.linalg.LinAlgError:  # A singular (an exact fit): the sum bounds both
        out[np.ix_(free, free)] = a + b
        return out
    Li = np.linalg.inv(L)
    C = Li @ b @ Li.T
    w, Q = np.linalg.eigh((C + C.T) / 2.0)
    m = L @ Q @ np.diag(np.maximum(w, 1.0)) @ Q.T @ L.T
    out[np.ix_(free, free)] = (m + m.T) / 2.0
    return out


def _either(x, y, confidence, through_origin, loss, ols: LineFit, bp: dict) -> LineFit:
    """``errors="either"`` of `fit_envelope`: intervals valid whether the scatter is constant or proportional.

    The line is that of the constant model (least squares, or the robust M-estimate of ``loss``), unbiased
    under both. Its covariance is the `loewner_max` of (i) its covariance under constant scatter and (ii) its
    covariance under scatter proportional to the strength, the sandwich
    (X^T X)^-1 X^T diag(s_p^2 v_i) X (X^T X)^-1 with v_i = (ŷ_i/ref)^2 and s_p the scale of the weighted fit
    (Carroll & Ruppert 1988, ch. 2); the variance of a new test of level y is max(s^2, s_p^2 (y/ref)^2)
    (`LineFit.variance_factor`). Each interval is thus at least as wide as the one either model gives on its
    own: no choice between them is made, so no test of low power on 6 dry tests can pick the wrong one. A dry
    test is flagged as an outlier only when the outlier test flags it under both models (`outlier_diagnostics`;
    the studentized residuals reported are the constant model's).
    """
    # both models start from the same least-squares line and its Breusch-Pagan test (``ols``, ``bp``)
    base = _fit_model(x, y, confidence, through_origin, "constant", loss, ols, bp)
    prop = _fit_model(x, y, confidence, through_origin, "proportional", loss, ols, bp)
    sp = prop.scale
    if sp is None or not np.isfinite(sp):
        return dataclasses.replace(base, errors="either")
    X = _design(x, through_origin)
    ref = prop.ref
    level = np.maximum(np.abs(prop.predict(x)), 1e-3 * ref)
    v = (level / ref) ** 2
    inv = np.linalg.inv(X.T @ X)
    Vp = inv @ ((X.T * (sp**2 * v)) @ X) @ inv
    cov_p = np.zeros((2, 2))
    if through_origin:
        cov_p[1, 1] = Vp[0, 0]
    else:
        cov_p[:, :] = Vp
    cov = loewner_max(base.covariance, cov_p)
    # an outlier is a test neither model explains: flagged by the outlier test under both error models
    diagnostics = dict(base.diagnostics or {})
    if diagnostics and prop.diagnostics:
        diagnostics["outlier"] = np.asarray(diagnostics["outlier"], bool) & np.asarray(
            prop.diagnostics["outlier"], bool
        )
    return dataclasses.replace(
        base,
        diagnostics=diagnostics,
        covariance=cov,
        intercept_se=float(np.sqrt(max(cov[0, 0], 0.0))),
        slope_se=float(np.sqrt(max(cov[1, 1], 0.0))),
        errors="either",
        scale=base.scale if base.scale is not None else math.sqrt(base.rss / base.dof) if base.dof > 0 else None,
        ref=ref,
        scale_proportional=float(sp),
    )


def _robust(Xw, yw, beta0, loss, n, p):
    """(beta, scale, covariance) of the M-estimate on the (weighted) design Xw, yw; see `fit_envelope`."""
    from scipy.optimize import least_squares

    def resid(b):
        return yw - Xw @ b

    beta = np.asarray(beta0, float)
    scale = _mad_scale(resid(beta), n, p)
    if not scale > 0:
        scale = math.sqrt(float(resid(beta) @ resid(beta)) / max(n - p, 1)) or 1.0
    for _ in range(3):  # scale and fit alternately (the scale of the OLS residuals is inflated by the outlier)
        beta = least_squares(resid, beta, loss="huber", f_scale=HUBER_K * scale, xtol=1e-14, ftol=1e-14).x
        if loss == "tukey":
            beta = least_squares(resid, beta, loss=_tukey_rho, f_scale=TUKEY_C * scale, xtol=1e-14, ftol=1e-14).x
        new = _mad_scale(resid(beta), n, p)
        if not new > 0:
            break
        scale = new
    u = resid(beta) / scale
    psi, dpsi = _psi(u, loss)
    A = (Xw.T * dpsi) @ Xw
    B = (Xw.T * psi**2) @ Xw
    try:
        Ainv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        Ainv = np.full(A.shape, np.nan)
    V = scale**2 * n / max(n - p, 1) * Ainv @ B @ Ainv
    return beta, scale, V
