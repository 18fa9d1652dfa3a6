"""report.html: one self-contained document per run (no network; figures inline as SVG; prints to A4).

Built with a jinja2 template (templates/report.html.j2) with autoescaping, so
user text (material names, test ids) is shown literally.
"""

from __future__ import annotations

import re
import sys
from datetime import UTC, datetime
from functools import cache

import numpy as np

from ..references import bibliography
from .render import SIGNIFICANT, fmt

#: the per-row table of the report shows at most this many rows (all are in the CSV)
MAX_REPORT_ROWS = 500

FLAG_MEANING = {
    "outside_pendular": "S_R above the pendular limit, for which the χ approximations were derived",
    "chi1_gt_1": "S_R > 3/(2π): χ1 = (2π S_R/3)^(2/3) exceeds 1",
    "dry_outlier": "dry test beyond the Bonferroni 5 % limit of the externally studentized residuals of its envelope",
    "no_concave_bridge": "more water than the last concave bridge at contact: no exact_neck prediction",
    "lower_positive_component": "lower bound with a positive (compressive) capillary component",
    "spherical_positive_component": "spherical bound with a positive capillary component",
    "edtp_positive_component": "EDTP bound with a positive capillary component",
    "spherical_negative_p_prime": "spherical bound gives p' < 0",
}


def _unit_text(unit: str) -> str:
    """A unit as printed: 'kN/m^3' -> 'kN/m³', '-' -> ''."""
    if unit in ("-", "dimensionless"):
        return ""
    return unit.replace("^-1", "⁻¹").replace("^2", "²").replace("^3", "³")


def _shown(value) -> bool:
    return value is not None and not (isinstance(value, (list, tuple, dict, str)) and len(value) == 0)


def option_value(value, quantity) -> tuple[str, str]:
    """(value, unit) of one option as a user types it: the nomenclature's unit (kPa, kN/m³), not SI.

    Parameters
    ----------
    value : object
        The option's value (SI for a quantity).
    quantity : capred.nomenclature.Quantity or None
        Its glossary entry (its unit and factor), None for a value without one.

    Returns
    -------
    tuple of str
        ``(value as printed, unit)``; the unit "" for a value without one.
    """
    if quantity is not None and isinstance(value, (int, float)) and not isinstance(value, bool):
        return fmt(value * quantity.factor, 6), _unit_text(quantity.unit)
    return _text(value), ""


def _in_force(options, used: set[str]) -> list[tuple[str, object, object]]:
    """(name, value, Quantity or None) of the options of one Options dataclass that are in force.

    Every set top-level option; of a nested one (model parameters), those a model of the run needs and those set to
    other than their default.
    """
    import dataclasses

    from ..nomenclature import QUANTITIES

    out = []
    for f in dataclasses.fields(options):
        if f.name.startswith("_"):
            continue
        value = getattr(options, f.name)
        if dataclasses.is_dataclass(value):
            for name, v, q in _in_force(value, used):
                sub = next(x for x in dataclasses.fields(value) if x.name == name)
                default = sub.default if sub.default is not dataclasses.MISSING else None
                if name in used or (_shown(v) and v != default):
                    out.append((f"{f.name}.{name}", v, q))
            continue
        if not _shown(value):
            continue
        qname = getattr(options, "QUANTITIES", {}).get(f.name)
        out.append((f.name, value, QUANTITIES.get(qname) if qname else None))
    return out


def _options(result, doc: dict) -> list[tuple[str, str, str]]:
    """Rows (option, value, unit) of the options in force, in the units a user types (kPa, kN/m³, mm)."""
    options = getattr(result, "options", None)
    if options is None or not hasattr(options, "__dataclass_fields__"):  # a result without an Options record
        units = doc.get("option_units", {})
        return [
            (k, _text(v), units.get(k, "")) for k, v in doc["options"].items() if _shown(v) and not isinstance(v, dict)
        ]
    used: set[str] = set()
    from ..physics.effective_stress_models import REGISTRY

    models = getattr(result, "models", ())
    for m in models if isinstance(models, (list, tuple)) else ():
        entry = REGISTRY.get(m) if isinstance(m, str) else None
        if entry is not None:
            used.update(name for name, _ in entry.requires)
    rows = []
    for name, value, quantity in _in_force(options, used):
        text, unit = option_value(value, quantity)
        rows.append((name, text, unit))
    return rows


def _text(v) -> str:
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return fmt(v, 6)
    if isinstance(v, (list, tuple)):
        return ", ".join(_text(x) for x in v)
    return "—" if v is None else str(v)


def _row_table(result, limit: int | None = None) -> tuple[str, dict, int]:
    """(file stem, {header: the first ``limit`` values}, number of rows) of a result's per-row table.

    Read from the columns its CSV is written from (no DataFrame where the result gives plain columns).
    """
    import numpy as np

    tables = result.csv_tables()
    if not tables:
        return "", {}, 0
    name, table = next(iter(tables.items()))
    if hasattr(table, "blocks"):  # a Spool: only the rows shown are read back
        return name, table.columns(0, min(table.n, limit if limit is not None else table.n)), table.n
    if isinstance(table, dict):
        n = len(next(iter(table.values()))) if table else 0
        return name, {str(k): np.asarray(v)[:limit] for k, v in table.items()}, n
    head = table if limit is None or len(table) <= limit else table.head(limit)
    return name, {str(c): head.iloc[:, j].to_numpy() for j, c in enumerate(table.columns)}, len(table)


def _flags(result) -> list[tuple[str, int, str]]:
    """(flag, tests, meaning) of the per-row table's flags column.

    Counted block by block for a long run (a Spool's blocks one at a time: never the whole table in memory).
    """
    tables = result.csv_tables()
    if not tables:
        return []
    table = next(iter(tables.values()))
    if hasattr(table, "blocks"):
        pieces = (block["flags"] for block in table.blocks() if "flags" in block)
    else:
        _, columns, _ = _row_table(result)
        pieces = [columns["flags"]] if "flags" in columns else []
    counts: dict[str, int] = {}
    for piece in pieces:
        for text in np.asarray(piece).tolist():
            if isinstance(text, str) and text:
                counts[text] = counts.get(text, 0) + 1
    out: dict[str, int] = {}
    for text, k in sorted(counts.items(), key=lambda kv: -kv[1]):  # distinct combinations, most frequent first
        for f in text.split(";"):
            out[f] = out.get(f, 0) + k
    return [(k, v, FLAG_MEANING.get(k, "")) for k, v in out.items()]


#: printable width of the per-row table on an A4 portrait page (210 mm − 2 × 12 mm margins) [mm]
PRINT_WIDTH_MM = 186.0
#: printable width of the per-row appendix, printed on A4 landscape pages (297 mm − 2 × 10 mm margins, less
#: 4 mm of slack for borders) [mm]: fewer, wider column groups than on portrait pages
APPENDIX_WIDTH_MM = 273.0
#: width of one character of the per-row table's 7 pt text [mm] (DejaVu Sans digits are 0.64 em; 7 pt = 2.47
#: mm), and the cell padding and border [mm]
CHAR_MM = 0.64 * 7 * 25.4 / 72
CELL_MM = 2.2


def _label_columns(columns: list[str]) -> list[int]:
    """Columns repeated in every column group of a split table.

    The test's identity (test_id, material, case, condition) where present, else the first column.
    """
    keys = [j for j, c in enumerate(columns) if c.split(" [")[0] in ("test_id", "case", "material", "condition")]
    return keys or [0]


def column_groups(columns: list[str], rows: list[list[str]], width_mm: float = PRINT_WIDTH_MM) -> list[list[int]]:
    """Columns packed into groups that each fit ``width_mm`` when printed, the label columns repeated in each.

    A column is as wide as its longest cell or the longest word of its header (headers wrap at spaces).

    Parameters
    ----------
    columns : list of str
        Column headers.
    rows : list of list of str
        Cells as printed.
    width_mm : float
        Printable width [mm].

    Returns
    -------
    list of list of int
        Column indices of each group, in order; every column is in exactly one group (besides the repeated
        label columns).
    """
    widths = []
    for j, head in enumerate(columns):
        longest = max([len(w) for w in head.split()] + [len(r[j]) for r in rows if j < len(r)] + [1])
        widths.append(longest * CHAR_MM + CELL_MM)
    from .render import pack_columns

    return pack_columns(widths, _label_columns(columns), width_mm)


def _per_row(result) -> dict:
    """The per-row table of report.html: its first MAX_REPORT_ROWS rows as printed, split into column groups.

    Built column by column (a float column formatted in one pass, escaping only text columns): cell by cell
    through pandas' rows it cost ~20 ms of a 52-test report's ~25.
    """
    import numpy as np

    name, head, total = _row_table(result, MAX_REPORT_ROWS)
    columns = list(head)
    arrays = list(head.values())
    kinds = [a.dtype.kind for a in arrays]
    floats = [j for j, k in enumerate(kinds) if k == "f"]
    cells: list = [None] * len(columns)
    if floats:  # every float column in one copy, formatted in one pass
        values = np.array([arrays[j] for j in floats], dtype=float)
        for j, col in zip(floats, _float_cells(values)):
            cells[j] = col
    for j, k in enumerate(kinds):
        if k != "f":
            cells[j] = [_cell(v) for v in arrays[j].tolist()]
    widths = [
        max([len(w) for w in h.split()] + [max(map(len, col), default=0)] + [1]) * CHAR_MM + CELL_MM
        for h, col in zip(columns, cells)
    ]
    from .render import pack_columns

    groups = pack_columns(widths, _label_columns(columns), APPENDIX_WIDTH_MM)
    left = [c.split(" [")[0] in _LEFT for c in columns]
    # only text is escaped, once per column (the label columns repeat in every group): numbers and booleans as
    # printed have nothing to escape
    from html import escape

    cells = [[escape(c, quote=False) for c in col] if k not in "fiub" else col for col, k in zip(cells, kinds)]
    parts = [
        {
            "head": _head_markup([(columns[j], left[j]) for j in g]),
            "body": _rows_markup([cells[j] for j in g], [left[j] for j in g]),
        }
        for g in groups
    ]
    return {
        "columns": columns,
        "parts": parts,
        "rows": range(len(arrays[0]) if arrays else 0),
        "total": total,
        "file": f"{name}.csv",
    }


def _cell(value) -> str:
    """One cell of a text or mixed column as printed.

    Numbers as ``fmt`` prints them, a list (an interval) as its numbers joined by '; ' (as in the CSV, never a Python
    repr), nothing for None.
    """
    if isinstance(value, (list, tuple)):
        return "; ".join(_cell(v) for v in value)
    return fmt(value) if isinstance(value, float) else ("" if value is None else str(value))


def _float_cells(values: np.ndarray) -> list[list[str]]:
    """Float columns (the rows of ``values``) as printed, as ``fmt`` prints each value.

    4 significant digits, '—' when not finite; one format call for every value.
    """
    rows, n = values.shape
    flat = (_FLOAT_FORMAT * values.size % tuple(values.ravel().tolist())).split("\x00")
    for k in np.flatnonzero(~np.isfinite(values.ravel())).tolist():
        flat[k] = "—"
    return [flat[i * n : (i + 1) * n] for i in range(rows)]


def _escape(text: str) -> str:
    """``markupsafe.escape(text)`` as a plain str (the same entities).

    At the cost of one regex search for the usual cell with nothing to escape (a number as printed).
    """
    if _SPECIAL.search(text) is None:
        return text
    from markupsafe import escape

    return str(escape(text))


_SPECIAL = re.compile("[&<>'\"]")


def _head_markup(columns: list[tuple[str, bool]]):
    """The <th> cells of a table's header row from (header, left-aligned) pairs, escaped, as one HTML string."""
    from markupsafe import Markup

    return Markup("".join(f'<th class="{"l" if is_left else ""}">{_escape(head)}</th>' for head, is_left in columns))


def _rows_markup(columns: list[list[str]], left: list[bool]):
    """The <tr> rows of a table from its columns of (escaped) cells, as one HTML string: one format per row."""
    from markupsafe import Markup

    row = "<tr>" + "".join('<td class="l">{}</td>' if is_left else "<td>{}</td>" for is_left in left) + "</tr>"
    return Markup("\n".join(map(row.format, *columns)))


#: one value of a float column as ``fmt`` prints it (``%`` and ``format`` give the same digits), and a separator
_FLOAT_FORMAT = f"%.{SIGNIFICANT}g\x00"


_LEFT = ("test_id", "case", "material", "condition", "flags", "status", "branch", "group", "source")


def _created() -> str:
    """The report's date: SOURCE_DATE_EPOCH when set (reproducible builds), else now (UTC, ISO 8601)."""
    from ..io import source_date_epoch

    when = source_date_epoch() or datetime.now(UTC)
    return when.replace(microsecond=0).isoformat()


@cache
def _template(name: str):
    """A template of this package, compiled once per process (with its Environment)."""
    from importlib.resources import files

    import jinja2

    from ..text_safety import html_finalize

    env = jinja2.Environment(autoescape=True, undefined=jinja2.StrictUndefined, finalize=html_finalize)
    if name == "season":
        return env.from_string(_SEASON)
    return env.from_string(files("capred.report").joinpath(f"templates/{name}").read_text(encoding="utf-8"))


def _methods(result) -> tuple[list[str], list[str]]:
    """Paragraphs and reference keys of the methods section.

    The command's (capred.reductions), the run's own notes (result.method_notes()) and, for retention, each fitted
    model's registry method and references.
    """
    from ..reductions import REDUCTIONS

    reduction = REDUCTIONS.get(result.command)
    paragraphs, refs = (list(reduction.method), list(reduction.references)) if reduction else ([], [])
    more, more_refs = result.method_notes()
    paragraphs, refs = paragraphs + list(more), refs + list(more_refs)
    if result.command == "retention":
        from ..fitting.retention_models import MODELS

        fitted = list(dict.fromkeys(m for fits in result.fits.values() for m in fits))
        for m in fitted:
            if m in MODELS:
                paragraphs.append(f"{MODELS[m].label}: {MODELS[m].method}")
                refs += list(MODELS[m].references)
    return list(dict.fromkeys(paragraphs)), list(dict.fromkeys(refs))


def render_html(result, figures: dict, plots: bool, command_line: str | None = None) -> str:
    """The report of one run as an HTML string.

    Parameters
    ----------
    result : Result
        Any command's result.
    figures : dict
        ``{sheet: {"svg": inline SVG, "caption": str, "panels": [(name, caption), ...]}}`` of the drawn sheets.
    plots : bool
        Whether figures were asked for (the report says so when they were not).
    command_line : str, optional
        The command shown (default: this process's command line, or ``capred COMMAND`` outside the CLI).

    Returns
    -------
    str
        A self-contained HTML document that prints whole on A4: wide tables split into column groups that
        repeat the test's identity, figures at their printed size.
    """
    from .presenters import console_tables, draws_figures

    doc = result.header()
    paragraphs, refs = _methods(result)
    names = ", ".join(i["path"].replace("\\", "/").rsplit("/", 1)[-1] for i in doc["inputs"]) or "options"
    return _template("report.html.j2").render(
        title=f"capred {result.command}: {names}",
        doc=doc,
        created=_created(),
        command_line=command_line
        if command_line is not None
        else " ".join(["capred", *sys.argv[1:]])
        if sys.argv and "capred" in sys.argv[0]
        else f"capred {result.command}",
        options=_options(result, doc),
        warnings=doc["warnings"],
        notes=doc["notes"],
        flags=_flags(result),
        tables=[_split_spec(t) for t in console_tables(result)],
        figures=_numbered(result, figures),
        plots=plots or not draws_figures(result),  # no "not drawn" note for a command that draws none
        methods=paragraphs,
        references=bibliography(refs),
        per_row=_per_row(result),
    )


def _numbered(result, figures: dict) -> list[tuple[str, dict, int | None, str]]:
    """(sheet, entry, figure number, heading) of each figure of the report.

    The drawn ones numbered in order, each heading the sheet's title (it names the material of a per-material sheet) and
    the input it shows.
    """
    names = ", ".join(i.path.replace("\\", "/").rsplit("/", 1)[-1] for i in getattr(result, "inputs", ()))
    out, number = [], 0
    for name, entry in figures.items():
        title = (entry.get("title") or "").strip()
        shown = names and f"({names})" not in title  # a sheet whose title names its input already: once
        heading = title + (f" ({names})." if shown else ".") if title else (f"{names}." if names else "")
        if entry.get("svg"):
            number += 1
            out.append((name, entry, number, heading))
        else:
            out.append((name, entry, None, heading or f"{name}."))
    return out


def _split_spec(spec) -> dict:
    """A summary table as column groups that fit the printed width, its row labels repeated in each."""
    heads = [h for h, _ in spec.columns]
    from .render import label_columns

    labels = label_columns(spec)
    widths = [
        max([len(w) for w in h.split()] + [len(r[j]) for r in spec.rows] + [1]) * CHAR_MM * 8.5 / 7 + CELL_MM
        for j, h in enumerate(heads)
    ]
    groups, current, used = [], [], sum(widths[j] for j in labels)
    for j in range(len(heads)):
        if j in labels:
            continue
        if current and used + widths[j] > PRINT_WIDTH_MM:
            groups.append(labels + current)
            current, used = [], sum(widths[k] for k in labels)
        current.append(j)
        used += widths[j]
    if current or not groups:
        groups.append(labels + current)
    return {
        "spec": spec,
        "parts": [
            {
                "head": _head_markup([(spec.columns[j][0], spec.columns[j][1] == "left") for j in g]),
                "body": _summary_rows(spec.rows, [spec.columns[j][1] == "left" for j in g], g),
            }
            for g in groups
        ],
    }


def _summary_rows(rows, left: list[bool], columns: list[int]):
    r"""The rows of one column group of a summary table as HTML.

    Each row is ``\n  <tr>...</tr>\n  `` (the layout the template's row loop gave), cells escaped as the template
    escapes them.
    """
    from markupsafe import Markup

    opens = ['<td class="l">' if is_left else '<td class="">' for is_left in left]
    return Markup(
        "".join(
            [
                "\n  <tr>" + "".join([o + _escape(str(r[j])) + "</td>" for o, j in zip(opens, columns)]) + "</tr>\n  "
                for r in rows
            ]
        )
    )


_SEASON = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width">
<title>capred season</title>
<style>@page { size: A4 landscape; margin: 10mm; }
body { font-family: "DejaVu Sans", Arial, sans-serif; font-size: 9pt; margin: 1em auto; max-width: 1240px;
padding: 0 10px; }
table { border-collapse: collapse; width: 100%; margin-bottom: 1em; }
th, td { border-bottom: 1px solid #ccc; padding: 2px 5px; text-align: right; vertical-align: top; }
th { background: #eee; font-weight: 600; white-space: normal; }
td { white-space: nowrap; } td.l, th.l { text-align: left; } td.l { white-space: normal; overflow-wrap: anywhere; }
td.failed, td.crashed, td.interrupted { color: #a00000; font-weight: 600; }
h1, h2, h3 { break-after: avoid; page-break-after: avoid; } tr { break-inside: avoid; }
ul.files { columns: 3; font-family: monospace; }
@media print { body { font-size: 7pt; margin: 0; max-width: none; padding: 0; } a { color: inherit; } }
</style></head>
<body><h1>capred season: {{ n }} runs, {{ n_ok }} ok{% if n_bad %}, {{ n_bad }} failed, crashed or not run{% endif %}</h1>
<h2>Runs</h2>
<table><thead><tr>{{ head }}</tr></thead>
<tbody>{{ body }}</tbody></table>
{% for section in sections %}<h2 id="{{ section.anchor }}">{{ section.command }}: {{ section.n }} rows
(<a href="{{ section.file }}">{{ section.file }}</a>)</h2>
{% for part in section.parts %}<table><thead><tr>{{ part.head }}</tr></thead><tbody>{{ part.body }}</tbody></table>
{% endfor %}{% endfor %}
<h2>Files of this batch</h2>
<p>Each run's files are listed in index.csv; the batch root holds (each protected by its hash in
provenance.json: a file edited since is never overwritten):</p>
<ul class="files">{% for f in files %}<li><a href="{{ f }}">{{ f }}</a></li>{% endfor %}</ul>
</body></html>
"""
_SEASON_LEFT = ("input", "command", "status", "reason", "material", "headline", "options", "best_model", "branch")
#: printable width of season.html on A4 landscape (297 mm − 2 × 10 mm) [mm] and of one 7 pt character [mm]
SEASON_WIDTH_MM = 277.0
SEASON_CHAR_MM = 0.64 * 7 * 25.4 / 72
#: longest text a wrapping (left-aligned) cell of season.html is counted with when columns are packed
SEASON_WRAP = 28


def _season_cells(frame, columns: list[str]) -> list[list[str]]:
    """Each column of a season table as printed: blank where a run has no value, numbers as ``fmt``."""
    out = []
    for c in frame:
        out.append(
            [
                ("" if v != v else fmt(v)) if isinstance(v, float) else ("" if v is None else str(v))
                for v in frame[c].tolist()
            ]
        )
    return out


def _season_markup(columns: list[str], texts: list[list[str]], group: list[int]):
    """(header markup, rows markup) of the columns ``group`` of a season table; the report a link."""
    from markupsafe import Markup

    def cls(name: str) -> str:
        return "l" if name.split(" [")[0] in _SEASON_LEFT else ""

    head = Markup("".join(f'<th class="{cls(columns[j])}">{_escape(columns[j])}</th>' for j in group))
    cells = []
    for j in group:
        name = columns[j]
        opened = f'<td class="{cls(name)}">'
        if name == "report":
            cells.append([opened + (f'<a href="{_escape(v)}">report</a>' if v else "") + "</td>\n" for v in texts[j]])
        elif name == "status":
            cells.append([f'<td class="l {_escape(v)}">' + _escape(v) + "</td>\n" for v in texts[j]])
        else:
            cells.append([opened + _escape(v) + "</td>\n" for v in texts[j]])
    body = Markup("".join(["<tr>" + "".join(row) + "</tr>" for row in zip(*cells)]))
    return head, body


def _season_groups(columns: list[str], texts: list[list[str]]) -> list[list[int]]:
    """Columns of a season table packed into groups that fit A4 landscape: no column is lost in print.

    The input and its labels are repeated in each group.
    """
    from .render import pack_columns

    widths = []
    for name, col in zip(columns, texts):
        longest = max([len(w) for w in name.split()] + [len(x) for x in col] + [1])
        if name.split(" [")[0] in _SEASON_LEFT:
            longest = min(longest, SEASON_WRAP)
        widths.append(longest * SEASON_CHAR_MM + CELL_MM)
    labels = [j for j, c in enumerate(columns) if c in ("input", "material", "branch")][:2] or [0]
    return pack_columns(widths, labels, SEASON_WIDTH_MM)


def render_season(frame, sections: dict | None = None, files=()) -> str:
    """The season page of a batch.

    Its runs (``frame``, a mapping of column name to array), one section per command (``sections``: {command: its detail
    columns}) and the list of the batch's files.

    The page fits 1280 px and prints on A4 landscape without losing a column: wide tables are split into
    column groups that repeat the input. Rows are built here, column by column (a template loop per cell
    cost ~0.8 s for 1,000 files).

    Parameters
    ----------
    frame : mapping
        Column name -> array, one row per run of the batch.
    sections : dict or None, optional
        Command -> its detail columns.
    files : sequence of str, optional
        The batch's files, listed on the page.

    Returns
    -------
    str
        The HTML page.
    """
    columns = [str(c) for c in frame]
    texts = _season_cells(frame, columns)
    head, body = _season_markup(columns, texts, list(range(len(columns))))
    parts = []
    for command, table in (sections or {}).items():
        names = [str(c) for c in table]
        cells = _season_cells(table, names)
        groups = _season_groups(names, cells)
        parts.append(
            {
                "command": command,
                "anchor": "season-" + command.replace(" ", "-"),
                "file": f"season_{command.replace(' ', '-')}.csv",
                "n": len(cells[0]) if cells else 0,
                "parts": [dict(zip(("head", "body"), _season_markup(names, cells, g))) for g in groups],
            }
        )
    status = frame["status"].tolist() if "status" in frame else []
    return _template("season").render(
        n=len(status),
        n_ok=sum(1 for x in status if x == "ok"),
        n_bad=sum(1 for x in status if x != "ok"),
        head=head,
        body=body,
        sections=parts,
        files=list(files),
    )
