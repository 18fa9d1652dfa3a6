"""Triaxial instrument exports as they are (issue 29.5) and the Lode angle of exact tests.

The export below is shaped like a GDSLAB data file: a metadata block, then one row per reading of every
stage of the test (saturation, consolidation, shear) with the instrument's standard columns.
"""

import warnings

import numpy as np
import pandas as pd
import pytest
from numpy.testing import assert_allclose

import capred
from capred.physics import triaxial as tx
from capred.pipelines.triaxial_curves import EXPORT_COLUMNS, read_curves

HEAD = (
    "Stage Number,Time since start of test (s),Time since start of stage (s),Radial Pressure (kPa),"
    "Radial Volume (mm³),Back Pressure (kPa),Back Volume (mm³),Load Cell (kN),Pore Pressure (kPa),"
    "Axial Displacement (mm),Axial Strain (%),Av Diameter Change (mm),Radial Strain (%),Axial Stress (kPa),"
    "Eff. Axial Stress (kPa),Eff. Radial Stress (kPa),Deviator Stress (kPa),Total Stress Ratio,"
    "Eff. Stress Ratio,Current Area (mm²),Shear Strain (%),Cambridge p (kPa),Eff. Cambridge p' (kPa),"
    "Max Shear Stress t (kPa),Volume Change (mm³),B Value{extra}"
)


def _export(path, stages, extra="", du=0.0, b_check=None):
    """A GDS-style export: ``stages`` maps a stage number to its deviator readings [kPa]; in the shear stage
    (the last) the pore pressure rises by ``du`` times the rise of q. ``b_check`` = B makes the first stage a
    B check: the cell pressure steps from 250 to 300 kPa, the pore pressure rises by B x 50 kPa to 200 kPa."""
    rows, t = [], 0
    for stage, qs in stages.items():
        for k, q in enumerate(qs):
            shear = stage == max(stages)
            eps = 0.5 * k if shear else 0.0  # axial strain [%] moves in the shear stage only
            u = 200 + (du * (q - qs[0]) if shear else 0.0)
            cell = 300
            if b_check is not None and stage == min(stages) and k == 0:
                cell, u = 250, 200 - b_check * 50
            rows.append(
                f"{stage},{t},{k},{cell},0,200,0,0,{u},0,{eps},0,0,{300 + q},{100 + q},100,{q},1,1,1134,0,"
                f"{300 + q / 3},{100 + q / 3},{q / 2},0,0.96" + (",x" if extra else "")
            )
            t += 60
    path.write_text(
        "Test ID: G1\nInitial diameter (mm): 38\nStation: 3\n\n" + HEAD.format(extra=extra) + "\n" + "\n".join(rows)
    )
    return path


def test_gds_standard_columns_are_known_and_stage_number_picks_the_shear_stage(tmp_path):
    # saturation (stage 1) and consolidation (stage 3) hold q near 0-12 kPa; the shear stage (4) peaks at 150 kPa
    # at its third reading (axial strain 1 %). A later reading of stage 3 above the shear stage's first reading
    # must not move the peak: only stage 4 is read.
    f = _export(tmp_path / "G1.csv", {1: [1, 2, 2], 3: [2, 10, 12], 4: [6, 80, 150, 120]})
    c = read_curves(f)
    assert c.warnings == [] and c.problems == []  # 24 standard columns, none warned about as "not used"
    assert c.peaks["G1"] == (150e3, 0.01)
    assert any("stage 4 of stages 1, 3, 4 taken as the shear stage" in n for n in c.notes)
    # a column that is not standard is still warned about (the list does not hide everything)
    (tmp_path / "other").mkdir()
    g = _export(tmp_path / "other" / "G1.csv", {4: [0, 50]}, ",Mystery")
    assert read_curves(g).warnings == ["column 'Mystery' is not used"]


def test_export_columns_are_listed_once():
    assert len(EXPORT_COLUMNS) == len(set(EXPORT_COLUMNS))


def test_gds_export_through_triaxial_bounds(tmp_path):
    f = _export(tmp_path / "G1.csv", {1: [1, 2, 2], 4: [6, 80, 150, 120]})
    tests = tmp_path / "tests.csv"
    # saturated tests on c' = 0, phi' = 30 (sigma'1 = 3 sigma'3); G1 total sigma3 = 300 kPa, u_b = 200 kPa
    tests.write_text(
        "test_id,condition,sigma3,q_f,back_pressure\ns1,saturated,100,200,0\ns2,saturated,200,400,0\n"
        "G1,saturated,300,,200\n"
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = capred.run_triaxial_bounds(tests, curves=f)
    assert not [w for w in caught if "not used" in str(w.message)]  # no Python warning either (a notebook)
    js = r.to_json()
    assert not [w for w in js["warnings"] if "not used" in w]
    g1 = js["tests"][2]
    assert g1["q_kPa"] == 150.0 and g1["sigma3_kPa"] == 100.0  # 300 - 200 kPa back pressure
    assert g1["lode_angle_deg"] == 0.0  # exact compression: 0, not round-off


def test_lode_angle_of_exact_tests_is_exact():
    # sigma' = sigma - u in floating point: 0.3 - 0.1 != 0.2, yet sigma2 = sigma3 is exact compression.
    s1, s3 = 300.3 - 0.1, 100.3 - 0.1
    s2 = 100.2 + 1e-14  # a round-off away from sigma3
    assert tx.lode_angle_deg(s1, s2, s3) == 0.0
    assert tx.lode_angle_deg(s1, s1 - 1e-14, s3) == 60.0
    assert np.isnan(tx.lode_angle_deg(100.0, 100.0, 100.0))
    # away from the ends the arctan form equals the cos 3 theta form of eq. 52-53 (both closed forms)
    rng = np.random.default_rng(1)
    s = np.sort(rng.uniform(0, 500, (3, 200)), axis=0)[::-1]
    d = s - s.mean(axis=0)
    c3 = np.sqrt(6) * np.sum(d**3, axis=0) / np.sum(d**2, axis=0) ** 1.5
    # arccos loses sqrt(eps) near its ends: 1e-6 deg compares the two away from them
    assert_allclose(tx.lode_angle_deg(*s), np.degrees(np.arccos(np.clip(c3, -1, 1)) / 3), atol=1e-6)
    # a measured difference (0.1 kPa on 300 kPa) is not snapped: theta = atan(sqrt3 (1 - Q)/(1 + Q)), Q = 199.9/200
    q = 199.9 / 200
    assert tx.lode_angle_deg(300.0, 100.1, 100.0) == pytest.approx(
        np.degrees(np.arctan(np.sqrt(3) * (1 - q) / (1 + q))), rel=1e-9
    )


def test_sample_compression_tests_print_lode_zero():
    r = capred.run_triaxial_bounds(capred.sample_path("triaxial-groups"))
    t = pd.DataFrame(r.to_json()["tests"]).set_index("test_id")
    assert (t.loc[["A-50", "A-100", "A-150", "SAT-50"], "lode_angle_deg"] == 0.0).all()
    assert (t.loc[["E-150", "E-250", "E-350"], "lode_angle_deg"] == 60.0).all()


def test_skempton_a_from_the_pore_pressure_of_the_shear_stage(tmp_path):
    # shear stage: q from 6 to 150 kPa (dq = 144) at constant cell pressure, u rises by q/2 (du = 72 kPa);
    # stage 1 is a B check giving du/dsigma3 = 48/50 = 0.96: A = (du - B dsigma3)/(B dq) = 72/(0.96 * 144) = 0.52083
    # (Skempton 1954). The export's B Value column (0.96 on every row, shear included) is not what is read.
    f = _export(tmp_path / "G1.csv", {1: [1, 2, 2], 4: [6, 80, 150, 120]}, du=0.5, b_check=0.96)
    tests = tmp_path / "tests.csv"
    head = "test_id,condition,sigma3,q_f,back_pressure{b}\ns1,saturated,100,200,0{x}\ns2,saturated,200,400,0{x}\n"
    tests.write_text(head.format(b="", x="") + "G1,saturated,300,,200\n")
    given = capred.TriaxialOptions(c_eff=0.0, phi_eff=30.0)  # the envelope is not the subject
    r = capred.run_triaxial_bounds(tests, given, curves=f)
    assert r.states.skempton_A[2] == pytest.approx(72 / (0.96 * 144), rel=1e-12)  # arithmetic only
    assert np.isnan(r.states.skempton_A[:2]).all()  # no curve, no A
    assert r.to_json()["tests"][2]["skempton_A"] == r.states.skempton_A[2]
    assert "skempton_A [-]" in r.table().columns
    assert any("Skempton's B = 0.96 from the B check (stage 1" in n for n in r.notes)
    # without a B-check stage, B = 1 with a note (never the running B Value column): A = 72/144 = 0.5
    g = _export(tmp_path / "G2.csv", {1: [1, 2, 2], 4: [6, 80, 150, 120]}, du=0.5)
    tests.write_text(head.format(b="", x="") + "G1,saturated,300,,200\n")
    r = capred.run_triaxial_bounds(tests, given, curves=g)
    assert r.states.skempton_A[2] == pytest.approx(0.5, rel=1e-12)
    assert any("B = 1" in n and "no B-check stage" in n for n in r.notes)
    # the tests table's B wins over the export's: B = 1 gives A = 72/144 = 0.5
    tests.write_text(head.format(b=",B", x=",") + "G1,saturated,300,,200,1\n")
    assert capred.run_triaxial_bounds(tests, given, curves=f).states.skempton_A[2] == pytest.approx(0.5, rel=1e-12)


def test_b_check_that_disagrees_with_the_logged_b_value_is_warned(tmp_path):
    # stage 1 is a B check of du/dsigma3 = 45/50 = 0.9 while the export's B Value column says 0.96: capred takes
    # the pressures' 0.9 (Skempton 1954) and a warning gives both
    f = _export(tmp_path / "G1.csv", {1: [1, 2, 2], 4: [6, 80, 150, 120]}, du=0.5, b_check=0.9)
    c = read_curves(f)
    assert c.at_peak["G1"]["B"] == pytest.approx(0.9, rel=1e-12)
    assert any("gives B = 0.9 but the export's B Value at its end is 0.96" in w for w in c.warnings)
