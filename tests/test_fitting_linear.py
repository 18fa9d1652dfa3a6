import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.errors import FitError
from capred.fitting.linear import fit_line, fit_line_origin, t_quantile

# NIST StRD "Norris" (linear least squares, lower difficulty); certified values to 15 digits.
NORRIS_Y = [
    0.1,
    338.8,
    118.1,
    888.0,
    9.2,
    228.1,
    668.5,
    998.5,
    449.1,
    778.9,
    559.2,
    0.3,
    0.1,
    778.1,
    668.8,
    339.3,
    448.9,
    10.8,
    557.7,
    228.3,
    998.0,
    888.8,
    119.6,
    0.3,
    0.6,
    557.6,
    339.3,
    888.0,
    998.5,
    778.9,
    10.2,
    117.6,
    228.9,
    668.4,
    449.2,
    0.2,
]
NORRIS_X = [
    0.2,
    337.4,
    118.2,
    884.6,
    10.1,
    226.5,
    666.3,
    996.3,
    448.6,
    777.0,
    558.2,
    0.4,
    0.6,
    775.5,
    666.9,
    338.0,
    447.5,
    11.6,
    556.0,
    228.1,
    995.8,
    887.6,
    120.2,
    0.3,
    0.3,
    556.8,
    339.1,
    887.2,
    999.0,
    779.0,
    11.1,
    118.3,
    229.2,
    669.1,
    448.9,
    0.5,
]


def test_fit_line_nist_norris_certified():
    f = fit_line(NORRIS_X, NORRIS_Y)
    # two-pass centred formulas keep ~12 significant digits on Norris; NIST asks for >= 9
    assert_allclose(f.intercept, -0.262323073774029, rtol=1e-10)
    assert_allclose(f.slope, 1.00211681802045, rtol=1e-12)
    assert_allclose(f.intercept_se, 0.232818234301152, rtol=1e-10)
    assert_allclose(f.slope_se, 0.429796848199937e-3, rtol=1e-10)
    assert_allclose(f.rss, 26.6173985294224, rtol=1e-10)
    assert_allclose(f.r2, 0.999993745883712, rtol=1e-12)
    assert f.n == 36 and f.dof == 34


def test_fit_line_textbook_by_hand():
    # x = 1..5, y = 2,4,5,4,5: Sxx = 10, Sxy = 6 -> slope 0.6, intercept 2.2,
    # RSS = 2.4, s^2 = 0.8, se(b) = sqrt(0.08), se(a) = sqrt(0.8 (1/5 + 9/10)), R^2 = 1 - 2.4/6
    f = fit_line([1, 2, 3, 4, 5], [2, 4, 5, 4, 5])
    assert_allclose([f.intercept, f.slope], [2.2, 0.6], rtol=1e-13)
    assert_allclose(f.slope_se, np.sqrt(0.08), rtol=1e-13)
    assert_allclose(f.intercept_se, np.sqrt(0.88), rtol=1e-13)
    assert_allclose(f.r2, 0.6, rtol=1e-13)
    # t(0.975, 3) = 3.182446 (standard t table)
    assert_allclose(f.t, 3.182446, rtol=1e-6)
    lo, hi = f.slope_ci
    assert_allclose(hi - 0.6, 3.182446 * np.sqrt(0.08), rtol=1e-6)


def test_fit_line_exact_thesis_envelope():
    # Evenepoel (VUB thesis), dry tests: steel spheres c = 0.3452 kPa, tan phi = 0.7146
    s = np.array([0.3, 0.6, 1.2, 2.4])
    f = fit_line(s, 0.3452 + 0.7146 * s)
    assert_allclose([f.intercept, f.slope], [0.3452, 0.7146], rtol=1e-12)
    assert f.slope_se < 1e-12 and f.r2 == pytest.approx(1.0)


def test_fit_line_rejects_too_few_or_degenerate():
    with pytest.raises(FitError, match="at least 3"):
        fit_line([1, 2], [1, 2])
    with pytest.raises(FitError, match="same abscissa"):
        fit_line([1, 1, 1], [1, 2, 3])
    with pytest.raises(FitError, match="NaN"):
        fit_line([1, 2, np.nan], [1, 2, 3])


def test_prediction_interval_and_unscaled_covariance_by_hand():
    # x = 1..5, y = 2,4,5,4,5 (above): s^2 = 0.8, xbar = 3, Sxx = 10. (X^T X)^-1 = [[1/5 + 9/10, -3/10],
    # [-3/10, 1/10]]. At x = 3 the mean has variance s^2/n = 0.16; a new point adds s^2: 0.96.
    f = fit_line([1, 2, 3, 4, 5], [2, 4, 5, 4, 5])
    assert_allclose(f.unscaled_covariance, [[1.1, -0.3], [-0.3, 0.1]], rtol=1e-13)
    lo, hi = f.prediction_interval(3.0)
    assert_allclose([lo, hi], [4.0 - 3.182446 * np.sqrt(0.96), 4.0 + 3.182446 * np.sqrt(0.96)], rtol=1e-6)
    mlo, mhi = f.mean_band(3.0)
    assert_allclose(mhi - 4.0, 3.182446 * np.sqrt(0.16), rtol=1e-6)  # t table to 7 digits
    # through the origin: (X^T X)^-1 = 1/sum x^2 = 1/14 for x = 1, 2, 3
    g = fit_line_origin([1, 2, 3], [1.1, 1.9, 3.0])
    assert_allclose(g.unscaled_covariance, [[0, 0], [0, 1 / 14]], rtol=1e-13)


def test_t_quantile_vectorised():
    # t table: t(0.975, 3) = 3.182446, t(0.975, 10) = 2.228139; dof <= 0 has no quantile
    assert_allclose(t_quantile(0.975, np.array([3, 10])), [3.182446, 2.228139], rtol=1e-6)
    assert np.isnan(t_quantile(0.975, 0)) and isinstance(t_quantile(0.975, 3), float)


def test_prediction_interval_covers_new_points():
    """400 lines of 6 points (noise SD 1): a new point at x = 5 falls inside the 95 % prediction interval
    95 % +/- 3 binomial SDs (1.09 %) of the time; the mean band holds it far less often."""
    rng = np.random.default_rng(4)
    x = np.array([1.0, 2, 3, 1, 2, 3])
    hit = hit_mean = 0
    for _ in range(400):
        f = fit_line(x, 1.0 + 0.5 * x + rng.normal(0, 1, 6))
        new = 1.0 + 0.5 * 5 + rng.normal(0, 1)
        lo, hi = f.prediction_interval(5.0)
        mlo, mhi = f.mean_band(5.0)
        hit += lo <= new <= hi
        hit_mean += mlo <= new <= mhi
    sd = np.sqrt(0.95 * 0.05 / 400)
    assert abs(hit / 400 - 0.95) <= 3 * sd
    assert hit_mean / 400 < 0.95 - 3 * sd


def test_t_quantile_closed_forms_by_hand():
    """nu = 1: t = tan(pi (p - 1/2)) (Cauchy); nu = 2: P(|T| <= t) = t / sqrt(2 + t^2), so t = sqrt(2) a /
    sqrt(1 - a^2) with a = 2p - 1 (Abramowitz & Stegun 1964, eq. 26.7.3-26.7.4). 2e-14 relative: a few ulp of
    theta times tan's condition number near pi/2, 1/(pi/2 - theta) = 64 at p = 0.995."""
    for p in (0.6, 0.9, 0.975, 0.995):
        a = 2 * p - 1
        assert_allclose(t_quantile(p, 1), np.tan(np.pi * (p - 0.5)), rtol=2e-14)
        assert_allclose(t_quantile(p, 2), np.sqrt(2) * a / np.sqrt(1 - a * a), rtol=2e-14)
        assert_allclose(t_quantile(1 - p, 2), -np.sqrt(2) * a / np.sqrt(1 - a * a), rtol=2e-14)
    assert t_quantile(0.5, 7) == 0.0


def test_t_quantile_matches_cephes_for_every_whole_dof_and_scipy_beyond():
    """Against scipy.special.stdtrit (Cephes) for nu = 1..260 (the closed form up to 200, scipy above) and
    levels from 0.51 to 0.9999. 1e-12 relative: the closed form's worst error measured against a 40-digit
    solution was 6e-13 at p = 0.9999 (1e-15 at 0.975); intervals print 4 digits. 1e-10 across the dependency
    versions capred allows: stdtrit itself moved by 5e-11 between scipy 1.14 and 1.17, and the closed form by
    1e-11 between numpy 2.0 and 2.4 (measured on this machine)."""
    from scipy.special import stdtrit

    nu = np.arange(1, 261)
    for p in (0.51, 0.9, 0.95, 0.975, 0.995, 0.9999, 0.025):
        assert_allclose(t_quantile(p, nu), stdtrit(nu, p), rtol=1e-10)
    assert_allclose(t_quantile(0.975, 2.5), stdtrit(2.5, 0.975), rtol=1e-15)  # a fraction: scipy
    got = t_quantile(0.975, np.array([3, 0, -1, np.nan, 3]))
    assert_allclose(got[[0, 4]], stdtrit(3, 0.975), rtol=1e-10) and np.isnan(got[1:4]).all()
    assert isinstance(t_quantile(0.975, 5), float) and isinstance(t_quantile(0.975, np.int64(5)), float)


def test_shear_run_does_not_import_scipy_special():
    """The everyday run's t quantiles do not pay for importing scipy.special (~0.25 s of every command)."""
    import subprocess
    import sys

    code = (
        "import sys, capred; capred.run_shear(capred.sample_path('shear'), capred.ShearOptions(bootstrap=200));"
        "print('scipy.special' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
