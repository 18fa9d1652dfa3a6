"""A batch's provenance: each file's provenance.json and report.html record the command that reproduces that
file's run alone (``capred shear FILE OPTIONS --out ITS_FOLDER``); the batch root's provenance.json records the
batch's whole command line once (issue 44: every file used to record all N paths, O(N²) in all)."""

import json
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import typer.main
from typer.testing import CliRunner

import capred
from capred.cli import _subcommand, app
from capred.cli.common import file_command_lines

runner = CliRunner()


def _copies(tmp_path: Path, n: int) -> list[Path]:
    (tmp_path / "k").mkdir()
    for k in range(n):
        shutil.copy(capred.sample_path("shear"), tmp_path / "k" / f"t{k}.csv")
    return [Path("k") / f"t{k}.csv" for k in range(n)]


def _capred(args, cwd):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    return subprocess.run([sys.executable, "-m", "capred", *args], cwd=cwd, env=env, capture_output=True, text=True)


def test_each_file_records_its_own_command_and_the_root_the_whole_one(tmp_path):
    files = _copies(tmp_path, 3)
    args = ["shear", *map(str, files), "--no-plots", "--bootstrap", "0", "--gamma-w", "10 kN/m³", "--out", "res"]
    res = _capred(args, tmp_path)
    assert res.returncode == 0, res.stderr
    for k in range(3):
        folder = tmp_path / "res" / f"shear_t{k}"
        line = json.loads((folder / "provenance.json").read_text())["command_line"]
        want = f"capred shear k/t{k}.csv --no-plots --bootstrap 0 --gamma-w '10 kN/m³' --out res/shear_t{k}"
        assert line == want
        others = [f"t{j}.csv" for j in range(3) if j != k]
        assert not any(o in line for o in others)
        html = (folder / "report.html").read_text()
        assert f"capred shear k/t{k}.csv --no-plots --bootstrap 0 --gamma-w &#39;10 kN/m³&#39;" in html
        assert not any(o in html for o in others)
    root = json.loads((tmp_path / "res" / "provenance.json").read_text())["command_line"]
    assert root.endswith("shear k/t0.csv k/t1.csv k/t2.csv --no-plots --bootstrap 0 --gamma-w 10 kN/m³ --out res")

    # the recorded command reproduces the file's run: the same numbers, into the same folder
    folder = tmp_path / "res" / "shear_t1"
    before = (folder / "summary.json").read_bytes()
    line = json.loads((folder / "provenance.json").read_text())["command_line"]
    again = _capred(shlex.split(line)[1:], tmp_path)
    assert again.returncode == 0, again.stderr
    assert (folder / "summary.json").read_bytes() == before


def test_a_manifest_line_gives_its_files_the_line_options(tmp_path, monkeypatch):
    _copies(tmp_path, 3)
    (tmp_path / "m.csv").write_text("command,input,options\nshear,k/*.csv,--no-plots --bootstrap 0 --dry-loss huber\n")
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["batch", "m.csv", "--out", "res"])
    assert res.exit_code == 0, res.output
    for k in range(3):
        line = json.loads((tmp_path / "res" / f"shear_t{k}" / "provenance.json").read_text())["command_line"]
        assert line == f"capred shear k/t{k}.csv --no-plots --bootstrap 0 --dry-loss huber --out res/shear_t{k}"


def test_option_values_are_never_taken_for_inputs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cmd = _subcommand(typer.main.get_command(app), "shear")
    argv = ["capred", "shear", "a.csv", "--curves", "b.csv", "c d.csv", "--no-plots", "--workers", "2", "-o", "r"]
    lines = file_command_lines("shear", [Path("a.csv"), Path("c d.csv")], [Path("r/a"), None], argv, cmd)
    assert lines == [
        "capred shear a.csv --curves b.csv --no-plots --out r/a",
        "capred shear 'c d.csv' --curves b.csv --no-plots",
    ]
    # arguments that are not this command's (the library outside the command line): no per-file line
    assert file_command_lines("shear", [Path("a.csv")], [None], ["pytest", "-q"], cmd) == [None]
