"""What `capred shear` says about chi: back-analysed capillary stress, fitted chi laws, prediction bands,
pendular-only scores and the bootstrap uncertainty of the model ranking.

All SI inside (Pa). The dry envelope of each material is tau = c + sigma_N tan(phi).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..fitting import chi_laws
from ..fitting.linear import LineFit
from ..physics import effective_stress_models as esm


def back_analysis(tau, sigma_N, suction, c, tan_phi, cov, s2):
    """Apparent capillary stress of wet tests and its standard uncertainty [Pa]; chi_back and its uncertainty.

    sigma_cap = (tau - c)/tan(phi) - sigma_N, the normal stress the dry
    envelope needs to carry the measured strength, minus the applied one.
    Its variance by the delta method: the dry-fit covariance of (c, tan phi)
    through d/dc = -1/b, d/db = -(tau - c)/b^2 (b = tan phi), plus the
    measurement of tau, taken as the dry fit's residual variance s^2, through
    d/dtau = 1/b. chi_back = sigma_cap / Delta_u (NaN where Delta_u = 0).

    Parameters
    ----------
    tau, sigma_N, suction : measured strength, normal stress, suction per test [Pa]
    c, tan_phi : dry envelope per test [Pa], [-]
    cov : (n, 2, 2) covariance of (c, tan phi) per test [Pa^2, Pa, -]
    s2 : residual variance of the dry fit per test [Pa^2]

    Returns
    -------
    sigma_cap, sigma_cap_se [Pa], chi_back, chi_back_se [-]
    """
    b = tan_phi
    cap = (tau - c) / b - sigma_N
    dc, db = -1.0 / b, -(tau - c) / b**2
    var = dc**2 * cov[:, 0, 0] + 2 * dc * db * cov[:, 0, 1] + db**2 * cov[:, 1, 1] + s2 / b**2
    se = np.sqrt(np.maximum(var, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        chi = np.where(suction > 0, cap / suction, np.nan)
        chi_se = np.where(suction > 0, se / suction, np.nan)
    return cap, se, chi, chi_se


def fit_laws(d: esm.ModelInputs, models, materials, params) -> dict[str, dict[str, chi_laws.FittedLaw]]:
    """The fitted chi laws among ``models``, per material, on its wet tests (dry c, phi held)."""
    out: dict[str, dict[str, chi_laws.FittedLaw]] = {}
    for model in models:
        if not esm.REGISTRY[model].fitted:
            continue
        out[model] = {}
        for m in materials:
            sel = d.wet & (d.material == m)
            if sel.sum() < 2:
                continue
            out[model][m] = _fit_one(model, d.subset(sel), params)
    return out


def _fit_one(model: str, w: esm.ModelInputs, params, start: dict | None = None):
    if model == "chi_power":
        return chi_laws.fit_chi_power(w.sigma_N, w.suction, w.S_R, w.tau_max, w.c, w.tan_phi, params.s_res or 0.0,
                                      start)
    return chi_laws.fit_khalili(w.sigma_N, w.suction, w.S_R, w.tau_max, w.c, w.tan_phi, params.eta, params.fit_eta,
                                start)


def prediction_band(model: str, d: esm.ModelInputs, cov: np.ndarray, t: np.ndarray):
    """Lower and upper band [Pa] of a model's tau prediction from the dry-fit covariance (delta method).

    The derivatives of tau_pred with respect to c and tan(phi) are taken by
    central differences of the model itself (fitted chi-law parameters held),
    so the band holds for every model of the registry.
    """
    base = esm.predict(model, d)[1]
    grads = []
    for name, ref in (("c", np.maximum(np.abs(d.c), 1.0)), ("tan_phi", np.maximum(np.abs(d.tan_phi), 1e-3))):
        h = 1e-6 * ref
        up = esm.predict(model, dataclasses.replace(d, **{name: getattr(d, name) + h}))[1]
        dn = esm.predict(model, dataclasses.replace(d, **{name: getattr(d, name) - h}))[1]
        grads.append((up - dn) / (2 * h))
    gc, gb = grads
    var = gc**2 * cov[:, 0, 0] + 2 * gc * gb * cov[:, 0, 1] + gb**2 * cov[:, 1, 1]
    half = t * np.sqrt(np.maximum(var, 0.0))
    return base - half, base + half


@dataclass
class RankingUncertainty:
    """Bootstrap of the model ranking of one material."""

    replicates: int
    seed: int
    probability: dict[str, float]
    rmse_ci: dict[str, tuple[float, float]]  # Pa
    best: str | None
    runner_up: str | None
    difference_ci: tuple[float, float] | None  # Pa, RMSE(runner-up) - RMSE(best)


def bootstrap_ranking(d_mat: esm.ModelInputs, dry_x, dry_y, models, params, fitted: dict, ranked: list[str],
                      replicates: int, seed: int, through_origin: bool) -> RankingUncertainty:
    """Paired bootstrap over the wet tests of one material, refitting the dry envelope in every replicate.

    Each replicate resamples the dry tests (with replacement) and refits c and
    tan(phi) (redrawing a sample whose normal stresses are all equal), then
    resamples the wet tests, refits the fitted laws (warm-started from the
    full-data fit) and scores every model on the same resampled wet tests.
    ``ranked`` lists the models by RMSE on the full data: its first two are
    the best and the runner-up whose RMSE difference is reported.
    """
    rng = np.random.default_rng(seed)
    nd, nw = dry_x.size, d_mat.sigma_N.size
    scores = {m: np.full(replicates, np.nan) for m in models}
    for r in range(replicates):
        for _ in range(100):
            di = rng.integers(0, nd, nd)
            x, y = dry_x[di], dry_y[di]
            if through_origin:
                if x @ x > 0:
                    c, b = 0.0, float(x @ y / (x @ x))
                    break
            elif np.ptp(x) > 0:
                b = float(np.polyfit(x, y, 1)[0])
                c = float(y.mean() - b * x.mean())
                break
        else:  # pragma: no cover - every dry sample degenerate: leave the replicate out
            continue
        w = d_mat.subset(rng.integers(0, nw, nw))
        w = dataclasses.replace(w, c=np.full(nw, c), tan_phi=np.full(nw, b))
        refit = {}
        for model in models:
            if esm.REGISTRY[model].fitted and w.material[0] in fitted.get(model, {}):
                law = _fit_one(model, w, params, start=fitted[model][w.material[0]])
                refit[model] = {w.material[0]: law.params}
        w = dataclasses.replace(w, fitted={**fitted, **refit})
        for model in models:
            pred = esm.predict(model, w)[1]
            ok = np.isfinite(pred)
            if ok.any():
                scores[model][r] = float(np.sqrt(np.mean((pred[ok] - w.tau_max[ok]) ** 2)))
    stack = np.column_stack([scores[m] for m in models])
    stack = stack[np.any(np.isfinite(stack), axis=1)]
    filled = np.where(np.isfinite(stack), stack, np.inf)
    winners = np.argmin(filled, axis=1)
    counts = np.bincount(winners, minlength=len(models))
    total = max(int(counts.sum()), 1)
    prob = {m: float(counts[k] / total) for k, m in enumerate(models)}
    ci = {m: tuple(float(v) for v in np.nanpercentile(scores[m], [2.5, 97.5])) for m in models
          if np.isfinite(scores[m]).any()}
    best, runner = (ranked + [None, None])[:2]
    diff = None
    if best is not None and runner is not None:
        dd = scores[runner] - scores[best]
        dd = dd[np.isfinite(dd)]
        if dd.size:
            diff = tuple(float(v) for v in np.percentile(dd, [2.5, 97.5]))
    return RankingUncertainty(int(stack.shape[0]), seed, prob, ci, best, runner, diff)


def fit_covariances(fits: dict[str, LineFit], material) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per test: covariance of (c, tan phi), residual variance and Student t of its material's dry fit."""
    names = list(fits)
    if not len(material):
        return np.empty((0, 2, 2)), np.empty(0), np.empty(0)
    index = {m: k for k, m in enumerate(names)}
    which = np.fromiter((index[m] for m in material), dtype=int, count=len(material))
    cov = np.stack([fits[m].covariance for m in names])[which]
    s2 = np.array([fits[m].residual_variance for m in names], dtype=float)[which]
    t = np.array([fits[m].t for m in names], dtype=float)[which]
    return cov, s2, t


@dataclass
class RetentionRelation:
    """S_R(s) of a material, for drawing model curves along it."""

    S_R: object  # callable: suction [Pa] -> S_R [-]
    source: str  # for the caption

    def suction(self, S_R, lo: float = 1e-3, hi: float = 1e9) -> np.ndarray:
        """The inverse: suction [Pa] at which the relation gives ``S_R`` (NaN outside its range).

        S_R(s) falls monotonically, so the root is bracketed on log s by bisection (vectorised).
        """
        target = np.atleast_1d(np.asarray(S_R, float))
        a = np.full(target.shape, np.log(lo))
        b = np.full(target.shape, np.log(hi))
        inside = (self.S_R(np.exp(a)) >= target) & (self.S_R(np.exp(b)) <= target)
        for _ in range(200):
            mid = 0.5 * (a + b)
            above = self.S_R(np.exp(mid)) > target
            a, b = np.where(above, mid, a), np.where(above, b, mid)
        return np.where(inside, np.exp(0.5 * (a + b)), np.nan)


def retention_relation(params, suction, S_R) -> RetentionRelation | None:
    """The water-retention relation of a material's wet tests: van Genuchten from the options (--retention
    or --vg-alpha/--vg-n), else a van Genuchten fit (m = 1 - 1/n) of the tests' own (suction, S_R) pairs;
    None when neither is possible (fewer than 4 tests at 3 suctions)."""
    from ..physics.retention import vg_water

    if params.retention_model is not None and params.vg_alpha is None:
        from ..fitting.retention_models import MODELS

        name, items, quantity = params.retention_model
        p = dict(items)
        model = MODELS[name]
        scale = 1.0 / p["y_s"] if quantity == "theta" else 1.0  # S_R = theta/theta_s
        return RetentionRelation(lambda s: model.water(s, **p) * scale,
                                 f"{model.label} fitted by capred retention")
    if params.vg_alpha is not None and params.vg_n is not None:
        s_res = params.s_res or 0.0
        a, n, m = params.vg_alpha, params.vg_n, params.vg_m
        return RetentionRelation(lambda s: vg_water(s, s_res, 1.0, a, n, m),
                                 f"van Genuchten from the options (α = {a * 1e3:.4g} 1/kPa, n = {n:.4g})")
    ok = (suction > 0) & np.isfinite(S_R)
    if ok.sum() < 4 or np.unique(suction[ok]).size < 3:
        return None
    from ..errors import FitError
    from ..fitting.retention import fit_van_genuchten

    try:
        f = fit_van_genuchten(suction[ok], S_R[ok])
    except FitError:
        return None
    p = f.params
    return RetentionRelation(lambda s: vg_water(s, p["y_r"], p["y_s"], p["alpha"], p["n"]),
                             f"van Genuchten fitted to the tests' own (suction, S_R) pairs (α = "
                             f"{p['alpha'] * 1e3:.4g} 1/kPa, n = {p['n']:.4g}, R² = {f.r2:.3f})")


def model_curves(result, material, relation: RetentionRelation, sigma_N: float, points: int = 120):
    """(S_R, {model: tau [Pa]}) along the retention relation at one normal stress; models fitted on the tests'
    own strengths (fredlund) are left out."""
    t = result.tests
    sel = (t["material"] == material) & (t["condition"] == "wet")
    s_pos = t["suction"][sel][t["suction"][sel] > 0]
    s = np.geomspace(s_pos.min() / 3, s_pos.max() * 3, points)
    S = np.clip(relation.S_R(s), 0.0, 1.0)
    fit = result.fits[material]
    n = s.size
    d = esm.ModelInputs(np.full(n, sigma_N), s, S, np.full(n, float(np.nanmedian(t["R"][sel]))), np.full(n, np.nan),
                        np.ones(n, bool), np.array([material] * n, dtype=object), np.full(n, fit.intercept),
                        np.full(n, fit.slope), result.options.surface_tension, result.options.model_params,
                        fitted=result.model_inputs.fitted)
    out = {}
    for m in result.models:
        if m == "fredlund":
            continue
        with np.errstate(invalid="ignore"):
            out[m] = esm.predict(m, d)[1]
    return S, out
