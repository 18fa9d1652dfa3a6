"""The search inside `capred retention` fits (issue 20): the vectorised pieces equal their plain definitions,
and the large-data shortcuts still end at the optimum.

Every start-grid value, every batched residual and every mixture pair is computed from moments or in stacks of
rows; these tests rebuild each from its definition (one curve at a time, the sum of squares written out).
"""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.fitting import retention_models as rm
from capred.physics import retention as rp

CM = 98.1  # Pa per cm of water (gamma_w = 9.81 kN/m^3)


def _problem(name, s, y, fixed=None, weights=None):
    fixed = fixed or {}
    sw = np.ones_like(y) if weights is None else np.sqrt(weights)
    return rm._Problem(rm.MODELS[name], s, y, sw, fixed, rm.bounds_for(s, y, name))


def _vg_curves(s):
    """Five van Genuchten curves, two of them far from the data (their unbounded θ_r < 0 or θ_s > 1)."""
    alpha = np.array([1 / 2000, 1 / 300, 1 / 50000, 1 / 5000, 1e-6])[:, None]
    n = np.array([2.0, 4.0, 1.3, 1.1, 6.0])[:, None]
    return rp.vg_effective_saturation(s[None, :], alpha, n)


def _data(seed=0, size=25):
    rng = np.random.default_rng(seed)
    s = np.geomspace(100, 1e6, size)
    return s, rp.vg_water(s, 0.05, 0.40, 1 / 4000, 2.2) + rng.normal(0, 0.004, size)


@pytest.mark.parametrize("fixed", [{}, {"y_r": 0.02}, {"y_s": 0.45}])
def test_fitted_rows_equal_the_scalar_projection(fixed):
    """Each row of the batched projection is the curve of the scalar bounded least squares of that row."""
    s, y = _data()
    w = np.linspace(0.5, 2.0, s.size)
    pb = _problem("vg", s, y, fixed, w)
    S = _vg_curves(s)
    rows = pb.fitted_rows(S)
    for i in range(S.shape[0]):
        p = {**fixed, **pb.linear(S[i])}
        assert_allclose(rows[i], p["y_r"] + (p["y_s"] - p["y_r"]) * S[i], rtol=1e-12, atol=1e-14)  # same algebra


def test_projected_rss_from_moments_equals_the_sum_of_squares():
    """The start grid's RSS from Σw S, Σw S², Σw S y equals Σ w (fitted - y)² written out (to the rounding
    of the moment formula, which subtracts sums of order n: 1e-9 relative is ~1e6 ulp of margin)."""
    s, y = _data(1)
    w = np.linspace(0.5, 2.0, s.size)
    pb = _problem("vg", s, y, weights=w)
    S = _vg_curves(s)
    wy = w * y
    rss = rm._projected_rss(pb, w.sum(), wy.sum(), wy @ y, S @ w, (S * S) @ w, S @ wy)
    direct = ((pb.fitted_rows(S) - y) ** 2 * w).sum(-1)
    assert_allclose(rss, direct, rtol=1e-9, atol=1e-15)


def test_cross_products_on_separate_axes():
    """Σ_n A B of two arrays living on different grid axes equals the broadcast product summed."""
    rng = np.random.default_rng(2)
    A = rng.random((3, 1, 4, 1, 7))
    B = rng.random((1, 5, 4, 2, 7))
    shape = (3, 5, 4, 2)
    assert_allclose(np.broadcast_to(rm._cross(A, B, shape), shape), (A * B).sum(-1), rtol=1e-13)


def test_durner_grid_pairs_equal_the_curve_of_each_pair():
    """Durner's start grid combines pairs from the components' moments; a few pairs rebuilt as curves agree:
    the weight from the unconstrained three-column fit y = c0 + c1 S1 + c2 S2 (normal equations regularised by
    1e-14 of their trace), w1 = c1/(c1 + c2) clipped, then the bounded (θ_r, θ_s)."""
    s, y = _data(3, 30)
    pb = _problem("durner", s, y)
    names, axes, rss, weights, mix = rm._screen(pb, np.arange(s.size))
    finite = np.argwhere(np.isfinite(rss))
    for pos in finite[np.linspace(0, len(finite) - 1, 12).round().astype(int)]:
        p = {k: axes[i][pos[i]] for i, k in enumerate(names)}
        S1 = rp.vg_effective_saturation(s, p["alpha1"], p["n1"])
        S2 = rp.vg_effective_saturation(s, p["alpha2"], p["n2"])
        X = np.column_stack([np.ones_like(s), S1, S2])
        A = X.T @ X
        c = np.linalg.solve(A + 1e-14 * np.trace(A) * np.eye(3), X.T @ y)  # regularised normal equations
        w1 = np.clip(c[1] / (c[1] + c[2]), 0, 1)
        if np.linalg.cond(A) < 1e8:  # else nearly collinear columns (e.g. a curve flat over the data): the
            # weight hardly changes the fit and the rounding decides it; here cond * eps <= 1e-8
            assert_allclose(weights[tuple(pos)], w1, rtol=1e-6, atol=1e-9)
        S = (weights[tuple(pos)] * S1 + (1 - weights[tuple(pos)]) * S2)[None, :]
        direct = ((pb.fitted_rows(S)[0] - y) ** 2).sum()
        assert_allclose(rss[tuple(pos)], direct, rtol=1e-8, atol=1e-14)  # moment formula, see above


def _synthetic_2000():
    """The benchmark's large set: 2,000 heads of 1-1e4 cm around a van Genuchten curve, noise 0.005."""
    rng = np.random.default_rng(1)
    h = np.geomspace(1, 1e4, 2_000)
    theta = 0.06 + 0.34 * (1 + (h / 40) ** 4) ** -0.75 + rng.normal(0, 0.005, h.size)
    return h * CM, theta


def test_brooks_corey_on_2000_points_reaches_the_interval_optimum():
    """More distinct suctions than start boxes: the air-entry suction is polished between neighbouring data
    suctions. unsatfit 5 (Seki et al. 2023) reaches RSS 0.205802 on this set, h_b 28.049 cm; the coarse boxes
    alone stopped at 0.205831 (h_b 28.13 cm, on a kink)."""
    s, y = _synthetic_2000()
    f = rm.fit_model("bc", s, y)
    assert f.rss <= 0.2058022  # unsatfit's printed RSS rounded up in its last digit
    assert_allclose(f.params_si["s_e"] / CM, 28.0495, rtol=2e-5)  # unsatfit 28.04942; both to ~1e-5
    knots = np.unique(s)
    i = np.searchsorted(knots, f.params_si["s_e"])
    assert knots[i - 1] < f.params_si["s_e"] < knots[i]  # an interior, smooth minimum


@pytest.mark.slow
@pytest.mark.parametrize("name", ["vg_m_free", "fx_no_c", "durner"])
def test_large_data_reaches_the_multistart_optimum(name):
    """On 2,000 points the first refinement runs on 100 of them; the fit still ends at the optimum of an
    independent multi-start fit on all points (the check of tests/test_retention_optimum.py)."""
    from test_retention_optimum import REL, multistart

    s, y = _synthetic_2000()
    f = rm.fit_model(name, s, y)
    assert f.rss <= multistart(name, s, y, 12) * (1 + REL)
