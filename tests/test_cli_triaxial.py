"""capred triaxial-bounds end to end: outputs, JSON keys, curves, groups, bad input."""
import json

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.physics import triaxial as tx
from conftest import file_hash

runner = CliRunner()
SAT = ("test_id,condition,sigma3,q_f\n"
       "s1,saturated,30,75.7\ns2,saturated,50,119.6\ns3,saturated,100,229.1\ns4,saturated,150,338.7\n")


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
    res = runner.invoke(app, ["triaxial-bounds", str(data), "--c-eff", "2.795", "--phi-eff", "31.523", "--json",
                              "--no-plots", "--out", str(data.parent / "o")])
    assert res.exit_code == 0, res.output
    t = json.loads(res.stdout)["tests"][0]
    assert t["edtp"] is None
    assert t["spherical"]["p_cap_kPa"] == pytest.approx(-64.0, abs=0.5)  # Table 2, p0 = 0


def test_triaxial_curves_give_peak_and_strain(tmp_path):
    tests = tmp_path / "t.csv"
    text = capred.sample_path("triaxial-bounds").read_text().splitlines()
    # drop q_f of the unsaturated tests: the curves must supply the peaks
    out = [",".join(c if not (k == 3 and "unsaturated" in ln) else "" for k, c in enumerate(ln.split(",")))
           if not ln.startswith("#") else ln for ln in text]
    tests.write_text("\n".join(out) + "\n")
    res = runner.invoke(app, ["triaxial-bounds", str(tests), "--curves", str(capred.sample_path("triaxial-curves")),
                              "--json", "--no-plots", "--out", str(tmp_path / "o")])
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
    "group_of_one": (SAT.replace("q_f\n", "q_f,group\n") + "u1,unsaturated,0,150,A\n",
                     ["line 6", "column 'group'", "group 'A' has one test"]),
    "missing_sigma3": ("test_id,condition,sigam3,q_f\nu1,unsaturated,0,150\n", ["missing column 'sigma3'", "did you mean"]),
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
