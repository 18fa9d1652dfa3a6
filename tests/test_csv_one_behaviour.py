"""One CSV reader behaviour (issue 32, item 4): a file mixing UTF-8 and Windows-1252 lines is read line by line
with a note naming the lines, never garbled; rows of delimiters only are skipped alike on every path (see also
tests/test_hostile_files.py for their bounds)."""

import pytest

from capred.io.grid import TableSource
from capred.io.table import read_table
from capred.pipelines.shear import SCHEMA

HEAD = b"test_id,material,condition,sigma_N [kPa],tau_max [kPa]\n"


def test_mixed_utf8_and_windows_1252_lines_are_each_read_in_their_encoding(tmp_path):
    p = tmp_path / "mixed.csv"
    # lines 2 and 4 in UTF-8 (c3 a9), line 3 pasted from a Windows program (e9): all three say 'béton'
    p.write_bytes(HEAD + b"a,b\xc3\xa9ton,dry,10,5\nb,b\xe9ton,dry,20,11\nc,b\xc3\xa9ton,dry,30,17\n")
    t = read_table(TableSource(p), SCHEMA)
    assert list(t.columns["material"]) == ["béton"] * 3  # never 'bÃ©ton'
    assert t.notes == [
        "the file mixes encodings: line 3 is not UTF-8 and was read as Windows-1252 (the rest as UTF-8); "
        "check those lines' accented letters"
    ]


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "cp1252", "utf-16"])
def test_a_file_in_one_encoding_is_read_without_a_note(tmp_path, encoding):
    p = tmp_path / "one.csv"
    p.write_bytes((HEAD.decode() + "a,béton µ,dry,10,5\nb,béton µ,dry,20,11\n").encode(encoding))
    t = read_table(TableSource(p), SCHEMA)
    assert list(t.columns["material"]) == ["béton µ"] * 2 and t.notes == []


@pytest.mark.parametrize("quote", ["", '"'])
@pytest.mark.parametrize("blank", [",,,,", ";;", " , ,", ",\t,"])
def test_delimiter_rows_in_the_middle_are_skipped_alike_on_both_paths(tmp_path, quote, blank):
    p = tmp_path / "t.csv"
    p.write_text(f"{HEAD.decode()}{quote}a{quote},m,dry,10,5\n{blank}\nb,m,dry,20,11\n{blank}\n")
    t = read_table(TableSource(p), SCHEMA)
    assert list(t.lines) == [2, 4] and not t.problems
    assert t.notes == ["2 rows holding only delimiters (as spreadsheet exports leave them) skipped: lines 3, 5"]
