"""Messages of the table reader name the file, whatever the file holds under its data (capred.io.table)."""

import pytest

from capred.errors import InputError
from capred.io.table import read_table
from capred.pipelines.shear import SCHEMA

HEADER = "test_id,condition,sigma_N [kPa],tau_max [kPa]\n"


def _problems(path):
    with pytest.raises(InputError) as err:
        table = read_table(path, SCHEMA)
        table.raise_if_problems()
    return [(p.file, p.line, p.message) for p in err.value.problems]


def test_a_header_and_a_note_only_names_the_file_not_the_note(tmp_path):
    """The note under the header is taken as a note; the refusal named the note as the file ('Remarks: ..., line 1')
    because the note's quoted text took the name of the file's variable."""
    path = tmp_path / "only_note.csv"
    path.write_text(HEADER + "Remarks: only a note\n", encoding="utf-8")
    assert _problems(path) == [(str(path), 1, "the file has a header but no data rows")]


def test_a_row_of_too_many_fields_above_a_note_names_the_file(tmp_path):
    """Line 3 has 5 filled fields under a header of 4; the remark under the data is a note."""
    path = tmp_path / "wide_row.csv"
    path.write_text(HEADER + "a,dry,1,1.0\nb,dry,2,1.7,extra\nc,dry,3,2.4\nRemarks: a note\n", encoding="utf-8")
    assert _problems(path) == [(str(path), 3, "5 fields but the header has 4")]


def test_a_missing_column_names_the_headers_not_read(tmp_path):
    # 'Net cell pressure' and 'Deviator at failure' are no spelling capred knows: the message says which headers
    # of the file were left unread, so that the user sees what to rename; a second bracketed part is named as such
    from capred.errors import InputError
    from capred.pipelines.triaxial_strength import run_triaxial_strength

    p = tmp_path / "t.csv"
    p.write_text("test_id,material,Net cell pressure [kPa],Deviator at failure [kPa],suction [kPa]\nA1,c,50,150,100\n")
    with pytest.raises(InputError) as info:
        run_triaxial_strength(p)
    text = str(info.value)
    assert "missing column 'sigma3'" in text and "'Net cell pressure [kPa]', 'Deviator at failure [kPa]'" in text
    p.write_text("test_id,material,Cell pressure (net) [kPa],q_f [kPa],suction [kPa]\nA1,c,50,150,100\n")
    with pytest.raises(InputError, match="holds text in brackets besides its unit"):
        run_triaxial_strength(p)
