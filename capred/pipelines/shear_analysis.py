"""What `capred shear` says about chi.

Back-analysed capillary stress, fitted chi laws, confidence bands and prediction intervals, and the bootstrap
uncertainty of the model ranking.

All SI inside (Pa). The dry envelope of each material is tau = c + sigma_N tan(phi), fitted by ordinary
least squares (`capred.fitting.linear`); every interval here carries its uncertainty.

What each interval covers (each checked by simulation in tests/test_shear_statistics.py):

- ``sigma_cap`` / ``chi_back`` intervals: the test's true capillary stress, t quantile of the dry fit's dof;
- fitted-law ``ci95``: the law's true parameters (`capred.fitting.chi_laws`);
- the MEAN band of a model (`tau_bands`, ``mean_low/high``): the model's true mean strength at the test's
  state, given the model;
- the PREDICTION interval (``pred_low/high``): a new test at that state (adds the residual variance).

References
----------
.. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley,
   doi:10.1002/9781118625590, ch. 1 (confidence band of the mean line, prediction interval of a new
   observation).
.. [2] Murphy, K. M. & Topel, R. H. (1985). Estimation and inference in two-step econometric models.
   J. Bus. Econ. Stat. 3(4):370-379, doi:10.1080/07350015.1985.10509470.
.. [3] Efron, B. & Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman & Hall,
   doi:10.1007/978-1-4899-4541-9 (ch. 6: bootstrap replications and their Monte-Carlo error; ch. 9:
   resampling cases of a regression).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..fitting import chi_laws
from ..fitting.comparison import difference_resolution
from ..fitting.linear import LineFit, fit_line, fit_line_origin, t_quantile
from ..physics import effective_stress_models as esm


def back_analysis(tau, sigma_N, suction, c, tan_phi, cov, s2):
    r"""Apparent capillary stress of wet tests and its standard uncertainty; chi_back and its uncertainty.

    .. math:: \sigma_{cap} = \frac{\tau - c}{\tan\phi} - \sigma_N, \qquad
              \chi_{back} = \sigma_{cap} / \Delta u

    the normal stress the dry envelope needs to carry the measured strength, minus the applied one. Its
    variance by the delta method, with b = tan(phi):

    .. math:: \mathrm{Var}\,\sigma_{cap} = g^T V g + s^2/b^2, \quad g = (-1/b,\; -(\tau - c)/b^2)

    V the dry-fit covariance of (c, b) and s^2 the dry fit's residual variance, standing for the
    measurement scatter of the wet test's tau (the same scatter is assumed for dry and wet tests).

    Parameters
    ----------
    tau, sigma_N, suction : (n,) ndarray
        Measured strength, normal stress, matric suction Delta_u per test [Pa].
    c, tan_phi : (n,) ndarray
        Dry envelope per test [Pa], [-].
    cov : (n, 2, 2) ndarray
        Covariance of (c, tan phi) per test [Pa^2, Pa, -].
    s2 : (n,) ndarray
        Residual variance of the dry fit per test [Pa^2].

    Returns
    -------
    sigma_cap, sigma_cap_se : ndarray [Pa]
    chi_back, chi_back_se : ndarray [-]
        NaN where Delta_u = 0.

    References
    ----------
    Draper & Smith (1998), doi:10.1002/9781118625590, ch. 1 (inverse prediction from a fitted line,
    by the delta method).
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


def back_analysis_intervals(tau, sigma_N, suction, c, tan_phi, cov, s2, dof, confidence: float = 0.95, wet=None):
    r"""`back_analysis` with intervals, as the run's record: sigma_cap -/+ t se, chi_back -/+ t se/Delta_u.

    .. math:: \sigma_{cap} \mp t_{1-\alpha/2,\,\nu}\,\mathrm{se}(\sigma_{cap}), \qquad
              \chi_{back} \mp t_{1-\alpha/2,\,\nu}\,\mathrm{se}(\sigma_{cap})/\Delta u

    with nu the dry fit's residual dof (n_dry - 2, or n_dry - 1 through the origin): the variance estimate
    rests on the dry residuals alone, so (sigma_cap_hat - sigma_cap)/se follows Student's t with nu dof
    (to first order in the dry fit's error). Simulated (tests/test_shear_statistics.py, 6 dry tests,
    400 sets): 94.8 % coverage; +/- 1.96 se covers 88.8 %.

    Parameters
    ----------
    tau, sigma_N, suction, c, tan_phi, cov, s2 :
        As for `back_analysis` [Pa, Pa, Pa, Pa, -, (Pa^2, Pa, -), Pa^2].
    dof : (n,) array_like of int
        Residual dof of each test's dry fit [-] (`fit_dof`).
    confidence : float
        Level [-].
    wet : (n,) bool ndarray, optional
        Tests to report; the others get NaN (dry tests carry no capillary stress).

    Returns
    -------
    capred.pipelines.shear_records.BackAnalysis
        ``sigma_cap``, ``sigma_cap_se``, ``sigma_cap_ci`` [Pa]; ``chi_back``, ``chi_back_se``,
        ``chi_back_ci`` [-]; ``dof`` [-].

    References
    ----------
    Draper & Smith (1998), doi:10.1002/9781118625590, ch. 1 (t intervals from a fitted line).
    """
    from .shear_records import BackAnalysis

    cap, se, chi, chi_se = back_analysis(tau, sigma_N, suction, c, tan_phi, cov, s2)
    nu = np.asarray(dof, dtype=float) * np.ones(np.shape(cap))
    t = t_quantile(0.5 + confidence / 2.0, nu)
    keep = np.ones(np.shape(cap), bool) if wet is None else np.asarray(wet, bool)

    def on(v):
        return np.where(keep, v, np.nan)

    return BackAnalysis(
        sigma_cap=on(cap),
        sigma_cap_se=on(se),
        sigma_cap_ci=(on(cap - t * se), on(cap + t * se)),
        chi_back=on(chi),
        chi_back_se=on(chi_se),
        chi_back_ci=(on(chi - t * chi_se), on(chi + t * chi_se)),
        dof=on(nu),
    )


def _dry_fit(d: esm.ModelInputs, material) -> LineFit | None:
    """The dry fit of ``material`` recomputed from the dry tests of ``d`` (None unless it reproduces d's c, tan phi).

    Through the origin when the envelope's c is exactly 0 (what `fit_line_origin` gives).
    """
    of = d.material == material
    sel = of & ~d.wet
    if not sel.any() or not of.any():
        return None
    c, b = float(d.c[of][0]), float(d.tan_phi[of][0])
    try:
        fit = (fit_line_origin if c == 0.0 else fit_line)(d.sigma_N[sel], d.tau_max[sel])
    except Exception:  # FitError: no dry fit to propagate
        return None
    scale = max(abs(c), abs(b) * float(np.max(np.abs(d.sigma_N[sel]))), 1.0)
    if abs(fit.intercept - c) > 1e-9 * scale or abs(fit.slope - b) > 1e-9 * max(abs(b), 1e-12):
        return None
    return fit


def fit_laws(
    d: esm.ModelInputs, models, materials, params, fits: dict[str, LineFit] | None = None
) -> dict[str, dict[str, chi_laws.FittedLaw]]:
    """The fitted chi laws among ``models``, per material, on its wet tests (dry c, phi held).

    Each law carries ``se`` and ``ci95`` with the dry fit's uncertainty propagated
    (`capred.fitting.chi_laws.law_uncertainty`).

    Parameters
    ----------
    d : ModelInputs
        Every test (dry and wet), with each test's dry envelope in ``c`` [Pa] and ``tan_phi`` [-].
    models : sequence of str
        Model names; those of the registry with fitted parameters are fitted.
    materials : sequence of str
        Materials to fit (those with a dry fit).
    params : ModelParams
        ``s_res``, ``eta``, ``fit_eta``.
    fits : {material: LineFit}, optional
        The dry fits. When absent they are recomputed from the dry tests in ``d`` (and used only if they
        reproduce d's c and tan phi; otherwise c and tan phi are taken as exact).

    Returns
    -------
    {model: {material: FittedLaw}}
        Materials with fewer than 2 wet tests are left out.

    References
    ----------
    Murphy & Topel (1985), doi:10.1080/07350015.1985.10509470 (the two-step covariance).
    """
    out: dict[str, dict[str, chi_laws.FittedLaw]] = {}
    for model in models:
        if not esm.REGISTRY[model].fitted:
            continue
        out[model] = {}
        for m in materials:
            sel = d.wet & (d.material == m)
            if sel.sum() < 2:
                continue
            dry = fits.get(m) if fits is not None else _dry_fit(d, m)
            out[model][m] = _fit_one(model, d.subset(sel), params, dry=dry)
    return out


def _fit_one(model: str, w: esm.ModelInputs, params, start: dict | None = None, dry: LineFit | None = None):
    return chi_laws.LAWS[model].fit(w, params, start, dry)


def _tau(model: str, d: esm.ModelInputs, **changes) -> np.ndarray:
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return esm.predict(model, dataclasses.replace(d, **changes) if changes else d)[1]


def _envelope_gradient(model: str, d: esm.ModelInputs):
    """Gradient d tau_pred / dc and d tau_pred / d tan(phi) per test, by central differences of the model itself."""
    grads = []
    for name, ref in (("c", np.maximum(np.abs(d.c), 1.0)), ("tan_phi", np.maximum(np.abs(d.tan_phi), 1e-3))):
        h = 1e-6 * ref
        up = _tau(model, d, **{name: getattr(d, name) + h})
        dn = _tau(model, d, **{name: getattr(d, name) - h})
        grads.append((up - dn) / (2 * h))
    return grads


def prediction_band(model: str, d: esm.ModelInputs, cov: np.ndarray, t: np.ndarray):
    r"""Confidence band of the MEAN tau prediction [Pa] from the dry-fit covariance (delta method).

    Kept for callers of the first version: despite its name this is the band of the mean (fitted-law
    parameters held), not the interval of a new test; use `tau_bands` for both.

    .. math:: \hat\tau \mp t\,\sqrt{g^T V g}, \qquad g = (\partial\tau/\partial c,\;
              \partial\tau/\partial\tan\phi)

    Parameters
    ----------
    model : str
        Registry name.
    d : ModelInputs
        Every test, with the fitted laws in ``d.fitted``.
    cov : (n, 2, 2) ndarray
        Covariance of (c, tan phi) per test [Pa^2, Pa, -].
    t : (n,) ndarray
        Student-t quantile per test [-].

    Returns
    -------
    low, high : ndarray [Pa]

    References
    ----------
    Draper & Smith (1998), doi:10.1002/9781118625590, ch. 1 (confidence band of the mean line).
    """
    base = _tau(model, d)
    gc, gb = _envelope_gradient(model, d)
    var = gc**2 * cov[:, 0, 0] + 2 * gc * gb * cov[:, 0, 1] + gb**2 * cov[:, 1, 1]
    half = t * np.sqrt(np.maximum(var, 0.0))
    return base - half, base + half


@dataclass
class TauBands:
    """Per test: the 95 % band of a model's mean strength and the 95 % interval of a new test.

    Attributes
    ----------
    tau : ndarray
        The model's prediction [Pa].
    mean_low, mean_high : ndarray
        Confidence band of the mean prediction [Pa]: covers the model's true mean strength at the test's
        state (given the model) with probability ``confidence``.
    pred_low, pred_high : ndarray
        Prediction interval [Pa]: covers the strength of a NEW test at the same state.
    dof : ndarray of int
        Degrees of freedom of the t quantile per test [-]: the dry fit's, or the joint fit's for the wet
        tests of a fitted law.
    confidence : float
        Level [-].
    """

    tau: np.ndarray
    mean_low: np.ndarray
    mean_high: np.ndarray
    pred_low: np.ndarray
    pred_high: np.ndarray
    dof: np.ndarray
    confidence: float = 0.95


def tau_bands(
    model: str,
    d: esm.ModelInputs,
    cov: np.ndarray,
    s2: np.ndarray,
    dof,
    laws: dict | None = None,
    confidence: float = 0.95,
    scatter=None,
) -> TauBands:
    r"""Confidence band of the mean and prediction interval of a new test, per test, for one model.

    .. math:: \hat\tau \mp t_{1-\alpha/2,\,\nu}\sqrt{g^T V g} \;\;\text{(mean)}, \qquad
              \hat\tau \mp t_{1-\alpha/2,\,\nu}\sqrt{g^T V g + s^2} \;\;\text{(new test)}

    g is the gradient of the prediction with respect to (c, tan phi) (central differences of the model
    itself, so every model of the registry is covered) and V the dry fit's covariance, s^2 its residual
    variance and nu its dof. For the wet tests of a fitted chi law (``laws`` given), g extends to the law's
    free parameters, V is the law's joint covariance of (c, tan phi, theta) and s^2, nu those of the joint
    fit (`capred.fitting.chi_laws.law_uncertainty`), so the law's own uncertainty widens both.

    Parameters
    ----------
    model : str
        Registry name.
    d : ModelInputs
        Every test, with the fitted laws in ``d.fitted``.
    cov : (n, 2, 2) ndarray
        Covariance of (c, tan phi) per test [Pa^2, Pa, -] (`fit_covariances`).
    s2 : (n,) ndarray
        Residual variance of the dry fit per test [Pa^2].
    dof : (n,) array_like of int
        Residual dof of the dry fit per test [-] (`fit_dof`).
    laws : {model: {material: FittedLaw}}, optional
        The fitted laws (`fit_laws`).
    confidence : float
        Level [-].
    scatter : callable, optional
        ``scatter(tau) -> (n,) ndarray``: the variance of one test of expected strength tau [Pa^2] when the
        scatter grows with the strength (``--errors proportional``); it replaces ``s2`` for the new test, and
        scales a fitted law's pooled variance by scatter(tau_hat)/mean(scatter(tau)) over its wet tests.

    Returns
    -------
    TauBands

    References
    ----------
    Draper & Smith (1998), doi:10.1002/9781118625590, ch. 1 (the band of the mean and the interval of a
    new observation); Murphy & Topel (1985), doi:10.1080/07350015.1985.10509470 (the law's covariance).
    """
    base = _tau(model, d)
    gc, gb = _envelope_gradient(model, d)
    var = gc**2 * cov[:, 0, 0] + 2 * gc * gb * cov[:, 0, 1] + gb**2 * cov[:, 1, 1]
    s2 = np.array(s2, dtype=float, copy=True) * np.ones(base.shape)
    if scatter is not None:
        s2 = np.asarray(scatter(base), dtype=float)
        s2_measured = np.asarray(scatter(d.tau_max), dtype=float)
    nu = np.asarray(dof, dtype=int) * np.ones(base.shape, dtype=int)
    for mat, law in ((laws or {}).get(model) or {}).items():
        sel = d.wet & (d.material == mat)
        if law.covariance is None or not sel.any() or not np.all(np.isfinite(law.covariance)):
            continue
        w = d.subset(sel)
        g = [gc[sel], gb[sel]]
        for name in law.names[2:]:
            v = law.values[name]
            h = 1e-6 * max(abs(v), 1e-12)
            parts = []
            for sign in (1.0, -1.0):
                fitted = {**w.fitted, model: {**w.fitted.get(model, {}), mat: {**law.values, name: v + sign * h}}}
                parts.append(_tau(model, w, fitted=fitted))
            g.append((parts[0] - parts[1]) / (2 * h))
        G = np.column_stack(g)
        var[sel] = np.einsum("ip,pq,iq->i", G, law.covariance, G)
        pooled = law.residual_variance if law.residual_variance is not None else np.nan
        if scatter is not None:
            ratio = s2[sel] / np.nanmean(s2_measured[sel])
            s2[sel] = pooled * ratio
        else:
            s2[sel] = pooled
        nu[sel] = law.dof
    t = t_quantile(0.5 + confidence / 2.0, nu)
    half_mean = t * np.sqrt(np.maximum(var, 0.0))
    half_new = t * np.sqrt(np.maximum(var + s2, 0.0))
    return TauBands(base, base - half_mean, base + half_mean, base - half_new, base + half_new, nu, confidence)


@dataclass
class RankingUncertainty:
    """Bootstrap of the model ranking of one material.

    Attributes
    ----------
    replicates : int
        Replicates that gave at least one score [-].
    seed : int
        Seed of the random stream.
    probability : {model: float}
        Share of replicates in which the model has the lowest RMSE [-].
    rmse_ci : {model: (low, high)}
        2.5 and 97.5 percentiles of the model's RMSE over the replicates [Pa].
    best, runner_up : str or None
        The first two models by RMSE on the full data.
    difference_ci : (low, high) or None
        Percentile interval of RMSE(runner-up) - RMSE(best) [Pa].
    requested : int or None
        Replicates asked for: the cap of the adaptive bootstrap, which stops at ``replicates`` once the printed
        numbers are resolved (`adaptive_stop`).
    """

    replicates: int
    seed: int
    probability: dict[str, float]
    rmse_ci: dict[str, tuple[float, float]]  # Pa
    best: str | None
    runner_up: str | None
    difference_ci: tuple[float, float] | None  # Pa, RMSE(runner-up) - RMSE(best)
    #: replicates asked for (``--bootstrap``, the cap of the adaptive bootstrap); ``replicates`` were used
    requested: int | None = None


#: Elements (replicates x tests) drawn and scored at once by the bootstrap: bounds its memory at any table
#: size (~30 B each). It sets the random stream of a material with more than BLOCK_ELEMENTS / R wet tests
#: (131 at R = 2000); earlier versions drew 1,000,000 at once (the same distribution, other resamples).
BLOCK_ELEMENTS = 262_144
#: Tests on which a model is checked to predict test by test and affinely in the envelope (the first ones of
#: the material), and tests whose coefficients and weighted sums are formed at once: the bootstrap's memory
#: per wet test stays a few floats per model.
CHECK_TESTS = 2048
CHUNK_TESTS = 16384
#: Wet tests of a material up to which the affine models' products are formed once and kept (~0.2 KB a test)
#: and the replicates drawn and scored a block at a time. Beyond, when every model is affine, the loop turns
#: round (`_score_long`): each chunk of CHUNK_TESTS tests forms its products once and every replicate's counts
#: of that chunk are drawn there (memory flat, cost linear in the tests; another random stream than the block
#: loop's, the same distribution); with a fitted law or a model scored replicate by replicate, the products are
#: formed CHUNK_TESTS tests at a time in every block.
KEEP_FEATURES_TESTS = 65536


def _affine_probes(d: esm.ModelInputs) -> dict:
    """What `_pointwise_affine` evaluates every model on, built once for all of them.

    The five envelopes (c0, b0), (c0 + hc, b0), (c0, b0 + hb), the probe (c0 - 2 hc, b0 - 3 hb) and
    (c0 + hc, b0 - hb) of the first ``CHECK_TESTS`` tests repeated five times (one prediction), and two
    subsets of them (half; all with the first half twice) for the checks that a model predicts test by test.
    """
    d = d if _size(d) <= CHECK_TESTS and not isinstance(d, _Selected) else d.subset(slice(0, CHECK_TESTS))
    n = d.sigma_N.size
    c0, b0 = float(d.c[0]), float(d.tan_phi[0])
    hc, hb = 0.1 * max(abs(c0), 1.0), 0.1 * max(abs(b0), 1e-3)
    envelopes = np.array([(c0, b0), (c0 + hc, b0), (c0, b0 + hb), (c0 - 2 * hc, b0 - 3 * hb), (c0 + hc, b0 - hb)])
    subs = (np.arange(n)[::-2], np.r_[np.arange(n), np.zeros(max(n // 2, 1), int)])

    def at(sub, c, tan_phi):  # the tests ``sub`` under the envelopes (c, tan_phi), one ModelInputs
        return dataclasses.replace(d.subset(sub), c=c, tan_phi=tan_phi)

    stacked = at(np.tile(np.arange(n), 5), np.repeat(envelopes[:, 0], n), np.repeat(envelopes[:, 1], n))
    parts = [at(sub, np.full(sub.size, c0 + hc), np.full(sub.size, b0 - hb)) for sub in subs]
    return {"n": n, "c0": c0, "b0": b0, "hc": hc, "hb": hb, "stacked": stacked, "subs": subs, "parts": parts}


def _pointwise_affine(model: str, d: esm.ModelInputs, probes: dict | None = None):
    """(e0, beta, gamma) with tau_pred(c, b) - tau = e0 + (c - c0) beta + (b - b0) gamma per test, or None.

    None when the model's prediction of a test is not affine in the envelope (c, b) or depends on which
    other tests are in the set (e.g. a parameter fitted on the set, as Fredlund's tan phi_b): such a
    model is evaluated replicate by replicate. ``probes``: `_affine_probes` of ``d`` (made here if absent).

    The check, on the first ``CHECK_TESTS`` tests: the five envelopes of `_affine_probes` at once (a model
    that predicts test by test gives each copy of a test what it gives alone), then each subset alone at
    (c0 + hc, b0 - hb), which must give what the whole set gave its tests (one that depends on the set
    fails there). The coefficients of every test then come from three envelopes, ``CHUNK_TESTS`` tests at a
    time; the first chunk must predict the checked tests as the checked set did.
    """
    p = _affine_probes(d) if probes is None else probes
    n, hc, hb = p["n"], p["hc"], p["hb"]
    t0, tc, tb, probe, full = _tau(model, p["stacked"]).reshape(5, n)
    beta = (tc - t0) / hc
    gamma = (tb - t0) / hb
    scale = np.nanmax(np.abs(t0)) if np.isfinite(t0).any() else 1.0
    tol = 1e-9 * max(scale, 1.0)
    got, want = [probe], [t0 - 2 * hc * beta - 3 * hb * gamma]
    for sub, part in zip(p["subs"], p["parts"]):
        got.append(_tau(model, part))
        want.append(full[sub])
    if not _all_close(np.concatenate(got), np.concatenate(want), tol):
        return None
    total = _size(d)
    if total == n:  # the checked tests are all of them
        return t0 - p["stacked"].tau_max[:n], beta, gamma
    e0, beta, gamma = np.empty(total), np.empty(total), np.empty(total)
    c0, b0 = p["c0"], p["b0"]
    for first in range(0, total, CHUNK_TESTS):
        k = min(CHUNK_TESTS, total - first)
        chunk = d.subset(slice(first, first + k))
        idx = np.tile(np.arange(k), 3)
        env_c = np.repeat([c0, c0 + hc, c0], k)
        env_b = np.repeat([b0, b0, b0 + hb], k)
        a0, ac, ab = _tau(model, dataclasses.replace(chunk.subset(idx), c=env_c, tan_phi=env_b)).reshape(3, k)
        e0[first : first + k] = a0 - chunk.tau_max
        beta[first : first + k] = (ac - a0) / hc
        gamma[first : first + k] = (ab - a0) / hb
    if not _all_close(e0[:n] + p["stacked"].tau_max[:n], t0, tol):
        return None  # a chunk predicts its first tests otherwise than the checked set did: it depends on the set
    return e0, beta, gamma


class _Selected:
    """The tests ``index`` of a ModelInputs, copied a slice at a time on demand (``subset``).

    A long material's inputs are never all copied when only the affine models' coefficients need them.
    """

    def __init__(self, d: esm.ModelInputs, index: np.ndarray):
        self.d, self.index, self.size = d, index, index.size

    def subset(self, rows) -> esm.ModelInputs:
        return self.d.subset(self.index[rows])


def _size(d) -> int:
    """Number of tests of a ModelInputs or a _Selected."""
    return d.size if isinstance(d, _Selected) else d.sigma_N.size


def _all_close(a: np.ndarray, b: np.ndarray, atol: float) -> bool:
    """``np.allclose(a, b, rtol=0, atol=atol, equal_nan=True)`` without its per-call overhead (~0.1 ms)."""
    with np.errstate(invalid="ignore"):
        return bool(np.all((a == b) | (np.abs(a - b) <= atol) | (np.isnan(a) & np.isnan(b))))


def _dry_groups(dry_x, through_origin: bool) -> np.ndarray:
    """(nd,) integer code of each dry test's group: its distinct normal stress.

    Through the origin: 1 for a usable test, whose square is not 0, else 0. What `_draw` checks a sample's fit on, in
    O(nd) memory.
    """
    if through_origin:
        return (dry_x * dry_x > 0).astype(np.intp)
    return np.unique(dry_x, return_inverse=True)[1].ravel().astype(np.intp)


def _draw(rng, dry_x, nw: int, count: int, through_origin: bool, groups="find"):
    """Resampling of one block of replicates, drawn as whole matrices.

    The dry indices of every replicate (count x nd), then the wet ones (count x nw); a dry sample that cannot
    fit a line (all its normal stresses equal; all zero through the origin) is redrawn, up to 100 times.
    Returns dry counts (count, nd), wet indices (count, nw) and the valid rows. (Versions before 0.2 drew
    replicate by replicate in a Python loop: the same distribution, another random stream.)

    A sample fits a line when the group codes of its draws (`_dry_groups`) are not all equal (through the
    origin: one is 1), decided from the codes of the drawn indices: the cost is that of the draw, whatever the
    number of distinct stresses (earlier versions multiplied the counts by a dense nd x k indicator matrix:
    quadratic when nearly every dry test has its own stress; the same decisions, the same random stream).
    """
    U, valid = _draw_dry(rng, dry_x, count, through_origin, groups)
    idx = rng.integers(0, nw, (count, nw))
    U[~valid] = 0.0
    return U, idx, valid


def _draw_dry(rng, dry_x, count: int, through_origin: bool, groups="find"):
    """The dry part of `_draw`: counts (count, nd) as floats and the rows whose sample fits a line.

    The same draws, in the same order, as `_draw` makes before its wet indices.
    """
    nd = dry_x.size
    code = _dry_groups(dry_x, through_origin) if isinstance(groups, str) else groups

    def counts(di):
        rows = np.repeat(np.arange(di.shape[0]), nd)
        return np.bincount(rows * nd + di.ravel(), minlength=di.size).reshape(di.shape)

    def fits(di):
        g = code[di]  # (rows, nd) group codes of the drawn tests
        if not nd:
            return np.zeros(di.shape[0], bool)
        return g.max(axis=1) > 0 if through_origin else g.min(axis=1) != g.max(axis=1)

    di = rng.integers(0, nd, (count, nd))
    U = counts(di)
    valid = fits(di)
    del di
    for _ in range(100):
        bad = np.flatnonzero(~valid)
        if not bad.size:
            break
        di = rng.integers(0, nd, (bad.size, nd))
        U[bad] = counts(di)
        valid[bad] = fits(di)
    return U.astype(float), valid


#: iterations of the vectorised reweighting of `_dry_refit` (proportional errors, robust losses): the full-data
#: IRLS converges in a handful; 30 leave a change below 1e-10 of the slope on the test tables
DRY_REFIT_ITERATIONS = 30


def _dry_refit(U, dry_x, dry_y, through_origin: bool, errors: str = "constant", loss: str = "ols", scale=None):
    r"""(c, tan phi) of every replicate from its dry counts, with the run's error model and loss (issue 41.4).

    Least squares (``errors`` constant or either, ``loss`` ols): closed-form weighted sums

    .. math:: b = \frac{\sum u (x - \bar x_u)(y - \bar y_u)}{\sum u (x - \bar x_u)^2}, \quad
              c = \bar y_u - b \bar x_u

    computed about the full sample's means (no cancellation); through the origin b = sum u x y / sum u x^2.
    Otherwise the same fit as `capred.fitting.linear.fit_envelope`, by iteratively reweighted least squares
    over all replicates at once (``DRY_REFIT_ITERATIONS``): weights u (ref/ŷ)² for proportional errors, times
    Huber's min(1, k/|z|) or Tukey's (1 - (z/c)²)² (after the Huber iterations) for a robust loss, with
    z = √w_prop r / ``scale`` and the scale that of the full-data fit (held: a MAD per replicate would cost a
    sort per replicate and changes the fit by its second order only).
    """
    if errors not in ("proportional",) and loss == "ols":
        return _weighted_line(U, dry_x, dry_y, through_origin)
    from ..fitting.linear import HUBER_K, TUKEY_C

    c, b = _weighted_line(U, dry_x, dry_y, through_origin)
    ref = float(np.mean(np.abs(dry_y))) or 1.0
    s = float(scale) if scale is not None and np.isfinite(scale) and scale > 0 else None
    half = DRY_REFIT_ITERATIONS // 2
    for it in range(DRY_REFIT_ITERATIONS):
        yhat = c[:, None] + b[:, None] * dry_x
        wp = (ref / np.maximum(np.abs(yhat), 1e-3 * ref)) ** 2 if errors == "proportional" else np.ones_like(yhat)
        W = U * wp
        if loss != "ols" and s is not None:
            z = np.sqrt(wp) * np.abs(dry_y - yhat) / s
            if loss == "huber" or it < half:  # Tukey starts from the Huber fit, as fit_envelope does
                W = W * np.minimum(1.0, HUBER_K / np.maximum(z, 1e-300))
            else:
                W = W * np.where(z < TUKEY_C, (1.0 - (z / TUKEY_C) ** 2) ** 2, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            c, b = _weighted_line(W, dry_x, dry_y, through_origin)
    return c, b


def _weighted_line(U, dry_x, dry_y, through_origin: bool):
    """(c, b) of the weighted least-squares line of every row of weights U (`_dry_refit`)."""
    if through_origin:
        return np.zeros(U.shape[0]), (U @ (dry_x * dry_y)) / (U @ (dry_x * dry_x))
    xm, ym = dry_x.mean(), dry_y.mean()
    xc, yc = dry_x - xm, dry_y - ym
    n = U.sum(axis=1)
    sx, sy = U @ xc, U @ yc
    b = (U @ (xc * yc) - sx * sy / n) / (U @ (xc * xc) - sx * sx / n)
    return ym + sy / n - b * (xm + sx / n), b


def bootstrap_ranking(
    d_mat: esm.ModelInputs,
    dry_x,
    dry_y,
    models,
    params,
    fitted: dict,
    ranked: list[str],
    replicates: int,
    seed: int,
    through_origin: bool,
    rows=None,
    errors: str = "constant",
    loss: str = "ols",
    scale: float | None = None,
    adaptive: bool = False,
) -> RankingUncertainty:
    r"""Paired bootstrap over the wet tests of one material, refitting the dry envelope in every replicate.

    Each replicate resamples the dry tests (with replacement) and refits c and tan(phi) (redrawing a
    sample whose normal stresses are all equal), then resamples the wet tests, refits the fitted laws
    (warm-started from the full-data fit) and scores every model by its RMSE on the same resampled wet
    tests. The share of replicates a model wins is its probability of being best; percentiles give the
    RMSE intervals (Efron & Tibshirani 1993, ch. 9, resampling cases).

    Vectorised: a replicate is a row of counts u (dry) and w (wet). The dry refit is the closed-form
    weighted least squares of the counts; a model whose prediction is affine in (c, b) and test by test
    (every registry model but Fredlund's) has

    .. math:: \mathrm{RMSE}_r^2 = \frac{\sum_i w_{ri} (e_i + \Delta c_r\,\beta_i + \Delta b_r\,\gamma_i)^2}
              {\sum_i w_{ri}}

    expanded into six weighted sums (one matrix product for all replicates); the fitted laws are refitted
    by a damped Gauss-Newton over all replicates at once (`capred.fitting.chi_laws.batch_least_squares`);
    other models are scored replicate by replicate. Replicates are drawn and scored in blocks of
    ``BLOCK_ELEMENTS`` counts; the affine models' coefficients are formed ``CHUNK_TESTS`` tests at a time.
    Beyond ``KEEP_FEATURES_TESTS`` wet tests, when every model is affine, the loop runs over chunks of tests
    instead (`_score_long`: each chunk's products formed once, every replicate's counts of it drawn there;
    cost linear in the tests, memory flat, about 0.1 KB per wet test plus the material's inputs; another
    random stream than the block loop, the same distribution); with a fitted law or a model scored
    replicate by replicate, the products are formed a chunk at a time in every block.

    The same seed gives the same resamples and the same numbers; the numbers are those of the replicate-by-
    replicate computation to rounding (RMSEs to ~1e-9 relative; fitted laws to their solver tolerance).

    Monte-Carlo error of the probabilities, measured as their SD over 50 seeds (it follows
    sqrt(p(1 - p)/R)): on a contested table (Bishop against Own 1 at p = 0.48/0.52; 21 wet tests,
    chi = (S_R + chi1)/2, noise 0.15 kPa) SD 0.040 at R = 200, 0.017 at 1000, 0.010 at 2000 and
    0.0086 at 4000; on the bundled sample (steel: Own 2 wins 97.4 %) 0.0075 at R = 500, 0.0052 at 1000,
    0.0034 at 2000 and 0.0023 at 4000, the binomial values to +/- 10 % (`benchmarks/bench_bootstrap.py
    --mc`). R = 2000 (the default of `capred shear`) holds the worst case (p = 0.5) near 0.01, the
    resolution at which the probabilities are printed (R = 1000 would leave 0.016 there). Its cost is
    mostly fixed: ~2 ms per material (the affine check of each model, the draws, the percentiles) plus
    ~1 us per replicate.

    Parameters
    ----------
    d_mat : ModelInputs
        The wet tests of one material, with the full-data envelope in ``c``, ``tan_phi``.
    dry_x, dry_y : (nd,) ndarray
        Normal stress and strength of the material's dry tests [Pa].
    models : sequence of str
        Models to rank.
    params : ModelParams
        Model parameters (for the fitted laws).
    fitted : {model: {material: params}}
        The full-data fitted laws (warm starts).
    ranked : list of str
        Models by RMSE on the full data: the first two are the best and the runner-up.
    replicates : int
        Number of bootstrap replicates R.
    seed : int
        Seed of ``numpy.random.default_rng``.
    through_origin : bool
        The dry envelope is fitted through the origin (c = 0).
    rows : array_like of bool or int, optional
        The material's wet tests within ``d_mat`` (then every test): their inputs are copied a chunk at a
        time for the affine models' coefficients, and whole only for a model that needs them in every
        replicate (a fitted law, a model scored replicate by replicate).
    errors, loss : str
        The dry envelope's error model and loss as the run fitted it (``LineFit.errors``, ``LineFit.loss``):
        every replicate refits it the same way (`_dry_refit`; ``either`` and ``constant`` give the
        least-squares line).
    scale : float, optional
        The full-data fit's scale [Pa] (``LineFit.scale``), held in a robust refit.
    adaptive : bool
        Stop before ``replicates`` once the Monte-Carlo error of every printed number is below its printed
        resolution (`adaptive_stop`); the replicates used are in ``RankingUncertainty.replicates``.

    Returns
    -------
    RankingUncertainty

    References
    ----------
    Efron & Tibshirani (1993), doi:10.1007/978-1-4899-4541-9, ch. 6 (number of replications and
    Monte-Carlo error) and ch. 9 (bootstrapping regression by resampling cases).
    """
    rng = np.random.default_rng(seed)
    dry_x, dry_y = np.asarray(dry_x, float), np.asarray(dry_y, float)
    if rows is not None:  # the material's tests, copied only where a model needs them all at once
        index = np.asarray(rows)
        d_mat = _Selected(d_mat, np.flatnonzero(index) if index.dtype == bool else index)
    nw = _size(d_mat)
    first_test = d_mat.subset(slice(0, 1))
    mat, c0, b0 = first_test.material[0], float(first_test.c[0]), float(first_test.tan_phi[0])
    models = list(models)
    laws = [m for m in models if esm.REGISTRY[m].fitted and m in chi_laws.LAWS and mat in fitted.get(m, {})]
    if laws and isinstance(d_mat, _Selected):  # a fitted law is refitted on every replicate's tests
        d_mat = d_mat.subset(slice(None))
    affine, per_replicate = {}, []
    probes = _affine_probes(d_mat) if any(m not in laws for m in models) else None
    for m in models:
        if m in laws:
            continue
        coef = _pointwise_affine(m, d_mat, probes)
        if coef is None:
            per_replicate.append(m)
        else:
            affine[m] = coef
    # six weighted sums per affine model: [ok, e^2, e beta, e gamma, beta^2, beta gamma, gamma^2], formed
    # once for up to KEEP_FEATURES_TESTS tests, else CHUNK_TESTS tests at a time in every block
    for m in affine:
        e, be, ga = affine[m]
        ok = np.isfinite(e) & np.isfinite(be) & np.isfinite(ga)
        affine[m] = tuple(np.where(ok, v, 0.0) for v in (e, be, ga)) + (ok,)
    chunks = [slice(k, min(k + CHUNK_TESTS, nw)) for k in range(0, nw, CHUNK_TESTS)]
    F_once = _affine_features(affine, slice(0, nw)) if affine and nw <= KEEP_FEATURES_TESTS else None
    del probes
    if isinstance(d_mat, _Selected):  # a model scored replicate by replicate needs every test's inputs
        d_mat = d_mat.subset(slice(None)) if per_replicate else None
    col = {m: k for k, m in enumerate(models)}
    affine_cols = np.array([col[m] for m in affine], dtype=int)
    material = _Material(d_mat, nw, dry_x, dry_y, through_origin, c0, b0, mat, (errors, loss, scale))
    scoring = _Scoring(affine, affine_cols, F_once, chunks, laws, per_replicate, col, params, fitted)
    scores = np.full((replicates, len(models)), np.nan)
    groups = _dry_groups(dry_x, through_origin)
    long = affine and not laws and not per_replicate and nw > KEEP_FEATURES_TESTS
    block = max(1, BLOCK_ELEMENTS // max(nw, dry_x.size, 1))

    def run(start: int, stop: int) -> None:  # replicates start..stop-1 into scores
        if long:
            _score_long(rng, scores[start:stop], material, scoring, groups)
            return
        for first in range(start, stop, block):
            count = min(block, stop - first)
            U, idx, valid = _draw(rng, dry_x, nw, count, through_origin, groups)
            kept = np.flatnonzero(valid)
            if not kept.size:  # no dry sample of the block could be refitted
                continue
            if kept.size < count:
                U, idx = U[kept], idx[kept]
            _score_replicates(scores, first + kept, U, idx, material, scoring)

    if not adaptive:
        run(0, replicates)
        return _summarise(scores, models, ranked, seed, replicates)
    done = 0
    while done < replicates:  # rounds of ADAPTIVE_ROUND replicates until the printed numbers are resolved
        stop = min(done + ADAPTIVE_ROUND, replicates)
        run(done, stop)
        done = stop
        if done >= ADAPTIVE_MIN and adaptive_stop(scores[:done], models, ranked):
            break
    return _summarise(scores[:done], models, ranked, seed, replicates)


#: the adaptive bootstrap (issue 44.2): replicates drawn in rounds of ADAPTIVE_ROUND, at least ADAPTIVE_MIN
ADAPTIVE_ROUND = 250
ADAPTIVE_MIN = 500
#: printed resolution of a probability of being best (the console prints whole percents)
PROBABILITY_RESOLUTION = 0.01


def quantile_mc_se(values: np.ndarray, q: float) -> float:
    """Monte-Carlo standard error of the q-quantile of ``values`` from its order statistics.

    Half the distance between the order statistics R q -/+ sqrt(R q (1 - q)) (the binomial 68 % interval of the
    quantile, distribution-free; Efron & Tibshirani 1993, doi:10.1007/978-1-4899-4541-9, ch. 19).

    Parameters
    ----------
    values : (R,) ndarray
        Finite replicate values.
    q : float
        Quantile level in (0, 1).

    Returns
    -------
    float
        The standard error [unit of values] (inf with fewer than 2 values).
    """
    return _sorted_quantile_se(np.sort(values), q)


def _sorted_quantile_se(s: np.ndarray, q: float) -> float:
    """`quantile_mc_se` of values already sorted (``s``): the adaptive stop sorts them once for every use."""
    n = s.size
    if n < 2:
        return float("inf")
    h = math.sqrt(n * q * (1.0 - q))  # scalars: math, not numpy's per-call overhead (the same IEEE results)
    lo = min(max(math.floor(n * q - h), 0), n - 1)
    hi = min(max(math.ceil(n * q + h), 0), n - 1)
    return float(s[hi] - s[lo]) / 2.0


def adaptive_stop(scores: np.ndarray, models: list[str], ranked: list[str]) -> bool:
    """True when every printed number of the ranking is resolved.

    The Monte-Carlo standard error of each model's probability of being best, sqrt(p(1 - p)/R) with p = (wins + 1)/(R +
    2) (never 0 at 0 or R wins), is below ``PROBABILITY_RESOLUTION``, and that of each end of the ΔRMSE interval
    (`quantile_mc_se`) below its printed resolution (`difference_resolution`).

    Parameters
    ----------
    scores : (R, models) ndarray
        RMSE of each model in each replicate so far (NaN: not scored).
    models : list of str
        The columns.
    ranked : list of str
        Models by full-data RMSE (best, runner-up first).

    Returns
    -------
    bool
    """
    finite = np.isfinite(scores)
    if finite.all():  # the usual case: every replicate scored every model (no copies to make)
        R, filled = scores.shape[0], scores
    else:
        rows = np.any(finite, axis=1)
        R = int(rows.sum())
        filled = np.where(finite[rows], scores[rows], np.inf)
    if R < 2:
        return False
    wins = np.bincount(np.argmin(filled, axis=1), minlength=len(models))
    p = (wins + 1.0) / (R + 2.0)
    if np.any(np.sqrt(p * (1.0 - p) / R) >= PROBABILITY_RESOLUTION):
        return False
    best, runner = (list(ranked) + [None, None])[:2]
    if best is None or runner is None:
        return True
    dd = scores[:, models.index(runner)] - scores[:, models.index(best)]
    dd = np.sort(dd[np.isfinite(dd)])  # sorted once: the interval's ends and their errors read it
    if dd.size < 2:
        return True
    res = difference_resolution(tuple(_sorted_percentiles(dd, (2.5, 97.5))))
    if res is None:
        return True
    return all(_sorted_quantile_se(dd, q) < res for q in (0.025, 0.975))


@dataclass(frozen=True)
class _Material:
    """One material as the bootstrap resamples it.

    Its wet tests (``wet``, a ModelInputs or `_Selected`; None when no model needs their inputs in every replicate),
    their number ``nw``, its dry tests ``dry_x``, ``dry_y`` [Pa], whether its dry envelope goes through the origin, the
    full-data envelope ``c0`` [Pa], ``b0`` [-] and its name.
    """

    wet: object
    nw: int
    dry_x: np.ndarray
    dry_y: np.ndarray
    through_origin: bool
    c0: float
    b0: float
    name: str
    dry_model: tuple = ("constant", "ols", None)  # (errors, loss, scale) of the dry refit (`_dry_refit`)


@dataclass(frozen=True)
class _Scoring:
    """How the bootstrap scores each model.

    The affine models' coefficients (``affine``: model -> (e, beta, gamma, ok)) and their columns in the scores, their
    products kept once (``features``; None beyond KEEP_FEATURES_TESTS wet tests, then formed a chunk of tests at a time,
    ``chunks``), the fitted laws and the models scored replicate by replicate, each model's column, the run's
    ModelParams and the full-data fitted laws (warm starts).
    """

    affine: dict
    affine_cols: np.ndarray
    features: np.ndarray | None
    chunks: list
    laws: list
    per_replicate: list
    col: dict
    params: object
    fitted: dict


def _score_replicates(scores, rows, U, idx, material: _Material, scoring: _Scoring) -> None:
    """Each model's RMSE in the replicates ``rows`` into ``scores``.

    The replicates are dry counts U and wet indices idx of ``material.nw`` tests; the wet tests' inputs are needed only
    by fitted laws and models scored replicate by replicate.
    """
    nw, d_mat, mat = material.nw, material.wet, material.name
    affine, F_once, chunks = scoring.affine, scoring.features, scoring.chunks
    laws, per_replicate, col = scoring.laws, scoring.per_replicate, scoring.col
    W = (
        np.bincount((idx + nw * np.arange(idx.shape[0])[:, None]).ravel(), minlength=idx.shape[0] * nw)
        .reshape(idx.shape)
        .astype(float)
    )
    c, b = _dry_refit(U, material.dry_x, material.dry_y, material.through_origin, *material.dry_model)
    dc, db = c - material.c0, b - material.b0
    if affine:  # every affine model at once: (replicates, models) arrays of its seven sums
        WF = W @ F_once if F_once is not None else sum(W[:, ch] @ _affine_features_t(affine, ch).T for ch in chunks)
        scores[rows[:, None], scoring.affine_cols] = _affine_rmse(WF, dc, db, len(affine))
    for m in laws:
        _, r = chi_laws.LAWS[m].refit_batch(d_mat, scoring.params, c, b, W, scoring.fitted[m][mat])
        ok = np.isfinite(r)
        wo = np.where(ok, W, 0.0)
        n_ok = wo.sum(axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            scores[rows, col[m]] = np.where(
                n_ok > 0, np.sqrt((wo * np.where(ok, r, 0.0) ** 2).sum(axis=1) / n_ok), np.nan
            )
    for k in range(idx.shape[0]) if per_replicate else ():
        w = d_mat.subset(idx[k])
        w = dataclasses.replace(w, c=np.full(nw, c[k]), tan_phi=np.full(nw, b[k]))
        for m in per_replicate:
            pred = _tau(m, w)
            ok = np.isfinite(pred)
            if ok.any():
                scores[rows[k], col[m]] = float(np.sqrt(np.mean((pred[ok] - w.tau_max[ok]) ** 2)))


def _affine_rmse(WF: np.ndarray, dc: np.ndarray, db: np.ndarray, models: int) -> np.ndarray:
    """(replicates, models) RMSEs of the affine models from their seven weighted sums per replicate.

    ``WF``, replicates x 7 models, as `_affine_features` orders them, and each replicate's envelope shift ``dc`` [Pa],
    ``db`` [-] from the full-data one; NaN where a replicate holds no test a model predicts.
    """
    n_ok, ee, eb, eg, bb, bg, gg = np.moveaxis(WF.reshape(-1, models, 7), 2, 0)
    dcm, dbm = dc[:, None], db[:, None]
    ss = ee + 2 * dcm * eb + 2 * dbm * eg + dcm * dcm * bb + 2 * dcm * dbm * bg + dbm * dbm * gg
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n_ok > 0, np.sqrt(np.maximum(ss, 0.0) / n_ok), np.nan)


def _score_long(rng, scores: np.ndarray, material: _Material, scoring: _Scoring, groups) -> None:
    """The affine models' RMSEs of every replicate of a long material into ``scores``, chunk by chunk of wet tests.

    A long material is one beyond KEEP_FEATURES_TESTS wet tests, every model affine: linear in the tests, memory flat.

    First the dry refit of every replicate (`_draw_dry`, a block of replicates at a time). Then each
    replicate's ``nw`` wet draws are split among the chunks of CHUNK_TESTS tests by a multinomial draw with
    probabilities proportional to the chunks' sizes, and drawn uniformly within each chunk: jointly the same
    multinomial(nw, 1/nw) counts per test as ``nw`` uniform draws over all tests (`_draw`). Each chunk forms
    its products (`_affine_features_t`) once and adds, for a group of replicates at a time, their counts
    times the products to the replicates' seven sums per model; the RMSEs follow from the sums
    (`_affine_rmse`). The block loop of `bootstrap_ranking` formed every chunk's products again in every block
    of one to four replicates: a cost step of 2-4x per test beyond KEEP_FEATURES_TESTS (README, Performance).
    """
    replicates = scores.shape[0]
    dry_x, nw = material.dry_x, material.nw
    dc, db = np.full(replicates, np.nan), np.full(replicates, np.nan)
    valid = np.zeros(replicates, bool)
    block = max(1, BLOCK_ELEMENTS // max(dry_x.size, 1))
    for first in range(0, replicates, block):
        count = min(block, replicates - first)
        U, ok = _draw_dry(rng, dry_x, count, material.through_origin, groups)
        kept = np.flatnonzero(ok)
        if kept.size:
            c, b = _dry_refit(U[kept], dry_x, material.dry_y, material.through_origin, *material.dry_model)
            dc[first + kept], db[first + kept] = c - material.c0, b - material.b0
            valid[first + kept] = True
    WF = np.zeros((replicates, 7 * len(scoring.affine)))
    for chunk, first, W in _wet_counts(rng, nw, replicates, scoring.chunks):
        if first == 0:
            F_t = _affine_features_t(scoring.affine, chunk)
        WF[first : first + W.shape[0]] += W @ F_t.T
    rows = np.flatnonzero(valid)
    scores[rows[:, None], scoring.affine_cols] = _affine_rmse(WF[rows], dc[rows], db[rows], len(scoring.affine))


def _wet_counts(rng, nw: int, replicates: int, chunks: list):
    """Each replicate's counts of the wet tests (nw draws with replacement), chunk by chunk.

    Yields (chunk, first replicate, W): W (group, tests of the chunk) holds the counts of the replicates
    ``first`` .. ``first + group - 1`` in the chunk, for every chunk in turn and, within it, groups of
    BLOCK_ELEMENTS // CHUNK_TESTS replicates from the first. A replicate's counts over all chunks sum to
    ``nw``: how many of its draws fall in each chunk is multinomial (chunk sizes / nw), then drawn uniformly
    within the chunk.
    """
    sizes = np.array([ch.stop - ch.start for ch in chunks], dtype=np.int64)
    in_chunk = rng.multinomial(nw, sizes / nw, size=replicates)  # (replicates, chunks)
    group = max(1, BLOCK_ELEMENTS // int(sizes.max()))
    for j, chunk in enumerate(chunks):
        k = int(sizes[j])
        for first in range(0, replicates, group):
            n = in_chunk[first : first + group, j]
            draws = rng.integers(0, k, int(n.sum()))
            draws += np.repeat(np.arange(n.size) * k, n)
            yield chunk, first, np.bincount(draws, minlength=n.size * k).reshape(n.size, k).astype(float)


def _affine_features(affine: dict, rows: slice) -> np.ndarray:
    """(tests, 7 m) products of the affine models' coefficients at the tests ``rows``.

    [ok, e^2, e beta, e gamma, beta^2, beta gamma, gamma^2], zero where not finite: their weighted sums give each
    replicate's RMSE.
    """
    out = []
    for e, be, ga, ok in affine.values():
        e, be, ga = e[rows], be[rows], ga[rows]
        out += [ok[rows].astype(float), e * e, e * be, e * ga, be * be, be * ga, ga * ga]
    return np.column_stack(out)


def _affine_features_t(affine: dict, rows: slice) -> np.ndarray:
    """`_affine_features` transposed, (7 m, tests), each row filled in place.

    What a material beyond KEEP_FEATURES_TESTS wet tests forms in every block. Without the interleaving copy of
    ``np.column_stack`` (before: 40 % of such a bootstrap, and a step of 3-4x in its cost per test at that size).
    """
    e0 = next(iter(affine.values()))[0][rows]
    out = np.empty((7 * len(affine), e0.size))
    for j, (e, be, ga, ok) in enumerate(affine.values()):
        e, be, ga = e[rows], be[rows], ga[rows]
        o = out[7 * j : 7 * j + 7]
        o[0] = ok[rows]
        np.multiply(e, e, out=o[1])
        np.multiply(e, be, out=o[2])
        np.multiply(e, ga, out=o[3])
        np.multiply(be, be, out=o[4])
        np.multiply(be, ga, out=o[5])
        np.multiply(ga, ga, out=o[6])
    return out


def _summarise(
    scores: np.ndarray, models: list[str], ranked: list[str], seed: int, cap: int | None = None
) -> RankingUncertainty:
    """Win shares, RMSE percentiles and the best/runner-up difference from the (R, models) RMSE matrix.

    ``cap``: the replicates asked for (the adaptive bootstrap may have stopped before).
    """
    finite = np.isfinite(scores)
    everywhere = bool(finite.all())
    stack = scores if everywhere else scores[np.any(finite, axis=1)]
    filled = stack if everywhere else np.where(np.isfinite(stack), stack, np.inf)
    winners = np.argmin(filled, axis=1)
    counts = np.bincount(winners, minlength=len(models))
    total = max(int(counts.sum()), 1)
    prob = {m: float(counts[k] / total) for k, m in enumerate(models)}
    best, runner = (list(ranked) + [None, None])[:2]
    paired = best is not None and runner is not None
    dd = scores[:, models.index(runner)] - scores[:, models.index(best)] if paired else None
    if everywhere:  # the usual case: every column and the difference in one sort
        bounds = _percentiles(np.column_stack([scores, dd]) if paired else scores, (2.5, 97.5))
        ci = {m: (float(bounds[0, k]), float(bounds[1, k])) for k, m in enumerate(models)}
        diff = (float(bounds[0, -1]), float(bounds[1, -1])) if paired else None
    else:
        ci = {
            m: tuple(float(v) for v in _percentiles(scores[finite[:, k], k], (2.5, 97.5)))
            for k, m in enumerate(models)
            if finite[:, k].any()
        }
        dd = dd[np.isfinite(dd)] if paired else None
        diff = tuple(float(v) for v in _percentiles(dd, (2.5, 97.5))) if paired and dd.size else None
    return RankingUncertainty(
        int(stack.shape[0]), seed, prob, ci, best, runner, diff, cap if cap is not None else int(scores.shape[0])
    )


def _percentiles(a: np.ndarray, q: tuple[float, ...]) -> np.ndarray:
    """``np.percentile(a, q, axis=0)`` (its default linear method, bit for bit) from one sort.

    Without its per-call overhead (~0.2 ms, half the bootstrap's summary).

    The q-th percentile of n sorted values lies at the virtual index (n - 1) q / 100 and is interpolated
    between its two neighbours as numpy's ``_lerp`` does (from the upper one above the midpoint).
    """
    return _sorted_percentiles(np.sort(a, axis=0), q)


def _sorted_percentiles(s: np.ndarray, q: tuple[float, ...]) -> np.ndarray:
    """`_percentiles` of values already sorted along axis 0 (``s``)."""
    n = s.shape[0]
    out = []
    for p in q:
        virtual = (n - 1) * (p / 100.0)
        lo = int(np.floor(virtual))
        hi = min(lo + 1, n - 1)
        g = virtual - lo
        below, above = s[lo], s[hi]
        diff = above - below
        out.append(above - diff * (1.0 - g) if g >= 0.5 else below + diff * g)
    return np.array(out)


def fit_covariances(fits: dict[str, LineFit], material) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per test: covariance of (c, tan phi), residual variance and Student t of its material's dry fit.

    Parameters
    ----------
    fits : {material: LineFit}
        Dry fits.
    material : (n,) array_like of str
        Material of each test.

    Returns
    -------
    cov : (n, 2, 2) ndarray [Pa^2, Pa, -]
    s2 : (n,) ndarray [Pa^2]
    t : (n,) ndarray [-]
        The fit's t quantile at its own confidence level (``LineFit.t``).
    """
    names = list(fits)
    if not len(material):
        return np.empty((0, 2, 2)), np.empty(0), np.empty(0)
    index = {m: k for k, m in enumerate(names)}
    which = np.fromiter((index[m] for m in material), dtype=int, count=len(material))
    cov = np.stack([fits[m].covariance for m in names])[which]
    s2 = np.array([fits[m].residual_variance for m in names], dtype=float)[which]
    t = np.array([fits[m].t for m in names], dtype=float)[which]
    return cov, s2, t


def fit_dof(fits: dict[str, LineFit], material) -> np.ndarray:
    """Residual degrees of freedom of each test's dry fit (n_dry - 2, or n_dry - 1 through the origin) [-].

    Parameters
    ----------
    fits : {material: LineFit}
    material : (n,) array_like of str

    Returns
    -------
    (n,) ndarray of int
    """
    dof = {m: f.dof for m, f in fits.items()}
    return np.fromiter((dof[m] for m in material), dtype=int, count=len(material))


@dataclass
class RetentionRelation:
    """S_R(s) of a material, for drawing model curves along it."""

    S_R: object  # callable: suction [Pa] -> S_R [-]
    source: str  # for the caption

    def suction(self, S_R, lo: float = 1e-3, hi: float = 1e9) -> np.ndarray:
        """The inverse: suction [Pa] at which the relation gives ``S_R`` (NaN outside its range).

        S_R(s) falls monotonically, so the root is bracketed on log s by bisection (vectorised).

        Parameters
        ----------
        S_R : array_like
            Degree of saturation [-].
        lo, hi : float, optional
            Bracket of the search [Pa].

        Returns
        -------
        ndarray
            Suction [Pa], NaN where ``S_R`` is outside the relation's values on the bracket.
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
    """The water-retention relation of a material's wet tests, or None.

    van Genuchten from the options (--retention or --vg-alpha/--vg-n), else a van Genuchten fit (m = 1 - 1/n) of the
    tests' own (suction, S_R) pairs; None when neither is possible (fewer than 4 tests at 3 suctions).

    Parameters
    ----------
    params : ModelParams
        The run's retention parameters (SI).
    suction : array_like
        Suction of the material's wet tests [Pa].
    S_R : array_like
        Their degree of saturation [-].

    Returns
    -------
    RetentionRelation or None
        S_R(s) with the caption saying where it comes from.

    References
    ----------
    .. [1] van Genuchten, M. Th. (1980). Soil Sci. Soc. Am. J. 44, 892-898.
       doi:10.2136/sssaj1980.03615995004400050002x
    """
    from ..physics.retention import vg_water

    if params.retention_model is not None and params.vg_alpha is None:
        from ..fitting.retention_models import MODELS

        name, items, quantity = params.retention_model
        p = dict(items)
        model = MODELS[name]
        # S_R = theta/theta_s; w/w_s for a fit of the water content by mass (at constant rho_d, S_R = w/w_sat)
        scale = 1.0 / p["y_s"] if quantity in ("theta", "w") else 1.0
        return RetentionRelation(lambda s: model.water(s, **p) * scale, f"{model.label} fitted by capred retention")
    if params.vg_alpha is not None and params.vg_n is not None:
        s_res = params.s_res or 0.0
        a, n, m = params.vg_alpha, params.vg_n, params.vg_m
        return RetentionRelation(
            lambda s: vg_water(s, s_res, 1.0, a, n, m),
            f"van Genuchten from the options (α = {a * 1e3:.4g} 1/kPa, n = {n:.4g})",
        )
    ok = (suction > 0) & np.isfinite(S_R)
    if ok.sum() < 4 or np.unique(suction[ok]).size < 3:
        return None
    from ..errors import FitError
    from ..fitting.retention_models import fit_model

    # the same least squares on the distinct (suction, S_R) pairs weighted by their counts: the cost stays that of
    # the distinct states however many tests repeat them (a 100,000-row file has a few dozen per material)
    pairs, counts = np.unique(np.column_stack([suction[ok], S_R[ok]]), axis=0, return_counts=True)
    s_fit, y_fit, w_fit = (
        (pairs[:, 0], pairs[:, 1], counts.astype(float)) if pairs.shape[0] >= 5 else (suction[ok], S_R[ok], None)
    )
    try:
        f = fit_model("vg", s_fit, y_fit, weights=w_fit)
    except FitError:
        return None
    p = f.params_si
    return RetentionRelation(
        lambda s: vg_water(s, p["y_r"], p["y_s"], p["alpha"], p["n"]),
        f"van Genuchten fitted to the tests' own (suction, S_R) pairs (α = "
        f"{p['alpha'] * 1e3:.4g} 1/kPa, n = {p['n']:.4g}, R² = {f.r2:.3f})",
    )


def model_curves(result, material, relation: RetentionRelation, sigma_N: float, points: int = 120):
    """(S_R, {model: tau [Pa]}) along the retention relation at one normal stress.

    Models whose registry entry says ``along_retention=False`` (fitted on the tests' own strengths) are left out.

    Parameters
    ----------
    result : ShearResult
        The run.
    material : str
        One of its materials.
    relation : RetentionRelation
        The S_R(s) relation to follow.
    sigma_N : float
        Normal stress [Pa].
    points : int, optional
        Number of suctions, log-spaced from a third of the smallest to three times the largest test suction [-].

    Returns
    -------
    tuple
        (S_R [-], {model: tau [Pa]}).
    """
    t = result.tests
    sel = (t["material"] == material) & (t["condition"] == "wet")
    s_pos = t["suction"][sel][t["suction"][sel] > 0]
    s = np.geomspace(s_pos.min() / 3, s_pos.max() * 3, points)
    S = np.clip(relation.S_R(s), 0.0, 1.0)
    fit = result.fits[material].line
    n = s.size
    d = esm.ModelInputs(
        np.full(n, sigma_N),
        s,
        S,
        np.full(n, float(np.nanmedian(t["R"][sel]))),
        np.full(n, np.nan),
        np.ones(n, bool),
        np.array([material] * n, dtype=object),
        np.full(n, fit.intercept),
        np.full(n, fit.slope),
        result.options.surface_tension,
        result.options.model_params,
        fitted=result.model_inputs.fitted,
    )
    out = {}
    for m in result.models:
        if not esm.REGISTRY[m].along_retention:  # e.g. a model fitted on the tests' own strengths
            continue
        with np.errstate(invalid="ignore"):
            out[m] = esm.predict(m, d)[1]
    return S, out


def summarise_ranking(scores: np.ndarray, models: list[str], ranked: list[str], seed: int) -> RankingUncertainty:
    """The RankingUncertainty of a (replicates x models) matrix of RMSEs [Pa] (NaN: not scored in a replicate).

    Win shares, 2.5/97.5 percentiles of each model's RMSE and of RMSE(runner-up) − RMSE(best): the summary of
    `bootstrap_ranking`, for a command that draws its replicates itself (`capred triaxial`).

    Parameters
    ----------
    scores : (R, M) ndarray
        RMSE of each model in each replicate [Pa].
    models : list of str
        The M models, in the columns' order.
    ranked : list of str
        The models by RMSE on the full data (best first).
    seed : int
        Seed of the replicates (reported).

    Returns
    -------
    RankingUncertainty

    References
    ----------
    Efron & Tibshirani (1993), doi:10.1007/978-1-4899-4541-9, ch. 13 (percentile intervals).
    """
    return _summarise(scores, models, ranked, seed)
