"""The files a run writes: tables and JSON through capred.io.writers, figures and report.html drawn here.

``write_outputs(result, out)`` is the public writer (``capred.write_outputs``):
the CLI, the batch runner and lab scripts all write a run through it.

Figures are drawn once: each panel on its own journal-sized figure (laid out
once), its pixels pasted into the sheet's composite PNG, which report.html
embeds as it is. Single panels (``figures/``) are written only when asked
(``panels=True``), vector formats only when named. Several sheets are drawn
by two processes on a machine with two cores or more.
"""
from __future__ import annotations

import os
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path

from .sheets import NO_STAMP  # noqa: F401  (kept importable from here)

#: draw the sheets in two processes when the run has at least this many panels in two sheets or more and a
#: core is free (the child costs ~15 % more CPU in all, re-loading fonts and copying pages; one panel ~0.3 s)
PARALLEL_MIN_PANELS = 6


@dataclass(frozen=True)
class FigureOptions:
    """What to draw: figure ``formats`` (png, pdf, svg), ``dpi`` of PNGs, single ``panels`` under figures/,
    and whether report.html wants each composite (``html``)."""

    formats: tuple[str, ...] = ("png",)
    dpi: int = 300
    panels: bool = False
    html: bool = True


def write_outputs(result, out, plots: bool = True, formats=("png",), dpi: int = 300,
                  command_line: str | None = None, html: bool = True, csv_dialect: str = "standard",
                  xlsx: bool = False, panels: bool = False) -> list[Path]:
    """Write every output of ``result`` into the folder ``out``, whole or not at all.

    Parameters
    ----------
    result : Result
        Any command's result (``capred.run_shear(...)`` and friends).
    out : str or Path
        Output folder; replaced as a whole (see capred.io.writers).
    plots : bool
        Draw the figure sheets: one composite per sheet in every format of ``formats``.
    formats : sequence of str
        Figure formats: ``png``, ``pdf``, ``svg``.
    dpi : int
        Resolution of PNG figures [dots per inch].
    command_line : str, optional
        Recorded in provenance.json (default: this process's argv).
    html : bool
        Write report.html (it embeds each composite: the PNG already drawn, or the SVG when ``svg`` is
        one of ``formats``).
    csv_dialect : {"standard", "excel-eu"}
        CSV flavour of the tables.
    xlsx : bool
        Also write every table into tables.xlsx.
    panels : bool
        Also write each panel alone, ``figures/<sheet>_<panel>.<format>`` (85 or 180 mm wide).

    Returns
    -------
    list of Path
        The files written.
    """
    from ..io.writers import write_run
    from ..progress import showing, task, wanted

    opts = FigureOptions(tuple(formats), int(dpi), bool(panels), bool(html))

    with showing(wanted()), ExitStack() as tables:
        tables.enter_context(task("writing tables"))

        def artifacts(folder) -> None:
            tables.close()  # the tables are written: their bar ends
            drawn = _write_figures(result, folder, opts) if plots else {}
            if html:
                from .html import render_html

                with task("writing report.html"):
                    folder.write_bytes("report.html", render_html(result, drawn, plots).encode("utf-8"))

        return write_run(result, out, command_line=command_line, csv_dialect=csv_dialect, xlsx=xlsx,
                         artifacts=artifacts)


# --- one sheet ----------------------------------------------------------------------------------------------
def _img_markup(name: str, png: bytes, width_mm: float) -> str:
    import base64
    import html

    data = base64.b64encode(png).decode("ascii")
    return (f"<img alt='{html.escape(name)}' src='data:image/png;base64,{data}' "
            f"style='width:100%;max-width:{width_mm:.0f}mm;height:auto'>")


def _draw_sheet(name: str, sheet, folder, opts: FigureOptions) -> tuple[dict, list[str]]:
    """Draw one sheet and write its files; returns (entry for report.html, names written)."""
    from .sheets import (NO_STAMP, Sheet, compose, compose_raster, encode_png, journal_style, panel_figure,
                         raster, sheet_layout)

    written: list[str] = []
    entry = {"caption": getattr(sheet, "caption", "") or "", "panels": [], "svg": ""}
    vector = [f for f in opts.formats if f in ("pdf", "svg")]
    want_png = "png" in opts.formats or (opts.html and "svg" not in opts.formats)

    def save(fig, fname, fmt):
        with journal_style(salt=fname):
            fig.savefig(folder.path_for(fname), format=fmt, dpi=opts.dpi, metadata=NO_STAMP[fmt])
        written.append(fname)

    if not isinstance(sheet, Sheet):  # a plain figure function: one composite, no panels
        from .sheets import _freeze_layout

        with journal_style():
            fig = sheet()
            _freeze_layout(fig)
        if want_png:
            png = encode_png(raster(fig), fig.dpi)
            if "png" in opts.formats:
                folder.path_for(f"{name}.png").write_bytes(png)
                written.append(f"{name}.png")
            entry["svg"] = _img_markup(name, png, fig.get_figwidth() * 25.4)
        for fmt in vector:
            save(fig, f"{name}.{fmt}", fmt)
        return _html_svg(entry, name, folder, opts), written

    pfigs = [panel_figure(sheet, p, opts.dpi) for p in sheet.panels]
    entry["panels"] = [(p.name, p.caption) for p in sheet.panels]
    if want_png:
        rasters = [raster(f) for f in pfigs]
        png = encode_png(compose_raster(sheet, rasters, opts.dpi), opts.dpi)
        if "png" in opts.formats:
            folder.path_for(f"{name}.png").write_bytes(png)
            written.append(f"{name}.png")
            if opts.panels:
                for p, img in zip(sheet.panels, rasters):
                    fname = f"figures/{name}_{p.name}.png"
                    folder.path_for(fname).write_bytes(encode_png(img, opts.dpi))
                    written.append(fname)
        entry["svg"] = _img_markup(name, png, sheet_layout(sheet)[1])
    if vector:
        composite = compose(sheet, opts.dpi, pfigs)
        for fmt in vector:
            save(composite, f"{name}.{fmt}", fmt)
            if opts.panels:
                for p, pfig in zip(sheet.panels, pfigs):
                    save(pfig, f"figures/{name}_{p.name}.{fmt}", fmt)
    return _html_svg(entry, name, folder, opts), written


def _html_svg(entry: dict, name: str, folder, opts: FigureOptions) -> dict:
    """With ``svg`` among the formats, report.html shows the SVG just written (vector) instead of the PNG."""
    if opts.html and "svg" in opts.formats:
        text = folder.path_for(f"{name}.svg").read_text(encoding="utf-8")
        entry["svg"] = text[text.index("<svg"):]  # without the XML declaration and DOCTYPE
    return entry


# --- every sheet ----------------------------------------------------------------------------------------------
def _write_figures(result, folder, opts: FigureOptions) -> dict:
    """Each sheet's composite in every format (its panels under figures/ when asked).

    Returns {sheet: {"svg": the composite's markup for report.html (an <img> of the PNG, or the inline SVG),
    "caption": ..., "panels": [(name, caption), ...]}}.
    """
    from ..progress import task
    from .presenters import figures

    sheets = list(figures(result).items())
    if not sheets:
        return {}
    if opts.panels:
        (folder.tmp / "figures").mkdir(exist_ok=True)
    cost = [len(getattr(s, "panels", ())) or 1 for _, s in sheets]
    with task("drawing figures", total=len(sheets)) as advance:
        if _parallel(cost):
            results = _two_processes(sheets, cost, folder, opts, advance)
        else:
            results = []
            for name, sheet in sheets:
                results.append(_draw_sheet(name, sheet, folder, opts))
                advance(1)
    out = {}
    for (name, _), (entry, names) in zip(sheets, results):
        for fname in names:
            folder.done(fname)
        out[name] = entry
    if opts.panels and not any(n.startswith("figures/") for _, names in results for n in names):
        os.rmdir(folder.tmp / "figures")
    return out


def _parallel(cost: list[int]) -> bool:
    """Two processes for several sheets with enough panels, when a second core is free: the machine has two
    or more and its load average leaves one idle (on a busy shared machine the fork's ~15 % more CPU buys no
    time: benchmarks/bench_one_path.py). CAPRED_FIGURE_PROCESSES=1 or 2 decides instead."""
    if len(cost) < 2 or sum(cost) < PARALLEL_MIN_PANELS or not hasattr(os, "fork"):
        return False
    import multiprocessing

    if multiprocessing.current_process().daemon:  # a batch worker: the batch already uses the cores
        return False
    forced = os.environ.get("CAPRED_FIGURE_PROCESSES")
    if forced in ("1", "2"):
        return forced == "2"
    cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]  # this run itself counts for up to one
    except OSError:
        load = 0.0
    return cores >= 2 and load < cores - 0.5


def _two_processes(sheets, cost, folder, opts, advance) -> list:
    """Draw the sheets in this process and one forked child, split by their panel counts; results in order."""
    import pickle
    import tempfile
    import threading

    mine, theirs, load = [], [], [0, 0]
    for k in sorted(range(len(sheets)), key=lambda k: -cost[k]):  # greedy: largest first, to the lighter side
        side = 0 if load[0] <= load[1] else 1
        (mine if side == 0 else theirs).append(k)
        load[side] += cost[k]
    mine.sort()
    theirs.sort()
    import gc

    from .sheets import warm_up

    warm_up(opts.dpi)  # fonts, glyphs and mathtext loaded once, before the child inherits them
    box = tempfile.TemporaryFile()
    ticks_r, ticks_w = os.pipe()
    gc.freeze()  # the child's collections leave the inherited objects alone: their pages stay shared
    pid = -1
    try:
        pid = os.fork()
    finally:
        if pid != 0:
            gc.unfreeze()
    if pid == 0:  # the child: draw its sheets, pickle the results into the shared file, leave
        code = 1
        try:
            from ..progress import detach

            detach()
            os.close(ticks_r)
            done = []
            try:
                for k in theirs:
                    done.append((k, _draw_sheet(*sheets[k], folder, opts)))
                    os.write(ticks_w, b".")
                pickle.dump(("ok", done), box)
            except BaseException as exc:  # noqa: BLE001 - sent to the parent, raised there
                import traceback

                try:
                    pickle.dump(("error", exc), box)
                except Exception:  # an exception that does not pickle
                    pickle.dump(("error", RuntimeError(traceback.format_exc())), box)
            box.flush()
            code = 0
        finally:
            os._exit(code)
    os.close(ticks_w)

    def ticks():  # the child's finished sheets advance the bar
        while os.read(ticks_r, 1):
            advance(1)

    reader = threading.Thread(target=ticks, daemon=True)
    reader.start()
    results: dict[int, tuple] = {}
    try:
        for k in mine:
            results[k] = _draw_sheet(*sheets[k], folder, opts)
            advance(1)
    except BaseException:
        import signal

        os.kill(pid, signal.SIGTERM)
        os.waitpid(pid, 0)
        os.close(ticks_r)
        box.close()
        raise
    _, status = os.waitpid(pid, 0)
    reader.join()
    os.close(ticks_r)
    box.seek(0)
    try:
        kind, payload = pickle.load(box)
    except EOFError:
        raise RuntimeError(f"the process drawing figures ended without a result (status {status})") from None
    finally:
        box.close()
    if kind == "error":
        raise payload
    results.update(dict(payload))
    return [results[k] for k in range(len(sheets))]
