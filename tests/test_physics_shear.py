"""Thesis formulas (Evenepoel, VUB thesis) against values worked by hand."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from capred.physics import effective_stress_models as esm
from capred.physics import shear as ph


def test_suction_from_head_thesis_factor():
    # Evenepoel (VUB thesis), "Apply suction": Delta_u = z1 * 0.1 kPa/cm with gamma_w = 10 kN/m^3
    assert_allclose(ph.suction_from_head(0.10, gamma_w=10_000.0), 1000.0, rtol=1e-15)
    assert_allclose(ph.suction_from_head(0.25, gamma_w=9810.0), 2452.5, rtol=1e-15)


def test_degree_of_saturation_from_burette():
    # S_R = (V_v - z2)/V_v: 27 cm^3 voids, 5.4 cm^3 air -> 0.8
    assert_allclose(ph.degree_of_saturation(5.4e-6, 27e-6), 0.8, rtol=1e-12)
    assert_allclose(ph.degree_of_saturation([0.0, 27e-6], 27e-6), [1.0, 0.0], atol=1e-15)


def test_normal_stress_from_masses():
    # (120 g cap + 77.47 g added) * 9.81 / 36 cm^2 = 538.1 Pa
    assert_allclose(ph.normal_stress(0.19747, 36e-4, 9.81), 0.19747 * 9.81 / 36e-4, rtol=1e-15)
    assert_allclose(ph.normal_stress(0.19747, 36e-4, 9.81), 538.1058, rtol=1e-6)


def test_chi1_is_one_at_three_over_two_pi():
    assert_allclose(ph.chi1(3 / (2 * np.pi)), 1.0, rtol=1e-14)
    # (2 pi 0.05 / 3)^(2/3) = 0.104720^(2/3) = exp(2/3 ln 0.104720) = 0.222170
    assert_allclose(ph.chi1(0.05), 0.222170, rtol=5e-6)


def test_chi2_for_2mm_steel_sphere():
    # 2 gamma / R = 2 * 0.0728 / 1e-3 = 145.6 Pa at (2 pi S_R/3) = 1
    assert_allclose(ph.chi2(3 / (2 * np.pi), 1e-3, 0.0728), 145.6, rtol=1e-12)


def test_four_models_worked_example():
    # sigma_N = 1 kPa, suction = 2 kPa, 2 pi S_R / 3 = 0.125 -> chi1 = 0.25, cube root 0.5
    S_R = 0.125 * 3 / (2 * np.pi)
    kw = dict(sigma_N=1000.0, suction=2000.0, S_R=S_R, R=1e-3, surface_tension=0.0728)
    assert_allclose(esm.effective_normal_stress("no_suction", **kw), 1000.0)
    assert_allclose(esm.effective_normal_stress("bishop", **kw), 1000.0 + 2000.0 * S_R, rtol=1e-14)
    assert_allclose(esm.effective_normal_stress("own1", **kw), 1500.0, rtol=1e-14)
    assert_allclose(esm.effective_normal_stress("own2", **kw), 1500.0 + 145.6 * 0.5, rtol=1e-14)
    # tau with the thesis steel-sphere envelope c = 0.3452 kPa, tan phi = 0.7146
    assert_allclose(ph.mohr_coulomb_strength(345.2, 0.7146, 1500.0), 345.2 + 1071.9, rtol=1e-14)


@given(st.floats(min_value=1e-9, max_value=1.0))
def test_chi1_exceeds_S_R(s):
    # (2 pi/3)^(2/3) S^(2/3) > S  <=>  S^(1/3) < (2 pi/3)^(2/3) = 1.637, true on (0, 1]
    assert ph.chi1(s) > s


@given(st.floats(0.0, 1.0), st.floats(0.0, 1e5), st.floats(0.0, 1e5), st.floats(0.0, 1e5))
def test_predictions_increase_with_suction(S_R, sigma_N, s1, s2):
    lo, hi = sorted((s1, s2))
    for model in esm.THESIS_MODELS:
        a = esm.effective_normal_stress(model, sigma_N, lo, S_R, 1e-3)
        b = esm.effective_normal_stress(model, sigma_N, hi, S_R, 1e-3)
        assert b >= a


@given(st.floats(1e-9, 1.0), st.floats(0.0, 1.0))
def test_degree_of_saturation_in_unit_interval(v_v, fraction):
    s = ph.degree_of_saturation(fraction * v_v, v_v)
    assert -1e-12 <= s <= 1.0 + 1e-12
