"""The one path of every command (issue 9): contract, transactional outputs, digits, console, API units."""

import errno
import json
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from conftest import ROOT
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.reductions import REDUCTIONS

runner = CliRunner()
SHARED_KEYS = {"command", "capred_version", "inputs", "options", "warnings", "notes"}


def _api_run(red):
    """The registry's quick run of a command through the API: its sample (if any) and its example options, run
    once per test session (both tests below compare with it; a bridge command's run costs ~1 s)."""
    from functools import cache

    return cache(
        lambda: capred.run(red.name, capred.sample_path(red.sample) if red.sample else None, **dict(red.example))
    )


# every command of the registry (capred.reductions.REDUCTIONS, so a new command is tested without editing this
# file): its quick run on the command line (Reduction.example_args) and the same run through the API
COMMANDS = {name: ([*red.example_args(), "--no-plots"], _api_run(red)) for name, red in REDUCTIONS.items()}


@pytest.mark.parametrize("command", list(COMMANDS))
def test_cli_json_equals_api_for_every_command(command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args, api = COMMANDS[command]
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc == api().to_json()
    assert SHARED_KEYS <= set(doc) and doc["command"] == command
    assert isinstance(doc["warnings"], list) and isinstance(doc["notes"], list)
    for entry in doc["inputs"]:
        assert re.fullmatch(r"[0-9a-f]{64}", entry["sha256"])
    # --json without --out writes nothing
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command", list(COMMANDS))
def test_written_json_equals_stdout_json(command, tmp_path):
    args, api = COMMANDS[command]
    res = runner.invoke(app, [*args, "--json", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    result = api()
    on_disk = json.loads((tmp_path / "o" / result.json_name).read_text())
    assert on_disk == json.loads(res.stdout)
    prov = json.loads((tmp_path / "o" / "provenance.json").read_text())
    assert _files(tmp_path / "o") == prov["outputs"]


def test_input_named_like_an_output_is_refused(tmp_path, monkeypatch):
    """`cp tests.csv results.csv; capred shear results.csv --out .` must not overwrite the data."""
    monkeypatch.chdir(tmp_path)
    data = tmp_path / "results.csv"
    shutil.copy(capred.sample_path("shear"), data)
    before = data.read_bytes()
    for out in (".", str(tmp_path)):
        res = runner.invoke(app, ["shear", "results.csv", "--out", out, "--no-plots"])
        assert res.exit_code == 1
        assert "Error:" in res.stderr and "Traceback" not in res.output
    # an output folder that holds the input
    res = runner.invoke(app, ["shear", str(data), "--out", str(tmp_path), "--no-plots"])
    assert res.exit_code == 1 and "holds the input" in res.stderr
    assert data.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.csv"]


def test_out_folder_of_other_files_is_refused_and_kept(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("lab notes")
    res = runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(out)])
    assert res.exit_code == 1 and "did not write" in res.stderr
    assert [p.name for p in out.iterdir()] == ["notes.txt"]


def test_out_that_is_a_file_and_too_long_names(tmp_path):
    f = tmp_path / "report"
    f.write_text("x")
    res = runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(f)])
    assert res.exit_code == 1 and "is a file" in res.stderr and f.read_text() == "x"
    res = runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(tmp_path / ("x" * 300))])
    assert res.exit_code == 1 and "too long" in res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]


def test_rerun_replaces_the_folder_whole(tmp_path):
    out = tmp_path / "o"
    assert runner.invoke(app, ["shear", "--sample", "--out", str(out)]).exit_code == 0
    assert any(p.suffix == ".png" for p in out.iterdir())
    assert runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(out)]).exit_code == 0
    # no stale figures of the earlier run, no hidden work folders left beside it
    assert sorted(p.name for p in out.iterdir()) == [
        "metrics.csv",  # the models' scores (summary.csv holds the dry envelopes)
        "provenance.json",
        "report.html",
        "results.csv",
        "summary.csv",
        "summary.json",
    ]
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


def test_full_disk_leaves_the_earlier_run_intact(tmp_path, monkeypatch):
    from capred.io import writers

    out = tmp_path / "o"
    assert runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(out)]).exit_code == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    calls = {"n": 0}
    original = writers.RunFolder.done

    def full(self, name):
        calls["n"] += 1
        if calls["n"] == 2:  # the disk fills up while the second file is written
            raise OSError(errno.ENOSPC, "No space left on device")
        return original(self, name)

    monkeypatch.setattr(writers.RunFolder, "done", full)
    res = runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(out), "--gamma-w", "10"])
    assert res.exit_code == 1
    assert "no space left" in res.stderr and "Traceback" not in res.output
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


def test_interrupted_write_leaves_the_earlier_run_intact(tmp_path, monkeypatch):
    from capred.io import writers

    out = tmp_path / "o"
    assert runner.invoke(app, ["shear", "--sample", "--no-plots", "--out", str(out)]).exit_code == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def interrupted(self, name):
        raise KeyboardInterrupt

    monkeypatch.setattr(writers.RunFolder, "done", interrupted)
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(gamma_w="10 kN/m^3"))
    with pytest.raises(KeyboardInterrupt):
        capred.write_outputs(result, out, plots=False)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


def _files(out: Path) -> list[str]:
    return sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())


def _complete(out: Path) -> bool:
    """A folder holding exactly the files its provenance lists, all from that run."""
    prov = json.loads((out / "provenance.json").read_text())
    return _files(out) == prov["outputs"]


def _capred(*args) -> list[str]:
    return [sys.executable, "-m", "capred", *args]


@pytest.mark.slow
def test_killed_reruns_never_leave_a_mixed_folder(tmp_path):
    """SIGKILL at random moments of a rerun: --out holds one complete run, the earlier or the new one."""
    out = tmp_path / "o"
    subprocess.run(_capred("shear", "--sample", "--out", str(out)), check=True, capture_output=True)
    first = json.loads((out / "provenance.json").read_text())["options"]["gamma_w"]
    for delay in (0.6, 0.9, 1.2, 1.5, 1.8):
        proc = subprocess.Popen(
            _capred("shear", "--sample", "--gamma-w", "10", "--out", str(out)),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        time.sleep(delay)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        assert _complete(out)
        gamma = json.loads((out / "provenance.json").read_text())["options"]["gamma_w"]
        summary = json.loads((out / "summary.json").read_text())
        assert gamma in (first, 10000.0) and summary["options"]["gamma_w"] == gamma
    # the next run sweeps the work folders the killed runs left behind
    subprocess.run(_capred("shear", "--sample", "--no-plots", "--out", str(out)), check=True, capture_output=True)
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


@pytest.mark.slow
def test_concurrent_runs_into_one_folder_do_not_mix(tmp_path):
    out = tmp_path / "o"
    procs = [
        subprocess.Popen(
            _capred("shear", "--sample", "--gamma-w", g, "--out", str(out)),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        for g in ("9.81", "10")
    ]
    for p in procs:
        assert p.wait() == 0, p.stderr.read()
    assert _complete(out)
    gamma = json.loads((out / "provenance.json").read_text())["options"]["gamma_w"]
    assert json.loads((out / "summary.json").read_text())["options"]["gamma_w"] == gamma
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


def test_batch_with_a_crashing_file_runs_the_others(tmp_path, monkeypatch):
    from capred import batch

    runs = tmp_path / "runs"
    runs.mkdir()
    for name in ("a", "boom", "c"):
        shutil.copy(capred.sample_path("shear"), runs / f"{name}.csv")
    original = batch.run_job

    def crashing(job):
        if "boom" in str(job.source):
            raise ZeroDivisionError("a bug")
        return original(job)

    monkeypatch.setattr(batch, "run_job", crashing)
    out = tmp_path / "out"
    res = runner.invoke(app, ["shear", str(runs / "*.csv"), "--no-plots", "--out", str(out)])
    assert res.exit_code == 1
    index = pd.read_csv(out / "index.csv")
    status = index.groupby("input")["status"].first()
    assert status["../runs/boom.csv"] == "crashed"  # inputs relative to the batch root
    assert status["../runs/a.csv"] == status["../runs/c.csv"] == "ok"
    log = (out / "shear_boom" / "errors.log").read_text()
    assert "ZeroDivisionError: a bug" in log and "Traceback" in log


def test_batch_interrupted_still_writes_the_index(tmp_path, monkeypatch):
    from capred import batch

    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(4):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    original = batch.run_safely
    seen = []

    def ctrl_c(job):
        seen.append(job)
        if len(seen) == 3:
            raise KeyboardInterrupt
        return original(job)

    monkeypatch.setattr(batch, "run_safely", ctrl_c)
    out = tmp_path / "out"
    # one worker: the patched job runs in this process (workers would not see the patch)
    res = runner.invoke(app, ["shear", str(runs / "*.csv"), "--no-plots", "--workers", "1", "--out", str(out)])
    assert res.exit_code == 130
    index = pd.read_csv(out / "index.csv")
    by_input = index.groupby("input")["status"].first()
    assert list(by_input.sort_index()) == ["ok", "ok", "interrupted", "interrupted"]
    assert not (out / "shear_s2").exists() and not (out / "shear_s3").exists()


def test_material_names_give_unique_file_names(tmp_path):
    text = capred.sample_path("shear").read_text().replace("steel_2mm", "a/b").replace("sand_208-417um", "a_b")
    (tmp_path / "t.csv").write_text(text)
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    pngs = sorted(p.name for p in (tmp_path / "o").glob("report_*.png"))
    assert pngs == ["report_a_b.png", "report_a_b_2.png"]


def test_numbers_keep_their_digits(tmp_path):
    """A bridge volume of 3.44675e-11 mm^3 must not be written as 3.4e-11 (issue 9)."""
    from capred.io.writers import encode_csv, encode_json

    x = 3.44675e-11
    assert json.loads(encode_json({"v": x}))["v"] == x
    assert float(encode_csv(pd.DataFrame({"v": [x, 1 / 3]})).decode().splitlines()[1]) == x
    assert float(encode_csv(pd.DataFrame({"v": [1 / 3]})).decode().splitlines()[1]) == 1 / 3
    # end to end: a micrometre bridge; JSON and CSV equal the exact values to the last bit
    (tmp_path / "b.csv").write_text("R [um],contact_angle,gap,suction\n1,0,0,50\n")
    res = capred.solve_bridges(tmp_path / "b.csv")
    exact = float(res.volume[0] * 1e9)
    assert exact < 1e-8  # a tiny volume in mm^3
    capred.write_outputs(res, tmp_path / "o")
    assert json.loads((tmp_path / "o" / "solve.json").read_text())["bridges"][0]["V_w_mm3"] == exact
    assert pd.read_csv(tmp_path / "o" / "solve.csv")["V_w [mm^3]"][0] == exact


def test_piped_console_never_truncates_numbers(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["retention", "--sample", "--no-plots"])
    # no number cut ('0.03…'): an ellipsis never appears (a range prints 'low to high')
    assert res.exit_code == 0 and "…" not in res.stdout
    assert "0.0383 to 0.0591" in res.stdout  # a 95 % interval of the sample's drying S_res, whole
    assert "alpha_per_kPa" in res.stdout  # the unit is in the parameter name, written whole


def test_narrow_terminal_folds_columns_not_digits():
    from rich.console import Console

    from capred.report.render import render_tables
    from capred.result import TableSpec

    spec = TableSpec("wide", [("case", "left")] + [(f"column_{k} [kPa]", "right") for k in range(12)])
    spec.rows.append(["A-1"] + [f"{123456.789 * (k + 1):.10g}" for k in range(12)])
    con = Console(width=80, force_terminal=True, record=True, color_system=None)
    render_tables([spec], con)
    text = con.export_text()
    assert "…" not in text
    for k in range(12):
        assert f"{123456.789 * (k + 1):.10g}" in text
    assert max(len(line) for line in text.splitlines()) <= 80


def test_per_row_tables_show_twenty_rows(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rows = "\n".join(f"c{k},1,0,0,{10 + k}" for k in range(60))
    (tmp_path / "many.csv").write_text("case,R,contact_angle,gap,suction\n" + rows + "\n")
    res = runner.invoke(app, ["bridge", "solve", "many.csv", "--out", "o"])
    assert res.exit_code == 0, res.output
    assert "c19" in res.stdout and "c20" not in res.stdout
    assert "first 20 of 60 rows" in res.stdout and "solve.csv" in res.stdout


@pytest.mark.parametrize("value", [9810.0, "9.81 kN/m^3", "9810 N/m^3", "1 gf/cm^3"])
def test_api_options_take_numbers_strings_and_quantities(value):
    assert capred.ShearOptions(gamma_w=value).gamma_w == pytest.approx(9810.0, rel=1e-3)


def test_api_options_take_pint_quantities():
    import pint

    ureg = pint.UnitRegistry()
    opt = capred.ShearOptions(gamma_w=10 * ureg("kN/m^3"), radius=156 * ureg.um)
    assert opt.gamma_w == pytest.approx(10_000.0) and opt.radius == pytest.approx(156e-6)


@pytest.mark.parametrize(
    "kw,message",
    [
        ({"gamma_w": "10 kPa"}, "not a unit of unit weight"),
        ({"gamma_w": "ten"}, "not a number"),
        ({"gamma_w": [1, 2]}, "expected a number"),
        ({"gamma_w": -1.0}, "must be >"),
        ({"radius": "0 mm"}, "particle radius must be >"),
        ({"models": ("own3",)}, "unknown model"),
    ],
)
def test_api_option_errors_are_option_errors(kw, message):
    with pytest.raises(capred.OptionError, match=message):
        capred.ShearOptions(**kw)


def test_implausible_unit_weight_warns_in_json():
    """ShearOptions(gamma_w=10) is 10 N/m^3 (SI), not the CLI's kN/m^3: said in the warnings."""
    doc = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(gamma_w=10)).to_json()
    assert any("gamma_w" in w and "check its unit" in w for w in doc["warnings"])
    assert not any("gamma_w" in w for w in capred.run_shear(capred.sample_path("shear")).to_json()["warnings"])


def test_no_user_facing_text_names_a_seed_file():
    texts = [p.read_text(encoding="utf-8") for p in (ROOT / "capred").rglob("*.py")]
    texts.append((ROOT / "README.md").read_text(encoding="utf-8"))
    for name in [*dict.fromkeys(n.split()[0] for n in REDUCTIONS), "batch"]:  # every command and group
        texts.append(runner.invoke(app, [name, "--help"]).stdout)
    pattern = re.compile(r"seed\s*0\d\d|seed's|the seeds?\b|0b13a170|65a0ce3c|5775559b", re.I)
    for text in texts:
        assert not pattern.search(text), pattern.search(text).group(0)


def test_new_model_is_one_registry_entry():
    from capred.physics import effective_stress_models as esm

    e = esm.REGISTRY["bishop"]
    assert e.reference in __import__("capred.references").references.REFERENCES
    assert set(esm.THESIS_MODELS) == {"no_suction", "bishop", "own1", "own2"}


def test_every_command_has_help_with_an_example():
    for args in [*(name.split() for name in REDUCTIONS), ["batch"]]:
        res = runner.invoke(app, [*args, "--help"])
        assert res.exit_code == 0 and "Example: capred" in res.stdout
