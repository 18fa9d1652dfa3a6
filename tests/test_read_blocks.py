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
        cells = [f"{rng.uniform(.1, 2):.4f}", f"{rng.uniform(0, 60):.3f}", f"{rng.uniform(0, .05):.5f}",
                 f"{rng.uniform(.1, 30):.4f}", "x"]
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
