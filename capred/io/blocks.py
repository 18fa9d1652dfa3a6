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
from collections.abc import Iterator, Sequence
from pathlib import Path

from ..errors import InputError
from ..units import conversion
from .grid import (
    SPREADSHEET_SUFFIXES,
    Grid,
    ReadLimits,
    as_source,
    blank_delimiter_rows,
    check_long_lines,
    csv_grid,
)
from .table import Column, Table, check_column_rule, grid_table, read_table, source_with_options

#: bytes of CSV text per block: about 50,000 rows of a four-column bridge table, enough for two processes to share
#: a block (capred.pipelines.bridge), small enough that 1M rows peak at 1.27x the memory of 100,000 (measured:
#: 180 MB against 142 MB); a shorter last piece (under a quarter of this) joins the block before it, so that
#: notes under the data stay with data rows
BLOCK_BYTES = 4 * 2**20

#: bytes that send a file to the whole-file reader (quoting, CR line ends, comments, other line breaks)
_NOT_PLAIN = (
    b'"',
    b"\r",
    b"#",
    b"\x00",
    b"\x0b",
    b"\x0c",
    b"\x1c",
    b"\x1d",
    b"\x1e",
    b"\xc2\x85",
    b"\xe2\x80\xa8",
    b"\xe2\x80\xa9",
)

#: the markers of _NOT_PLAIN that are ASCII bytes
_NOT_PLAIN_ASCII = tuple(m for m in _NOT_PLAIN if m.isascii())


def read_table_blocks(
    source,
    schema: list[Column],
    *,
    ignore_columns=(),
    limits: ReadLimits | None = None,
    block_bytes: int | None = None,
    select=None,
) -> Iterator[Table]:
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
    select : callable, optional
        ``select(k)``: whether to parse the block of index ``k`` (from 0); a block not selected is yielded as
        None, unparsed, so that processes that share a file's blocks see the same indices
        (capred.pipelines.bridge_blocks). Default: every block. A note or warning is then not repeated among
        the selected blocks only.

    Yields
    ------
    Table or None
        One per block, in file order: its columns in SI, its rows' own line
        numbers, its problems (None for a block not selected). The first block carries the metadata above
        the header; a note or warning already given by an earlier block is
        not repeated.

    Notes
    -----
    Every block is read like the whole file would be: the same header, units
    row and delimiter, each block's problems named by file, line and column.
    A table that cannot be split (see the module docstring) is one block.
    """
    src = source_with_options(as_source(source), ignore_columns, limits)
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
    if (
        size <= block_bytes + block_bytes // 4
        or p.suffix.lower() in SPREADSHEET_SUFFIXES
        or size > (src.limits or ReadLimits()).max_bytes
        or not _plain_utf8(p)
    ):
        yield read_table(src, schema)  # read whole: its own checks and messages
        return
    limits = src.limits or ReadLimits()
    shown = str(path)
    # rows of delimiters only, counted over the whole file first: the first block's note gives their total and
    # first lines, as the whole-file reader's does; a later block of nothing else is skipped (issue 32.4)
    counted = _delimiter_rows(p, block_bytes, limits, shown)
    seen: set[str] = set()
    prefix: list[str] = []  # the header line (and units row) that every later block repeats
    index = -1  # the block's index among the blocks of data, the same in every process (``select``)
    pieces = _with_data(_pieces(p, block_bytes, limits, shown))
    piece, following = next(pieces, None), next(pieces, None)
    while piece is not None:
        first_line, text = piece
        after = next(pieces, None) if following is not None else None
        tables = []
        index += 1
        if select is not None and not select(index):
            if first_line == 1:  # its header (and units row) is what every later block repeats
                head = _split_head(text)[0]
                prefix = _prefix(head, grid_table(csv_grid(shown, head, limits=limits), src, schema))
            # the trailing rows a selected block would take in are taken here too: the indices stay those of
            # every other process
            if _trailing(following, after, prefix, shown, limits, src, schema) is not None:
                following = None
            piece, following = following, after
            yield None
            continue
        if first_line == 1:
            # the head (header, metadata, the first rows) read as usual, the rest of the piece by the fast path
            # when it can take it, joined as one block (the blocks, and so every number computed on them, stay
            # as they were); else the piece read whole
            head, rest = _split_head(text)
            if rest and not rest[: rest.find("\n")].translate(_NUMERIC_CHARS):  # numbers after the head
                table = grid_table(_counted(csv_grid(shown, head, limits=limits), counted), src, schema)
                prefix = _prefix(head, table)
                fast = _numeric_block(shown, src, schema, prefix, HEAD_LINES + 1, rest)
                if fast is not None and _numeric_line(head[head.rfind("\n") + 1 :], len(prefix[0].split(","))):
                    tables = [_joined(table, fast)]
            if not tables:
                table = grid_table(_counted(csv_grid(shown, text, limits=limits), counted), src, schema)
                prefix = _prefix(text, table)
                tables = [table]
        else:
            table = _numeric_block(shown, src, schema, prefix, first_line, text)
            if table is None:
                # the header (and units row) just above the block's lines, which keep their line numbers
                grid = csv_grid(shown, "\n".join(prefix) + "\n" + text, first_line - len(prefix), limits)
                table = grid_table(_counted(grid, None), src, schema)
            tables = [table]
        trailing = _trailing(following, after, prefix, shown, limits, src, schema)  # once the prefix is set
        if trailing is not None:
            following = None
            if trailing.units_line is not None:  # said by the first block
                trailing.notes.remove(f"units read from the row under the header (line {trailing.units_line})")
            tables[-1].notes += trailing.notes
            tables[-1].warnings += trailing.warnings
        piece, following = following, after
        for table in tables:
            if table.units_line is not None and first_line > 1:
                # said once, by the first block
                table.notes.remove(f"units read from the row under the header (line {table.units_line})")
            table.notes = _unseen(table.notes, seen)
            table.warnings = _unseen(table.warnings, seen)
            yield table
        del tables, table


#: the characters of a line that holds no data: blanks and the delimiters of a row of delimiters only
_EMPTY_ROW_CHARS = " \t\n,;"
#: the bytes a line of delimiters only ends with (before its line end: a delimiter or a blank)
_DELIMITER_ROW_LAST = b",; \t"


def _trailing(following, after, prefix: list[str], shown: str, limits: ReadLimits, src, schema) -> Table | None:
    """The last piece read as notes under the data, or None.

    It is read so when it begins with rows of delimiters only and holds no data rows (its lines under them that are not
    data are notes, said by the block before it: a block of no data would be refused as 'no data rows'); None otherwise
    (the piece is a block of its own).
    """
    if following is None or after is not None or not _delimiter_row_first(following[1]):
        return None
    lines = "\n".join(prefix) + "\n" + following[1]
    grid = csv_grid(shown, lines, following[0] - len(prefix), limits)
    trailing = grid_table(_counted(grid, None), src, schema, empty_ok=True)
    return None if len(trailing.lines) else trailing


def _with_data(pieces: Iterator[tuple[int, str]]) -> Iterator[tuple[int, str]]:
    """The pieces, less the later ones of blank lines and rows of delimiters only.

    Those hold no data; their rows are counted by _delimiter_rows and said by the first block.
    """
    for first_line, text in pieces:
        if first_line == 1 or text.strip(_EMPTY_ROW_CHARS):
            yield first_line, text


def _delimiter_row_first(text: str) -> bool:
    """True when the first line of ``text`` holds only delimiters (and blanks), at least one of ',' or ';'."""
    first = text[: text.find("\n")] if "\n" in text else text
    return bool(first.strip(" \t")) and not first.strip(" \t,;")


def _delimiter_rows(path: Path, block_bytes: int, limits: ReadLimits, shown: str) -> Grid:
    """The rows of delimiters only of the whole file (",,,," as spreadsheet exports leave them).

    They are counted as the whole-file reader counts them: a Grid holding their number and first line numbers.

    The file is searched only when a line of it can be one (a line ending in a delimiter or a blank): a file of
    numbers costs one read of its bytes.
    """
    counted = Grid(shown, None, [])
    if _may_hold_delimiter_rows(path, block_bytes):
        for first_line, text in _pieces(path, block_bytes, limits, shown):
            counted.first_line = first_line
            blank_delimiter_rows(counted, text)
    return counted


def _may_hold_delimiter_rows(path: Path, block_bytes: int) -> bool:
    """Whether a line of the file ends in a delimiter or a blank, as a row of delimiters only does.

    The ends looked for are ',' ';' ' ' or tab; False proves the file holds no such row. Looked for with numpy, a block
    of bytes at a time.
    """
    import numpy as np

    last = np.zeros(256, bool)
    last[list(_DELIMITER_ROW_LAST)] = True
    before = b"\n"  # the last byte of the block before
    with open(path, "rb") as fh:
        while data := fh.read(block_bytes):
            chars = np.frombuffer(data, np.uint8)
            ends = np.flatnonzero(chars == 10)
            if ends.size and ends[0] == 0:
                if before in _DELIMITER_ROW_LAST:
                    return True
                ends = ends[1:]
            if last[chars[ends - 1]].any():
                return True
            before = data[-1:]
    return before in _DELIMITER_ROW_LAST  # the last line, without a line end


def _counted(grid: Grid, counted: Grid | None) -> Grid:
    """``grid`` (of one piece) with the rows of delimiters only of the whole file.

    ``counted`` holds them (None: none), so that the note on them is given once, with the file's total, by the first
    block.
    """
    grid.delimiter_rows = counted.delimiter_rows if counted is not None else 0
    grid.delimiter_lines = list(counted.delimiter_lines) if counted is not None else []
    return grid


#: lines of the first piece read by the whole-file reader (header, metadata, units row, first rows); the lines after
#: them go to the fast reader of plain numeric blocks when it can take them
HEAD_LINES = 1000
#: the characters of a plain numeric block: digits, signs, decimal points, exponents, commas and line ends
_NUMERIC_CHARS = str.maketrans("", "", "0123456789+-.eE,\n")


def _prefix(text: str, table: Table) -> list[str]:
    """The header line (and units row) of ``text`` as ``table`` found them: what every later block repeats."""
    lines = text.split("\n", table.units_line or table.header_line)
    return [lines[table.header_line - 1]] + ([lines[table.units_line - 1]] if table.units_line else [])


def _split_head(text: str) -> tuple[str, str]:
    """(the first HEAD_LINES lines, the rest) of the first piece; the rest is empty for a short piece."""
    cut = -1
    for _ in range(HEAD_LINES):
        cut = text.find("\n", cut + 1)
        if cut < 0:
            return text, ""
    return text[:cut], text[cut + 1 :]


def _numeric_line(line: str, width: int) -> bool:
    """True for a line of ``width`` filled cells of plain-number characters."""
    return not line.translate(_NUMERIC_CHARS) and line.count(",") == width - 1 and "" not in line.split(",")


class _Cells(Sequence):
    """Column ``j`` of a plain numeric block's lines as text, cut out when a message needs a cell (Table.raw)."""

    def __init__(self, text: str, width: int, j: int, n: int) -> None:
        self._text, self._width, self._j, self._n = text, width, j, n
        self._lines: list[str] | None = None

    def __len__(self) -> int:
        return self._n

    def __getitem__(self, i):
        if self._lines is None:
            self._lines = self._text.split("\n")
        if isinstance(i, slice):
            return [ln.split(",")[self._j] for ln in self._lines[i]]
        return self._lines[i].split(",")[self._j]


def _numeric_block(
    shown: str, src, schema: list[Column], prefix: list[str], first_line: int, text: str
) -> Table | None:
    """The Table of a block whose every cell is a plain number, or None.

    It is the Table the whole-file reader makes, made without a Python object per cell; None where the block is anything
    else (or has any problem), for the usual reader.

    Taken only when every line has as many filled cells as the header (no blank cell, line or header cell),
    every character is a digit, sign, point, exponent mark, comma or line end, the header is comma-separated,
    no column the schema reads is text and no thousands separator is set. What the reader says of the header
    (its line, units row, units, notes, warnings) comes from the usual reader on the header and the block's
    first line; the numbers are parsed by orjson (correctly rounded, as float() is; cells JSON does not take,
    such as '+1' or '.5', by float()); a block with any value out of range goes to the usual reader, which
    names it.
    """
    import numpy as np

    header = prefix[0]
    width = header.count(",") + 1
    if (
        not text
        or text.translate(_NUMERIC_CHARS)
        or src.thousands is not None
        or ";" in "".join(prefix)
        or "\t" in "".join(prefix)
        or any(not c.strip() for c in header.split(","))
    ):
        return None
    if text[0] in ",\n" or text[-1] in ",\n" or "\n\n" in text or ",," in text or ",\n" in text or "\n," in text:
        return None  # a blank line or a blank cell
    n = text.count("\n") + 1
    if text.count(",") != n * (width - 1):
        return None
    first = text[: text.find("\n")] if n > 1 else text
    limits = src.limits or ReadLimits()
    try:
        check_long_lines(shown, text, first_line, limits)  # a cell over --max-cell-chars: the usual reader's
        grid = csv_grid(shown, "\n".join(prefix) + "\n" + first, first_line - len(prefix), limits)
        table = grid_table(grid, src, schema)
    except InputError:
        return None
    cols = {c.name: c for c in schema}
    headers = [c.strip() for c in header.split(",")]
    if table.problems or len(table) != 1 or any(cols[name].kind == "text" for name in table.headers):
        return None
    values = _parse_numbers(text, n, width)
    if values is None:
        return None
    table.lines = np.arange(first_line, first_line + n)
    for name, shown_header in table.headers.items():
        j = headers.index(shown_header)
        col = cols[name]
        as_read = np.ascontiguousarray(values[:, j])
        factor = conversion(table.units[name], col.kind)[0]
        with np.errstate(over="ignore", invalid="ignore"):
            si = as_read * factor
        if np.isinf(si).any():
            return None
        table.raw[name] = _Cells(text, width, j, n)
        table.as_read[name] = as_read
        table.columns[name] = si
        check_column_rule(table, col)
        if table.problems:
            return None
    return table


def _joined(head: Table, rest: Table) -> Table:
    """The table of the head's lines then the rest's.

    The rest is read by _numeric_block after the head: the table is what the whole-file reader makes of both together.
    """
    import numpy as np

    for name in head.columns:
        head.columns[name] = np.concatenate([head.columns[name], rest.columns[name]])
        head.as_read[name] = np.concatenate([head.as_read[name], rest.as_read[name]])
        head.raw[name] = _Concatenated(head.raw[name], rest.raw[name])
    head.lines = np.concatenate([head.lines, rest.lines])
    return head


class _Concatenated(Sequence):
    """Two sequences of cells as one (Table.raw of a head and the rest read after it)."""

    def __init__(self, first, second) -> None:
        self._first, self._second = first, second

    def __len__(self) -> int:
        return len(self._first) + len(self._second)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        k = len(self._first)
        return self._first[i] if i < k else self._second[i - k]


def _parse_numbers(text: str, n: int, width: int):
    """The cells of a plain numeric block as an (n, width) float array, or None.

    None where a line has another width or a cell is not a number.
    """
    import numpy as np

    try:
        import orjson

        if not _minus_zero(text):  # JSON reads the integer -0 as 0 (float reads -0.0)
            values = np.array(orjson.loads("[" + text.replace("\n", ",") + "]"), dtype=float)
            if values.shape != (n * width,) or not _rectangular(text, n, width):
                return None
            return values.reshape(n, width)
    except (ImportError, ValueError, TypeError, OverflowError):  # orjson.JSONDecodeError is a ValueError
        pass
    cells = text.replace("\n", ",").split(",")
    if len(cells) != n * width or any(ln.count(",") != width - 1 for ln in text.split("\n")):
        return None
    try:
        return np.fromiter(map(float, cells), float, len(cells)).reshape(n, width)
    except ValueError:
        return None


def _rectangular(text: str, n: int, width: int) -> bool:
    """True when each of the n lines of an ASCII ``text`` has width - 1 commas (counted with numpy)."""
    import numpy as np

    chars = np.frombuffer(text.encode("ascii"), np.uint8)
    line_ends = np.flatnonzero(chars == 10)
    commas_per_line = np.bincount(np.searchsorted(line_ends, np.flatnonzero(chars == 44)), minlength=n)
    return line_ends.size == n - 1 and bool(np.all(commas_per_line == width - 1))


def _minus_zero(text: str) -> bool:
    """True when some cell of the lines is exactly '-0'."""
    if text == "-0" or text.startswith(("-0,", "-0\n")) or text.endswith((",-0", "\n-0")):
        return True
    return any(p in text for p in (",-0,", ",-0\n", "\n-0,", "\n-0\n"))


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
            # a marker split between two chunks is found at the seam (markers are at most 3 bytes); an ASCII chunk
            # holds none of the multi-byte markers (each scan of those costs ~25x a one-byte scan)
            markers = _NOT_PLAIN_ASCII if data.isascii() else _NOT_PLAIN
            if any(m in data for m in markers) or any(m in tail + data[:2] for m in _NOT_PLAIN):
                return False
            if not (data.isascii() and not decoder.getstate()[0]):  # ASCII after a whole character is UTF-8
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


def _pieces(
    path: Path, block_bytes: int, limits: ReadLimits | None = None, shown: str | None = None
) -> Iterator[tuple[int, str]]:
    """(line number of the first line, text) of consecutive blocks of whole lines.

    Each block is without its last line end; the first without its BOM.

    A line longer than half a block is read whole into the block where it starts (the lines before it keep it
    company: a first block is never its header alone) and is first checked against ``limits.max_cell_chars``
    [-]: a cell over the limit is refused as the whole-file reader refuses it (LimitError, with a short excerpt
    and the cell's length, the file named as ``shown``), the line held once, not copied block after block.
    """
    limits = limits or ReadLimits()
    shown = str(path) if shown is None else shown
    first_line = 1
    carry = b""
    with open(path, "rb") as fh:
        data = fh.read(block_bytes)
        start = len(codecs.BOM_UTF8) if data.startswith(codecs.BOM_UTF8) else 0
        while data:
            data = carry + data if carry else data
            ahead = fh.read(block_bytes)
            if ahead and len(ahead) < block_bytes // 4:  # a short last piece joins this block
                data += ahead
                ahead = fh.read(block_bytes)
            if ahead:
                cut = data.rfind(b"\n") + 1
                k = ahead.find(b"\n")
                if len(data) - cut + (k if k >= 0 else len(ahead)) > block_bytes // 2:
                    # the line in progress is long: read to its end, check its cells, keep it in this block
                    data, ahead = _long_line(fh, data, cut, ahead, block_bytes, first_line, start, shown, limits)
                    cut, carry = len(data), b""
                else:
                    carry = data[cut:]
            else:
                cut, carry = len(data), b""
            end = cut - 1 if cut > start and data[cut - 1] == 0x0A else cut
            yield first_line, str(memoryview(data)[start:end], "utf-8")  # decoded in place, no copy of the bytes
            first_line += data.count(b"\n", start, cut)
            data, start = ahead, 0  # the last block takes what is left: nothing is carried past the end


def _long_line(fh, data: bytes, cut: int, ahead: bytes, block_bytes: int, first_line: int, start: int, shown, limits):
    """(the block's bytes through the end of the long line begun at ``cut``, the bytes after it) for _pieces.

    The bytes are read on from ``fh``; the line's cells are checked against ``limits`` (LimitError for one over the
    limit).
    """
    line = bytearray(memoryview(data)[cut:])  # grown in place: the line is held once
    rest = ahead
    while rest:
        k = rest.find(b"\n")
        if k >= 0:
            line += memoryview(rest)[: k + 1]
            rest = rest[k + 1 :]
            break
        line += rest
        rest = fh.read(block_bytes)
    number = first_line + data.count(b"\n", start, cut)
    # the line as the whole-file reader sees it: without its line end (nor the file's BOM)
    text = str(memoryview(line)[max(0, start - cut) : len(line) - line.endswith(b"\n")], "utf-8")
    try:
        check_long_lines(shown, text, number, limits)
    except InputError as exc:  # raised without the frames that hold the line (a 100 MB cell, twice)
        error = exc.with_traceback(None)
    else:
        error = None
    del text
    if error is not None:
        del line, data
        raise error
    data = data[:cut] + line
    del line
    if rest and len(rest) < block_bytes // 4:  # a short rest: the last piece joins this block
        more = fh.read(block_bytes)
        if not more:
            data, rest = data + rest, b""
        else:
            rest += more
    return data, rest


#: the bytes of a line that hold no data (blanks, line ends, the delimiters of a row of delimiters only)
_NO_DATA_BYTES = b" \t\r\n,;"


def data_lines(path, block_bytes: int | None = None) -> int:
    """How many lines of a text file hold anything but blanks and delimiters: about its rows.

    The header and any note lines are included; a quoted cell that spans lines counts once per line. Counted
    without reading the file as a table, a block of bytes at a time with numpy (about 1 s for 250 MB).

    A line ends at a line feed or a carriage return (CRLF, LF and lone CR files alike). Used to say, before a
    run computes anything, how large its outputs would be (capred.report.outputs.check_outputs_ahead).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    block_bytes : int, optional
        Bytes read at a time (default :data:`BLOCK_BYTES`).

    Returns
    -------
    int
        Lines that hold data.
    """
    import numpy as np

    data_byte = np.ones(256, bool)
    data_byte[list(_NO_DATA_BYTES)] = False
    count, open_line = 0, False  # open_line: the line the block before ended in holds data
    with open(path, "rb") as fh:
        while data := fh.read(block_bytes or BLOCK_BYTES):
            chars = np.frombuffer(data, np.uint8)
            filled = np.cumsum(data_byte[chars], dtype=np.int64)
            ends = np.flatnonzero((chars == 10) | (chars == 13))
            if not ends.size:
                open_line = open_line or bool(filled[-1])
                continue
            at = filled[ends]
            per_line = np.diff(at, prepend=0)
            count += int(np.count_nonzero(per_line)) + (open_line and not per_line[0])
            open_line = bool(filled[-1] - at[-1])
    return count + open_line
