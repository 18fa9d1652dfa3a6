"""capred triaxial-bounds end to end: outputs, JSON keys, curves, groups, bad input."""

import json

import numpy as np
import pytest
from conftest import file_hash
from numpy.testing import assert_allclose
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.physics import triaxial as tx

runner = CliRunner()
SAT = (
    "test_id,condition,sigma3,q_f\n"
    "s1,saturated,30,75.7\ns2,saturated,50,119.6\ns3,saturated,100,229.1\ns4,saturated,150,338.7\n"
)


def test_triaxial_sample_writes_outputs(tmp_path):
    res = runner.invoke(app, ["triaxial-bounds", "--sample", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert {"results.csv", "summary.json", "report.png", "provenance.json"} <= {p.name for p in tmp_path.iterdir()}
    assert "UB EDTP" in res.output


def test_triaxial_json_keys(tmp_path):
    res = runner.invoke(app, ["triaxial-bounds", "--sample", "--json", "--no-plots", "--out", str(tmp_path)])
    assert res.exit_code == 0
    js = json.loads(res.stdout)
    assert set(js["envelope"]) >= {"c_kPa", "phi_deg", "M", "k_kPa", "c_se_kPa", "phi_se_deg"}
    t = [x for x in js["tests"] if x["condition"] == "unsaturated"][0]
    assert set(t) >= {"test_id", "sigma3_kPa", "sigma1_kPa", "p_kPa", "q_kPa", "spherical", "lower", "edtp"}
    keys = {"sigma1_cap_kPa", "sigma3_cap_kPa", "p_cap_kPa", "q_cap_kPa", "p_prime_kPa", "q_prime_kPa", "gain"}
    for b in ("spherical", "lower", "edtp"):
        assert set(t[b]) >= keys
    # p = (sigma1 + 2 sigma3)/3 for the p0 = 0 test: sigma1 = q = 150.2
    assert t["p_kPa"] == pytest.approx(150.2 / 3, rel=1e-9)


def test_triaxial_envelope_from_options_and_no_s0(write_csv):
    data = write_csv("test_id,condition,sigma3,sigma1\nu1,unsaturated,0,150.2\n")
    res = runner.invoke(
        app,
        [
            "triaxial-bounds",
            str(data),
            "--c-eff",
            "2.795",
            "--phi-eff",
            "31.523",
            "--json",
            "--no-plots",
            "--out",
            str(data.parent / "o"),
        ],
    )
    assert res.exit_code == 0, res.output
    t = json.loads(res.stdout)["tests"][0]
    assert t["edtp"] is None
    assert t["spherical"]["p_cap_kPa"] == pytest.approx(-64.0, abs=0.5)  # Table 2, p0 = 0


def test_triaxial_curves_give_peak_and_strain(tmp_path):
    tests = tmp_path / "t.csv"
    text = capred.sample_path("triaxial-bounds").read_text().splitlines()
    # drop q_f of the unsaturated tests: the curves must supply the peaks
    out = [
        ",".join(c if not (k == 3 and "unsaturated" in ln) else "" for k, c in enumerate(ln.split(",")))
        if not ln.startswith("#")
        else ln
        for ln in text
    ]
    tests.write_text("\n".join(out) + "\n")
    res = runner.invoke(
        app,
        [
            "triaxial-bounds",
            str(tests),
            "--curves",
            str(capred.sample_path("triaxial-curves")),
            "--json",
            "--no-plots",
            "--out",
            str(tmp_path / "o"),
        ],
    )
    assert res.exit_code == 0, res.output
    js = {t["test_id"]: t for t in json.loads(res.stdout)["tests"]}
    # the synthetic curves peak at the failure deviators, at eps_a = 2 + p0/100 %
    assert js["UNSAT-0"]["q_kPa"] == pytest.approx(150.2, abs=1e-9)
    assert js["UNSAT-100"]["strain_at_failure"] == pytest.approx(0.03, abs=1e-12)
    assert js["UNSAT-150"]["q_kPa"] == pytest.approx(396.7, abs=1e-9)


def test_triaxial_group_spherical_tensor_recovered(write_csv):
    c, phi = 2.795e3, 31.523
    rows = [SAT.strip()]
    for k, s3 in enumerate((20e3, 80e3, 140e3)):
        s1 = tx.sigma1_at_failure(s3 + 30e3, c, phi) - 30e3  # shared spherical tensor -30 kPa
        rows.append(f"g{k},unsaturated,{s3 / 1e3},{float(s1 - s3) / 1e3!r},A")
    rows[0] = rows[0].replace("q_f\n", "q_f,group\n", 1)
    data = write_csv("\n".join(rows) + "\n")
    res = runner.invoke(app, ["triaxial-bounds", str(data), "--json", "--no-plots", "--out", str(data.parent / "o")])
    assert res.exit_code == 0, res.output
    g = json.loads(res.stdout)["groups"][0]
    assert g["n"] == 3 and g["eq49_holds"]
    # the saturated q_f are rounded to 0.1 kPa, so the fitted c', phi' carry ~0.1 % error
    assert g["eq37_sigma_cap_kPa"] == pytest.approx(-30.0, abs=0.5)
    assert g["phi_difference_deg"] == pytest.approx(0.0, abs=0.05)
    assert g["lode_angles_deg"] == pytest.approx([0, 0, 0], abs=1e-3)


BAD = {
    "no_envelope": ("test_id,condition,sigma3,q_f\nu1,unsaturated,0,150\n", ["no saturated test", "--c-eff"]),
    "q_nonpositive": (SAT + "u1,unsaturated,0,-3\n", ["line 6", "column 'q_f'", "must be > 0"]),
    "sigma3_negative": (SAT + "u1,unsaturated,-10,100\n", ["line 6", "column 'sigma3'", "negative"]),
    "unknown_condition": (SAT + "u1,partly,0,100\n", ["line 6", "'partly' is not one of"]),
    "group_of_one": (
        SAT.replace("q_f\n", "q_f,group\n") + "u1,unsaturated,0,150,A\n",
        ["line 6", "column 'group'", "group 'A' has one test"],
    ),
    "missing_sigma3": (
        "test_id,condition,sigam3,q_f\nu1,unsaturated,0,150\n",
        ["missing column 'sigma3'", "did you mean"],
    ),
    "text_in_number": (SAT + "u1,unsaturated,zero,150\n", ["line 6", "'zero' is not a number"]),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_triaxial_bad_input(case, tmp_path, write_csv):
    text, expected = BAD[case]
    data = write_csv(text, "bad.csv")
    before = file_hash(data)
    res = runner.invoke(app, ["triaxial-bounds", str(data), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1
    assert res.stderr.startswith("Error:") and "Traceback" not in res.stderr
    for piece in expected:
        assert piece in res.stderr, (piece, res.stderr)
    assert not (tmp_path / "o").exists() and file_hash(data) == before


def test_triaxial_bad_options():
    res = runner.invoke(app, ["triaxial-bounds", "--sample", "--c-eff", "3"])
    assert res.exit_code == 1 and "both --c-eff and --phi-eff" in res.stderr


def test_triaxial_api_matches_cli(tmp_path):
    api = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds")).to_json()
    res = runner.invoke(app, ["triaxial-bounds", "--sample", "--json", "--no-plots", "--out", str(tmp_path)])
    cli = json.loads(res.stdout)
    assert cli["tests"] == api["tests"] and cli["envelope"] == api["envelope"]
    assert np.isfinite(api["envelope"]["c_se_kPa"])


# --- pore pressures, export cross-checks, membrane (issue 23, item 5) -------------------------------
def _gavet(**extra):
    """The Gavet sample as a DataFrame with plain column names, optionally shifted and extended."""
    import pandas as pd

    t = pd.read_csv(capred.sample_path("triaxial-bounds"), comment="#")
    t.columns = [c.split(" [")[0] for c in t.columns]
    for k, v in extra.items():
        t[k] = v
    return t


def test_triaxial_back_pressure_gives_the_envelope_without_it(tmp_path):
    # saturated rows: sigma3 and p0 are cell pressures with u_b = 200 kPa; unsaturated rows: axis translation
    # with u_a = 200 kPa. Subtracting them gives back the sample, whose envelope is c' = 2.795 kPa.
    plain = capred.run_triaxial_bounds(_gavet()).to_json()
    shifted = _gavet()
    shifted["sigma3"] += 200
    shifted["p0"] += 200
    bare = capred.run_triaxial_bounds(shifted)
    # without a word about the back pressure the fit is the one the issue quotes: c' = -119.9 kPa, now warned
    assert bare.to_json()["envelope"]["c_kPa"] == pytest.approx(-119.9, abs=0.05)
    assert any("c' = -119.9 kPa < 0" in w and "back_pressure" in w for w in bare.warnings)
    shifted["back_pressure"] = [200.0] * 4 + [None] * 3
    shifted["u_a"] = [None] * 4 + [200.0] * 3
    csv = tmp_path / "bp.csv"
    shifted.to_csv(csv, index=False)
    res = runner.invoke(app, ["triaxial-bounds", str(csv), "--json", "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    # 230 - 200 = 30 exactly in binary floating point, so the envelope is the same to the last digit
    for key in ("c_kPa", "phi_deg", "c_se_kPa", "phi_se_deg"):
        assert js["envelope"][key] == pytest.approx(plain["envelope"][key], rel=1e-12, abs=1e-9)
    for a, b in zip(js["tests"], plain["tests"]):
        for bound in ("spherical", "lower", "edtp"):
            if a[bound]:
                assert a[bound]["sigma3_cap_kPa"] == pytest.approx(b[bound]["sigma3_cap_kPa"], abs=1e-9)
    assert js["tests"][0]["sigma3_total_kPa"] == 230.0 and js["tests"][0]["back_pressure_kPa"] == 200.0
    assert js["tests"][4]["u_a_kPa"] == 200.0 and js["tests"][4]["sigma3_kPa"] == 0.0
    assert not any("c' =" in w for w in json.loads((tmp_path / "o" / "summary.json").read_text())["warnings"])


def _export(folder, tid, radial, back=None, q_peak=100.0, eps_peak=5.0):
    """An instrument export whose deviator rises linearly to q_peak at eps_peak % and then falls."""
    folder.mkdir(exist_ok=True)
    head = "Axial Strain (%),Deviator Stress (kPa),Radial Pressure (kPa)" + (",Back Pressure (kPa)" if back else "")
    rows = [f"Test ID: {tid}", "Initial diameter (mm): 38", "", head]
    for eps in (0.0, 1.0, 2.0, 3.0, 4.0, eps_peak, eps_peak + 1):
        q = q_peak * eps / eps_peak if eps <= eps_peak else 0.9 * q_peak
        rows.append(f"{eps},{q},{radial}" + (f",{back}" if back else ""))
    (folder / f"{tid}.csv").write_text("\n".join(rows) + "\n")


def test_triaxial_sigma3_against_export_radial_pressure(tmp_path, write_csv):
    rows = SAT.replace("s4,saturated,150,338.7\n", "s4,saturated,30,\n")
    data = write_csv(rows, "t.csv")
    _export(tmp_path / "exp", "s4", 230.0, q_peak=75.7)
    r = capred.run_triaxial_bounds(data, curves=tmp_path / "exp")
    # 30 against 230 kPa is far outside ASTM D4767's 2 kPa: warned, the table's 30 kept
    assert any("'s4': sigma3 = 30 kPa" in w and "radial pressure at failure is 230 kPa" in w for w in r.warnings)
    assert r.to_json()["tests"][3]["radial_pressure_kPa"] == 230.0
    # the same export with a back pressure of 200 kPa: 30 = 230 - 200, the table is already effective
    _export(tmp_path / "exp2", "s4", 230.0, back=200.0, q_peak=75.7)
    r = capred.run_triaxial_bounds(data, curves=tmp_path / "exp2")
    assert not any("radial pressure" in w for w in r.warnings)
    assert any("already effective" in n for n in r.notes)
    assert r.to_json()["tests"][3]["sigma3_kPa"] == 30.0
    # within the tolerance (231 vs 230 kPa, tolerance 2.3 kPa) the table is total: no warning
    data2 = write_csv(rows.replace("s4,saturated,30,", "s4,saturated,231,"), "t2.csv")
    given = capred.pipelines.triaxial.TriaxialOptions(c_eff=2795.0, phi_eff=31.523)
    assert not any("radial" in w for w in capred.run_triaxial_bounds(data2, given, curves=tmp_path / "exp").warnings)


def test_triaxial_back_pressure_from_the_export(tmp_path, write_csv):
    # a saturated test whose table gives the cell pressure; the export holds the back pressure
    rows = SAT.replace("s4,saturated,150,338.7\n", "s4,saturated,350,\n")
    data = write_csv(rows, "t.csv")
    _export(tmp_path / "exp", "s4", 350.0, back=200.0, q_peak=338.7)
    js = capred.run_triaxial_bounds(data, curves=tmp_path / "exp").to_json()
    ref = capred.run_triaxial_bounds(write_csv(SAT, "ref.csv")).to_json()
    s4 = js["tests"][3]
    assert s4["sigma3_kPa"] == pytest.approx(150.0, abs=1e-9) and s4["back_pressure_kPa"] == 200.0
    # the same four effective failure states: the same envelope (floating point only)
    assert js["envelope"]["c_kPa"] == pytest.approx(ref["envelope"]["c_kPa"], rel=1e-9)


def test_triaxial_membrane_correction_by_hand(tmp_path, write_csv):
    # ASTM D4767: dq = 4 E_m t_m eps_a / D = 4 * 1400 kPa * 0.2 mm * 0.05 / 38 mm = 1.47368 kPa
    data = write_csv(
        "test_id,condition,sigma3,q_f,strain_at_failure [%],D0 [mm]\n"
        "s1,saturated,30,75.7,5,38\ns2,saturated,50,119.6,5,38\ns3,saturated,100,229.1,5,38\n"
        "u1,unsaturated,0,150.2,5,38\n"
    )
    res = runner.invoke(app, ["triaxial-bounds", str(data), "--json", "--no-plots", "--out", str(tmp_path / "o")])
    js0 = json.loads(res.stdout)
    assert any(
        "no membrane correction" in n for n in json.loads((tmp_path / "o" / "summary.json").read_text())["notes"]
    )
    opts = capred.pipelines.triaxial.TriaxialOptions(membrane_thickness="0.2 mm", membrane_modulus="1400 kPa")
    js = capred.run_triaxial_bounds(data, opts).to_json()
    dq = 4 * 1400 * 0.2 * 0.05 / 38
    for a, b in zip(js["tests"], js0["tests"]):
        assert a["membrane_correction_kPa"] == pytest.approx(dq, rel=1e-12)  # arithmetic only
        assert a["q_kPa"] == pytest.approx(b["q_kPa"] - dq, rel=1e-12)
    assert any("membrane correction" in n and "0.2 mm" in n for n in capred.run_triaxial_bounds(data, opts).notes)


def test_triaxial_membrane_correction_of_curves_before_the_peak(tmp_path, write_csv):
    # the curve rises to 100 kPa at 5 % and falls to 90 kPa at 6 %: the correction grows with strain, so the
    # corrected peak is 100 - dq(5 %) (dq(6 %) = 1.768 kPa does not lift the 6 % reading above it)
    data = write_csv("test_id,condition,sigma3,q_f\nu1,unsaturated,30,\n", "t.csv")
    _export(tmp_path / "exp", "u1", 30.0)
    opts = capred.pipelines.triaxial.TriaxialOptions(
        c_eff=2795.0, phi_eff=31.523, membrane_thickness=0.2e-3, membrane_modulus=1400e3
    )
    t = capred.run_triaxial_bounds(data, opts, curves=tmp_path / "exp").to_json()["tests"][0]
    assert t["q_kPa"] == pytest.approx(100 - 4 * 1400 * 0.2 * 0.05 / 38, rel=1e-12)
    assert t["strain_at_failure"] == pytest.approx(0.05, rel=1e-12)


BAD_PORE = {
    "u_a_on_saturated": (
        SAT.replace("q_f\n", "q_f,u_a\n").replace("75.7\n", "75.7,10\n"),
        ["line 2", "u_a is for unsaturated tests"],
    ),
    "back_pressure_unsat_without_u_a": (
        SAT.replace("q_f\n", "q_f,back_pressure\n") + "u1,unsaturated,0,150,50\n",
        ["line 6", "give the pore-air pressure 'u_a'"],
    ),
    "negative_effective_sigma3": (
        SAT.replace("q_f\n", "q_f,back_pressure\n").replace("75.7\n", "75.7,50\n"),
        ["line 2", "effective confining stress", "negative"],
    ),
    "membrane_without_strain": (SAT, ["needs 'strain_at_failure' and 'D_c' (or 'D0')"]),
}


@pytest.mark.parametrize("case", sorted(BAD_PORE))
def test_triaxial_pore_pressure_problems(case, tmp_path, write_csv):
    text, expected = BAD_PORE[case]
    data = write_csv(text, "bad.csv")
    extra = ["--c-eff", "1", "--phi-eff", "30"] if case != "membrane_without_strain" else []
    opts = (
        capred.pipelines.triaxial.TriaxialOptions(membrane_thickness=0.2e-3, membrane_modulus=1400e3)
        if case == "membrane_without_strain"
        else None
    )
    with pytest.raises(capred.CapredError) as exc:
        capred.run_triaxial_bounds(data, opts)
    for piece in expected:
        assert piece in str(exc.value), (piece, str(exc.value))
    del extra


def test_triaxial_membrane_options_both_or_neither():
    with pytest.raises(capred.CapredError, match="both --membrane-thickness and --membrane-modulus"):
        capred.pipelines.triaxial.TriaxialOptions(membrane_thickness=0.2e-3)
    with pytest.raises(capred.CapredError, match="must be > 0"):
        capred.pipelines.triaxial.TriaxialOptions(membrane_thickness=-1.0, membrane_modulus=1e6)


# --- the consolidated diameter of the membrane correction and the extension path (issue 30.7) ----------------
MEMBRANE = "test_id,condition,sigma3,q_f,strain_at_failure [%],D0 [mm],H0 [mm],{extra}\n" + (
    "s1,saturated,30,75.7,5,38,76,{a}\ns2,saturated,50,119.6,5,38,76,{b}\ns3,saturated,100,229.1,5,38,76,{c}\n"
)


def test_membrane_correction_uses_the_diameter_after_consolidation(write_csv):
    opts = capred.pipelines.triaxial.TriaxialOptions(membrane_thickness="0.2 mm", membrane_modulus="1400 kPa")
    # D_c given (s1), from dV_c = 5 cm^3 isotropically (s2), from dV_c with H_c = 75 mm (s3)
    data = write_csv(MEMBRANE.format(extra="D_c [mm],dV_c [cm^3],H_c [mm]", a="36,,", b=",5,", c=",5,75"))
    r = capred.run_triaxial_bounds(data, opts)
    v0 = np.pi * 19.0**2 * 76.0 / 1e3  # initial volume [cm^3] = 86.19
    d_c = [
        36.0,
        38.0 * (1 - 5 / v0) ** (1 / 3),  # isotropic: every length scales by the cube root of the volume
        np.sqrt(4 * (v0 - 5) * 1e3 / (np.pi * 75.0)),  # A_c = V_c / H_c
    ]
    # ASTM D4767: dq = 4 E_m t_m eps_a / D_c [kPa]; arithmetic only
    assert_allclose(r.states.membrane_correction, [4 * 1400 * 0.2 * 0.05 / d for d in d_c], rtol=1e-12)
    assert not any("initial diameter D0" in n for n in r.notes)
    # without D_c or dV_c the initial diameter is used, and the notes name the tests
    bare = capred.run_triaxial_bounds(write_csv(MEMBRANE.format(extra="dV_c [cm^3]", a="", b="", c=""), "b.csv"), opts)
    assert_allclose(bare.states.membrane_correction, 4 * 1400 * 0.2 * 0.05 / 38.0, rtol=1e-12)
    assert any("initial diameter D0" in n and "s1, s2, s3" in n for n in bare.notes)
    assert any("D_c" in p for p in bare.method_notes()[0])


def test_membrane_volume_change_beyond_the_specimen_is_an_error(write_csv):
    opts = capred.pipelines.triaxial.TriaxialOptions(membrane_thickness="0.2 mm", membrane_modulus="1400 kPa")
    data = write_csv(MEMBRANE.format(extra="dV_c [cm^3]", a="90", b="1", c="1"))
    with pytest.raises(capred.CapredError, match=r"line 2, column 'dV_c.*volume decrease during consolidation"):
        capred.run_triaxial_bounds(data, opts)


def test_extension_path_is_settable_by_hand(tmp_path, write_csv):
    # c' = 0, phi' = 30 deg (K_p = 3), extension test from p'0 = 300 kPa, s0 = 20 kPa.
    # axial-unloading (slope -3): sigma'1 = sigma'2 = 300, sigma'3 = 100 -> q'_sat = 200 kPa.
    # radial-loading (slope 3/2): sigma'3 = 300 (axial), sigma'1 = sigma'2 = 900 -> q'_sat = 600 kPa;
    #   q = (M_e p0 + k_e)/(1 - M_e/1.5) = (6/7 * 300)/(3/7) = 600. EDTP from p'0 = 320: sigma'3 = 320,
    #   sigma'1 = 960 -> caps 300 - 960 = -660 (sigma1, sigma2), 50 - 320 = -270 (sigma3).
    data = write_csv("test_id,condition,sigma3,sigma1,sigma2,p0,s0\nx1,unsaturated,50,300,300,300,20\n")
    tol = dict(rtol=1e-12, atol=1e-9)  # closed forms, floating point only
    for path, q_sat, edtp in (
        ("axial-unloading", 200.0, [-20.0, -20.0, 50 - 320 / 3]),
        ("radial-loading", 600.0, [-660.0, -660.0, -270.0]),
    ):
        opts = capred.pipelines.triaxial.TriaxialOptions(c_eff=0.0, phi_eff=30.0, extension_path=path)
        r = capred.run_triaxial_bounds(data, opts)
        t = r.to_json()["tests"][0]
        assert_allclose(t["q_sat_kPa"], q_sat, **tol)
        assert_allclose([t["edtp"][f"sigma{k}_cap_kPa"] for k in (1, 2, 3)], edtp, **tol)
        assert any(path in p and "slope" in p for p in r.method_notes()[0])  # the methods text states it
    res = runner.invoke(
        app,
        ["triaxial-bounds", str(data), "--c-eff", "0", "--phi-eff", "30", "--extension-path", "radial-loading"]
        + ["--json", "--no-plots", "--out", str(tmp_path / "o")],
    )
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["tests"][0]["q_sat_kPa"] == pytest.approx(600.0, rel=1e-12)
    bad = runner.invoke(app, ["triaxial-bounds", str(data), "--extension-path", "sideways", "--out", str(tmp_path)])
    assert bad.exit_code != 0 and "axial-unloading, radial-loading" in bad.output


def test_triaxial_curves_honour_max_megabytes(tmp_path):
    """--max-megabytes reaches the --curves file (it was read within the 256 MiB default whatever the run asked): a
    1.5 MiB curves file is refused under --max-megabytes 1 before it is read, naming it and the limit; nothing
    written. The tests table itself is small and within the limit."""
    curves = tmp_path / "curves.csv"
    curves.write_text(capred.sample_path("triaxial-curves").read_text() + "\n" * int(1.5 * 2**20))
    res = runner.invoke(
        app, ["triaxial-bounds", str(capred.sample_path("triaxial-bounds")), "--curves", str(curves),
              "--max-megabytes", "1", "--no-plots", "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code == 1 and "--max-megabytes" in res.stderr and "limit of 1 MiB" in res.stderr, res.output
    assert str(curves) in res.stderr and "Traceback" not in res.output
    assert not (tmp_path / "o").exists()
