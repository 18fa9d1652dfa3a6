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
``z1 (mm)``, or a unit suffix ``tau_max_kPa``. Every problem of a file is
collected in one pass.
"""
from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, Problem, UnitError
from ..units import conversion
from .grid import _parse, as_source, read_grid

_BLANKS = {"", "na", "n/a", "nan", "none", "null"}
_UNIT_IN_HEADER = re.compile(r"^(?P<name>.*?)\s*[\[(]\s*(?P<unit>[^\])]*?)\s*[\])]\s*$")


@dataclass(frozen=True)
class Column:
    """One input column: canonical name, quantity kind, default unit and valid range."""

    name: str
    kind: str  # a key of capred.units.SI_UNIT, or "text"
    unit: str | None
    description: str
    aliases: tuple[str, ...] = ()
    rule: str | None = None  # "positive", "nonnegative", "fraction", or None
    choices: tuple[str, ...] = ()  # allowed values of a text column (lower case)
    quantity: str | None = None  # nomenclature name: its range rule is used (the same as for options)
    words: tuple[tuple[str, float], ...] = ()  # words a numeric column also accepts, e.g. ("plane", inf)


def _key(text: str) -> str:
    """Normalised spelling used to match headers: lower case, '_' between words."""
    k = re.sub(r"[\s\-./]+", "_", text.strip().lower())
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

    def __len__(self) -> int:
        return len(self.lines)

    def has(self, name: str) -> bool:
        return name in self.columns

    def get(self, name: str, default: float = np.nan) -> np.ndarray:
        """Column values, or ``default`` everywhere when the column is absent."""
        if name in self.columns:
            return self.columns[name]
        return np.full(len(self), default, dtype=float)

    def add_problem(self, row: int | None, column: str | None, message: str) -> None:
        line = self.header_line if row is None else int(self.lines[row])
        shown = self.headers.get(column, column) if column else None
        value = self.raw[column][row] if (row is not None and column in self.raw) else None
        self.problems.append(Problem(self.path, line, shown, message, self.sheet, value))

    def missing_column(self, name: str, why: str = "") -> None:
        """Record a required column that is absent, suggesting the nearest header."""
        near = difflib.get_close_matches(_key(name), [_key(h) for h in self.unmatched], n=1, cutoff=0.6)
        hint = ""
        if near:
            original = next(h for h in self.unmatched if _key(h) == near[0])
            hint = f"; did you mean '{original}'?"
        self.problems.append(
            Problem(self.path, self.header_line, None, f"missing column '{name}'{why}{hint}", self.sheet)
        )
        self.missing.add(name)

    def check_unique(self, name: str) -> None:
        """Record blank and repeated identifiers in a text column (e.g. test_id)."""
        seen: dict[str, int] = {}
        for i, v in enumerate(self.columns[name]):
            if not v:
                self.add_problem(i, name, f"empty {name}")
            elif v in seen:
                self.add_problem(i, name, f"duplicate {name} '{v}' (first on line {seen[v]})")
            else:
                seen[v] = int(self.lines[i])

    def value_text(self, name: str, row: int) -> str:
        return self.raw[name][row] if name in self.raw else ""

    def raise_if_problems(self) -> None:
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


def _match_header(header: str, lookup: dict[str, Column]) -> tuple[Column | None, str | None]:
    """Column a header names, and the unit it declares (None = default)."""
    text = header.strip()
    m = _UNIT_IN_HEADER.match(text)
    if m and m.group("name"):
        col = lookup.get(_key(m.group("name")))
        return (col, m.group("unit")) if col else (None, None)
    col = lookup.get(_key(text))
    if col is not None:
        return col, None
    # unit as a suffix: tau_max_kPa, z1_mm
    if "_" in text:
        stem, suffix = text.rsplit("_", 1)
        col = lookup.get(_key(stem))
        if col is not None and col.kind != "text":
            return col, suffix
    return None, None


def _lookup(schema: list[Column]) -> dict[str, Column]:
    lookup: dict[str, Column] = {}
    for col in schema:
        for spelling in (col.name, *col.aliases):
            lookup[_key(spelling)] = col
    return lookup


def _header_hits(cells: list[str], lookup) -> int:
    return sum(1 for c in cells if c and _match_header(c, lookup)[0] is not None)


def _find_header(rows: list[tuple[int, list[str]]], lookup) -> tuple[int, int]:
    """(index of the header row, known columns it names): the first row naming two known columns
    (or, failing that, the first naming one; else the first row)."""
    first_one = None
    for k, (_, cells) in enumerate(rows[:60]):
        hits = _header_hits(cells, lookup)
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
    """A row of units under the header: no number in it, and a valid unit under at least one numeric column."""
    if not any(cells) or any(_PLAIN_RE.fullmatch(c.strip().replace(",", ".")) for c in cells if c.strip()):
        return False
    valid = 0
    for j, col, _ in positions.values():
        if col.kind == "text" or j >= len(cells) or not cells[j].strip():
            continue
        unit = _unit_cell(cells[j])
        if unit in ("-", "–"):
            continue
        try:
            conversion(unit, col.kind)
        except UnitError:
            return False
        valid += 1
    return valid > 0


def _metadata(rows: list[tuple[int, list[str]]]) -> dict[str, str]:
    out: dict[str, str] = {}
    for _, cells in rows:
        filled = [c for c in cells if c]
        if not filled:
            continue
        if len(filled) == 1 and ":" in filled[0]:
            key, _, value = filled[0].partition(":")
        elif len(filled) >= 2:
            key, value = filled[0].rstrip(":"), " ".join(filled[1:])
        else:
            key, value = filled[0], ""
        out[key.strip()] = value.strip()
    return out


def read_table(source, schema: list[Column]) -> Table:
    """Read ``source`` (a path to a CSV, .xlsx or .ods file, a DataFrame, or a TableSource naming the
    sheet and the thousands separator) against ``schema``.

    Problems are collected in ``Table.problems``, every one of the file in one pass.
    Raises InputError at once only when the file cannot be read as a table at
    all (missing, binary, empty, no data rows).
    """
    src = as_source(source)
    grid = read_grid(src)
    lookup = _lookup(schema)
    if grid.text_rows:  # CSV: the delimiter whose header names most known columns (ties: , ; tab)
        best = max(grid.delimiters, key=lambda d: (_find_header(grid.text_rows[d], lookup)[1],
                                                   -grid.delimiters.index(d)))
        if _find_header(grid.text_rows[best], lookup)[1] == 0:  # no known column at all: the widest first row
            best = max(grid.delimiters, key=lambda d: (len(grid.text_rows[d][0][1]) if grid.text_rows[d] else 0,
                                                       -grid.delimiters.index(d)))
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
    k, _ = _find_header(rows, lookup)
    header_line, headers = rows[k]
    metadata = _metadata(rows[:k])
    body = rows[k + 1:]

    table = Table(shown, {}, {}, np.empty(0, dtype=int), {}, {}, header_line, [], sheet=sheet, metadata=metadata,
                  known=tuple(dict.fromkeys(sp for col in schema for sp in (col.name, *col.aliases))))
    positions: dict[str, tuple[int, Column, str | None]] = {}
    for j, h in enumerate(headers):
        col, unit = _match_header(h, lookup)
        if col is None:
            if h.strip():
                table.unmatched.append(h.strip())
                bad = _bad_unit_header(h, lookup)
                if bad:
                    table.problems.append(Problem(shown, header_line, h.strip(), bad, sheet))
            elif any(j < len(cells) and cells[j] for _, cells in body):
                table.warnings.append(f"column {j + 1} has data but no header: it is not used")
            continue
        if col.name in positions:
            first = headers[positions[col.name][0]].strip()
            table.problems.append(Problem(shown, header_line, h.strip(), f"names the same quantity as column '{first}'",
                                          sheet))
            continue
        positions[col.name] = (j, col, unit)
        table.headers[col.name] = h.strip()
    for h in table.unmatched:
        near = difflib.get_close_matches(_key(h), [_key(x) for x in table.known], n=1, cutoff=0.6)
        name = next((x for x in table.known if _key(x) == near[0]), None) if near else None
        canonical = lookup[_key(name)].name if name else None
        if canonical and canonical in positions:
            canonical = None  # the column it resembles is there already
        table.warnings.append(f"column '{h}' is not used" + (f" — did you mean '{canonical}'?" if canonical else ""))

    if body and _is_units_row(body[0][1], positions):
        for name, (j, col, unit) in positions.items():
            cell = _unit_cell(body[0][1][j]) if j < len(body[0][1]) else ""
            if col.kind == "text" or not cell or cell in ("-", "–") and col.kind != "dimensionless":
                continue
            if unit is not None and unit != cell:
                table.problems.append(Problem(shown, body[0][0], table.headers[name],
                                              f"the header says '{unit}' but the units row says '{cell}'", sheet))
                continue
            positions[name] = (j, col, cell)
        table.notes.append(f"units read from the row under the header (line {body[0][0]})")
        body = body[1:]
    if not body:
        raise InputError(Problem(shown, header_line, None, "the file has a header but no data rows", sheet))
    if tail is not None and any(ln.count(delimiter) != len(headers) - 1 for ln in tail[1]):
        body = body + _parse("\n" * (tail[0] - 1) + "\n".join(tail[1]), delimiter)  # ragged: row by row
        tail = None
    table.lines = np.array([n for n, _ in body], dtype=int)
    cells_by_row = [cells for _, cells in body]

    width = len(headers)
    lengths = list(map(len, cells_by_row))
    for n, cells in (body[k] for k, w in enumerate(lengths) if w > width):
        if any(c for c in cells[width:]):
            table.problems.append(Problem(shown, int(n), None, f"{len(cells)} fields but the header has {width}",
                                          sheet))
    if all(w == width for w in lengths):  # the usual, rectangular table: columns by transposition
        transposed = list(zip(*cells_by_row))
        column_cells = {name: list(transposed[j]) for name, (j, _, _) in positions.items()}
        del transposed
    else:
        column_cells = {name: [row[j] if j < len(row) else "" for row in cells_by_row]
                        for name, (j, _, _) in positions.items()}
    if tail is not None:  # the rows after the first 200: split at once, as columns
        first, lines = tail
        flat = delimiter.join(lines).split(delimiter)
        width = len(headers)
        for name, (j, _, _) in positions.items():
            column_cells[name].extend(flat[j::width])
        table.lines = np.concatenate([table.lines, np.arange(first, first + len(lines))])
        del flat
    del cells_by_row, body, rows  # the row lists: only the columns are kept
    grid.rows = []

    numeric = [cells for name, cells in column_cells.items() if positions[name][1].kind != "text"]
    decimal_comma = delimiter not in (None, ",") and any(
        _DECIMAL_COMMA.fullmatch(c) for cells in numeric for c in cells[:2000] if "," in c)
    for name, (j, col, unit) in positions.items():
        cells = _stripped(column_cells[name])
        table.raw[name] = cells
        if col.kind == "text":
            values = np.array(cells, dtype=object)
            if col.choices:
                for i, c in enumerate(cells):
                    if c.lower() not in col.choices:
                        allowed = " or ".join(f"'{x}'" for x in col.choices)
                        table.add_problem(i, name, f"'{c}' is not one of {allowed}")
                values = np.array([c.lower() for c in cells], dtype=object)
            table.columns[name] = values
            continue
        unit_used = unit if unit is not None else col.unit
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
        values = _parse_column(cells, decimal_comma)
        if values is None:  # some cell is not a plain number: cell by cell, naming the bad ones
            values = np.empty(len(cells))
            for i, c in enumerate(cells):
                v = _parse_number(c, decimal_comma)
                if v is None:
                    if c.strip().lower() in ("inf", "-inf", "+inf", "infinity"):
                        table.add_problem(i, name, f"'{c}' is not a finite number")
                    else:
                        table.add_problem(i, name, f"'{c}' is not a number")
                    v = float("nan")
                values[i] = v
        table.as_read[name] = values
        with np.errstate(over="ignore", invalid="ignore"):
            si = values * factor
        for i in np.flatnonzero(np.isinf(si)):
            table.add_problem(i, name, f"'{cells[i]}' is too large once converted to SI units")
            si[i] = np.nan
        for i, v in worded.items():
            si[i] = values[i] = v
        table.columns[name] = si
        _check_rule(table, col)
    return table


def _plain_tail(grid, delimiter: str, lookup) -> tuple[int, list[str]] | None:
    """A long plain CSV (no quotes, no blank line after its first 200 lines, every header named): the first
    200 lines become ``grid.rows`` and the rest is returned as (first line number, lines) to be split as
    columns at once; None where the row-by-row parse is needed."""
    text = grid.full_text
    if text is None or '"' in text or "\r" in text:
        return None
    head = grid.text_rows[delimiter]
    k, found = _find_header(head, lookup)
    if not found or k > len(head) - 3 or any(not h.strip() for h in head[k][1]):
        return None
    lines = text.split("\n")
    if len(lines) <= 200:
        return None
    tail = lines[200:]
    while tail and not tail[-1].strip():
        tail.pop()
    if not tail or any(not ln or ln.isspace() for ln in tail):
        return None
    grid.rows, grid.full_text = head, None
    return 201, tail


_EDGE_SPACE = re.compile(r"\s\x00|\x00\s|^\s|\s$")
#: every character str.isspace() (and so the regex \s) counts as white space: a column without any needs no strip
_SPACES = ("\t\n\x0b\x0c\r\x1c\x1d\x1e\x1f \x85\xa0\u1680" + "".join(map(chr, range(0x2000, 0x200B)))
           + "\u2028\u2029\u202f\u205f\u3000")


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
                table.add_problem(i, name, f"'{c}' is ambiguous in a file with decimal commas: a thousands "
                                           f"separator ({c.replace('.', '')}) or a decimal point "
                                           f"({c.replace('.', ',')})? Give --thousands . to read dots as "
                                           f"thousands separators, or write the number without them")
        return cells
    return cells


def _bad_unit_header(header: str, lookup) -> str | None:
    """Why a header that names a known column cannot be read (its brackets do not match), else None."""
    if not any(ch in header for ch in "[]()"):
        return None
    name = re.split(r"[\[\]()]", header, maxsplit=1)[0]
    if lookup.get(_key(name)) is None:
        return None
    return f"cannot read the unit of '{header.strip()}': its brackets do not match (write e.g. 'name [kPa]')"


def _check_rule(table: Table, col: Column) -> None:
    """Values outside the column's range: the quantity's range (the same rule as options) or ``col.rule``."""
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
        bad = {"positive": v <= 0, "nonnegative": v < 0, "fraction": (v < 0) | (v > 1)}.get(col.rule)
    if bad is None:
        return
    what = {"positive": "must be > 0", "nonnegative": "must not be negative",
            "fraction": "must lie between 0 and 1"}[col.rule]
    for i in np.flatnonzero(bad):
        table.add_problem(i, col.name, f"{col.description} {what} (got {table.raw[col.name][i]} {unit})".rstrip())
