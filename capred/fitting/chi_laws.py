r"""Chi laws fitted per material on the wet tests, their honest uncertainty, and the information criteria.

With the dry envelope (c, tan phi) of the material, a wet test's strength is

.. math:: \tau = c + (\sigma_N + \chi(\theta)\,\Delta u)\tan\phi

and the law's parameters theta are fitted by least squares on the measured tau
with (c, tan phi) held at the dry fit (two-step estimation: every model of a
material shares one dry envelope, so the models compare on equal terms).

Uncertainty: the dry fit is itself uncertain, and its error moves theta. The
covariance of the two-step estimate is (Murphy & Topel 1985, their corrected
second-step covariance, for a first step fitted on independent data)

.. math:: V_\theta = s^2\,[A + G M G^T], \quad A = (J_\theta^T J_\theta)^{-1}, \quad
          G = -A J_\theta^T J_{c\phi}, \quad M = (X^T X)^{-1}_{dry}

with J_theta and J_cphi the Jacobians of the wet predictions with respect to
theta and to (c, tan phi), and s^2 the residual variance of the joint fit of
(c, tan phi, theta) on the dry and wet tests together (linearised at the
two-step estimate; see `law_uncertainty`): the same measurement scatter is
assumed for dry and wet tests (as `back_analysis` does). Intervals are
theta -/+ t_{0.975, nu} se with the joint fit's nu = n_dry + n_wet - p_env - p
(multiplicative for s_b: on ln s_b). Holding (c, tan phi) fixed instead (``se_conditional``) understates
the scatter of kappa about 2.3-fold on 6 dry + 10 wet tests (72 % coverage of
a nominal 95 % interval, capred issue 23).

Information criteria use Gaussian errors of unknown variance, the same for
every model on the same wet tests: with k = p + 1 (the p fitted parameters
and the error variance; the dry c and phi are common to all models and not
counted), AIC = n ln(RSS/n) + 2k, AICc = AIC + 2k(k + 1)/(n - k - 1),
BIC = n ln(RSS/n) + k ln(n) (Burnham & Anderson 2002, ch. 2 and 6).

References
----------
.. [1] Vanapalli, S. K., Fredlund, D. G., Pufahl, D. E. & Clifton, A. W. (1996). Model for the prediction
   of shear strength with respect to soil suction. Can. Geotech. J. 33(3):379-392, doi:10.1139/t96-060.
.. [2] Khalili, N. & Khabbaz, M. H. (1998). A unique relationship for chi for the determination of the
   shear strength of unsaturated soils. Geotechnique 48(5):681-687, doi:10.1680/geot.1998.48.5.681.
.. [3] Murphy, K. M. & Topel, R. H. (1985). Estimation and inference in two-step econometric models.
   J. Bus. Econ. Stat. 3(4):370-379, doi:10.1080/07350015.1985.10509470.
.. [4] Burnham, K. P. & Anderson, D. R. (2002). Model Selection and Multimodel Inference, 2nd ed.
   Springer, doi:10.1007/b97636.
.. [5] Seber, G. A. F. & Wild, C. J. (1989). Nonlinear Regression. Wiley, doi:10.1002/0471725315
   (the linearised covariance s^2 (J^T J)^-1, t intervals, Gauss-Newton, ch. 14).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..parameters import Parameter, Parameters, correlation_from_covariance, deprecated, fit_report
from ..spec.chi_laws import LAWS, ChiLaw  # noqa: F401  (the registry, declared without numerics)
from .linear import LineFit, t_quantile


@dataclass
class FittedLaw:
    """A chi law fitted on the wet tests of one material.

    ``law.params[NAME]`` gives each parameter as the JSON and console name it (``kappa``, ``s_b_kPa``,
    ``eta``) with its standard error and 95 % interval in the user's unit (`capred.parameters.Parameter`);
    ``law.summary()`` a plain-text report. The SI values stay in ``values``.

    Attributes
    ----------
    values : {name: value}
        The law's parameters, SI (``kappa`` [-]; ``s_b`` [Pa]; ``eta`` [-]); what the models compute with.
    se : {name: value or None}
        Standard errors with the dry fit's uncertainty propagated (when the dry fit was given; else with
        c, tan phi taken as exact) [units of the parameter]; None for a fixed or unidentified parameter.
    rss : float
        Residual sum of squares of the wet tests [Pa^2].
    n : int
        Number of wet tests [-].
    converged : bool
        The optimiser's success flag.
    fixed : tuple of str
        Parameters held (``eta`` of Khalili-Khabbaz unless fitted).
    at_bound : list of str
        Parameters that ended at a bound of the search.
    ci95 : {name: (low, high) or None}
        95 % intervals, theta -/+ t_{0.975, dof} se (s_b: exp(ln s_b -/+ t se/s_b)).
    dof : int or None
        Degrees of freedom of ``ci95``: n_dry - p_dry + n_wet - p (dry fit given), else n_wet - p.
    se_conditional : {name: value or None}
        Standard errors with (c, tan phi) held exact (the wet tests' scatter only) [units of the parameter].
    covariance : ndarray or None
        Joint covariance of ``names`` = (c, tan_phi, free parameters...) [Pa^2, Pa, ...]; None without the
        dry fit.
    names : tuple of str
        Order of ``covariance``.
    residual_variance : float or None
        s^2 behind ``se`` [Pa^2]: pooled over dry and wet tests when the dry fit was given.
    """

    values: dict[str, float]  # SI (s_b in Pa)
    se: dict[str, float | None]
    rss: float  # Pa^2
    n: int
    converged: bool
    fixed: tuple[str, ...] = ()
    at_bound: list[str] = field(default_factory=list)
    ci95: dict[str, tuple[float, float] | None] = field(default_factory=dict)
    dof: int | None = None
    se_conditional: dict[str, float | None] = field(default_factory=dict)
    covariance: np.ndarray | None = None
    names: tuple[str, ...] = ()
    residual_variance: float | None = None
    identifiability: list[str] = field(default_factory=list)
    #: parameters the data cannot determine (`unidentified`): their ``se`` and ``ci95`` are None
    unidentified: tuple[str, ...] = ()

    @property
    def params(self):
        """The parameters by JSON name in the user's units (``kappa`` [-], ``s_b_kPa`` [kPa], ``eta`` [-]).

        Returns
        -------
        capred.parameters.Parameters
            Each with ``value``, ``stderr``, ``ci95``, ``unit``; ``fixed`` for a parameter held (eta unless
            fitted). Before this release ``params`` was the dict of SI values (``params["s_b"]`` in Pa): that
            spelling still answers the old value for one release, with a DeprecationWarning naming ``values``.
        """
        items = []
        for name, v in self.values.items():
            json_name, factor, unit, desc = LAW_PARAMETERS.get(name, (name, 1.0, "-", name))
            se = self.se.get(name)
            ci = self.ci95.get(name)
            items.append(
                Parameter(
                    json_name,
                    float(v) * factor,
                    np.nan if se is None else se * factor,
                    (np.nan, np.nan) if ci is None else (ci[0] * factor, ci[1] * factor),
                    unit,
                    desc,
                    name in self.fixed,
                )
            )
        corr = {}
        if self.covariance is not None and self.names:
            json_names = [LAW_PARAMETERS.get(k, (k,))[0] for k in self.names]
            json_names = ["c_kPa" if k == "c" else k for k in json_names]
            corr = correlation_from_covariance(json_names, self.covariance)
        return _LawParameters(tuple(items), corr, dict(self.values))

    def summary(self, title: str = "fitted chi law") -> str:
        """A plain-text report (lmfit's ``fit_report`` in spirit): parameters, SE, 95 % CI, correlations, warnings.

        Parameters
        ----------
        title : str
            First line, e.g. ``"chi_power of material 'sand'"``.

        Returns
        -------
        str
        """
        ic = information_criteria(self.rss, self.n, len(self.values) - len(self.fixed))
        stats = {"n (wet)": self.n, "dof": self.dof, "RSS [kPa²]": self.rss / 1e6, "AICc": ic["aicc"]}
        warn = [f"{k} lies at its bound" for k in self.at_bound] + list(self.identifiability)
        if ic["aicc"] is None:
            warn.append(
                f"AICc undefined: n - k - 1 = {self.n - (len(self.values) - len(self.fixed) + 1) - 1} <= 0 "
                "(too few wet tests for the parameters and the error variance)"
            )
        return fit_report(title, self.params, stats, warn)


#: SI name of a law parameter -> (JSON name, factor SI -> user unit, unit, description)
LAW_PARAMETERS = {
    "kappa": ("kappa", 1.0, "-", "exponent κ of χ = S_e^κ"),
    "s_b": ("s_b_kPa", 1e-3, "kPa", "air-entry suction s_b of χ = (s/s_b)^−η"),
    "eta": ("eta", 1.0, "-", "exponent η of χ = (s/s_b)^−η"),
    "tan_phi": ("tan_phi", 1.0, "-", "dry friction coefficient"),
}


class _LawParameters(Parameters):
    """Parameters of a law; an old SI key (``"s_b"``) answers its old SI value with a DeprecationWarning."""

    def __init__(self, items, correlation, si):
        super().__init__(items, correlation)
        object.__setattr__(self, "_si", si)

    def __getitem__(self, name):
        if name in self._si and name not in {p.name for p in self.items_}:
            new = LAW_PARAMETERS.get(name, (name,))[0]
            return deprecated(f"law.params[{name!r}] (SI)", f"law.params[{new!r}].value or law.values", self._si[name])
        return super().__getitem__(name)


def information_criteria(rss: float, n: int, p: int) -> dict[str, float | None]:
    r"""AIC, AICc and BIC of a least-squares fit with p fitted parameters on n points (k = p + 1).

    .. math:: \mathrm{AIC} = n\ln(\mathrm{RSS}/n) + 2k, \quad
              \mathrm{AICc} = \mathrm{AIC} + \frac{2k(k+1)}{n-k-1}, \quad
              \mathrm{BIC} = n\ln(\mathrm{RSS}/n) + k\ln n

    Parameters
    ----------
    rss : float
        Residual sum of squares [Pa^2] (any unit: only differences between models on the same data count).
    n : int
        Number of points [-].
    p : int
        Number of fitted parameters of the law [-] (the error variance is added: k = p + 1).

    Returns
    -------
    dict
        ``aic``, ``aicc``, ``bic`` [-]; None where undefined (rss <= 0, n <= 0, or n - k - 1 <= 0 for AICc).

    References
    ----------
    Burnham & Anderson (2002), doi:10.1007/b97636, ch. 2 (AIC and AICc in their least-squares form)
    and ch. 6 (BIC).
    """
    k = p + 1
    if n <= 0 or rss <= 0:
        return {"aic": None, "aicc": None, "bic": None}
    base = n * np.log(rss / n)
    aic = base + 2 * k
    aicc = aic + 2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else None
    return {"aic": float(aic), "aicc": None if aicc is None else float(aicc), "bic": float(base + k * np.log(n))}


def akaike_weights(aicc: dict[str, float | None]) -> dict[str, tuple[float | None, float | None]]:
    r"""(delta AICc, Akaike weight) of each model; models without an AICc get (None, None).

    .. math:: w_i = \frac{\exp(-\Delta_i/2)}{\sum_j \exp(-\Delta_j/2)}, \quad
              \Delta_i = \mathrm{AICc}_i - \min_j \mathrm{AICc}_j

    Parameters
    ----------
    aicc : {model: AICc or None}

    Returns
    -------
    {model: (delta [-], weight [-]) or (None, None)}

    References
    ----------
    Burnham & Anderson (2002), doi:10.1007/b97636, ch. 2 (Akaike weights).
    """
    finite = {m: a for m, a in aicc.items() if a is not None and np.isfinite(a)}
    if not finite:
        return {m: (None, None) for m in aicc}
    best = min(finite.values())
    rel = {m: np.exp(-0.5 * (a - best)) for m, a in finite.items()}
    total = sum(rel.values())
    return {m: ((finite[m] - best, rel[m] / total) if m in finite else (None, None)) for m in aicc}


def _inv(a: np.ndarray) -> np.ndarray:
    try:
        out = np.linalg.inv(a)
    except np.linalg.LinAlgError:
        return np.full(a.shape, np.nan)
    return out if np.all(np.isfinite(out)) else np.full(a.shape, np.nan)


def _finite(x) -> float | None:
    x = float(x)
    return x if np.isfinite(x) else None


def law_uncertainty(
    names,
    values,
    jac_law,
    jac_envelope,
    resid_wet,
    dry: LineFit | None = None,
    log_scale: tuple[str, ...] = (),
    confidence: float = 0.95,
) -> dict:
    r"""Standard errors, t intervals and joint covariance of a law fitted with the dry envelope held.

    .. math:: V_\theta = s^2\,[A + G M G^T], \quad A = (J_\theta^T J_\theta)^{-1}, \quad
              G = -A J_\theta^T J_{c\phi}, \quad M = (X^T X)^{-1}_{dry}

    (Murphy & Topel 1985, doi:10.1080/07350015.1985.10509470: the corrected covariance of a second-step
    estimate, the first step fitted on independent data). The variance s^2 is that of the JOINT
    least-squares fit of (c, tan phi, theta) on the dry and wet tests together, linearised at the two-step
    estimate,

    .. math:: s^2 = \frac{\mathrm{RSS}_{dry} + \mathrm{RSS}_{wet} - g^T (J^T J)^{-1} g}
                         {n_{dry} + n_{wet} - p_{env} - p}, \quad
              g = J^T r = (J_{c\phi}^T r_{wet},\; J_\theta^T r_{wet})

    with J the stacked Jacobian [[X, 0], [J_cphi, J_theta]] (the dry residuals are orthogonal to X). Not the
    two-step residuals alone: the dry fit's error leaves a lack of fit in the wet residuals that would
    inflate s^2 (about 1.3-fold on 6 dry + 10 wet tests with chi = (s/s_b)^-0.55, intervals covering 99 %
    instead of 95 %). Intervals use Student's t with the joint fit's dof nu = n_dry + n_wet - p_env - p.
    Without ``dry``: V = s^2 A, s^2 = RSS_wet/(n_wet - p) (Seber & Wild 1989, doi:10.1002/0471725315).

    Parameters
    ----------
    names : sequence of str
        The free parameters, in the order of the columns of ``jac_law``.
    values : sequence of float
        Their fitted values (SI).
    jac_law : (n_wet, p) ndarray
        d tau_pred / d theta at the optimum [Pa per unit of the parameter].
    jac_envelope : (n_wet, 2) ndarray
        d tau_pred / d(c, tan phi) at the optimum [-, Pa].
    resid_wet : (n_wet,) ndarray
        Residuals tau_pred - tau of the wet tests at the optimum [Pa].
    dry : LineFit, optional
        The material's dry fit; None treats c and tan phi as exact.
    log_scale : tuple of str
        Parameters whose interval is built on their logarithm (positive scale parameters such as s_b).
    confidence : float
        Level of the intervals [-].

    Returns
    -------
    dict
        ``se``, ``se_conditional``, ``ci`` ({name: (low, high) or None}), ``dof``, ``covariance``
        (joint, over ``("c", "tan_phi", *names)``, or None), ``residual_variance`` [Pa^2], ``unidentified``
        (the parameters the tests cannot determine, `unidentified`: their se and ci are None). The inverse
        (J^T J)^-1 is taken on the directions the tests determine (`_pinv_scaled`).

    References
    ----------
    .. [1] Murphy, K. M. & Topel, R. H. (1985). Estimation and inference in two-step econometric models.
       J. Bus. Econ. Stat. 3(4):370-379. doi:10.1080/07350015.1985.10509470, Theorem 1 (the corrected
       covariance of the second-step estimate).
    .. [2] Seber, G. A. F. & Wild, C. J. (1989). Nonlinear Regression. Wiley. doi:10.1002/0471725315,
       ch. 2 (the linearised covariance s^2 (J^T J)^-1 and Student-t intervals; equation number not
       checked).
    """
    names = tuple(names)
    values = np.asarray(values, float)
    jt = np.asarray(jac_law, float).reshape(-1, len(names))
    r = np.asarray(resid_wet, float)
    rss_wet = float(r @ r)
    n, p = jt.shape
    unid = unidentified(jt, names)
    A = _pinv_scaled(jt) if n else np.full((p, p), np.nan)
    se_cond = np.sqrt(np.maximum(np.diag(A) * rss_wet / (n - p), 0.0)) if n > p else np.full(p, np.nan)
    joint = None
    if dry is None:
        dof = n - p
        s2 = rss_wet / dof if dof > 0 else np.nan
        cov = s2 * A
    elif getattr(dry, "errors", "constant") != "constant":
        # a weighted dry fit (scatter proportional to the strength): its own covariance V (not s^2 M) and the wet
        # tests' variance, V_theta = s_wet^2 A + G V G^T (Murphy & Topel 1985, Theorem 1, the first step's
        # covariance as given); the dry and wet scatters are not pooled (they hold at different strengths)
        je = np.asarray(jac_envelope, float).reshape(n, 2)
        dof = n - p
        s2 = rss_wet / dof if dof > 0 else np.nan
        V = np.asarray(dry.covariance, float)
        G = -A @ jt.T @ je
        cov = s2 * A + G @ V @ G.T
        joint = np.block([[V, V @ G.T], [G @ V, cov]])
    else:
        je = np.asarray(jac_envelope, float).reshape(n, 2)
        free = [1] if dry.through_origin else [0, 1]
        # a robust dry fit: its sandwich covariance per unit scale^2 stands for (X^T X)^-1 and dof scale^2 for
        # its RSS (the outlier's residual does not inflate the pooled variance)
        robust = getattr(dry, "loss", "ols") != "ols"
        M = np.asarray(dry.covariance, float) / dry.residual_variance if robust else dry.unscaled_covariance
        rss_dry = dry.dof * dry.residual_variance if robust else dry.rss
        dof = dry.n - len(free) + n - p
        jc = je[:, free]
        xtx = _inv(M[np.ix_(free, free)])
        JtJ = np.block([[xtx + jc.T @ jc, jc.T @ jt], [jt.T @ jc, jt.T @ jt]])
        g = np.concatenate([jc.T @ r, jt.T @ r])
        try:
            drop = float(g @ np.linalg.solve(JtJ, g))
        except np.linalg.LinAlgError:
            drop = 0.0
        rss_joint = max(rss_dry + rss_wet - (drop if np.isfinite(drop) else 0.0), 0.0)
        s2 = rss_joint / dof if dof > 0 else np.nan
        G = -A @ jt.T @ je
        cov = s2 * (A + G @ M @ G.T)
        joint = np.block([[s2 * M, s2 * M @ G.T], [s2 * G @ M, cov]])
    se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    for k, name in enumerate(names):  # not identifiable: undetermined, never the 0 of a singular inverse
        if name in unid:
            se[k] = se_cond[k] = np.nan
    t = t_quantile(0.5 + confidence / 2.0, dof) if dof > 0 else np.nan
    ci: dict[str, tuple[float, float] | None] = {}
    for k, name in enumerate(names):
        v, h = values[k], t * se[k]
        if not np.isfinite(h):
            ci[name] = None
        elif name in log_scale and v > 0:
            f = np.exp(h / v)
            ci[name] = (float(v / f), float(v * f))
        else:
            ci[name] = (float(v - h), float(v + h))
    return {
        "se": {k: _finite(se[i]) for i, k in enumerate(names)},
        "se_conditional": {k: _finite(se_cond[i]) for i, k in enumerate(names)},
        "ci": ci,
        "dof": int(dof),
        "covariance": joint,
        "residual_variance": _finite(s2),
        "unidentified": tuple(unid),
    }


#: column-scaled Jacobian condition number beyond which a direction of the parameters is not determined at all:
#: J^T J then has fewer than 2 significant digits in double precision (cond(J)^2 > 1e14), so an inverse gives
#: rounding noise (standard errors of 0 or 1e9 from one data set to the next)
RANK_LIMIT = 1e7


def unidentified(jac_law, names) -> list[str]:
    """The parameters the data cannot determine.

    A Jacobian column of zeros (the law does not depend on it at the tests), or a share above 1 % of a right singular
    vector of the column-scaled Jacobian whose singular value is below 1/``RANK_LIMIT`` of the largest (a direction the
    tests do not see, e.g. s_b and eta of Khalili's law when every wet test has one suction).

    Parameters
    ----------
    jac_law : (n, p) ndarray
        d tau / d theta at the optimum [Pa per unit of the parameter].
    names : sequence of str
        The parameters, in the order of the columns.

    Returns
    -------
    list of str

    References
    ----------
    Seber, G. A. F. & Wild, C. J. (1989). Nonlinear Regression. Wiley, doi:10.1002/0471725315, ch. 3
    (parameter redundancy: a rank-deficient Jacobian).
    """
    J = np.asarray(jac_law, float).reshape(-1, len(names))
    if J.shape[0] == 0 or not np.all(np.isfinite(J)):
        return list(names)
    norms = np.linalg.norm(J, axis=0)
    out = {names[k] for k in np.flatnonzero(norms <= 0)}
    live = np.flatnonzero(norms > 0)
    if live.size:
        _, sv, Vt = np.linalg.svd(J[:, live] / norms[live], full_matrices=True)
        sv = np.concatenate([sv, np.zeros(live.size - sv.size)])
        for j in np.flatnonzero(sv < sv[0] / RANK_LIMIT):
            out |= {names[live[k]] for k in np.flatnonzero(np.abs(Vt[j]) > 0.01)}
    return [k for k in names if k in out]


def _pinv_scaled(J) -> np.ndarray:
    """(J^T J)^-1 on the directions the tests determine; NaN when J is not finite.

    The pseudo-inverse of the column-scaled J^T J with the singular values below 1/``RANK_LIMIT`` of the largest
    dropped, so a band at the tests stays finite and right even when a parameter on its own is not identified.
    """
    J = np.asarray(J, float)
    if not np.all(np.isfinite(J)):
        return np.full((J.shape[1],) * 2, np.nan)
    norms = np.linalg.norm(J, axis=0)
    d = np.where(norms > 0, norms, 1.0)
    Js = J / d
    U, sv, Vt = np.linalg.svd(Js, full_matrices=False)
    keep = sv >= sv[0] / RANK_LIMIT if sv.size and sv[0] > 0 else np.zeros(sv.shape, bool)
    inv = (Vt[keep].T / sv[keep] ** 2) @ Vt[keep]
    return inv / np.outer(d, d)


def _with_uncertainty(law: FittedLaw, names, values, jac_law, jac_env, resid, dry, log_scale=()) -> FittedLaw:
    u = law_uncertainty(names, values, jac_law, jac_env, resid, dry, log_scale)
    law.se.update(u["se"])
    law.se_conditional = {**{k: None for k in law.values}, **u["se_conditional"]}
    law.ci95 = {**{k: None for k in law.values}, **u["ci"]}
    law.dof = u["dof"]
    law.covariance = u["covariance"]
    law.names = ("c", "tan_phi", *names)
    law.residual_variance = u["residual_variance"]
    law.unidentified = u["unidentified"]
    law.identifiability = identifiability(law, jac_law)
    return law


#: relative standard error above which a strictly positive parameter is not identified (its 68 % interval
#: reaches zero); correlation and (column-scaled) Jacobian condition number beyond which two parameters cannot be
#: told apart (lmfit reports correlations; 1e4 on J is 1e8 on J^T J: half the digits of the normal equations lost)
RELATIVE_SE_LIMIT = 1.0
CORRELATION_LIMIT = 0.99
CONDITION_LIMIT = 1e4
#: the laws' parameters that are strictly positive scales or shapes (judged by their relative SE)
POSITIVE_PARAMETERS = ("kappa", "s_b", "eta")


def identifiability(law: FittedLaw, jac_law=None) -> list[str]:
    """Warnings naming the parameters a fit cannot determine (empty when every parameter is identified).

    Three checks: a strictly positive parameter (κ, s_b, η) whose standard error exceeds its value (relative SE
    > 1: the data cannot tell it from zero or from twice its value); two free parameters of the law correlated
    beyond 0.99; the condition number of the law's Jacobian, columns scaled to unit length, above 1e4 (the
    directions the data cannot separate, as lmfit and Seber & Wild 1989 ch. 3 judge ill-conditioning).

    Parameters
    ----------
    law : FittedLaw
        With ``se`` and ``covariance`` filled (`law_uncertainty`).
    jac_law : (n, p) ndarray, optional
        d tau / d theta at the optimum.

    Returns
    -------
    list of str

    References
    ----------
    .. [1] Seber, G. A. F. & Wild, C. J. (1989). Nonlinear Regression. Wiley, doi:10.1002/0471725315, ch. 3
       (ill-conditioning and parameter redundancy).
    """
    out = []
    free = [k for k in law.values if k not in law.fixed]
    for k in getattr(law, "unidentified", ()):
        out.append(
            f"{LAW_PARAMETERS.get(k, (k,))[0]} is not identifiable from these tests: its standard error and interval "
            "are undetermined (reported as null)"
        )
    for k in free:
        se, v = law.se.get(k), law.values.get(k)
        if k in POSITIVE_PARAMETERS and se is not None and v and np.isfinite(v) and se / abs(v) > RELATIVE_SE_LIMIT:
            name = LAW_PARAMETERS.get(k, (k,))[0]
            out.append(
                f"{name} is not identified: its standard error is {se / abs(v):.3g} times its value (> {RELATIVE_SE_LIMIT:g})"
            )
        if k in POSITIVE_PARAMETERS and law.se.get(k) is None and law.converged and k not in law.unidentified:
            out.append(f"{LAW_PARAMETERS.get(k, (k,))[0]} has no standard error (singular fit): not identified")
    if law.covariance is not None and law.names:
        idx = [law.names.index(k) for k in free if k in law.names]
        cov = np.asarray(law.covariance, float)
        for a in range(len(idx)):
            for b in range(a + 1, len(idx)):
                i, j = idx[a], idx[b]
                d = cov[i, i] * cov[j, j]
                if d > 0 and abs(cov[i, j] / np.sqrt(d)) > CORRELATION_LIMIT:
                    out.append(
                        f"{LAW_PARAMETERS.get(law.names[i], (law.names[i],))[0]} and "
                        f"{LAW_PARAMETERS.get(law.names[j], (law.names[j],))[0]} correlate at "
                        f"{cov[i, j] / np.sqrt(d):+.4f} (|r| > {CORRELATION_LIMIT:g}): the data cannot separate them"
                    )
    if jac_law is not None:
        J = np.asarray(jac_law, float)
        if J.ndim == 2 and J.shape[1] > 1 and J.shape[0] >= J.shape[1] and np.all(np.isfinite(J)):
            norms = np.linalg.norm(J, axis=0)
            if np.all(norms > 0):
                cond = float(np.linalg.cond(J / norms))
                if cond > CONDITION_LIMIT:
                    out.append(
                        f"the Jacobian of {', '.join(LAW_PARAMETERS.get(k, (k,))[0] for k in free)} has condition "
                        f"number {cond:.3g} (> {CONDITION_LIMIT:g}): the fit cannot separate them"
                    )
    return out


def chi_power(S_R, vanapalli_kappa, S_res: float = 0.0):
    r"""Bishop's chi = S_e^kappa with S_e = (S_R - S_res)/(1 - S_res) clipped to [0, 1] [-] (Vanapalli et al. 1996).

    .. math:: \chi = S_e^{\kappa}, \quad S_e = \frac{S_R - S_{res}}{1 - S_{res}}

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-].
    vanapalli_kappa : float or array_like
        Exponent κ [-], > 0 (broadcast against ``S_R``); the fitted law's JSON parameter is ``kappa``.
    S_res : float
        Residual degree of saturation [-].

    Returns
    -------
    ndarray
        chi [-], in [0, 1].

    References
    ----------
    Vanapalli et al. (1996), doi:10.1139/t96-060: their strength equation with the normalised water
    content raised to kappa.
    """
    S_e = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 0.0, 1.0)
    return S_e ** np.asarray(vanapalli_kappa, float)


def fit_chi_power(
    sigma_N, suction, S_R, tau, c, tan_phi, S_res: float = 0.0, start: dict | None = None, dry: LineFit | None = None
) -> FittedLaw:
    r"""Exponent kappa > 0 of chi = S_e^kappa on the wet tests of one material, with its honest uncertainty.

    .. math:: \min_\kappa \sum_i [c + (\sigma_{N,i} + S_{e,i}^\kappa\,\Delta u_i)\tan\phi - \tau_i]^2,
              \quad S_e = (S_R - S_{res})/(1 - S_{res})

    Three starting values (0.3, 1, 3), or one from ``start`` (a warm start). Bounds 1e-6 <= kappa <= 100.

    Parameters
    ----------
    sigma_N, suction, tau : array_like
        Normal stress, matric suction Delta_u and measured peak shear stress of the wet tests [Pa].
    S_R : array_like
        Degree of saturation [-].
    c : float or array_like
        Dry cohesion [Pa].
    tan_phi : float or array_like
        Dry friction coefficient tan(phi) [-].
    S_res : float
        Residual degree of saturation [-].
    start : dict, optional
        ``{"kappa": value}`` to start from.
    dry : LineFit, optional
        The dry fit behind (c, tan phi): its uncertainty is propagated into ``se`` and ``ci95``
        (module docstring); without it c and tan phi are taken as exact.

    Returns
    -------
    FittedLaw
        ``params = {"kappa": ...}``.

    References
    ----------
    Vanapalli et al. (1996), doi:10.1139/t96-060 (the law); Murphy & Topel (1985),
    doi:10.1080/07350015.1985.10509470 (the propagated two-step covariance).
    """
    from scipy.optimize import least_squares

    sigma_N, suction, tau = (np.asarray(x, float) for x in (sigma_N, suction, tau))
    S_e = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 1e-300, 1.0)
    scale = max(float(np.std(tau)), 1.0)

    def resid(p):
        return (c + (sigma_N + S_e ** p[0] * suction) * tan_phi - tau) / scale

    lo, hi = 1e-6, 100.0
    best = min(
        (
            least_squares(resid, [k0], bounds=([lo], [hi]), xtol=1e-14, ftol=1e-14, gtol=1e-14)
            for k0 in ((start["kappa"],) if start else (0.3, 1.0, 3.0))
        ),
        key=lambda r: r.cost,
    )
    kappa = float(best.x[0])
    r = resid(best.x) * scale
    rss = float(r @ r)
    chi = S_e**kappa
    b = np.broadcast_to(tan_phi, r.shape)
    jac = (b * suction * chi * np.log(S_e))[:, None]
    jac_env = np.column_stack([np.ones(r.size), sigma_N + chi * suction])
    at_bound = ["kappa"] if (kappa <= lo * 1.001 or kappa >= hi * 0.999) else []
    law = FittedLaw({"kappa": kappa}, {"kappa": None}, rss, int(r.size), bool(best.success), at_bound=at_bound)
    return _with_uncertainty(law, ("kappa",), [kappa], jac, jac_env, r, dry)


def _khalili_chi(s, s_b, eta):
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return np.where(s > s_b, (np.where(s > 0, s, 1.0) / s_b) ** -eta, 1.0)


def fit_khalili(
    sigma_N,
    suction,
    S_R,
    tau,
    c,
    tan_phi,
    eta: float = 0.55,
    fit_eta: bool = False,
    start: dict | None = None,
    dry: LineFit | None = None,
) -> FittedLaw:
    r"""s_b (and eta with ``fit_eta``) of chi = (s/s_b)^-eta for s > s_b, else 1, with its honest uncertainty.

    .. math:: \chi = (s/s_b)^{-\eta} \; (s > s_b), \quad \chi = 1 \; (s \le s_b)

    The objective is not smooth where s_b passes a measured suction, so s_b is first located on a fine
    logarithmic grid (within [min s / 100, max s * 100]) and then refined locally (from ``start`` alone
    when given: a warm start).

    Parameters
    ----------
    sigma_N, suction, tau : array_like
        Normal stress, matric suction s and measured peak shear stress of the wet tests [Pa].
    S_R : array_like
        Degree of saturation [-] (unused by the law; kept for a common signature).
    c : float or array_like
        Dry cohesion [Pa].
    tan_phi : float or array_like
        Dry friction coefficient [-].
    eta : float
        Exponent [-] (Khalili & Khabbaz found 0.55); fitted in [1e-3, 10] with ``fit_eta``.
    fit_eta : bool
        Fit eta too.
    start : dict, optional
        ``{"s_b": Pa, "eta": -}`` to start from.
    dry : LineFit, optional
        The dry fit behind (c, tan phi), propagated into ``se`` and ``ci95``; ``ci95["s_b"]`` is built on
        ln s_b (it stays positive).

    Returns
    -------
    FittedLaw
        ``params = {"s_b": Pa, "eta": -}``.

    References
    ----------
    Khalili & Khabbaz (1998), doi:10.1680/geot.1998.48.5.681 (the law); Murphy & Topel (1985),
    doi:10.1080/07350015.1985.10509470 (the propagated two-step covariance).
    """
    from scipy.optimize import least_squares

    s = np.asarray(suction, float)
    sigma_N, tau = np.asarray(sigma_N, float), np.asarray(tau, float)
    pos = s[s > 0]
    if pos.size == 0:
        return FittedLaw(
            {"s_b": float("nan"), "eta": eta},
            {"s_b": None, "eta": None},
            float("nan"),
            s.size,
            False,
            ci95={"s_b": None, "eta": None},
        )
    lo, hi = float(pos.min()) / 100.0, float(pos.max()) * 100.0

    def resid(p):
        e = p[1] if fit_eta else eta
        return c + (sigma_N + _khalili_chi(s, np.exp(p[0]), e) * s) * tan_phi - tau

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
    s_b = float(np.exp(p[0]))
    e_hat = float(p[1]) if fit_eta else eta
    # analytic Jacobian in the physical parameters: d chi/d s_b = eta chi / s_b, d chi/d eta = -chi ln(s/s_b)
    chi = _khalili_chi(s, s_b, e_hat)
    above = s > s_b
    b = np.broadcast_to(tan_phi, r.shape)
    cols = [np.where(above, b * s * e_hat * chi / s_b, 0.0)]
    names = ["s_b"]
    if fit_eta:
        with np.errstate(divide="ignore", invalid="ignore"):
            cols.append(np.where(above, -b * s * chi * np.log(np.where(above, s / s_b, 1.0)), 0.0))
        names.append("eta")
    jac_env = np.column_stack([np.ones(r.size), sigma_N + chi * s])
    at_bound = [
        name
        for name, v, (a, bb) in (("s_b", s_b, (lo, hi)),) + ((("eta", e_hat, (1e-3, 10.0)),) if fit_eta else ())
        if v <= a * 1.001 or v >= bb * 0.999
    ]
    law = FittedLaw(
        {"s_b": s_b, "eta": e_hat},
        {"s_b": None, "eta": None},
        rss,
        int(r.size),
        bool(res.success),
        () if fit_eta else ("eta",),
        at_bound,
    )
    return _with_uncertainty(
        law, names, [s_b, e_hat][: len(names)], np.column_stack(cols), jac_env, r, dry, log_scale=("s_b",)
    )


# ----------------------------------------------------------------------------------------------------------
# Many refits at once (the bootstrap): a damped Gauss-Newton over replicates, warm-started


def batch_least_squares(
    resid_jac: Callable,
    x0: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    weights: np.ndarray,
    max_iter: int = 100,
    xtol: float = 1e-12,
):
    r"""Minimise sum_i w_ri r_i(x_r)^2 for every replicate r at once (Levenberg-Marquardt, box bounds).

    .. math:: (J^T W J + \lambda\,\mathrm{diag}(J^T W J))\,\delta = -J^T W r

    A step is taken only where it lowers the replicate's weighted RSS (then lambda /= 10, else
    lambda *= 10); iteration stops when every replicate's step is below ``xtol`` (relative) or its
    lambda has grown past 1e16 (no descent left).

    Parameters
    ----------
    resid_jac : callable
        ``resid_jac(x) -> (r, J)`` with x of shape (R, p), r (R, n) [Pa] and J (R, n, p).
    x0 : (R, p) ndarray
        Starting values (a warm start: the full-data fit).
    lo, hi : (R, p) or (p,) ndarray
        Bounds.
    weights : (R, n) ndarray
        Resampling counts (or any non-negative weights).
    max_iter : int
        Iteration cap.
    xtol : float
        Relative step tolerance.

    Returns
    -------
    x : (R, p) ndarray
        The minimisers.
    r : (R, n) ndarray
        Residuals at ``x`` [Pa].

    References
    ----------
    Seber & Wild (1989), doi:10.1002/0471725315, ch. 14 (Gauss-Newton and Levenberg-Marquardt).
    """
    w = np.asarray(weights, float)
    x = np.clip(np.asarray(x0, float), lo, hi)
    r, J = resid_jac(x)
    cost = np.einsum("rn,rn->r", w, r * r)
    lam = np.full(x.shape[0], 1e-3)
    p = x.shape[1]
    for _ in range(max_iter):
        wJ = w[:, :, None] * J
        g = np.einsum("rnp,rn->rp", wJ, r)
        H = np.einsum("rnp,rnq->rpq", wJ, J)
        Hd = H + lam[:, None, None] * (np.eye(p) * (np.diagonal(H, axis1=1, axis2=2)[:, :, None] + 1e-300))
        if p == 1:
            step = -g / Hd[:, :, 0]
        else:
            step = -np.linalg.solve(Hd, g[:, :, None])[:, :, 0]
        step = np.where(np.isfinite(step), step, 0.0)
        xn = np.clip(x + step, lo, hi)
        rn, Jn = resid_jac(xn)
        cn = np.einsum("rn,rn->r", w, rn * rn)
        better = cn < cost
        moved = np.abs(xn - x).max(axis=1)
        x = np.where(better[:, None], xn, x)
        r = np.where(better[:, None], rn, r)
        J = np.where(better[:, None, None], Jn, J)
        cost = np.where(better, cn, cost)
        lam = np.where(better, lam / 10.0, lam * 10.0)
        done = (better & (moved <= xtol * (1.0 + np.abs(x).max(axis=1)))) | (lam > 1e16)
        if done.all():
            break
    return x, r


def refit_chi_power_batch(sigma_N, suction, S_R, tau, c, tan_phi, weights, kappa0: float, S_res: float = 0.0):
    r"""Exponent kappa of chi = S_e^kappa refitted in every bootstrap replicate at once (weighted least squares).

    .. math:: \min_{\kappa_r} \sum_i w_{ri}\,[c_r + (\sigma_{N,i} + S_{e,i}^{\kappa_r}\Delta u_i)
              \tan\phi_r - \tau_i]^2

    Parameters
    ----------
    sigma_N, suction, tau : (n,) ndarray
        Wet tests [Pa].
    S_R : (n,) ndarray
        Degree of saturation [-].
    c, tan_phi : (R,) ndarray
        Each replicate's dry envelope [Pa], [-].
    weights : (R, n) ndarray
        Resampling counts.
    kappa0 : float
        Warm start (the full-data fit) [-].
    S_res : float
        Residual degree of saturation [-].

    Returns
    -------
    params : {"kappa": (R,) ndarray}
    residuals : (R, n) ndarray
        tau_pred - tau [Pa] with the predictions of `chi_power` (S_e clipped to [0, 1]).

    References
    ----------
    Vanapalli et al. (1996), doi:10.1139/t96-060 (the law).
    """
    S_e = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 1e-300, 1.0)
    lnS = np.log(S_e)
    cc, bb = np.asarray(c, float)[:, None], np.asarray(tan_phi, float)[:, None]

    def f(x):
        chi = S_e[None, :] ** x
        r = cc + (sigma_N + chi * suction) * bb - tau
        return r, (bb * suction * chi * lnS)[:, :, None]

    R = cc.shape[0]
    x, _ = batch_least_squares(f, np.full((R, 1), kappa0), np.array([1e-6]), np.array([100.0]), weights)
    kappa = x[:, 0]
    r = cc + (sigma_N + chi_power(S_R, kappa[:, None], S_res) * suction) * bb - tau
    return {"kappa": kappa}, r


def refit_khalili_batch(
    sigma_N, suction, S_R, tau, c, tan_phi, weights, s_b0: float, eta: float = 0.55, fit_eta: bool = False
):
    """s_b (and eta) of chi = (s/s_b)^-eta refitted in every bootstrap replicate at once.

    Works on ln s_b within each replicate's [min s / 100, max s * 100] (the bounds of `fit_khalili`,
    over the tests drawn), warm-started from the full-data fit.

    Parameters
    ----------
    sigma_N, suction, tau : (n,) ndarray
        Wet tests [Pa].
    S_R : (n,) ndarray
        Degree of saturation [-] (unused by the law).
    c, tan_phi : (R,) ndarray
        Each replicate's dry envelope [Pa], [-].
    weights : (R, n) ndarray
        Resampling counts.
    s_b0 : float
        Warm start [Pa].
    eta : float
        Exponent [-], the warm start when ``fit_eta``.
    fit_eta : bool
        Fit eta too (within [1e-3, 10]).

    Returns
    -------
    params : {"s_b": (R,) ndarray [Pa], "eta": (R,) ndarray [-]}
    residuals : (R, n) ndarray
        tau_pred - tau [Pa].

    References
    ----------
    Khalili & Khabbaz (1998), doi:10.1680/geot.1998.48.5.681 (the law).
    """
    s = np.asarray(suction, float)
    w = np.asarray(weights, float)
    cc, bb = np.asarray(c, float)[:, None], np.asarray(tan_phi, float)[:, None]
    R = cc.shape[0]
    drawn = (w > 0) & (s > 0)
    # a replicate that drew no test with suction has no bounds (NaN; it keeps the warm start below)
    some = drawn.any(axis=1)
    lo, hi = np.full(R, np.nan), np.full(R, np.nan)
    lo[some] = np.log(np.where(drawn, s, np.inf).min(axis=1)[some] / 100.0)
    hi[some] = np.log(np.where(drawn, s, 0.0).max(axis=1)[some] * 100.0)
    ls = np.log(np.where(s > 0, s, 1.0))

    def f(x):
        g = x[:, :1]
        e = x[:, 1:2] if fit_eta else eta
        above = s > np.exp(g)
        chi = np.where(above, np.exp(-e * (ls - g)), 1.0)
        r = cc + (sigma_N + chi * s) * bb - tau
        cols = [np.where(above, bb * s * e * chi, 0.0)]
        if fit_eta:
            cols.append(np.where(above, -bb * s * chi * (ls - g), 0.0))
        return r, np.stack(cols, axis=2)

    x0 = np.column_stack([np.full(R, np.log(s_b0))] + ([np.full(R, eta)] if fit_eta else []))
    lo2 = np.column_stack([lo] + ([np.full(R, 1e-3)] if fit_eta else []))
    hi2 = np.column_stack([hi] + ([np.full(R, 10.0)] if fit_eta else []))
    ok = np.isfinite(lo) & np.isfinite(hi)
    lo2, hi2 = np.where(ok[:, None], lo2, x0), np.where(ok[:, None], hi2, x0)
    x, _ = batch_least_squares(f, x0, lo2, hi2, w)
    s_b = np.exp(x[:, 0])
    e_hat = x[:, 1] if fit_eta else np.full(R, eta)
    r = cc + (sigma_N + _khalili_chi(s, s_b[:, None], e_hat[:, None]) * s) * bb - tau
    return {"s_b": s_b, "eta": e_hat}, r


def chi_power_law(S_R, suction, kappa, S_res: float = 0.0):
    r"""χ of the law ``chi_power`` in the registry's form: `chi_power` of S_R (the suction is not used) [-].

    .. math:: \chi = S_e^{\kappa}, \quad S_e = \frac{S_R - S_{res}}{1 - S_{res}}

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-].
    suction : array_like
        Matric suction [Pa] (broadcast only).
    kappa : float or array_like
        Exponent κ [-], > 0.
    S_res : float
        Residual degree of saturation [-].

    Returns
    -------
    numpy.ndarray
        χ [-], in [0, 1].

    References
    ----------
    Vanapalli et al. (1996), doi:10.1139/t96-060.
    """
    S_R, _ = np.broadcast_arrays(np.asarray(S_R, float), np.asarray(suction, float))
    return chi_power(S_R, kappa, S_res)


def khalili_law(S_R, suction, s_b, eta):
    r"""χ of the law ``khalili_fit`` in the registry's form: (s/s_b)^-η above s_b, 1 below (S_R is not used) [-].

    .. math:: \chi = (s/s_b)^{-\eta} \; (s > s_b), \quad \chi = 1 \; (s \le s_b)

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-] (broadcast only).
    suction : array_like
        Matric suction s [Pa], >= 0.
    s_b : float or array_like
        Air-entry suction [Pa], > 0.
    eta : float or array_like
        Exponent η [-].

    Returns
    -------
    numpy.ndarray
        χ [-], in (0, 1].

    References
    ----------
    Khalili & Khabbaz (1998), doi:10.1680/geot.1998.48.5.681.
    """
    _, s = np.broadcast_arrays(np.asarray(S_R, float), np.asarray(suction, float))
    return _khalili_chi(s, s_b, eta)


def _fit_chi_power_law(w, mp, start=None, dry=None):
    return fit_chi_power(w.sigma_N, w.suction, w.S_R, w.tau_max, w.c, w.tan_phi, mp.s_res or 0.0, start, dry)


def _refit_chi_power_law(w, mp, c, b, weights, start):
    return refit_chi_power_batch(w.sigma_N, w.suction, w.S_R, w.tau_max, c, b, weights, start["kappa"], mp.s_res or 0.0)


def _fit_khalili_law(w, mp, start=None, dry=None):
    return fit_khalili(w.sigma_N, w.suction, w.S_R, w.tau_max, w.c, w.tan_phi, mp.eta, mp.fit_eta, start, dry)


def _refit_khalili_law(w, mp, c, b, weights, start):
    return refit_khalili_batch(
        w.sigma_N, w.suction, w.S_R, w.tau_max, c, b, weights, start["s_b"], start.get("eta", mp.eta), mp.fit_eta
    )
