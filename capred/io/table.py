"""Read a lab table (CSV, .xlsx, .ods, or a DataFrame) into SI arrays, remembering where every value came from.

The header row is the first row that names known columns; rows above it are
a metadata block (``key: value`` or ``key,value``), kept as metadata. A row
of units directly under the header (``kPa``, ``(g)``, ``-``) gives the
columns' units. Lines starting with '#' and blank lines are skipped but
still counted, so line numbers in messages are the ones a spreadsheet or
text editor shows. The delimiter is ',', ';' or tab (the one whose header
names most known columns); in a file that writes decimal commas ("0,35"), a
cell such as ``1.000`` (a thousands separator or a decimal point?) is an
error unless ``thousands='.'`` says how to read it. Only plain decimal
numbers are numbers. A header may declare its unit: ``tau_max [Pa]``,
``z1 (mm)``, ``V_v [cm³]``, or a unit suffix ``tau_max_kPa``. Every problem
of a file is collected in one pass.

Text under the data whose first cell alone is filled ("Remarks: sample
disturbed") is kept as a note (``Table.notes``), not read as a test.

Unused columns are warnings, except a **near miss of a decisive column**:
a column whose absence changes what is computed, not only what is shown.
Decisive are every text column of a schema (identities and groups:
``test_id``, ``material``, ``condition``, ``group``, ``branch``, ``case``)
and the numeric columns of :data:`DECISIVE_COLUMNS` (``R``, ``R2``,
``back_pressure``, ``u_a``, ``weight``) or marked ``decisive=True``. A
header of an unused column that is one edit away from their name (five
letters or more) or an alias (six or more; two edits for eight or more;
case, spaces and '_' ignored), such as ``Materiaal`` for ``material``,
while the column itself is absent, is an error naming both: read as a warning, it
would silently pool two materials. ``ignore_columns`` (CLI
``--ignore-column NAME``) leaves such a column out and goes on.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from ..errors import InputError, Problem, UnitError
from ..spec.columns import DECISIVE_COLUMNS, Column  # noqa: F401 (re-exported: capred.io.table.Column)
from ..text_safety import excerpt
from ..units import conversion
from .grid import MAX_COLUMNS, ReadLimits, as_source, parse_rows, read_grid
from .plain_tail import PlainTail, TailCells, read_columns

#: the most characters of a note under the data that messages quote
NOTE_CHARS = 500
#: problems recorded in one table before reading stops: a table with more is not this command's input, or damaged,
#: and recording every one of its cells' problems made time and memory grow without bound (a 3 MB file of 1,000,000
#: rows '1,' under 'test_id,condition': 2,000,000 problems, over 120 s and 900 MB); the first ones are all listed
MAX_PROBLEMS = 100_000
#: numeric columns whose absence changes what is computed (a default radius, equal spheres, no back pressure,
#: equal weights); text columns (identities and groups) are decisive too. A near miss of one stops the run.

_BLANKS = {"", "na", "n/a", "nan", "none", "null"}
_UNIT_IN_HEADER = re.compile(r"^(?P<name>.*?)\s*[\[(]\s*(?P<unit>[^\])]*?)\s*[\])]\s*$")


@lru_cache(maxsize=4096)
def header_key(text: str) -> str:
    """Normalised spelling used to match headers: lower case, '_' between words.

    Words are separated by any run of spaces and the punctuation instruments and locales put between them
    (``-``, ``.``, ``/``, ``,``, ``;``, ``:``, ``_``): ``Eff. Axial Stress``, ``Eff, Axial Stress`` (an export
    whose decimal points a regional setting turned into commas), ``Eff Axial Stress`` and ``eff_axial_stress``
    are one key.

    Parameters
    ----------
    text : str
        A header or alias as written.

    Returns
    -------
    str
        The key that `column_lookup` maps to a column.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    k = re.sub(r"[\s\-./,;:]+", "_", text.strip().lower())
    return re.sub(r"_+", "_", k).strip("_")


@dataclass
class Table:
    """Parsed columns (floats in SI, NaN where blank; text as str) and their origin."""

    path: str
    columns: dict[str, np.ndarray]
    raw: dict[str, list[str]]
    lines: np.ndarray
    headers: dict[str, str]
    units: dict[str, str]
    header_line: int
    unmatched: list[str]
    notes: list[str] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    sheet: str | None = None
    metadata: dict[str, str] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    known: tuple[str, ...] = ()  # every spelling the schema accepts, for suggestions
    missing: set[str] = field(default_factory=set)  # required columns reported absent
    as_read: dict[str, np.ndarray] = field(default_factory=dict)  # numbers in the file's own unit (before SI)
    units_line: int | None = None  # the line of a units row under the header (None: no units row)
    #: ``ignore_columns`` names (as given) the header does not have: each warned about once (see forget_ignores)
    ignores_unused: list[str] = field(default_factory=list)
    ignores_used: set[str] = field(default_factory=set)  # header_key of the ignore_columns names it has
    unit_given: set[str] = field(default_factory=set)  # columns whose unit the header or a units row wrote

    def __len__(self) -> int:
        return len(self.lines)

    def has(self, name: str) -> bool:
        """True when the table has column ``name``.

        Parameters
        ----------
        name : str
            A canonical column name.

        Returns
        -------
        bool
        """
        return name in self.columns

    def get(self, name: str, default: float = np.nan) -> np.ndarray:
        """Column values, or ``default`` everywhere when the column is absent.

        Parameters
        ----------
        name : str
            A canonical column name.
        default : float, optional
            Value of every row when the column is absent (default NaN).

        Returns
        -------
        numpy.ndarray
            The column's values, in the units of the table (no conversion here).
        """
        if name in self.columns:
            return self.columns[name]
        return np.full(len(self), default, dtype=float)

    def add_problem(self, row: int | None, column: str | None, message: str) -> None:
        """Record a problem of one cell (or of the header when ``row`` is None), with its file, sheet, line and value.

        Parameters
        ----------
        row : int or None
            Row index in the table (0 = first data row), None for the header line.
        column : str or None
            Canonical column name (shown as the header writes it), None for a whole row.
        message : str
            What is wrong.

        Raises
        ------
        InputError
            When the table reaches :data:`MAX_PROBLEMS` problems: reading stops there, every problem so far listed.
        """
        line = self.header_line if row is None else int(self.lines[row])
        shown = self.headers.get(column, column) if column else None
        value = self.raw[column][row] if (row is not None and column in self.raw) else None
        self.problems.append(Problem(self.path, line, shown, message, self.sheet, value))
        if len(self.problems) >= MAX_PROBLEMS:
            stop = (
                f"{len(self.problems):,} problems found by line {line}: reading stopped there (a table with this "
                "many is not this command's input, or is damaged)"
            )
            raise InputError([*self.problems, Problem(self.path, None, None, stop, self.sheet)])

    def missing_column(self, name: str, why: str = "") -> None:
        """Record a required column that is absent, suggesting the nearest header.

        Parameters
        ----------
        name : str
            The canonical column name.
        why : str, optional
            Appended to the message (e.g. why the column is needed).
        """
        near = difflib.get_close_matches(header_key(name), [header_key(h) for h in self.unmatched], n=1, cutoff=0.6)
        hint = ""
        if near:
            original = next(h for h in self.unmatched if header_key(h) == near[0])
            hint = f"; did you mean '{original}'?"
        elif self.unmatched:  # name the headers that were not read, so the user sees what to rename
            shown = ", ".join(f"'{h}'" for h in self.unmatched[:8]) + (" ..." if len(self.unmatched) > 8 else "")
            hint = f"; columns of the file not read: {shown} (the command's --help lists the accepted spellings)"
        self.problems.append(
            Problem(self.path, self.header_line, None, f"missing column '{name}'{why}{hint}", self.sheet)
        )
        self.missing.add(name)

    def check_unique(self, name: str) -> None:
        """Record blank and repeated identifiers in a text column (e.g. test_id).

        Parameters
        ----------
        name : str
            A text column.
        """
        seen: dict[str, int] = {}
        for i, v in enumerate(self.columns[name]):
            if not v:
                self.add_problem(i, name, f"empty {name}")
            elif v in seen:
                self.add_problem(i, name, f"duplicate {name} '{v}' (first on line {seen[v]})")
            else:
                seen[v] = int(self.lines[i])

    def value_text(self, name: str, row: int) -> str:
        """The cell of column ``name`` on row ``row`` as the file writes it ("" when the column is absent).

        Parameters
        ----------
        name : str
            A canonical column name.
        row : int
            Row index in the table (0 = first data row).

        Returns
        -------
        str
        """
        return self.raw[name][row] if name in self.raw else ""

    def forget_ignores(self, used: set[str] | None = None) -> None:
        """Take back the warnings about --ignore-column names this table's header lacks, where another file has them.

        Another file of the same command; ``used``: their header keys; None: every one.

        A command that reads several files (a tests table and its ``--curves``) leaves every file its ignore
        list: a name is warned about once, on the first file, and only when no file has it.

        Parameters
        ----------
        used : set of str, optional
            header_key of the names another file had (None: forget them all, this being a secondary file).
        """
        for name in [n for n in self.ignores_unused if used is None or header_key(n) in used]:
            self.ignores_unused.remove(name)
            if _unused_ignore(name) in self.warnings:
                self.warnings.remove(_unused_ignore(name))

    def raise_if_problems(self) -> None:
        """Raise InputError listing every problem recorded so far; do nothing when there is none."""
        if self.problems:
            raise InputError(self.problems)


def _parse_number(text: str, decimal_comma: bool) -> float | None:
    """Float value of a cell; NaN for a blank; None when it is not a plain decimal number.

    Plain means ASCII digits with an optional sign, decimal point (or comma
    in a decimal-comma file) and exponent: no '_', no other digits, no 'inf'.
    """
    t = text.strip()
    if t.lower() in _BLANKS:
        return float("nan")
    if decimal_comma and "," in t and "." not in t:
        t = t.replace(",", ".")
    if not _PLAIN_RE.fullmatch(t):
        return None
    v = float(t)
    return v if np.isfinite(v) else None


_PLAIN = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"
_PLAIN_RE = re.compile(_PLAIN)
_THOUSANDS_DOT = re.compile(r"[-+]?[1-9][0-9]{0,2}(?:\.[0-9]{3})+")  # 1.000, 12.500, 1.234.567
_DECIMAL_COMMA = re.compile(r"[-+]?[0-9]*,[0-9]+(?:[eE][-+]?[0-9]+)?")
_ALL_PLAIN = re.compile(rf"(?:(?:{_PLAIN})?\n)*(?:{_PLAIN})?")
_COMMA = _PLAIN.replace(chr(92) + ".", ",")
_ALL_PLAIN_COMMA = re.compile(rf"(?:(?:{_COMMA})?\n)*(?:{_COMMA})?")


_NUMBER_CHARS = str.maketrans("", "", "0123456789+-.eE\n")


def _parse_column(cells: list[str], decimal_comma: bool) -> np.ndarray | None:
    """Every cell of a column at once when all are plain decimal numbers or blank (the usual case); else None.

    Plain: ASCII digits, sign, one decimal point (a comma in a decimal-comma
    file), exponent; numpy parses, and a column holding any other character
    ('_', letters such as 'nan' or 'inf', other digits) goes cell by cell.
    """
    if not cells:
        return np.empty(0)
    joined = "\n".join(cells)
    if decimal_comma and "," in joined:
        if "." in joined:  # decimal commas and points mixed: cell by cell
            return None
        joined = joined.replace(",", ".")
    if joined.translate(_NUMBER_CHARS):
        return None
    try:
        return np.array([c or "nan" for c in joined.split("\n")], dtype=float)  # blank cells are NaN
    except ValueError:
        return None


def match_header(header: str, lookup: dict[str, Column]) -> tuple[Column | None, str | None]:
    """Column a header names, and the unit it declares (None = default).

    Parameters
    ----------
    header : str
        A header cell as written (e.g. ``tau_max [kPa]``).
    lookup : dict of str to Column
        Spellings of the known columns (`column_lookup`).

    Returns
    -------
    (Column or None, str or None)
        The column named (None: unknown) and the unit written in brackets (None: the column's default unit).

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    declared, key, unit, stem, suffix = _header_spellings(header)
    col = lookup.get(key)
    if declared:
        return (col, unit) if col else (None, None)
    if col is not None:
        return col, None
    if stem is not None:  # unit as a suffix: tau_max_kPa, z1_mm
        col = lookup.get(stem)
        if col is not None and col.kind != "text":
            return col, suffix
    return None, None


@lru_cache(maxsize=8192)
def _header_spellings(header: str) -> tuple[bool, str, str | None, str | None, str | None]:
    """What match_header looks up of a header cell.

    (declares a unit in brackets, key of the name, that unit, key of the stem before a last '_', the suffix); cached:
    the first rows of a file are searched for every candidate delimiter.
    """
    text = header.strip()
    m = _UNIT_IN_HEADER.match(text)
    if m and m.group("name"):
        return True, header_key(m.group("name")), m.group("unit"), None, None
    if "_" in text:
        stem, suffix = text.rsplit("_", 1)
        return False, header_key(text), None, header_key(stem), suffix
    return False, header_key(text), None, None, None


def column_lookup(schema: list[Column]) -> dict[str, Column]:
    """Every spelling (name and aliases, as `header_key` normalises them) of a schema's columns.

    Parameters
    ----------
    schema : list of Column
        The columns a command reads.

    Returns
    -------
    dict of str to Column
        Normalised spelling -> column.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    lookup: dict[str, Column] = {}
    for col in schema:
        for spelling in (col.name, *col.aliases):
            lookup[header_key(spelling)] = col
    return lookup


def _header_hits(cells: list[str], lookup) -> int:
    return sum(1 for c in cells if c and match_header(c, lookup)[0] is not None)


def find_header(rows: list[tuple[int, list[str]]], lookup, width: int = MAX_COLUMNS) -> tuple[int, int]:
    """(index of the header row, known columns it names).

    The first row naming two known columns (or, failing that, the first naming one; else the first row). Only the first
    ``width`` + 1 cells of a row are looked at (a wider header is refused afterwards), so the search is bounded.

    Parameters
    ----------
    rows : list of (int, list of str)
        Rows with their line numbers, as `capred.io.grid.parse_rows` gives them.
    lookup : dict of str to Column
        Spellings of the known columns (`column_lookup`).
    width : int, optional
        The most columns a table may have.

    Returns
    -------
    (int, int)
        Index of the header row in ``rows`` and the number of known columns it names.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    first_one = None
    for k, (_, cells) in enumerate(rows[:60]):
        hits = _header_hits(cells[: width + 1], lookup)
        if hits >= 2:
            return k, hits
        if hits == 1 and first_one is None:
            first_one = k
    return (first_one, 1) if first_one is not None else (0, 0)


def _unit_cell(text: str) -> str:
    t = text.strip()
    if len(t) >= 2 and t[0] in "([" and t[-1] in ")]":
        t = t[1:-1].strip()
    return t


def _is_units_row(cells: list[str], positions) -> bool:
    """A row of units under the header.

    No number in it, and a valid unit under at least one numeric column (a unit that is not valid under another column
    is then reported as such, not read as a data row).
    """
    if not any(cells) or any(_PLAIN_RE.fullmatch(c.strip().replace(",", ".")) for c in cells if c.strip()):
        return False
    for j, col, _ in positions.values():
        if col.kind == "text" or j >= len(cells) or not cells[j].strip():
            continue
        unit = _unit_cell(cells[j])
        if unit in ("-", "–"):
            continue
        try:
            conversion(unit, col.kind)
        except UnitError:
            continue
        return True
    return False


def _metadata(rows: list[tuple[int, list[str]]], merged: dict | None = None) -> dict[str, str]:
    """The metadata block above the header: ``key: value`` in one cell, or a key and its value in the next cells.

    A merged range is one cell, as the workbook shows it (``merged``: Grid.merged): its value once, not once per
    column it spans. A merged cell alone on its row with no ``key:`` in it is a title: ``title`` (``title 2``
    for a second one).
    """
    out: dict[str, str] = {}
    merged = merged or {}
    titles = 0
    for line, cells in rows:
        cells, heads = list(cells), set()
        for c1, c2, r1 in merged.get(line, ()):
            first = c1 if line == r1 else c1 - 1  # the range's own cell keeps its value, its copies are blanked
            for c in range(first, min(c2, len(cells))):
                cells[c] = ""
            if line == r1 and c2 > c1:
                heads.add(c1 - 1)
        filled = [c for c in cells if c]
        if not filled:
            continue
        if len(filled) == 1 and ":" not in filled[0] and cells.index(filled[0]) in heads:
            titles += 1
            out["title" if titles == 1 else f"title {titles}"] = filled[0].strip()
            continue
        if len(filled) == 1 and ":" in filled[0]:
            key, _, value = filled[0].partition(":")
        elif len(filled) >= 2:
            key, value = filled[0].rstrip(":"), " ".join(filled[1:])
        else:
            key, value = filled[0], ""
        out[key.strip()] = value.strip()
    return out


def read_table(source, schema: list[Column], *, ignore_columns=(), limits: ReadLimits | None = None) -> Table:
    """Read ``source`` against ``schema``.

    ``source`` is a path to a CSV, .xlsx or .ods file, a DataFrame, or a TableSource naming the sheet, the thousands
    separator, the columns to ignore and the limits.

    Parameters
    ----------
    source : path, DataFrame or TableSource
        The table.
    schema : list of Column
        The columns the command reads.
    ignore_columns : sequence of str
        Header names of columns to leave out (as if absent), added to the source's own; a near miss of a
        decisive column is an error unless it is ignored (CLI ``--ignore-column NAME``).
    limits : ReadLimits, optional
        Reading limits (bytes, cells, columns); default the source's, else :class:`ReadLimits`'s defaults
        (CLI ``--max-megabytes``, ``--max-cells``, ``--max-columns``).

    Returns
    -------
    Table
        Columns in SI, with ``problems`` (every one of the file, in one pass), ``warnings`` and ``notes``.

    Raises InputError at once only when the file cannot be read as a table at
    all (missing, binary, empty, no data rows), and LimitError (an InputError)
    when it is over a reading limit.
    """
    src = source_with_options(as_source(source), ignore_columns, limits)
    return grid_table(read_grid(src), src, schema)


def source_with_options(src, ignore_columns, limits):
    """A table source with columns to ignore and read limits added.

    Parameters
    ----------
    src : TableSource
        Where a table is read from.
    ignore_columns : str or sequence of str or None
        Columns to leave unread, added to the source's own.
    limits : ReadLimits or None
        Read limits replacing the source's (None: keep them).

    Returns
    -------
    TableSource
        ``src`` itself when nothing is added, else a copy.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    if ignore_columns or limits is not None:
        extra = (ignore_columns,) if isinstance(ignore_columns, str) else tuple(ignore_columns or ())
        src = replace(
            src, ignore_columns=src.ignore_columns + extra, limits=limits if limits is not None else src.limits
        )
    return src


def grid_table(grid, src, schema: list[Column], empty_ok: bool = False) -> Table:
    """The table of a grid read from ``src`` (see read_table).

    Parameters
    ----------
    grid : Grid
        The cells read (`capred.io.grid.read_grid` or `capred.io.grid.csv_grid`).
    src : TableSource
        Where the grid was read from (its name, sheet, options and limits).
    schema : list of Column
        The columns the command reads.
    empty_ok : bool
        A grid of no data rows gives a table of none (its notes, warnings and header problems), not the error
        (the last block of a long CSV, `capred.io.blocks`).

    Returns
    -------
    Table
        Columns in SI with their units, line numbers and metadata.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    limits = src.limits or ReadLimits()
    width_cap = limits.max_columns
    lookup = column_lookup(schema)
    if grid.text_rows:  # CSV: the delimiter whose header names most known columns (ties: , ; tab)
        found = {d: find_header(grid.text_rows[d], lookup, width_cap) for d in grid.delimiters}
        best = max(grid.delimiters, key=lambda d: (found[d][1], -grid.delimiters.index(d)))
        if found[best][1] == 0:  # no known column at all: the widest first row
            best = max(
                grid.delimiters,
                key=lambda d: (len(grid.text_rows[d][0][1]) if grid.text_rows[d] else 0, -grid.delimiters.index(d)),
            )
        head = grid.text_rows[best]
        k0 = found[best][0]
        if head and len(_trimmed(head[k0][1])) > width_cap:  # before the whole file is split
            raise limits.error(
                "max_columns", f"the header has {len(_trimmed(head[k0][1])):,} columns", grid.shown, head[k0][0]
            )
        tail = _plain_tail(grid, best, lookup)
        if tail is None:
            grid.parse_all(best)
        delimiter = best
    else:
        delimiter = None
        tail = None
    shown, sheet = grid.shown, grid.sheet
    rows = grid.rows
    if not rows:
        raise InputError(Problem(shown, None, None, "the file is empty (no header and no data rows)", sheet))
    broken = [(n, cells[0]) for n, cells in rows if cells and cells[0].startswith("\x00csv error")]
    if broken:
        raise InputError(Problem(shown, broken[0][0], None, broken[0][1][1:] + " (a quote is not closed?)", sheet))
    k, _ = find_header(rows, lookup, width_cap)
    header_line, headers = rows[k]
    if len(_trimmed(headers)) > width_cap:
        raise limits.error(
            "max_columns", f"the header has {len(_trimmed(headers)):,} columns", shown, header_line, sheet=sheet
        )
    metadata = _metadata(rows[:k], grid.merged)
    body = rows[k + 1 :]

    table = Table(
        shown,
        {},
        {},
        np.empty(0, dtype=int),
        {},
        {},
        header_line,
        [],
        sheet=sheet,
        metadata=metadata,
        known=tuple(dict.fromkeys(sp for col in schema for sp in (col.name, *col.aliases))),
    )
    table.notes += grid.notes
    table.warnings += grid.warnings
    if grid.delimiter_rows:
        first = ", ".join(map(str, grid.delimiter_lines))
        more = ", ..." if grid.delimiter_rows > len(grid.delimiter_lines) else ""
        table.notes.append(
            f"{grid.delimiter_rows:,} row{'s' if grid.delimiter_rows > 1 else ''} holding only delimiters "
            f"(as spreadsheet exports leave them) skipped: line{'s' if grid.delimiter_rows > 1 else ''} {first}{more}"
        )
    ignored = {header_key(x): x for x in src.ignore_columns}
    used_ignores: set[str] = set()
    positions: dict[str, tuple[int, Column, str | None]] = {}
    blank_headers = []
    for j, h in enumerate(headers):
        hit = _ignored(h, ignored)
        if hit is not None:
            used_ignores.add(hit)
            table.notes.append(f"column '{h.strip()}' ignored, as asked")
            continue
        col, unit = match_header(h, lookup)
        if col is None:
            if h.strip():
                table.unmatched.append(h.strip())
                bad = _bad_unit_header(h, lookup)
                if bad:
                    table.problems.append(Problem(shown, header_line, h.strip(), bad, sheet))
            else:
                blank_headers.append(j)
            continue
        if col.name in positions:
            first = headers[positions[col.name][0]].strip()
            table.problems.append(
                Problem(shown, header_line, h.strip(), f"names the same quantity as column '{first}'", sheet)
            )
            continue
        positions[col.name] = (j, col, unit)
        table.headers[col.name] = h.strip()
    table.ignores_used = used_ignores
    for key, name in ignored.items():
        if key not in used_ignores:
            table.ignores_unused.append(name)
            table.warnings.append(_unused_ignore(name))
    for j in _with_data(blank_headers, body):
        table.warnings.append(f"column {j + 1} has data but no header: it is not used")
    _unused_columns(table, schema, lookup, positions)

    if body and _is_units_row(body[0][1], positions):
        units_line = body[0][0]
        for name, (j, col, unit) in positions.items():
            cell = _unit_cell(body[0][1][j]) if j < len(body[0][1]) else ""
            if col.kind == "text" or not cell or cell in ("-", "–") and col.kind != "dimensionless":
                continue
            if unit is not None and unit != cell:
                table.problems.append(
                    Problem(
                        shown,
                        units_line,
                        table.headers[name],
                        f"the header says '{unit}' but the units row says '{cell}'",
                        sheet,
                    )
                )
                continue
            try:
                conversion(cell, col.kind)
            except UnitError as exc:
                table.problems.append(
                    Problem(shown, units_line, table.headers[name], f"units row: {exc}", sheet, body[0][1][j])
                )
                continue
            positions[name] = (j, col, cell)
        table.notes.append(f"units read from the row under the header (line {units_line})")
        table.units_line = units_line
        body = body[1:]
    if tail is not None:
        tail.width = len(headers)
        if not tail.rectangular():  # ragged: row by row
            body = body + parse_rows(tail.text[tail.start : tail.end], delimiter, tail.first_line)
            tail = None
    notes = []  # text lines under the data ("Remarks: ..."): notes, not tests
    while tail is not None and tail.n and (text := _note_text(tail.last_line().split(delimiter), positions)):
        notes.append((tail.first_line + tail.n - 1, text))
        tail.drop_last_line()
    if tail is not None and not tail.n:
        tail = None
    while tail is None and body and (text := _note_text(body[-1][1], positions)):
        notes.append((body[-1][0], text))
        body.pop()
    for n, text in reversed(notes):  # a long note is quoted in part (its length said); the file keeps it whole
        quoted = text if len(text) <= NOTE_CHARS else f"{text[:NOTE_CHARS]}… ({len(text):,} characters)"
        table.notes.append(f"note under the data (line {n}): {quoted}")
    if not body:
        if empty_ok:
            return table
        raise InputError(Problem(shown, header_line, None, "the file has a header but no data rows", sheet))
    table.lines = np.array([n for n, _ in body], dtype=int)
    cells_by_row = [cells for _, cells in body]

    width = len(headers)
    lengths = list(map(len, cells_by_row))
    for n, cells in (body[k] for k, w in enumerate(lengths) if w > width):
        if any(c for c in cells[width:]):
            table.problems.append(
                Problem(shown, int(n), None, f"{len(cells)} fields but the header has {width}", sheet)
            )
    if all(w == width for w in lengths):  # the usual, rectangular table: columns by transposition
        transposed = list(zip(*cells_by_row))
        column_cells = {name: list(transposed[j]) for name, (j, _, _) in positions.items()}
        del transposed
    else:
        column_cells = {
            name: [row[j] if j < len(row) else "" for row in cells_by_row] for name, (j, _, _) in positions.items()
        }
    del cells_by_row, body, rows  # the row lists: only the columns are kept
    grid.rows = []

    numeric = [name for name, (_, col, _) in positions.items() if col.kind != "text"]
    decimal_comma = delimiter not in (None, ",") and any(
        _DECIMAL_COMMA.fullmatch(c)
        for name in numeric
        for c in (column_cells[name] + (tail.first_cells(positions[name][0], 2000) if tail else []))[:2000]
        if "," in c
    )
    tail_values: dict[int, np.ndarray | None] = {}
    if tail is not None:  # the rows after the first 200: as columns, a window of lines at a time
        table.lines = np.concatenate([table.lines, np.arange(tail.first_line, tail.first_line + tail.n)])
        plain = [] if decimal_comma or src.thousands is not None else numeric
        fast = [positions[name][0] for name in plain if not positions[name][1].words]
        texts = [j for j, _, _ in positions.values() if j not in fast]  # text, and numbers read cell by cell
        tail_values, tail_texts = read_columns(tail, fast, texts, _parse_column, _stripped)
        for name, (j, _, _) in positions.items():
            if tail_values.get(j) is None:  # a text column, or numbers read cell by cell
                column_cells[name] += tail_texts[j] if j in tail_texts else tail.cells(j)
        del tail_texts
    for name, (j, col, unit) in positions.items():
        cells = _stripped(column_cells[name])
        head_values = _parse_column(cells, False) if tail_values.get(j) is not None else None
        if tail_values.get(j) is not None and head_values is None:  # the first rows hold another cell
            cells = _stripped(column_cells[name] + tail.cells(j))
        elif head_values is not None:  # the cells of the tail cut out of its text when a message quotes one
            cells = TailCells(cells, tail, j)
        table.raw[name] = cells
        if col.kind == "text":
            values = np.array(cells, dtype=object)
            if col.choices:
                lower = {c: c.lower() for c in dict.fromkeys(cells)}  # each distinct cell once
                bad = [i for i, c in enumerate(cells) if lower[c] not in col.choices]
                if bad:
                    _choice_problems(table, name, col, cells, bad)
                values = np.array([lower[c] for c in cells], dtype=object)
            table.columns[name] = values
            continue
        unit_used = unit if unit is not None else col.unit
        if unit is not None:
            table.unit_given.add(name)
        try:
            factor, note = conversion(unit_used, col.kind)
        except UnitError as exc:
            table.add_problem(None, name, str(exc))
            factor, note = float("nan"), None
        if note:
            table.notes.append(f"column '{table.headers[name]}': {note}")
        table.units[name] = unit_used
        cells = _thousands(table, name, cells, decimal_comma, src.thousands)
        worded = {}
        if col.words:
            meaning = dict(col.words)
            worded = {i: meaning[c.lower()] for i, c in enumerate(cells) if c.lower() in meaning}
            cells = [("" if i in worded else c) for i, c in enumerate(cells)]
        if head_values is not None:
            values = np.concatenate([head_values, tail_values[j]])
        else:
            values = _parse_column(cells, decimal_comma)
        if values is None:  # some cell is not a plain number: cell by cell, naming the bad ones
            values = np.empty(len(cells))
            not_numbers = []
            for i, c in enumerate(cells):
                v = _parse_number(c, decimal_comma)
                if v is None:
                    if c.strip().lower() in ("inf", "-inf", "+inf", "infinity"):
                        table.add_problem(i, name, f"'{c}' is not a finite number")
                    else:
                        not_numbers.append(i)
                    v = float("nan")
                values[i] = v
            _number_problems(table, name, cells, not_numbers, delimiter)
        table.as_read[name] = values
        with np.errstate(over="ignore", invalid="ignore"):
            si = values * factor
        for i in np.flatnonzero(np.isinf(si)):
            table.add_problem(i, name, f"'{cells[i]}' is too large once converted to SI units")
            si[i] = np.nan
        for i, v in worded.items():
            si[i] = values[i] = v
        table.columns[name] = si
        check_column_rule(table, col)
        _check_magnitude(table, col)
    _flag_controls(table)
    return table


def _choice_problems(table: Table, name: str, col: Column, cells: list[str], bad: list[int]) -> None:
    """Values of a text column outside its choices: one problem per cell.

    The console shows the same value in many cells once (capred.errors.InputError), with a hint when it is a known word
    of another language (capred.nomenclature.VALUE_TRANSLATIONS).
    """
    from ..nomenclature import VALUE_TRANSLATIONS

    allowed = " or ".join(f"'{x}'" for x in col.choices)
    words = VALUE_TRANSLATIONS.get(col.name, {})
    for i in bad:
        value = cells[i]
        known = words.get(value.strip().lower())
        hint = f" ('{value}' is {known[1]} for '{known[0]}': write '{known[0]}')" if known else ""
        table.add_problem(i, name, f"{excerpt(value)} is not one of {allowed}{hint}")


_DECIMAL_COMMA_CELL = re.compile(r"\s*[-+]?\d+,\d+\s*")


def _number_problems(table: Table, name: str, cells: list[str], rows: list[int], delimiter: str | None) -> None:
    """Cells that are not numbers, one problem each.

    The console shows many of a column as one line (capred.errors.InputError); a decimal comma in a comma-delimited file
    suggests ';'.
    """
    comma = any(_DECIMAL_COMMA_CELL.fullmatch(cells[i]) for i in rows)
    hint = (
        " — decimal commas in a comma-delimited file: save it with ';' as the delimiter (capred then reads "
        "'10,5' as 10.5)"
        if comma and delimiter == ","
        else ""
    )
    for i in rows:
        table.add_problem(i, name, f"{excerpt(cells[i])} is not a number{hint}")


def _flag_controls(table: Table) -> None:
    """One warning when the table's text holds control or bidi characters.

    Headers, text cells, notes, metadata: the characters are kept, and shown as escapes wherever text meets a reader
    (capred.text_safety).
    """
    from ..text_safety import controls_warning, has_unsafe

    for name, header in table.headers.items():
        if has_unsafe(header):
            table.warnings.append(controls_warning(f"{table.path}, line {table.header_line}, a header", header))
            return
    for name, values in table.columns.items():
        if values.dtype != object or not has_unsafe("\n".join(map(str, values))):
            continue
        i = next(i for i, v in enumerate(values) if has_unsafe(str(v)))
        where = f"{table.path}, line {int(table.lines[i])}, column '{table.headers.get(name, name)}'"
        table.warnings.append(controls_warning(where, str(values[i])))
        return
    for text in [*table.notes, *table.metadata.keys(), *table.metadata.values()]:
        if has_unsafe(text):
            table.warnings.append(controls_warning(f"{table.path}, a note or metadata line", text))
            return


def _trimmed(cells: list[str]) -> list[str]:
    """A row without its trailing blank cells (the width a header really has)."""
    end = len(cells)
    while end and not cells[end - 1].strip():
        end -= 1
    return cells[:end]


def _name_part(header: str) -> str:
    """A header without the unit it declares in brackets: 'Materiaal [-]' -> 'Materiaal'."""
    m = _UNIT_IN_HEADER.match(header.strip())
    return m.group("name") if m and m.group("name") else header.strip()


def _unused_ignore(name: str) -> str:
    return f"ignore_columns: the header has no column '{name}'"


def _ignored(header: str, ignored: dict[str, str]) -> str | None:
    """The key of ``ignored`` naming this header (as written, or without its unit), else None."""
    if not ignored or not header.strip():
        return None
    for k in (header_key(header), header_key(_name_part(header))):
        if k in ignored:
            return k
    return None


def _with_data(columns: list[int], body, rows: int = 10_000) -> list[int]:
    """Which of ``columns`` hold data in the first ``rows`` rows (a bounded look, for a warning)."""
    left, found = set(columns), []
    for _, cells in body[:rows]:
        if not left:
            break
        for j in [j for j in left if j < len(cells) and cells[j]]:
            left.discard(j)
            found.append(j)
    return sorted(found)


def edits_within(a: str, b: str, limit: int) -> bool:
    """True when ``a`` becomes ``b`` with at most ``limit`` edits.

    Insertions, deletions, substitutions or swaps of neighbours (optimal string alignment distance), computed in a band
    of width ``limit``.

    Parameters
    ----------
    a, b : str
        The two spellings.
    limit : int
        The most edits allowed.

    Returns
    -------
    bool

    References
    ----------
    Damerau, F. J. (1964). A technique for computer detection and correction of spelling errors.
    Commun. ACM 7(3):171-176, doi:10.1145/363958.363994 (the edit operations counted here).
    """
    if abs(len(a) - len(b)) > limit:
        return False
    prev2, prev = None, list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        cur = [i] + [limit + 1] * len(b)
        for j in range(max(1, i - limit), min(len(b), i + limit) + 1):
            cost = a[i - 1] != b[j - 1]
            v = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost)
            if prev2 is not None and i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                v = min(v, prev2[j - 2] + 1)
            cur[j] = v
        if min(cur) > limit:
            return False
        prev2, prev = prev, cur
    return prev[len(b)] <= limit


def _near_miss(header: str, spellings: dict[str, Column]) -> Column | None:
    """The decisive column one of whose ``spellings`` is one edit from the header; None when there is none.

    Two edits for spellings of 8 or more letters; case, spaces and '_' ignored.
    """
    h = header_key(_name_part(header)).replace("_", "")
    if len(h) < 4:
        return None
    for spelling, col in spellings.items():
        if h != spelling and edits_within(h, spelling, 2 if len(spelling) >= 8 else 1):
            return col
    return None


#: unused columns warned about one by one (with the nearest known name); the rest are counted
_UNUSED_SHOWN = 50


def _unused_columns(table: Table, schema: list[Column], lookup: dict[str, Column], positions: dict) -> None:
    """A warning per unused column, with the nearest known name.

    An error for a near miss of a decisive column that is absent (it would change the analysis without a word).
    """
    if not table.unmatched:
        return
    spellings = {}
    for col in schema:
        if col.is_decisive and col.name not in positions:
            for sp in (col.name, *col.aliases):  # short aliases ('state', 'soil') are too near everyday words
                compact = header_key(sp).replace("_", "")
                if len(compact) >= (5 if sp == col.name else 6):
                    spellings.setdefault(compact, col)
    known_keys = {}
    for x in table.known:
        known_keys.setdefault(header_key(x), x)
    told = 0
    for h in table.unmatched:
        col = _near_miss(h, spellings) if spellings else None
        if col is None and told >= _UNUSED_SHOWN:
            continue
        if col is not None:
            table.problems.append(
                Problem(
                    table.path,
                    table.header_line,
                    h,
                    f"column {excerpt(h)} is not used, but its name is close to '{col.name}' ({col.description}), which "
                    f"changes the analysis when it is absent. Rename the column '{col.name}' if that is what it holds, "
                    f"or leave it out with --ignore-column '{h}' (from Python: ignore_columns=('{h}',))",
                    table.sheet,
                )
            )
            continue
        near = difflib.get_close_matches(header_key(h), list(known_keys), n=1, cutoff=0.6) if len(h) <= 64 else []
        canonical = lookup[near[0]].name if near else None
        if canonical and canonical in positions:
            canonical = None  # the column it resembles is there already
        table.warnings.append(
            f"column {excerpt(h)} is not used" + (f" — did you mean '{canonical}'?" if canonical else "")
        )
        told += 1
    if len(table.unmatched) - told > 0 and told >= _UNUSED_SHOWN:
        more = len(table.unmatched) - told - sum(1 for p in table.problems if "is not used, but" in p.message)
        if more > 0:
            table.warnings.append(f"... and {more:,} more columns not used")


def _note_text(cells: list[str], positions: dict) -> str | None:
    """The text of a line under the data that is a note, not a test.

    Only its first cell filled, not a number, and a sentence ('Remarks: ...', three words or more) or text under a
    numeric or unused first column.
    """
    first = cells[0].strip() if cells else ""
    if not first or len(positions) < 2 or any(c.strip() for c in cells[1:]):
        return None
    if _PLAIN_RE.fullmatch(first.replace(",", ".")):
        return None
    col0 = next((col for j, col, _ in positions.values() if j == 0), None)
    if ":" in first or len(first.split()) >= 3 or col0 is None or col0.kind != "text":
        return first
    return None


_BLANK_LINE = re.compile(r"^[^\S\n]*$", re.M)


def _plain_tail(grid, delimiter: str, lookup) -> PlainTail | None:
    """A long plain CSV read as columns, a window of lines at a time; None where rows must be parsed.

    No quotes, no blank line after its first 200 lines, every header named: the first 200 lines become ``grid.rows`` and
    the rest is returned as a PlainTail; None where the row-by-row parse is needed.
    """
    text = grid.full_text
    if text is None or '"' in text or "\r" in text or grid.head_cut:  # cut first rows: the whole parse
        return None
    head = grid.text_rows[delimiter]
    k, found = find_header(head, lookup)
    if not found or k > len(head) - 3 or any(not h.strip() for h in head[k][1]):
        return None
    pos = 0  # the tail starts after the first 200 lines; it is split only when it holds no blank line (a
    for _ in range(200):  # file padded with millions of blank lines is never made a list of them)
        pos = text.find("\n", pos) + 1
        if pos == 0:
            return None
    last = _data_end(text)  # blank lines at the end are dropped
    end = text.find("\n", last)
    end = len(text) if end < 0 else end
    if last <= pos or _BLANK_LINE.search(text, pos, end) is not None:  # the text itself: no copy of it
        return None
    grid.rows, grid.full_text = head, None
    return PlainTail(text, pos, end, grid.first_line + 200, delimiter)


def _data_end(text: str, step: int = 2**20) -> int:
    """The length of ``text`` without its trailing white space (text.rstrip() without copying the text)."""
    hi = len(text)
    while hi > 0:
        lo = max(0, hi - step)
        kept = len(text[lo:hi].rstrip())
        if kept:
            return lo + kept
        hi = lo
    return 0


_EDGE_SPACE = re.compile(r"\s\x00|\x00\s|^\s|\s$")
#: every character str.isspace() (and so the regex \s) counts as white space: a column without any needs no strip
_SPACES = (
    "\t\n\x0b\x0c\r\x1c\x1d\x1e\x1f \x85\xa0\u1680"
    + "".join(map(chr, range(0x2000, 0x200B)))
    + "\u2028\u2029\u202f\u205f\u3000"
)


def _stripped(cells) -> list[str]:
    """The cells without surrounding white space (checked for the whole column at once)."""
    cells = list(cells)
    joined = "\x00".join(cells)
    if any(ch in joined for ch in _SPACES) and _EDGE_SPACE.search(joined):
        return [c.strip() for c in cells]
    return cells


def _thousands(table: Table, name: str, cells: list[str], decimal_comma: bool, thousands: str | None) -> list[str]:
    """Cells with thousands separators removed as ``thousands`` says; ambiguous cells are problems."""
    if thousands is not None:
        group = re.compile(rf"[-+]?[1-9][0-9]{{0,2}}(?:{re.escape(thousands)}[0-9]{{3}})+(?:[.,][0-9]+)?")
        return [c.replace(thousands, "") if thousands in c and group.fullmatch(c) else c for c in cells]
    if decimal_comma:
        for i, c in enumerate(cells):
            if "." in c and _THOUSANDS_DOT.fullmatch(c):
                table.add_problem(
                    i,
                    name,
                    f"'{c}' is ambiguous in a file with decimal commas: a thousands "
                    f"separator ({c.replace('.', '')}) or a decimal point "
                    f"({c.replace('.', ',')})? Give --thousands . to read dots as "
                    f"thousands separators, or write the number without them",
                )
        return cells
    return cells


def _bad_unit_header(header: str, lookup) -> str | None:
    """Why a header that names a known column cannot be read, else None.

    Its brackets do not match, or it holds bracketed text besides its unit.
    """
    if not any(ch in header for ch in "[]()"):
        return None
    name = re.split(r"[\[\]()]", header, maxsplit=1)[0]
    if lookup.get(header_key(name)) is None:
        return None
    balanced = header.count("[") == header.count("]") and header.count("(") == header.count(")")
    why = "it holds text in brackets besides its unit" if balanced else "its brackets do not match"
    return (
        f"cannot read the unit of '{header.strip()}': {why} (a header is a name and one unit in brackets at its "
        f"end: write e.g. '{name.strip()} [kPa]')"
    )


def _check_magnitude(table: Table, col: Column) -> None:
    """Magnitudes no soil test reaches are errors (one per cell), implausible ones one warning per column.

    The bounds and their reasons: capred.nomenclature.MAGNITUDES.
    """
    from ..nomenclature import magnitude_of, magnitude_problem, magnitude_warning

    name = col.quantity or col.name
    m = magnitude_of(name, col.kind)
    if m is None:
        return
    v = table.columns[col.name]
    with np.errstate(invalid="ignore"):
        a = np.abs(v)
        too_big = np.flatnonzero((a > m.error) | ((a > 0) & (a < m.floor)))  # or below a floor (a molecule)
        odd = np.flatnonzero((a > m.warn) & (a <= m.error))
    if too_big.size:
        shown = table.headers.get(col.name, col.name)
        told = {p.line for p in table.problems if p.column == shown}  # out of its range already: one message a cell
        for i in too_big:
            if int(table.lines[i]) not in told:
                table.add_problem(int(i), col.name, magnitude_problem(name, float(v[i]), col.kind))
    if odd.size:
        first = int(odd[0])
        what = magnitude_warning(name, float(v[first]), col.kind)
        more = (
            f" ({odd.size:,} values, the first on line {int(table.lines[first])})"
            if odd.size > 1
            else (f" (line {int(table.lines[first])})")
        )
        table.warnings.append(f"column '{table.headers.get(col.name, col.name)}'{more}: {what}")


def check_column_rule(table: Table, col: Column) -> None:
    """Values outside the column's range: the quantity's range (the same rule as options) or ``col.rule``.

    Parameters
    ----------
    table : Table
        The table read; its problems are collected there.
    col : Column
        The column checked.

    Returns
    -------
    None

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    v = table.columns[col.name]
    unit = table.units.get(col.name, "")
    if col.quantity is not None:
        from ..nomenclature import QUANTITIES, range_problem

        q = QUANTITIES[col.quantity]
        with np.errstate(invalid="ignore"):  # candidates by the bounds at once, the message per bad cell
            bad = np.zeros(v.shape, bool)
            if q.lower is not None:
                bad |= (v <= q.lower) if q.lower_open else (v < q.lower)
            if q.upper is not None:
                bad |= (v >= q.upper) if q.upper_open else (v > q.upper)
        for i in np.flatnonzero(bad & np.isfinite(v)):
            why = range_problem(col.quantity, float(v[i]))
            if why:
                table.add_problem(i, col.name, why)
        return
    with np.errstate(invalid="ignore"):
        bad = {
            "positive": v <= 0,
            "nonnegative": v < 0,
            "fraction": (v < 0) | (v > 1),
            "coefficient": (v <= 0) | (v > 1),
        }.get(col.rule)
    if bad is None:
        return
    what = {
        "positive": "must be > 0",
        "nonnegative": "must not be negative",
        "fraction": "must lie between 0 and 1",
        "coefficient": "must lie in (0, 1]",
    }[col.rule]
    for i in np.flatnonzero(bad):
        table.add_problem(i, col.name, f"{col.description} {what} (got {table.raw[col.name][i]} {unit})".rstrip())
