"""A result in a notebook.

``result.plot()`` shows its figures, ``result._repr_html_()`` a compact summary, ``result.report_html()`` the full
report.

capred draws on ``matplotlib.figure.Figure`` (never pyplot), so no IPython formatter knows its figures unless
one is registered: ``plot()`` registers a PNG formatter for Figure in the running IPython kernel (nothing
outside IPython), and returns several sheets as a ``Figures`` mapping that displays each one.
"""

from __future__ import annotations

import base64
import html

from .presenters import console_tables, figures  # noqa: F401 - Result.figures() and console_tables() come here

#: rows of each summary table shown in a notebook (the files hold them all)
NOTEBOOK_ROWS = 8
#: summary tables shown by ``_repr_html_`` (the first ones: the key results; all are in the report)
NOTEBOOK_TABLES = 3
#: resolution of the figure in ``_repr_html_`` [dots per inch]: one panel, small and quick
NOTEBOOK_DPI = 60
#: resolution of the Figures ``plot()`` returns, as a notebook shows them [dots per inch]
#: (``fig.savefig(..., dpi=300)`` still gives print resolution)
NOTEBOOK_SCREEN_DPI = 100
#: resolution of the figures inlined by ``report_html()`` [dots per inch]
REPORT_DPI = 120
#: the most ``_repr_html_`` may weigh [bytes]: a notebook stays light to open and to version
REPR_HTML_LIMIT = 30_000


def _png(sheet, dpi: int) -> bytes:
    """PNG bytes of a sheet's composite: each panel drawn once at ``dpi``, pasted under the title."""
    from .sheets import Sheet, compose_raster, encode_png, freeze_layout, journal_style, panel_figure, raster

    if not isinstance(sheet, Sheet):  # a plain figure function
        with journal_style():
            fig = sheet()
            freeze_layout(fig)
        return encode_png(raster(fig), fig.dpi)
    images = [raster(panel_figure(sheet, p, dpi)) for p in sheet.panels]
    return encode_png(compose_raster(sheet, images, dpi), dpi)


def _panel_png(sheet, dpi: int) -> bytes:
    """PNG bytes of the first panel of a sheet alone (the whole figure of a plain figure function)."""
    from .sheets import Sheet, encode_png, panel_figure, raster

    if not isinstance(sheet, Sheet) or not sheet.panels:
        return _png(sheet, dpi)
    return encode_png(raster(panel_figure(sheet, sheet.panels[0], dpi)), dpi)


def figure_png(fig) -> bytes:
    """PNG bytes of a matplotlib Figure as drawn (its layout is final: no layout engine runs again).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure ``result.plot()`` returned.

    Returns
    -------
    bytes
        The PNG file's bytes, at the figure's own dpi.
    """
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=fig.dpi)
    return buf.getvalue()


def register_figure_formatter() -> bool:
    """Let the running IPython kernel show a matplotlib Figure as PNG.

    As pyplot's inline backend does for pyplot figures, unless a formatter for Figure is registered already.

    Returns
    -------
    bool
        True when a kernel is running (a Figure then displays as an image), False elsewhere.
    """
    import sys

    if "IPython" not in sys.modules:
        return False
    from IPython import get_ipython

    shell = get_ipython()
    if shell is None:
        return False
    from matplotlib.figure import Figure

    formatter = shell.display_formatter.formatters["image/png"]
    try:
        formatter.lookup_by_type(Figure)  # one is there already (pyplot's inline backend): the user's, kept
    except KeyError:
        formatter.for_type(Figure, figure_png)
    return True


class Figures(dict):
    """The sheets ``result.plot()`` drew, {name: matplotlib Figure}; a notebook shows each under its name."""

    def _ipython_display_(self) -> None:
        from IPython.display import Markdown, display

        for name, fig in self.items():
            display(Markdown(f"**{name}**"))
            display(fig)


def plot(result, name: str | None = None):
    """The run's figure sheets drawn as matplotlib Figures (no file written); one sheet when ``name`` is given.

    Each composite is laid out as the files are (panels 85 or 180 mm wide, at most 180 mm a sheet), with
    its layout final (no layout engine runs again when the notebook shows or saves it). In a Jupyter kernel
    the figures display as PNG images.

    Parameters
    ----------
    result : Result
        Any command's result.
    name : str, optional
        One sheet (a key of ``result.figures()``); all when omitted.

    Returns
    -------
    matplotlib.figure.Figure or Figures
        The named sheet, or every sheet by name.
    """
    from ..errors import OptionError
    from .sheets import Sheet, compose

    sheets = figures(result)
    if name is not None:
        if name not in sheets:
            raise OptionError(f"no figure '{name}'; this result has: {', '.join(sheets) or 'none'}")
        sheets = {name: sheets[name]}
    register_figure_formatter()
    drawn = {k: compose(s, dpi=NOTEBOOK_SCREEN_DPI) if isinstance(s, Sheet) else s() for k, s in sheets.items()}
    return drawn[name] if name is not None else Figures(drawn)


def _table_html(spec) -> str:
    head = "".join(
        f"<th style='text-align:{'left' if a == 'left' else 'right'}'>{html.escape(h)}</th>" for h, a in spec.columns
    )
    body = []
    for row in spec.rows[:NOTEBOOK_ROWS]:
        cells = "".join(
            f"<td style='text-align:{'left' if a == 'left' else 'right'}'>{html.escape(str(v))}</td>"
            for v, (_, a) in zip(row, spec.columns)
        )
        body.append(f"<tr>{cells}</tr>")
    shown = min(len(spec.rows), NOTEBOOK_ROWS)
    total = spec.total_rows or len(spec.rows)
    more = (
        f"<p><small>{shown} of {total} rows shown; all are in the result's tables "
        f"(<code>result.table()</code>).</small></p>"
        if total > shown
        else ""
    )
    return (
        f"<p><b>{html.escape(spec.title)}</b></p><table><thead><tr>{head}</tr></thead>"
        f"<tbody>{''.join(body)}</tbody></table>{more}"
    )


def repr_html(result, figure: bool = True) -> str:
    """A compact summary of a result for Jupyter (under ``REPR_HTML_LIMIT`` bytes).

    Title, warnings, the key summary tables (the first ``NOTEBOOK_TABLES``, ``NOTEBOOK_ROWS`` rows each) and the first
    panel of the first figure sheet as a small PNG; the full report is ``result.report_html()``.

    Parameters
    ----------
    result : Result
        Any command's result.
    figure : bool
        Include the small figure.

    Returns
    -------
    str
        An HTML fragment.
    """
    parts = [f"<h4>capred {html.escape(result.command)}</h4>"]
    for w in result.all_warnings():
        parts.append(f"<p style='color:#a15c00'>warning: {html.escape(w)}</p>")
    specs = console_tables(result)
    for spec in specs[:NOTEBOOK_TABLES]:
        parts.append(_table_html(spec))
    sheets = figures(result) if figure else {}
    more = []
    if len(specs) > NOTEBOOK_TABLES:
        more.append(f"{len(specs) - NOTEBOOK_TABLES} more tables")
    if sheets:
        more.append(f"{len(sheets)} figure sheet{'s' if len(sheets) != 1 else ''}: <code>result.plot()</code>")
    more.append("the full report: <code>result.report_html()</code>")
    tail = f"<p><small>{'; '.join(more)}.</small></p>"
    if sheets:
        first = next(iter(sheets))
        data = base64.b64encode(_panel_png(sheets[first], NOTEBOOK_DPI)).decode("ascii")
        img = f"<img alt='{html.escape(first)}' src='data:image/png;base64,{data}'/>"
        if sum(map(len, parts)) + len(img) + len(tail) + 40 <= REPR_HTML_LIMIT:
            parts.append(img)
    parts.append(tail)
    out = "<div class='capred-result'>" + "".join(parts) + "</div>"
    while len(out.encode("utf-8")) > REPR_HTML_LIMIT and len(parts) > 2:  # a huge table: fewer tables shown
        parts.pop(-2)
        out = "<div class='capred-result'>" + "".join(parts) + "</div>"
    return out


def report_html(result, dpi: int = REPORT_DPI) -> str:
    """The full report.html of a result as a string, its figures inlined as PNG (nothing written).

    Parameters
    ----------
    result : Result
        Any command's result.
    dpi : int
        Resolution of the inlined figures [dots per inch].

    Returns
    -------
    str
        The self-contained HTML document ``write_outputs`` writes as report.html.
    """
    from .html import render_html
    from .outputs import img_markup, on_request_entry
    from .sheets import Sheet, sheet_layout

    drawn = {}
    for name, sheet in figures(result).items():
        if getattr(sheet, "on_request", False):
            drawn[name] = on_request_entry(sheet)
            continue
        width = sheet_layout(sheet)[1] if isinstance(sheet, Sheet) else 180.0
        drawn[name] = {
            "svg": img_markup(name, _png(sheet, dpi), width),
            "caption": getattr(sheet, "caption", "") or "",
            "title": str(getattr(sheet, "title", "") or ""),
            "panels": [(p.name, p.caption) for p in getattr(sheet, "panels", ())],
        }
    return render_html(result, drawn, True)
