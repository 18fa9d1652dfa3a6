"""The samples that are capred outputs (sample_data/generate_results.py): `capred retention-convert --sample`
reads the fits.json of `capred retention --sample`, `capred history --sample` a small lab store; a store is
only ever read by history, never changed (the sample ships inside the package)."""

import hashlib
import json
import sqlite3

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred import lab_store
from capred.cli import app

runner = CliRunner()
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")  # the planted run warns


def _digest(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_retention_fits_sample_is_the_fits_json_of_the_retention_sample():
    """The bundled fits.json holds the parameters `capred retention --sample` fits today (regenerate it with
    sample_data/generate_results.py when the fits change). rtol 1e-6: the same optimiser on the same data,
    written with 17 significant digits; only a change of the fit moves them."""
    doc = json.loads(capred.sample_path("retention-convert").read_text(encoding="utf-8"))
    fresh = capred.run_retention(capred.sample_path("retention"))
    assert doc["command"] == "retention"
    assert [i["path"] for i in doc["inputs"]] == ["retention.csv"]  # no path of the machine that made it
    assert set(doc["branches"]) == set(fresh.fits) == {"drying", "wetting"}
    for branch, fits in fresh.fits.items():
        assert set(doc["branches"][branch]["fits"]) == set(fits)
        for model, fit in fits.items():
            for name, p in fit.params.items():
                stored = doc["branches"][branch]["fits"][model][name]
                assert stored == pytest.approx(p.value, rel=1e-6), (branch, model, name)


def test_retention_convert_sample_runs(tmp_path):
    res = runner.invoke(app, ["retention-convert", "--sample", "--to", "bc", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    out = json.loads((tmp_path / "o" / "fits.json").read_text(encoding="utf-8"))
    assert set(out["fits"]) == {"bc"}


def test_history_sample_flags_its_planted_run_and_is_left_untouched(tmp_path):
    """12 days of dry shear tests of one sand; day 9's friction angle was shifted by +3 deg (about 10 times
    the day-to-day scatter of 0.3 deg, so far beyond the 3-sigma limits set by days 1-8): it alone is flagged.
    The store ships inside the package: the run changes neither its bytes nor its folder."""
    store = capred.sample_path("history")
    assert store.stat().st_size < 300_000
    before, folder = _digest(store), sorted(p.name for p in store.parent.iterdir())
    res = runner.invoke(app, ["history", "--sample", "--quantity", "phi_deg", "--out", str(tmp_path / "h")])
    assert res.exit_code == 0, res.output
    doc = json.loads((tmp_path / "h" / "history.json").read_text(encoding="utf-8"))
    assert doc["material"] == "Toyoura sand" and len(doc["runs"]) == 12
    assert doc["flagged_runs"] == [9]
    assert [r["test_date"] for r in doc["runs"]] == [f"2026-03-{d:02d}" for d in range(1, 13)]
    assert _digest(store) == before
    assert sorted(p.name for p in store.parent.iterdir()) == folder  # no -wal, -shm or -journal beside it


def test_history_of_an_old_schema_reads_it_without_migrating_it(tmp_path):
    """A query reads a schema-1 store (no test_date column) through a migrated copy in memory: the file keeps
    its bytes and schema; the next recorded run migrates it in place."""
    store = tmp_path / "old.sqlite"
    con = sqlite3.connect(store)
    for sql in lab_store.MIGRATIONS[0]:
        con.execute(sql)
    con.execute(f"PRAGMA application_id = {lab_store.APPLICATION_ID}")
    con.execute("PRAGMA user_version = 1")
    con.execute(
        "INSERT INTO runs (run_key, command, created_utc, capred_version, inputs, options, metadata, document) "
        "VALUES ('k1', 'shear', '2026-01-05T10:00:00+00:00', '0.0.9', '[]', '{}', ?, '{}')",
        (json.dumps({"date": "2025-12-24"}),),
    )
    con.execute("INSERT INTO records VALUES (1, 'sand', 'phi_deg', 35.1, 34.5, 35.7, 'deg')")
    con.commit()
    con.close()
    before = _digest(store)
    frame = capred.history(store, quantity="phi_deg")
    assert frame["test_date"].tolist() == ["2025-12-24"] and frame["value"].tolist() == [35.1]
    assert _digest(store) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.sqlite"]
    con = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    assert con.execute("PRAGMA user_version").fetchone()[0] == 1
    con.close()


def test_history_of_a_missing_store_is_an_error_and_creates_nothing(tmp_path):
    with pytest.raises(capred.InputError, match="no capred store"):
        capred.history(tmp_path / "none.sqlite")
    assert list(tmp_path.iterdir()) == []


def test_sample_store_values_match_the_recorded_documents():
    """Each record of the sample is the run's own JSON value (phi_deg of its material block)."""
    con = lab_store.connect_readonly(capred.sample_path("history"))
    rows = con.execute(
        "SELECT r.value, u.document FROM records r JOIN runs u ON u.id = r.run WHERE r.quantity = 'phi_deg'"
    ).fetchall()
    con.close()
    assert len(rows) == 12
    for value, document in rows:
        assert value == json.loads(document)["materials"]["Toyoura sand"]["phi_deg"]
    assert np.isfinite([v for v, _ in rows]).all()


def test_every_sample_file_ships_in_the_wheel():
    """Each bundled sample matches a package-data pattern of capred.sample_data (pyproject.toml), so that
    `capred COMMAND --sample` works from an installed wheel, not only from this checkout."""
    import fnmatch
    import tomllib

    from conftest import ROOT

    from capred.samples import SAMPLES, sample_path

    data = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]["package-data"]
    for key, name in SAMPLES.items():
        path = sample_path(key)
        if path.is_dir():  # a folder of files: its own package (capred.sample_data.<folder>)
            patterns, files = data[f"capred.sample_data.{name}"], [p.name for p in path.iterdir() if p.is_file()]
        else:
            patterns, files = data["capred.sample_data"], [name]
        for f in files:
            assert any(fnmatch.fnmatch(f, pat) for pat in patterns), (key, f)
