r"""Extended Mohr-Coulomb envelope of unsaturated soils (Fredlund et al. 1978): c', phi', phi_b from failure states.

Direct shear (a plane in net normal stress and suction):

.. math:: \tau_f = c' + (\sigma - u_a)\tan\phi' + (u_a - u_w)\tan\phi_b

and its triaxial forms, from the same plane written with the principal stresses at failure
(:math:`K_p = \tan^2(45° + \phi'/2) = (1 + \sin\phi')/(1 - \sin\phi')`, :math:`c = c' + s\tan\phi_b`):

.. math::

    \text{compression: } q_f = (K_p - 1)\,(\sigma_3 - u_a) + 2\sqrt{K_p}\,(c' + s\tan\phi_b)

    \text{extension: } q_f = (1 - 1/K_p)\,(\sigma_r - u_a) + \frac{2}{\sqrt{K_p}}\,(c' + s\tan\phi_b)

with :math:`\sigma_3` (:math:`\sigma_r`) the net cell pressure and :math:`q_f = |\sigma_a - \sigma_r|` at failure.
Each is linear in its coefficients, :math:`y = a + b\,x + d\,s`: fitted by least squares (``errors="constant"``:
ordinary; ``"proportional"``: weighted with a scatter proportional to the strength, iterated to its fixed
point; ``"auto"``: proportional when the Breusch-Pagan test of the ordinary residuals against the fitted
strength is significant, the rule of `capred shear`), then mapped to (c', phi', phi_b) with standard errors by
the delta method. phi' is a monotone function of b alone, so its interval is b's Student-t interval mapped
(exact under normal errors); c' and phi_b have delta-method intervals. Coverage by simulation:
``tests/test_extended_mc.py`` and docs/user_guide/triaxial_strength.md.

At s -> 0 the plane is the effective (saturated) envelope c', phi': with no saturated test this is the envelope
a run may use, named as such, with its covariance (`ExtendedMCFit.zero_suction_line`).

References
----------
.. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). The shear strength of unsaturated soils.
   Can. Geotech. J. 15(3):313-321, doi:10.1139/t78-029 (the planar envelope in net stress and suction).
.. [2] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley, doi:10.1002/9781118625590
   (multiple regression, its covariance and the prediction interval of a new observation).
.. [3] Carroll, R. J. & Ruppert, D. (1988). Transformation and Weighting in Regression. Chapman & Hall,
   doi:10.1201/9780203735268, ch. 2 (iteratively reweighted least squares for a variance that is a power of
   the mean).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import FitError
from ..parameters import Parameter, Parameters, correlation_from_covariance, fit_report
from .chi_laws import information_criteria
from .linear import ERROR_MODELS, breusch_pagan, loewner_max, t_quantile

#: the forms of the envelope: name -> what the strength y and the stress x are
FORMS = {
    "direct_shear": "tau_f = c' + sigma_net tan(phi') + s tan(phi_b)",
    "compression": "q_f = (Kp - 1) sigma3_net + 2 sqrt(Kp) (c' + s tan(phi_b))",
    "extension": "q_f = (1 - 1/Kp) sigma_r,net + (2/sqrt(Kp)) (c' + s tan(phi_b))",
}

#: iterations of the proportional-error fit (the weights 1/y_hat^2 move by < 1e-10 relative after ~6)
_IRLS_ITERATIONS = 30


def passive_coefficient(phi_deg):
    r"""Passive earth-pressure coefficient :math:`K_p = (1 + \sin\phi')/(1 - \sin\phi')` [-].

    Parameters
    ----------
    phi_deg : array_like
        Friction angle φ' [deg], in [0, 90).

    Returns
    -------
    numpy.ndarray
        :math:`K_p = \tan^2(45° + \phi'/2)` [-].

    References
    ----------
    .. [1] Prunier, F. et al. (2024). Eur. J. Environ. Civ. Eng., doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    s = np.sin(np.radians(np.asarray(phi_deg, float)))
    return (1 + s) / (1 - s)


def coefficients(form: str, c_eff, phi_deg, tan_phi_b=0.0):
    r"""The linear coefficients (a, b, d) of :math:`y = a + b x + d s` for an envelope (c' [Pa], φ' [deg], tan φ_b).

    .. math:: a = g\,c', \quad d = g \tan\phi_b, \quad (b, g) = (\tan\phi', 1),\; (K_p - 1, 2\sqrt{K_p}),\;
              (1 - 1/K_p, 2/\sqrt{K_p})

    for direct shear, triaxial compression and extension (Fredlund et al. 1978; the triaxial forms from the
    principal stresses at failure).

    Parameters
    ----------
    form : {"direct_shear", "compression", "extension"}
    c_eff : array_like
        Effective cohesion c' [Pa].
    phi_deg : array_like
        φ' [deg].
    tan_phi_b : array_like, default 0
        tan φ_b [-].

    Returns
    -------
    (a [Pa], b [-], d [-])

    References
    ----------
    .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). Can. Geotech. J. 15(3):313-321,
       doi:10.1139/t78-029.
    """
    b, g = _slope_and_gain(form, phi_deg)
    return g * np.asarray(c_eff, float), b, g * np.asarray(tan_phi_b, float)


def _slope_and_gain(form: str, phi_deg):
    phi = np.asarray(phi_deg, float)
    if form == "direct_shear":
        return np.tan(np.radians(phi)), np.ones_like(phi)
    kp = passive_coefficient(phi)
    if form == "compression":
        return kp - 1.0, 2.0 * np.sqrt(kp)
    if form == "extension":
        return 1.0 - 1.0 / kp, 2.0 / np.sqrt(kp)
    raise ValueError(f"form must be one of {', '.join(FORMS)} (got {form!r})")


def envelope_of(form: str, a, b, d=0.0):
    """(c' [Pa], φ' [deg], tan φ_b [-]) of the linear coefficients (a, b, d): the inverse of `coefficients`.

    Parameters
    ----------
    form : {"direct_shear", "compression", "extension"}
    a : array_like
        Intercept [Pa].
    b : array_like
        Slope on the net stress [-].
    d : array_like, default 0
        Slope on the suction [-].

    Returns
    -------
    (c' [Pa], φ' [deg], tan φ_b [-]); NaN where b gives no friction angle in [0, 90).

    References
    ----------
    .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). Can. Geotech. J. 15(3):313-321,
       doi:10.1139/t78-029.
    """
    b = np.asarray(b, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        if form == "direct_shear":
            phi = np.where(b >= 0, np.degrees(np.arctan(b)), np.nan)
        else:
            kp = 1.0 + b if form == "compression" else 1.0 / (1.0 - b)
            ok = (kp >= 1.0) & np.isfinite(kp) if form == "compression" else (b >= 0) & (b < 1)
            sk = np.sqrt(np.where(ok, kp, np.nan))
            phi = np.degrees(2.0 * np.arctan(sk)) - 90.0
        _, g = _slope_and_gain(form, phi)
        return np.asarray(a, float) / g, phi, np.asarray(d, float) / g


@dataclass(frozen=True)
class ExtendedMCFit:
    """An extended Mohr-Coulomb fit (Fredlund et al. 1978) of one material.

    ``params["c_eff_kPa"]``, ``params["phi_eff_deg"]``, ``params["phi_b_deg"]`` (and ``tan_phi_b``) carry
    value, standard error and 95 % interval in the user's units; ``summary()`` is the plain-text report.

    Attributes
    ----------
    form : str
        ``"direct_shear"``, ``"compression"`` or ``"extension"`` (`FORMS`).
    x, s, y : numpy.ndarray
        Net stress [Pa] (σ_N − u_a, or the net cell pressure), suction [Pa] and strength (τ_f or q_f) [Pa].
    coef : numpy.ndarray
        (a [Pa], b [-], d [-]) of y = a + b x + d s.
    covariance : numpy.ndarray
        3 x 3 covariance of ``coef`` [SI].
    residual_variance : float
        s² [Pa²] (constant errors) or the variance of y/ŷ [-] (proportional errors).
    errors : str
        The error model used: ``"constant"``, ``"proportional"`` or ``"either"`` (the constant model's plane
        with intervals that hold under both, see `fit_extended_mc`).
    errors_option : str
        As asked (``"auto"`` resolves to constant or proportional).
    heteroscedasticity : dict
        Breusch-Pagan test of the ordinary residuals against the fitted strength (`capred.fitting.linear`).
    confidence : float
        Level of the intervals [-].
    weights : numpy.ndarray
        Weights of the final least squares [1/Pa² up to a constant] (ones for constant errors).
    """

    form: str
    x: np.ndarray
    s: np.ndarray
    y: np.ndarray
    coef: np.ndarray
    covariance: np.ndarray
    residual_variance: float
    errors: str
    errors_option: str
    heteroscedasticity: dict
    confidence: float
    weights: np.ndarray
    warnings: tuple = field(default=())
    #: ``errors="either"``: the variance of y/ŷ of the proportional model [-] (a new test's variance is the larger
    #: of ``residual_variance`` and this times ŷ²)
    residual_variance_proportional: float = math.nan

    # --- sizes and statistics ---------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Failure states fitted [-]."""
        return int(self.y.size)

    @property
    def dof(self) -> int:
        """Residual degrees of freedom n − 3 [-]."""
        return self.n - 3

    @property
    def t(self) -> float:
        """Two-sided Student-t quantile of ``confidence`` at ``dof`` [-]."""
        return float(t_quantile(0.5 + self.confidence / 2, self.dof))

    @property
    def fitted(self) -> np.ndarray:
        """ŷ of the fitted tests [Pa]."""
        return self.predict(self.x, self.s)

    @property
    def residuals(self) -> np.ndarray:
        """Residuals y − ŷ of the fitted tests [Pa]."""
        return self.y - self.fitted

    @property
    def rss(self) -> float:
        """Residual sum of squares (unweighted) [Pa²]."""
        return float(np.sum(self.residuals**2))

    @property
    def r2(self) -> float:
        """Coefficient of determination of y [-]."""
        tss = float(np.sum((self.y - self.y.mean()) ** 2))
        return 1.0 - self.rss / tss if tss > 0 else math.nan

    def information_criteria(self) -> dict:
        """AIC, AICc and BIC with three fitted coefficients.

        Returns
        -------
        dict
            ``aic``, ``aicc``, ``bic`` [-] as :func:`capred.fitting.chi_laws.information_criteria` computes them
            (k = 3 coefficients + the error variance); None where undefined.
        """
        return information_criteria(self.rss, self.n, 3)

    # --- the envelope -----------------------------------------------------------------------------------
    @property
    def envelope(self) -> tuple[float, float, float]:
        """(c' [Pa], φ' [deg], tan φ_b [-])."""
        c, phi, tb = envelope_of(self.form, *self.coef)
        return float(c), float(phi), float(tb)

    def _derived(self, coef):
        c, phi, tb = envelope_of(self.form, *coef)
        return np.array([c, phi, np.degrees(np.arctan(tb)), tb], dtype=float)

    def derived_covariance(self) -> np.ndarray:
        """Covariance of the envelope's parameters by the delta method.

        The Jacobian of (c', φ', φ_b, tan φ_b) with respect to ``coef`` is taken by central differences (steps of
        1e-6 relative) and carried through ``covariance``.

        Returns
        -------
        numpy.ndarray
            4 x 4 covariance of (c' [Pa], φ' [deg], φ_b [deg], tan φ_b [-]) in those units squared.
        """
        base = self.coef
        J = np.zeros((4, 3))
        for k in range(3):
            h = 1e-6 * max(abs(base[k]), 1e-3 if k else 1.0)
            up, dn = base.copy(), base.copy()
            up[k] += h
            dn[k] -= h
            J[:, k] = (self._derived(up) - self._derived(dn)) / (2 * h)
        return J @ self.covariance @ J.T

    def zero_suction_line(self) -> tuple[float, float, np.ndarray]:
        """The envelope at s -> 0 as the line y = a + b x: (a [Pa], b [-], 2 x 2 covariance of (a, b)).

        Returns
        -------
        (float, float, numpy.ndarray)
        """
        return float(self.coef[0]), float(self.coef[1]), self.covariance[:2, :2].copy()

    @property
    def params(self) -> Parameters:
        """The envelope's parameters: c' [kPa], φ' [deg], φ_b [deg] and tan φ_b [-], with standard error and interval at ``confidence``."""
        values = self._derived(self.coef)
        cov = self.derived_covariance()
        se = np.sqrt(np.maximum(np.diag(cov), 0.0))
        t = self.t
        # φ' is a monotone function of b: its interval is b's interval mapped (exact under normal errors)
        b_half = t * math.sqrt(max(self.covariance[1, 1], 0.0))
        phi_lo = float(self._derived(self.coef - np.array([0, b_half, 0]))[1])
        phi_hi = float(self._derived(self.coef + np.array([0, b_half, 0]))[1])
        if not np.isfinite(phi_lo) and np.isfinite(values[1]):
            phi_lo = 0.0
        specs = (
            ("c_eff_kPa", 1e-3, "kPa", "effective cohesion c' (at zero suction)"),
            ("phi_eff_deg", 1.0, "deg", "effective friction angle φ'"),
            ("phi_b_deg", 1.0, "deg", "angle φ_b of the strength gain with suction"),
            ("tan_phi_b", 1.0, "-", "tan φ_b"),
        )
        items = []
        for k, (name, scale, unit, text) in enumerate(specs):
            v, e = values[k] * scale, se[k] * scale
            ci = (phi_lo, phi_hi) if k == 1 else (v - t * e, v + t * e)
            items.append(Parameter(name, float(v), float(e), (float(ci[0]), float(ci[1])), unit, text))
        return Parameters(tuple(items), correlation_from_covariance([p.name for p in items[:3]], cov[:3, :3]))

    # --- prediction -------------------------------------------------------------------------------------
    def predict(self, x, s) -> np.ndarray:
        """Strength on the fitted plane, ŷ = a + b x + d s (Fredlund et al. 1978).

        Parameters
        ----------
        x : float or array_like
            Net stress [Pa] (σ_N − u_a, or the net cell pressure).
        s : float or array_like
            Suction u_a − u_w [Pa], broadcast against ``x``.

        Returns
        -------
        numpy.ndarray
            Predicted strength (τ_f or q_f, as ``form``) [Pa].

        References
        ----------
        .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). The shear strength of unsaturated soils.
           Canadian Geotechnical Journal 15(3), 313-321. doi:10.1139/t78-029
        """
        a, b, d = self.coef
        return a + b * np.asarray(x, float) + d * np.asarray(s, float)

    def _design(self, x, s) -> np.ndarray:
        x, s = np.broadcast_arrays(np.asarray(x, float), np.asarray(s, float))
        return np.stack([np.ones(x.shape), x, s], axis=-1)

    def mean_band(self, x, s) -> tuple[np.ndarray, np.ndarray]:
        """Confidence band of the mean strength, ŷ ∓ t √(g' V g).

        g is the design row (1, x, s), V the covariance of ``coef`` and t the two-sided Student-t quantile at
        ``confidence``.

        Parameters
        ----------
        x : float or array_like
            Net stress [Pa].
        s : float or array_like
            Suction [Pa], broadcast against ``x``.

        Returns
        -------
        lower, upper : numpy.ndarray
            The band's edges [Pa].
        """
        X = self._design(x, s)
        half = self.t * np.sqrt(np.maximum(np.einsum("...i,ij,...j->...", X, self.covariance, X), 0.0))
        y = self.predict(x, s)
        return y - half, y + half

    def new_test_variance(self, x, s) -> np.ndarray:
        """Variance of one new test's strength about its mean.

        s² for constant errors, s² ŷ² for proportional errors, and the larger of the two for ``errors="either"``.

        Parameters
        ----------
        x : float or array_like
            Net stress [Pa].
        s : float or array_like
            Suction [Pa], broadcast against ``x``.

        Returns
        -------
        numpy.ndarray
            The variance [Pa²].
        """
        y = self.predict(x, s)
        if self.errors == "either":
            return np.maximum(self.residual_variance, self.residual_variance_proportional * y**2)
        return self.residual_variance * (y**2 if self.errors == "proportional" else np.ones_like(y))

    def prediction_interval(self, x, s) -> tuple[np.ndarray, np.ndarray]:
        """Interval of a new test's strength, ŷ ∓ t √(g' V g + variance of one test).

        Parameters
        ----------
        x : float or array_like
            Net stress [Pa].
        s : float or array_like
            Suction [Pa], broadcast against ``x``.

        Returns
        -------
        lower, upper : numpy.ndarray
            The interval's edges [Pa] at level ``confidence``.
        """
        X = self._design(x, s)
        var = np.einsum("...i,ij,...j->...", X, self.covariance, X) + self.new_test_variance(x, s)
        half = self.t * np.sqrt(np.maximum(var, 0.0))
        y = self.predict(x, s)
        return y - half, y + half

    # --- report -----------------------------------------------------------------------------------------
    def summary(self, title: str = "") -> str:
        """Plain-text report of the fit, as lmfit's ``fit_report``.

        Parameters, standard errors and intervals, strong correlations, statistics (n, dof, R², RMSE [kPa], AICc) and
        warnings.

        Parameters
        ----------
        title : str, optional
            First line of the report (default: the fit's name and form).

        Returns
        -------
        str
            The report.
        """
        crit = self.information_criteria()
        stats = {
            "form": self.form,
            "n": self.n,
            "dof": self.dof,
            "errors": self.errors,
            "R²": self.r2,
            "RMSE [kPa]": 1e-3 * math.sqrt(self.rss / self.n),
            "AICc": crit["aicc"],
        }
        return fit_report(
            title or f"extended Mohr-Coulomb fit (Fredlund et al. 1978), {FORMS[self.form]}",
            self.params,
            stats,
            self.warnings,
        )

    def __repr__(self) -> str:
        c, phi, tb = self.envelope
        return (
            f"<ExtendedMCFit {self.form}: c' = {1e-3 * c:.4g} kPa, φ' = {phi:.4g} deg, "
            f"φ_b = {math.degrees(math.atan(tb)):.4g} deg, n = {self.n}>"
        )

    def _repr_html_(self) -> str:
        """The plain-text report (`summary`) in a notebook, escaped."""
        import html

        return f"<pre>{html.escape(self.summary())}</pre>"


def fit_extended_mc(
    x, s, y, form: str = "compression", errors: str = "constant", confidence: float = 0.95
) -> ExtendedMCFit:
    r"""Fit the extended Mohr-Coulomb envelope (c', φ', φ_b) to failure states of one material.

    .. math:: y_i = a + b\,x_i + d\,s_i + \varepsilon_i, \qquad
              \mathrm{Var}\,\varepsilon_i = \sigma^2 \;(\text{constant}) \text{ or } \sigma^2 \hat y_i^2
              \;(\text{proportional})

    then :math:`(c', \phi', \tan\phi_b)` from (a, b, d) by `envelope_of`.

    Parameters
    ----------
    x : array_like
        Net stress [Pa]: σ_N − u_a (direct shear) or the net cell pressure σ3 − u_a (triaxial).
    s : array_like
        Matric suction u_a − u_w [Pa].
    y : array_like
        Strength at failure [Pa]: τ_f (direct shear) or q_f (triaxial).
    form : {"direct_shear", "compression", "extension"}, default "compression"
    errors : {"constant", "proportional", "auto", "either"}, default "constant"
        The scatter of a test: constant (ordinary least squares), proportional to the strength (weighted, iterated),
        chosen by the Breusch-Pagan test of the ordinary residuals against the fitted strength, or ``either``: the
        ordinary least-squares plane (unbiased under both) with the covariance `capred.fitting.linear.loewner_max`
        of its covariance under constant scatter and its sandwich covariance under scatter proportional to the
        strength, and a new test's variance the larger of the two models' (as ``--errors either`` of `capred
        shear`): every interval at least as wide as either model's, with no choice made.
    confidence : float, default 0.95
        Level of the intervals.

    Returns
    -------
    ExtendedMCFit

    Raises
    ------
    FitError
        Fewer than 4 states, no spread of the net stress or of the suction (the plane is not determined), or a
        slope that gives no friction angle.

    References
    ----------
    .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). Can. Geotech. J. 15(3):313-321,
       doi:10.1139/t78-029.
    .. [2] Draper & Smith (1998), doi:10.1002/9781118625590 (the covariance s² (X'WX)⁻¹).
    """
    if form not in FORMS:
        raise FitError(f"form must be one of {', '.join(FORMS)} (got {form!r})")
    if errors not in ERROR_MODELS:
        raise FitError(f"errors must be one of {', '.join(ERROR_MODELS)} (got {errors!r})")
    x, s, y = (np.asarray(v, float).ravel() for v in (x, s, y))
    if not (x.size == s.size == y.size):
        raise FitError("x, s and y must have the same length")
    if not np.all(np.isfinite(x) & np.isfinite(s) & np.isfinite(y)):
        raise FitError("the failure states hold a missing or non-finite value")
    n = y.size
    if n < 4:
        raise FitError(f"the extended Mohr-Coulomb envelope needs at least 4 failure states (got {n}): 3 coefficients")
    X = np.column_stack([np.ones(n), x, s])
    if np.ptp(x) <= 0 or np.ptp(s) <= 0 or np.linalg.matrix_rank(X) < 3:
        raise FitError(
            "the failure states do not determine the plane: the net stress and the suction must each take at least "
            "two values, and not vary together"
        )
    if errors == "either":
        return _either(X, x, s, y, form, confidence)
    ols, *_ = np.linalg.lstsq(X, y, rcond=None)
    bp = breusch_pagan(X @ ols, y - X @ ols, float(np.max(np.abs(y))))
    used = errors if errors != "auto" else ("proportional" if bp["significant"] else "constant")
    w = np.ones(n)
    coef = ols
    notes: list[str] = []
    if used == "proportional":
        for _ in range(_IRLS_ITERATIONS):
            yhat = X @ coef
            if np.any(yhat <= 0):
                notes.append("proportional errors need a positive fitted strength: constant errors used instead")
                used, w, coef = "constant", np.ones(n), ols
                break
            w_new = 1.0 / yhat**2
            sw = np.sqrt(w_new)
            new, *_ = np.linalg.lstsq(X * sw[:, None], y * sw, rcond=None)
            done = np.allclose(new, coef, rtol=1e-12, atol=0.0)
            coef, w = new, w_new
            if done:
                break
    dof = n - 3
    r = y - X @ coef
    # weights scaled so that the residual variance is that of y/ŷ (proportional) or of y (constant)
    s2 = float(np.sum(w * r**2) / dof) if dof > 0 else math.nan
    XtWX = X.T @ (X * w[:, None])
    cov = s2 * np.linalg.inv(XtWX) if dof > 0 else np.full((3, 3), np.nan)
    fit = ExtendedMCFit(form, x, s, y, coef, cov, s2, used, errors, bp, confidence, w, tuple(notes))
    c, phi, _ = fit.envelope
    if not np.isfinite(phi):
        raise FitError(
            f"the fitted slope b = {coef[1]:.4g} on the net stress gives no friction angle in [0, 90) deg "
            f"({FORMS[form]})"
        )
    warns = list(notes)
    if dof < 3:
        warns.append(f"only {dof} residual degree(s) of freedom: wide intervals")
    if c < 0:
        warns.append(f"negative cohesion c' = {1e-3 * c:.3g} kPa at zero suction (an extrapolation below the data)")
    return ExtendedMCFit(form, x, s, y, coef, cov, s2, used, errors, bp, confidence, w, tuple(warns))


def _either(X, x, s, y, form, confidence) -> ExtendedMCFit:
    """``errors="either"`` of `fit_extended_mc`: intervals valid whether the scatter is constant or proportional.

    The sandwich covariance of the ordinary least-squares coefficients under Var y_i = s_p² ŷ_i² is
    (X'X)⁻¹ X' diag(s_p² ŷ²) X (X'X)⁻¹ (Carroll & Ruppert 1988, ch. 2), with s_p² the variance of y/ŷ of the
    proportional fit.
    """
    const = fit_extended_mc(x, s, y, form, "constant", confidence)
    prop = fit_extended_mc(x, s, y, form, "proportional", confidence)
    if prop.errors != "proportional" or not np.isfinite(prop.residual_variance):
        return dataclasses.replace(const, errors_option="either")
    level = np.maximum(np.abs(X @ const.coef), 1e-3 * float(np.max(np.abs(y))))
    inv = np.linalg.inv(X.T @ X)
    cov_p = inv @ ((X.T * (prop.residual_variance * level**2)) @ X) @ inv
    return dataclasses.replace(
        const,
        covariance=loewner_max(const.covariance, cov_p),
        errors="either",
        errors_option="either",
        residual_variance_proportional=float(prop.residual_variance),
    )
