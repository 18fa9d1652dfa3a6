"""report.html: one self-contained document per run (no network; figures inline as SVG; prints to A4).

Built with a jinja2 template (templates/report.html.j2) with autoescaping, so
user text (material names, test ids) is shown literally.
"""
from __future__ import annotations

import sys
from datetime import datetime, timezone

from ..references import bibliography
from .render import fmt

#: the per-row table of the report shows at most this many rows (all are in the CSV)
MAX_REPORT_ROWS = 500

FLAG_MEANING = {
    "outside_pendular": "S_R above the pendular limit, for which the χ approximations were derived",
    "chi1_gt_1": "S_R > 3/(2π): χ1 = (2π S_R/3)^(2/3) exceeds 1",
    "no_concave_bridge": "more water than the last concave bridge at contact: no exact_neck prediction",
    "lower_positive_component": "lower bound with a positive (compressive) capillary component",
    "spherical_positive_component": "spherical bound with a positive capillary component",
    "edtp_positive_component": "EDTP bound with a positive capillary component",
    "spherical_negative_p_prime": "spherical bound gives p' < 0",
}

def _options(doc: dict) -> list[tuple[str, str, str]]:
    units = doc.get("option_units", {})
    out = []
    for name, value in doc["options"].items():
        if isinstance(value, dict):
            for k, v in value.items():
                out.append((f"{name}.{k}", _text(v), ""))
        else:
            out.append((name, _text(value), units.get(name, "")))
    return out


def _text(v) -> str:
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, (list, tuple)):
        return ", ".join(_text(x) for x in v)
    return "—" if v is None else str(v)


def _flags(result) -> list[tuple[str, int, str]]:
    try:
        frame = result.table()
    except Exception:  # pragma: no cover - every result has a table
        return []
    if "flags" not in frame.columns:
        return []
    counts: dict[str, int] = {}
    for text, k in frame["flags"].value_counts().items():  # distinct flag combinations, counted once each
        for f in (text.split(";") if isinstance(text, str) and text else []):
            counts[f] = counts.get(f, 0) + int(k)
    return [(k, v, FLAG_MEANING.get(k, "")) for k, v in counts.items()]


def _per_row(result) -> dict:
    frame = result.table()
    rows = []
    for values in frame.head(MAX_REPORT_ROWS).itertuples(index=False):
        rows.append([fmt(v) if isinstance(v, float) else ("" if v is None else str(v)) for v in values])
    name = next(iter(result.tables()))
    return {"columns": [str(c) for c in frame.columns], "rows": rows, "total": len(frame), "file": f"{name}.csv"}


def render_html(result, figures: dict, plots: bool) -> str:
    """The report of one run as an HTML string (figures: {sheet: {"svg", "caption", "panels"}})."""
    from importlib.resources import files

    import jinja2

    from .presenters import console_tables

    template = jinja2.Environment(autoescape=True, undefined=jinja2.StrictUndefined).from_string(
        files("capred.report").joinpath("templates/report.html.j2").read_text(encoding="utf-8"))
    doc = result.header()
    from ..reductions import REDUCTIONS

    reduction = REDUCTIONS.get(result.command)
    paragraphs, refs = (list(reduction.method), list(reduction.references)) if reduction else ([], [])
    more, more_refs = result.method_notes()
    paragraphs, refs = paragraphs + more, list(dict.fromkeys(refs + more_refs))
    names = ", ".join(i["path"].replace("\\", "/").rsplit("/", 1)[-1] for i in doc["inputs"]) or "options"
    return template.render(
        title=f"capred {result.command}: {names}",
        doc=doc,
        created=datetime.now(timezone.utc).replace(microsecond=0).isoformat(),
        command_line=" ".join(["capred", *sys.argv[1:]]) if sys.argv and "capred" in sys.argv[0] else
        f"capred {result.command}",
        options=_options(doc),
        warnings=doc["warnings"],
        notes=doc["notes"],
        flags=_flags(result),
        tables=console_tables(result),
        figures=list(figures.items()),
        plots=plots,
        methods=paragraphs,
        references=bibliography(refs),
        per_row=_per_row(result),
    )


_SEASON = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>capred season</title>
<style>@page { size: A4 landscape; margin: 12mm; } body { font-family: "DejaVu Sans", Arial, sans-serif;
font-size: 9pt; margin: 1.5em; } table { border-collapse: collapse; } th, td { border-bottom: 1px solid #ccc;
padding: 2px 6px; text-align: right; } th { background: #eee; } td.l, th.l { text-align: left; }</style></head>
<body><h1>capred season: {{ n }} runs</h1>
<table><tr>{% for c in columns %}<th class="l">{{ c }}</th>{% endfor %}</tr>
{% for row in rows %}<tr>{% for c, v in row %}<td class="{{ 'l' if c in ('input', 'command', 'status', 'material',
'best_model') else '' }}">{% if c == 'report' and v %}<a href="{{ v }}">report</a>{% else %}{{ v }}{% endif %}</td>
{% endfor %}</tr>{% endfor %}</table></body></html>
"""


def render_season(frame) -> str:
    """The season table of a batch as one HTML page linking each run's report.html."""
    import jinja2

    rows = [[(c, fmt(v) if isinstance(v, float) else ("" if v is None else str(v))) for c, v in zip(frame.columns, r)]
            for r in frame.itertuples(index=False)]
    return jinja2.Environment(autoescape=True).from_string(_SEASON).render(
        n=int(frame["input"].nunique()) if len(frame) else 0, columns=list(frame.columns), rows=rows)
