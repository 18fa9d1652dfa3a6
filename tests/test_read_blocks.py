"""A long plain CSV read in blocks (capred.io.blocks) gives what the whole-file reader gives, block by block."""

import random

import numpy as np
import pytest

from capred.io.blocks import read_table_blocks
from capred.io.table import read_table
from capred.pipelines.bridge import SOLVE_SCHEMA


def _lab_file(path, rows=6000, quote=False):
    """A bridge table with metadata above the header, a units row, bad cells spread over the file, a blank line,
    an unused column and a remark under the data."""
    rng = random.Random(4)
    lines = ["Operator: A. N. Other", "Date: 2026-11-23", "R,contact_angle,gap,suction,extra", "mm,deg,mm,kPa,-"]
    for i in range(rows):
        cells = [
            f"{rng.uniform(0.1, 2):.4f}",
            f"{rng.uniform(0, 60):.3f}",
            f"{rng.uniform(0, 0.05):.5f}",
            f"{rng.uniform(0.1, 30):.4f}",
            "x",
        ]
        if i in (5, rows // 2, rows - 3):
            cells[1] = "abc"
        if i == rows // 3:
            lines.append("")
        lines.append(",".join(cells))
    if quote:
        lines[10] = lines[10].replace(",x", ',"x"')
    lines += ["Remarks: bridges of the second series", ""]
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def test_blocks_join_to_the_whole_file(tmp_path):
    f = _lab_file(tmp_path / "cases.csv")
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    whole = read_table(f, SOLVE_SCHEMA)
    assert len(blocks) > 5  # ~170 kB in blocks of 20 kB (the short last piece joins its neighbour)
    for name, values in whole.columns.items():  # exact: the same cells parsed by the same code
        np.testing.assert_array_equal(np.concatenate([b.columns[name] for b in blocks]), values)
    np.testing.assert_array_equal(np.concatenate([b.lines for b in blocks]), whole.lines)
    assert [str(p) for b in blocks for p in b.problems] == [str(p) for p in whole.problems]
    assert len(whole.problems) == 3  # the three 'abc' cells, each named by its own line
    # notes and warnings said once, the units row's by the first block, the remark by the last
    assert [n for b in blocks for n in b.notes] == whole.notes
    assert [w for b in blocks for w in b.warnings] == whole.warnings
    assert blocks[0].metadata == whole.metadata == {"Operator": "A. N. Other", "Date": "2026-11-23"}
    assert blocks[-1].notes == ["note under the data (line 6006): Remarks: bridges of the second series"]


@pytest.mark.parametrize("quote", [True, False])
def test_a_file_that_cannot_be_split_is_one_block(tmp_path, quote):
    f = _lab_file(tmp_path / "cases.csv", rows=300 if not quote else 6000, quote=quote)
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000 if quote else 10**6))
    assert len(blocks) == 1  # quoted cells (or a file shorter than a block) are read whole
    assert [str(p) for p in blocks[0].problems] == [str(p) for p in read_table(f, SOLVE_SCHEMA).problems]


def _numeric_file(path, rows=3000, units_row=False, cells=None):
    """A plain numeric bridge table (the usual long file): numbers only, every cell filled; ``cells`` replaces
    cells by (row, column): text."""
    rng = np.random.default_rng(11)
    lines = (
        ["R,contact_angle,gap,suction", "mm,deg,mm,kPa"]
        if units_row
        else ["R [mm],contact_angle [deg],gap [mm],suction [kPa]"]
    )
    data = [
        [
            repr(rng.uniform(0.1, 2)),
            repr(rng.uniform(0, 60)),
            repr(rng.uniform(0, 0.05)),
            repr(10 ** rng.uniform(-1, 1.5)),
        ]
        for _ in range(rows)
    ]
    for (i, j), text in (cells or {}).items():
        data[i][j] = text
    path.write_text("\n".join(lines + [",".join(r) for r in data]) + "\n", encoding="utf-8")
    return path


def _same_tables(blocks, whole):
    for name, values in whole.columns.items():  # bit for bit: the same numbers, parsed another way
        np.testing.assert_array_equal(
            np.concatenate([b.columns[name] for b in blocks]).view(np.int64), values.view(np.int64)
        )
        np.testing.assert_array_equal(np.concatenate([b.as_read[name] for b in blocks]), whole.as_read[name])
        assert [b.raw[name][i] for b in blocks for i in range(len(b))] == list(whole.raw[name])
    np.testing.assert_array_equal(np.concatenate([b.lines for b in blocks]), whole.lines)
    assert [str(p) for b in blocks for p in b.problems] == [str(p) for p in whole.problems]
    assert [n for b in blocks for n in b.notes] == whole.notes
    assert [w for b in blocks for w in b.warnings] == whole.warnings
    assert all(b.units == whole.units and b.headers == whole.headers for b in blocks)


@pytest.mark.parametrize("units_row", [False, True])
def test_plain_numeric_blocks_read_fast_give_the_whole_file(tmp_path, monkeypatch, units_row):
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 50)  # the first block: 50 lines as usual, the rest fast
    f = _numeric_file(tmp_path / "cases.csv", units_row=units_row)
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    assert len(blocks) > 5
    # every block went through the fast reader (its cells are cut from the text only when asked for)
    assert all(type(b.raw["R"]).__name__ in ("_Cells", "_Concatenated") for b in blocks)
    _same_tables(blocks, read_table(f, SOLVE_SCHEMA))
    # the first block is the head and the rest of the first piece joined: the blocks are those of the usual reader
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 10**9)
    assert [len(b) for b in read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000)] == [len(b) for b in blocks]


def test_cells_json_does_not_take_are_read_as_float_reads_them(tmp_path, monkeypatch):
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 50)
    odd = {
        (700, 0): "+1",
        (701, 1): ".5",
        (702, 2): "1.",
        (2500, 3): "-0",
        (704, 2): "1E-3",
        (705, 3): "007",
        (706, 0): "1.2345678901234567890123456789",
        (707, 2): "0e5",
    }
    f = _numeric_file(tmp_path / "cases.csv", cells=odd)
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    _same_tables(blocks, read_table(f, SOLVE_SCHEMA))
    gap = np.concatenate([b.as_read["gap"] for b in blocks])
    assert gap[702] == 1.0 and gap[704] == 0.001 and gap[707] == 0.0  # as float('1.'), float('1E-3'), float('0e5')
    suction = np.concatenate([b.as_read["suction"] for b in blocks])
    assert suction[2500] == 0 and np.signbit(suction[2500])  # '-0' is -0.0, as float('-0') (JSON would say 0)


@pytest.mark.parametrize(
    "cell, message", [("-0.5", "must be > 0"), ("abc", "is not a number"), ("", "blank"), ("1e400", "too large")]
)
def test_a_block_with_a_bad_cell_goes_to_the_usual_reader(tmp_path, monkeypatch, cell, message):
    """The fast reader takes only blocks without a problem; any other block is read (and its problem named)
    as before."""
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 50)
    f = _numeric_file(tmp_path / "cases.csv", cells={(1500, 0): cell})
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    whole = read_table(f, SOLVE_SCHEMA)
    _same_tables(blocks, whole)
    if cell:  # a blank cell is a problem of the command (blank R), not of the reader
        assert len(whole.problems) == 1 and message in str(whole.problems[0])
        assert "line 1502" in str(whole.problems[0])  # header on line 1, row 1500 (from 0) on line 1502


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig"])
def test_a_header_in_non_ascii_and_a_byte_order_mark(tmp_path, monkeypatch, encoding):
    """'contact_angle [°]' in UTF-8 (with or without a byte-order mark): the numeric blocks read fast, the same
    table; a file whose later bytes are not UTF-8 is read whole by the usual reader."""
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 50)
    f = _numeric_file(tmp_path / "cases.csv")
    text = f.read_text(encoding="utf-8").replace("contact_angle [deg]", "contact_angle [°]")
    f.write_bytes(text.encode(encoding))
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    assert len(blocks) > 5 and type(blocks[-1].raw["R"]).__name__ == "_Cells"
    _same_tables(blocks, read_table(f, SOLVE_SCHEMA))
    # a Latin-1 byte deep in the file: not UTF-8, so one block, as read_table reads it
    g = tmp_path / "latin.csv"
    g.write_bytes(text.encode("utf-8") + "0.5,1,0,1 µ\n".encode("latin-1"))
    assert len(list(read_table_blocks(g, SOLVE_SCHEMA, block_bytes=20_000))) == 1


def test_lines_of_other_widths_go_to_the_usual_reader(tmp_path, monkeypatch):
    """A line with a cell too many and another with one too few in the same block (the block's commas add up):
    the usual reader reads that block and names the long line."""
    monkeypatch.setattr("capred.io.blocks.HEAD_LINES", 50)
    f = _numeric_file(tmp_path / "cases.csv")
    lines = f.read_text().split("\n")
    lines[1501] += ",1.5"
    lines[1502] = lines[1502].rsplit(",", 1)[0]
    f.write_text("\n".join(lines))
    blocks = list(read_table_blocks(f, SOLVE_SCHEMA, block_bytes=20_000))
    whole = read_table(f, SOLVE_SCHEMA)
    _same_tables(blocks, whole)
    assert [str(p) for p in whole.problems] == [f"{f}, line 1502: 5 fields but the header has 4"]
    assert np.isnan(whole.columns["suction"][1501])  # the short line's missing cell is blank
