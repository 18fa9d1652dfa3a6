"""The one renderer of capred: any Result's console tables, warnings and notes.

Numbers are never truncated or wrapped. On a terminal, tables are drawn with
rich; a table wider than the terminal is folded into several tables of whole
columns, each repeating the row labels (the leading left-aligned columns: a
material and a model, a test and a bound), never shortened; headers wrap at
their spaces before a table is folded. When stdout is not a terminal (a pipe,
a file), tables are plain full-width text. User text (material names, test
ids) is shown literally, never read as markup.

Zero: a number whose magnitude is below ``ZERO_RTOL`` times the magnitude it
was computed from (``scale``: the largest of its row or column) prints as 0.
"""

from __future__ import annotations

import math

from ..result import TableSpec
from ..sampling import MAX_ROWS  # per-row tables: the first rows only (re-exported)

#: The one rule for numbers in console tables: this many significant digits.
SIGNIFICANT = 4
#: A value below ZERO_RTOL x the magnitudes it was computed from is 0 within the computation's tolerance: the
#: stresses of capred are sums and differences of a few terms of that magnitude in double precision, whose
#: rounding errors are a few ulp (~1e-15 relative; the triaxial console printed 7.276e-15 kPa for an exact 0
#: among values of ~100 kPa). 1e-9 leaves six orders of margin above rounding and stays five orders below the
#: 4 significant digits a table shows, so no value a user can read is hidden.
ZERO_RTOL = 1e-9
#: Row labels repeated in every piece of a folded table: at most this many leading left-aligned columns.
MAX_LABEL_COLUMNS = 3


def fmt(x, sig: int = SIGNIFICANT, sign: bool = False, scale: float | None = None) -> str:
    """A number for a console table: ``sig`` significant digits, '—' for a missing value.

    Parameters
    ----------
    x : float, int, bool, str or None
        The value (text is returned as it is).
    sig : int
        Significant digits.
    sign : bool
        Always print the sign.
    scale : float, optional
        Magnitude of the values ``x`` was computed from (the largest of its row or column, same unit): when
        ``|x| <= ZERO_RTOL * scale``, ``x`` is 0 within the computation's rounding and prints as ``0``.

    Returns
    -------
    str
    """
    if x is None or isinstance(x, str):
        return "—" if x is None else x
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return f"{x:+d}" if sign else str(x)
    x = float(x)
    if not math.isfinite(x):
        return "—"
    if scale is not None and math.isfinite(scale) and abs(x) <= ZERO_RTOL * abs(scale):
        return "0"
    return format(x, f"{'+' if sign else ''}.{sig}g")


def magnitude(values) -> float:
    """The largest finite magnitude among ``values`` (numbers, None and text ignored), 0 when there is none:
    the ``scale`` of ``fmt`` for a row or a column of one quantity."""
    out = 0.0
    for v in values:
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
            out = max(out, abs(float(v)))
    return out


def row_table(
    title: str,
    rows: list[dict],
    keys: list[str],
    full_table: str | None = None,
    left: tuple[str, ...] = ("case", "test_id", "status", "material"),
    total: int | None = None,
) -> TableSpec:
    """A per-row table of at most MAX_ROWS rows, saying how many there are (``total``, when ``rows`` holds only
    the first ones) and where the rest is."""
    spec = TableSpec(title, [(k, "left" if k in left else "right") for k in keys])
    shown = rows[:MAX_ROWS]
    scale = {k: magnitude(r.get(k) for r in shown) for k in keys}  # per column: one quantity, one unit
    for r in shown:
        spec.rows.append([fmt(r.get(k), scale=scale[k]) for k in keys])
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


def _folded_widths(spec: TableSpec) -> list[int]:
    """Width of each column when its header may wrap at spaces: the longest cell or header word."""
    w = [max(len(x) for x in (h.split() or [""])) for h, _ in spec.columns]
    for row in spec.rows:
        for j, cell in enumerate(row):
            w[j] = max(w[j], len(cell))
    return w


def wrap_header(head: str, width: int) -> str:
    """A header broken at its spaces into lines of at most ``width`` characters (a word longer stays whole)."""
    lines: list[str] = []
    for word in head.split(" "):
        if lines and len(lines[-1]) + 1 + len(word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return "\n".join(lines)


def label_columns(spec: TableSpec) -> list[int]:
    """The row labels of a table: its leading left-aligned columns (at most MAX_LABEL_COLUMNS; a table may set
    ``label_columns`` to the number it wants), repeated in every piece when the table is folded."""
    n = getattr(spec, "label_columns", None)
    if n is None:
        n = 0
        while n < min(len(spec.columns) - 1, MAX_LABEL_COLUMNS) and spec.columns[n][1] == "left":
            n += 1
    return list(range(max(1, min(n, len(spec.columns)))))


def plain_text(spec: TableSpec) -> str:
    """The table as aligned plain text of its full width."""
    w = _widths(spec)

    def line(cells):
        return "  ".join(
            c.ljust(w[j]) if spec.columns[j][1] == "left" else c.rjust(w[j]) for j, c in enumerate(cells)
        ).rstrip()

    out = [spec.title, line([h for h, _ in spec.columns]), "  ".join("-" * x for x in w)]
    out += [line(r) for r in spec.rows]
    out.append(_more(spec))
    return "\n".join(x for x in out if x) + "\n\n"


def _more(spec: TableSpec) -> str:
    if spec.total_rows is None:
        return ""
    where = f"; all rows are in {spec.full_table}" if spec.full_table else ""
    return f"(first {len(spec.rows)} of {spec.total_rows} rows{where})"


def column_groups(spec: TableSpec, width: int) -> list[list[int]]:
    """Columns packed into groups that fit ``width`` characters, the row labels (``label_columns``) repeated
    in each group; headers wrap at spaces before a column moves to the next group."""
    w = [x + 3 for x in _folded_widths(spec)]  # rich: padding and border per column
    return pack_columns(w, label_columns(spec), width, base=1)


def pack_columns(widths, labels: list[int], limit: float, base: float = 0.0) -> list[list[int]]:
    """Column indices packed in order into groups whose widths (the label columns', repeated in each group,
    included; plus ``base``) fit ``limit``; every other column is in exactly one group."""
    start = base + sum(widths[j] for j in labels)
    groups, current, used = [], [], start
    for j in range(len(widths)):
        if j in labels:
            continue
        if current and used + widths[j] > limit:
            groups.append(labels + current)
            current, used = [], start
        current.append(j)
        used += widths[j]
    if current or not groups:
        groups.append(labels + current)
    return groups


_column_groups = column_groups


def rich_tables(spec: TableSpec, width: int) -> list:
    from rich.table import Table
    from rich.text import Text

    widths = _folded_widths(spec)
    out = []
    groups = column_groups(spec, width)
    for k, cols in enumerate(groups):
        title = spec.title + (f" ({k + 1}/{len(groups)})" if len(groups) > 1 else "")
        t = Table(title=Text(title), title_justify="left")
        for j in cols:
            head, justify = spec.columns[j]
            t.add_column(Text(wrap_header(head, widths[j])), justify=justify, no_wrap=True, min_width=widths[j])
        for i, row in enumerate(spec.rows):
            t.add_row(
                *(Text(row[j]) for j in cols),
                style="bold" if i in spec.bold_rows else None,
                end_section=i in spec.sections,
            )
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

    from ..text_safety import safe_spec

    for spec in map(safe_spec, specs):  # a cell's control characters never reach the terminal
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

    from ..text_safety import visible

    text = visible(text)  # a warning or note quoting a cell never acts on the terminal
    if terminal:
        con.print(Text(prefix, style=style) + Text(text), soft_wrap=True)
    else:
        print(prefix + text, file=con.file)


def spec(title: str, headers: list[str], left: int = 1) -> TableSpec:
    """An empty console table: the first ``left`` columns left-aligned, the others right-aligned."""
    return TableSpec(title, [(h, "left" if j < left else "right") for j, h in enumerate(headers)])
