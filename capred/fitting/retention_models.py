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
from .nonlinear import NonlinearFit, fit_curve


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


def fit_model(name: str, s, y, fixed=None, weights=None) -> NonlinearFit:
    """Fit one retention model by (weighted) least squares, with automatic starts."""
    from .retention import fit_brooks_corey

    s = np.asarray(s, float)
    y = np.asarray(y, float)
    fixed = dict(fixed or {})
    if name == "bc":
        return fit_brooks_corey(s, y, fixed, weights=weights)
    model = MODELS[name]
    b = bounds_for(s, y)
    for k, v in fixed.items():
        lo, hi = b[k]
        if not lo <= v <= hi:
            raise FitError(f"fixed value {k} = {v:.6g} is outside its range [{lo:.4g}, {hi:.4g}]")
    return fit_curve(model.water, s, y, model.names, model.starts(s, y), b, fixed, weights)


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
