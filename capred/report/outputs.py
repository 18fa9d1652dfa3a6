"""The files a run writes: tables and JSON through capred.io.writers, figures and report.html drawn here.

``write_outputs(result, out)`` is the public writer (``capred.write_outputs``):
the CLI, the batch runner and lab scripts all write a run through it.
"""
from __future__ import annotations

import io
from pathlib import Path

#: no timestamps in figure files: reruns give the same bytes
NO_STAMP = {"png": {"Software": None}, "pdf": {"CreationDate": None, "Producer": None},
            "svg": {"Date": None}}


def write_outputs(result, out, plots: bool = True, formats=("png",), dpi: int = 150,
                  command_line: str | None = None, html: bool = True, csv_dialect: str = "standard",
                  xlsx: bool = False) -> list[Path]:
    """Write every output of ``result`` into the folder ``out``, whole or not at all.

    Parameters
    ----------
    result : Result
        Any command's result (``capred.run_shear(...)`` and friends).
    out : str or Path
        Output folder; replaced as a whole (see capred.io.writers).
    plots : bool
        Draw the figure sheets (each in every format of ``formats``, its panels under ``figures/``).
    formats : sequence of str
        Figure formats: ``png``, ``pdf``, ``svg``.
    dpi : int
        Resolution of raster figures [dots per inch].
    command_line : str, optional
        Recorded in provenance.json (default: this process's argv).
    html : bool
        Write report.html.
    csv_dialect : {"standard", "excel-eu"}
        CSV flavour of the tables.
    xlsx : bool
        Also write every table into tables.xlsx.

    Returns
    -------
    list of Path
        The files written.
    """
    from ..io.writers import write_run

    def artifacts(folder) -> None:
        drawn = _write_figures(result, folder, formats, dpi, svg_inline=html) if plots else {}
        if html:
            from .html import render_html

            folder.write_bytes("report.html", render_html(result, drawn, plots).encode("utf-8"))

    return write_run(result, out, command_line=command_line, csv_dialect=csv_dialect, xlsx=xlsx,
                     artifacts=artifacts)


def _write_figures(result, folder, formats, dpi: int, svg_inline: bool) -> dict:
    """Each sheet as a composite in every format, and each panel alone under figures/.

    Returns {sheet: {"svg": inline SVG of the composite (for the HTML report), "caption": ..., "panels": ...}}.
    """
    from .presenters import figures
    from .sheets import Sheet, compose, single

    out = {}
    for name, sheet in figures(result).items():
        if not isinstance(sheet, Sheet):  # a plain figure function: one composite, no panels
            fig, panels = sheet(), []
        else:
            fig, panels = compose(sheet), sheet.panels
        for fmt in formats:
            fname = f"{name}.{fmt}"
            fig.savefig(folder.path_for(fname), format=fmt, dpi=dpi, metadata=NO_STAMP[fmt])
            folder.done(fname)
        entry = {"caption": getattr(sheet, "caption", "") or "", "panels": []}
        if svg_inline:
            buf = io.StringIO()
            fig.savefig(buf, format="svg", metadata=NO_STAMP["svg"])
            entry["svg"] = buf.getvalue()
        for panel in panels:
            single_fig = single(sheet, panel)
            (folder.tmp / "figures").mkdir(exist_ok=True)
            for fmt in formats:
                fname = f"figures/{name}_{panel.name}.{fmt}"
                single_fig.savefig(folder.path_for(fname), format=fmt, dpi=dpi, metadata=NO_STAMP[fmt])
                folder.done(fname)
            entry["panels"].append((panel.name, panel.caption))
        out[name] = entry
    return out
