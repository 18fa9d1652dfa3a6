"""Phase relations (capred.physics.phase): published sample states completed from a measured subset."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred.physics.phase import InconsistentState, complete_state

# Prunier et al. (2024), Table 1 (Gavet silt): w = 10.5 %, rho_s = 2.72 g/cm^3, rho_d = 1.82 g/cm^3,
# e = 0.494, S_r = 57.7 %. Published to 3 digits: e and S_r are checked to half a unit of their last digit
# (0.0005 and 0.0005) plus the rounding of the inputs w (0.05 %) and rho_d (0.005 g/cm^3), i.e. ~0.3 % relative.
PRUNIER = {"w": 0.105, "rho_s": 2720.0, "rho_d": 1820.0}


def test_complete_state_prunier_table1_from_measured_subset():
    s = complete_state(**PRUNIER)
    assert_allclose(s["e"], 0.494, rtol=3e-3)
    assert_allclose(s["S_r"], 0.577, rtol=3e-3)
    assert_allclose(s["G_s"], 2.72, rtol=1e-12)  # rho_s / rho_w exactly
    # n = e/(1+e) and theta = w rho_d/rho_w = S_r n (two routes to the same number)
    assert_allclose(s["n"], s["e"] / (1 + s["e"]), rtol=1e-12)
    assert_allclose(s["theta"], 0.105 * 1.82, rtol=1e-12)
    assert_allclose(s["theta"], s["S_r"] * s["n"], rtol=1e-12)


def test_complete_state_whole_published_row_is_consistent():
    s = complete_state(**PRUNIER, e=0.494, S_r=0.577)
    assert_allclose(s["e"], 0.494)  # given values are kept as given
    assert_allclose(s["S_r"], 0.577)


@pytest.mark.parametrize(
    "given",
    [
        {"e": 0.494, "S_r": 0.577, "G_s": 2.72},  # void ratio and saturation: w and rho_d follow
        {"n": 0.494 / 1.494, "theta": 0.1911, "rho_s": 2720.0},  # porosity and volumetric water content
        {"rho_d": 1820.0, "theta": 0.1911, "S_r": 0.5775},  # rho_s from theta/S_r = n
    ],
)
def test_complete_state_other_subsets_give_the_same_state(given):
    s = complete_state(**given)
    assert_allclose(s["w"], 0.105, rtol=3e-3)
    assert_allclose(s["rho_d"], 1820.0, rtol=3e-3)


def test_complete_state_vectorised_with_unknowns():
    s = complete_state(rho_d=[1820.0, 1600.0], G_s=2.7, w=[0.105, np.nan])
    assert np.isfinite(s["S_r"][0]) and np.isnan(s["S_r"][1])
    assert_allclose(s["e"][1], 2700 / 1600 - 1)


def test_complete_state_inconsistent_subset_names_row_and_values():
    with pytest.raises(InconsistentState) as exc:
        complete_state(rho_d=[1820.0, 1820.0], rho_s=2720.0, e=[0.494, 0.6])
    assert [p[0] for p in exc.value.problems] == [1]  # only the second row contradicts itself
    assert "0.6" in str(exc.value) and "0.4945" in str(exc.value)


@pytest.mark.parametrize("given", [{"S_r": 1.2}, {"rho_d": -1.0}, {"n": 1.0}])
def test_complete_state_impossible_value_is_an_error(given):
    with pytest.raises(InconsistentState, match="outside"):
        complete_state(**given)


def test_complete_state_implied_saturation_above_one_is_an_error():
    with pytest.raises(InconsistentState, match="implied"):
        complete_state(rho_d=1820.0, rho_s=2720.0, w=0.35)


def test_shear_and_retention_check_a_rows_sample_state(tmp_path):
    """Every command reading a sample state goes through the phase relations (capred.pipelines.sample_state)."""
    from capred.errors import InputError
    from capred.pipelines.retention import run_retention
    from capred.pipelines.shear_run import run_shear

    shear = tmp_path / "shear.csv"
    shear.write_text(
        "test_id,material,condition,sigma_N,tau_max,e,rho_d,G_s,height,box_area\n"
        "a,s,dry,10,7,0.6,1650,2.65,20,36\nb,s,dry,20,14,0.9,1650,2.65,20,36\nc,s,dry,30,21,0.606,1650,2.65,20,36\n"
    )
    # line 3: e = 0.9 but G_s rho_w/rho_d - 1 = 0.606 (line 4's 0.606 agrees)
    with pytest.raises(InputError, match=r"line 3, column 'e'.*0\.9") as exc:
        run_shear(shear)
    assert len(exc.value.problems) == 1
    ret = tmp_path / "ret.csv"
    ret.write_text(
        "suction,w,rho_d,theta\n1,0.2,1600,0.32\n10,0.18,1600,0.40\n100,0.1,1600,0.16\n1000,0.05,1600,0.08\n"
    )
    # line 3: theta = 0.40 but w rho_d/rho_w = 0.288
    with pytest.raises(InputError, match=r"line 3.*0\.288"):
        run_retention(ret)
