"""capred shear on constructed data whose answer is known by hand."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import capred
from capred.pipelines.shear import ShearOptions
from capred.pipelines.shear_run import run_shear

# Noise-free file built from the thesis's dry envelopes (Evenepoel (VUB thesis), "Dry tests"):
# steel c = 0.3452 kPa, tan phi = 0.7146; sand c = 0.0721 kPa, tan phi = 0.7955.
# Box 36 cm^2, cap 120 g, g = 9.81 -> sigma_N = (120 + m) g / A.
AREA, CAP, G = 36e-4, 0.120, 9.81
ENV = {"steel": (345.2, 0.7146, 1.0), "sand": (72.1, 0.7955, 0.156)}


def _sigma(m_g):
    return (CAP + m_g / 1000) * G / AREA


def exact_csv(truth_model="own2"):
    from capred.physics import effective_stress_models as esm

    rows = ["test_id,material,condition,z1,z2,V_v,added_mass,cap_mass,box_area,R,tau_max"]
    for mat, (c, t, r_mm) in ENV.items():
        for k, m in enumerate((0.0, 77.47, 300.0, 600.0)):
            rows.append(f"{mat}-d{k},{mat},dry,,,27,{m},120,36,{r_mm},{(c + _sigma(m) * t) / 1e3!r}")
        for k, (z1, z2) in enumerate(((5, 25.65), (10, 26.0), (20, 5.4))):
            for m in (0.0, 77.47):
                S_R = (27 - z2) / 27
                eff = esm.effective_normal_stress(truth_model, _sigma(m), 9810 * z1 / 100, S_R, r_mm / 1e3)
                rows.append(f"{mat}-w{k}-{m},{mat},wet,{z1},{z2},27,{m},120,36,{r_mm},{float((c + eff * t) / 1e3)!r}")
    return "\n".join(rows) + "\n"


def test_shear_recovers_thesis_envelopes_exactly(write_csv):
    r = run_shear(write_csv(exact_csv()))
    js = r.to_json()
    steel, sand = js["materials"]["steel"], js["materials"]["sand"]
    assert_allclose([steel["c_kPa"], steel["tan_phi"]], [0.3452, 0.7146], rtol=1e-8)
    assert_allclose([sand["c_kPa"], sand["tan_phi"]], [0.0721, 0.7955], rtol=1e-8)
    # Evenepoel (VUB thesis) prints the angles: atan(0.7146) = 35.55 deg, atan(0.7955) = 38.50 deg
    assert steel["phi_deg"] == pytest.approx(35.55, abs=0.005)
    assert sand["phi_deg"] == pytest.approx(38.50, abs=0.005)
    assert steel["n"] == 4 and steel["r2"] == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("truth", ["bishop", "own1", "own2"])
def test_shear_best_model_is_the_generating_one(write_csv, truth):
    r = run_shear(write_csv(exact_csv(truth)))
    assert r.best_model == {"steel": truth, "sand": truth}
    assert r.metrics["steel"][truth].si.rmse < 1e-9
    assert r.metrics["sand"][truth].r2 == pytest.approx(1.0, abs=1e-9)


def test_shear_derived_quantities_by_hand(write_csv):
    r = run_shear(write_csv(exact_csv()), ShearOptions(gamma_w=10_000.0))
    t = r.tests
    i = list(t["test_id"]).index("steel-w2-77.47")
    assert_allclose(t["suction"][i], 2000.0, rtol=1e-14)  # 20 cm * 0.1 kPa/cm (thesis gamma_w)
    assert_allclose(t["S_R"][i], 0.8, rtol=1e-12)  # (27 - 5.4) / 27
    assert_allclose(t["sigma_N"][i], _sigma(77.47), rtol=1e-12)
    js = r.to_json()
    row = js["tests"][i]
    assert row["flags"] == ["outside_pendular", "chi1_gt_1"]
    dry = js["tests"][0]
    assert dry["condition"] == "dry" and dry["suction_kPa"] == 0 and dry["S_R"] == 0 and dry["flags"] == []
    # S_R = 0.65/27 = 0.024 is inside the pendular regime: no flag
    j = list(t["test_id"]).index("steel-w1-0.0")
    assert js["tests"][j]["flags"] == []


def test_shear_units_in_headers_give_same_result(write_csv):
    base = run_shear(write_csv(exact_csv(), "a.csv")).to_json()
    text = exact_csv().splitlines()
    text[0] = (
        "test_id,material,condition,z1 (mm),z2 [mm^3],V_v [mL],added_mass [kg],cap_mass [kg],"
        "box_area [mm^2],R [um],tau_max [Pa]"
    )
    conv = [1, 1, 1, 10, 1000, 1, 1e-3, 1e-3, 100, 1000, 1000]
    out = [text[0]]
    for line in text[1:]:
        cells = line.split(",")
        out.append(",".join(c if (k < 3 or c == "") else repr(float(c) * conv[k]) for k, c in enumerate(cells)))
    other = run_shear(write_csv("\n".join(out) + "\n", "b.csv")).to_json()
    for mat in ("steel", "sand"):
        for key in ("c_kPa", "tan_phi", "c_se_kPa"):
            assert other["materials"][mat][key] == pytest.approx(base["materials"][mat][key], rel=1e-9, abs=1e-12)
    for a, b in zip(base["tests"], other["tests"]):
        for m in ("no_suction", "bishop", "own1", "own2"):
            assert b["tau_pred_kPa"][m] == pytest.approx(a["tau_pred_kPa"][m], rel=1e-9)


def test_shear_reduced_columns_and_aliases(write_csv):
    # data reduced elsewhere: sigma_N, suction, S_R directly; alias spellings of headers
    text = (
        "Test ID;Material;Condition;Sigma N (kPa);Suction [kPa];Sr [%];Tau max;R [mm]\n"
        "d1;x;dry;1;;;1,0452;1\n"
        "d2;x;dry;2;;;1,7598;1\n"
        "d3;x;dry;3;;;2,4744;1\n"
        "w1;x;wet;1;2;5;1,5;1\n"
    )
    r = run_shear(write_csv(text))
    js = r.to_json()
    assert js["materials"]["x"]["c_kPa"] == pytest.approx(0.3306, abs=1e-9)
    assert js["materials"]["x"]["tan_phi"] == pytest.approx(0.7146, abs=1e-9)
    w = js["tests"][3]
    assert w["S_R"] == pytest.approx(0.05) and w["suction_kPa"] == pytest.approx(2.0)
    assert w["tau_pred_kPa"]["bishop"] == pytest.approx(0.3306 + (1 + 0.05 * 2) * 0.7146, rel=1e-9)


def test_shear_options_fill_blank_columns_but_file_wins(write_csv):
    text = "test_id,material,condition,added_mass,box_area,tau_max\na,m,dry,0,,1\nb,m,dry,100,,2\nc,m,dry,200,18,3\n"
    r = run_shear(write_csv(text), ShearOptions(box_area=36e-4, cap_mass=0.0))
    s = r.tests["sigma_N"]
    assert_allclose(s, [0.0, 0.1 * 9.81 / 36e-4, 0.2 * 9.81 / 18e-4], rtol=1e-12)


@pytest.mark.parametrize("given", ["e_height", "rho_d_G_s"])
def test_void_ratio_and_dry_density_inputs_write_every_output(tmp_path, given):
    """The documented alternatives to V_v (e with the sample height; rho_d with G_s) give the same S_R as V_v and
    every output file (issue 18: e + height used to crash when results.csv was written)."""
    import pandas as pd
    from typer.testing import CliRunner

    from capred.cli import app

    frame = pd.read_csv(capred.sample_path("shear"), comment="#")
    v_v, area, height = frame["V_v [cm^3]"], frame["box_area [cm^2]"], 2.0  # cm^3, cm^2, cm
    e = v_v / (area * height - v_v)  # from V_v = A h e/(1 + e)
    frame = frame.drop(columns=["V_v [cm^3]"]).assign(**{"height [mm]": height * 10})
    if given == "e_height":
        frame["e [-]"] = e
    else:
        frame["G_s [-]"] = 2.65
        frame["rho_d [kg/m^3]"] = 2.65 * 1000.0 / (1.0 + e)  # e = G_s rho_w/rho_d - 1
    path = tmp_path / "tests.csv"
    frame.to_csv(path, index=False)
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["shear", str(path), "--bootstrap", "0", "--out", str(out), "--xlsx"])
    assert res.exit_code == 0, res.output
    names = {p.name for p in out.iterdir()}
    assert {"results.csv", "summary.csv", "summary.json", "report.html", "provenance.json", "tables.xlsx"} <= names
    assert any(n.endswith(".png") for n in names)
    table = pd.read_csv(out / "results.csv")
    reference = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)).table()
    # S_R = (V_v - z2)/V_v with V_v rebuilt from e (or rho_d): the same to rounding of the e round trip
    np.testing.assert_allclose(table["S_R [-]"], reference["S_R [-]"], rtol=1e-9, atol=1e-12)
