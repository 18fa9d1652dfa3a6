"""Errors that help (issue 29, item 6): the same problem in many cells is one message with the count, the first
lines and a hint; a table that is another command's input says which command to try."""

import json

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import InputError, Problem

runner = CliRunner()
HEAD = "test_id,material,condition,sigma_N [kPa],tau_max [kPa]\n"


def test_a_dutch_condition_column_is_one_message_per_word_with_a_hint(tmp_path):
    p = tmp_path / "nl.csv"
    p.write_text(HEAD + "".join(f"t{i},m,{'droog' if i % 2 else 'nat'},{10 + i},{5 + i}\n" for i in range(40)))
    with pytest.raises(InputError) as err:
        capred.run_shear(p)
    assert len(err.value.problems) == 40  # scripts (--json) get every cell
    assert str(err.value).splitlines()[1:] == [
        f"  - {p}, column 'condition': 'nat' is not one of 'dry' or 'wet' or 'saturated' ('nat' is Dutch for "
        "'wet': write 'wet') (in 20 lines: 2, 4, 6, 8, 10, ...)",
        f"  - {p}, column 'condition': 'droog' is not one of 'dry' or 'wet' or 'saturated' ('droog' is Dutch for "
        "'dry': write 'dry') (in 20 lines: 3, 5, 7, 9, 11, ...)",
    ]


@pytest.mark.parametrize(("word", "means"), [("sec", "French for 'dry'"), ("nass", "German for 'wet'")])
def test_one_foreign_word_gets_its_hint_too(tmp_path, word, means):
    p = tmp_path / "t.csv"
    p.write_text(HEAD + f"a,m,{word},10,5\nb,m,dry,20,11\n")
    with pytest.raises(InputError, match=means):
        capred.run_shear(p)


def test_decimal_commas_in_a_comma_delimited_file_suggest_a_semicolon(tmp_path):
    p = tmp_path / "dc.csv"
    p.write_text(HEAD + "".join(f't{i},m,dry,{10 + i},"{5 + i},5"\n' for i in range(10)))
    res = runner.invoke(app, ["shear", str(p), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1
    assert "10 cells are not numbers (lines 2, 3, 4, 5, 6, ...: '5,5', '6,5'" in res.output
    assert "save it with ';' as the delimiter" in res.output
    assert len(res.output.splitlines()) <= 3  # one line, not ten


def test_the_same_message_in_many_lines_is_shown_once():
    probs = [Problem("f.csv", n, "x", "no suction") for n in range(2, 12)] + [Problem("f.csv", 3, "y", "odd")]
    probs += [Problem("f.csv", n, "z", f"'v{n}' is not a number") for n in range(2, 5)]
    text = str(InputError(probs))
    assert "f.csv, column 'x': no suction (in 10 lines: 2, 3, 4, 5, 6, ...)" in text
    assert "f.csv, line 3, column 'y': odd" in text
    assert "f.csv, column 'z': 3 cells are not numbers (lines 2, 3, 4: 'v2', 'v3', 'v4')" in text
    assert len(InputError(probs).as_json()["errors"]) == 14  # scripts still get every problem


def test_a_shear_table_given_to_retention_says_try_shear(tmp_path):
    src = capred.sample_path("shear")
    res = runner.invoke(app, ["retention", str(src), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1
    first = res.output.strip().splitlines()[0]
    assert first.startswith(f"Error: {src}: this looks like a direct-shear table (it has ")
    assert f"try capred shear {src}" in first and len(res.output.strip().splitlines()) == 1
    js = runner.invoke(app, ["retention", str(src), "--json", "--no-plots", "--out", str(tmp_path / "o")])
    errors = json.loads(js.stdout)["errors"]
    assert "looks like a direct-shear table" in errors[0]["message"] and len(errors) > 10


def test_a_right_table_with_a_bad_cell_gets_no_such_hint(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text(HEAD + "a,m,dry,10,x\nb,m,dry,20,11\n")
    res = runner.invoke(app, ["shear", str(p), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "looks like" not in res.output


def test_a_retention_branch_named_as_the_literature_names_it_gets_a_hint(tmp_path):
    # 'Desorption' is the drying branch (and 'Adsorption' the wetting one): one message for the column, with the word
    path = tmp_path / "ret.csv"
    rows = "".join(f"{s},{t},Desorption\n" for s, t in [(1, 0.3), (2, 0.28), (5, 0.2), (10, 0.15), (20, 0.1)])
    path.write_text("suction [kPa],theta,branch\n" + rows, encoding="utf-8")
    res = CliRunner().invoke(app, ["retention", str(path), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1
    assert "'Desorption' is another word for 'drying': write 'drying'" in res.output
    assert res.output.count("Desorption") <= 2 and not (tmp_path / "o").exists()
