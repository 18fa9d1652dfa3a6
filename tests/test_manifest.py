"""Batch manifests (issue 19, item 4): every malformed manifest is one clear error naming the file, the line and
the column, never a traceback; a manifest with no runs is an error; a Windows-1252 manifest is read as data
files are."""

import shutil

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import InputError
from capred.io.manifest import read_manifest

runner = CliRunner()


def _problems(path):
    with pytest.raises(InputError) as info:
        read_manifest(path)
    return info.value.problems


def test_read_manifest_csv_row_shorter_than_its_header(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("command,input,options\nshear,a.csv,--no-plots\nshear\nretention,r.csv\n")
    (p,) = _problems(path)  # line 4 lacks only its options: a run with none, as before
    assert (p.file, p.line, p.column) == (str(path), 3, "input")
    assert "1 field but the header has 3" in p.message


def test_read_manifest_csv_extra_fields_are_not_dropped(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("command,input,options\nshear,a.csv,--gamma-w 10,--no-plots\n")
    (p,) = _problems(path)  # the '--no-plots' after an unquoted comma would be lost without a word
    assert p.line == 2 and "4 fields" in p.message and "quote the options" in p.message


def test_read_manifest_csv_header_near_miss(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("command,input,option\nshear,a.csv,--no-plots\n")
    (p,) = _problems(path)
    assert (p.line, p.column) == (1, "option") and "did you mean 'options'" in p.message


def test_read_manifest_latin1_is_read_like_a_data_file(tmp_path):
    path = tmp_path / "m.csv"
    path.write_bytes("command,input,options\nshear,résumé.csv,--no-plots\n".encode("cp1252"))
    assert read_manifest(path) == [(2, "shear", "résumé.csv", "--no-plots")]


@pytest.mark.parametrize(
    "text,line,column,words",
    [
        ("run = 5\n", 1, "run", "not a number"),
        ('title = "season"\nrun = "shear"\n', 2, "run", "not a string"),
        ('[run]\ncommand = "shear"\ninput = "a.csv"\n', 1, "run", "[[run]]"),
        ('[[run]]\ncommand = "shear"\n', 1, "input", "needs 'input'"),
        ('[[run]]\ncommand = "shear"\ninput = 5\n', 3, "input", "non-empty string"),
        ('[[run]]\ncommand = "shear"\ninput = "a.csv"\noptions = 3\n', 4, "options", "string or a list"),
        ('[[run]]\ncommand = "shear"\ninput = "a.csv"\noption = "--no-plots"\n', 1, "option", "unknown key"),
        ('[[run]]\ncommand = "shear"\ninput = "a.csv"\n[[run]]\ncommand = "shear"\n', 4, "input", "number 2"),
        ("[[run]\n", 1, None, "not valid TOML"),
    ],
)
def test_read_manifest_toml_wrong_types_name_line_and_column(tmp_path, text, line, column, words):
    path = tmp_path / "m.toml"
    path.write_text(text)
    (p,) = _problems(path)
    assert (p.line, p.column) == (line, column) and words in p.message


@pytest.mark.parametrize(
    "name,text",
    [
        ("m.csv", "command,input,options\n"),
        ("m.csv", "command,input,options\n# x\n"),
        ("m.toml", "# nothing yet\n"),
        ("m.toml", ""),
    ],
)
def test_read_manifest_without_runs_is_an_error(tmp_path, name, text):
    (tmp_path / name).write_text(text)
    (p,) = _problems(tmp_path / name)
    assert "no runs" in p.message or "is empty" in p.message


def test_read_manifest_toml_lines_are_those_of_the_runs(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(
        '# season\n\n[[run]]\ncommand = "shear"\ninput = "a.csv"\n\n[[run]]\ncommand = "retention"\n'
        'input = "r.csv"\noptions = ["--model", "vg", 2]\n'
    )
    assert read_manifest(path) == [(3, "shear", "a.csv", ""), (7, "retention", "r.csv", ["--model", "vg", "2"])]


@pytest.mark.parametrize(
    "name,text,expect",
    [
        ("m.toml", "run = 5\n", "m.toml, line 1, column 'run'"),
        ("m.csv", "command,input,options\nshear\n", "m.csv, line 2, column 'input'"),
        ("m.csv", "command,input,options\n", "no runs"),
    ],
)
def test_batch_bad_manifest_is_one_message(tmp_path, name, text, expect):
    (tmp_path / name).write_text(text)
    res = runner.invoke(app, ["batch", str(tmp_path / name), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and expect in res.stderr and "Traceback" not in res.output
    assert res.exception is None or isinstance(res.exception, SystemExit)


def test_batch_latin1_manifest_runs(tmp_path):
    shutil.copy(capred.sample_path("retention"), tmp_path / "rétention.csv")
    (tmp_path / "m.csv").write_bytes(
        "command,input,options\nretention,rétention.csv,--model vg --no-plots\n".encode("cp1252")
    )
    res = runner.invoke(app, ["batch", str(tmp_path / "m.csv"), "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
