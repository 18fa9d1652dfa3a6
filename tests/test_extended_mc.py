"""Extended Mohr-Coulomb fit (capred.fitting.extended_mc): forms, the OLS equality, intervals by simulation."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.errors import FitError
from capred.fitting.extended_mc import coefficients, envelope_of, fit_extended_mc, passive_coefficient


def test_triaxial_compression_form_by_hand():
    # phi' = 30 deg: Kp = (1 + 1/2)/(1 - 1/2) = 3, so q = 2 sigma3 + 2 sqrt(3) (c' + s tan phi_b)
    a, b, d = coefficients("compression", 10e3, 30.0, 0.5)
    assert_allclose(passive_coefficient(30.0), 3.0, rtol=1e-12)
    assert_allclose((a, b, d), (2 * math.sqrt(3) * 10e3, 2.0, 2 * math.sqrt(3) * 0.5), rtol=1e-12)
    # extension: q = (1 - 1/3) sigma_r + (2/sqrt(3)) (c' + s tan phi_b)
    a, b, d = coefficients("extension", 10e3, 30.0, 0.5)
    assert_allclose((a, b, d), (2 / math.sqrt(3) * 10e3, 2 / 3, 2 / math.sqrt(3) * 0.5), rtol=1e-12)


@pytest.mark.parametrize("form", ["direct_shear", "compression", "extension"])
def test_envelope_of_inverts_coefficients(form):
    c, phi, tb = envelope_of(form, *coefficients(form, 12e3, 33.0, 0.3))
    assert_allclose((c, phi, tb), (12e3, 33.0, 0.3), rtol=1e-12)


def _states(rng, n=12, form="compression", c=10e3, phi=30.0, phib=18.0, noise=0.0):
    a, b, d = coefficients(form, c, phi, math.tan(math.radians(phib)))
    x, s = rng.uniform(20e3, 400e3, n), rng.uniform(20e3, 400e3, n)
    y = a + b * x + d * s
    return x, s, y + noise * rng.normal(size=n)


@pytest.mark.parametrize("form", ["direct_shear", "compression", "extension"])
def test_fit_recovers_exact_envelope(form):
    x, s, y = _states(np.random.default_rng(3), form=form)
    p = fit_extended_mc(x, s, y, form).params
    # exact data: the fit reproduces the plane to rounding (1e-9 relative of a 10 kPa cohesion)
    assert_allclose([p["c_eff_kPa"].value, p["phi_eff_deg"].value, p["phi_b_deg"].value], [10, 30, 18], rtol=1e-9)


def test_constant_errors_equal_numpy_lstsq_of_the_triaxial_formula():
    """Issue 40: with constant errors the parameters are the OLS fit of q = (Kp-1) s3 + 2 sqrt(Kp)(c' + s tan phi_b)."""
    rng = np.random.default_rng(7)
    x, s, y = _states(rng, n=15, noise=8e3)
    fit = fit_extended_mc(x, s, y, "compression", errors="constant")
    X = np.column_stack([np.ones_like(x), x, s])
    beta, rss, *_ = np.linalg.lstsq(X, y, rcond=None)
    kp = 1 + beta[1]
    # independent mapping of the OLS coefficients: phi' from Kp = tan^2(45 + phi'/2)
    phi = 2 * math.degrees(math.atan(math.sqrt(kp))) - 90
    c = beta[0] / (2 * math.sqrt(kp))
    phib = math.degrees(math.atan(beta[2] / (2 * math.sqrt(kp))))
    p = fit.params
    # two least-squares solvers on the same 15 x 3 problem: agreement to 1e-9 relative
    assert_allclose(p["phi_eff_deg"].value, phi, rtol=1e-9)
    assert_allclose(p["c_eff_kPa"].value, c / 1e3, rtol=1e-9)
    assert_allclose(p["phi_b_deg"].value, phib, rtol=1e-9)
    assert_allclose(fit.rss, rss[0], rtol=1e-9)
    # the standard errors of the coefficients are those of OLS: s^2 (X'X)^-1
    s2 = rss[0] / (15 - 3)
    assert_allclose(fit.covariance, s2 * np.linalg.inv(X.T @ X), rtol=1e-8)


def test_params_summary_and_correlation():
    x, s, y = _states(np.random.default_rng(5), noise=5e3)
    fit = fit_extended_mc(x, s, y)
    p = fit.params
    assert set(p) == {"c_eff_kPa", "phi_eff_deg", "phi_b_deg", "tan_phi_b"}
    assert p["phi_eff_deg"].ci95[0] < p["phi_eff_deg"].value < p["phi_eff_deg"].ci95[1]
    assert all(-1 <= r <= 1 for r in p.correlation.values())
    text = fit.summary()
    assert "c_eff_kPa" in text and "phi_b_deg" in text and "AICc" in text


def test_too_few_or_degenerate_states_are_clear_errors():
    with pytest.raises(FitError, match="at least 4"):
        fit_extended_mc([1, 2, 3], [1, 2, 3], [1, 2, 3])
    with pytest.raises(FitError, match="suction"):
        fit_extended_mc([1e3, 2e3, 3e3, 4e3], [5e3] * 4, [3e3, 5e3, 7e3, 9e3])


def test_either_is_at_least_as_wide_as_each_model():
    # the default error model: the OLS plane, every interval at least as wide as the constant and the proportional
    # model's (the Loewner maximum of their covariances; a new test's variance the larger of theirs)
    rng = np.random.default_rng(3)
    a, b, d = coefficients("compression", 10e3, 30.0, math.tan(math.radians(18)))
    x, s = rng.uniform(20e3, 400e3, 12), rng.uniform(20e3, 400e3, 12)
    mu = a + b * x + d * s
    y = mu + rng.normal(size=12) * 0.06 * mu
    either = fit_extended_mc(x, s, y, "compression", "either")
    const = fit_extended_mc(x, s, y, "compression", "constant")
    prop = fit_extended_mc(x, s, y, "compression", "proportional")
    assert either.errors == "either"
    np.testing.assert_allclose(either.coef, const.coef, rtol=1e-12)  # the same least-squares plane
    x0, s0 = np.array([30e3, 200e3, 390e3]), np.array([50e3, 200e3, 350e3])
    w = np.diff(np.array(either.prediction_interval(x0, s0)), axis=0)
    for other in (const, prop):
        # prop's own interval is centred on its own (weighted) plane: compare half-widths, 1e-9 for rounding
        assert np.all(w >= np.diff(np.array(other.prediction_interval(x0, s0)), axis=0) * (1 - 1e-9))
    for name in ("c_eff_kPa", "phi_b_deg"):
        assert either.params[name].stderr >= const.params[name].stderr * (1 - 1e-9)


def _coverage(errors, noise, reps, seed=1):
    """Coverage of 95 % intervals of c', phi', phi_b and of a new test's q_f per third of the net-stress range.

    6-20 tests per material, sigma3 and s uniform in 20-400 kPa, c' = 10 kPa, phi' = 30, phi_b = 18 deg;
    noise "prop": sd = 6 % of q; "const": sd = 15 kPa.
    """
    rng = np.random.default_rng(seed)
    a, b, d = coefficients("compression", 10e3, 30.0, math.tan(math.radians(18)))
    hits, newc, newn, ok = np.zeros(3), np.zeros(3), np.zeros(3), 0
    for _ in range(reps):
        n = rng.integers(6, 21)
        x, s = rng.uniform(20e3, 400e3, n), rng.uniform(20e3, 400e3, n)
        mu = a + b * x + d * s
        y = mu + rng.normal(size=n) * (0.06 * mu if noise == "prop" else 15e3)
        p = fit_extended_mc(x, s, y, "compression", errors).params
        ok += 1
        for k, (name, true) in enumerate((("c_eff_kPa", 10), ("phi_eff_deg", 30), ("phi_b_deg", 18))):
            hits[k] += p[name].ci95[0] <= true <= p[name].ci95[1]
        fit = fit_extended_mc(x, s, y, "compression", errors)
        x0, s0 = rng.uniform(20e3, 400e3, 30), rng.uniform(20e3, 400e3, 30)
        mu0 = a + b * x0 + d * s0
        y0 = mu0 + rng.normal(size=30) * (0.06 * mu0 if noise == "prop" else 15e3)
        lo, hi = fit.prediction_interval(x0, s0)
        third = np.minimum(((x0 - 20e3) / (380e3 / 3)).astype(int), 2)
        for k in range(3):
            newn[k] += np.sum(third == k)
            newc[k] += np.sum(((lo <= y0) & (y0 <= hi))[third == k])
    return hits / ok, newc / newn


@pytest.mark.slow
@pytest.mark.parametrize(
    "errors, noise",
    [("proportional", "prop"), ("constant", "const"), ("either", "prop"), ("either", "const")],
)
def test_interval_coverage_by_simulation(errors, noise):
    # 1000 materials (and 30,000 new tests): the binomial SE of a 95 % coverage is 0.7 % (0.2 % for new tests);
    # issue 40 asks >= 93 % for each interval and each third of the stress range (measured: 94-95 % for the
    # matching model; 94.7-98.4 % for the default "either" under both kinds of scatter)
    params, new = _coverage(errors, noise, 1000)
    assert np.all(params >= 0.93), params
    assert np.all(new >= 0.93), new


def test_fit_displays_its_report_in_a_notebook():
    x, s = np.array([50e3, 100e3, 200e3, 300e3, 100e3]), np.array([0.0, 100e3, 50e3, 200e3, 300e3])
    y = 20e3 + 2.0 * x + 0.5 * s + np.array([1e3, -2e3, 1.5e3, -0.5e3, 0.7e3])
    fit = fit_extended_mc(x, s, y)
    page = fit._repr_html_()
    assert page.startswith("<pre>") and "c_eff_kPa" in page and "phi_b_deg" in page and "&#x27;" in page
