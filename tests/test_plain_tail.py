"""The lines of a long plain CSV after its first 200 are read as columns a window at a time (capred.io.plain_tail,
issue 46): the table, its cells' text and every message are those of the row-by-row reader.

Each file is read twice: as written (the tail path) and with its header's first cell quoted, which sends the
whole file to the row-by-row reader (a quote in the text) without changing any cell.
"""

import numpy as np
import pytest

from capred.errors import InputError
from capred.io import plain_tail, read_table
from capred.pipelines.retention import SCHEMA as RETENTION
from capred.pipelines.triaxial_strength import SCHEMA as TRIAXIAL

HEADER = "z1 [cm],z2 [cm^3],V_v [cm^3],branch"


def _rows(n):
    return [
        f"{2 + (i % 97) * 0.5:.1f},{(i % 89) * 0.3:.2f},30.5,{'drying' if i < n // 2 else 'wetting'}" for i in range(n)
    ]


def _both(tmp_path, header, rows, schema, window=None, monkeypatch=None):
    """(table or InputError) read by the tail path and by the row-by-row path."""
    if window is not None:
        monkeypatch.setattr(plain_tail, "WINDOW_CHARS", window)  # many windows in a small file
    out = []
    d = ";" if ";" in header else ","
    for name, head in (("tail.csv", header), ("rows.csv", '"' + header.replace(d, '"' + d, 1))):
        path = tmp_path / name
        path.write_text(head + "\n" + "\n".join(rows) + "\n")
        try:
            out.append(read_table(path, schema))
        except InputError as exc:
            out.append(exc)
    return out


def _same(a, b):
    if isinstance(a, InputError) or isinstance(b, InputError):
        assert isinstance(a, InputError) and isinstance(b, InputError), (a, b)
        strip = lambda e: [(p.line, p.column, p.message, p.value) for p in e.problems]  # noqa: E731
        assert strip(a) == strip(b)
        return
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        x, y = a.columns[name], b.columns[name]
        if x.dtype == object:
            assert list(x) == list(y), name
        else:
            np.testing.assert_array_equal(x, y)  # the same text parsed: the same floats, NaN where blank
        assert list(a.raw[name]) == list(b.raw[name]), name
    np.testing.assert_array_equal(a.lines, b.lines)
    assert [(p.line, p.column, p.message, p.value) for p in a.problems] == [
        (p.line, p.column, p.message, p.value) for p in b.problems
    ]
    assert a.notes == b.notes and a.warnings == b.warnings


@pytest.mark.parametrize("window", [None, 64])
def test_a_valid_long_table_is_read_alike(tmp_path, window, monkeypatch):
    a, b = _both(tmp_path, HEADER, _rows(1000), RETENTION, window, monkeypatch)
    _same(a, b)
    assert isinstance(a.raw["head"], plain_tail.TailCells)  # the tail's cells are not kept as strings
    assert len(a.lines) == 1000 and a.lines[-1] == 1001  # line 1 is the header
    assert a.columns["head"][999] == pytest.approx((2 + (999 % 97) * 0.5) * 0.01)  # cm -> m


@pytest.mark.parametrize("window", [None, 64])
def test_bad_cells_in_the_tail_are_named_alike(tmp_path, window, monkeypatch):
    """A word, an infinity and a branch outside the choices, all after line 200: each named by line, column and
    value as the row-by-row reader names them."""
    rows = _rows(1000)
    rows[600] = "abc,0.3,30.5,drying"  # line 602
    rows[700] = "5.0,inf,30.5,drying"  # line 702
    rows[800] = "5.0,0.3,30.5,dry"  # line 802
    a, b = _both(tmp_path, HEADER, rows, RETENTION, window, monkeypatch)
    _same(a, b)  # the problems are the table's, raised by the command once every one is known
    lines = {(p.line, p.column) for p in a.problems}
    assert {(602, "z1 [cm]"), (702, "z2 [cm^3]"), (802, "branch")} <= lines
    assert any(p.value == "abc" and "is not a number" in p.message for p in a.problems)


def test_spaces_blanks_and_a_note_row_under_the_data_are_read_alike(tmp_path):
    rows = _rows(500)
    rows[300] = " 5.0 , 0.3 ,30.5, drying "
    rows[301] = "5.0,,30.5,drying"  # a blank cell: NaN
    rows.append("Remarks: measured by hand,,,")
    a, b = _both(tmp_path, HEADER, rows, RETENTION)
    _same(a, b)
    assert np.isnan(a.columns["z2"][301]) and a.columns["head"][300] == pytest.approx(0.05)
    assert any("Remarks: measured by hand" in n for n in a.notes)


def test_a_triaxial_table_with_ids_and_materials_is_read_alike(tmp_path):
    header = "test_id,material,sigma3 [kPa],q_f [kPa],suction [kPa]"
    rows = [f"T{i},{'sand' if i % 3 else 'silt'},{50 + i % 7 * 50},{120 + i % 11},{i % 13 * 10}" for i in range(900)]
    a, b = _both(tmp_path, header, rows, TRIAXIAL)
    _same(a, b)
    assert a.columns["test_id"][899] == "T899" and a.raw["test_id"][899] == "T899"


def test_a_decimal_comma_table_is_read_alike(tmp_path):
    """';' as delimiter and decimal commas: the tail's numbers are read cell by cell, as the row-by-row reader
    reads them (a cell with a dot there is ambiguous and named)."""
    rows = [r.replace(",", ";").replace(".", ",") for r in _rows(600)]
    rows[400] = "1.000;0,3;30,5;drying"  # a thousands separator or a decimal point? (line 402)
    a, b = _both(tmp_path, HEADER.replace(",", ";"), rows, RETENTION)
    _same(a, b)
    assert a.columns["z2"][1] == pytest.approx(0.3e-6)  # 0,30 cm^3
    assert any(p.line == 402 and "ambiguous" in p.message for p in a.problems)
