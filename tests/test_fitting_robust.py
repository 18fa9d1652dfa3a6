"""Scatter that grows with stress, outliers and robust losses of the dry envelope (capred issue 30.1-30.2):
each statistic against a hand computation or an independent route to the same number."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.errors import FitError
from capred.fitting.linear import (
    breusch_pagan,
    choose_errors,
    fit_envelope,
    fit_line,
    outlier_diagnostics,
    t_quantile,
)

X = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])


def test_breusch_pagan_by_hand():
    # squared residuals exactly linear in x: the auxiliary R² is 1, so LM = n R² = 6 and
    # p = P(chi2_1 > 6) = erfc(sqrt(3)) = 0.014306 (chi-square tables: 0.0143)
    e = np.sqrt(X) * np.array([1, -1, 1, -1, 1, -1])
    t = breusch_pagan(X, e)
    assert t["statistic"] == pytest.approx(6.0, rel=1e-12)
    assert t["p_value"] == pytest.approx(math.erfc(math.sqrt(3.0)), rel=1e-12)
    assert t["p_value"] == pytest.approx(0.0143, abs=5e-5)
    assert t["significant"]
    # residuals of equal size everywhere: no trend at all (LM undefined -> not testable, never significant)
    flat = breusch_pagan(X, np.array([1, -1, 1, -1, 1, -1.0]))
    assert not flat["significant"]
    # a variance that FALLS with x is not "scatter growing with stress"
    falling = breusch_pagan(X, e[::-1])
    assert falling["statistic"] == pytest.approx(6.0, rel=1e-12) and not falling["significant"]


def test_proportional_fit_is_the_weighted_fixed_point():
    rng = np.random.default_rng(3)
    y = 500.0 + 0.7 * X * 1e3 * (1 + 0.04 * rng.standard_normal(6))
    f = fit_envelope(X * 1e3, y, errors="proportional")
    a, b = f.intercept, f.slope
    yhat = a + b * X * 1e3
    w = (f.ref / yhat) ** 2  # the weights of its own fitted values
    # weighted normal equations: sum w r = 0 and sum w r x = 0 (to rounding)
    r = y - yhat
    assert abs(np.sum(w * r)) <= 1e-8 * np.sum(w * np.abs(y))
    assert abs(np.sum(w * r * X)) <= 1e-8 * np.sum(w * np.abs(y) * X)
    # covariance s² (X'WX)^-1 with s² = sum w r² / (n - 2)
    Xd = np.column_stack([np.ones(6), X * 1e3])
    s2 = float(np.sum(w * r * r) / 4)
    assert_allclose(f.covariance, s2 * np.linalg.inv((Xd.T * w) @ Xd), rtol=1e-8)
    assert f.ref == pytest.approx(np.mean(y))
    # the scatter of a new test grows as the strength: twice the strength, twice the standard deviation
    assert_allclose(f.scatter_variance(2 * f.ref), 4 * f.residual_variance, rtol=1e-12)
    lo, hi = f.prediction_interval(np.array([10e3, 60e3]))
    assert (hi - lo)[1] > 2.5 * (hi - lo)[0]  # the interval at 60 kPa is much wider than at 10 kPa


def test_huber_equals_least_squares_when_no_residual_reaches_k():
    # residuals tiny against the scale: every point inside Huber's corner, psi linear, the M-estimate is OLS
    y = 100.0 + 2.0 * X + np.array([0.3, -0.2, -0.25, 0.2, 0.28, -0.3])
    ols = fit_line(X, y)
    hub = fit_envelope(X, y, loss="huber")
    u = (y - hub.predict(X)) / hub.scale
    assert np.all(np.abs(u) <= 1.345)  # the premise of this test (MAD scale of these residuals)
    assert_allclose([hub.intercept, hub.slope], [ols.intercept, ols.slope], rtol=1e-9)
    # sandwich with psi' = 1 and psi = u: s² n/(n-p) (X'X)^-1 (X'diag(u²)X) (X'X)^-1
    Xd = np.column_stack([np.ones(6), X])
    inv = np.linalg.inv(Xd.T @ Xd)
    V = hub.scale**2 * 6 / 4 * inv @ ((Xd.T * u**2) @ Xd) @ inv
    assert_allclose(hub.covariance, V, rtol=1e-8)


def test_robust_fits_resist_one_outlier():
    rng = np.random.default_rng(7)
    y = 500.0 + 0.7 * X * 1e3 + 400.0 * rng.standard_normal(6)
    y[3] += 8 * 400.0
    truth = 0.7
    ols = fit_envelope(X * 1e3, y)
    for loss in ("huber", "tukey"):
        rob = fit_envelope(X * 1e3, y, loss=loss)
        assert abs(rob.slope - truth) < abs(ols.slope - truth) or abs(rob.slope - truth) < 0.01
        assert rob.slope_se < ols.slope_se  # the outlier no longer inflates the scatter
        assert rob.residual_variance < ols.residual_variance
    with pytest.raises(FitError):
        fit_envelope(X, y, loss="cauchy")
    with pytest.raises(FitError):
        fit_envelope(X, y, errors="log")


def test_externally_studentized_residual_equals_leave_one_out():
    rng = np.random.default_rng(11)
    y = 10 + 0.5 * X + rng.standard_normal(6)
    y[2] += 15.0
    diag = outlier_diagnostics(X, y)
    for i in range(6):  # t_i = (y_i - yhat_(i)) / (s_(i) sqrt(1 + x_i'(X_(i)'X_(i))^-1 x_i)), the textbook identity
        keep = np.arange(6) != i
        f = fit_line(X[keep], y[keep])
        pred_se = math.sqrt(
            f.residual_variance + f.covariance[0, 0] + 2 * X[i] * f.covariance[0, 1] + X[i] ** 2 * f.covariance[1, 1]
        )
        assert diag["studentized"][i] == pytest.approx((y[i] - f.predict(X[i])) / pred_se, rel=1e-9)
    # Bonferroni limit t(1 - 0.05/12, 3) and the flag of the outlier only
    assert diag["threshold"] == pytest.approx(t_quantile(1 - 0.05 / 12, 3), rel=1e-12)
    assert list(np.flatnonzero(diag["outlier"])) == [2]
    # Cook's distance by hand: e² h / (p s² (1 - h)²)
    f = fit_line(X, y)
    e = y - f.predict(X)
    h = diag["leverage"]
    assert_allclose(diag["cooks"], e**2 * h / (2 * f.residual_variance * (1 - h) ** 2), rtol=1e-9)


def test_auto_rule_follows_the_test():
    rng = np.random.default_rng(5)
    x = np.repeat(X, 4) * 1e3
    y = 0.7 * x * (1 + 0.1 * rng.standard_normal(x.size))
    choice, test = choose_errors(x, y)
    assert test["significant"] == (test["p_value"] < 0.05)
    assert choice == ("proportional" if test["significant"] else "constant")
    assert fit_envelope(x, y, errors="auto").errors == choice
    y_const = 0.7 * x + 300 * rng.standard_normal(x.size)
    c2, t2 = choose_errors(x, y_const)
    assert c2 == ("proportional" if t2["significant"] else "constant")


def test_loewner_max_bounds_both_and_equals_the_larger():
    from capred.fitting.linear import loewner_max

    A = np.array([[4.0, 1.0], [1.0, 2.0]])
    B = np.array([[1.0, -0.5], [-0.5, 5.0]])
    M = loewner_max(A, B)
    # M - A and M - B are positive semi-definite (eigenvalues >= 0 up to rounding of 1e-12 of the entries)
    assert np.linalg.eigvalsh(M - A).min() >= -1e-12 and np.linalg.eigvalsh(M - B).min() >= -1e-12
    # B <= 0.5 A in the PSD order: the max is A itself
    assert np.allclose(loewner_max(A, 0.25 * A), A, rtol=1e-12)
    # a line through the origin keeps the intercept's row and column at zero: a scalar max
    Z = loewner_max(np.diag([0.0, 2.0]), np.diag([0.0, 3.0]))
    assert np.allclose(Z, np.diag([0.0, 3.0]))


def test_either_intervals_are_at_least_those_of_each_model():
    rng = np.random.default_rng(4)
    x = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    y = 0.5 + 0.7 * x
    y = y + 0.04 * y * rng.standard_normal(x.size)
    either = fit_envelope(x, y, errors="either")
    const = fit_envelope(x, y, errors="constant")
    prop = fit_envelope(x, y, errors="proportional")
    # the line is the least-squares line (unbiased under both models)
    assert either.slope == pytest.approx(const.slope, rel=1e-12) and either.errors == "either"
    grid = np.linspace(0.0, 80.0, 17)
    lo_e, hi_e = either.prediction_interval(grid)
    lo_c, hi_c = const.prediction_interval(grid)
    assert np.all(hi_e - lo_e >= (hi_c - lo_c) * (1 - 1e-12))  # same centre: at least the constant model's width
    # a new test's variance: at least the proportional model's s_p^2 (y/ref)^2 at every level
    level = either.predict(grid)
    assert np.all(either.scatter_variance(level) >= prop.scatter_variance(level) * (1 - 1e-12))
    assert np.all(either.scatter_variance(level) >= const.residual_variance * (1 - 1e-12))


def test_either_flags_an_outlier_only_when_both_models_do():
    x = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    y = 0.5 + 0.7 * x + np.array([0.1, -0.2, 0.15, 0.0, -0.1, 0.05])
    y_out = y.copy()
    y_out[2] += 3.0  # 15+ sd of the 0.15 kPa scatter at mid-range: an outlier under either model
    f = fit_envelope(x, y_out, errors="either")
    assert f.diagnostics["outlier"].tolist() == [False, False, True, False, False, False]
    for k in range(6):  # the rule, test by test: the AND of the two models' flags
        c = fit_envelope(x, y_out, errors="constant").diagnostics["outlier"][k]
        p = fit_envelope(x, y_out, errors="proportional").diagnostics["outlier"][k]
        assert f.diagnostics["outlier"][k] == (c and p)
