"""The one place where bytes become a grid of cells: CSV text, .xlsx and .ods spreadsheets.

A grid is a list of rows, each with the line (or spreadsheet row) number a
person sees and its cells as text. Numbers from spreadsheets are written in
shortest round-trip form, so nothing is rounded on the way. Comment lines
(starting with '#') and blank lines are skipped but keep their numbers.

Spreadsheets are read as streams over the cells that hold data, never as a
whole sheet: an .xlsx or .ods is a zip of XML parts, and a hostile one (a
zip bomb, a stray cell at XFD1048576, a million repeated cells) could
otherwise take minutes and gigabytes. :class:`ReadLimits` bounds the work:

- ``max_bytes`` (default :data:`MAX_BYTES`): the bytes a file may hold, a CSV
  as it is, a workbook once decompressed; a zip whose declared sizes exceed
  it is refused before anything is decompressed, and decompression stops at
  the limit whatever the zip declares;
- ``max_cells`` (default :data:`MAX_CELLS`): the cells of a sheet the reader
  visits (every cell element of the XML, and the blanks a row is padded
  with), and the shared strings of a workbook;
- ``max_columns`` (default :data:`MAX_COLUMNS`): the column of the last cell
  holding data (spreadsheets) and the width of the header (every table).

Over a limit, :class:`capred.errors.LimitError` names the file, the sheet,
the cell or line, the limit and how to raise it (the CLI options
``--max-megabytes``, ``--max-cells``, ``--max-columns``). XML parts with a
document type declaration are refused (no entity expansion, no external
entities).
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, LimitError, Problem
from ..text_safety import visible

#: default limit on the bytes of an input: a CSV file's size, a workbook's decompressed parts (256 MiB)
MAX_BYTES = 256 * 2**20
#: default limit on the cells a spreadsheet sheet may make the reader visit (and on a workbook's shared strings)
MAX_CELLS = 2_000_000
#: default limit on the columns of a table (the header's width; a spreadsheet's last column holding data)
MAX_COLUMNS = 1000
#: default limit on the characters of one cell, header or note once expanded (repeated spaces of an .ods, shared
#: strings): 32,767, the most a cell of Excel or LibreOffice Calc holds
MAX_CELL_CHARS = 32_767
#: XML elements a part may hold per cell of ``max_cells`` (a cell is <c><v> or <c><is><t>, with rows, formats and
#: rich-text runs around them); more is not a spreadsheet's structure
ELEMENTS_PER_CELL = 4
#: elements read after a worksheet's <sheetData> (where its merged ranges are) before the rest is left unread
AFTER_DATA_ELEMENTS = 100_000
#: deepest nesting of XML elements in a part (spreadsheets nest about 10 deep)
MAX_XML_DEPTH = 200
#: the rows a worksheet holds in Excel and LibreOffice: a row number beyond is a damaged or hand-made file
MAX_SHEET_ROWS = 1_048_576
#: a spreadsheet is a zip of tens to hundreds of parts; more than this is not a spreadsheet capred reads
MAX_ZIP_PARTS = 10_000
#: the command-line option that raises each limit
LIMIT_OPTIONS = {
    "max_bytes": "--max-megabytes",
    "max_cells": "--max-cells",
    "max_columns": "--max-columns",
    "max_cell_chars": "--max-cell-chars",
}

SPREADSHEET_SUFFIXES = (".xlsx", ".xlsm", ".ods")
_MAGIC = (
    (b"PK\x03\x04", "a zip archive (an .xlsx or .ods spreadsheet?)"),
    (b"\xd0\xcf\x11\xe0", "an old binary Excel workbook (.xls); save it as .xlsx or .csv"),
    (b"%PDF", "a PDF document"),
    (b"\x89PNG", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"\x1f\x8b", "a gzip archive"),
)


@dataclass(frozen=True)
class ReadLimits:
    """How much of a file the reader may take on before it refuses it.

    Attributes
    ----------
    max_bytes : int
        Bytes of a CSV file, or of a workbook's XML once decompressed [bytes].
    max_cells : int
        Cells of a spreadsheet sheet the reader visits (cell elements and the
        blanks rows are padded with), and shared strings of a workbook [-].
    max_columns : int
        Columns of a table: the header's width, and the column of the last
        cell holding data in a spreadsheet [-].
    max_cell_chars : int
        Characters of one cell, header or note once expanded (an .ods's
        repeated spaces, a workbook's shared strings, a CSV's longest line
        split at its delimiter) [-].
    """

    max_bytes: int = MAX_BYTES
    max_cells: int = MAX_CELLS
    max_columns: int = MAX_COLUMNS
    max_cell_chars: int = MAX_CELL_CHARS

    def __post_init__(self) -> None:
        from ..errors import OptionError

        for name in ("max_bytes", "max_cells", "max_columns", "max_cell_chars"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise OptionError(f"{LIMIT_OPTIONS[name]} ({name}) must be a whole number >= 1 (got {value!r})")

    def shown(self, name: str) -> str:
        """The setting of limit ``name`` as a person reads it (MiB for bytes).

        Parameters
        ----------
        name : str
            A limit, e.g. ``"max_bytes"`` or ``"max_rows"``.

        Returns
        -------
        str
            E.g. ``"64 MiB"`` or ``"1,000,000"``.
        """
        value = getattr(self, name)
        return f"{value / 2**20:g} MiB" if name == "max_bytes" else f"{value:,}"

    def error(
        self,
        name: str,
        what: str,
        file: str,
        line: int | None = None,
        column: str | None = None,
        sheet: str | None = None,
    ) -> LimitError:
        """The error for ``what`` going over limit ``name``, saying how to raise it.

        Parameters
        ----------
        name : str
            The limit exceeded.
        what : str
            What went over it, e.g. "the file holds 70.0 MiB".
        file : str
            The file as shown in messages.
        line : int or None, optional
            Line of the input where the limit was reached.
        column : str or None, optional
            Column of the input.
        sheet : str or None, optional
            Sheet of a workbook.

        Returns
        -------
        LimitError
            The error to raise (not raised here).
        """
        unit = "N (MiB)" if name == "max_bytes" else "N"
        message = (
            f"{what}: over the limit of {self.shown(name)} ({name}), so it is not read. If the file is "
            f"genuine, raise the limit with {LIMIT_OPTIONS[name]} {unit} (from Python: "
            f"limits=ReadLimits({name}=...))"
        )
        return LimitError(Problem(file, line, column, message, sheet), name, getattr(self, name))


@dataclass(frozen=True)
class TableSource:
    """A table to read and how to read it.

    A path (CSV, .xlsx, .ods) or a DataFrame, the sheet of a workbook, how to read thousands separators ("." to read
    1.000 as one thousand in a decimal-comma file), the columns to leave out (``ignore_columns``: names as the header
    writes them) and the reading limits (``limits``: a :class:`ReadLimits`; None for the defaults).
    """

    path: object
    sheet: str | int | None = None
    thousands: str | None = None
    ignore_columns: tuple[str, ...] = ()
    limits: ReadLimits | None = None

    def __post_init__(self) -> None:
        from ..errors import OptionError

        if self.thousands not in (None, ".", ",", " ", "'"):
            raise OptionError(f"--thousands must be '.', ',', ' ' or \"'\" (got {self.thousands!r})")
        ignore = (self.ignore_columns,) if isinstance(self.ignore_columns, str) else self.ignore_columns
        try:
            ignore = tuple(ignore or ())
        except TypeError:
            raise OptionError(f"ignore_columns must be column names (got {self.ignore_columns!r})") from None
        if not all(isinstance(x, str) and x.strip() for x in ignore):
            raise OptionError(f"--ignore-column takes a column name as the header writes it (got {ignore!r})")
        object.__setattr__(self, "ignore_columns", ignore)
        if self.limits is not None and not isinstance(self.limits, ReadLimits):
            raise OptionError(f"limits must be a capred.io.grid.ReadLimits (got {type(self.limits).__name__})")


def source_path(source):
    """The path (or DataFrame) behind a source given as a path, a DataFrame or a TableSource.

    Parameters
    ----------
    source : str, pathlib.Path, pandas.DataFrame or TableSource
        The table as the caller gave it.

    Returns
    -------
    str, pathlib.Path or pandas.DataFrame
        ``source.path`` for a TableSource, else ``source`` itself.
    """
    return source.path if isinstance(source, TableSource) else source


def as_source(source) -> TableSource:
    """A TableSource of a source given as a path, a DataFrame or a TableSource (returned as is).

    Parameters
    ----------
    source : str, pathlib.Path, pandas.DataFrame or TableSource
        The table as the caller gave it.

    Returns
    -------
    TableSource
        ``source`` when it already is one, else ``TableSource(source)`` (default sheet, limits).
    """
    return source if isinstance(source, TableSource) else TableSource(source)


@dataclass
class Grid:
    """The cells of a table as read, before any column is interpreted: a CSV's rows or one sheet's.

    Each field is described where it is declared: the file as messages name it (``shown``), the sheet, the rows
    with their line numbers, a CSV's candidate delimiters and text, and what the reading itself noticed (rows of
    delimiters only, lines of another encoding, merged cells, hidden sheets) for the Table's notes and warnings.
    """

    shown: str  # the file as messages name it
    sheet: str | None
    rows: list[tuple[int, list[str]]]  # (line number, cells)
    delimiters: tuple[str, ...] = (",",)  # candidate CSV delimiters (spreadsheets: none needed)
    text_rows: dict[str, list[tuple[int, list[str]]]] = field(default_factory=dict)  # first rows, per delimiter
    full_text: str | None = None  # a CSV's text (comment lines blanked), parsed once the delimiter is known
    first_line: int = 1  # the line number of the text's first line (a block of a long file starts later)
    #: rows holding only delimiters (",,,," as spreadsheet exports leave them): how many, and the first lines
    delimiter_rows: int = 0
    delimiter_lines: list[int] = field(default_factory=list)
    #: notes of the reading itself (lines of another encoding, merged cells), for Table.notes
    notes: list[str] = field(default_factory=list)
    #: warnings of the reading itself (hidden sheets passed over), for Table.warnings
    warnings: list[str] = field(default_factory=list)
    #: a workbook's merged ranges, by line: (first column, last column, first line) of each, from 1; their cells
    #: hold the first cell's value (as the sheet shows it), and a metadata block reads them as one cell
    merged: dict[int, list[tuple[int, int, int]]] = field(default_factory=dict)
    #: the reading limits of a CSV (its rows are split into at most max_columns + 1 cells)
    limits: ReadLimits | None = None
    #: a line of the first rows (``text_rows``) was cut (too long to split for each candidate delimiter)
    head_cut: bool = False

    def parse_all(self, delimiter: str) -> None:
        """Every row of a CSV with the chosen delimiter (spreadsheets: nothing to do).

        Parameters
        ----------
        delimiter : str
            The CSV delimiter detected or given.
        """
        if self.full_text is not None:
            limits = self.limits or ReadLimits()
            try:
                self.rows = parse_rows(self.full_text, delimiter, self.first_line, limits.max_columns)
            except RowTooWide as exc:
                raise limits.error(
                    "max_columns", f"the line holds text in {exc.cells:,} cells", self.shown, exc.line
                ) from None
            self.full_text = None

    def where(self) -> str:
        """The file as messages name it, with its sheet when it has one.

        Returns
        -------
        str
            E.g. ``"tests.xlsx, sheet 'dry'"``.
        """
        return f"{self.shown}, sheet '{self.sheet}'" if self.sheet is not None else self.shown


def read_grid(source: TableSource) -> Grid:
    """Rows of cells of a CSV file, a spreadsheet or a DataFrame. Raises InputError when it cannot be read.

    Parameters
    ----------
    source : TableSource
        The file or DataFrame, its sheet and its reading limits.

    Returns
    -------
    Grid
        The rows of text cells, with the file name and sheet shown in messages.
    """
    path = source.path
    if hasattr(path, "to_csv"):  # a pandas DataFrame from a lab script: read like the same table in a file
        return csv_grid("<DataFrame>", path.to_csv(index=False))
    p = Path(path)
    shown = str(path)
    if not p.exists():
        from ..errors import MissingFileError

        raise MissingFileError(shown)
    if not p.is_file():
        raise InputError(Problem(shown, None, None, "not a file"))
    limits = source.limits or ReadLimits()
    size = p.stat().st_size
    if size > limits.max_bytes:
        raise limits.error("max_bytes", f"the file holds {size / 2**20:.1f} MiB", shown)
    data = p.read_bytes()
    if p.suffix.lower() in SPREADSHEET_SUFFIXES:
        return _spreadsheet_grid(shown, data, p.suffix.lower(), source.sheet, limits)
    if p.suffix.lower() == ".xls":
        raise InputError(
            Problem(shown, None, None, "old binary Excel workbooks (.xls) cannot be read: save it as .xlsx or .csv")
        )
    for magic, what in _MAGIC:
        if data.startswith(magic):
            raise InputError(
                Problem(
                    shown,
                    None,
                    None,
                    f"this file is {what}, not a CSV text table"
                    + (": give it its real extension (.xlsx or .ods)" if magic == b"PK\x03\x04" else ""),
                )
            )
    text, other = _decode_mixed(data)
    del data
    if "\x00" in text[:4096]:
        raise InputError(Problem(shown, None, None, "this is a binary file, not a CSV text table"))
    if source.sheet is not None:
        raise InputError(Problem(shown, None, None, "--sheet is for .xlsx and .ods workbooks, not CSV files"))
    grid = csv_grid(shown, text, limits=limits)
    if other:
        shown_lines = ", ".join(map(str, other[:5])) + (f" and {len(other) - 5:,} more" if len(other) > 5 else "")
        grid.notes.append(
            f"the file mixes encodings: line{'s' if len(other) > 1 else ''} {shown_lines} "
            f"{'are' if len(other) > 1 else 'is'} not UTF-8 and {'were' if len(other) > 1 else 'was'} read as "
            "Windows-1252 (the rest as UTF-8); check those lines' accented letters"
        )
    return grid


def _decode_mixed(data: bytes) -> tuple[str, list[int]]:
    """(text, lines read as Windows-1252) of a file's bytes, never garbled silently.

    UTF-8 (or UTF-16 with a BOM) as a whole where it can be; a file whose lines mix UTF-8 and Windows-1252 (one pasted
    from another program) line by line, each in its own encoding; a file of Windows-1252 alone as a whole.
    """
    if data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        return decode_text(data), []
    try:
        return data.decode("utf-8-sig"), []
    except UnicodeDecodeError:
        pass
    lines = data.split(b"\n")
    utf8_text = False
    for ln in lines:
        if not ln.isascii():
            try:
                ln.decode("utf-8")
                utf8_text = True
                break
            except UnicodeDecodeError:
                continue
    if not utf8_text:  # no UTF-8 beyond ASCII: one legacy encoding throughout
        return decode_text(data), []
    out, other = [], []
    for k, ln in enumerate(lines, start=1):
        try:
            out.append(ln.decode("utf-8-sig" if k == 1 else "utf-8"))
        except UnicodeDecodeError:
            try:
                out.append(ln.decode("cp1252"))
            except UnicodeDecodeError:
                out.append(ln.decode("latin-1"))
            other.append(k)
    return "\n".join(out), other


def decode_text(data: bytes) -> str:
    """Text of a file's bytes: UTF-8 (with or without BOM), UTF-16 with a BOM, else Windows-1252.

    Parameters
    ----------
    data : bytes
        The file's content.

    Returns
    -------
    str

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    encodings = ("utf-8-sig", "utf-16") if data[:2] in (b"\xff\xfe", b"\xfe\xff") else ("utf-8-sig", "cp1252")
    for enc in encodings:
        try:
            return data.decode(enc)
        except UnicodeDecodeError:
            continue
    return data.decode("latin-1")


#: a comment line: blanks (not line ends), then '#' (its line end kept, so the numbering holds)
_COMMENT_LINE = re.compile(r"^[^\S\n]*+#[^\n]*", re.M)
#: characters of text a CSV is split into at a time (whole lines): its blank stretches are skipped whole
CHUNK_CHARS = 1 << 20


def line_chunks(text: str, size: int = CHUNK_CHARS):
    r"""``text`` in pieces of about ``size`` characters cut at line ends.

    The ``\n`` between two pieces is left out, so that a pass over a file's lines never holds a list of all of them.

    Parameters
    ----------
    text : str
        Lines ending in ``\n``.
    size : int
        Characters per piece, at least (a piece ends at the next line end).

    Yields
    ------
    str
        Whole lines joined by ``\n``; ``"\n".join`` of the pieces is ``text``.
    """
    a = 0
    while True:
        b = text.find("\n", a + size)
        if b < 0:
            yield text[a:]
            return
        yield text[a:b]
        a = b + 1


#: a run of CSV lines that hold only delimiters (and blanks): empty rows, as spreadsheet exports leave them
_DELIMITER_ROWS = re.compile(r"^(?:[ \t]*+[,;][,;\t ]*+(?:\n|\Z)){1,4096}+", re.M)


def blank_delimiter_rows(grid: Grid, text: str) -> str:
    """``text`` with its rows of delimiters only blanked (their line numbers kept); counts them on ``grid``.

    Runs of such rows are matched whole, so a file of millions of them costs one pass.

    Parameters
    ----------
    grid : Grid
        The grid being read: its count of skipped delimiter rows (and their first lines) grows.
    text : str
        CSV text.

    Returns
    -------
    str
        The text with each row of delimiters only emptied (its line end kept).
    """
    pieces, changed, line = [], False, grid.first_line
    for piece in line_chunks(text):  # a chunk of blank lines is passed over whole
        lines = piece.count("\n") + 1
        if not piece.isspace() and _DELIMITER_ROWS.search(piece) is not None:
            piece, changed = _blank_rows(grid, piece, line), True
        pieces.append(piece)
        line += lines
    return "\n".join(pieces).rstrip("\n") if changed else text


def _blank_rows(grid: Grid, text: str, first_line: int) -> str:
    """``text`` (whole lines, the first numbered ``first_line``) with its rows of delimiters emptied."""
    where = [first_line, 0]  # line number at position

    def blank(m) -> str:
        run = m.group()
        n = run.count("\n")
        rows = n + (not run.endswith("\n"))
        if len(grid.delimiter_lines) < 3:
            where[0] += text.count("\n", where[1], m.start())
            where[1] = m.start()
            grid.delimiter_lines += range(where[0], where[0] + min(rows, 3 - len(grid.delimiter_lines)))
        grid.delimiter_rows += rows
        return "\n" * n

    return _DELIMITER_ROWS.sub(blank, text)


def check_long_lines(shown: str, text: str, first_line: int, limits: ReadLimits) -> None:
    """Refuse a CSV one of whose cells (or headers, or notes) is over ``limits.max_cell_chars`` characters.

    This runs before any line is split. Stretches of max_cell_chars/2 characters are probed for a line end: only a line
    longer than that is split, at each candidate delimiter, and it is refused when even the delimiter that cuts it
    finest leaves a cell over the limit.

    Parameters
    ----------
    shown : str
        The file's name as messages show it.
    text : str
        CSV text.
    first_line : int
        The file line number of the text's first line.
    limits : ReadLimits
        The reading limits (``max_cell_chars``).

    Raises
    ------
    LimitError
        Naming the line and quoting the cell's first 30 characters with its length.
    """
    limit = limits.max_cell_chars
    step = max(1, limit // 2)
    end = -1
    for pos in range(0, len(text), step):
        if pos < end or text.find("\n", pos, pos + step) >= 0 or pos + step > len(text):
            continue
        start = text.rfind("\n", 0, pos) + 1
        end = text.find("\n", pos)
        end = len(text) if end < 0 else end
        widest, at = min(_widest_field(text, start, end, d, step) for d in (",", ";", "\t"))
        if widest > limit:
            line = first_line + text.count("\n", 0, start)
            raise limits.error(
                "max_cell_chars",
                f"a cell of {widest:,} characters ('{visible(text[at : at + 30])}…')",
                shown,
                line,
            )


def _widest_field(text: str, start: int, end: int, delim: str, step: int) -> int:
    """(length, start) of the longest run between ``delim``s in text[start:end].

    Runs are looked for where a stretch of ``step`` characters holds no ``delim``.
    """
    widest, at, last = 0, start, -1
    for pos in range(start, end, step):
        if pos < last or text.find(delim, pos, min(end, pos + step)) >= 0:
            continue
        a = max(text.rfind(delim, start, pos) + 1, start)
        last = text.find(delim, pos, end)
        last = end if last < 0 else last
        if last - a > widest:
            widest, at = last - a, a
    return widest, at


def csv_grid(shown: str, text: str, first_line: int = 1, limits: ReadLimits | None = None) -> Grid:
    """Rows of a CSV text for each candidate delimiter (the table reader picks the one whose header fits).

    Parsed as a whole (not line by line), so quoted fields may span lines; a
    row's number is the line it starts on. Only the first rows are parsed
    for each candidate; the whole text is parsed once, with the delimiter
    chosen (``Grid.parse_all``).

    Parameters
    ----------
    shown : str
        The file's name as messages show it.
    text : str
        The CSV text.
    first_line : int, optional
        Line number of the text's first line in its file.
    limits : ReadLimits, optional
        Read limits (None: the defaults).

    Returns
    -------
    Grid

    References
    ----------
    RFC 4180, Common Format and MIME Type for Comma-Separated Values (CSV) Files, doi:10.17487/RFC4180.
    """
    if "#" in text or "\r" in text:
        # comment lines become blank (keeping the numbering); a '#' inside a quoted field is left alone. Lines
        # end only at \n, \r\n or \r, as for the csv module (str.splitlines would also split at \v, \f, \x1c-\x1e,
        # U+0085 -- the '…' of a Windows-1252 file read as Latin-1 -- and U+2028/2029 inside a cell)
        # (on the whole text, never as a list of every line: a file of millions of blank lines or lone CRs
        # costs a few copies of its text, not a Python string per line)
        kept = text.replace("\r\n", "\n").replace("\r", "\n") if "\r" in text else text
        if kept.endswith("\n"):  # the last line's end
            kept = kept[:-1]
        if "#" in kept:
            kept = _COMMENT_LINE.sub("", kept)
    else:  # the usual file: nothing to blank, lines already end in '\n'
        kept = text  # its last line end kept (cutting it would copy the whole text): a blank last line, skipped
    grid = Grid(shown, None, [], (",", ";", "\t"), first_line=first_line)
    check_long_lines(shown, kept, first_line, limits or ReadLimits())
    kept = blank_delimiter_rows(grid, kept)
    head, grid.head_cut = _head(kept)
    limits = limits or ReadLimits()
    grid.limits = limits
    for delim in grid.delimiters:  # each candidate: a line split into max_columns + 1 cells at most
        grid.text_rows[delim] = parse_rows(head, delim, first_line, limits.max_columns, strict=False)
    grid.full_text = kept
    grid.rows = grid.text_rows[","]
    return grid


class RowTooWide(Exception):
    """A CSV line holding more cells with text than a table may have columns (raised by :func:`parse_rows`)."""

    def __init__(self, line: int, cells: int):
        super().__init__(line, cells)
        self.line, self.cells = line, cells


#: characters of the first 200 lines of a CSV split for each candidate delimiter, all together; a line beyond
#: is cut to HEAD_LINE_CHARS (its cells are then read by the whole parse, not from the head)
HEAD_CHARS = 4 * 2**20
HEAD_LINE_CHARS = 64 * 2**10


def _head(text: str, lines: int = 200) -> tuple[str, bool]:
    """The first ``lines`` lines of ``text`` and whether a line was cut.

    At most HEAD_CHARS characters, each line at least HEAD_LINE_CHARS; made without a copy of the rest of the text.
    """
    pieces, a, budget, cut = [], 0, HEAD_CHARS, False
    for _ in range(lines):
        b = text.find("\n", a)
        end = len(text) if b < 0 else b
        allow = max(HEAD_LINE_CHARS, budget)
        if end - a > allow:
            end, cut = a + allow, True
        pieces.append(text[a:end])
        budget -= end - a
        if b < 0:
            break
        a = b + 1
    return "\n".join(pieces), cut


#: cells the first lines of a CSV may be split into, all together, for each candidate delimiter (a header wider
#: than the limit is split whole, so that its message counts its columns; a file of such lines is not)
HEAD_CELLS = 100_000


def _head_cap(line: str, delim: str, cap: int, rows: list) -> int:
    """The maxsplit of one of the first lines: -1 (whole) or ``cap``.

    -1 while the first lines' cells stay under HEAD_CELLS or the line is narrower than ``cap`` cells, else ``cap``.
    """
    if cap < 0:
        return -1
    n = line.count(delim) + 1
    if n <= cap or sum(len(r[1]) for r in rows) + n <= HEAD_CELLS:
        return -1
    return cap


def _cap_width(rows: list, start: int, delim: str, cap: int, strict: bool) -> None:
    """Rows ``start:`` split with at most ``cap`` + 1 cells.

    The last cell, the rest of a longer line, is emptied when it holds only delimiters and blanks (a spreadsheet's
    trailing empty cells), else RowTooWide is raised when ``strict``.
    """
    for k in range(start, len(rows)):
        cells = rows[k][1]
        if len(cells) > cap:
            rest = cells[cap]
            if rest.strip(delim + " \t"):
                if strict:
                    raise RowTooWide(rows[k][0], cap + 1 + rest.count(delim))
            else:
                cells[cap] = ""


def parse_rows(
    text: str, delim: str, first_line: int = 1, max_cells: int | None = None, strict: bool = True
) -> list[tuple[int, list[str]]]:
    """Rows with their first line number (the text's first line is ``first_line``).

    The cells of the first 200 rows are stripped (the header and the metadata are searched there), later cells kept as
    written (the table reader strips columns where needed).

    Parameters
    ----------
    text : str
        The CSV text.
    delim : str
        The delimiter.
    first_line : int, optional
        Line number of the text's first line.

    Returns
    -------
    list of (int, list of str)

    Raises
    ------
    RowTooWide
        With ``max_cells`` and ``strict``: a line holds text in more than ``max_cells`` cells (a line is split
        into ``max_cells`` + 1 cells at most, so the cells made are bounded by rows x columns; trailing empty
        cells are dropped). Without ``strict`` (a candidate delimiter tried on the first lines) the rest of the
        line is kept in its last cell.

    References
    ----------
    RFC 4180, Common Format and MIME Type for Comma-Separated Values (CSV) Files, doi:10.17487/RFC4180.
    """
    rows = []
    cap = -1 if max_cells is None else int(max_cells)
    if '"' not in text and "\r" not in text:  # no quoting: a line is a row, split on the delimiter (fast)
        # split a chunk at a time, and a chunk of blank lines not at all (counted, never listed)
        line = first_line
        for piece in line_chunks(text):
            if not piece.isspace():
                start = len(rows)
                rows += [
                    (line + k, ln.split(delim, cap if strict else _head_cap(ln, delim, cap, rows)))
                    for k, ln in enumerate(piece.split("\n"))
                    if ln and not ln.isspace()
                ]
                if cap >= 0 and strict:
                    _cap_width(rows, start, delim, cap, strict)
            line += piece.count("\n") + 1
        for k in range(min(200, len(rows))):
            rows[k] = (rows[k][0], [c.strip() for c in rows[k][1]])
        return rows
    reader = csv.reader(io.StringIO(text), delimiter=delim)
    start = first_line
    try:
        for cells in reader:
            if cells and (cells[0].strip() or "".join(cells).strip()):  # skip blank rows (first cell decides fast)
                keep = cap if strict else _head_cap(delim.join(cells), delim, cap, rows)
                if 0 <= keep < len(cells):  # one row at a time: its extra cells joined back, then bounded
                    cells = [*cells[:keep], delim.join(cells[keep:])]
                rows.append((start, [c.strip() for c in cells] if len(rows) < 200 else cells))
                if strict and 0 <= cap < len(cells):
                    _cap_width(rows, len(rows) - 1, delim, cap, strict)
            start = reader.line_num + first_line
    except csv.Error as exc:
        rows.append((start, [f"\x00csv error: {exc}"]))
    return rows


def _cell_text(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "TRUE" if value else "FALSE"
    if isinstance(value, float):
        return "" if value != value else repr(value)
    if isinstance(value, int):
        return str(value)
    if hasattr(value, "isoformat"):
        return value.isoformat()
    return str(value).strip()


def _spreadsheet_grid(shown: str, data: bytes, suffix: str, sheet, limits: ReadLimits | None = None) -> Grid:
    """The rows holding data of one sheet of an .xlsx or .ods workbook, read as a stream within ``limits``."""
    limits = limits or ReadLimits()
    try:
        book = _Zip(shown, data, limits)
        name, rows = (_ods_rows if suffix == ".ods" else _xlsx_rows)(book, sheet)
    except InputError:
        raise
    except Exception as exc:  # a damaged or mislabelled workbook: one clear message
        raise InputError(
            Problem(shown, None, None, f"cannot be read as a {suffix} workbook ({type(exc).__name__}: {exc})")
        ) from None
    rows = [(n, cells) for n, cells in rows if any(cells) and not cells[0].startswith("#")]
    return Grid(shown, name, rows, (), notes=book.notes, warnings=book.warnings, merged=book.merged)


def _pick_sheet(shown: str, names: list[str], sheet, hidden: set[int] = frozenset(), book=None) -> int:
    """Index (from 0) of the sheet asked for.

    The first *visible* one when None, a name, or a number counted from 1. ``hidden`` holds the indices of hidden
    sheets: one passed over, or one asked for, is said on ``book.warnings``.
    """
    if not names:
        raise InputError(Problem(shown, None, None, "the workbook has no sheets"))
    if sheet is None:
        k = next((i for i in range(len(names)) if i not in hidden), 0)
        if k > 0 and book is not None:
            before = ", ".join(f"'{names[i]}'" for i in range(k))
            book.warnings.append(
                f"{shown}: the workbook's first sheet{'s' if k > 1 else ''} {before} "
                f"{'are' if k > 1 else 'is'} hidden: sheet '{names[k]}', the first visible one, is read "
                f"(--sheet '{names[0]}' reads a hidden one)"
            )
        elif k in hidden and book is not None:
            book.warnings.append(f"{shown}: every sheet of the workbook is hidden: the first, '{names[0]}', is read")
        return k
    k = _pick_named_sheet(shown, names, sheet)
    if k in hidden and book is not None:
        book.notes.append(f"sheet '{names[k]}' is hidden in the workbook; read as asked (--sheet)")
    return k


def _pick_named_sheet(shown: str, names: list[str], sheet) -> int:
    """Index (from 0) of the sheet asked for by name or by number counted from 1."""
    if isinstance(sheet, int) or (
        isinstance(sheet, str) and sheet.strip().lstrip("-").isdigit() and sheet.strip() not in names
    ):
        k = int(sheet)
        if not 1 <= k <= len(names):
            raise InputError(
                Problem(
                    shown,
                    None,
                    None,
                    f"there is no sheet number {k}: the workbook has "
                    f"{len(names)} ({', '.join(names)}); sheets count from 1",
                )
            )
        return k - 1
    if sheet not in names:
        raise InputError(Problem(shown, None, None, f"no sheet named '{sheet}'; the sheets are {', '.join(names)}"))
    return names.index(sheet)


class _Stop(Exception):
    """Raised inside an XML handler to stop reading a part (what was needed has been read)."""


class _Zip:
    """A workbook's zip archive, opened after its declared sizes were checked against ``limits.max_bytes``.

    Its parts are parsed as streams, decompression stopping at the limit whatever the zip declares.
    """

    def __init__(self, shown: str, data: bytes, limits: ReadLimits):
        import zipfile

        self.shown, self.limits = shown, limits
        parts = _zip_parts(data)
        if parts is not None and parts > MAX_ZIP_PARTS:
            raise InputError(
                Problem(
                    shown,
                    None,
                    None,
                    f"the zip archive holds {parts:,} parts; a spreadsheet "
                    f"holds tens to hundreds (at most {MAX_ZIP_PARTS:,} are read)",
                )
            )
        self.zip = zipfile.ZipFile(io.BytesIO(data))
        infos = self.zip.infolist()
        declared = sum(i.file_size for i in infos)
        if declared > limits.max_bytes:
            big = max(infos, key=lambda i: i.file_size)
            raise limits.error(
                "max_bytes",
                f"the workbook's {len(infos)} parts expand to {declared / 2**20:,.1f} MiB "
                f"({big.filename}: {big.file_size / 2**20:,.1f} MiB, compressed "
                f"{big.compress_size / 2**20:,.2f} MiB; a zip bomb?)",
                shown,
            )
        self.names = {i.filename for i in infos}
        self.used = 0  # bytes decompressed so far, across parts
        self.notes: list[str] = []  # what the reading of the workbook tells (merged cells, a hidden sheet read)
        self.warnings: list[str] = []  # hidden sheets passed over
        #: line -> (first column, last column, first line) of each merged range over it that spans columns or rows
        self.merged: dict[int, list[tuple[int, int, int]]] = {}

    def has(self, name: str) -> bool:
        return name in self.names

    def parse(self, name: str, handler, sheet: str | None = None) -> None:
        """Feed part ``name`` to ``handler`` (start, end, text methods) in 1 MiB pieces; a DTD is refused."""
        from xml.parsers import expat

        parser = expat.ParserCreate(namespace_separator=" ")
        parser.buffer_text = True
        parser.ordered_attributes = False

        def doctype(*_):
            raise InputError(
                Problem(
                    self.shown,
                    None,
                    None,
                    f"part '{name}' declares a document type (DTD); a "
                    "spreadsheet never does: refused (entity expansion)",
                    sheet,
                )
            )

        parser.StartDoctypeDeclHandler = doctype
        parser.EntityDeclHandler = doctype
        # every element counts, and its depth: a hostile part may nest or repeat elements no cell holds
        budget = [ELEMENTS_PER_CELL * self.limits.max_cells + 100_000, 0]  # elements left, depth
        start, end = handler.start, handler.end

        def counted_start(name, attrs):
            budget[0] -= 1
            budget[1] += 1
            if budget[1] > MAX_XML_DEPTH:
                raise InputError(
                    Problem(
                        self.shown,
                        None,
                        None,
                        f"part '{name_}' nests XML elements more than {MAX_XML_DEPTH} deep; a spreadsheet nests "
                        "about 10: refused (a damaged or hostile file)",
                        sheet,
                    )
                )
            if budget[0] < 0:
                raise self.limits.error(
                    "max_cells",
                    f"part '{name_}' holds more XML elements than {ELEMENTS_PER_CELL} per cell allowed",
                    self.shown,
                    sheet=sheet,
                )
            start(name, attrs)

        def counted_end(name):
            budget[1] -= 1
            end(name)

        name_ = name
        parser.StartElementHandler = counted_start
        parser.EndElementHandler = counted_end
        parser.CharacterDataHandler = handler.text
        with self.zip.open(name) as stream:
            try:
                while True:
                    chunk = stream.read(1 << 20)
                    self.used += len(chunk)
                    if self.used > self.limits.max_bytes:
                        raise self.limits.error(
                            "max_bytes",
                            f"the workbook's XML expands beyond what its zip declares (at part '{name}')",
                            self.shown,
                            sheet=sheet,
                        )
                    parser.Parse(chunk, not chunk)
                    if not chunk:
                        break
            except _Stop:
                pass
            except expat.ExpatError as exc:
                raise InputError(
                    Problem(
                        self.shown,
                        None,
                        None,
                        f"part '{name}' is not valid XML ({expat.ErrorString(exc.code)}, line {exc.lineno})",
                        sheet,
                    )
                ) from None


def _zip_parts(data: bytes) -> int | None:
    """The number of parts a zip's end record declares (read before the central directory is), or None."""
    k = data.rfind(b"PK\x05\x06", max(0, len(data) - 65_557))
    if k < 0 or k + 12 > len(data):
        return None
    n = int.from_bytes(data[k + 10 : k + 12], "little")
    if n == 0xFFFF:  # zip64: the count is in the zip64 end record
        j = data.rfind(b"PK\x06\x06", 0, k)
        if j >= 0 and j + 40 <= len(data):
            n = int.from_bytes(data[j + 32 : j + 40], "little")
    return n


def _local(name: str) -> str:
    """The local name of an expat name 'namespace local'."""
    return name.rpartition(" ")[2]


def _attr(attrs: dict, local: str, default=None):
    """An attribute by its local name, whatever its namespace."""
    for key, value in attrs.items():
        if key == local or key.endswith(" " + local):
            return value
    return default


def _number_text(text: str, integral_floats: bool = False) -> str:
    """A number as the XML writes it, as text.

    A whole number when written as one (and, with ``integral_floats``, a float of integral value, as .ods readers give
    it), else the shortest float that round-trips.
    """
    t = text.strip()
    try:
        if t.lstrip("+-").isdigit():
            return str(int(t))
        v = float(t)
    except ValueError:
        return t
    if v != v:
        return ""
    return str(int(v)) if integral_floats and v.is_integer() else repr(v)


class _Rows:
    """The rows of one sheet being read.

    Each row's cells (column -> text), padded to its last cell holding data; every cell is counted against ``max_cells``
    and the columns against ``max_columns``.
    """

    def __init__(self, shown: str, limits: ReadLimits):
        self.shown, self.limits = shown, limits
        self.sheet: str | None = None
        self.rows: list[tuple[int, list[str]]] = []
        self.visited = 0
        self.chars = 0  # characters of cell text made so far (expanded), against max_bytes
        self.merges: list[tuple[int, int, int, int]] = []  # merged ranges: first row, column, last row, column
        self.formulas: list[str] = []  # cells holding a formula without a saved value

    def merge(self, ref: str, rows: int | None = None, cols: int | None = None, line: int = 0, col: int = 0) -> None:
        """Record a merged range: ``ref`` as 'B2:B8' (.xlsx), or its size from the top-left cell (.ods)."""
        if rows is None:
            a, _, b = ref.partition(":")
            m1, m2 = _CELL_REF.fullmatch(a.replace("$", "")), _CELL_REF.fullmatch(b.replace("$", ""))
            if not (m1 and m2):
                return
            c1, r1, c2, r2 = _column_number(m1[1]), int(m1[2]), _column_number(m2[1]), int(m2[2])
        else:
            c1, r1, c2, r2 = col, line, col + cols - 1, line + rows - 1
        self.visit((r2 - r1 + 1) * (c2 - c1 + 1), r1)  # the cells a merge fills count
        self.column_ok(c2, r1)
        self.merges.append((r1, c1, r2, c2))

    def formula(self, col: int, line: int, text: str) -> None:
        """Record a cell holding a formula without the value it computes."""
        if len(self.formulas) < 1000:
            self.formulas.append(f"{_column_letters(col)}{line} (={text[:40]})")

    def refuse_formulas(self) -> None:
        """A sheet with formulas whose values were never saved cannot be read as it looks: refused, naming them."""
        if self.formulas:
            shown = ", ".join(self.formulas[:5]) + (
                f" and {len(self.formulas) - 5:,} more" if len(self.formulas) > 5 else ""
            )
            raise InputError(
                Problem(
                    self.shown,
                    None,
                    None,
                    f"{'cells' if len(self.formulas) > 1 else 'cell'} {shown} "
                    f"{'hold formulas' if len(self.formulas) > 1 else 'holds a formula'} without a saved value "
                    "(the workbook was written by a program "
                    "that does not compute formulas): capred reads values, not formulas. Open and save the "
                    "workbook in Excel or LibreOffice, or paste the values",
                    self.sheet,
                )
            )

    def fill_merges(self, book) -> None:
        """Give each merged range the value of its top-left cell in every row holding data (as it looks).

        The fill is said once in ``book.notes``.
        """
        if not self.merges:
            return
        at = {line: k for k, (line, _) in enumerate(self.rows)}
        filled = []
        for r1, c1, r2, c2 in self.merges:
            k = at.get(r1)
            cells = self.rows[k][1] if k is not None else []
            value = cells[c1 - 1] if c1 - 1 < len(cells) else ""
            if not value or (r1 == r2 and c1 == c2):
                continue
            for line in range(r1, r2 + 1):
                j = at.get(line)
                if j is None:
                    continue
                book.merged.setdefault(line, []).append((c1, c2, r1))
                row = self.rows[j][1]
                if len(row) < c2:
                    row.extend([""] * (c2 - len(row)))
                for c in range(c1, c2 + 1):
                    if not row[c - 1]:
                        row[c - 1] = value
            filled.append(f"{_column_letters(c1)}{r1}:{_column_letters(c2)}{r2} ('{value[:30]}')")
        if filled:
            more = f" and {len(filled) - 5:,} more" if len(filled) > 5 else ""
            book.notes.append(f"merged cells take the value of their first cell: {', '.join(filled[:5])}{more}")

    def cell_chars(self, n: int, line: int | None, col: int | None = None) -> None:
        """Refuse the file when one cell's text, expanded, holds ``n`` > ``max_cell_chars`` characters."""
        if n > self.limits.max_cell_chars:
            ref = f"cell {_column_letters(col)}{line}" if col and line else f"a cell of row {line}"
            raise self.limits.error(
                "max_cell_chars",
                f"{ref} holds more than {self.limits.max_cell_chars:,} characters once expanded",
                self.shown,
                line,
                _column_letters(col) if col else None,
                self.sheet,
            )

    def more_text(self, n: int, line: int | None) -> None:
        """Count ``n`` more characters of expanded text against ``max_bytes``.

        That is what the XML's bytes do not bound: an .ods's repeated spaces, cells and rows, a workbook's shared
        strings times the cells referencing them.
        """
        self.chars += n
        if self.chars > self.limits.max_bytes:
            raise self.limits.error(
                "max_bytes",
                f"the sheet's text expands beyond {self.limits.shown('max_bytes')} (at row {line})",
                self.shown,
                line,
                sheet=self.sheet,
            )

    def visit(self, n: int = 1, line: int | None = None) -> None:
        self.visited += n
        if self.visited > self.limits.max_cells:
            raise self.limits.error(
                "max_cells",
                f"the sheet holds more than {self.limits.max_cells:,} cells (reached at row {line})",
                self.shown,
                line,
                sheet=self.sheet,
            )

    def column_ok(self, col: int, line: int) -> None:
        if col > self.limits.max_columns:
            ref = f"{_column_letters(col)}{line}"
            raise self.limits.error(
                "max_columns",
                f"cell {ref} holds data in column {col:,}",
                self.shown,
                line,
                _column_letters(col),
                self.sheet,
            )

    def add(self, line: int, cells: dict[int, str], repeat: int = 1) -> None:
        if not cells:
            return
        width = max(cells)
        self.visit((width - len(cells)) + (repeat - 1) * width, line)
        if line + repeat - 1 > MAX_SHEET_ROWS:
            shown = f"{line:,}" if line < 10**20 else "a number of 21 digits or more"
            raise InputError(
                Problem(
                    self.shown,
                    None,
                    None,
                    f"data in row {shown}, beyond the {MAX_SHEET_ROWS:,} rows a worksheet holds: "
                    "a damaged or hand-made file (save it again from the spreadsheet program)",
                    self.sheet,
                )
            )
        if repeat > 1:  # the copies of a repeated row's text count as text made
            self.more_text(sum(map(len, cells.values())) * (repeat - 1), line)
        row = [""] * width
        for col, text in cells.items():
            row[col - 1] = text
        self.rows.append((line, row))
        for k in range(1, repeat):
            self.rows.append((line + k, list(row)))


_CELL_REF = re.compile(r"([A-Za-z]{1,3})([0-9]{1,7})")


def _column_letters(col: int) -> str:
    letters = ""
    while col > 0:
        col, r = divmod(col - 1, 26)
        letters = chr(65 + r) + letters
    return letters


def _column_number(ref: str) -> int:
    n = 0
    for ch in ref:
        o = ord(ch) & ~32  # upper case
        if 65 <= o <= 90:
            n = n * 26 + o - 64
        else:
            break
    return n


# --- .xlsx (Office Open XML) -----------------------------------------------------------------------------------------
_REL = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"


class _Collect:
    """Elements of interest as (local name, attributes) with the text inside chosen elements."""

    def __init__(self, wanted: set[str]):
        self.wanted = wanted
        self.found: list[tuple[str, dict]] = []

    def start(self, name, attrs):
        local = _local(name)
        if local in self.wanted:
            self.found.append((local, attrs))

    def end(self, name):
        pass

    def text(self, data):
        pass


def _xlsx_rows(book: _Zip, sheet) -> tuple[str, list]:
    import posixpath

    def rels(path: str) -> dict[str, tuple[str, str]]:
        folder, base = posixpath.split(path)
        rel_path = posixpath.join(folder, "_rels", base + ".rels")
        out = {}
        if book.has(rel_path):
            c = _Collect({"Relationship"})
            book.parse(rel_path, c)
            for _, a in c.found:
                target = a.get("Target", "")
                full = (
                    target.lstrip("/") if target.startswith("/") else posixpath.normpath(posixpath.join(folder, target))
                )
                out[a.get("Id", "")] = (a.get("Type", "").rpartition("/")[2], full)
        return out

    root = rels("")
    wb_path = next((p for t, p in root.values() if t == "officeDocument"), "xl/workbook.xml")
    c = _Collect({"sheet", "workbookPr"})
    book.parse(wb_path, c)
    found = [a for tag, a in c.found if tag == "sheet"]
    sheets = [(a.get("name", ""), _attr(a, "id", "")) for a in found]
    hidden = {k for k, a in enumerate(found) if a.get("state", "visible") in ("hidden", "veryHidden")}
    date1904 = any(tag == "workbookPr" and a.get("date1904", "").lower() in ("1", "true") for tag, a in c.found)
    names = [n for n, _ in sheets]
    k = _pick_sheet(book.shown, names, sheet, hidden, book)
    name = names[k]
    wb_rels = rels(wb_path)
    kind, path = wb_rels.get(sheets[k][1], ("", ""))
    if kind != "worksheet" or not book.has(path):
        raise InputError(
            Problem(
                book.shown, None, None, f"sheet '{name}' is not a table of cells ({kind or 'no worksheet part'})", name
            )
        )
    strings_path = next((p for t, p in wb_rels.values() if t == "sharedStrings"), None)
    styles_path = next((p for t, p in wb_rels.values() if t == "styles"), None)
    strings = _xlsx_strings(book, strings_path, name) if strings_path and book.has(strings_path) else []
    dates = _xlsx_date_styles(book, styles_path) if styles_path and book.has(styles_path) else {}
    rows = _Rows(book.shown, book.limits)
    rows.sheet = name
    handler = _XlsxSheet(rows, strings, dates, date1904)
    book.parse(path, handler, name)
    rows.refuse_formulas()
    rows.fill_merges(book)
    return name, rows.rows


class _XlsxStrings:
    """The shared strings of a workbook: the text of each <si>, phonetic runs left out."""

    def __init__(self, book: _Zip, sheet: str):
        self.book, self.sheet = book, sheet
        self.strings: list[str] = []
        self.parts: list[str] | None = None
        self.in_t = False
        self.phonetic = 0

    def start(self, name, attrs):
        local = _local(name)
        if local == "si":
            self.parts = []
            self.chars = 0
        elif local == "t" and self.parts is not None and not self.phonetic:
            self.in_t = True
        elif local == "rPh":
            self.phonetic += 1

    def end(self, name):
        local = _local(name)
        if local == "t":
            self.in_t = False
        elif local == "rPh":
            self.phonetic -= 1
        elif local == "si" and self.parts is not None:
            self.strings.append("".join(self.parts))
            self.parts = None
            if len(self.strings) > self.book.limits.max_cells:
                raise self.book.limits.error(
                    "max_cells",
                    f"the workbook holds more than {self.book.limits.max_cells:,} shared strings",
                    self.book.shown,
                    sheet=self.sheet,
                )

    def text(self, data):
        if self.in_t:
            self.parts.append(data)
            self.chars = getattr(self, "chars", 0) + len(data)
            if self.chars > self.book.limits.max_cell_chars:
                raise self.book.limits.error(
                    "max_cell_chars",
                    f"shared string {len(self.strings) + 1:,} holds more than "
                    f"{self.book.limits.max_cell_chars:,} characters",
                    self.book.shown,
                    sheet=self.sheet,
                )


def _xlsx_strings(book: _Zip, path: str, sheet: str) -> list[str]:
    handler = _XlsxStrings(book, sheet)
    book.parse(path, handler, sheet)
    return handler.strings


def _xlsx_date_styles(book: _Zip, path: str) -> dict[int, bool]:
    """Cell styles (index into cellXfs) whose number format is a date or a time: True for a duration."""
    from openpyxl.styles.numbers import BUILTIN_FORMATS, is_date_format, is_timedelta_format

    class Styles:
        def __init__(self):
            self.formats: dict[int, str] = {}
            self.xfs: list[int] = []
            self.in_xfs = False

        def start(self, name, attrs):
            local = _local(name)
            if local == "numFmt":
                try:
                    self.formats[int(attrs.get("numFmtId", "-1"))] = attrs.get("formatCode", "")
                except ValueError:
                    pass
            elif local == "cellXfs":
                self.in_xfs = True
            elif local == "xf" and self.in_xfs:
                try:
                    self.xfs.append(int(attrs.get("numFmtId", "0")))
                except ValueError:
                    self.xfs.append(0)
                if len(self.xfs) > book.limits.max_cells:
                    raise book.limits.error(
                        "max_cells", "the workbook's styles hold more cell formats than the cells allowed", book.shown
                    )

        def end(self, name):
            if _local(name) == "cellXfs":
                self.in_xfs = False

        def text(self, data):
            pass

    st = Styles()
    book.parse(path, st)
    out = {}
    for k, fid in enumerate(st.xfs):
        code = st.formats.get(fid, BUILTIN_FORMATS.get(fid, ""))
        if code and is_date_format(code):
            out[k] = is_timedelta_format(code)
    return out


class _XlsxSheet:
    """A worksheet's <row>/<c> elements to rows of text, only the cells holding a value kept."""

    def __init__(self, rows: _Rows, strings: list[str], dates: dict[int, bool], date1904: bool):
        self.out, self.strings, self.dates, self.date1904 = rows, strings, dates, date1904
        self.line = 0
        self.col = 0
        self.cells: dict[int, str] | None = None
        self.ctype = "n"
        self.style = 0
        self.buf: list[str] | None = None
        self.value: str | None = None
        self.inline: list[str] | None = None
        self.phonetic = 0
        self.chars = 0  # characters of the current cell's text
        self.formula: list[str] | str | None = None  # the current cell's formula (its text while read)
        self.after_data: int | None = None  # elements seen after </sheetData> (None: not yet there)

    def start(self, name, attrs):
        local = _local(name)
        if self.after_data is not None:  # past <sheetData>: only the merged ranges are read, the rest is formatting
            self.after_data += 1
            if self.after_data > AFTER_DATA_ELEMENTS:
                raise _Stop
            if local == "mergeCell":
                self.out.merge(attrs.get("ref", ""))
            return
        if local == "c":
            ref = attrs.get("r")
            self.col = _column_number(ref) if ref else self.col + 1
            self.ctype = attrs.get("t", "n")
            style = attrs.get("s")
            self.style = int(style) if style and style.isdigit() else 0
            self.value = None
            self.inline = None
            self.formula = None
            self.chars = 0
            self.out.visit(1, self.line)
        elif local == "v":
            self.buf = []
        elif local == "f":
            self.formula = []
        elif local == "row":
            r = attrs.get("r")
            # a row number of thousands of digits is not converted (Python refuses, and no sheet has it)
            self.line = (int(r) if len(r) <= 20 else 10**20) if r and r.isdigit() else self.line + 1
            self.col = 0
            self.cells = {}
        elif local == "is":
            self.inline = []
        elif local == "t" and self.inline is not None and not self.phonetic:
            self.buf = []
        elif local == "rPh":
            self.phonetic += 1

    def end(self, name):
        local = _local(name)
        if self.after_data is not None:
            if local == "mergeCells":
                raise _Stop  # nothing after it is read
            return
        if local == "sheetData":
            self.after_data = 0
        elif local == "v":
            self.value = "".join(self.buf)
            self.buf = None
        elif local == "t" and self.buf is not None and self.inline is not None:
            self.inline.append("".join(self.buf))
            self.buf = None
        elif local == "rPh":
            self.phonetic -= 1
        elif local == "f" and self.formula is not None:
            self.formula = "".join(self.formula) or "(shared)"
        elif local == "c":
            text = self._cell()
            if not text and self.formula is not None and not self.value:
                self.out.formula(self.col, self.line, self.formula)
            if text:
                self.out.column_ok(self.col, self.line)
                if self.ctype == "s":  # a shared string's text is made again for every cell referencing it
                    self.out.more_text(len(text), self.line)
                if self.cells is None:  # a cell outside any row: its own row
                    self.cells = {}
                self.cells[self.col] = text
        elif local == "row":
            if self.cells:
                self.out.add(self.line, self.cells)
            self.cells = None

    def text(self, data):
        if isinstance(self.formula, list) and len(self.formula) < 64:
            self.formula.append(data)
        if self.buf is not None:
            self.buf.append(data)
            self.chars += len(data)
            if self.chars > self.out.limits.max_cell_chars:
                self.out.cell_chars(self.chars, self.line, self.col)

    def _cell(self) -> str:
        t, v = self.ctype, self.value
        if t == "inlineStr":
            return "".join(self.inline or ()).strip()
        if v is None or v == "":
            return ""
        if t == "s":
            k = v.strip()
            return self.strings[int(k)].strip() if k.isdigit() and int(k) < len(self.strings) else ""
        if t == "b":
            return "TRUE" if v.strip() in ("1", "true") else "FALSE"
        if t in ("str", "e"):
            return v.strip()
        if t == "d":
            return v.strip()
        if self.style in self.dates:
            from openpyxl.utils.datetime import CALENDAR_MAC_1904, CALENDAR_WINDOWS_1900, from_excel

            try:
                when = from_excel(
                    float(v),
                    CALENDAR_MAC_1904 if self.date1904 else CALENDAR_WINDOWS_1900,
                    timedelta=self.dates[self.style],
                )
                return str(when) if self.dates[self.style] else when.isoformat()
            except (ValueError, OverflowError):
                return _number_text(v)
        return _number_text(v)


# --- .ods (OpenDocument) ---------------------------------------------------------------------------------------------
class _OdsContent:
    """content.xml of an .ods: the rows of the sheet asked for and the names of the sheets seen.

    Repeated rows and cells are expanded only where they hold data.
    """

    def __init__(self, rows: _Rows, sheet):
        self.out, self.want = rows, sheet
        self.names: list[str] = []
        self.kept: dict[int, list] = {}  # sheet index -> rows, for the candidates of ``want``
        self.active = False
        self.line = 0
        self.col = 0
        self.cells: dict[int, str] | None = None
        self.row_repeat = 1
        self.cell: dict | None = None
        self.parts: list[str] | None = None
        self.paragraphs = 0
        self.skip = 0  # inside an annotation (a comment on the cell): its text is not the cell's
        digits = isinstance(sheet, str) and sheet.strip().lstrip("-").isdigit()
        self.by_number = int(sheet) if isinstance(sheet, int) or digits else None
        self.first_visible = sheet is None  # the default: the first sheet not hidden
        self.hidden: set[int] = set()  # indices (from 0) of hidden sheets seen
        self.hidden_styles: set[str] = set()  # table styles that hide a sheet (table:display="false")
        self.style: str | None = None
        self.by_name = sheet if isinstance(sheet, str) else None
        self.final = not digits  # a sheet asked for by a name or a number: stop once it is read

    def start(self, name, attrs):
        local = _local(name)
        if self.active:
            if local == "table-cell" or local == "covered-table-cell":
                self.cell = attrs
                self.parts = []
                self.chars = 0
                self.paragraphs = 0
                self.out.visit(1, self.line + 1)
                spans = _count(_attr(attrs, "number-rows-spanned")), _count(_attr(attrs, "number-columns-spanned"))
                if spans != (1, 1):
                    self.out.merge("", spans[0], spans[1], self.line + 1, self.col + 1)
                formula = _attr(attrs, "formula")
                if formula is not None and _attr(attrs, "value-type") is None:
                    self.out.formula(self.col + 1, self.line + 1, (formula.partition(":")[2] or formula).lstrip("="))
                return
            if local == "table-row":
                self.cells = {}
                self.col = 0
                self.row_repeat = _count(_attr(attrs, "number-rows-repeated"))
                return
            if self.parts is not None and not self.skip:
                if local in ("p", "h"):
                    if self.paragraphs:
                        self.parts.append("\n")
                    self.paragraphs += 1
                elif local == "s":  # spaces: counted as expanded, before they are made
                    n = min(_count(_attr(attrs, "c")), self.out.limits.max_cell_chars + 1)
                    self._count_text(n)
                    self.parts.append(" " * n)
                elif local == "tab":
                    self._count_text(1)
                    self.parts.append("\t")
                elif local == "line-break":
                    self._count_text(1)
                    self.parts.append("\n")
            if local == "annotation":
                self.skip += 1
            return
        if local == "style":
            self.style = _attr(attrs, "name") if _attr(attrs, "family") == "table" else None
        elif local == "table-properties" and self.style and _attr(attrs, "display", "true") == "false":
            self.hidden_styles.add(self.style)
        if local == "table":
            self.names.append(_attr(attrs, "name", f"Sheet{len(self.names) + 1}"))
            k = len(self.names)
            if _attr(attrs, "style-name") in self.hidden_styles:
                self.hidden.add(k - 1)
            if (
                k == self.by_number
                or (self.by_name is not None and self.names[-1] == self.by_name)
                or (self.first_visible and k - 1 not in self.hidden)
            ):
                self.first_visible = False
                self.active = True
                self.line = 0
                self.out.rows = self.kept.setdefault(k, [])
                self.out.sheet = self.names[-1]

    def end(self, name):
        if not self.active:
            return
        local = _local(name)
        if local == "table-cell" or local == "covered-table-cell":
            repeat = _count(_attr(self.cell, "number-columns-repeated"))
            text = self._value()
            if text:
                self.out.column_ok(self.col + repeat, self.line + 1)
                self.out.visit(repeat - 1, self.line + 1)
                self.out.more_text(len(text) * (repeat - 1), self.line + 1)  # the copies of a repeated cell
                for k in range(1, repeat + 1):
                    self.cells[self.col + k] = text
            self.col += repeat
            self.cell = self.parts = None
        elif local == "annotation":
            self.skip -= 1
        elif local == "table-row":
            self.out.add(self.line + 1, self.cells, self.row_repeat if self.cells else 1)
            self.line += self.row_repeat
            self.cells = None
        elif local == "table":
            self.active = False
            if self.final:
                raise _Stop

    def text(self, data):
        if self.parts is not None and self.paragraphs and not self.skip:
            self._count_text(len(data))
            self.parts.append(data)

    def _count_text(self, n: int) -> None:
        self.chars += n
        self.out.cell_chars(self.chars, self.line + 1, self.col + 1)
        self.out.more_text(n, self.line + 1)

    def _value(self) -> str:
        a = self.cell
        kind = _attr(a, "value-type")
        if kind in ("float", "percentage", "currency"):
            return _number_text(_attr(a, "value", ""), integral_floats=True)
        if kind == "boolean":
            return "TRUE" if _attr(a, "boolean-value", "").strip().lower() in ("true", "1") else "FALSE"
        if kind == "date":
            from datetime import datetime

            v = _attr(a, "date-value", "")
            try:
                return datetime.fromisoformat(v).isoformat()
            except ValueError:
                return v.strip()
        if kind == "time":
            return _attr(a, "time-value", "").strip()
        return "".join(self.parts or ()).strip()


def _count(text) -> int:
    """A repeat count attribute (1 when absent or not a whole number)."""
    if text and str(text).isdigit():
        return max(1, int(text)) if len(text) <= 20 else 10**20  # beyond any sheet: refused where it holds data
    return 1


def _ods_rows(book: _Zip, sheet) -> tuple[str, list]:
    if not book.has("content.xml"):
        raise InputError(Problem(book.shown, None, None, "no content.xml: not an OpenDocument spreadsheet"))
    rows = _Rows(book.shown, book.limits)
    content = _OdsContent(rows, sheet)
    book.parse("content.xml", content)
    rows.refuse_formulas()
    rows.fill_merges(book)
    names = content.names
    if content.final and content.kept:  # found (names of later sheets were not read)
        k = next(iter(content.kept))
        _pick_sheet(book.shown, names[:k], sheet, content.hidden, book)  # what is said of hidden sheets
        return names[k - 1], content.kept[k]
    k = _pick_sheet(book.shown, names, sheet, content.hidden, book) + 1
    return names[k - 1], content.kept.get(k, [])
