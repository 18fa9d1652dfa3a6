"""capred.batch: worker count, per-file refusals before computing, crashed folders a rerun may replace, the batch's
record of its root files."""

import json
import os
import shutil
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred import batch
from capred.cli import app

runner = CliRunner()


def _jobs(tmp_path: Path, n: int, root: str = "out") -> list:
    runs = tmp_path / "runs"
    runs.mkdir(exist_ok=True)
    sources = []
    for k in range(n):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
        sources.append(runs / f"s{k}.csv")
    dirs = batch.output_dirs(["shear"] * n, sources, tmp_path / root)
    options = capred.ShearOptions(bootstrap=0)
    return [batch.Job("shear", s, d, options, plots=False) for s, d in zip(sources, dirs)]


def test_default_workers_is_one_per_core_at_most_one_per_job():
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    assert batch.default_workers(1) == 1
    assert batch.default_workers(1000) == cores
    assert batch.default_workers(0) == 1


def test_default_run_all_uses_the_cores_and_writes_the_same_files(tmp_path):
    jobs = _jobs(tmp_path, 3, "auto")
    outcomes, interrupted = batch.run_all(jobs)  # workers=None: one per core
    assert not interrupted and [o.status for o in outcomes] == ["ok"] * 3
    serial = [
        batch.Job(j.command, j.source, tmp_path / "serial" / j.out_dir.name, j.options, plots=False) for j in jobs
    ]
    batch.run_all(serial, workers=1)
    for a, b in zip(jobs, serial):
        assert (a.out_dir / "results.csv").read_bytes() == (b.out_dir / "results.csv").read_bytes()
    assert [o.source for o in outcomes] == [str(j.source) for j in jobs]  # input order kept


def test_a_folder_capred_may_not_replace_is_refused_before_computing(tmp_path, monkeypatch):
    job = _jobs(tmp_path, 1)[0]
    job.out_dir.mkdir(parents=True)
    (job.out_dir / "notes.txt").write_text("mine")
    calls = []
    from capred.reductions import REDUCTIONS

    monkeypatch.setattr(type(REDUCTIONS["shear"]), "run", lambda self, *a: calls.append(a))
    outcome = batch.run_safely(job)
    assert outcome.status == "failed" and "notes.txt" in outcome.message
    assert calls == [] and (job.out_dir / "notes.txt").read_text() == "mine"


def test_a_crashed_jobs_folder_is_replaced_by_the_next_run(tmp_path, monkeypatch):
    job = _jobs(tmp_path, 1)[0]
    original = batch.run_job

    def boom(j):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(batch, "run_job", boom)
    assert batch.run_safely(job).status == "crashed"
    prov = json.loads((job.out_dir / "provenance.json").read_text())
    assert prov["outputs"] == ["errors.log", "provenance.json"] and prov["status"] == "crashed"
    monkeypatch.setattr(batch, "run_job", original)
    assert batch.run_safely(job).status == "ok"  # the errors.log folder was capred's: replaced
    assert not (job.out_dir / "errors.log").exists() and (job.out_dir / "results.csv").exists()


def test_root_file_stays_recognised_when_its_replacement_is_interrupted(tmp_path, monkeypatch):
    """The record holds the old and the new hash while a root file changes: a batch killed then leaves a
    file the next batch still recognises as its own."""
    from capred.io import writers

    root = tmp_path / "out"
    writers.write_batch_file(root, "season.csv", b"input\nA\n")
    assert writers.foreign_batch_files(root) == []

    original = writers.atomic_write_bytes

    def killed(path, data):
        if Path(path).name == "season.csv":
            raise KeyboardInterrupt  # after the record names both hashes, before the new file is in place
        return original(path, data)

    monkeypatch.setattr(writers, "atomic_write_bytes", killed)
    with pytest.raises(KeyboardInterrupt):
        writers.write_batch_file(root, "season.csv", b"input\nB\n")
    monkeypatch.undo()
    assert (root / "season.csv").read_bytes() == b"input\nA\n"
    assert len(writers.batch_record(root)["season.csv"]) == 2 and writers.foreign_batch_files(root) == []
    writers.write_batch_file(root, "season.csv", b"input\nB\n")
    assert len(writers.batch_record(root)["season.csv"]) == 1 and writers.foreign_batch_files(root) == []


def test_batch_cli_writes_its_provenance_beside_the_index(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(2):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    (tmp_path / "m.csv").write_text(f"command,input,options\nshear,{runs}/*.csv,--no-plots --bootstrap 0\n")
    out = tmp_path / "o"
    res = runner.invoke(app, ["batch", str(tmp_path / "m.csv"), "--out", str(out)])
    assert res.exit_code == 0, res.output
    prov = json.loads((out / "provenance.json").read_text())
    assert prov["outputs"] == ["index.csv", "provenance.json", "season.csv", "season.html", "season_shear.csv"]
    assert prov["runs"] == ["shear_s0", "shear_s1"]
    index = pd.read_csv(out / "index.csv")
    assert set(index["status"]) == {"ok"}


def test_season_counts_stay_whole_numbers_in_a_mixed_batch(tmp_path):
    """season.csv of a shear + retention batch: counts are integers where a run has them and empty where it has
    none (they were written 12.0 because the retention rows have no n_dry). The sample's steel has 12 dry and
    14 wet tests (sample_data/shear_tests.csv, counted by hand); the retention sample's drying branch 16 points."""
    manifest = tmp_path / "runs.csv"
    manifest.write_text(
        "command,input,options\n"
        f"shear,{capred.sample_path('shear')},--no-plots --bootstrap 0\n"
        f"retention,{capred.sample_path('retention')},--no-plots\n"
    )
    res = CliRunner().invoke(app, ["batch", str(manifest), "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    shear = pd.read_csv(tmp_path / "out" / "season_shear.csv", dtype=str, keep_default_na=False)
    steel = shear[shear["material"] == "steel_2mm"].iloc[0]
    assert (steel["n_dry [-]"], steel["n_wet [-]"]) == ("12", "14")
    retention = pd.read_csv(tmp_path / "out" / "season_retention.csv", dtype=str, keep_default_na=False)
    drying = retention[retention["branch"] == "drying"].iloc[0]
    assert drying["n_points [-]"] == "16" and "n_dry [-]" not in retention  # one kind of record per table
    html = (tmp_path / "out" / "season.html").read_text()
    assert "12.0" not in html and "<NA>" not in html
