"""Exact capillary bridges (issue 3): accuracy against an independent Young-Laplace integration,
limits, consistency, approximations, and the `capred bridge` commands."""

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.physics import bridge as br

runner = CliRunner()


def ode_reference(beta, theta, s):
    """Independent reference: integrate the Young-Laplace ODE in arc length from the contact line
    to the neck (psi = 0) with DOP853 at rtol 1e-12. Units of R and gamma.

    d psi/d sigma = -(s + cos psi / y), dx/d sigma = -cos psi, dy/d sigma = -sin psi (walking to the neck).
    Returns (half-length L, volume under the meridian, neck radius, psi at the end).
    """

    def rhs(_, u):
        x, y, psi, v = u
        return [-np.cos(psi), -np.sin(psi), -(s + np.cos(psi) / y), np.pi * y * y * np.cos(psi)]

    def neck(_, u):
        return u[2]

    neck.terminal, neck.direction = True, -1
    u0 = [0.0, np.sin(beta), 0.5 * np.pi - beta - theta, 0.0]
    sol = solve_ivp(rhs, (0.0, 50.0), u0, method="DOP853", rtol=1e-12, atol=1e-14, events=neck)
    x, y, psi, v = sol.y_events[0][0]
    return -x, v, y, psi


GRID = [(th, s, f) for th in (0.0, 20.0, 40.0, 60.0) for s in (0.3, 3.0, 30.0, 300.0) for f in (0.1, 0.4, 0.7, 0.95)]


@pytest.mark.parametrize("theta_deg,s,frac", GRID)
def test_bridge_matches_independent_young_laplace_integration(theta_deg, s, frac):
    th = np.radians(theta_deg)
    beta = frac * (0.5 * np.pi - th)
    gap, vol, force, neck = (float(x) for x in br.geometry(beta, th, s))
    L, v_under, y0, _ = ode_reference(beta, th, s)
    h = 1 - np.cos(beta)
    vol_ref = 2 * (v_under - np.pi * h * h * (3 - h) / 3)
    f_neck = 2 * y0 + s * y0 * y0  # force through the neck, from the ODE
    # relative 1e-6 asked; quadrature and DOP853 agree far better on this grid
    assert_allclose(gap / 2 + 1 - np.cos(beta), L, rtol=1e-6)
    assert_allclose(vol, vol_ref, rtol=1e-6, atol=1e-15)
    assert_allclose(force, f_neck, rtol=1e-6)
    assert_allclose(neck, y0, rtol=1e-6)
    assert abs(gap - 2 * (L + np.cos(beta) - 1)) < 2e-6


def test_force_balance_neck_equals_contact_line():
    # F at the neck (2 pi r0 gamma + pi r0^2 du) equals F at the contact line
    # (2 pi R gamma sin b sin(b + theta) + pi R^2 du sin^2 b): the first integral, checked on the ODE
    for th, s, b in ((0.0, 5.0, 0.3), (0.5, 50.0, 0.2), (0.9, 0.5, 0.4)):
        _, _, y0, _ = ode_reference(b, th, s)
        assert_allclose(2 * y0 + s * y0**2, 2 * np.sin(b) * np.sin(b + th) + s * np.sin(b) ** 2, rtol=1e-9)


@pytest.mark.parametrize("theta_deg", [0.0, 30.0, 60.0])
def test_israelachvili_limit_at_contact(theta_deg):
    th = np.radians(theta_deg)
    vols = np.array([1e-4, 1e-6, 1e-8, 1e-10])
    b, s, st = br.solve_for_volume(th, vols, 0.0)
    ratio = br.geometry(b, th, s)[2] * np.pi / br.israelachvili_force(1.0, 1.0, th)
    assert np.all(st == 0) and np.all(np.diff(ratio) > 0)  # approaches from below as V -> 0
    assert abs(ratio[-1] - 1) < 5e-3


def test_suction_and_volume_solvers_agree():
    th = np.radians([0.0, 15.0, 35.0, 50.0])
    s = np.array([2.0, 20.0, 200.0, 8.0])
    D = np.array([0.0, 0.01, 0.002, 0.05])
    b, st = br.solve_for_suction(th, s, D)
    assert np.all(st == 0)
    gap, vol, F, _ = br.geometry(b, th, s)
    assert_allclose(gap, D, atol=1e-12)
    b2, s2, st2 = br.solve_for_volume(th, vol, D)
    assert np.all(st2 == 0)
    assert_allclose(b2, b, rtol=1e-9)
    assert_allclose(s2, s, rtol=1e-7)


def test_stable_branch_is_continuous_and_ends_at_rupture():
    gaps = np.linspace(0.0, 0.3, 301)
    b, st = br.solve_for_suction(0.2, 5.0, gaps)
    ok = st == 0
    assert ok[0] and not ok[-1]  # a bridge at contact, none far away
    last = np.flatnonzero(ok)[-1]
    assert np.all(ok[: last + 1])  # one connected range up to the rupture gap
    assert np.max(np.abs(np.diff(b[: last + 1]))) < 0.05  # no jump between neighbouring gaps
    assert np.all(np.diff(b[: last + 1]) < 0)  # filling angle shrinks as the spheres separate


def test_bridge_is_symmetric_neck_to_both_spheres():
    # integrate outward from the neck with the quadrature's r0: the meridian meets the sphere whose
    # centre sits at x = L + cos(beta) at the right contact angle (mirror image of the first sphere)
    th, s, beta = 0.3, 4.0, 0.5
    gap, _, _, y0 = (float(x) for x in br.geometry(beta, th, s))
    xc = gap / 2 + 1.0

    def rhs(_, u):
        return [np.cos(u[2]), np.sin(u[2]), s + np.cos(u[2]) / u[1]]

    def hit(_, u):
        return np.hypot(u[0] - xc, u[1]) - 1.0

    hit.terminal = True
    sol = solve_ivp(rhs, (0, 10), [0.0, y0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, events=hit)
    x, y, psi = sol.y_events[0][0]
    b_hit = np.arctan2(y, xc - x)
    assert_allclose(b_hit, beta, rtol=1e-7)
    assert_allclose(psi, 0.5 * np.pi - beta - th, rtol=1e-7)


def test_toroidal_within_few_percent_at_small_volume():
    for th in (0.0, np.radians(30)):
        b, s, _ = br.solve_for_volume(th, np.array([1e-5, 1e-4, 1e-3]), 0.0)
        exact = br.geometry(b, th, s)[2]
        tor = br.toroidal(b, th, 0.0)[2]
        assert np.all(np.abs(tor / exact - 1) < 0.03)  # the circle approximation's known few-percent error


def test_no_bridge_cases_are_reported_not_raised():
    b, st = br.solve_for_suction(0.0, 2.0, [0.5, 0.0])
    assert list(st) == [1, 0] and np.isnan(b[0])
    b, s, st = br.solve_for_volume(0.0, [2.0, 1e-3, 1e-9], [0.0, 0.0, 0.2])
    assert list(st) == [3, 0, 1]


def test_solve_command_json(tmp_path):
    res = runner.invoke(app, ["bridge", "solve", "--sample", "--json", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.stdout)["bridges"]
    keys = {"r0_mm", "F_cap_mN", "F_L_mN", "F_T_mN", "V_w_mm3", "filling_angle_deg", "S_R", "sigma_prime_kPa", "status"}
    assert all(keys <= set(r) for r in rows)
    first = rows[0]  # steel spheres in contact at 1 kPa
    assert first["status"] == "ok"
    assert first["F_cap_mN"] == pytest.approx(first["F_L_mN"] + first["F_T_mN"], rel=1e-9)
    # unit cell (Evenepoel, VUB thesis): S_R = 3 V/(2 pi R^3), sigma' = F/(pi R^2) with R = 1 mm
    assert first["S_R"] == pytest.approx(3 * first["V_w_mm3"] / (2 * np.pi), rel=1e-9)
    assert first["sigma_prime_kPa"] == pytest.approx(first["F_cap_mN"] / np.pi, rel=1e-9)  # mN/mm^2 = kPa
    assert [r["status"] for r in rows[-2:]] == ["no bridge: beyond rupture", "no concave bridge: too much water"]


def test_compare_command(tmp_path):
    res = runner.invoke(app, ["bridge", "compare", "--sample", "--json", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.stdout)["comparison"]
    rel = [abs(r["residual_exact_mN"]) / r["F_measured_mN"] for r in rows]
    assert max(rel) < 0.12  # synthetic tests carry 3 % noise on the exact force
    assert (tmp_path / "compare.png").exists()


def test_curve_command_redraws_thesis_comparison(tmp_path):
    res = runner.invoke(app, ["bridge", "curve", "--points", "300", "--json", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    err = js["rms_relative_error_vs_exact"]
    # thesis conclusion: Own 2 follows the exact bridge, Bishop (S_R du) is far below it
    assert err["outside"]["own2"] < 0.15 and err["outside"]["bishop"] > 0.5
    assert err["inside"]["own2"] < err["inside"]["own1"] < err["inside"]["bishop"]
    assert (tmp_path / "curve.png").exists()
    assert capred.bridge_curve(points=300).to_json()["curve"] == js["curve"]


BAD = {
    "negative_radius": ("R,theta,gap,suction\n-1,0,0,1\n", ["line 2", "column 'R'", "must be > 0"]),
    "theta_90": ("R,theta,gap,suction\n1,95,0,1\n", ["line 2", "column 'theta'", "below 90 deg"]),
    "negative_gap": ("R,theta,gap,suction\n1,0,-0.1,1\n", ["line 2", "column 'gap'", "negative"]),
    "missing_column": ("R,theta,suction\n1,0,1\n", ["missing column 'gap'"]),
    "unknown_unit": ("R [furlongz],theta,gap,suction\n1,0,0,1\n", ["unknown unit 'furlongz'"]),
    "both_inputs": ("R,theta,gap,suction,V_w\n1,0,0,1,0.1\n", ["not both"]),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bridge_bad_input(case, write_csv, tmp_path):
    text, expected = BAD[case]
    data = write_csv(text, "bad.csv")
    res = runner.invoke(app, ["bridge", "solve", str(data), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "Traceback" not in res.stderr
    for piece in expected:
        assert piece in res.stderr, (piece, res.stderr)
    assert not (tmp_path / "o").exists()


def test_volume_controlled_scan_never_reports_a_wrong_bridge():
    """Issue 13: theta in {0, 1, 5, 15, 30, 60} deg, gaps from contact to 0.2 R, volumes over six decades:
    every bridge reported ok reproduces its gap and volume when its geometry is computed forward."""
    from capred.physics import bridge as br

    th, D, V = np.meshgrid(
        np.radians([0, 1, 5, 15, 30, 60]),
        np.r_[0.0, np.geomspace(1e-3, 0.2, 8)],
        np.geomspace(1e-6, 1.0, 13),
        indexing="ij",
    )
    th, D, V = th.ravel(), D.ravel(), V.ravel()
    beta, s, status = br.solve_for_volume(th, V, D)
    ok = status == 0
    assert ok.sum() > 0.4 * ok.size  # most of the scan has a bridge
    g, v, _, _ = br.geometry(beta[ok], th[ok], s[ok])
    # forward: the reported bridge holds the requested volume at the requested gap (1e-9, the verify tolerance;
    # gaps below 1e-3 R are held to 1e-12 R absolute)
    assert np.all(np.abs(g - D[ok]) <= 1e-9 * np.maximum(D[ok], 1e-3))
    assert np.all(np.abs(v - V[ok]) <= 1e-9 * V[ok])
    assert set(np.unique(status)) <= {0, 1, 3, 4}


def test_issue_examples_are_never_wrong(tmp_path):
    (tmp_path / "b.csv").write_text(
        "R,contact_angle,gap,V_w\n1,0,0.2,0.008\n1,0,0.2,0.01\n1,0,0.01,1e-5\n1,0,0.01,2.264e-6\n"
    )
    res = capred.solve_bridges(tmp_path / "b.csv")
    for row, (gap, vol) in zip(res.rows(), ((0.2, 0.008), (0.2, 0.01), (0.01, 1e-5), (0.01, 2.264e-6))):
        if row["status"] == "ok":  # a bridge reported is the bridge asked for
            assert row["V_w_mm3"] == pytest.approx(vol, rel=1e-9)
        else:
            assert row["V_w_mm3"] is None


def test_volume_newton_path_matches_the_scan_of_the_arc():
    """The fast Newton path of the volume solver returns the bridge of the scan of the arc (its fallback) and the
    bridge a suction-controlled solve built: same suction, same filling angle."""
    rng = np.random.default_rng(11)
    n = 160
    th = np.radians(rng.uniform(0, 60, n))
    s = 10 ** rng.uniform(-1, 2.5, n)
    rho = np.where(
        rng.uniform(size=n) < 0.5, 1.0, np.where(rng.uniform(size=n) < 0.3, np.inf, 10 ** rng.uniform(-0.5, 1, n))
    )
    b0 = rng.uniform(0.05, 0.9, n) * (np.pi / 2 - th)
    D = np.where(np.arange(n) % 2 == 0, 0.0, np.clip(br.gap_of(b0, th, s, rho), 0, None) * rng.uniform(0.2, 1, n))
    b, st = br.solve_for_suction(th, s, D, rho)
    ok = st == 0
    th, s, rho, D, b = th[ok], s[ok], rho[ok], D[ok], b[ok]
    V = br.bridge(b, th, s, rho).volume
    y0, s_newton, found = br._newton_volume(th, V, D, rho, th)
    assert found.mean() > 0.97  # the rest (huge bridges) go through the continuation or the scan
    b_scan, s_scan, st_scan = br._scan_for_volume(th[found], V[found], D[found], rho[found], th[found])
    assert np.all(st_scan == 0)
    # both stop on gap and volume residuals of 1e-12 relative; the suction follows through a conditioning of
    # at most ~1e4 (near the fold): 1e-7
    assert_allclose(s_newton[found], s_scan, rtol=1e-7)
    assert_allclose(s_newton[found], s[found], rtol=1e-7)
    b_new, s_new, st_new = br.solve_for_volume(th, V, D, rho)
    assert np.all(st_new == 0)
    assert_allclose(b_new, b, rtol=1e-9)  # the filling angle is well conditioned: 1e-9, the verify tolerance


@pytest.mark.parametrize(
    "gap,s,past_minimum",
    [(0.1, 0.01, True), (0.1, 0.1, True), (0.1, 0.5, True), (0.1, 2.0, False), (0.3, 0.1, False), (0.3, 0.5, False)],
)
def test_volume_newton_certifies_only_the_branch_continuous_with_contact(gap, s, past_minimum):
    """Equal spheres, theta = 0. The thin bridge of a suction-controlled pair (smaller filling angle) lies on the
    arc of its gap either before the volume minimum (past the suction fold: the bridge at constant volume) or
    after it, where a thicker bridge of the arc holds the same volume and is the one continuous with contact.
    A Newton iteration started on the thin bridge converges to it; the branch certificate (the volume along
    the arc must rise with the neck) accepts it exactly when the scan of the arc returns it too."""
    from scipy.optimize import brentq

    th, rho = 0.0, 1.0
    grid = np.linspace(0.001, 1.5, 3000)
    g = br.gap_of(grid, th, s, rho)
    j = int(np.nanargmax(g))
    b_thin = brentq(lambda x: float(br.gap_of(x, th, s, rho)) - gap, grid[0], grid[j], xtol=1e-15)
    thin = br.bridge(b_thin, th, s, rho)
    V = np.atleast_1d(thin.volume)
    y0, _, found = br._newton_volume(
        np.array([th]),
        V,
        np.array([gap]),
        np.array([rho]),
        np.array([th]),
        start=(np.atleast_1d(thin.neck), np.array([s])),
    )
    assert y0[0] == pytest.approx(float(thin.neck), rel=1e-9)  # converged to the thin bridge (1e-12 residuals)
    assert found[0] == (not past_minimum)
    b_scan, s_scan, st_scan = br._scan_for_volume(np.array([th]), V, np.array([gap]), np.array([rho]), np.array([th]))
    b, s_v, st = br.solve_for_volume(th, V, gap, rho)
    assert st[0] == st_scan[0] == 0
    assert_allclose(s_v, s_scan, rtol=1e-7)  # same bridge as the scan (see the test above for 1e-7)
    neck = float(br.bridge(b, th, s_v, rho).neck[0])
    if past_minimum:
        assert neck > 1.2 * float(thin.neck)  # the thicker bridge (37 % or more here)
    else:
        assert neck == pytest.approx(float(thin.neck), rel=1e-9)
