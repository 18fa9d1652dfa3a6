"""The one renderer of capred: any Result's console tables, warnings and notes.

Numbers are never truncated or wrapped. On a terminal, a table that fits the
terminal's width (its headers wrapped at their spaces) is drawn with rich; a
table wider than the terminal prints as stacked blocks, one per row: the row's
labels (its leading short left-aligned columns, a blank label carrying the one
above it: a material, then a model) on one line, then ``name: value`` pairs
packed into lines of the terminal's width, a value broken only at its spaces.
So every number stays whole, every row names itself, and no column is
squeezed to nothing at 80, 100 or 120 columns. When stdout is not a terminal
(a pipe, a file), tables are plain full-width text. User text (material names,
test ids) is shown literally, never read as markup.

Zero: a number whose magnitude is below ``ZERO_RTOL`` times the magnitude it
was computed from (``scale``: the largest of its row or column) prints as 0.
"""

from __future__ import annotations

import math

from ..sampling import MAX_ROWS  # per-row tables: the first rows only (re-exported)
from ..table_spec import TableSpec

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
#: A left-aligned column is a row label only while its cells are this short [characters]: a long text column
#: (retention's "parameters (± se)") is a value, never repeated as a label.
MAX_LABEL_WIDTH = 24
#: Separator of the ``name: value`` pairs on one line of a stacked block.
PAIR_GAP = "   "


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
    """The largest finite magnitude among ``values`` (numbers, None and text ignored), 0 when there is none.

    The ``scale`` of ``fmt`` for a row or a column of one quantity.

    Parameters
    ----------
    values : iterable
        Cells of a row or column.

    Returns
    -------
    float
    """
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
    """A per-row table of at most MAX_ROWS rows, saying how many there are and where the rest is.

    ``total``, when ``rows`` holds only the first ones.

    Parameters
    ----------
    title : str
        The table's title.
    rows : list of dict
        The rows (at most MAX_ROWS are shown), values already formatted or numbers.
    keys : list of str
        The keys shown, in order; each key is the column header.
    full_table : str or None, optional
        The file that holds every row, named under the title when rows are left out.
    left : tuple of str, optional
        Keys whose columns are left-aligned.
    total : int or None, optional
        Number of rows in all (default ``len(rows)``).

    Returns
    -------
    capred.table_spec.TableSpec
    """
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
    """A header broken at its spaces into lines of at most ``width`` characters (a word longer stays whole).

    Parameters
    ----------
    head : str
        The header.
    width : int
        Most characters per line.

    Returns
    -------
    str
        Lines joined by newlines.
    """
    lines: list[str] = []
    for word in head.split(" "):
        if lines and len(lines[-1]) + 1 + len(word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return "\n".join(lines)


def label_columns(spec: TableSpec) -> list[int]:
    """The row labels of a table: its leading left-aligned columns whose cells are short.

    At most MAX_LABEL_COLUMNS columns of at most MAX_LABEL_WIDTH characters (a table may set ``label_columns`` to the
    number it wants), repeated in every piece when a table is split and heading each stacked block.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.

    Returns
    -------
    list of int
        Column indices.
    """
    n = getattr(spec, "label_columns", None)
    if n is None:
        n = 0
        while (
            n < min(len(spec.columns) - 1, MAX_LABEL_COLUMNS)
            and spec.columns[n][1] == "left"
            and max((len(r[n]) for r in spec.rows), default=0) <= MAX_LABEL_WIDTH
        ):
            n += 1
    return list(range(max(1, min(n, len(spec.columns)))))


def plain_text(spec: TableSpec) -> str:
    """The table as aligned plain text of its full width.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.

    Returns
    -------
    str
        Title, header, rule and rows, one per line.
    """
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
    """Columns packed into groups that fit ``width`` characters, the row labels repeated in each group.

    The row labels are ``label_columns``; headers wrap at spaces before a column moves to the next group.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.
    width : int
        Terminal width [characters].

    Returns
    -------
    list of list of int
        Column indices of each group.
    """
    w = [x + 3 for x in _folded_widths(spec)]  # rich: padding and border per column
    return pack_columns(w, label_columns(spec), width, base=1)


def pack_columns(widths, labels: list[int], limit: float, base: float = 0.0) -> list[list[int]]:
    """Column indices packed in order into groups whose widths fit ``limit``.

    The label columns' widths, repeated in each group, are included, plus ``base``; every other column is in exactly one
    group.

    Parameters
    ----------
    widths : sequence of float
        Width of each column [characters].
    labels : list of int
        Indices of the label columns.
    limit : float
        Most width of a group [characters].
    base : float, optional
        Width a group takes besides its columns (a border).

    Returns
    -------
    list of list of int
        Column indices of each group, label columns first.
    """
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


def table_width(spec: TableSpec, compact: bool = False) -> int:
    """Characters a rich table of ``spec`` takes, its headers wrapped at their spaces (cells never wrap).

    With borders (3 per column and 1), or ``compact`` (no border, a rule under the header, two spaces between columns).

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.
    compact : bool, optional
        Without borders.

    Returns
    -------
    int
        Width [characters].
    """
    widths = _folded_widths(spec)
    if compact:
        return sum(w + 2 for w in widths) - 1
    return sum(w + 3 for w in widths) + 1


def row_labels(spec: TableSpec) -> list[str]:
    """The label of each row as a stacked block heads it.

    Its label cells joined by ' · ', a blank label cell taking the value of the row above (a model row under its
    material).

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.

    Returns
    -------
    list of str
        One label per row.
    """
    labels = label_columns(spec)
    last = [""] * len(spec.columns)
    out = []
    for row in spec.rows:
        parts = []
        for j in labels:
            if row[j].strip():
                last[j] = row[j]
                for k in labels:  # a new outer label starts its inner labels afresh
                    if k > j:
                        last[k] = ""
            parts.append(last[j] if not row[j].strip() else row[j])
        out.append(" · ".join(p for p in parts if p))
    return out


def _pack(pairs: list[str], width: int, indent: str) -> list[str]:
    """``name: value`` pairs packed into lines of at most ``width`` characters.

    A pair longer than a line is broken at its spaces only (a number is never cut); a word longer than the line stays
    whole.
    """
    lines: list[str] = []
    current = ""
    for pair in pairs:
        if current and len(indent) + len(current) + len(PAIR_GAP) + len(pair) <= width:
            current += PAIR_GAP + pair
            continue
        if current:
            lines.append(indent + current)
        current = ""
        if len(indent) + len(pair) <= width:
            current = pair
            continue
        # a long value (a list of parameters): broken after its '; ' where it can, else at its spaces
        for word in _pieces(pair, width - len(indent)):
            if current and len(indent) + len(current) + 1 + len(word) > width:
                lines.append(indent + current)
                current = "  " + word  # continuation lines indented under the pair
            else:
                current = f"{current} {word}" if current else word
        lines.append(indent + current)
        current = ""
    if current:
        lines.append(indent + current)
    return lines


def _pieces(text: str, width: int) -> list[str]:
    """The words of ``text`` for line breaking.

    Its '; '-separated parts kept whole where they fit ``width`` (a parameter with its value and error), else split at
    their spaces.
    """
    out = []
    parts = text.split("; ")
    for k, part in enumerate(parts):
        part = part + (";" if k < len(parts) - 1 else "")
        out += [part] if len(part) <= width - 2 else part.split(" ")
    return out


def stacked_blocks(spec: TableSpec, width: int) -> list[tuple[str, bool]]:
    """A table too wide for ``width`` as text lines.

    Its title, then per row its label line and its other cells as ``name: value`` pairs packed into lines of ``width``
    (cells that are empty left out). Returns (line, bold) pairs; a row of ``bold_rows`` is bold.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.
    width : int
        Terminal width [characters].

    Returns
    -------
    list of tuple of (str, bool)
    """
    labels = set(label_columns(spec))
    heads = [" ".join(h.split()) for h, _ in spec.columns]
    out: list[tuple[str, bool]] = [(line, False) for line in _pack([spec.title], width, "")]
    for i, (row, label) in enumerate(zip(spec.rows, row_labels(spec))):
        bold = i in spec.bold_rows
        pairs = [f"{heads[j]}: {cell}" for j, cell in enumerate(row) if j not in labels and cell.strip()]
        out.append((label or f"row {i + 1}", bold))
        out += [(line, bold) for line in _pack(pairs, width, "  ")]
    return out


def rich_tables(spec: TableSpec, width: int) -> list:
    """What a terminal of ``width`` columns prints for a table.

    One rich Table when it fits (headers wrapped at spaces), with borders or else compact (no borders), else the stacked
    blocks (``stacked_blocks``) as one rich Text.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.
    width : int
        Terminal width [characters].

    Returns
    -------
    list
        rich renderables (Table or Text), printed in order.
    """
    from rich import box
    from rich.table import Table
    from rich.text import Text

    whole = sum(w + 3 for w in _widths(spec)) + 1 <= width  # fits with its headers on one line each
    widths = _widths(spec) if whole else _folded_widths(spec)
    compact = table_width(spec) > width
    if compact and table_width(spec, compact=True) > width:
        text = Text(no_wrap=True, overflow="ignore")
        for k, (line, bold) in enumerate(stacked_blocks(spec, width)):
            if k:
                text.append("\n")
            style = "bold" if bold or k == 0 else None
            text.append(line, style=style)
        return [text]
    t = (
        Table(title=Text(spec.title), title_justify="left", box=box.SIMPLE_HEAD, show_edge=False, padding=(0, 1, 0, 0))
        if compact
        else Table(title=Text(spec.title), title_justify="left")
    )
    for j, (head, justify) in enumerate(spec.columns):
        t.add_column(Text(wrap_header(head, widths[j])), justify=justify, no_wrap=True, min_width=widths[j])
    for i, row in enumerate(spec.rows):
        t.add_row(
            *(Text(cell) for cell in row),
            style="bold" if i in spec.bold_rows else None,
            end_section=i in spec.sections,
        )
    return [t]


def render(result, out_dir=None, written=None, console=None) -> None:
    """Print a result's summary tables, then its warnings and notes, then where its files are.

    Parameters
    ----------
    result : capred.result.Result
        The run.
    out_dir : str, pathlib.Path or None, optional
        The output folder, named in the last line.
    written : list of pathlib.Path or None, optional
        The files written (None: no line about files).
    console : rich.console.Console or None, optional
        Where to print (default: a new Console on standard output).
    """
    from rich.console import Console

    con = console or Console()
    terminal = con.is_terminal
    render_tables(result.console_tables(), con)  # the run's tables, as capred.report.presenters makes them
    for w in result.all_warnings():
        _line(con, terminal, "warning: ", "yellow", w)
    for n in result.all_notes():
        _line(con, terminal, "note: ", "cyan", n)
    if written is not None:
        _line(con, terminal, "", "bold", f"Wrote {len(written)} files to {out_dir}")


def render_tables(specs: list[TableSpec], con) -> None:
    """Print tables: rich and folded to the width on a terminal, plain full-width text otherwise.

    Parameters
    ----------
    specs : list of capred.table_spec.TableSpec
        The tables.
    con : rich.console.Console
        Where to print.
    """
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
    """An empty console table: the first ``left`` columns left-aligned, the others right-aligned.

    Parameters
    ----------
    title : str
        The table's title.
    headers : list of str
        Column headers.
    left : int, optional
        Number of left-aligned columns (default 1).

    Returns
    -------
    capred.table_spec.TableSpec
        With no rows yet.
    """
    return TableSpec(title, [(h, "left" if j < left else "right") for j, h in enumerate(headers)])
