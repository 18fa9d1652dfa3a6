"""The water-retention models of `capred retention`, one registry entry each, and their fitting.

Suction s in Pa inside. Every model gives y(s) = y_r + (y_s - y_r) S_e(s)
except Fredlund-Xing with its correction factor, y = y_s C(s) S_e(s). Start
values are found automatically from the data (several starts, the best end
point wins); any parameter may be fixed.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import FitError
from ..physics import retention as rp
from .nonlinear import NonlinearFit, fit_curve, summarize_fit


@dataclass(frozen=True)
class RetentionModel:
    name: str
    label: str
    reference: str  # key of capred.references.REFERENCES
    names: tuple[str, ...]  # parameters (internal names, SI)
    water: Callable  # water(s, **params) -> y
    starts: Callable  # starts(s, y) -> list of dicts over ``names``

    def effective_saturation(self, s, p: dict):
        """S_e(s) in [0, 1] (for Fredlund-Xing with C: y/y_s)."""
        y = self.water(s, **p)
        y_r = p.get("y_r", 0.0)
        return (y - y_r) / (p["y_s"] - y_r)


def _smid(s):
    pos = s[s > 0]
    return float(np.median(pos)) if pos.size else 1.0


def _base(y):
    return {"y_r": max(float(np.min(y)) * 0.5, 0.0), "y_s": float(np.max(y))}


def _vg_starts(s, y, m_free=False):
    m = _smid(s)
    return [{**_base(y), "alpha": a / m, "n": n, "m": 1 - 1 / n} for a in (0.3, 1.0, 3.0)
            for n in (1.3, 2.0, 4.0, 10.0, 20.0)]


def _kosugi_starts(s, y):
    m = _smid(s)
    return [{**_base(y), "s_m": f * m, "sigma": sg} for f in (0.5, 1.0, 2.0) for sg in (0.1, 0.4, 1.2)]


def _fx_starts(s, y, with_c):
    m = _smid(s)
    smax = float(np.max(s)) if s.size else 1.0
    out = []
    for f in (0.5, 1.0, 2.0):
        for n in (2.0, 5.0, 20.0):
            for mm in (0.5, 1.0, 2.0):
                p = {**_base(y), "a": f * m, "n": n, "m": mm}
                if with_c:
                    p["s_r"] = 10.0 * smax
                out.append(p)
    return out


def _durner_starts(s, y):
    m = _smid(s)
    return [{**_base(y), "w1": w, "alpha1": a1 / m, "n1": n1, "alpha2": a2 / m, "n2": n2}
            for w in (0.3, 0.7) for a1, a2 in ((3.0, 0.1), (1.0, 0.03)) for n1, n2 in ((4.0, 1.5), (10.0, 2.0))]


MODELS: dict[str, RetentionModel] = {m.name: m for m in (
    RetentionModel("vg", "van Genuchten, m = 1 - 1/n", "vangenuchten1980", ("y_r", "y_s", "alpha", "n"),
                   lambda s, y_r, y_s, alpha, n: rp.vg_water(s, y_r, y_s, alpha, n), _vg_starts),
    RetentionModel("vg_m_free", "van Genuchten, m free", "vangenuchten1980", ("y_r", "y_s", "alpha", "n", "m"),
                   lambda s, y_r, y_s, alpha, n, m: rp.vg_water(s, y_r, y_s, alpha, n, m),
                   lambda s, y: _vg_starts(s, y, True)),
    RetentionModel("bc", "Brooks-Corey", "brooks_corey1964", ("y_r", "y_s", "s_e", "lam"),
                   lambda s, y_r, y_s, s_e, lam: rp.bc_water(s, y_r, y_s, s_e, lam), lambda s, y: []),
    RetentionModel("kosugi", "Kosugi (lognormal)", "kosugi1996", ("y_r", "y_s", "s_m", "sigma"),
                   lambda s, y_r, y_s, s_m, sigma: y_r + (y_s - y_r) * rp.kosugi_effective_saturation(s, s_m, sigma),
                   _kosugi_starts),
    RetentionModel("fx", "Fredlund-Xing with C(s)", "fredlund_xing1994", ("y_s", "a", "n", "m", "s_r"),
                   lambda s, y_s, a, n, m, s_r: y_s * rp.fx_correction(s, s_r) * rp.fx_shape(s, a, n, m),
                   lambda s, y: [{k: v for k, v in p.items() if k != "y_r"} for p in _fx_starts(s, y, True)]),
    RetentionModel("fx_no_c", "Fredlund-Xing without C(s)", "fredlund_xing1994", ("y_r", "y_s", "a", "n", "m"),
                   lambda s, y_r, y_s, a, n, m: y_r + (y_s - y_r) * rp.fx_shape(s, a, n, m),
                   lambda s, y: _fx_starts(s, y, False)),
    RetentionModel("durner", "Durner (bimodal van Genuchten)", "durner1994",
                   ("y_r", "y_s", "w1", "alpha1", "n1", "alpha2", "n2"),
                   lambda s, y_r, y_s, w1, alpha1, n1, alpha2, n2: y_r + (y_s - y_r) * rp.durner_effective_saturation(
                       s, w1, alpha1, n1, alpha2, n2), _durner_starts),
)}


def bounds_for(s, y) -> dict[str, tuple[float, float]]:
    top = max(1.0, float(np.max(y)))
    pos = s[s > 0]
    smin = float(pos.min()) if pos.size else 1.0
    smax = float(s.max()) if s.size else 1.0
    return {
        "y_r": (0.0, float(np.max(y))), "y_s": (float(np.min(y)), top),
        "alpha": (1e-3 / smax, 1e3 / smin), "alpha1": (1e-3 / smax, 1e3 / smin), "alpha2": (1e-3 / smax, 1e3 / smin),
        "n": (1.005, 100.0), "n1": (1.005, 100.0), "n2": (1.005, 100.0), "m": (1e-3, 20.0), "w1": (0.0, 1.0),
        "s_e": (smin * 1e-3, smax), "lam": (1e-3, 50.0),
        "s_m": (smin * 1e-3, smax * 1e3), "sigma": (1e-3, 10.0),
        "a": (smin * 1e-3, smax * 1e3), "s_r": (smin, 1e9),
    }


class _VarPro:
    """Variable projection: for given shape parameters the linear ones (y_r, y_s) are solved exactly.

    y = y_r (1 - S) + y_s S with S = S_e(s; shape) (Fredlund-Xing with C: y = y_s S), so the least-squares
    problem shrinks to the shape parameters; y_r and y_s are the (bounded) weighted linear solution.
    """

    def __init__(self, model: RetentionModel, s, y, sw, fixed, bounds):
        self.model, self.s, self.y, self.sw, self.fixed, self.b = model, s, y, sw, fixed, bounds
        self.lin = [k for k in ("y_r", "y_s") if k in model.names and k not in fixed]
        self.shape = [k for k in model.names if k not in ("y_r", "y_s") and k not in fixed]

    def S(self, theta) -> np.ndarray:
        p = {**self.fixed, **dict(zip(self.shape, theta))}
        if "y_r" in self.model.names:
            p["y_r"] = 0.0
        p["y_s"] = 1.0
        return self.model.water(self.s, **p)

    def linear(self, S) -> dict[str, float]:
        """Weighted least squares of (y_r, y_s) given S, within their bounds (0 <= y_r <= y_s)."""
        cols = {"y_r": 1.0 - S, "y_s": S} if "y_r" in self.model.names else {"y_s": S}
        rhs = self.y.copy()
        for k, v in self.fixed.items():
            if k in cols:
                rhs = rhs - v * cols[k]
        if not self.lin:
            return {}
        w2 = self.sw**2
        if len(self.lin) == 2:  # the 2 x 2 normal equations, solved in closed form
            c1, c2 = cols[self.lin[0]], cols[self.lin[1]]
            a11, a12, a22 = (w2 * c1 * c1).sum(), (w2 * c1 * c2).sum(), (w2 * c2 * c2).sum()
            b1, b2 = (w2 * c1 * rhs).sum(), (w2 * c2 * rhs).sum()
            det = a11 * a22 - a12 * a12
            beta = [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det] if det > 0 else [np.nan, np.nan]
        else:
            c = cols[self.lin[0]]
            beta = [(w2 * c * rhs).sum() / max((w2 * c * c).sum(), 1e-300)]
        if not np.all(np.isfinite(beta)):
            beta = [self.b[k][0] if k == "y_r" else float(np.max(self.y)) for k in self.lin]
        out = dict(zip(self.lin, (float(v) for v in beta)))
        clipped = {k: float(np.clip(v, *self.b[k])) for k, v in out.items()}
        if clipped != out and len(self.lin) == 2:  # one at its bound: the other by 1-D least squares
            best = None
            for k in self.lin:
                other = self.lin[1 - self.lin.index(k)]
                xk = clipped[k]
                r = rhs - xk * cols[k]
                xo = float(np.clip((cols[other] * self.sw**2) @ r / max((cols[other] ** 2 * self.sw**2).sum(), 1e-300),
                                   *self.b[other]))
                cand = {k: xk, other: xo}
                res = self.resid_with(S, cand)
                if best is None or res @ res < best[0]:
                    best = (res @ res, cand)
            return best[1]
        return clipped

    def resid_with(self, S, lin) -> np.ndarray:
        p = {**{k: v for k, v in self.fixed.items() if k in ("y_r", "y_s")}, **lin}
        y_r = p.get("y_r", 0.0)
        return (y_r + (p["y_s"] - y_r) * S - self.y) * self.sw

    def resid(self, theta) -> np.ndarray:
        S = self.S(theta)
        return self.resid_with(S, self.linear(S))

    def rss(self, theta) -> float:
        r = self.resid(theta)
        return float(r @ r) if np.all(np.isfinite(r)) else np.inf

    def full(self, theta) -> dict:
        S = self.S(theta)
        return {**self.fixed, **dict(zip(self.shape, theta)), **self.linear(S)}


def fit_model(name: str, s, y, fixed=None, weights=None) -> NonlinearFit:
    """Fit one retention model by (weighted) least squares, with automatic starts.

    The linear parameters are projected out (variable projection), the starts
    are screened by their projected residual and only the best two are
    optimised; a last full fit from the optimum gives the standard errors.
    Brooks-Corey, whose objective has kinks at the data suctions, profiles
    the air-entry suction over a grid first.
    """
    from scipy.optimize import least_squares

    s = np.asarray(s, float)
    y = np.asarray(y, float)
    fixed = dict(fixed or {})
    model = MODELS[name]
    if not np.all(np.isfinite(s)) or not np.all(np.isfinite(y)) or np.any(s < 0):
        raise FitError("the retention data hold negative, NaN or infinite values")
    if np.unique(s[s > 0]).size < 2:
        raise FitError("fewer than two distinct positive suctions: no retention curve can be fitted")
    b = bounds_for(s, y)
    for k, v in fixed.items():
        lo, hi = b[k]
        if not lo <= v <= hi:
            raise FitError(f"fixed value {k} = {v:.6g} is outside its range [{lo:.4g}, {hi:.4g}]")
    free = [k for k in model.names if k not in fixed]
    if s.size <= len(free):
        raise FitError(f"{s.size} points for {len(free)} free parameters: too few to fit")

    sw = np.ones_like(y) if weights is None else np.sqrt(np.asarray(weights, float))
    vp = _VarPro(model, s, y, sw, fixed, b)
    lo = np.array([b[k][0] for k in vp.shape])
    hi = np.array([b[k][1] for k in vp.shape])
    if name == "bc" and "s_e" in vp.shape:
        candidates = _bc_profile(vp, s, lo, hi)[:1]
    else:
        starts = [np.clip([st[k] for k in vp.shape], lo, hi) for st in model.starts(s, y)]
        candidates = sorted(starts, key=vp.rss)[:2]
    best = None
    for x0 in candidates:
        if not vp.shape:
            break
        x0 = np.clip(x0, lo + 1e-12 * (hi - lo), hi - 1e-12 * (hi - lo))
        r = least_squares(vp.resid, x0, bounds=(lo, hi), x_scale="jac", xtol=1e-14, ftol=1e-14, gtol=1e-14,
                          max_nfev=2000)
        if np.all(np.isfinite(r.fun)) and (best is None or r.cost < best.cost):
            best = r
    optimum = vp.full(best.x if best is not None else np.array([]))
    return summarize_fit(model.water, s, y, model.names, optimum, b, fixed, weights,
                         converged=best is None or bool(best.success))


def _bc_profile(vp: _VarPro, s, lo, hi) -> list:
    """Starts for Brooks-Corey: the projected RSS on a grid of (air-entry suction, lambda), all at once.

    The objective has kinks where s_e passes a data suction, so a local
    optimiser alone may stop in the wrong cell; the grid finds the right one.
    """
    i_se = vp.shape.index("s_e")
    i_lam = vp.shape.index("lam") if "lam" in vp.shape else None
    pos = s[s > 0]
    se = np.geomspace(max(pos.min() * 0.3, lo[i_se]), hi[i_se], 40)[:, None, None]
    lam = (np.geomspace(lo[i_lam], hi[i_lam], 40) if i_lam is not None else
           np.array([vp.fixed["lam"]]))[None, :, None]
    keep = np.arange(s.size) if s.size <= 400 else np.linspace(0, s.size - 1, 400).astype(int)  # for the start only
    x = s[keep][None, None, :]
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        S = np.where(x > se, (se / np.where(x > 0, x, 1.0)) ** lam, 1.0)
    w2 = (vp.sw[keep] ** 2)[None, None, :]
    y = vp.y[keep][None, None, :]
    c1, c2 = 1.0 - S, S
    a11, a12, a22 = (w2 * c1 * c1).sum(-1), (w2 * c1 * c2).sum(-1), (w2 * c2 * c2).sum(-1)
    b1, b2 = (w2 * c1 * y).sum(-1), (w2 * c2 * y).sum(-1)
    det = a11 * a22 - a12 * a12
    with np.errstate(divide="ignore", invalid="ignore"):
        y_r = np.clip((a22 * b1 - a12 * b2) / det, *vp.b["y_r"])
        y_s = np.clip((a11 * b2 - a12 * b1) / det, *vp.b["y_s"])
        rss = (w2 * (y - y_r[..., None] * c1 - y_s[..., None] * c2) ** 2).sum(-1)
    rss = np.where(np.isfinite(rss), rss, np.inf)
    g, k = np.unravel_index(int(np.argmin(rss)), rss.shape)
    theta = np.array([float(se[g, 0, 0]) if n == "s_e" else float(lam[0, k, 0]) for n in vp.shape])
    return [theta]


def confidence_band(name: str, fit: NonlinearFit, s_grid, level_t: float | None = None):
    """Lower and upper 95 % confidence band of the fitted curve at ``s_grid`` (delta method)."""
    model = MODELS[name]
    s_grid = np.asarray(s_grid, float)
    base = model.water(s_grid, **fit.params)
    if fit.covariance is None or not fit.free:
        return base, base
    cols = []
    for k in fit.free:
        h = 1e-6 * max(abs(fit.params[k]), 1e-12)
        up = dict(fit.params, **{k: fit.params[k] + h})
        dn = dict(fit.params, **{k: fit.params[k] - h})
        cols.append((model.water(s_grid, **up) - model.water(s_grid, **dn)) / (2 * h))
    J = np.column_stack(cols)
    var = np.einsum("ij,jk,ik->i", J, fit.covariance, J)
    half = (level_t if level_t is not None else fit.t) * np.sqrt(np.maximum(var, 0.0))
    return base - half, base + half


def fit_hysteresis(s_d, y_d, s_w, y_w, fixed=None, weights=None) -> NonlinearFit:
    """Kool & Parker (1987): drying and wetting branches fitted jointly by van Genuchten (m = 1 - 1/n) with
    shared y_s, y_r and n and separate alpha_d (drying) and alpha_w (wetting)."""
    s = np.concatenate([np.asarray(s_d, float), np.asarray(s_w, float)])
    y = np.concatenate([np.asarray(y_d, float), np.asarray(y_w, float)])
    branch = np.concatenate([np.zeros(len(s_d)), np.ones(len(s_w))])

    def water(x, y_r, y_s, n, alpha_d, alpha_w):
        alpha = np.where(branch == 0, alpha_d, alpha_w)
        return rp.vg_water(x, y_r, y_s, alpha, n)

    b = bounds_for(s, y)
    b = {**b, "alpha_d": b["alpha"], "alpha_w": b["alpha"]}
    m = _smid(s)
    starts = [{**_base(y), "n": n, "alpha_d": a / m, "alpha_w": a * r / m} for a in (0.3, 1.0, 3.0)
              for n in (1.5, 3.0, 8.0) for r in (1.0, 2.0)]
    return fit_curve(water, s, y, ("y_r", "y_s", "n", "alpha_d", "alpha_w"), starts, b, fixed, weights)
