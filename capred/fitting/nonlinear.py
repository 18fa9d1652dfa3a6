"""Bounded nonlinear least squares with fixed parameters, several starts and
standard errors (lmfit-style result object, built on scipy.optimize)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import FitError


@dataclass
class NonlinearFit:
    """Estimates, standard errors (None for fixed parameters), n, dof, RSS, R^2, AIC, BIC."""

    params: dict[str, float]
    stderr: dict[str, float | None]
    fixed: tuple[str, ...]
    n: int
    rss: float
    r2: float
    aic: float
    bic: float
    converged: bool
    message: str = ""
    extra: dict = field(default_factory=dict)
    covariance: np.ndarray | None = None  # of the free parameters, in the order of ``free``
    free: tuple[str, ...] = ()
    bounds: dict = field(default_factory=dict)
    t: float = float("nan")  # Student t of the 95 % intervals (dof = n - free)

    @property
    def aicc(self) -> float:
        """AIC with the small-sample correction: AIC + 2k(k + 1)/(n - k - 1) (k free parameters)."""
        k = self.nfree
        return self.aic + 2 * k * (k + 1) / (self.n - k - 1) if self.n - k - 1 > 0 else float("nan")

    @property
    def rmse(self) -> float:
        return float(np.sqrt(self.rss / self.n))

    def ci95(self, name: str) -> tuple[float, float] | None:
        se = self.stderr.get(name)
        if se is None or not np.isfinite(se):
            return None
        return self.params[name] - self.t * se, self.params[name] + self.t * se

    def correlation(self) -> dict[str, dict[str, float]]:
        """Correlation matrix of the free parameters (unsatfit and SWRC Fit report it)."""
        if self.covariance is None:
            return {}
        sd = np.sqrt(np.clip(np.diag(self.covariance), 1e-300, None))
        r = self.covariance / np.outer(sd, sd)
        return {a: {b: float(r[i, j]) for j, b in enumerate(self.free)} for i, a in enumerate(self.free)}

    def at_bounds(self, rel: float = 1e-6) -> list[str]:
        """Free parameters that ended on (within ``rel`` of the range of) their bounds."""
        out = []
        for k in self.free:
            lo, hi = self.bounds.get(k, (-np.inf, np.inf))
            span = (hi - lo) if np.isfinite(hi - lo) else max(abs(self.params[k]), 1.0)
            if self.params[k] <= lo + rel * span or self.params[k] >= hi - rel * span:
                out.append(k)
        return out

    @property
    def nfree(self) -> int:
        return len(self.params) - len(self.fixed)

    @property
    def dof(self) -> int:
        return self.n - self.nfree


def fit_curve(model, x, y, names, starts, bounds, fixed=None, weights=None) -> NonlinearFit:
    """Minimise sum w (model(x, **p) - y)^2 over the free parameters.

    ``starts``: list of dicts of initial values (all names); the best end point
    wins. ``bounds``: {name: (lo, hi)}. ``fixed``: {name: value}.
    ``weights``: per-point weights (default 1); RSS, R^2 and the criteria are weighted.
    """
    from scipy.optimize import least_squares

    x = np.asarray(x, float)
    y = np.asarray(y, float)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise FitError("the data to fit contain NaN or infinite values")
    fixed = dict(fixed or {})
    free = [k for k in names if k not in fixed]
    if len(y) <= len(free):
        raise FitError(f"{len(y)} points for {len(free)} free parameters: too few to fit")
    lo = np.array([bounds[k][0] for k in free], float)
    hi = np.array([bounds[k][1] for k in free], float)

    def full(v):
        p = dict(fixed)
        p.update(zip(free, v))
        return p

    sw = np.ones_like(y) if weights is None else np.sqrt(np.asarray(weights, float))

    def resid(v):
        return (model(x, **full(v)) - y) * sw

    best = None
    for start in starts:
        v0 = np.clip([start[k] for k in free], lo + 1e-12 * (hi - lo), hi - 1e-12 * (hi - lo))
        try:
            r = least_squares(resid, v0, bounds=(lo, hi), method="trf", x_scale="jac",
                              xtol=1e-14, ftol=1e-14, gtol=1e-14, max_nfev=4000)
        except ValueError:
            continue
        if np.all(np.isfinite(r.fun)) and (best is None or r.cost < best.cost):
            best = r
    if best is None:
        raise FitError("the fit did not converge from any starting point")
    rss = float(2.0 * best.cost)
    return _assemble(names, full(best.x), fixed, free, y, sw, rss, best.jac, bounds, bool(best.success),
                     str(best.message))


def _assemble(names, params, fixed, free, y, sw, rss, jac, bounds, converged, message="") -> NonlinearFit:
    """The fit statistics: weighted R^2, AIC/BIC, standard errors and covariance from the Jacobian."""
    n, k = len(y), len(free)
    wts = sw**2
    ybar = float(np.sum(wts * y) / np.sum(wts))
    tss = float(np.sum(wts * (y - ybar) ** 2))
    try:
        cov = np.linalg.inv(jac.T @ jac) * rss / (n - k)
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        cov, se = None, np.full(k, np.nan)
    stderr: dict[str, float | None] = {name: None for name in names}
    stderr.update({name: float(v) for name, v in zip(free, se)})
    rss_n = max(rss / n, 1e-300)
    return NonlinearFit(
        params={name: float(params[name]) for name in names}, stderr=stderr, fixed=tuple(fixed), n=n, rss=rss,
        r2=1.0 - rss / tss if tss > 0 else float("nan"),
        aic=n * np.log(rss_n) + 2 * k, bic=n * np.log(rss_n) + k * np.log(n),
        converged=converged, message=message, covariance=cov, free=tuple(free),
        bounds={k_: tuple(bounds[k_]) for k_ in free}, t=_t95(n - k),
    )


def _t95(dof: int) -> float:
    from .linear import t_quantile

    return t_quantile(0.975, dof) if dof > 0 else float("nan")


def summarize_fit(model, x, y, names, params: dict, bounds, fixed=None, weights=None,
                  converged: bool = True) -> NonlinearFit:
    """The NonlinearFit of given optimal parameters (no optimisation): RSS, R^2, criteria, and standard
    errors from a central-difference Jacobian of the weighted residuals."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    fixed = dict(fixed or {})
    free = [k for k in names if k not in fixed]
    sw = np.ones_like(y) if weights is None else np.sqrt(np.asarray(weights, float))
    r = (model(x, **params) - y) * sw
    cols = []
    for k in free:
        h = 1e-7 * max(abs(params[k]), 1e-12)
        lo, hi = bounds[k]
        up, dn = min(params[k] + h, hi), max(params[k] - h, lo)
        cols.append((model(x, **{**params, k: up}) - model(x, **{**params, k: dn})) * sw / (up - dn))
    jac = np.column_stack(cols) if cols else np.empty((x.size, 0))
    return _assemble(names, params, fixed, free, y, sw, float(r @ r), jac, bounds, converged)
