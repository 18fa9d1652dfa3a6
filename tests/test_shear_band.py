"""Issue 45 part 3: shear-band angles (Coulomb, Roscoe, Arthur) from the envelope, beside measured ones."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.physics import shear_band as sb
from capred.pipelines.calculators import ShearBandOptions, reduce_shear_band

runner = CliRunner()


def test_closed_forms_by_hand():
    """45 + phi'/2, 45 + psi/2, 45 + (phi' + psi)/4 (exact in floating point at these values); Arthur's is the mean
    of the other two; the dilatancy angle from the triaxial rate: d = 0 -> 0, d = 2/3 -> sin psi = 1/4."""
    assert sb.coulomb_angle(30.0) == 60.0 and sb.roscoe_angle(10.0) == 50.0 and sb.arthur_angle(30.0, 10.0) == 55.0
    phi, psi = np.array([25.0, 33.0, 41.0]), np.array([0.0, 7.5, 15.0])
    np.testing.assert_allclose(
        sb.arthur_angle(phi, psi), (sb.coulomb_angle(phi) + sb.roscoe_angle(psi)) / 2, rtol=1e-15
    )
    assert sb.dilatancy_angle_triaxial(0.0) == 0.0
    assert sb.dilatancy_angle_triaxial(2.0 / 3.0) == pytest.approx(np.degrees(np.arcsin(0.25)), rel=1e-14)


def test_prunier_fig14_measured_angles_beside_the_envelope(tmp_path):
    """Prunier et al. (2024), Fig. 14: bands at about 70 deg (simple compression) and 60 deg (100 kPa). A table of
    the two tests with phi' = 30 deg: Coulomb 60 deg meets the confined test, and is 10 deg below the unconfined
    one; the differences are those by hand."""
    f = tmp_path / "bands.csv"
    f.write_text("case,phi_eff,shear_band_angle\nsimple compression,30,70\np0 = 100 kPa,30,60\n")
    res = reduce_shear_band(f, ShearBandOptions())
    doc = res.to_json()
    rows = doc["cases"]
    assert [r["coulomb_deg"] for r in rows] == [60.0, 60.0]
    assert [r["coulomb_minus_measured_deg"] for r in rows] == [-10.0, 0.0]
    assert any("need ψ" in n for n in res.notes)


def test_cli_from_a_triaxial_envelope(tmp_path):
    """phi' read from triaxial-bounds' summary.json (its envelope), psi from the dilatancy rate."""
    out = tmp_path / "tx"
    assert runner.invoke(app, ["triaxial-bounds", "--sample", "--out", str(out), "--no-plots"]).exit_code == 0
    phi = json.loads((out / "summary.json").read_text())["envelope"]["phi_deg"]
    res = runner.invoke(
        app,
        [
            "shear-band",
            "--triaxial",
            str(out / "summary.json"),
            "--dilatancy-rate",
            "0.5",
            "--measured",
            "60",
            "--json",
        ],
    )
    assert res.exit_code == 0, res.output
    row = json.loads(res.output)["cases"][0]
    psi = np.degrees(np.arcsin(0.5 / 2.5))
    assert row["coulomb_deg"] == pytest.approx(45 + phi / 2, rel=1e-14)
    assert row["arthur_deg"] == pytest.approx(45 + (phi + psi) / 4, rel=1e-12)
    both = runner.invoke(app, ["shear-band", "--phi-eff", "30", "--triaxial", str(out / "summary.json")])
    assert both.exit_code == 1 and "not both" in both.output


def test_phi_from_a_capred_triaxial_summary(tmp_path):
    # the envelope of `capred triaxial` (one material) gives phi'; several materials are named with their phi'
    one = tmp_path / "one.json"
    one.write_text(json.dumps({"command": "triaxial", "materials": {"clay": {"envelope": {"phi_deg": 30.0}}}}))
    res = reduce_shear_band(None, ShearBandOptions(triaxial=str(one), dilatancy_angle=10.0))
    assert float(res.cases.coulomb[0]) == 60.0 and float(res.cases.arthur[0]) == 55.0
    two = tmp_path / "two.json"
    mats = {"clay": {"envelope": {"phi_deg": 30.0}}, "sand": {"envelope": {"phi_deg": 36.0}}}
    two.write_text(json.dumps({"command": "triaxial", "materials": mats}))
    out = runner.invoke(app, ["shear-band", "--triaxial", str(two)])
    assert out.exit_code == 1 and "'clay' 30 deg, 'sand' 36 deg" in out.output and "Traceback" not in out.output
