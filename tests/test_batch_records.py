"""season.csv as typed records (issue 28, item 1): one SeasonRun per run, its headers from the field declarations."""

from __future__ import annotations

import dataclasses
import shutil
from pathlib import Path

import pandas as pd
from typer.testing import CliRunner

import capred
from capred.batch import Outcome, SeasonRun, season_runs, season_table, season_tables
from capred.cli import app

#: season.csv's header as capred 0.x and this release write it (a public interface)
HEADER = ["command", "input", "status", "reason", "material", "headline", "options", "warnings [-]", "report"]


def test_headers_derive_from_the_fields():
    assert [SeasonRun.header(f) for f in dataclasses.fields(SeasonRun)] == HEADER
    assert list(season_table([])) == HEADER  # a batch with no run still has every column


def test_records_of_outcomes(tmp_path):
    """Paths relative to the root; a failed run's reason on one line, no warning count; an ok run's count."""
    root = tmp_path / "batch"
    (root / "a").mkdir(parents=True)
    ok = Outcome("shear", str(tmp_path / "in" / "a.csv"), str(root / "a"), "ok", warnings=2,
                 season=[{"material": "sand", "c_kPa": 1.0}], headline="sand: c 1 kPa")  # fmt: skip
    bad = Outcome("shear", str(tmp_path / "in" / "b.csv"), str(root / "b"), "failed", "line 2: bad\nline 3: bad")
    a, b = season_runs(root, [ok, bad])
    assert (a.input, a.status, a.material, a.warnings, a.reason) == ("../in/a.csv", "ok", "sand", 2, "")
    assert b.warnings is None and b.status == "failed" and b.reason == "line 2: bad | line 3: bad"
    table, details = season_tables(root, [ok, bad])
    assert list(table) == HEADER
    assert list(table["warnings [-]"]) == [2, None]
    assert list(details["shear"]) == ["input", "material", "c [kPa]"]


def test_batch_files_match_the_records(tmp_path):
    """A real batch: season.csv's header is the records' and its rows their values."""
    shutil.copy(capred.sample_path("rumpf"), tmp_path / "r.csv")
    shutil.copy(capred.sample_path("prism"), tmp_path / "p.csv")
    manifest = tmp_path / "m.csv"
    manifest.write_text("command,input,options\nrumpf,r.csv,--no-plots\nprism,p.csv,--no-plots\n")
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["batch", str(manifest), "--out", str(out)])
    assert res.exit_code == 0, res.output
    table = pd.read_csv(out / "season.csv", dtype=str, keep_default_na=False)
    assert list(table.columns) == HEADER
    assert list(table["command"]) == ["rumpf", "prism"] and set(table["status"]) == {"ok"}
    assert list(table["warnings [-]"]) == ["0", "0"]


# --- `capred batch --json` from records (issue 28, items 1 and 4) ------------------------------------------
#: the document's keys as capred 0.x and this release print them (a public interface)
JSON_KEYS = ["files", "index", "failed", "interrupted"]
FILE_KEYS = ["input", "command", "status", "ok", "error", "out_dir", "result"]


def test_batch_json_keys_derive_from_the_fields():
    from capred.batch import BatchDocument, BatchFile

    assert [f.name for f in dataclasses.fields(BatchDocument)] == JSON_KEYS
    assert [f.name for f in dataclasses.fields(BatchFile)] == FILE_KEYS
    ok = Outcome("shear", "a.csv", "/out/a", "ok", result_json={"command": "shear"})
    bad = Outcome("shear", "b.csv", "/out/b", "failed", "line 2: bad")
    stop = Outcome("shear", "c.csv", "/out/c", "interrupted")
    doc = BatchDocument.of([ok, bad, stop], None, wrote=False).to_json()
    assert list(doc) == JSON_KEYS and doc["index"] is None
    assert (doc["failed"], doc["interrupted"]) == (1, 1)
    assert [list(f) for f in doc["files"]] == [FILE_KEYS] * 3
    assert doc["files"][0] == {"input": "a.csv", "command": "shear", "status": "ok", "ok": True, "error": None,
                               "out_dir": None, "result": {"command": "shear"}}  # fmt: skip
    assert doc["files"][1]["error"] == "line 2: bad" and doc["files"][1]["ok"] is False
    assert BatchDocument.of([ok], Path("/b/index.csv"), wrote=True).to_json()["files"][0]["out_dir"] == "/out/a"


def test_batch_json_on_the_command_line(tmp_path):
    import json

    shutil.copy(capred.sample_path("rumpf"), tmp_path / "r.csv")
    shutil.copy(capred.sample_path("prism"), tmp_path / "p.csv")
    manifest = tmp_path / "m.csv"
    manifest.write_text("command,input,options\nrumpf,r.csv,--no-plots\nprism,p.csv,--no-plots\n")
    res = CliRunner().invoke(app, ["batch", str(manifest), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert list(doc) == JSON_KEYS and doc["failed"] == 0
    assert [f["command"] for f in doc["files"]] == ["rumpf", "prism"]
    assert all(list(f) == FILE_KEYS and f["ok"] and f["result"]["command"] == f["command"] for f in doc["files"])


def test_season_detail_headers_come_from_the_one_rule_and_the_glossary():
    from capred.batch import unit_header

    assert unit_header("c [kPa]", [1.0]) == "c [kPa]"  # a record's header is kept
    assert unit_header("alpha_per_kPa", [0.1]) == "alpha [1/kPa]"  # capred.result.csv_header, as every CSV
    assert unit_header("V_w_mm3", [2.0]) == "V_w [mm^3]"  # a suffix the batch's own list used to miss
    assert unit_header("sigma3", [100.0]) == "sigma3 [kPa]"  # a glossary quantity: its output unit
    assert unit_header("n_points", [12]) == "n_points [-]"  # a count
    assert unit_header("branch", ["drying"]) == "branch"  # text
