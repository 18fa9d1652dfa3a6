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
            row = next(r for r in table if r["model"] == model and r.get("branch", "") in (branch, ""))
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
    assert (out / "results.csv").is_file() and (out / "provenance.json").is_file()
