"""A result in a notebook: ``result.plot()`` draws figures, ``result._repr_html_()`` shows tables and the main figure."""

from __future__ import annotations

import base64
import html

#: rows of each summary table shown in a notebook (the files hold them all)
NOTEBOOK_ROWS = 12
#: resolution of the figure in ``_repr_html_`` [dots per inch]: small and quick, the files hold 300 dpi
NOTEBOOK_DPI = 80
#: resolution of the Figures ``plot()`` returns, as a notebook shows them [dots per inch]
#: (``fig.savefig(..., dpi=300)`` still gives print resolution)
NOTEBOOK_SCREEN_DPI = 100


def _png(sheet, dpi: int) -> bytes:
    """PNG bytes of a sheet's composite: each panel drawn once at ``dpi``, pasted under the title."""
    from .sheets import Sheet, _freeze_layout, compose_raster, encode_png, journal_style, panel_figure, raster

    if not isinstance(sheet, Sheet):  # a plain figure function
        with journal_style():
            fig = sheet()
            _freeze_layout(fig)
        return encode_png(raster(fig), fig.dpi)
    images = [raster(panel_figure(sheet, p, dpi)) for p in sheet.panels]
    return encode_png(compose_raster(sheet, images, dpi), dpi)


def plot(result, name: str | None = None):
    """The run's figure sheets drawn as matplotlib Figures (no file written); one sheet when ``name`` is given.

    Each composite is laid out as the files are (panels 85 or 180 mm wide, at most 180 mm a sheet), with
    its layout final (no layout engine runs again when the notebook shows or saves it)."""
    from ..errors import OptionError
    from .presenters import figures
    from .sheets import Sheet, compose

    sheets = figures(result)
    if name is not None:
        if name not in sheets:
            raise OptionError(f"no figure '{name}'; this result has: {', '.join(sheets) or 'none'}")
        sheets = {name: sheets[name]}
    drawn = {k: compose(s, dpi=NOTEBOOK_SCREEN_DPI) if isinstance(s, Sheet) else s() for k, s in sheets.items()}
    return drawn[name] if name is not None else drawn


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
    """HTML of a result for Jupyter: title, warnings, summary tables and the first figure sheet (PNG at
    ``NOTEBOOK_DPI``)."""
    from .presenters import console_tables, figures

    parts = [f"<h4>capred {html.escape(result.command)}</h4>"]
    for w in result.all_warnings():
        parts.append(f"<p style='color:#a15c00'>warning: {html.escape(w)}</p>")
    for spec in console_tables(result):
        parts.append(_table_html(spec))
    if figure:
        sheets = figures(result)
        if sheets:
            data = base64.b64encode(_png(next(iter(sheets.values())), NOTEBOOK_DPI)).decode("ascii")
            parts.append(f"<img alt='{html.escape(next(iter(sheets)))}' src='data:image/png;base64,{data}'/>")
    return "<div class='capred-result'>" + "".join(parts) + "</div>"
