"""One-parameter chi laws fitted per material on the wet tests, and the information criteria.

With the dry envelope (c, tan phi) held, a wet test's strength is
tau = c + (sigma_N + chi Delta_u) tan phi; the law's parameters are fitted by
least squares on the measured tau. Standard errors come from the Jacobian,
se = sqrt(diag(s^2 (J^T J)^-1)) with s^2 = RSS / (n - p).

Information criteria use Gaussian errors of unknown variance, the same for
every model on the same wet tests: with k = p + 1 (the p fitted parameters
and the error variance; the dry c and phi are common to all models and not
counted), AIC = n ln(RSS/n) + 2k, AICc = AIC + 2k(k + 1)/(n - k - 1),
BIC = n ln(RSS/n) + k ln(n) (Burnham & Anderson's small-sample forms).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class FittedLaw:
    params: dict[str, float]  # SI (s_b in Pa)
    se: dict[str, float | None]
    rss: float  # Pa^2
    n: int
    converged: bool
    fixed: tuple[str, ...] = ()
    at_bound: list[str] = field(default_factory=list)


def information_criteria(rss: float, n: int, p: int) -> dict[str, float | None]:
    """AIC, AICc and BIC of a least-squares fit with p fitted parameters on n points (k = p + 1)."""
    k = p + 1
    if n <= 0 or rss <= 0:
        return {"aic": None, "aicc": None, "bic": None}
    base = n * np.log(rss / n)
    aic = base + 2 * k
    aicc = aic + 2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else None
    return {"aic": float(aic), "aicc": None if aicc is None else float(aicc), "bic": float(base + k * np.log(n))}


def akaike_weights(aicc: dict[str, float | None]) -> dict[str, tuple[float | None, float | None]]:
    """(delta AICc, Akaike weight) of each model; models without an AICc get (None, None)."""
    finite = {m: a for m, a in aicc.items() if a is not None and np.isfinite(a)}
    if not finite:
        return {m: (None, None) for m in aicc}
    best = min(finite.values())
    rel = {m: np.exp(-0.5 * (a - best)) for m, a in finite.items()}
    total = sum(rel.values())
    return {m: ((finite[m] - best, rel[m] / total) if m in finite else (None, None)) for m in aicc}


def _se_from_jacobian(jac: np.ndarray, rss: float, n: int) -> np.ndarray:
    p = jac.shape[1]
    if n - p <= 0:
        return np.full(p, np.nan)
    try:
        cov = np.linalg.inv(jac.T @ jac) * rss / (n - p)
    except np.linalg.LinAlgError:
        return np.full(p, np.nan)
    return np.sqrt(np.maximum(np.diag(cov), 0.0))


def fit_chi_power(sigma_N, suction, S_R, tau, c, tan_phi, S_res: float = 0.0, start: dict | None = None) -> FittedLaw:
    """kappa > 0 of chi = S_e^kappa, S_e = (S_R - S_res)/(1 - S_res) (the form of Vanapalli et al. 1996).

    Three starting values (0.3, 1, 3), or one from ``start`` (a warm start, as in the bootstrap).
    """
    from scipy.optimize import least_squares

    S_e = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 1e-300, 1.0)
    scale = max(float(np.std(tau)), 1.0)

    def resid(p):
        return (c + (sigma_N + S_e ** p[0] * suction) * tan_phi - tau) / scale

    lo, hi = 1e-6, 100.0
    best = min((least_squares(resid, [k0], bounds=([lo], [hi]), xtol=1e-14, ftol=1e-14, gtol=1e-14)
                for k0 in ((start["kappa"],) if start else (0.3, 1.0, 3.0))), key=lambda r: r.cost)
    kappa = float(best.x[0])
    r = resid(best.x) * scale
    rss = float(r @ r)
    jac = (tan_phi * suction * S_e**kappa * np.log(S_e))[:, None]
    se = _se_from_jacobian(jac, rss, r.size)
    at_bound = ["kappa"] if (kappa <= lo * 1.001 or kappa >= hi * 0.999) else []
    return FittedLaw({"kappa": kappa}, {"kappa": _finite(se[0])}, rss, int(r.size), bool(best.success),
                     at_bound=at_bound)


def fit_khalili(sigma_N, suction, S_R, tau, c, tan_phi, eta: float = 0.55, fit_eta: bool = False,
                start: dict | None = None) -> FittedLaw:
    """s_b (and eta with ``fit_eta``) of chi = (s/s_b)^-eta for s > s_b, else 1 (Khalili & Khabbaz 1998).

    The objective is not smooth where s_b passes a measured suction, so s_b is
    first located on a fine logarithmic grid and then refined locally (from
    ``start`` alone when given: a warm start, as in the bootstrap).
    """
    from scipy.optimize import least_squares

    s = np.asarray(suction, float)
    pos = s[s > 0]
    if pos.size == 0:
        return FittedLaw({"s_b": float("nan"), "eta": eta}, {"s_b": None, "eta": None}, float("nan"), s.size, False)
    lo, hi = float(pos.min()) / 100.0, float(pos.max()) * 100.0

    def resid(p):
        e = p[1] if fit_eta else eta
        chi = np.where(s > np.exp(p[0]), (np.where(s > 0, s, 1.0) / np.exp(p[0])) ** -e, 1.0)
        return c + (sigma_N + chi * s) * tan_phi - tau

    if start is not None and np.isfinite(start.get("s_b", np.nan)):
        g0, e0 = float(np.clip(np.log(start["s_b"]), np.log(lo), np.log(hi))), start.get("eta", eta)
        costs = [(float(resid([g0, e0]) @ resid([g0, e0])), g0, e0)]
    else:
        grid = np.linspace(np.log(lo), np.log(hi), 400)
        etas = np.linspace(0.05, 2.0, 40) if fit_eta else [eta]
        costs = [(float(resid([g, e]) @ resid([g, e])), g, e) for g in grid for e in etas]
    _, g0, e0 = min(costs)
    x0 = [g0, e0] if fit_eta else [g0]
    bounds = ([np.log(lo), 1e-3], [np.log(hi), 10.0]) if fit_eta else ([np.log(lo)], [np.log(hi)])
    res = least_squares(lambda p: resid(p if fit_eta else [p[0], eta]), x0, bounds=bounds, xtol=1e-14, ftol=1e-14)
    p = res.x if res.cost <= 0.5 * min(costs)[0] else np.array(x0)
    r = resid(p if fit_eta else [p[0], eta])
    rss = float(r @ r)
    # standard errors by central differences on (s_b, eta), the physical parameters
    s_b = float(np.exp(p[0]))
    e_hat = float(p[1]) if fit_eta else eta
    cols = []
    for k, value in enumerate([s_b, e_hat][: 2 if fit_eta else 1]):
        h = 1e-6 * abs(value)
        up, dn = [np.log(s_b), e_hat], [np.log(s_b), e_hat]
        if k == 0:
            up[0], dn[0] = np.log(s_b + h), np.log(s_b - h)
        else:
            up[1], dn[1] = e_hat + h, e_hat - h
        cols.append((resid(up) - resid(dn)) / (2 * h))
    se = _se_from_jacobian(np.column_stack(cols), rss, r.size)
    at_bound = [name for name, v, (a, b) in (("s_b", s_b, (lo, hi)),) + ((("eta", e_hat, (1e-3, 10.0)),)
                if fit_eta else ()) if v <= a * 1.001 or v >= b * 0.999]
    return FittedLaw({"s_b": s_b, "eta": e_hat}, {"s_b": _finite(se[0]), "eta": _finite(se[1]) if fit_eta else None},
                     rss, int(r.size), bool(res.success), () if fit_eta else ("eta",), at_bound)


def _finite(x) -> float | None:
    x = float(x)
    return x if np.isfinite(x) else None
