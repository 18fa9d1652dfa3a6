"""Read a lab CSV export into SI arrays, remembering where every value came from.

A file has one header line, then one row per test. Lines starting with '#'
and blank lines are skipped but still counted, so line numbers in messages
are the ones a spreadsheet or text editor shows. The delimiter is ',', ';' or
tab (whichever the header uses most); with ';' or tab, a decimal comma is
accepted ("0,35"). A header may declare its unit: ``tau_max [Pa]``,
``z1 (mm)``, or a unit suffix ``tau_max_kPa``.
"""
from __future__ import annotations

import csv
import difflib
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, Problem, UnitError
from ..units import conversion

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
        self.problems.append(Problem(self.path, line, shown, message))

    def missing_column(self, name: str, why: str = "") -> None:
        """Record a required column that is absent, suggesting the nearest header."""
        near = difflib.get_close_matches(_key(name), [_key(h) for h in self.unmatched], n=1, cutoff=0.6)
        hint = ""
        if near:
            original = next(h for h in self.unmatched if _key(h) == near[0])
            hint = f"; did you mean '{original}'?"
        self.problems.append(
            Problem(self.path, self.header_line, None, f"missing column '{name}'{why}{hint}")
        )

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


def _decode(path: Path) -> str:
    data = path.read_bytes()
    for enc in ("utf-8-sig", "utf-16") if data[:2] in (b"\xff\xfe", b"\xfe\xff") else ("utf-8-sig", "cp1252"):
        try:
            return data.decode(enc)
        except UnicodeDecodeError:
            continue
    return data.decode("latin-1")


def _parse_number(text: str, decimal_comma: bool) -> float | None:
    """Float value of a cell; NaN for a blank; None when it is not a number."""
    t = text.strip()
    if t.lower() in _BLANKS:
        return float("nan")
    if decimal_comma and "," in t and "." not in t:
        t = t.replace(",", ".")
    try:
        v = float(t)
    except ValueError:
        return None
    return v if np.isfinite(v) else None


_PLAIN = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_ALL_PLAIN = re.compile(rf"(?:(?:{_PLAIN})?\n)*(?:{_PLAIN})?")
_COMMA = _PLAIN.replace(chr(92) + ".", ",")
_ALL_PLAIN_COMMA = re.compile(rf"(?:(?:{_COMMA})?\n)*(?:{_COMMA})?")


def _parse_column(cells: list[str], decimal_comma: bool) -> np.ndarray | None:
    """Every cell of a column at once when all are plain decimal numbers (the usual case); else None."""
    if not cells:
        return np.empty(0)
    joined = "\n".join(cells)
    if _ALL_PLAIN.fullmatch(joined):
        pass
    elif decimal_comma and _ALL_PLAIN_COMMA.fullmatch(joined):
        joined = joined.replace(",", ".")
    else:
        return None
    return np.array([c or "nan" for c in joined.split("\n")], dtype=float)  # blank cells are NaN


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


def read_table(path, schema: list[Column]) -> Table:
    """Read ``path`` (a CSV file, or a pandas DataFrame) against ``schema``.

    Problems are collected in ``Table.problems``.

    Raises InputError at once only when the file cannot be read as a table at
    all (missing, empty, no data rows); every other problem is collected so
    the caller can add its own checks and report them together.
    """
    if hasattr(path, "to_csv"):  # a pandas DataFrame from a lab script: parsed like the same table in a file
        shown = "<DataFrame>"
        text = path.to_csv(index=False)
    else:
        p = Path(path)
        shown = str(path)
        if not p.is_file():
            raise InputError(Problem(shown, None, None, "file not found"))
        text = _decode(p)
    numbered = [
        (i + 1, line)
        for i, line in enumerate(text.splitlines())
        if line.strip() and not line.lstrip().startswith("#")
        and line.replace(",", "").replace(";", "").replace("\t", "").strip()
    ]
    if not numbered:
        raise InputError(Problem(shown, None, None, "the file is empty (no header and no data rows)"))
    header_line, header_text = numbered[0]
    delimiter = max([",", ";", "\t"], key=header_text.count)
    decimal_comma = delimiter != ","
    rows = list(csv.reader([line for _, line in numbered], delimiter=delimiter))
    headers, body = rows[0], rows[1:]
    lines = np.array([n for n, _ in numbered[1:]], dtype=int)
    if not body:
        raise InputError(Problem(shown, header_line, None, "the file has a header but no data rows"))

    lookup: dict[str, Column] = {}
    for col in schema:
        for spelling in (col.name, *col.aliases):
            lookup[_key(spelling)] = col

    table = Table(shown, {}, {}, lines, {}, {}, header_line, [])
    positions: dict[str, tuple[int, Column, str | None]] = {}
    for j, h in enumerate(headers):
        col, unit = _match_header(h, lookup)
        if col is None:
            if h.strip():
                table.unmatched.append(h.strip())
            continue
        if col.name in positions:
            first = headers[positions[col.name][0]].strip()
            table.problems.append(Problem(shown, header_line, h.strip(),
                                          f"names the same quantity as column '{first}'"))
            continue
        positions[col.name] = (j, col, unit)
        table.headers[col.name] = h.strip()

    for n, row in zip(lines, body):
        if len(row) > len(headers) and any(c.strip() for c in row[len(headers):]):
            table.problems.append(Problem(shown, int(n), None,
                                          f"{len(row)} fields but the header has {len(headers)}"))

    width = len(headers)
    if all(len(row) == width for row in body):  # the usual, rectangular table: columns by transposition
        transposed = list(zip(*body))
        column_cells = {name: [c.strip() for c in transposed[j]] for name, (j, _, _) in positions.items()}
    else:
        column_cells = {name: [row[j].strip() if j < len(row) else "" for row in body]
                        for name, (j, _, _) in positions.items()}
    for name, (j, col, unit) in positions.items():
        cells = column_cells[name]
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
        values = _parse_column(cells, decimal_comma)
        if values is None:  # some cell is blank or not a plain number: cell by cell, naming the bad ones
            values = np.empty(len(cells))
            for i, c in enumerate(cells):
                v = _parse_number(c, decimal_comma)
                if v is None:
                    table.add_problem(i, name, f"'{c}' is not a number")
                    v = float("nan")
                values[i] = v
        with np.errstate(over="ignore", invalid="ignore"):
            si = values * factor
        for i in np.flatnonzero(np.isinf(si)):
            table.add_problem(i, name, f"'{cells[i]}' is too large once converted to SI units")
            si[i] = np.nan
        table.columns[name] = si
        _check_rule(table, col)
    return table


def _check_rule(table: Table, col: Column) -> None:
    v = table.columns[col.name]
    unit = table.units.get(col.name, "")
    with np.errstate(invalid="ignore"):
        bad = {"positive": v <= 0, "nonnegative": v < 0, "fraction": (v < 0) | (v > 1)}.get(col.rule)
    if bad is None:
        return
    what = {"positive": "must be > 0", "nonnegative": "must not be negative",
            "fraction": "must lie between 0 and 1"}[col.rule]
    for i in np.flatnonzero(bad):
        table.add_problem(i, col.name, f"{col.description} {what} (got {table.raw[col.name][i]} {unit})".rstrip())
