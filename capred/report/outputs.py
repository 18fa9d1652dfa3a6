"""The files a run writes: tables and JSON through capred.io.writers, figures and report.html drawn here.

``write_outputs(result, out)`` is the public writer (``capred.write_outputs``):
the CLI, the batch runner and lab scripts all write a run through it.

Figures are drawn once. By default a sheet is one journal-sized figure with
one layout pass (``sheets.sheet_figure``), saved in each format asked for,
and report.html embeds the PNG written. With single panels (``panels=True``)
each panel is drawn on its own figure and the sheet's PNG is pasted from the
panels' pixels. Vector formats are written only when named, and the sheets a
command draws only on request (``Sheet.on_request``, e.g. shear's capillary
stress sheet) only with ``figures="all"``. Several sheets are drawn by two
processes on a machine with two cores or more.
"""

from __future__ import annotations

import os
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path

from .sheets import NO_STAMP  # noqa: F401  (kept importable from here)

#: draw the sheets in two processes when the run has at least this many panels in two sheets or more and a
#: core is free. The child re-loads fonts and re-parses every label (~0.6 s of CPU); a 4-panel sheet costs ~0.55 s:
#: the README's two report sheets drawn in two processes cost 17 % more CPU for 11 % less wall time
#: (benchmarks/bench_one_path.py), so a second process starts from three sheets' worth
PARALLEL_MIN_PANELS = 12
#: which sheets ``figures`` draws: those drawn by default, or every sheet (also those on request)
FIGURE_SETS = ("main", "all")
#: resolutions a PNG may have [dots per inch], as the CLI's --dpi accepts them
DPI_RANGE = (30, 2400)


@dataclass(frozen=True)
class FigureOptions:
    """What to draw: figure formats, resolution, single panels and which sheets.

    Figure ``formats`` (png, pdf, svg), ``dpi`` of PNGs, single ``panels`` under figures/, whether report.html wants
    each composite (``html``), and which sheets (``figures``: "main" leaves out the sheets drawn only on request, "all"
    draws them too).
    """

    formats: tuple[str, ...] = ("png",)
    dpi: int = 300
    panels: bool = False
    html: bool = True
    figures: str = "main"

    def __post_init__(self) -> None:
        """Refuse a resolution outside ``DPI_RANGE`` (the CLI's --dpi range): a whole number of dots per inch."""
        import numbers

        dpi = self.dpi
        whole = isinstance(dpi, numbers.Real) and not isinstance(dpi, bool) and float(dpi).is_integer()
        if not whole or not DPI_RANGE[0] <= dpi <= DPI_RANGE[1]:
            from ..errors import OptionError

            raise OptionError(
                f"dpi (--dpi) must be a whole number of dots per inch between {DPI_RANGE[0]} and {DPI_RANGE[1]} "
                f"(got {dpi!r})"
            )
        object.__setattr__(self, "dpi", int(dpi))


def output_cells(command: str, options) -> int:
    """Table cells a command's outputs take per input row with these options; 0 where it declares none.

    Its ``Reduction.row_cells``: the columns of its per-row table, more for each model in ``options.models`` or each
    registered bridge law.

    Parameters
    ----------
    command : str
        The command (a key of capred.reductions.REDUCTIONS).
    options : object
        Its options object.

    Returns
    -------
    int
        Cells per input row.
    """
    from ..reductions import REDUCTIONS

    red = REDUCTIONS[command]
    fixed, per_model = red.row_cells
    if per_model and red.row_cells_per == "bridge_laws":  # bridge compare: a force and a residual per law
        from ..spec.bridge_laws import LAWS

        return fixed + per_model * len(LAWS)
    models = getattr(options, "models", ()) if per_model else ()
    if isinstance(models, str):  # "thesis", "all" or a comma-separated list, as triaxial's options take it
        from ..physics.effective_stress_models import resolve_models

        models = resolve_models(models)
    return fixed + per_model * len(models)


def check_outputs_ahead(command: str, source, options, out, extra_inputs=()) -> None:
    """Refuse a run whose outputs would exceed the writer's bound, before anything is read or computed.

    A long input file's data lines x the cells its outputs take per row (``Reduction.row_cells``) x about 40 bytes a
    cell, against the writer's bound (capred.io.writers.output_budget). The writer checks the tables again once
    computed.

    Only a plain text file is counted (capred.io.check_rows_output); a workbook, a DataFrame, a command that
    declares no per-row outputs or a file too short to matter costs nothing here.

    Parameters
    ----------
    command : str
        The command (a key of capred.reductions.REDUCTIONS).
    source : str, pathlib.Path, pandas.DataFrame or capred.io.TableSource
        Its input.
    options : object
        Its options (the models it compares set its columns).
    out : pathlib.Path
        The output folder (for the message).
    extra_inputs : sequence of path, optional
        Further inputs of the run (their bytes count toward the bound, as in the writer).

    Raises
    ------
    capred.errors.OutputError
        Over the bound, with nothing written.
    """
    from ..io import check_rows_output
    from ..reductions import REDUCTIONS

    if command in REDUCTIONS and REDUCTIONS[command].row_cells[0]:
        check_rows_output(source, output_cells(command, options), out, extra_inputs)


def write_outputs(
    result,
    out,
    plots: bool = True,
    formats=("png",),
    dpi: int = 300,
    command_line: str | None = None,
    html: bool = True,
    csv_dialect: str = "standard",
    xlsx: bool = False,
    panels: bool = False,
    figures: str = "main",
    store=None,
) -> list[Path]:
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
        Recorded in provenance.json and report.html (default: this process's argv; a batch gives each file the
        command that reproduces that file's run alone).
    html : bool
        Write report.html (it embeds each composite: the PNG already drawn, or the SVG when ``svg`` is
        one of ``formats``).
    csv_dialect : {"standard", "excel-eu"}
        CSV flavour of the tables.
    xlsx : bool
        Also write every table into tables.xlsx.
    panels : bool
        Also write each panel alone, ``figures/<sheet>_<panel>.<format>`` (85 or 180 mm wide).
    figures : {"main", "all"}
        Which sheets: "main" (default) the command's main sheets (shear: the report sheet of each material,
        and its raw curves when they were read); "all" also the sheets drawn only on request (shear: the
        back-analysed capillary stress of each material). report.html names the sheets left out.
    store : str or Path, optional
        A lab's store (SQLite, capred.lab_store) to record the run in once its files are written; default
        the environment variable ``CAPRED_STORE``, else nothing is recorded.

    Returns
    -------
    list of Path
        The files written.
    """
    from ..io import write_run
    from ..progress import showing, task, wanted

    if figures not in FIGURE_SETS:
        from ..errors import OptionError

        raise OptionError(f"figures must be one of {', '.join(FIGURE_SETS)} (got {figures!r})")
    opts = FigureOptions(tuple(formats), dpi, bool(panels), bool(html), figures)

    with showing(wanted()), ExitStack() as tables:
        tables.enter_context(task("writing tables"))

        def artifacts(folder) -> None:
            tables.close()  # the tables are written: their bar ends
            drawn = _write_figures(result, folder, opts) if plots else {}
            if html:
                from .html import render_html

                with task("writing report.html"):
                    page = render_html(result, drawn, plots, command_line=command_line)
                    folder.write_bytes("report.html", page.encode("utf-8"))

        from ..lab_store import Recorder, store_from

        store = store_from(store) if result.command != "history" else None
        # the store is opened and checked before any file is written; the run is recorded once its folder is
        # in place, and a store that fails then puts the earlier folder back (capred.io.writers.RunFolder.commit)
        recorder = Recorder(store) if store is not None else None
        if recorder is not None:
            _note_recorded_before(result, store)
        try:
            return write_run(
                result,
                out,
                command_line=command_line,
                csv_dialect=csv_dialect,
                xlsx=xlsx,
                artifacts=artifacts,
                seal=None if recorder is None else lambda folder: recorder.record(result, folder),
            )
        finally:
            if recorder is not None:
                recorder.close()


def _note_recorded_before(result, store) -> None:
    """Add a note to ``result`` (console, JSON, report) where the store already holds its run.

    The same command, inputs' SHA-256 and options are recorded once (capred.lab_store.run_key), so this run is
    not recorded again.
    """
    from ..lab_store import recorded_as

    run = recorded_as(store, result)
    if run is None:
        return
    note = (
        f"already recorded in {store} as run {run} (same inputs and options); not recorded again (its files "
        "are written all the same)"
    )
    add_line(result, "notes", note)


def add_line(result, kind: str, text: str) -> None:
    """Append ``text`` to ``result``'s notes or warnings, which the console, the JSON document and report show.

    The document is built again. A result that cannot take it prints it on stderr.

    Parameters
    ----------
    result : Result
        Any command's result.
    kind : {"notes", "warnings"}
        Which list.
    text : str
        The line.
    """
    lines = getattr(result, kind, None)
    if isinstance(lines, list):
        lines.append(text)
    else:
        try:
            setattr(result, kind, [*(lines or ()), text])
        except (AttributeError, TypeError):  # a result that cannot take it: the console still says it
            import sys

            print(f"{kind[:-1]}: {text}", file=sys.stderr)
            return
    for cached in ("_json_lazy", "_json_cache"):  # the document is built again with the line
        result.__dict__.pop(cached, None)


# --- one sheet ----------------------------------------------------------------------------------------------
def _title(sheet) -> str:
    """A sheet's title for report.html's caption (a per-material sheet names its material there)."""
    return str(getattr(sheet, "title", "") or "")


def img_markup(name: str, png: bytes, width_mm: float) -> str:
    """An ``<img>`` element holding a PNG inline (base64 data URI) at a width in millimetres.

    Parameters
    ----------
    name : str
        Alternative text.
    png : bytes
        The PNG file.
    width_mm : float
        Displayed width [mm].

    Returns
    -------
    str
        HTML.

    References
    ----------
    RFC 2397, The "data" URL scheme, doi:10.17487/RFC2397.
    """
    import base64
    import html

    data = base64.b64encode(png).decode("ascii")
    return (
        f"<img alt='{html.escape(name)}' src='data:image/png;base64,{data}' "
        f"style='width:100%;max-width:{width_mm:.0f}mm;height:auto'>"
    )


def _draw_sheet(name: str, sheet, folder, opts: FigureOptions) -> tuple[dict, list[str]]:
    """Draw one sheet and write its files; returns (entry for report.html, names written)."""
    from .sheets import (
        Sheet,
        compose,
        compose_raster,
        encode_png,
        journal_style,
        panel_figure,
        raster,
        release,
        sheet_figure,
        sheet_layout,
    )

    written: list[str] = []
    entry = {"caption": getattr(sheet, "caption", "") or "", "panels": [], "svg": "", "title": _title(sheet)}
    vector = [f for f in opts.formats if f in ("pdf", "svg")]
    want_png = "png" in opts.formats or (opts.html and "svg" not in opts.formats)

    def save(fig, fname, fmt):
        with journal_style(salt=fname):
            fig.savefig(folder.path_for(fname), format=fmt, dpi=opts.dpi, metadata=NO_STAMP[fmt])
        written.append(fname)

    if not isinstance(sheet, Sheet):  # a plain figure function: one composite, no panels
        from .sheets import freeze_layout

        with journal_style():
            fig = sheet()
            freeze_layout(fig)
        if want_png:
            png = encode_png(raster(fig), fig.dpi)
            if "png" in opts.formats:
                folder.path_for(f"{name}.png").write_bytes(png)
                written.append(f"{name}.png")
            entry["svg"] = img_markup(name, png, fig.get_figwidth() * 25.4)
        for fmt in vector:
            save(fig, f"{name}.{fmt}", fmt)
        return _html_svg(entry, name, folder, opts), written

    entry["panels"] = [(p.name, p.caption) for p in sheet.panels]
    if not opts.panels:  # the sheet alone: one figure, laid out once, saved in each format
        # drawn on the figure of the previous sheet of its shape (the other material's, a batch's previous
        # file's) when there is one, and handed back once written: the same pixels, without making the axes
        # and their ticks anew (sheets.release)
        fig = sheet_figure(sheet, opts.dpi, reuse=not vector)
        if want_png:
            png = encode_png(raster(fig), opts.dpi)
            if "png" in opts.formats:
                folder.path_for(f"{name}.png").write_bytes(png)
                written.append(f"{name}.png")
            entry["svg"] = img_markup(name, png, sheet_layout(sheet)[1])
        for fmt in vector:
            save(fig, f"{name}.{fmt}", fmt)
        if not vector:
            release(fig)
        return _html_svg(entry, name, folder, opts), written

    # single panels asked for: each panel on its own figure, the sheet's PNG pasted from their pixels
    pfigs = [panel_figure(sheet, p, opts.dpi) for p in sheet.panels]
    if want_png:
        rasters = [raster(f) for f in pfigs]
        png = encode_png(compose_raster(sheet, rasters, opts.dpi), opts.dpi)
        if "png" in opts.formats:
            folder.path_for(f"{name}.png").write_bytes(png)
            written.append(f"{name}.png")
            for p, img in zip(sheet.panels, rasters):
                fname = f"figures/{name}_{p.name}.png"
                folder.path_for(fname).write_bytes(encode_png(img, opts.dpi))
                written.append(fname)
        entry["svg"] = img_markup(name, png, sheet_layout(sheet)[1])
    if vector:
        composite = compose(sheet, opts.dpi, pfigs)
        for fmt in vector:
            save(composite, f"{name}.{fmt}", fmt)
            for p, pfig in zip(sheet.panels, pfigs):
                save(pfig, f"figures/{name}_{p.name}.{fmt}", fmt)
    return _html_svg(entry, name, folder, opts), written


def _html_svg(entry: dict, name: str, folder, opts: FigureOptions) -> dict:
    """With ``svg`` among the formats, report.html shows the SVG just written (vector) instead of the PNG."""
    if opts.html and "svg" in opts.formats:
        text = folder.path_for(f"{name}.svg").read_text(encoding="utf-8")
        entry["svg"] = text[text.index("<svg") :]  # without the XML declaration and DOCTYPE
    return entry


# --- every sheet ----------------------------------------------------------------------------------------------
def _write_figures(result, folder, opts: FigureOptions) -> dict:
    """Each sheet's composite in every format (its panels under figures/ when asked).

    Returns {sheet: {"svg": the composite's markup for report.html (an <img> of the PNG, or the inline SVG),
    "caption": ..., "panels": [(name, caption), ...]}}, in the presenter's order; a sheet drawn only on
    request and not asked for has no picture ("svg" empty) and a caption saying how to have it.
    """
    from ..progress import task
    from .presenters import figures

    every = list(figures(result).items())
    sheets = [(k, s) for k, s in every if opts.figures == "all" or not getattr(s, "on_request", False)]
    skipped = {k: on_request_entry(s) for k, s in every if (k, s) not in sheets}
    if not sheets:
        return skipped
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
    drawn = {}
    for (name, _), (entry, names) in zip(sheets, results):
        for fname in names:
            folder.done(fname)
        drawn[name] = entry
    if opts.panels and not any(n.startswith("figures/") for _, names in results for n in names):
        os.rmdir(folder.tmp / "figures")
    return {name: drawn.get(name) or skipped[name] for name, _ in every}


def on_request_entry(sheet) -> dict:
    """report.html's entry of a sheet not drawn (drawn on request only).

    No picture, a caption saying how to have it.

    Parameters
    ----------
    sheet : Sheet
        The sheet left undrawn.

    Returns
    -------
    dict
        The entry, as the report's template reads it.

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    what = getattr(sheet, "title", "") or ""
    return {
        "svg": "",
        "title": _title(sheet),
        "panels": [],
        "caption": f"Not drawn by default: {what} ({len(getattr(sheet, 'panels', ()))} panels) is drawn with "
        '--figures all (write_outputs(..., figures="all")). ' + (getattr(sheet, "caption", "") or ""),
    }


def _parallel(cost: list[int]) -> bool:
    """Two processes for several sheets with enough panels (PARALLEL_MIN_PANELS), when a second core is free.

    `capred.io.writers.second_core_free`: on a busy shared machine the fork's extra CPU buys no time,
    benchmarks/bench_one_path.py. CAPRED_FIGURE_PROCESSES=1 or 2 decides instead.
    """
    from ..io import second_core_free

    if len(cost) < 2:
        return False
    if os.environ.get("CAPRED_FIGURE_PROCESSES") not in ("1", "2") and sum(cost) < PARALLEL_MIN_PANELS:
        return False
    return second_core_free("CAPRED_FIGURE_PROCESSES")


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
