"""The one place where bytes become a grid of cells: CSV text, .xlsx and .ods spreadsheets.

A grid is a list of rows, each with the line (or spreadsheet row) number a
person sees and its cells as text. Numbers from spreadsheets are written in
shortest round-trip form, so nothing is rounded on the way. Comment lines
(starting with '#') and blank lines are skipped but keep their numbers.
"""
from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, Problem

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
class TableSource:
    """A table to read: a path (CSV, .xlsx, .ods) or a DataFrame, the sheet of a workbook, and how to
    read thousands separators ("." to read 1.000 as one thousand in a decimal-comma file)."""

    path: object
    sheet: str | int | None = None
    thousands: str | None = None

    def __post_init__(self) -> None:
        from ..errors import OptionError

        if self.thousands not in (None, ".", ",", " ", "'"):
            raise OptionError(f"--thousands must be '.', ',', ' ' or \"'\" (got {self.thousands!r})")


def source_path(source):
    """The path (or DataFrame) behind a source given as a path, a DataFrame or a TableSource."""
    return source.path if isinstance(source, TableSource) else source


def as_source(source) -> TableSource:
    return source if isinstance(source, TableSource) else TableSource(source)


@dataclass
class Grid:
    shown: str  # the file as messages name it
    sheet: str | None
    rows: list[tuple[int, list[str]]]  # (line number, cells)
    delimiters: tuple[str, ...] = (",",)  # candidate CSV delimiters (spreadsheets: none needed)
    text_rows: dict[str, list[tuple[int, list[str]]]] = field(default_factory=dict)  # first rows, per delimiter
    full_text: str | None = None  # a CSV's text (comment lines blanked), parsed once the delimiter is known

    def parse_all(self, delimiter: str) -> None:
        """Every row of a CSV with the chosen delimiter (spreadsheets: nothing to do)."""
        if self.full_text is not None:
            self.rows = _parse(self.full_text, delimiter)
            self.full_text = None

    def where(self) -> str:
        return f"{self.shown}, sheet '{self.sheet}'" if self.sheet is not None else self.shown


def read_grid(source: TableSource) -> Grid:
    """Rows of cells of a CSV file, a spreadsheet or a DataFrame. Raises InputError when it cannot be read."""
    path = source.path
    if hasattr(path, "to_csv"):  # a pandas DataFrame from a lab script: read like the same table in a file
        return _csv_grid("<DataFrame>", path.to_csv(index=False))
    p = Path(path)
    shown = str(path)
    if not p.exists():
        from ..errors import MissingFileError

        raise MissingFileError(shown)
    if not p.is_file():
        raise InputError(Problem(shown, None, None, "not a file"))
    data = p.read_bytes()
    if p.suffix.lower() in SPREADSHEET_SUFFIXES:
        return _spreadsheet_grid(shown, data, p.suffix.lower(), source.sheet)
    if p.suffix.lower() == ".xls":
        raise InputError(Problem(shown, None, None, "old binary Excel workbooks (.xls) cannot be read: save it as "
                                                    ".xlsx or .csv"))
    for magic, what in _MAGIC:
        if data.startswith(magic):
            raise InputError(Problem(shown, None, None, f"this file is {what}, not a CSV text table"
                                     + (": give it its real extension (.xlsx or .ods)" if magic == b"PK\x03\x04"
                                        else "")))
    text = _decode(data)
    if "\x00" in text[:4096]:
        raise InputError(Problem(shown, None, None, "this is a binary file, not a CSV text table"))
    if source.sheet is not None:
        raise InputError(Problem(shown, None, None, "--sheet is for .xlsx and .ods workbooks, not CSV files"))
    return _csv_grid(shown, text)


def _decode(data: bytes) -> str:
    encodings = ("utf-8-sig", "utf-16") if data[:2] in (b"\xff\xfe", b"\xfe\xff") else ("utf-8-sig", "cp1252")
    for enc in encodings:
        try:
            return data.decode(enc)
        except UnicodeDecodeError:
            continue
    return data.decode("latin-1")


def _csv_grid(shown: str, text: str) -> Grid:
    """Rows of a CSV text for each candidate delimiter (the table reader picks the one whose header fits).

    Parsed as a whole (not line by line), so quoted fields may span lines; a
    row's number is the line it starts on. Only the first rows are parsed
    for each candidate; the whole text is parsed once, with the delimiter
    chosen (``Grid.parse_all``).
    """
    if "#" in text or "\r" in text or any(ch in text for ch in "\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"):
        # comment lines become blank (keeping the numbering); a '#' inside a quoted field is left alone
        kept = "\n".join("" if ln.lstrip().startswith("#") else ln for ln in text.splitlines())
    else:  # the usual file: nothing to blank, lines already end in '\n'
        kept = text[:-1] if text.endswith("\n") else text
    grid = Grid(shown, None, [], (",", ";", "\t"))
    head = "\n".join(kept.split("\n", 200)[:200])
    for delim in grid.delimiters:
        grid.text_rows[delim] = _parse(head, delim)
    grid.full_text = kept
    grid.rows = grid.text_rows[","]
    return grid


def _parse(text: str, delim: str) -> list[tuple[int, list[str]]]:
    """Rows with their first line number; the cells of the first 200 rows stripped (the header and the
    metadata are searched there), later cells as written (the table reader strips columns where needed)."""
    rows = []
    if '"' not in text and "\r" not in text:  # no quoting: a line is a row, split on the delimiter (fast)
        lines = text.split("\n")
        rows = [(k + 1, ln.split(delim)) for k, ln in enumerate(lines) if ln and not ln.isspace()]
        for k in range(min(200, len(rows))):
            rows[k] = (rows[k][0], [c.strip() for c in rows[k][1]])
        return rows
    reader = csv.reader(io.StringIO(text), delimiter=delim)
    start = 1
    try:
        for cells in reader:
            if cells and (cells[0].strip() or "".join(cells).strip()):  # skip blank rows (first cell decides fast)
                rows.append((start, [c.strip() for c in cells] if len(rows) < 200 else cells))
            start = reader.line_num + 1
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


def _spreadsheet_grid(shown: str, data: bytes, suffix: str, sheet) -> Grid:
    try:
        if suffix == ".ods":
            names, rows_of = _ods(data)
        else:
            names, rows_of = _xlsx(data)
    except InputError:
        raise
    except Exception as exc:  # a damaged or mislabelled workbook: one clear message
        raise InputError(Problem(shown, None, None, f"cannot be read as a {suffix} workbook "
                                                    f"({type(exc).__name__}: {exc})")) from None
    if sheet is None:
        name = names[0] if names else None
    elif isinstance(sheet, int) or (isinstance(sheet, str) and sheet.strip().lstrip("-").isdigit()
                                    and sheet.strip() not in names):
        k = int(sheet)
        if not 1 <= k <= len(names):
            raise InputError(Problem(shown, None, None, f"there is no sheet number {k}: the workbook has "
                                                        f"{len(names)} ({', '.join(names)}); sheets count from 1"))
        name = names[k - 1]
    else:
        if sheet not in names:
            raise InputError(Problem(shown, None, None, f"no sheet named '{sheet}'; the sheets are "
                                                        f"{', '.join(names)}"))
        name = sheet
    if name is None:
        raise InputError(Problem(shown, None, None, "the workbook has no sheets"))
    rows = [(n, [_cell_text(v) for v in cells]) for n, cells in rows_of(name)]
    rows = [(n, cells) for n, cells in rows if any(cells) and not cells[0].startswith("#")]
    return Grid(shown, name, rows, ())


def _xlsx(data: bytes):
    import openpyxl

    wb = openpyxl.load_workbook(io.BytesIO(data), data_only=True)

    def rows_of(name):
        for row in wb[name].iter_rows():
            if row:
                yield row[0].row, [c.value for c in row]

    return list(wb.sheetnames), rows_of


def _ods(data: bytes):
    import pandas as pd

    book = pd.read_excel(io.BytesIO(data), sheet_name=None, header=None, engine="odf", dtype=object)

    def rows_of(name):
        frame = book[name]
        for k, row in enumerate(frame.itertuples(index=False), start=1):
            yield k, [None if (isinstance(v, float) and v != v) else v for v in row]

    return list(book), rows_of
