"""Issue 6: the Python API equals the CLI, DataFrames in, batches, manifests."""

import json
import shutil

import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.reductions import REDUCTIONS

runner = CliRunner()


def _cli_json(args, tmp_path):
    res = runner.invoke(app, [*args, "--json", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


#: keys that say where the rows came from: the file's path, hash and line numbers (a DataFrame has row numbers)
WHERE = {"source", "inputs", "line", "first_line", "last_line"}


def _without_where(doc):
    """A JSON document without the keys that say where its rows came from (WHERE), at any depth."""
    if isinstance(doc, dict):
        return {k: _without_where(v) for k, v in doc.items() if k not in WHERE}
    if isinstance(doc, list):
        return [_without_where(v) for v in doc]
    return doc


@pytest.mark.parametrize("command", list(REDUCTIONS))
def test_every_command_equals_the_api_on_a_dataframe(command, tmp_path):
    """Every command of the registry (capred.reductions.REDUCTIONS: a new command is tested without editing this
    file): its quick run on the command line (Reduction.example_args, on the sample file) gives the JSON of the same
    run through the API (Reduction.run with the example options) on a DataFrame of the sample's rows, but for the
    source, the inputs' hashes and line numbers (tests/test_one_path.py compares the API on the file itself). A
    command whose sample is not a CSV table (a folder, a fits.json, a database) or without input runs on it."""
    red = REDUCTIONS[command]
    path = capred.sample_path(red.sample) if red.sample else None
    frame = pd.read_csv(path, comment="#") if path is not None and path.suffix.lower() == ".csv" else None
    api = red.run(path if frame is None else frame, red.options(**dict(red.example))).to_json()
    cli = _cli_json([*red.example_args(), "--no-plots"], tmp_path)
    if frame is None:
        assert cli == api
    else:
        assert api["source"] == "<DataFrame>" and cli["source"] == str(path)
        assert _without_where(cli) == _without_where(api)


def test_api_accepts_a_dataframe():
    path = capred.sample_path("shear")
    frame = pd.read_csv(path, comment="#")
    a = capred.run_shear(path).to_json()
    b = capred.run_shear(frame).to_json()
    assert b["source"] == "<DataFrame>"
    assert a["materials"] == b["materials"] and a["metrics"] == b["metrics"]
    assert capred.run_shear(frame).table().shape[0] == len(frame)


def test_api_raises_input_error_with_problems(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("test_id,condition,sigma_N,tau_max\na,dry,1,x\n")
    with pytest.raises(capred.InputError) as info:
        capred.run_shear(bad)
    p = info.value.problems[0]
    assert (p.line, p.column) == (2, "tau_max") and "not a number" in p.message


def test_batch_of_files_one_bad(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(3):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    (runs / "bad.csv").write_text("test_id,z1\nA,not-a-number\n")
    out = tmp_path / "out"
    res = runner.invoke(app, ["shear", str(runs / "*.csv"), "--no-plots", "--out", str(out)])
    assert res.exit_code == 1
    assert "bad.csv, line 2, column 'z1'" in res.stderr
    assert "3 of 4 files reduced" in res.stdout
    for k in range(3):
        assert (out / f"shear_s{k}" / "results.csv").exists()
    index = pd.read_csv(out / "index.csv")
    assert set(index["status"]) == {"ok", "failed"}
    assert (index["status"] == "failed").sum() == 1
    assert not (out / "shear_bad").exists()


def test_batch_workers_give_the_same_files(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(4):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    for w in (1, 2):
        res = runner.invoke(
            app,
            [
                "shear",
                *map(str, sorted(runs.glob("*.csv"))),
                "--no-plots",
                "--workers",
                str(w),
                "--out",
                str(tmp_path / f"w{w}"),
            ],
        )
        assert res.exit_code == 0, res.output
    for k in range(4):
        a = (tmp_path / "w1" / f"shear_s{k}" / "results.csv").read_bytes()
        assert a == (tmp_path / "w2" / f"shear_s{k}" / "results.csv").read_bytes()


def test_batch_json_lists_every_file(tmp_path):
    files = [str(capred.sample_path("shear"))] * 1 + [str(tmp_path / "missing.csv")]
    res = runner.invoke(app, ["shear", *files, "--json", "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1
    js = json.loads(res.stdout)
    assert [f["ok"] for f in js["files"]] == [True, False]
    assert js["files"][0]["result"]["best_model"] and "file not found" in js["files"][1]["error"]


def test_manifest_csv_and_toml(tmp_path):
    shutil.copy(capred.sample_path("shear"), tmp_path / "a.csv")
    shutil.copy(capred.sample_path("triaxial-bounds"), tmp_path / "t.csv")
    (tmp_path / "m.csv").write_text(
        "command,input,options\n# a comment\nshear,a.csv,--gamma-w 10 --no-plots\ntriaxial-bounds,t.csv,--no-plots\n"
    )
    res = runner.invoke(app, ["batch", str(tmp_path / "m.csv"), "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    prov = json.loads((tmp_path / "o" / "shear_a" / "provenance.json").read_text())
    assert prov["options"]["gamma_w"] == pytest.approx(10_000.0)
    assert (tmp_path / "o" / "triaxial_t" / "summary.json").exists()
    (tmp_path / "m.toml").write_text(
        '[[run]]\ncommand = "retention"\ninput = "{}"\noptions = ["--model", "vg"]\n'.format(
            capred.sample_path("retention")
        )
    )
    res = runner.invoke(app, ["batch", str(tmp_path / "m.toml"), "--out", str(tmp_path / "o2"), "--json"])
    assert res.exit_code == 0, res.output
    assert set(json.loads(res.stdout)["files"][0]["result"]["fits"]) == {"vg"}


def test_manifest_errors_name_the_line(tmp_path):
    (tmp_path / "m.csv").write_text(
        "command,input,options\nshear,a.csv,\nfrobnicate,b.csv,\nshear,x.csv,--no-such-option\n"
    )
    res = runner.invoke(app, ["batch", str(tmp_path / "m.csv")])
    assert res.exit_code == 1
    assert "m.csv, line 3, column 'command'" in res.stderr
    assert "m.csv, line 4, column 'options'" in res.stderr and "no-such-option" in res.stderr
