"""Volume-change model of Pedrotti & Tarantino (submitted), eq. 1-10: capred.physics.pedrotti_tarantino.

Reference numbers are worked by hand (each derivation in a comment). The paper
prints no fitted parameters or simulated values (its Fig. 14-17 are drawings
and plots), so the published content tested is its equations, its two limits
(S_r = 1: slurry lines; S_r = 0: dry-powder lines) and the behaviour its
section 4.2 describes for each stage of the path of Fig. 13.
"""

from math import log

import numpy as np
import pytest
from numpy.testing import assert_allclose

import capred
from capred.physics import pedrotti_tarantino as pt

kPa = 1.0e3
SAMPLE = capred.sample_path("pt-volume")  # the bundled sample, found as an installed wheel finds it (issue 32.8)

# round lines for hand arithmetic: slurry lambda 0.2, kappa 0.02, e = 2.0 at 1 kPa;
# dry powder lambda 0.1, kappa 0.01, e = 1.8 at 1 kPa
HAND = pt.PTVolumeParameters(lambda_W=0.2, kappa_W=0.02, e_ncl_W=2.0, lambda_A=0.1, kappa_A=0.01, e_ncl_A=1.8)


# --- eq. 1-2 ---------------------------------------------------------------------------------
def test_effective_stresses_by_hand():
    # sigma = 100 kPa, u_w = -50 kPa, u_a = 0, S_r = 0.6:
    # sigma'_W = (100 + 50) 0.6 = 90 kPa (eq. 1); sigma'_A = (100 - 0) 0.4 = 40 kPa (eq. 2)
    assert_allclose(pt.water_saturated_effective_stress(100 * kPa, -50 * kPa, 0.6), 90 * kPa, rtol=1e-15)
    assert_allclose(pt.air_saturated_effective_stress(100 * kPa, 0.0, 0.6), 40 * kPa, rtol=1e-15)


def test_effective_stresses_vectorised_and_limits():
    S = np.array([[0.0], [0.25], [1.0]])  # (3, 1) against (4,) -> (3, 4)
    sigma = np.array([10, 50, 100, 200]) * kPa
    sW = pt.water_saturated_effective_stress(sigma, -20 * kPa, S)
    sA = pt.air_saturated_effective_stress(sigma, 5 * kPa, S)
    assert sW.shape == sA.shape == (3, 4)
    # exact arithmetic: S_r = 1 gives Terzaghi's sigma - u_w, S_r = 0 the dry sigma - u_a
    assert_allclose(sW[2], sigma + 20 * kPa, rtol=1e-15)
    assert_allclose(sA[0], sigma - 5 * kPa, rtol=1e-15)
    assert_allclose(sW[0], 0.0, atol=0)
    assert_allclose(sA[2], 0.0, atol=0)


# --- lines, eq. 6-10 --------------------------------------------------------------------------
def test_lines_and_class_laws_by_hand():
    # ncl: e = 2.0 - 0.2 ln(100) = 2.0 - 0.921034 = 1.078966
    assert_allclose(pt.ncl_void_ratio(100 * kPa, 0.2, 2.0), 1.0789659628, rtol=1e-10)
    # url below a yield stress of 100 kPa, at 25 kPa: 1.078966 + 0.02 ln 4 = 1.106692
    assert_allclose(
        pt.compression_void_ratio(25 * kPa, 100 * kPa, 0.2, 0.02, 2.0), 1.0789659628 + 0.02 * log(4), rtol=1e-10
    )  # the literal carries 11 digits
    # above the yield stress the pores are on the ncl
    assert_allclose(pt.compression_void_ratio(400 * kPa, 100 * kPa, 0.2, 0.02, 2.0), 2.0 - 0.2 * log(400), rtol=1e-14)
    # eq. 6/7: -kappa ln(50/100) = +0.02 ln 2 = 0.0138629; eq. 10: -lambda ln 2 = -0.1386294
    assert_allclose(pt.url_void_ratio_change(0.02, 100 * kPa, 50 * kPa), 0.0138629436, rtol=1e-9)
    assert_allclose(pt.ncl_void_ratio_change(0.2, 100 * kPa, 200 * kPa), -0.1386294361, rtol=1e-9)


def test_equivalent_preconsolidation_and_transitions_by_hand():
    # sigma* where the slurry ncl (2.0, 0.2) passes through e = 1.408798: exp((2.0 - 1.408798)/0.2) kPa
    # = exp(2.956012) = 19.2212 kPa; back on the line it returns the same void ratio
    s_star = pt.equivalent_preconsolidation_stress(1.4087976995, 0.2, 2.0)
    assert_allclose(s_star, 19.221155 * kPa, rtol=1e-6)  # 7 digits carried by hand
    assert_allclose(pt.ncl_void_ratio(s_star, 0.2, 2.0), 1.4087976995, rtol=1e-13)
    # eq. 9 (sigma' = 100 kPa above sigma* = 50 kPa): -0.2 ln 2 = -0.138629 (collapse onto the ncl)
    # eq. 8 (sigma' = 25 kPa below sigma* = 50 kPa): -0.02 ln 0.5 = +0.013863 (rebound on the url)
    d = pt.transition_void_ratio_change(np.array([100, 25]) * kPa, 50 * kPa, 0.2, 0.02)
    assert_allclose(d, [-0.2 * log(2), 0.02 * log(2)], rtol=1e-14)


# --- eq. 3-5 ------------------------------------------------------------------------------------
def test_eq3_eq4_as_printed_by_hand():
    # eq. 3: de_WW = -0.01, de_AW = -0.1, S_r = 0.8 after dS_r = 0.2: weight 0.2/0.8 = 0.25
    # -> -0.01 * 0.75 - 0.1 * 0.25 = -0.0325; a drying step (dS_r < 0) has no AW class: de_W = de_WW
    assert_allclose(pt.water_saturated_increment(-0.01, -0.1, 0.8, [0.2, -0.05]), [-0.0325, -0.01], rtol=1e-14)
    # eq. 4: de_AA = 0.002, de_WA = 0.05, S_r = 0.3 after dS_r = -0.07: weight 0.07/0.7 = 0.1
    # -> 0.002 * 0.9 + 0.05 * 0.1 = 0.0068; a wetting step has no WA class
    assert_allclose(pt.air_saturated_increment(0.002, 0.05, 0.3, [-0.07, 0.1]), [0.0068, 0.002], rtol=1e-12)


def test_eq5_coupling_by_hand_and_limits():
    # e_W = 1, e_A = 2, S_r = 0.5: 1 * 2 / (1 * 0.5 + 2 * 0.5) = 4/3; solids check:
    # M_W = S e / e_W = 2/3, M_A = (1 - S) e / e_A = 1/3, M_W + M_A = 1
    assert_allclose(pt.coupled_void_ratio(1.0, 2.0, 0.5), 4.0 / 3.0, rtol=1e-15)
    e_W, e_A = np.array([0.9, 1.3]), np.array([1.5, 1.1])
    assert_allclose(pt.coupled_void_ratio(e_W, e_A, 1.0), e_W, rtol=1e-15)  # water-saturated sample
    assert_allclose(pt.coupled_void_ratio(e_W, e_A, 0.0), e_A, rtol=1e-15)  # dry sample
    assert_allclose(pt.coupled_void_ratio(1.2, 1.2, [0.1, 0.7]), 1.2, rtol=1e-15)  # equal parts


# --- the simulator ------------------------------------------------------------------------------
def test_hand_worked_wetting_step():
    """One wetting step at constant total stress, every number by hand (lines HAND).

    Point 0: sigma = 100 kPa, u_w = -100 kPa, u_a = 0, S_r = 0.5
      sigma'_W = 200 * 0.5 = 100 kPa, sigma'_A = 100 * 0.5 = 50 kPa; both parts on their ncl:
      e_W0 = 2.0 - 0.2 ln 100 = 1.078966, e_A0 = 1.8 - 0.1 ln 50 = 1.408798
      eq. 5: e0 = e_W0 e_A0 / (0.5 e_W0 + 0.5 e_A0) = 1.222017
      solids: M_W = 0.5 e0 / e_W0 = 0.566291, M_A = 0.433709
    Point 1: sigma = 100 kPa, u_w = -20 kPa, S_r = 0.7
      sigma'_W = 120 * 0.7 = 84 kPa, sigma'_A = 100 * 0.3 = 30 kPa (both unload: urls)
      WW (eq. 7): e_W = 1.078966 + 0.02 ln(100/84) = 1.082453
      AA (eq. 6): e_A = 1.408798 + 0.01 ln(50/30) = 1.413906
      at constant fluid content S_r would be M_W 1.082453 / (M_W 1.082453 + M_A 1.413906) = 0.4999 < 0.7:
      air-saturated pores become water-saturated.
      AW (eq. 9): sigma'*_W = exp((2.0 - 1.408798)/0.2) = 19.22 kPa < 84 kPa: collapse onto the slurry ncl,
      e_T = 2.0 - 0.2 ln 84 = 1.113837, de_AW = 1.113837 - 1.408798 = -0.294961
      share x of the air-saturated solids that changes fluid, from (1 - S) V_W = S V_A:
      D = 0.7 M_A 1.413906 - 0.3 M_W 1.082453 = 0.245362
      x = D / (0.3 M_A 1.113837 + 0.7 M_A 1.413906) = 0.427325
      V_W = M_W 1.082453 + x M_A 1.113837 = 0.819416, V_A = (1 - x) M_A 1.413906 = 0.351178
      e = V_W + V_A = 1.170594; e_W = V_W / (M_W + x M_A) = 1.090192; e_A = 1.413906
      eq. 3 weight: x M_A 1.113837 / V_W = 0.251927 (dS_r / S_r = 0.2/0.7 = 0.2857 to first order)
    """
    r = pt.simulate_volume_path(
        [100 * kPa, 100 * kPa], [-100 * kPa, -20 * kPa], [0.0, 0.0], [0.5, 0.7], params=HAND, substeps=1
    )
    # rtol 1e-6: the hand values above carry 6-7 significant digits
    assert_allclose(r.e, [1.2220170181, 1.1705939572], rtol=1e-6)
    assert_allclose(r.e_W, [1.0789659628, 1.0901915540], rtol=1e-6)
    assert_allclose(r.e_A, [1.4087976995, 1.4139059557], rtol=1e-6)
    assert_allclose(r.solid_fraction_W[0], 0.5662908100, rtol=1e-6)
    assert_allclose(r.de_WW[1], 1.0824530305 - 1.0789659628, rtol=1e-6)
    assert_allclose(r.de_AA[1], 1.4139059557 - 1.4087976995, rtol=1e-6)
    assert_allclose(r.de_AW[1], -0.2949610592, rtol=1e-6)
    assert_allclose(r.sigma_star_W[1], 19.221155 * kPa, rtol=1e-6)
    assert_allclose(r.w_AW[1], 0.2519265239, rtol=1e-6)
    assert np.isnan(r.de_WA[1]) and r.w_WA[1] == 0.0
    assert list(r.loading_W) == [False, False] and list(r.loading_A) == [False, False]
    # the collapsed pores sit on the slurry ncl; the rest of the water-saturated part on its url
    assert 0 < r.ncl_fraction_W[1] < 1 and r.ncl_fraction_A[1] == 0.0


def test_saturated_path_follows_slurry_ncl_and_url():
    # S_r = 1: sigma'_W = sigma - u_w; the air-saturated part never exists (Pedrotti & Tarantino, hypothesis 3)
    sigma = np.array([10, 50, 200, 400, 100, 25, 100, 800]) * kPa
    u_w = np.full(sigma.size, 5 * kPa)  # positive pore-water pressure: saturated below the water table
    r = pt.simulate_volume_path(sigma, u_w, np.zeros(sigma.size), np.ones(sigma.size), params=HAND, substeps=1)
    s = (sigma - u_w) / kPa
    ncl = 2.0 - 0.2 * np.log(s)
    expect = ncl.copy()
    # unloading from 395 kPa and reloading to 95 kPa: url of slope 0.02 through (395 kPa, ncl)
    for i in (4, 5, 6):
        expect[i] = ncl[3] + 0.02 * np.log(s[3] / s[i])
    # exact arithmetic of logs: rtol 1e-12
    assert_allclose(r.e, expect, rtol=1e-12)
    assert_allclose(r.e_W, expect, rtol=1e-12)
    assert np.all(np.isnan(r.e_A)) and np.all(r.solid_fraction_W == 1.0)
    assert list(r.yielding_W) == [True, True, True, True, False, False, False, True]
    assert list(r.loading_W) == [False, True, True, True, False, False, True, True]


def test_dry_path_follows_dry_powder_line():
    # S_r = 0: sigma'_A = sigma - u_a; pore-water pressure is irrelevant
    sigma = np.array([20, 100, 300, 60, 600]) * kPa
    u_a = np.full(sigma.size, 10 * kPa)
    r = pt.simulate_volume_path(sigma, np.full(sigma.size, -1e6), u_a, np.zeros(sigma.size), params=HAND, substeps=1)
    s = (sigma - u_a) / kPa
    expect = 1.8 - 0.1 * np.log(s)
    expect[3] = expect[2] + 0.01 * np.log(s[2] / s[3])  # unloading on the dry-powder url
    assert_allclose(r.e, expect, rtol=1e-12)  # exact arithmetic
    assert np.all(np.isnan(r.e_W)) and np.all(r.solid_fraction_W == 0.0)


def test_unloading_moves_kept_pores_on_their_urls():
    # unloading at constant S_r and suction from the normally consolidated state: the pores that keep
    # their fluid change by -kappa dln(sigma') exactly (eq. 6 and 7), whatever fluid transfer occurs
    sigma = np.array([300, 100]) * kPa
    r = pt.simulate_volume_path(sigma, [-200 * kPa] * 2, [0.0, 0.0], [0.6, 0.6], params=HAND, substeps=1)
    assert_allclose(r.de_WW[1], -0.02 * np.log(r.sigma_W[1] / r.sigma_W[0]), rtol=1e-12)
    assert_allclose(r.de_AA[1], -0.01 * np.log(r.sigma_A[1] / r.sigma_A[0]), rtol=1e-12)
    assert r.e[1] > r.e[0]  # rebound
    assert not r.yielding_W[1] and not r.yielding_A[1]


@pytest.mark.parametrize("S_r", [0.0, 0.3, 0.6, 0.9, 1.0])
def test_loading_at_constant_suction_and_saturation_compresses(S_r):
    # monotone loading at constant S_r and suction: e never increases
    sigma = np.linspace(20, 800, 40) * kPa
    n = sigma.size
    r = pt.simulate_volume_path(sigma, np.full(n, -100 * kPa), np.zeros(n), np.full(n, S_r), params=pt.EXAMPLE_KAOLIN)
    assert np.all(np.diff(r.e) < 0)


def test_model_saturation_matches_path_and_eq5_holds():
    # the books of voids: S_r of the model equals the path's; eq. 5 with the parts' void ratios gives e
    d = np.genfromtxt(SAMPLE, delimiter=",", comments="#", skip_header=6)
    sigma, u_w, u_a, S_r = d[:, 2] * kPa, d[:, 3] * kPa, d[:, 4] * kPa, d[:, 5]
    r = pt.simulate_volume_path(sigma, u_w, u_a, S_r, params=pt.EXAMPLE_KAOLIN)
    # round-off only: 1e-12
    assert_allclose(r.solid_fraction_W * r.e_W / r.e, S_r, rtol=1e-12)
    assert_allclose(pt.coupled_void_ratio(r.e_W, r.e_A, S_r), r.e, rtol=1e-12)
    # eq. 3 weights dS_r/S_r hold when the two parts deform alike; on the wetting and loading steps
    # here the water-saturated part swells or compresses more, which moves the weights by up to 20.4 %
    # (first wetting step: the swelling WW pores raise S_r by themselves); 25 % bounds that. On the
    # unloading steps the air-saturated part rebounds much more (sigma'_A falls from 153 to 7 kPa)
    # and the weights of eq. 4 differ by up to 36 %: that is where the books of voids and the literal
    # eq. 4 part, so no bound is asserted there, only that water-to-air transfer happened.
    dS = np.diff(S_r)
    wet, dry = dS > 0, dS < 0
    assert_allclose(r.w_AW[1:][wet], (dS / S_r[1:])[wet], rtol=0.25)
    assert np.all(r.w_WA[1:][dry] > 0) and np.all(r.w_AW[1:][dry] == 0)


def test_sample_path_reproduces_the_stages_of_the_paper():
    """Section 4.2 of Pedrotti & Tarantino, on the path of their Fig. 13 (sample_data/pt_volume_path.csv)."""
    d = np.genfromtxt(SAMPLE, delimiter=",", comments="#", skip_header=6)
    stage_end = {"A": 0, "B": 7, "C": 14, "D": 20}
    r = pt.simulate_volume_path(d[:, 2] * kPa, d[:, 3] * kPa, d[:, 4] * kPa, d[:, 5], params=pt.EXAMPLE_KAOLIN)
    A, B, C, D = (stage_end[k] for k in "ABCD")
    # A: end of compaction, both parts on their ncl; e near 1.2 by the choice of EXAMPLE_KAOLIN
    assert r.ncl_fraction_W[A] == 1.0 and r.ncl_fraction_A[A] == 1.0
    assert_allclose(r.e[A], 1.2, atol=0.01)  # the intercepts were set to about this (see EXAMPLE_KAOLIN)
    # A-B (Fig. 14): unloading dries the sample; AA and WW rebound on their urls, WA pores rebound on the
    # dry-powder url (eq. 8) from sigma*_A above sigma'_A
    ab = slice(A + 1, B + 1)
    assert np.all(r.de_AA[ab] > 0) and np.all(r.de_WW[ab] > 0) and np.all(r.de_WA[ab] > 0)
    assert np.all(r.sigma_star_A[ab] > r.sigma_A[ab])
    # B-C (Fig. 15): wetting; AA rebound (sigma'_A falls), WW swell (suction falls), AW pores collapse (eq. 9)
    bc = slice(B + 1, C + 1)
    assert np.all(r.de_AA[bc] > 0) and np.all(r.de_WW[bc] > 0) and np.all(r.de_AW[bc] < 0)
    # C-D (Fig. 16): loading at constant suction; two classes of water-saturated pores, one on the ncl
    # (those that came from air) and one on the url (from compaction), and more AW collapse
    cd = slice(C + 1, D + 1)
    assert np.all(r.de_AW[cd] < 0) and np.all(np.diff(r.e[C : D + 1]) < 0)
    assert 0.0 < r.ncl_fraction_W[D] < 1.0


def test_substeps_converge():
    # the points A, B, C, D of the sample path only. First-order scheme: one step per stage is off by
    # up to 0.035 in e at C (the AW pores of a single wetting step skip the collapse at high sigma'_W);
    # the automatic sub-steps (|dS_r| <= 0.002) are within 1e-3 of 1500 sub-steps per stage (measured:
    # 2.1e-4), which are themselves within 1e-4 of 3000 by the first-order error (halves with the step).
    d = np.genfromtxt(SAMPLE, delimiter=",", comments="#", skip_header=6)[[0, 7, 14, 20]]
    args = (d[:, 2] * kPa, d[:, 3] * kPa, d[:, 4] * kPa, d[:, 5])
    auto = pt.simulate_volume_path(*args, params=pt.EXAMPLE_KAOLIN)
    fine = pt.simulate_volume_path(*args, params=pt.EXAMPLE_KAOLIN, substeps=1500)
    one = pt.simulate_volume_path(*args, params=pt.EXAMPLE_KAOLIN, substeps=1)
    assert_allclose(auto.e, fine.e, atol=1e-3)
    assert np.max(np.abs(one.e - fine.e)) > 0.01  # the step size matters: why sub-steps are the default


def test_initial_yield_starts_overconsolidated():
    # a past yield stress of 400 kPa: at 100 kPa the saturated sample sits on the url, 0.02 ln 4 above the ncl
    r = pt.simulate_volume_path([100 * kPa], [0.0], [0.0], [1.0], params=HAND, initial_yield_W=400 * kPa)
    assert_allclose(r.e[0], 2.0 - 0.2 * log(400) + 0.02 * log(4), rtol=1e-14)
    assert r.ncl_fraction_W[0] == 0.0


# --- bad input ------------------------------------------------------------------------------------
def test_parameters_rejected_with_all_problems():
    with pytest.raises(ValueError, match="kappa_W.*lambda_W") as err:
        pt.PTVolumeParameters(lambda_W=0.1, kappa_W=0.2, e_ncl_W=2.0, lambda_A=-0.1, kappa_A=0.01, e_ncl_A=1.8)
    assert "lambda_A must be > 0" in str(err.value)


def test_path_problems_located():
    probs = pt.path_problems(
        [100 * kPa, 10 * kPa, 50 * kPa], [-50 * kPa, 0.0, 0.0], [0.0, 20 * kPa, 0.0], [0.5, 0.5, 1.2]
    )
    assert (2, "S_r", "degree of saturation must lie between 0 and 1 (got 1.2)") in probs
    assert any(i == 1 and c == "u_a" for i, c, _ in probs)  # sigma - u_a = -10 kPa with S_r < 1
    with pytest.raises(ValueError, match="point 3, S_r"):
        pt.simulate_volume_path(
            [100 * kPa, 10 * kPa, 50 * kPa], [-50 * kPa, 0.0, 0.0], [0.0, 20 * kPa, 0.0], [0.5, 0.5, 1.2], params=HAND
        )
    assert pt.path_problems([1.0], [0.0, 1.0], [0.0], [0.5])[0][0] == -1  # unequal lengths
