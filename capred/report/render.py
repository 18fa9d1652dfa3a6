"""The one renderer of capred: any Result's console tables, warnings and notes.

Numbers are never truncated or wrapped. On a terminal, tables are drawn with
rich; a table wider than the terminal is folded into several tables of whole
columns (the first column repeated), never shortened. When stdout is not a
terminal (a pipe, a file), tables are plain full-width text. User text
(material names, test ids) is shown literally, never read as markup.
"""
from __future__ import annotations

import math

from ..result import TableSpec

#: The one rule for numbers in console tables: this many significant digits.
SIGNIFICANT = 4
#: Per-row tables show at most this many rows; the rest are in the output files.
MAX_ROWS = 20


def fmt(x, sig: int = SIGNIFICANT, sign: bool = False) -> str:
    """A number for a console table: ``sig`` significant digits, '—' for a missing value."""
    if x is None or isinstance(x, str):
        return "—" if x is None else x
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return f"{x:+d}" if sign else str(x)
    x = float(x)
    if not math.isfinite(x):
        return "—"
    return format(x, f"{'+' if sign else ''}.{sig}g")


def row_table(title: str, rows: list[dict], keys: list[str], full_table: str | None = None,
              left: tuple[str, ...] = ("case", "test_id", "status", "material"), total: int | None = None) -> TableSpec:
    """A per-row table of at most MAX_ROWS rows, saying how many there are (``total``, when ``rows`` holds only
    the first ones) and where the rest is."""
    spec = TableSpec(title, [(k, "left" if k in left else "right") for k in keys])
    for r in rows[:MAX_ROWS]:
        spec.rows.append([fmt(r.get(k)) for k in keys])
    n = len(rows) if total is None else total
    if n > MAX_ROWS:
        spec.total_rows, spec.full_table = n, full_table
    return spec


def _widths(spec: TableSpec) -> list[int]:
    w = [len(h) for h, _ in spec.columns]
    for row in spec.rows:
        for j, cell in enumerate(row):
            w[j] = max(w[j], len(cell))
    return w


def plain_text(spec: TableSpec) -> str:
    """The table as aligned plain text of its full width."""
    w = _widths(spec)

    def line(cells):
        return "  ".join(c.ljust(w[j]) if spec.columns[j][1] == "left" else c.rjust(w[j])
                         for j, c in enumerate(cells)).rstrip()

    out = [spec.title, line([h for h, _ in spec.columns]), "  ".join("-" * x for x in w)]
    out += [line(r) for r in spec.rows]
    out.append(_more(spec))
    return "\n".join(x for x in out if x) + "\n\n"


def _more(spec: TableSpec) -> str:
    if spec.total_rows is None:
        return ""
    where = f"; all rows are in {spec.full_table}" if spec.full_table else ""
    return f"(first {len(spec.rows)} of {spec.total_rows} rows{where})"


def _column_groups(spec: TableSpec, width: int) -> list[list[int]]:
    """Columns packed into groups that fit ``width``, the first column repeated in each group."""
    w = [x + 3 for x in _widths(spec)]  # rich: padding and border per column
    groups, current, used = [], [0], w[0] + 1
    for j in range(1, len(w)):
        if used + w[j] > width and len(current) > 1:
            groups.append(current)
            current, used = [0], w[0] + 1
        current.append(j)
        used += w[j]
    groups.append(current)
    return groups


def rich_tables(spec: TableSpec, width: int) -> list:
    from rich.table import Table
    from rich.text import Text

    widths = _widths(spec)
    out = []
    groups = _column_groups(spec, width)
    for k, cols in enumerate(groups):
        title = spec.title + (f" ({k + 1}/{len(groups)})" if len(groups) > 1 else "")
        t = Table(title=Text(title), title_justify="left")
        for j in cols:
            head, justify = spec.columns[j]
            t.add_column(Text(head), justify=justify, no_wrap=True, min_width=widths[j])
        for i, row in enumerate(spec.rows):
            t.add_row(*(Text(row[j]) for j in cols), style="bold" if i in spec.bold_rows else None,
                      end_section=i in spec.sections)
        out.append(t)
    return out


def render(result, out_dir=None, written=None, console=None) -> None:
    """Print a result's summary tables, then its warnings and notes, then where its files are."""
    from rich.console import Console

    con = console or Console()
    terminal = con.is_terminal
    from .presenters import console_tables

    render_tables(console_tables(result), con)
    for w in result.all_warnings():
        _line(con, terminal, "warning: ", "yellow", w)
    for n in result.all_notes():
        _line(con, terminal, "note: ", "cyan", n)
    if written is not None:
        _line(con, terminal, "", "bold", f"Wrote {len(written)} files to {out_dir}")


def render_tables(specs: list[TableSpec], con) -> None:
    """Print tables: rich and folded to the width on a terminal, plain full-width text otherwise."""
    from rich.text import Text

    for spec in specs:
        if con.is_terminal:
            for t in rich_tables(spec, con.width):
                con.print(t)
            more = _more(spec)
            if more:
                con.print(Text(more))
        else:
            print(plain_text(spec), end="", file=con.file)


def _line(con, terminal: bool, prefix: str, style: str, text: str) -> None:
    from rich.text import Text

    if terminal:
        con.print(Text(prefix, style=style) + Text(text), soft_wrap=True)
    else:
        print(prefix + text, file=con.file)


def spec(title: str, headers: list[str], left: int = 1) -> TableSpec:
    """An empty console table: the first ``left`` columns left-aligned, the others right-aligned."""
    return TableSpec(title, [(h, "left" if j < left else "right") for j, h in enumerate(headers)])
