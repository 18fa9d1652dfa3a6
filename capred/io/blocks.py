"""A long plain CSV read in blocks of lines, so that a run's memory does not grow with the file (issue 20).

``read_table_blocks`` yields :class:`capred.io.table.Table` objects, each one
block of consecutive data lines of the same file, with the file's own line
numbers, header, units row and delimiter. A command whose rows are
independent (``bridge solve``) computes and writes block by block; its peak
memory is then that of one block, whatever the length of the file.

Only a file the fast reader handles as a whole would handle alike is split:
a CSV path (not a workbook or DataFrame) larger than one block, valid UTF-8,
without quotes, carriage returns, comment marks ('#') or the rarer line
breaks (vertical tab, form feed, U+001C-001E, U+0085, U+2028/2029). Any
other table is read whole (one block), exactly as ``read_table`` reads it.
"""
from __future__ import annotations

import codecs
from pathlib import Path
from typing import Iterator

from .grid import SPREADSHEET_SUFFIXES, ReadLimits, _csv_grid, as_source
from .table import Column, Table, _grid_table, _with_options, read_table

#: bytes of CSV text per block: about 50,000 rows of a four-column bridge table, enough for two processes to share
#: a block (capred.pipelines.bridge), small enough that 1M rows peak at 1.27x the memory of 100,000 (measured:
#: 180 MB against 142 MB); a shorter last piece (under a quarter of this) joins the block before it, so that
#: notes under the data stay with data rows
BLOCK_BYTES = 4 * 2**20

#: bytes that send a file to the whole-file reader (quoting, CR line ends, comments, other line breaks)
_NOT_PLAIN = (b'"', b"\r", b"#", b"\x00", b"\x0b", b"\x0c", b"\x1c", b"\x1d", b"\x1e", b"\xc2\x85",
              b"\xe2\x80\xa8", b"\xe2\x80\xa9")


def read_table_blocks(source, schema: list[Column], *, ignore_columns=(), limits: ReadLimits | None = None,
                      block_bytes: int | None = None) -> Iterator[Table]:
    """Read ``source`` against ``schema`` one block of lines at a time.

    Parameters
    ----------
    source : path, DataFrame or TableSource
        The table, as for :func:`capred.io.table.read_table`.
    schema : list of Column
        The columns the command reads.
    ignore_columns : sequence of str
        Header names of columns to leave out (see read_table).
    limits : ReadLimits, optional
        Reading limits (see read_table).
    block_bytes : int, optional
        Bytes of text per block [B] (default :data:`BLOCK_BYTES`).

    Yields
    ------
    Table
        One per block, in file order: its columns in SI, its rows' own line
        numbers, its problems. The first block carries the metadata above
        the header; a note or warning already given by an earlier block is
        not repeated.

    Notes
    -----
    Every block is read like the whole file would be: the same header, units
    row and delimiter, each block's problems named by file, line and column.
    A table that cannot be split (see the module docstring) is one block.
    """
    src = _with_options(as_source(source), ignore_columns, limits)
    block_bytes = block_bytes or BLOCK_BYTES
    path = src.path
    if hasattr(path, "to_csv") or src.sheet is not None:
        yield read_table(src, schema)
        return
    p = Path(path)
    try:
        size = p.stat().st_size if p.is_file() else 0
    except OSError:
        size = 0
    if (size <= block_bytes + block_bytes // 4 or p.suffix.lower() in SPREADSHEET_SUFFIXES
            or size > (src.limits or ReadLimits()).max_bytes or not _plain_utf8(p)):
        yield read_table(src, schema)  # read whole: its own checks and messages
        return
    seen: set[str] = set()
    prefix: list[str] = []  # the header line (and units row) that every later block repeats
    for first_line, text in _pieces(p, block_bytes):
        if first_line == 1:
            table = _grid_table(_csv_grid(str(path), text), src, schema)
            lines = text.split("\n", table.units_line or table.header_line)
            prefix = [lines[table.header_line - 1]] + ([lines[table.units_line - 1]] if table.units_line else [])
        else:
            if not text.strip():
                continue
            # the header (and units row) just above the block's lines, which keep their line numbers
            grid = _csv_grid(str(path), "\n".join(prefix) + "\n" + text, first_line - len(prefix))
            table = _grid_table(grid, src, schema)
            if table.units_line is not None:  # said once, by the first block
                table.notes.remove(f"units read from the row under the header (line {table.units_line})")
        table.notes = _unseen(table.notes, seen)
        table.warnings = _unseen(table.warnings, seen)
        yield table


def _unseen(messages: list[str], seen: set[str]) -> list[str]:
    fresh = [m for m in messages if m not in seen]
    seen.update(fresh)
    return fresh


def _plain_utf8(path: Path, chunk: int = 2**22) -> bool:
    """True when the file is valid UTF-8 (an optional byte-order mark) with none of the bytes of _NOT_PLAIN."""
    decoder = codecs.getincrementaldecoder("utf-8")()
    tail = b""
    with open(path, "rb") as fh:
        while data := fh.read(chunk):
            window = tail + data  # a marker split between two chunks is found too
            if any(m in window for m in _NOT_PLAIN):
                return False
            try:
                decoder.decode(data)
            except UnicodeDecodeError:
                return False
            tail = data[-2:]
    try:
        decoder.decode(b"", final=True)
    except UnicodeDecodeError:
        return False
    return True


def _pieces(path: Path, block_bytes: int) -> Iterator[tuple[int, str]]:
    """(line number of the first line, text) of consecutive blocks of whole lines; the first without its BOM."""
    first_line = 1
    carry = b""
    with open(path, "rb") as fh:
        data = fh.read(block_bytes)
        if data.startswith(codecs.BOM_UTF8):
            data = data[len(codecs.BOM_UTF8):]
        while data:
            data = carry + data
            ahead = fh.read(block_bytes)
            if ahead and len(ahead) < block_bytes // 4:  # a short last piece joins this block
                data += ahead
                ahead = fh.read(block_bytes)
            if ahead:
                cut = data.rfind(b"\n") + 1
                if cut == 0:  # a line longer than a block: keep reading
                    carry, data = data, ahead
                    continue
                data, carry = data[:cut], data[cut:]
            else:
                carry = b""
            text = data.decode("utf-8")
            yield first_line, text[:-1] if text.endswith("\n") else text
            first_line += data.count(b"\n")
            data = ahead  # the last block takes what is left: nothing is carried past the end
