"""Fits of van Genuchten and Brooks-Corey retention curves (suction in Pa)."""
from __future__ import annotations

import numpy as np

from ..errors import FitError
from ..physics.retention import bc_water, vg_water
from .nonlinear import NonlinearFit, fit_curve

VG_NAMES = ("y_r", "y_s", "alpha", "n")
VG_FREE_M_NAMES = ("y_r", "y_s", "alpha", "n", "m")
BC_NAMES = ("y_r", "y_s", "s_e", "lam")


def _bounds(y, s):
    top = max(1.0, float(np.max(y)))
    spos = s[s > 0]
    smin = float(spos.min()) if spos.size else 1.0
    smax = float(s.max()) if s.size else 1.0
    return {
        "y_r": (0.0, float(np.max(y))),
        "y_s": (float(np.min(y)), top),
        "alpha": (1e-3 / smax, 1e3 / smin),
        "n": (1.005, 100.0),
        "m": (1e-3, 20.0),
        "s_e": (smin * 1e-3, smax),
        "lam": (1e-3, 50.0),
    }


def _check(s, y, fixed, bounds):
    if s.size != y.size or s.size == 0:
        raise FitError("no retention data to fit")
    if np.any(s < 0):
        raise FitError("negative suction in the retention data")
    for k, v in fixed.items():
        lo, hi = bounds[k]
        if not lo <= v <= hi:
            raise FitError(f"fixed value {k} = {v:.6g} is outside its range [{lo:.4g}, {hi:.4g}]")


def fit_van_genuchten(s, y, fixed=None, bounds=None, m_free=False) -> NonlinearFit:
    """Least squares on y (unweighted) of y_r + (y_s - y_r)[1 + (alpha s)^n]^(-m).

    m = 1 - 1/n (Mualem constraint) unless ``m_free``. Several starts over
    alpha and n; the lowest residual sum of squares wins.
    """
    s = np.asarray(s, float)
    y = np.asarray(y, float)
    b = {**_bounds(y, s), **(bounds or {})}
    fixed = dict(fixed or {})
    _check(s, y, fixed, b)
    spos = s[s > 0]
    s_mid = float(np.median(spos)) if spos.size else 1.0
    starts = [
        {"y_r": max(float(y.min()) * 0.5, 0.0), "y_s": float(y.max()), "alpha": a / s_mid, "n": n, "m": 1 - 1 / n}
        for a in (0.3, 1.0, 3.0) for n in (1.3, 2.0, 4.0, 10.0, 20.0)
    ]
    if m_free:
        model = lambda x, y_r, y_s, alpha, n, m: vg_water(x, y_r, y_s, alpha, n, m)  # noqa: E731
        return fit_curve(model, s, y, VG_FREE_M_NAMES, starts, b, fixed)
    model = lambda x, y_r, y_s, alpha, n: vg_water(x, y_r, y_s, alpha, n)  # noqa: E731
    return fit_curve(model, s, y, VG_NAMES, starts, b, fixed)


def fit_brooks_corey(s, y, fixed=None, bounds=None, weights=None) -> NonlinearFit:
    """Least squares of y_r + (y_s - y_r)(s_e/s)^lambda (s > s_e), y_s below s_e.

    The objective has kinks at the data suctions as s_e moves past them, so
    s_e is profiled: a scan over a log grid with (y_r, y_s, lambda) fitted at
    each value, a bounded refinement around the best, then a final fit of all
    free parameters from there (standard errors from that last Jacobian).
    """
    from scipy.optimize import minimize_scalar

    s = np.asarray(s, float)
    y = np.asarray(y, float)
    b = {**_bounds(y, s), **(bounds or {})}
    fixed = dict(fixed or {})
    _check(s, y, fixed, b)
    model = lambda x, y_r, y_s, s_e, lam: bc_water(x, y_r, y_s, s_e, lam)  # noqa: E731
    start = {"y_r": max(float(y.min()) * 0.5, 0.0), "y_s": float(y.max()), "lam": 1.0}
    starts = [dict(start, lam=v) for v in (0.3, 1.0, 4.0)]

    def profile(log_se: float) -> float:
        inner = dict(fixed, s_e=float(np.exp(log_se)))
        try:
            return fit_curve(model, s, y, BC_NAMES, [dict(st, s_e=inner["s_e"]) for st in starts], b, inner,
                             weights).rss
        except FitError:
            return np.inf

    if "s_e" in fixed:
        return fit_curve(model, s, y, BC_NAMES, [dict(st, s_e=fixed["s_e"]) for st in starts], b, fixed, weights)
    lo, hi = np.log(b["s_e"][0]), np.log(b["s_e"][1])
    grid = np.linspace(max(lo, np.log(max(s[s > 0].min() * 0.3, b["s_e"][0]))), hi, 60)
    rss = np.array([profile(g) for g in grid])
    k = int(np.argmin(rss))
    a, c = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    best = minimize_scalar(profile, bounds=(a, c), method="bounded", options={"xatol": 1e-10})
    log_se = best.x if best.fun <= rss[k] else grid[k]
    s_e = float(np.exp(log_se))
    inner = fit_curve(model, s, y, BC_NAMES, [dict(st, s_e=s_e) for st in starts], b, dict(fixed, s_e=s_e), weights)
    final = fit_curve(model, s, y, BC_NAMES, [inner.params], b, fixed, weights)
    return final if final.rss <= inner.rss * (1 + 1e-12) else _unfix(inner, "s_e")


def _unfix(fit: NonlinearFit, name: str) -> NonlinearFit:
    """A profiled parameter is an estimate, not a user-fixed value (its standard error stays unknown)."""
    fit.fixed = tuple(k for k in fit.fixed if k != name)
    fit.aic += 2
    fit.bic += np.log(fit.n)
    return fit
