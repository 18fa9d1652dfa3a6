"""`capred bridge compare` draws on the one law registry (issue 42): every closed-form law of
`capred.spec.bridge_laws.LAWS` is compared with the measured forces, beside the exact bridge."""

import csv
import json

import numpy as np
import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.physics import bridge_laws as bl
from capred.pipelines import bridge as pb

runner = CliRunner()


def _micro_tests(tmp_path):
    # two equal spheres (R = 1 mm) at 10 um and a sphere on a plane, water 0.005 mm^3, theta = 20 deg
    f = tmp_path / "m.csv"
    f.write_text(
        "R [mm],R2 [mm],contact_angle,gap [mm],V_w [mm^3],F_cap [mN]\n1,1,20,0.01,0.005,0.4\n1,inf,20,0.01,0.005,0.8\n"
    )
    return f


def test_compare_has_every_registered_law(tmp_path):
    row_sphere, row_plane = pb.compare_measured(_micro_tests(tmp_path)).rows()
    for name, law in bl.LAWS.items():
        # by hand: F = 2 pi R gamma * law(theta, V/R^3, D/R, R2/R), gamma of water at 20 C
        for row, rho, geometry in ((row_sphere, 1.0, "equal"), (row_plane, np.inf, "plane")):
            F = 2 * np.pi * 1e-3 * 0.0728 * law.force(np.radians(20.0), 0.005 / 1.0, 0.01, rho) * 1e3  # mN
            if geometry in law.geometries:
                assert row[f"F_{name}_mN"] == pytest.approx(float(F), rel=1e-12), name  # one formula, rounding
                assert row[f"residual_{name}_mN"] == pytest.approx(float(F) - row["F_measured_mN"], rel=1e-12)
            else:
                assert row[f"F_{name}_mN"] is None, name  # e.g. Soulie and Mikami: sphere pairs only


def test_compare_willett_column_is_the_registrys_simple_law(tmp_path):
    # the historical F_willett column (Willett et al. 2000, simple form, Derjaguin's R*) is the registry's
    # willett_simple: two implementations of one equation agree to rounding
    for row in pb.compare_measured(_micro_tests(tmp_path)).rows():
        assert row["F_willett_mN"] == pytest.approx(row["F_willett_simple_mN"], rel=1e-12)


def test_a_law_registered_at_run_time_is_compared(monkeypatch, tmp_path):
    law = bl.Law(
        "toy_contact",
        "Toy contact",
        "Israelachvili (2011), Intermolecular and Surface Forces, 3rd ed.",
        "10.1016/C2009-0-21560-1",
        "F/(2πR*γ) = cos θ",
        "spheres in contact",
        ("equal", "unequal", "plane"),
        lambda theta, V, D, rho: bl.effective_radius(rho) * np.cos(theta) + 0.0 * V * D,
    )
    monkeypatch.setitem(bl.LAWS, "toy_contact", law)
    out = tmp_path / "o"
    res = runner.invoke(app, ["bridge", "compare", str(_micro_tests(tmp_path)), "--out", str(out)])
    assert res.exit_code == 0, res.output
    rows = json.loads((out / "compare.json").read_text(encoding="utf-8"))["comparison"]
    # Israelachvili's limit with R* (R for equal spheres, 2R on a plane) [mN]
    want = [2 * np.pi * 1e-3 * 0.0728 * np.cos(np.radians(20.0)) * k * 1e3 for k in (1.0, 2.0)]
    assert [r["F_toy_contact_mN"] for r in rows] == pytest.approx(want, rel=1e-12)
    assert [r["F_israelachvili_mN"] for r in rows] == pytest.approx(want, rel=1e-12)  # the same limit
    with (out / "compare.csv").open(encoding="utf-8-sig", newline="") as fh:
        header = next(csv.reader(fh))
    assert "F_toy_contact [mN]" in header and "residual_toy_contact [mN]" in header


def test_compare_console_rates_each_law_by_its_residuals(tmp_path):
    from capred.report.bridge_tables import bridge_compare_tables

    res = pb.compare_measured(_micro_tests(tmp_path))
    rows = res.rows()
    _, laws = bridge_compare_tables(res)
    assert [r[0] for r in laws.rows] == [law.label for law in bl.LAWS.values()]
    for line, name in zip(laws.rows, bl.LAWS):
        # by hand from the JSON rows: the pairs a law applies to, RMS and mean of its residuals [mN]
        r = np.array([row[f"residual_{name}_mN"] for row in rows if row[f"residual_{name}_mN"] is not None])
        assert line[1] == str(r.size) and r.size in (1, 2)  # Soulie and Mikami: the sphere pair alone
        assert float(line[2]) == pytest.approx(np.sqrt(np.mean(r**2)), rel=5e-4)  # printed to 4 digits
        assert float(line[3]) == pytest.approx(np.mean(r), rel=5e-4)
