"""Public data nobody here wrote, run as a user runs it: the source's own numbers, CLI with files written, and the API.

The data sets and their sources are in ``tests/data/real/SOURCES.md``; the checks (source value, capred's value,
tolerance and why) in ``tests/real_cases.py``, from which the documentation's "Validated against" table is made.
"""

import csv
import json

import pytest
import real_cases as rc
from conftest import file_hash
from typer.testing import CliRunner

from capred.cli import app

runner = CliRunner()


def _failures(rows):
    return [
        f"{r.dataset}: {r.quantity}: source {r.published!r}, capred {r.capred!r} ({r.difference})"
        for r in rows
        if not r.passed
    ]


def test_retention_fits_reach_unsatfits_optimum():
    rows = rc.retention_rows()
    assert len(rows) == 40  # 4 models x (4 unsatfit samples + 2 pmsim sets + 2 UNSODA soils x 2 branches)
    assert not _failures(rows)


def test_bridge_laws_equal_yades_regression_check():
    rows = rc.bridge_rows()
    assert len(rows) == 3
    assert not _failures(rows)


def test_gdslab_export_peak_and_skempton_a():
    rows = rc.triaxial_rows()
    assert not _failures(rows)


def test_validation_rows_carry_every_field_for_the_documentation():
    rows = rc.validation_rows()
    assert {"dataset", "source", "quantity", "published", "capred", "difference", "tolerance", "passed"} <= set(rows[0])
    assert all(r["passed"] for r in rows)


@pytest.mark.parametrize("name", ["unsatfit_gilat.csv", "unsoda_1410.csv"])
def test_retention_cli_writes_the_fits_the_api_gives(tmp_path, name):
    source = rc.RETENTION / name
    before = file_hash(source)
    out = tmp_path / "out"
    models = ",".join(rc.UNSATFIT_MODELS.values())
    res = runner.invoke(app, ["retention", str(source), "--model", models, "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    assert file_hash(source) == before  # the user's file is never touched
    written = json.loads((out / "fits.json").read_text())
    with (out / "fits.csv").open(encoding="utf-8") as f:
        table = list(csv.DictReader(f))
    api = rc._fits_by_branch(rc._retention_fit(name))
    disk = rc._fits_by_branch(written)
    assert disk.keys() == api.keys()
    rss_header = next(h for h in table[0] if h.startswith("RSS"))
    for branch, fits in api.items():
        for model, fit in fits.items():
            # the same data through the same optimiser on one machine: the file holds the API's optimum (1e-12
            # relative leaves room for JSON's 17 significant digits, nothing more)
            assert disk[branch][model]["rss"] == pytest.approx(fit["rss"], rel=1e-12)
            named = branch or written["main_branch"]  # "" holds the main branch's fits
            row = next(r for r in table if r["model"] == model and r.get("branch", named) == named)
            assert float(row[rss_header]) == pytest.approx(fit["rss"], rel=1e-12)


def test_noisy_unsoda_wetting_branch_is_reported_not_hidden(tmp_path):
    # UNSODA 1301's laboratory wetting branch scatters (unsatfit's best R² 0.85): the run succeeds, the fit's R²
    # is written as computed, and nothing of the file is dropped
    source = rc.RETENTION / "unsoda_1301.csv"
    out = tmp_path / "out"
    res = runner.invoke(app, ["retention", str(source), "--model", "vg", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    js = json.loads((out / "fits.json").read_text())
    wetting = js["branches"]["wetting"]
    assert wetting["n_points"] == 16 and js["branches"]["drying"]["n_points"] == 20
    assert wetting["fits"]["vg"]["r2"] < 0.9


def test_gdslab_export_cli_writes_its_report(tmp_path):
    table = rc.TRIAXIAL / "triax10m_tests.csv"
    export = rc.TRIAXIAL / rc.EXPORT
    before = file_hash(export)
    out = tmp_path / "out"
    res = runner.invoke(
        app, ["triaxial-bounds", str(table), "--curves", str(export), *rc.ENVELOPE_CLI, "--out", str(out), "--no-plots"]
    )
    assert res.exit_code == 0, res.output
    assert file_hash(export) == before
    js = json.loads((out / "summary.json").read_text())
    (test,) = js["tests"]
    assert test["q_kPa"] == pytest.approx(rc.EXPORT_PEAK_Q_KPA, rel=1e-6)
    assert 0.45 <= test["skempton_A"] <= 0.8
    # the export's strains are in per cent without saying so (14.99 at the end: impossible as a fraction)
    assert test["strain_at_failure"] == pytest.approx(rc.EXPORT_PEAK_STRAIN_PERCENT / 100, rel=1e-9)
    assert any("read in per cent" in n for n in js["notes"])
    # its suction, S_R and void-ratio columns hold -u_w, a negative S_R and 0 (no phase data entered): refused,
    # each with a warning, never reported as the specimen's state
    assert test["suction_kPa"] is None and test["S_R"] is None and test["void_ratio"] is None
    for words in ("matric suction", "degree of saturation", "void ratio"):
        assert any(f"export's {words} at failure" in w and "not taken" in w for w in js["warnings"])
    assert (out / "results.csv").is_file() and (out / "provenance.json").is_file()


def test_hostun_sand_scanning_loops_stay_out_of_the_main_curves(tmp_path):
    # Lins et al.'s Hostun sand record, in the order measured: main drying (readings 1-17, to 2.59 kPa), a
    # scanning wetting (18-28, to 0.99 kPa), a scanning drying (29-44) and the main wetting (45-71). The scanning
    # readings are labelled and kept out of the main fits; the main drying curve alone is smooth (R2 >= 0.95)
    source = rc.RETENTION / "pmsim_hostun_sand.csv"
    out = tmp_path / "out"
    res = runner.invoke(app, ["retention", str(source), "--model", "vg", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    js = json.loads((out / "fits.json").read_text())
    assert js["reversals_kPa"][:2] == pytest.approx([2.59, 0.99])
    with (out / "points.csv").open(encoding="utf-8") as f:
        points = list(csv.DictReader(f))
    assert len(points) == 71  # nothing dropped
    branch = [p["branch"] for p in points]
    assert set(branch[17:28]) == {"scanning"}  # readings 18-28, the scanning wetting
    assert js["branches"]["drying"]["fits"]["vg"]["r2"] >= 0.95
