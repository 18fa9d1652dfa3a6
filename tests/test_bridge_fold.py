"""Issue 20: the bulk verdicts of the suction-controlled solver (no bridge beyond rupture, too much water, a
bridge) against an independent brute-force search of the rupture gap, row by row."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.physics import bridge as br


def brute_rupture_gap(theta, s, rho):
    """The largest gap* of any concave bridge at suction s* (the rupture gap at that suction), per row: gap*(beta)
    on 2,000 filling angles from 1e-6 of the last concave bridge to it, the best refined by 60 golden sections
    with the full quadrature; and the gap* of the last concave bridge. Independent of the solver's grid, scan and
    thresholds (each row on its own grid, computed for all rows at once)."""
    b_end = 0.5 * (np.pi - np.arctan2(np.sin(theta), np.cos(theta) + 0.5 * s))
    b = b_end[:, None] * np.geomspace(1e-6, 1.0, 2000)
    g = br._below(br.gap_of(b, theta[:, None], s[:, None], rho[:, None]))
    r = np.arange(theta.size)
    j = np.argmax(g, axis=1)
    _, best = br.golden(
        lambda x, i: br.gap_of(x, theta[i], s[i], rho[i]),
        b[r, np.maximum(j - 1, 0)],
        b[r, np.minimum(j + 1, b.shape[1] - 1)],
        iters=60,
    )
    return np.fmax(best, g[r, j]), g[:, -1]


def random_rows(n, seed):
    """Rows whose gap lies within 10 % of the rupture gap at their suction (where the fold check decides):
    theta 0-70 deg, s* 1e-2-1e3, equal spheres, unequal ones (R2/R 0.1-10) and planes."""
    rng = np.random.default_rng(seed)
    th = np.radians(rng.uniform(0.0, 70.0, n))
    s = 10 ** rng.uniform(-2.0, 3.0, n)
    u = rng.uniform(size=n)
    rho = np.where(u < 0.4, 1.0, np.where(u < 0.6, np.inf, 10 ** rng.uniform(-1.0, 1.0, n)))
    peak, at_end = brute_rupture_gap(th, s, rho)
    D = peak * rng.uniform(0.9, 1.1, n)
    return th, s, rho, D, peak, at_end


@pytest.mark.parametrize("seed", [0, 1])
def test_bulk_verdicts_match_a_brute_force_search_row_by_row(seed):
    th, s, rho, D, peak, at_end = random_rows(300, seed)
    beta, status = br.solve_for_suction(th, s, D, rho)
    # the rupture gap is known to about 1e-9 relative from 60 golden steps on the 3,000-point grid; rows
    # within 1e-6 of it may fall either way and are left out
    clear = np.abs(D / peak - 1) > 1e-6
    beyond = clear & (D > peak)
    within = clear & (D < peak) & (at_end < D)  # a bridge, and not too much water at the last concave one
    assert beyond.sum() > 50 and within.sum() > 50  # both verdicts are exercised
    assert np.all(status[beyond] == 1)  # every "beyond rupture" is true, and every true one is found
    assert np.all(status[within] == 0)
    # every bridge reproduces its gap (VERIFY_RTOL, 1e-12 absolute near contact) and is the stable one: a
    # slightly larger filling angle gives a smaller gap
    ok = status == 0
    g = br.gap_of(beta[ok], th[ok], s[ok], rho[ok])
    assert np.all(np.abs(g - D[ok]) <= 1e-9 * np.maximum(D[ok], 1e-3))
    assert np.all(br.gap_of(beta[ok] * (1 + 1e-6), th[ok], s[ok], rho[ok]) < D[ok] + 1e-12)


def test_bulk_verdicts_match_row_by_row_calls():
    # the same rows solved at once and one at a time: the scan settles rows independently of their neighbours
    th, s, rho, D, _, _ = random_rows(60, 2)
    beta, status = br.solve_for_suction(th, s, D, rho)
    one = [br.solve_for_suction(*row) for row in zip(th, s, D, rho)]
    assert np.array_equal(status, [st[0] for _, st in one])
    ok = status == 0
    # equal up to the root finder's stopping point (|gap - D| <= 1e-12 D): filling angles to 1e-9
    assert_allclose(beta[ok], np.array([b[0] for b, _ in one])[ok], rtol=1e-9)


def test_bridge_at_suction_verifies_on_its_own_fields():
    th, s, rho, D, _, _ = random_rows(40, 3)
    beta, status, b = br.bridge_at_suction(th, s, D, rho)
    beta2, status2 = br.solve_for_suction(th, s, D, rho)
    assert np.array_equal(status, status2)
    ok = status == 0
    assert_allclose(beta[ok], beta2[ok], rtol=0)  # the same solver underneath, the same filling angles
    assert np.all(np.abs(b.gap[ok] - D[ok]) <= 1e-9 * np.maximum(D[ok], 1e-3))
    assert np.all(np.isnan(b.force[~ok])) and np.all(np.isnan(beta[~ok]))


def test_bulk_no_bridge_of_volume_rows_agrees_with_the_scan_of_the_arc():
    # volume-controlled rows around their rupture distance (Lian et al. 1993: about (1 + theta/2) V^(1/3)), equal
    # spheres, unequal ones and planes: every row the bulk check settles as beyond rupture is beyond rupture
    # for the scan of the arc too (the row-by-row fallback of the volume solver), and most far rows are settled
    rng = np.random.default_rng(11)
    n = 200
    th = np.radians(rng.uniform(0.0, 70.0, n))
    V = 10 ** rng.uniform(-9.0, -1.0, n)
    u = rng.uniform(size=n)
    rho = np.where(u < 0.4, 1.0, np.where(u < 0.6, np.inf, 10 ** rng.uniform(-1.0, 1.0, n)))
    D = br.lian_rupture_gap(th, V) * rng.uniform(0.5, 3.0, n)
    far = br._beyond_rupture(th, V, D, rho, th)
    _, _, st_scan = br._scan_for_volume(th, V, D, rho, th)
    assert np.all(st_scan[far] == 1)
    assert far.sum() > 0.5 * np.sum(D > 2 * br.lian_rupture_gap(th, V))  # the bulk check does settle rows
    # and the solver's verdicts are the scan's wherever either finds no bridge
    _, _, st = br.solve_for_volume(th, V, D, rho)
    none = (st != 0) | (st_scan != 0)
    assert np.array_equal(st[none], st_scan[none])
