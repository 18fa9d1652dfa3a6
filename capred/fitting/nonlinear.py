r"""Bounded nonlinear least squares with fixed parameters, several starts and standard errors.

The result record :class:`NonlinearFit` follows lmfit's ``MinimizerResult``:
estimates, standard errors, covariance, n, dof, RSS, R², AIC, AICc, BIC.
Standard errors come from the Jacobian of the weighted residuals at the
optimum, :math:`\mathrm{Cov} = (J^T J)^{-1}\, \mathrm{RSS}/(n - k)`
(the linearisation at the optimum); a parameter that ends on one of its bounds is
held there for the standard errors of the others (the same numbers as a refit
with it fixed), and the fit's ``notes`` say so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import FitError


@dataclass
class NonlinearFit:
    r"""One least-squares fit.

    Attributes
    ----------
    params : dict[str, float]
        Estimates, in the units of the model's parameters (SI inside capred: Pa, 1/Pa, -).
    stderr : dict[str, float | None]
        Standard errors in the same units; None for fixed parameters and for parameters held at a bound.
    fixed : tuple[str, ...]
        Parameters fixed by the caller (not estimated).
    n : int
        Number of data points.
    rss : float
        Weighted residual sum of squares, :math:`\sum w_i (f(x_i) - y_i)^2` [unit of y squared].
    r2 : float
        Weighted coefficient of determination, 1 - RSS/TSS [-].
    aic, bic : float
        Akaike and Bayesian information criteria, :math:`n \ln(\mathrm{RSS}/n) + 2k` and
        :math:`n \ln(\mathrm{RSS}/n) + k \ln n`, k the number of estimated parameters.
    converged : bool
        The optimiser met its tolerances.
    message : str
        The optimiser's message.
    extra : dict
        Free-form additions of the caller.
    covariance : numpy.ndarray or None
        Covariance of the free parameters in the order of ``free`` (rows and columns of held parameters are 0).
    free : tuple[str, ...]
        Estimated parameters.
    bounds : dict[str, tuple[float, float]]
        Search bounds of the free parameters.
    t : float
        Student t quantile (0.975) of the 95 % intervals, with ``dof_se`` degrees of freedom.
    notes : list[str]
        Plain-language remarks on the fit (e.g. a parameter held at its bound for the standard errors).
    log_params : dict[str, float]
        Parameters whose natural scale is logarithmic, ``{name: offset}``: the scale is ln(value - offset)
        (bound checks are made on that scale).
    held : tuple[str, ...]
        Free parameters that ended on a bound and were held there for the standard errors.
    """

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
    covariance: np.ndarray | None = None
    free: tuple[str, ...] = ()
    bounds: dict = field(default_factory=dict)
    t: float = float("nan")
    notes: list = field(default_factory=list)
    log_params: dict = field(default_factory=dict)
    held: tuple[str, ...] = ()

    @property
    def aicc(self) -> float:
        r"""AIC with the small-sample correction, :math:`\mathrm{AIC} + 2k(k + 1)/(n - k - 1)` (k free parameters)."""
        k = self.nfree
        return self.aic + 2 * k * (k + 1) / (self.n - k - 1) if self.n - k - 1 > 0 else float("nan")

    @property
    def rmse(self) -> float:
        """Root mean square of the weighted residuals, sqrt(RSS/n) [unit of y]."""
        return float(np.sqrt(self.rss / self.n))

    def ci95(self, name: str) -> tuple[float, float] | None:
        """95 % interval of one parameter, estimate ± t·SE (None without a standard error).

        Parameters
        ----------
        name : str
            A parameter of the fit.

        Returns
        -------
        tuple of float or None
            (lower, upper) in the parameter's unit.
        """
        se = self.stderr.get(name)
        if se is None or not np.isfinite(se):
            return None
        return self.params[name] - self.t * se, self.params[name] + self.t * se

    def correlation(self) -> dict[str, dict[str, float]]:
        """Correlation matrix of the free parameters, as unsatfit and SWRC Fit report it.

        Only parameters with a standard error take part (held ones and those of zero variance are left out).

        Returns
        -------
        dict of str to dict of str to float
            ``r[a][b]``, the correlation of parameters ``a`` and ``b`` [-]; empty without a covariance.
        """
        if self.covariance is None:
            return {}
        var = np.diag(self.covariance)
        keep = [i for i, k in enumerate(self.free) if k not in self.held and var[i] > 0]
        sd = np.sqrt(var[keep])
        r = self.covariance[np.ix_(keep, keep)] / np.outer(sd, sd)
        names = [self.free[i] for i in keep]
        return {a: {b: float(r[i, j]) for j, b in enumerate(names)} for i, a in enumerate(names)}

    def at_bounds(self, rel: float = 1e-6) -> list[str]:
        """Free parameters that ended on one of their bounds.

        The distance to a bound is measured in the parameter's own scale (ln(value - offset) for the
        parameters of ``log_params``, the value itself otherwise) and compared with ``rel`` times the
        width of the range on that scale.

        Parameters
        ----------
        rel : float, optional
            Tolerance, as a share of the range's width on the parameter's scale [-] (default 1e-6).

        Returns
        -------
        list of str
            Names of the parameters at a bound.
        """
        return [
            k
            for k in self.free
            if _at_bound(self.params[k], self.bounds.get(k, (-np.inf, np.inf)), self.log_params.get(k), rel)
        ]

    @property
    def nfree(self) -> int:
        """Number of estimated parameters (including those held at a bound for the standard errors)."""
        return len(self.params) - len(self.fixed)

    @property
    def dof(self) -> int:
        """Degrees of freedom n - k."""
        return self.n - self.nfree

    @property
    def dof_se(self) -> int:
        """Degrees of freedom of the standard errors: n minus the parameters not held at a bound."""
        return self.n - self.nfree + len(self.held)


def _at_bound(value: float, bounds, offset, rel: float) -> bool:
    """True when ``value`` lies within ``rel`` of the range width of a bound, on the parameter's own scale."""
    lo, hi = bounds
    if offset is not None:  # logarithmic scale ln(x - offset)

        def f(x):
            return float(np.log(x - offset)) if x > offset else -np.inf

        u, ulo, uhi = f(value), f(lo), f(hi)
    else:
        u, ulo, uhi = value, lo, hi
    span = uhi - ulo if np.isfinite(uhi - ulo) else max(abs(u), 1.0)
    return bool(u <= ulo + rel * span or u >= uhi - rel * span)


def fit_curve(model, x, y, names, starts, bounds, fixed=None, weights=None, log_params=None) -> NonlinearFit:
    r"""Minimise :math:`\sum_i w_i\,(f(x_i; p) - y_i)^2` over the free parameters p, from several starts.

    Parameters
    ----------
    model : callable
        ``model(x, **params) -> y`` (numpy, vectorised over x).
    x, y : array_like
        Data (any units; y in the unit of the model's output).
    names : sequence of str
        All parameter names of the model, in order.
    starts : list of dict
        Initial values (every name); the lowest end point wins.
    bounds : dict[str, tuple[float, float]]
        Search bounds per parameter.
    fixed : dict[str, float], optional
        Parameters held at given values.
    weights : array_like, optional
        Per-point weights w_i (default 1); RSS, R² and the criteria are weighted.
    log_params : dict[str, float], optional
        ``{name: offset}`` of parameters with a logarithmic scale (bound checks).

    Returns
    -------
    NonlinearFit
        The best fit, standard errors from its Jacobian.

    Raises
    ------
    FitError
        NaN or infinite data, fewer points than free parameters, or no start converged.

    References
    ----------
    Branch, M. A., Coleman, T. F., Li, Y. (1999). A subspace, interior, and conjugate gradient method for
    large-scale bound-constrained minimization problems. SIAM J. Sci. Comput. 21(1):1-23,
    doi:10.1137/S1064827595289108 (the trust-region reflective method of scipy's least_squares).
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
            r = least_squares(
                resid,
                v0,
                bounds=(lo, hi),
                method="trf",
                x_scale="jac",
                xtol=1e-14,
                ftol=1e-14,
                gtol=1e-14,
                max_nfev=4000,
            )
        except ValueError:
            continue
        if np.all(np.isfinite(r.fun)) and (best is None or r.cost < best.cost):
            best = r
    if best is None:
        raise FitError("the fit did not converge from any starting point")
    return summarize_fit(
        model,
        x,
        y,
        names,
        full(best.x),
        bounds,
        fixed,
        weights,
        bool(best.success),
        log_params=log_params,
        message=str(best.message),
    )


def _assemble(
    names, params, fixed, free, y, sw, rss, jac, bounds, converged, message="", held=(), log_params=None, notes=None
) -> NonlinearFit:
    """The fit statistics: weighted R², AIC/BIC, standard errors and covariance from the Jacobian.

    Columns of ``held`` parameters are left out of the covariance (their rows and columns are 0).
    """
    n, k = len(y), len(free)
    keep = [i for i, name in enumerate(free) if name not in held]
    wts = sw**2
    ybar = float(np.sum(wts * y) / np.sum(wts))
    tss = float(np.sum(wts * (y - ybar) ** 2))
    dof_se = n - len(keep)
    cov = None
    se = np.full(k, np.nan)
    if keep and dof_se > 0:
        J = jac[:, keep]
        try:
            sub = np.linalg.inv(J.T @ J) * rss / dof_se
            if np.all(np.isfinite(sub)):
                cov = np.zeros((k, k))
                cov[np.ix_(keep, keep)] = sub
                d = np.diag(sub)
                # a variance <= 0 with scatter left (rss > 0) is a singular J^T J: the data do not determine
                # that parameter, so its SE is undefined (NaN, printed "—"), not a zero-width interval
                se[keep] = np.where(d > 0, np.sqrt(np.abs(d)), 0.0 if rss == 0 else np.nan)
        except np.linalg.LinAlgError:
            pass
    elif not keep:
        cov = np.zeros((k, k))
    stderr: dict[str, float | None] = {name: None for name in names}
    stderr.update({name: (float(v) if name not in held else None) for name, v in zip(free, se)})
    rss_n = max(rss / n, 1e-300)
    return NonlinearFit(
        params={name: float(params[name]) for name in names},
        stderr=stderr,
        fixed=tuple(fixed),
        n=n,
        rss=rss,
        r2=1.0 - rss / tss if tss > 0 else float("nan"),
        aic=n * np.log(rss_n) + 2 * k,
        bic=n * np.log(rss_n) + k * np.log(n),
        converged=converged,
        message=message,
        covariance=cov,
        free=tuple(free),
        bounds={k_: tuple(bounds[k_]) for k_ in free},
        t=_t95(dof_se),
        notes=list(notes or []),
        log_params=dict(log_params or {}),
        held=tuple(held),
    )


#: degrees of freedom above which a fit's t quantile comes from its asymptotic series (t_quantile_large_dof)
LARGE_DOF = 200


def _t95(dof: int) -> float:
    from .linear import t_quantile

    if dof > LARGE_DOF:  # a large data set: the series, without importing scipy.special (~0.3 s)
        return t_quantile_large_dof(0.975, dof)
    return t_quantile(0.975, dof) if dof > 0 else float("nan")


def t_quantile_large_dof(p: float, dof: float) -> float:
    """Student-t quantile t_{p, ν} for many degrees of freedom, by its asymptotic series in 1/ν.

    Parameters
    ----------
    p : float
        Lower-tail probability [-], in (0, 1).
    dof : float
        Degrees of freedom ν [-]; meant for ν > 200, where four terms of the series suffice.

    Returns
    -------
    float
        t with P(T <= t) = p [-].

    Notes
    -----
    With x the standard normal quantile of p (``statistics.NormalDist``),

    .. math:: t = x + g_1/ν + g_2/ν^2 + g_3/ν^3 + g_4/ν^4,

    g_1 = (x^3 + x)/4, g_2 = (5x^5 + 16x^3 + 3x)/96, g_3 = (3x^7 + 19x^5 + 17x^3 - 15x)/384,
    g_4 = (79x^9 + 776x^7 + 1482x^5 - 1920x^3 - 945x)/92160 (Abramowitz & Stegun 1964, eq. 26.7.5, after
    Fisher & Cornish). Against scipy's ``stdtrit`` its relative error for ν >= 201 is at most 1.2e-12 at
    p = 0.975 and 8e-11 at p = 0.9995 (``tests/test_retention_speed.py``). It spares a fit of many readings
    the import of scipy.special.

    References
    ----------
    .. [1] Abramowitz, M. & Stegun, I. A. (1964). Handbook of Mathematical Functions. NBS Applied
       Mathematics Series 55 (no DOI), eq. 26.7.5.
    """
    from statistics import NormalDist

    x = NormalDist().inv_cdf(p)
    x2 = x * x
    g1 = (x2 + 1.0) * x / 4.0
    g2 = ((5.0 * x2 + 16.0) * x2 + 3.0) * x / 96.0
    g3 = (((3.0 * x2 + 19.0) * x2 + 17.0) * x2 - 15.0) * x / 384.0
    g4 = ((((79.0 * x2 + 776.0) * x2 + 1482.0) * x2 - 1920.0) * x2 - 945.0) * x / 92160.0
    nu = float(dof)
    return x + (g1 + (g2 + (g3 + g4 / nu) / nu) / nu) / nu


def summarize_fit(
    model,
    x,
    y,
    names,
    params: dict,
    bounds,
    fixed=None,
    weights=None,
    converged: bool = True,
    log_params=None,
    message: str = "",
    notes=None,
) -> NonlinearFit:
    """The :class:`NonlinearFit` of given optimal parameters (no optimisation).

    RSS, R², the criteria, and standard errors from a central-difference Jacobian of the weighted residuals
    (step 1e-6 of the parameter's own scale). A free parameter on one of its bounds is held there: the other
    standard errors are those of a refit with it fixed, its own is None, and a note says so.

    Parameters
    ----------
    model : callable
        ``model(x, **params) -> y``.
    x, y : array_like
        Data.
    names : sequence of str
        All parameter names.
    params : dict[str, float]
        The optimum (every name).
    bounds : dict[str, tuple[float, float]]
        Search bounds of the free parameters.
    fixed : dict[str, float], optional
        Parameters fixed by the caller.
    weights : array_like, optional
        Per-point weights.
    converged : bool
        Recorded in the result.
    log_params : dict[str, float], optional
        ``{name: offset}`` of log-scaled parameters.
    message : str
        Recorded in the result.
    notes : list of str, optional
        Remarks carried into the result.

    Returns
    -------
    NonlinearFit

    References
    ----------
    Bates, D. M., Watts, D. G. (1988). Nonlinear Regression Analysis and Its Applications. Wiley,
    doi:10.1002/9780470316757, section 2.3 (linearisation: Cov = s² (JᵀJ)⁻¹, s² = RSS/(n - k)).
    """
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    fixed = dict(fixed or {})
    log_params = dict(log_params or {})
    free = [k for k in names if k not in fixed]
    sw = np.ones_like(y) if weights is None else np.sqrt(np.asarray(weights, float))
    r = (model(x, **params) - y) * sw
    held = tuple(k for k in free if _at_bound(params[k], bounds[k], log_params.get(k), 1e-6))
    notes = list(notes or [])
    for k in held:
        lo, hi = bounds[k]
        side = "lower" if abs(params[k] - lo) <= abs(params[k] - hi) else "upper"
        notes.append(
            f"{k} ended on its {side} bound ({params[k]:.6g}); the standard errors of the other "
            "parameters are those of a fit with it held there, it has none"
        )
    cols = []
    for k in free:
        lo, hi = bounds[k]
        v = params[k]
        if k in log_params:
            h = 1e-6 * max(v - log_params[k], 1e-300)
        else:
            span = hi - lo if np.isfinite(hi - lo) else 1.0
            h = 1e-6 * max(abs(v), 1e-3 * span, 1e-300)
        up, dn = min(v + h, hi), max(v - h, lo)
        if up <= dn:
            cols.append(np.zeros_like(y))
            continue
        cols.append((model(x, **{**params, k: up}) - model(x, **{**params, k: dn})) * sw / (up - dn))
    jac = np.column_stack(cols) if cols else np.empty((x.size, 0))
    return _assemble(
        names, params, fixed, free, y, sw, float(r @ r), jac, bounds, converged, message, held, log_params, notes
    )
