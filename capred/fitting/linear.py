"""Ordinary least-squares straight line with standard errors and intervals."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import FitError


def t_quantile(p: float, dof: int) -> float:
    """Student-t quantile (scipy.special is much lighter to import than scipy.stats)."""
    from scipy.special import stdtrit

    return float(stdtrit(dof, p))


@dataclass(frozen=True)
class LineFit:
    """y = intercept + slope x fitted by ordinary least squares.

    Standard errors come from the residual variance s^2 = RSS / (n - 2) and
    (X^T X)^-1; intervals use Student's t with n - 2 degrees of freedom.
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
    def intercept_ci(self) -> tuple[float, float]:
        h = self.t * self.intercept_se
        return self.intercept - h, self.intercept + h

    @property
    def slope_ci(self) -> tuple[float, float]:
        h = self.t * self.slope_se
        return self.slope - h, self.slope + h

    def predict(self, x):
        return self.intercept + self.slope * np.asarray(x, dtype=float)

    def mean_band(self, x):
        """Lower and upper confidence band of the fitted mean line at ``x``."""
        x = np.asarray(x, dtype=float)
        cov = self.covariance
        se = np.sqrt(np.maximum(cov[0, 0] + 2 * x * cov[0, 1] + x**2 * cov[1, 1], 0.0))
        y = self.predict(x)
        return y - self.t * se, y + self.t * se


def fit_line(x, y, confidence: float = 0.95) -> LineFit:
    """Fit y = a + b x by least squares; needs >= 3 points and two distinct x."""
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
    return LineFit(intercept, slope, float(np.sqrt(cov[0, 0])), float(np.sqrt(cov[1, 1])),
                   cov, n, rss, r2, confidence, t, float(x_mean), sxx)


def fit_line_origin(x, y, confidence: float = 0.95) -> LineFit:
    """Fit y = b x through the origin by least squares (cohesionless soil, c = 0); needs >= 2 points.

    Standard error of b: sqrt(s^2 / sum x^2) with s^2 = RSS / (n - 1); R^2 is
    1 - RSS/TSS about the mean of y, as for the free fit, so both compare.
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
    return LineFit(0.0, slope, 0.0, float(np.sqrt(cov[1, 1])), cov, n, rss, r2, confidence, t,
                   float(x.mean()), float(np.sum((x - x.mean()) ** 2)), True)
