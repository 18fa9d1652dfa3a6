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

    @property
    def nfree(self) -> int:
        return len(self.params) - len(self.fixed)

    @property
    def dof(self) -> int:
        return self.n - self.nfree


def fit_curve(model, x, y, names, starts, bounds, fixed=None) -> NonlinearFit:
    """Minimise sum (model(x, **p) - y)^2 over the free parameters.

    ``starts``: list of dicts of initial values (all names); the best end point
    wins. ``bounds``: {name: (lo, hi)}. ``fixed``: {name: value}.
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

    def resid(v):
        return model(x, **full(v)) - y

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
    n = len(y)
    k = len(free)
    tss = float(np.sum((y - y.mean()) ** 2))
    s2 = rss / (n - k)
    try:
        cov = np.linalg.inv(best.jac.T @ best.jac) * s2
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        se = np.full(k, np.nan)
    stderr: dict[str, float | None] = {name: None for name in names}
    stderr.update({name: float(v) for name, v in zip(free, se)})
    rss_n = max(rss / n, 1e-300)
    return NonlinearFit(
        params={name: float(full(best.x)[name]) for name in names},
        stderr=stderr, fixed=tuple(fixed), n=n, rss=rss,
        r2=1.0 - rss / tss if tss > 0 else float("nan"),
        aic=n * np.log(rss_n) + 2 * k, bic=n * np.log(rss_n) + k * np.log(n),
        converged=bool(best.success), message=str(best.message),
    )
