"""Triaxial instrument exports read as they are (issue 39, part 2).

The exports in tests/data/exports are GDSLAB-layout data files (57 columns, the quoted header block) written by
tests/data/exports/make_gdslab_exports.py from the physics of the tests they record (SOURCES.md there):

- ``gdslab_cu_decimal_comma.csv``: a consolidated undrained test as a computer with decimal commas writes it
  (';' delimiter, ``Eff, Axial Stress (kPa)``): saturation ramp, B check (B = 0.96), consolidation to
  sigma'3 = 100 kPa, undrained shear with Δu = B (Δσ3 + A Δq), A = 0.55 at the peak q = 97.3 kPa (4.25 %),
  the cell creeping 3 kPa; its ``B Value`` column is GDSLAB's running Δu/Δσ3 (13 to 177 in the shear stage);
- ``gdslab_unsaturated_cd.csv``: a drained test under axis translation (u_a 300, u_w 250 kPa) logging matric
  suction, degree of saturation and void ratio;
- ``drained_drift/``: three drained tests with back pressure 200 kPa on c' = 5 kPa, phi' = 30 deg, the logged
  cell pressure of D-200 1.3 % above the tests table's sigma3.
"""

import importlib.util
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import CapredWarning, InputError
from capred.io import header_key
from capred.pipelines.triaxial_curves import read_curves

runner = CliRunner()
DATA = Path(__file__).parent / "data" / "exports"
CU = DATA / "gdslab_cu_decimal_comma.csv"
UNSAT = DATA / "gdslab_unsaturated_cd.csv"
DRIFT = DATA / "drained_drift"


def _maker():
    spec = importlib.util.spec_from_file_location("make_gdslab_exports", DATA / "make_gdslab_exports.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_committed_exports_are_what_the_script_writes(tmp_path):
    mk = _maker()
    (tmp_path / "drained_drift").mkdir()
    for p in mk.write_all(tmp_path):
        assert p.read_bytes() == (DATA / p.relative_to(tmp_path)).read_bytes(), p.name
    header = CU.read_text(encoding="utf-8").splitlines()[18]
    assert len(header.split(";")) == 57 and '"Eff, Axial Stress (kPa)"' in header


@pytest.mark.parametrize(
    "spelling", ["Eff. Axial Stress", "Eff, Axial Stress", "Eff Axial Stress", "eff_axial_stress", "EFF.AXIAL STRESS"]
)
def test_export_headers_match_in_any_punctuation(spelling):
    assert header_key(spelling) == "eff_axial_stress"


def _cu_tests(tmp_path, extra=""):
    tests = tmp_path / "tests.csv"
    tests.write_text("test_id,condition,sigma3,q_f" + extra + "\nCU-1,saturated,,\n")
    return tests


def test_gdslab_cu_export_as_exported_gives_the_peak_and_skempton_a(tmp_path):
    out = tmp_path / "out"
    tests = _cu_tests(tmp_path)
    args = ["triaxial-bounds", str(tests), "--curves", str(CU), "--c-eff", "0", "--phi-eff", "30", "--no-plots"]
    res = runner.invoke(app, [*args, "--out", str(out)])
    assert res.exit_code == 0, res.output
    js = json.loads((out / "summary.json").read_text())
    t = js["tests"][0]
    # the peak of the shear stage as the file writes it (4 decimals): q 97.3 kPa at 4.25 %
    assert t["q_kPa"] == pytest.approx(97.3, abs=1e-4) and t["strain_at_failure"] == pytest.approx(0.0425, abs=1e-6)
    # issue 39's criterion, then the value the export was built with: A = 0.55 (Skempton 1954); the file's
    # 4-decimal pressures move A by less than 1e-4
    assert 0.45 <= t["skempton_A"] <= 0.8
    assert t["skempton_A"] == pytest.approx(0.55, abs=1e-4)
    # sigma'3 at failure = radial - pore pressure of the peak's row (400.85 and 352.7203 kPa as written): the
    # table's blank sigma3 filled from the export, the pore pressure subtracted once
    assert t["sigma3_kPa"] == pytest.approx(400.85 - 352.7203, abs=1e-9)
    assert any("Skempton's B = 0.96 from the B check (stage 2" in n for n in js["notes"])
    assert not [w for w in js["warnings"] if "not used" in w or "B Value" in w]
    assert not any("Eff" in w for w in js["warnings"])


def test_the_running_b_value_column_is_never_read_as_b(tmp_path):
    # the shear stage's B Value is Δu over the cell's creep: far above 1 on every row after the first
    c = read_curves(CU)
    st = c.at_peak["CU-1"]
    assert st["B"] == pytest.approx(0.96, abs=1e-4) and st["B_source"] == "b_check"
    table = c.tables[0]
    shear = np.array([s == "4" for s in table.columns["stage"]])
    running = table.get("B")[shear][1:]
    assert running.min() > 10 and running.max() > 150
    # what taking the last row as B gave (the bug): an A nowhere near the export's 0.55
    b_last = running[-1]
    wrong = (st["du"] - b_last * st["dsigma3"]) / (b_last * st["dq"])
    assert not 0.45 <= wrong <= 0.8


def test_a_b_check_outside_zero_one_leaves_a_uncomputed_with_a_warning(tmp_path, monkeypatch):
    mk = _maker()
    monkeypatch.setattr(mk, "CU_B", 1.1)  # a B check whose pore pressure rose more than the cell: B = 1.1
    f = mk.write_cu(tmp_path / "cu.csv")
    tests = _cu_tests(tmp_path)
    given = capred.TriaxialOptions(c_eff=0.0, phi_eff=30.0)
    with pytest.warns(CapredWarning, match=r"gives B = 1\.1, outside \(0, 1\]"):
        r = capred.run_triaxial_bounds(tests, given, curves=f)
    assert np.isnan(r.states.skempton_A[0])  # no A rather than a wrong one
    # the tests table's B wins, and is checked too: 0 < B <= 1
    tests.write_text("test_id,condition,sigma3,q_f,B\nCU-1,saturated,,,0.9\n")
    assert capred.run_triaxial_bounds(tests, given, curves=f).states.skempton_A[0] > 0
    tests.write_text("test_id,condition,sigma3,q_f,B\nCU-1,saturated,,,1.2\n")
    with pytest.raises(InputError, match=r"must lie in \(0, 1\]"):
        capred.run_triaxial_bounds(tests, given, curves=f)


def test_comma_delimited_export_with_comma_in_its_headers(tmp_path):
    # the same test written with ',' delimiters and decimal points, its headers quoted "Eff, Axial Stress"
    mk = _maker()
    f = mk.write_cu(tmp_path / "cu.csv", decimal_comma=False)
    f.write_text(f.read_text(encoding="utf-8").replace('"Eff. ', '"Eff, '), encoding="utf-8")
    c = read_curves(f)
    assert c.problems == [] and c.warnings == []
    assert c.peaks["CU-1"] == pytest.approx((97.3e3, 0.0425), rel=1e-9)


def test_unsaturated_export_feeds_suction_saturation_and_void_ratio(tmp_path):
    tests = tmp_path / "tests.csv"
    tests.write_text("test_id,condition,sigma3,q_f\nUD-50,unsaturated,,\n")
    given = capred.TriaxialOptions(c_eff=0.0, phi_eff=30.0)
    r = capred.run_triaxial_bounds(tests, given, curves=UNSAT)
    t = r.to_json()["tests"][0]
    # built: suction u_a - u_w = 50 kPa at the start of the shear, u_a creeping 1.2 kPa over 12 % (50.6 kPa at
    # the peak, 6 %); e 0.700 -> 0.684 at the peak; S_r = 0.62 x 0.700/0.684 (constant water volume)
    assert t["s0_kPa"] == pytest.approx(50.0, abs=1e-4)
    assert t["suction_kPa"] == pytest.approx(50.6, abs=1e-4)
    assert t["void_ratio"] == pytest.approx(0.684, abs=1e-4)
    assert t["S_R"] == pytest.approx(0.62 * 0.700 / 0.684, abs=1e-6)  # written in % with 4 decimals
    assert t["sigma3_kPa"] == pytest.approx(400 - 300.6, abs=1e-4)  # net of the air pressure at the peak
    notes = r.to_json()["notes"]
    assert any(n.startswith("s0 taken from the export's matric suction") and "UD-50 (50 kPa)" in n for n in notes)
    for words in ("matric suction", "degree of saturation", "void ratio"):
        assert any(n == f"{words} at failure taken from the export: UD-50" for n in notes)
    assert t["skempton_A"] is None  # an unsaturated test: A is not a quantity of it
    assert {"suction [kPa]", "S_R [-]", "void_ratio [-]"} <= set(r.table().columns)
    # the tests table's s0 wins over the export's
    tests.write_text("test_id,condition,sigma3,q_f,s0\nUD-50,unsaturated,,,40\n")
    assert capred.run_triaxial_bounds(tests, given, curves=UNSAT).to_json()["tests"][0]["s0_kPa"] == 40.0


def test_a_drifting_cell_pressure_keeps_the_back_pressure_subtracted(tmp_path):
    tests = tmp_path / "tests.csv"
    tests.write_text("test_id,condition,sigma3\nD-100,saturated,300\nD-200,saturated,400\nD-300,saturated,500\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = capred.run_triaxial_bounds(tests, curves=DRIFT)
    env = r.to_json()["envelope"]
    # truth c' 5 kPa, phi' 30 deg; q written with 4 decimals moves the fit by less than 1e-3 kPa and 1e-4 deg
    assert env["c_kPa"] == pytest.approx(5.0, abs=1e-3) and env["phi_deg"] == pytest.approx(30.0, abs=1e-4)
    assert [t["sigma3_kPa"] for t in r.to_json()["tests"]] == pytest.approx([100.0, 200.0, 300.0], abs=1e-9)
    drift = [w for w in r.warnings if "D-200" in w]
    assert len(drift) == 1
    # both values named, and what was done
    assert "sigma3 = 400 kPa in the table" in drift[0] and "radial pressure at failure is 405.2 kPa" in drift[0]
    assert "+1.3 %" in drift[0] and "the pore pressure 200 kPa is subtracted" in drift[0]
    assert any(drift[0] in str(w.message) for w in caught)  # a Python warning too
    assert any("not computed for tests sheared drained" in n for n in r.notes)  # no A = 0 for drained tests


def test_ignore_column_reaches_every_file_a_command_reads(tmp_path):
    out = tmp_path / "out"
    tests = _cu_tests(tmp_path)
    res = runner.invoke(
        app,
        [
            "triaxial-bounds",
            str(tests),
            "--curves",
            str(CU),
            "--c-eff",
            "0",
            "--phi-eff",
            "30",
            "--no-plots",
            "--ignore-column",
            "Eff, Axial Stress (kPa)",
            "--ignore-column",
            "Nowhere",
            "--out",
            str(out),
        ],
    )
    assert res.exit_code == 0, res.output
    js = json.loads((out / "summary.json").read_text())
    assert "column 'Eff, Axial Stress (kPa)' ignored, as asked" in js["notes"]
    # a name some file has is not warned about; one no file has is warned about once
    assert [w for w in js["warnings"] if w.startswith("ignore_columns")] == [
        "ignore_columns: the header has no column 'Nowhere'"
    ]


def test_ignore_column_reaches_shear_curves(tmp_path):
    tests = tmp_path / "tests.csv"
    # dry tests on tau = 0.5 sigma_N: peaks 5, 10, 15 kPa from the curves
    tests.write_text("test_id,material,condition,sigma_N\nt1,sand,dry,10\nt2,sand,dry,20\nt3,sand,dry,30\n")
    curves = tmp_path / "curves.csv"
    rows = ["test_id,displacement [mm],tau [kPa],Operator"]
    for tid, peak in (("t1", 5.0), ("t2", 10.0), ("t3", 15.0)):
        rows += [f"{tid},{d},{peak * min(d, 2) / 2},AB" for d in (0.5, 1.0, 2.0, 3.0)]
    curves.write_text("\n".join(rows) + "\n")
    res = runner.invoke(
        app,
        ["shear", str(tests), "--curves", str(curves), "--ignore-column", "Operator", "--json", "--no-plots"],
    )
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    assert not [w for w in js["warnings"] if "Operator" in w]  # neither "not used" nor "no column"
    assert js["materials"]["sand"]["phi_deg"] == pytest.approx(np.degrees(np.arctan(0.5)), abs=1e-6)
