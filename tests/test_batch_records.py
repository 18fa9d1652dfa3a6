"""season.csv as typed records (issue 28, item 1): one SeasonRun per run, its headers from the field declarations."""

from __future__ import annotations

import dataclasses
import shutil

import pandas as pd
from typer.testing import CliRunner

import capred
from capred.batch import Outcome, SeasonRun, season_runs, season_table, season_tables
from capred.cli import app

#: season.csv's header as capred 0.x and this release write it (a public interface)
HEADER = ["command", "input", "status", "reason", "material", "headline", "warnings [-]", "report"]


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
