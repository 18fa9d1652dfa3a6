"""The one CLI path: every command builds an Invocation, ``execute`` runs it.

A command function parses its options into the reduction's Options and
returns an Invocation; ``execute`` runs it on one file (tables or JSON) or on
many (a batch with progress and index.csv). `capred batch` parses each
manifest line with the same command functions, so a manifest line means
exactly what it means on the command line.
"""

import inspect
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated

import typer

from ..errors import CapredError

#: command name -> function turning the parsed parameters into an Invocation
BUILDERS: dict[str, Callable[..., "Invocation"]] = {}


# --- option types shared by the commands ----------------------------------------------------------
OutOpt = Annotated[
    Path | None,
    typer.Option(
        "--out",
        "-o",
        help="Output folder, replaced as a whole by each run [default: ./capred_out/<command>_<input>; "
        "with --json, no files unless --out is given].",
    ),
]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON document on stdout instead of tables.")]
PlotOpt = Annotated[bool, typer.Option("--plots/--no-plots", help="Write the report figures.")]
SampleOpt = Annotated[bool, typer.Option("--sample", help="Run on the bundled (synthetic) sample data.")]
WorkersOpt = Annotated[
    int | None,
    typer.Option(
        min=1,
        help="Worker processes for a batch of files [default: one per core, at most one per file].",
        show_default=False,
    ),
]
SheetOpt = Annotated[
    str | None,
    typer.Option(help="Sheet of an .xlsx or .ods workbook: its name or its number (from 1) [default: the first]."),
]
ThousandsOpt = Annotated[
    str | None,
    typer.Option(
        help="Thousands separator of the file, e.g. '.' to read 1.000 as one thousand in a file with decimal commas."
    ),
]
IgnoreOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--ignore-column",
        help="A column of the file to leave out, as its header writes it (repeat for several); "
        "also lets a run go on past a header that looks like a misspelt known column.",
        show_default=False,
    ),
]
MaxMbOpt = Annotated[
    int | None,
    typer.Option(
        "--max-megabytes",
        min=1,
        help="Largest input the reader takes "
        "on: bytes of a CSV or JSON file or of a workbook once decompressed "
        "[MiB; default 256].",
        show_default=False,
    ),
]
MaxCellsOpt = Annotated[
    int | None,
    typer.Option(
        "--max-cells",
        min=1,
        help="Most cells of a spreadsheet the reader visits [default 2,000,000].",
        show_default=False,
    ),
]
MaxCellCharsOpt = Annotated[
    int | None,
    typer.Option(
        "--max-cell-chars",
        min=1,
        help="Longest cell, header or note the reader takes on, once expanded [characters; default 32,767, "
        "the most a spreadsheet cell holds].",
        show_default=False,
    ),
]
MaxColumnsOpt = Annotated[
    int | None,
    typer.Option(
        "--max-columns", min=1, help="Widest table the reader takes on [columns; default 1,000].", show_default=False
    ),
]


@dataclass(frozen=True)
class OutputOptions:
    """How a run's files are written (the same options for every command)."""

    formats: tuple[str, ...] = ("png",)
    dpi: int = 300
    html: bool = True
    csv_dialect: str = "standard"
    xlsx: bool = False
    panels: bool = False
    figures: str = "main"
    store: str | None = None  # a lab's store (capred history) to record the run in; None: $CAPRED_STORE


@dataclass
class Invocation:
    """A parsed command.

    The builder of a command gives ``command``, ``options`` and ``extra_inputs``; ``command()`` fills in the inputs,
    output folder and output options shared by every command.
    """

    command: str
    options: object
    sources: list = field(default_factory=lambda: [None])  # paths (or None for a run from options only)
    plots: bool = True
    out: Path | None = None
    json: bool = False
    workers: int | None = None  # None: one per core
    extra_inputs: list = field(default_factory=list)  # further files read (curves, a retention fit)
    output: OutputOptions = field(default_factory=OutputOptions)
    limits: object = None  # the reading limits asked for (--max-megabytes ...): a run without a table reads within them


def physics_refusal(exc: ValueError):
    """The OptionError that a ValueError raised by capred.physics stands for, or None for any other ValueError.

    The physics raises a plain ValueError, with a clear text, for a value it refuses (a parameter out of its
    range: κ not below λ, a degree of saturation outside (0, 1]); options built from a command line meet it
    when they check such values at once. The message is kept word for word. A ValueError raised anywhere else
    (numpy's, the CLI's own) is a bug and keeps its traceback.

    Parameters
    ----------
    exc : ValueError
        The error caught.

    Returns
    -------
    OptionError or None
        The error to report, or None where ``exc`` was not raised in capred.physics.
    """
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None or not str(tb.tb_frame.f_globals.get("__name__", "")).startswith("capred.physics."):
        return None
    from ..errors import OptionError

    return OptionError(str(exc))


def fail(exc: CapredError, code: int = 1) -> None:
    """One clean message on stderr and a non-zero exit (no traceback).

    Parameters
    ----------
    exc : CapredError
        The error; its message is printed after ``Error:``, control characters made visible.
    code : int, optional
        Exit status [-].

    Raises
    ------
    typer.Exit
        Always, with ``code``.
    """
    from ..text_safety import visible

    typer.echo(f"Error: {visible(str(exc))}", err=True)  # a cell quoted in a message never acts on the terminal
    raise typer.Exit(code)


_OUTPUT_PARAMS = {
    "formats": (
        Annotated[str, typer.Option("--format", help="Figure formats, comma separated: any of png, pdf, svg.")],
        "png",
    ),
    "dpi": (Annotated[int, typer.Option(help="Resolution of PNG figures [dots per inch].")], 300),
    "html": (
        Annotated[
            bool, typer.Option("--html/--no-html", help="Write report.html, one self-contained document of the run.")
        ],
        True,
    ),
    "csv_dialect": (
        Annotated[
            str,
            typer.Option(
                metavar="standard|excel-eu",
                help="CSV tables: 'standard' (comma, decimal point) or 'excel-eu' "
                "(semicolon, decimal comma, UTF-8 BOM).",
            ),
        ],
        "standard",
    ),
    "xlsx": (Annotated[bool, typer.Option("--xlsx", help="Also write tables.xlsx, a sheet per table.")], False),
    "panels": (
        Annotated[
            bool,
            typer.Option(
                "--panels",
                help="Also write each panel of a figure alone, "
                "figures/<figure>_<panel>.<format>, one journal "
                "column (85 mm) or two (180 mm) wide.",
            ),
        ],
        False,
    ),
    "figures": (
        Annotated[
            str,
            typer.Option(
                metavar="main|all",
                help="Figure sheets: 'main', or 'all' to add "
                "those drawn on request (shear: the "
                "capillary-stress sheets).",
            ),
        ],
        "main",
    ),
    "store": (
        Annotated[
            Path | None,
            typer.Option(
                "--store",
                help="Record the run in this lab store (SQLite, one file; see `capred history`) once its files "
                "are written. Default: the environment variable CAPRED_STORE.",
            ),
        ],
        None,
    ),
}


def _output_options(
    formats: str,
    dpi: int,
    html: bool,
    csv_dialect: str,
    xlsx: bool,
    panels: bool = False,
    figures: str = "main",
    store: Path | None = None,
) -> OutputOptions:
    from ..errors import OptionError

    fmts = tuple(dict.fromkeys(f.strip().lower() for f in formats.split(",") if f.strip()))
    bad = [f for f in fmts if f not in ("png", "pdf", "svg")]
    if bad or not fmts:
        raise OptionError(f"--format: choose png, pdf and/or svg, comma separated (got '{formats}')")
    if not 30 <= dpi <= 2400:
        raise OptionError(f"--dpi must lie between 30 and 2400 (got {dpi})")
    if csv_dialect not in ("standard", "excel-eu"):
        raise OptionError(f"--csv-dialect must be 'standard' or 'excel-eu' (got '{csv_dialect}')")
    if figures not in ("main", "all"):
        raise OptionError(f"--figures must be 'main' or 'all' (got '{figures}')")
    return OutputOptions(fmts, dpi, html, csv_dialect, xlsx, panels, figures, None if store is None else str(store))


def _param(name: str, annotation, default) -> inspect.Parameter:
    return inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=annotation)


def command(app: typer.Typer, name: str, full_name: str | None = None, data: str | None = None, plots: bool = True):
    """Register ``builder`` as the command ``name`` of ``app``; it runs through ``execute``.

    The builder parses the command's own options and returns an Invocation.
    The options every command shares are declared and read here, once: the
    input files (``data``: the help of the DATA argument; None for a command
    without input files) with --sample, --workers, --sheet and --thousands;
    --out and --json; --plots/--no-plots (``plots``); and the output options
    (--format, --dpi, --html/--no-html, --csv-dialect, --xlsx). A builder that
    needs one of them (shear reads --thousands for its curves) declares it
    in its own signature and gets it too.

    Parameters
    ----------
    app : typer.Typer
        The application or command group.
    name : str
        The command's name in ``app`` (``solve`` in ``bridge``).
    full_name : str, optional
        Its name in capred's registry of reductions (``bridge solve``; default ``name``).
    data : str, optional
        Help of the DATA argument; None for a command without input files.
    plots : bool, optional
        The command writes figures (else --plots is accepted and ignored).

    Returns
    -------
    callable
        The decorator; it returns the builder unchanged.
    """
    full = full_name or name
    # every command takes --plots/--no-plots (a command without figures accepts and ignores it)
    shared = {"out": (OutOpt, None), "json_out": (JsonOpt, False), "plots": (PlotOpt, True)}
    if data is not None:
        shared = {
            "data": (data_arg(data), None),
            **shared,
            "sample": (SampleOpt, False),
            "workers": (WorkersOpt, None),
            "sheet": (SheetOpt, None),
            "thousands": (ThousandsOpt, None),
            "ignore_column": (IgnoreOpt, None),
            "max_megabytes": (MaxMbOpt, None),
            "max_cells": (MaxCellsOpt, None),
            "max_columns": (MaxColumnsOpt, None),
            "max_cell_chars": (MaxCellCharsOpt, None),
        }

    def deco(builder):
        sig = inspect.signature(builder)
        own = set(sig.parameters)
        extra = [_param(k, a, d) for k, (a, d) in {**shared, **_OUTPUT_PARAMS}.items() if k not in own]

        def build(**params):
            common = {k: (params[k] if k in own else params.pop(k, d)) for k, (_, d) in shared.items()}
            out = _output_options(**{k: params.pop(k, d) for k, (_, d) in _OUTPUT_PARAMS.items()})
            inv = builder(**params)
            from ..parameters import non_finite_options

            bad = non_finite_options(inv.options)
            if bad:  # nan and inf parse as floats: no value of any quantity (issue 46)
                from ..errors import OptionError

                raise OptionError(
                    f"{'; '.join(bad)}: an option must be a finite number (NaN and infinities are not values)"
                )
            if data is not None:
                inv.limits = _limits(common)
                inv.sources = sources(
                    common["data"],
                    common["sample"],
                    full,
                    common["sheet"],
                    common["thousands"],
                    common["ignore_column"],
                    inv.limits,
                )
                inv.workers = common["workers"]
            inv.out, inv.json, inv.output = common["out"], common["json_out"], out
            inv.plots = common["plots"] and plots
            return inv

        def run(**params):
            try:
                inv = build(**params)
            except CapredError as exc:
                fail(exc)
            except ValueError as exc:  # a value the physics refuses, checked as the options are built
                refusal = physics_refusal(exc)
                if refusal is None:
                    raise
                fail(refusal)
            execute(inv)

        run.__name__, run.__doc__ = builder.__name__, builder.__doc__
        BUILDERS[full] = build
        from ..reductions import REDUCTIONS

        summary = REDUCTIONS[full].summary if full in REDUCTIONS else None
        app.command(name, short_help=summary or None)(_Callback(run, builder, extra))
        return builder

    return deco


class _Callback:
    """A command's callback whose signature is evaluated when typer builds the command, not when it is registered.

    The signature holds the options typer reads: the option annotations of a builder module with postponed annotations
    (``from __future__ import annotations``) call capred.cli.declare.option, which reads the Options declarations, only
    for the command asked for (`capred --help` reads none).

    Parameters
    ----------
    run : callable
        What the command runs, with the shared and the builder's options as keywords.
    builder : callable
        The command's builder (its parameters: the command's own options).
    extra : list of inspect.Parameter
        The shared options the builder does not declare itself.
    """

    def __init__(self, run, builder, extra):
        self._run, self._builder, self._extra = run, builder, extra
        self.__name__ = self.__qualname__ = builder.__name__
        self.__doc__, self.__module__ = builder.__doc__, builder.__module__
        self._signature = None

    def __call__(self, **params):
        return self._run(**params)

    @property
    def __signature__(self) -> inspect.Signature:
        sig = inspect.signature(self._builder)
        if self._signature is None:  # the builder's own options, evaluated once
            names = self._builder.__globals__
            self._signature = [
                p.replace(
                    kind=inspect.Parameter.KEYWORD_ONLY,
                    annotation=eval(p.annotation, names) if isinstance(p.annotation, str) else p.annotation,  # noqa: S307 (the module's own annotation)
                )
                for p in sig.parameters.values()
                if p.kind is not inspect.Parameter.VAR_KEYWORD
            ]
        mine = list(self._signature)
        if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in sig.parameters.values()):
            from .declare import model_parameter_options  # **model_options: the models' own, as registered now

            mine += [p for p in model_parameter_options() if p.name not in sig.parameters]
        first = [p for p in self._extra if p.name == "data"]  # the DATA argument leads
        return sig.replace(
            parameters=[*first, *mine, *(p for p in self._extra if p.name != "data")], return_annotation=None
        )

    @property
    def __annotations__(self) -> dict:
        return {p.name: p.annotation for p in self.__signature__.parameters.values()}


def data_arg(what: str):
    """The annotation of the DATA argument: input files or globs, several run as a batch.

    Parameters
    ----------
    what : str
        What the files hold (the help's first words).

    Returns
    -------
    typing.Annotated
        ``list[Path] | None`` with its typer.Argument.
    """
    return Annotated[
        list[Path] | None, typer.Argument(help=f"{what}; several files or globs run as a batch.", show_default=False)
    ]


def _limits(common: dict):
    """The reading limits the options ask for (None: the reader's defaults)."""
    given = {k: common.get(k) for k in ("max_megabytes", "max_cells", "max_columns", "max_cell_chars")}
    if all(v is None for v in given.values()):
        return None
    from ..io import ReadLimits

    kw = {
        "max_cells": given["max_cells"],
        "max_columns": given["max_columns"],
        "max_cell_chars": given["max_cell_chars"],
        "max_bytes": None if given["max_megabytes"] is None else given["max_megabytes"] * 2**20,
    }
    return ReadLimits(**{k: v for k, v in kw.items() if v is not None})


def sources(
    data: list[Path] | None,
    sample: bool,
    command: str,
    sheet: str | None = None,
    thousands: str | None = None,
    ignore_columns=None,
    limits=None,
) -> list:
    """Input files: the arguments with globs expanded (sorted), the bundled sample, or [None].

    As TableSources when a sheet, a thousands separator, columns to ignore or reading limits are given.

    Parameters
    ----------
    data : list of Path or None
        The DATA arguments (files or globs).
    sample : bool
        Run on the command's bundled sample.
    command : str
        The command's registry name.
    sheet : str, optional
        Sheet of a workbook (name or number from 1).
    thousands : str, optional
        Thousands separator.
    ignore_columns : sequence of str, optional
        Columns to leave out.
    limits : optional
        Reading limits (megabytes, cells, columns, cell characters).

    Returns
    -------
    list
        Paths (or TableSources), or ``[None]`` for a run from options only.

    Raises
    ------
    OptionError, InputError
        Both a file and --sample, no file where one is required, or a glob that matches nothing.
    """
    paths = _paths(data, sample, command)
    if sheet is None and thousands is None and not ignore_columns and limits is None:
        return paths
    from ..io import TableSource

    return [
        TableSource(p, sheet, thousands, tuple(ignore_columns or ()), limits) if p is not None else None for p in paths
    ]


def _paths(data: list[Path] | None, sample: bool, command: str) -> list:
    import glob

    from ..errors import InputError, OptionError, Problem
    from ..reductions import REDUCTIONS
    from ..samples import sample_path

    red = REDUCTIONS[command]
    if sample and data:
        raise OptionError("give a data file or --sample, not both")
    if sample:
        return [sample_path(red.sample)]
    if not data:
        if red.source == "required":
            raise OptionError(f"no data file given (try: capred {command} --sample)")
        return [None]
    out: list[Path] = []
    for p in data:
        p = Path(p)  # older typer/click pass list arguments as str
        text = str(p)
        if any(ch in text for ch in "*?[") and not p.exists():
            hits = sorted(glob.glob(text, recursive=True))
            if not hits:
                raise InputError(Problem(text, None, None, "no file matches this pattern"))
            out += [Path(h) for h in hits]
        else:
            out.append(p)
    return out


def default_out(command: str, source) -> Path:
    """Default output folder of one run: ``./capred_out/<prefix>_<input stem>`` (``options`` without input).

    Parameters
    ----------
    command : str
        The command's registry name.
    source : path or TableSource or None
        The run's input.

    Returns
    -------
    Path
    """
    from ..io import source_path
    from ..reductions import REDUCTIONS

    stem = Path(source_path(source)).stem if source is not None else "options"
    return Path.cwd() / "capred_out" / f"{REDUCTIONS[command].out_prefix}_{stem}"


def execute(inv: Invocation) -> None:
    """Run an invocation: one file (tables or JSON) or several (a batch).

    Parameters
    ----------
    inv : Invocation
        The parsed command.

    Raises
    ------
    typer.Exit
        With status 1 on a CapredError (message on stderr; with --json, the problems as JSON on stdout).
    """
    from ..errors import InputError

    try:
        if len(inv.sources) == 1:
            _single(inv)
        else:
            _batch(inv)
    except InputError as exc:
        hint = _looks_like(inv.command, inv.sources[0], len(exc.problems)) if len(inv.sources) == 1 else None
        if hint is not None:  # the one message that helps; every problem stays in the JSON
            problems = exc.problems
            exc = InputError(hint)
            exc.problems = [hint, *problems]
        if inv.json:  # scripts get every problem, as data
            from ..io import encode_json

            typer.echo(encode_json(exc.as_json()).decode("utf-8"), nl=False)
            raise typer.Exit(1) from None
        fail(exc)
    except CapredError as exc:
        fail(exc)


def _table_kinds() -> dict[str, str]:
    """What each command's input table is called, for "this looks like ..." (``Reduction.table_kind``)."""
    from ..reductions import REDUCTIONS

    return {name: red.table_kind for name, red in REDUCTIONS.items() if red.table_kind}


def _schema_of(command: str):
    """The columns the command reads from its table (the SCHEMA of its pipeline module), or None."""
    from importlib import import_module

    from ..reductions import REDUCTIONS

    red = REDUCTIONS.get(command)
    if red is None:
        return None
    return getattr(import_module(red.run_path.split(":")[0]), "SCHEMA", None)


def _looks_like(command: str, source, n_problems: int = 0):
    """A Problem saying which command to try when the failed table is clearly another command's input, else None.

    Clearly: its header names at least two more of that command's columns than of this one's, three it lacks.
    """
    from ..errors import Problem
    from ..io import TableSource, column_lookup, find_header, match_header, read_grid, source_path

    path = source_path(source)
    if path is None or hasattr(path, "to_csv"):
        return None
    try:
        grid = read_grid(source if isinstance(source, TableSource) else TableSource(path))
    except CapredError:
        return None
    candidates = list(grid.text_rows.values()) or [grid.rows]  # a CSV: the first rows split at each delimiter

    def named(schema) -> set[str]:
        lookup = column_lookup(schema)
        best: set[str] = set()
        for rows in candidates:
            if rows:
                k, _ = find_header(rows, lookup)
                cols = {c.name for c in (match_header(h, lookup)[0] for h in rows[k][1]) if c is not None}
                best = max(best, cols, key=len)
        return best

    own_schema = _schema_of(command)
    if own_schema is None:  # a command without a table schema of its own (bridges, calculators): no comparison
        return None
    own = named(own_schema)
    best, best_cols = None, own
    kinds = _table_kinds()
    for other in kinds:
        schema = _schema_of(other) if other != command else None
        if schema:
            cols = named(schema)
            if len(cols) >= len(best_cols) + 2 and len(cols - own) >= 3:
                best, best_cols = other, cols
    if best is None:
        return None
    shown = ", ".join(sorted(best_cols - own)[:6])
    more = f" ({n_problems:,} problems reading it as the input of capred {command}: --json lists them)"
    return Problem(
        str(path),
        None,
        None,
        f"this looks like {kinds[best]} (it has {shown}), not an input of capred {command}: "
        f"try capred {best} {path}" + (more if n_problems else ""),
    )


def _single(inv: Invocation) -> None:
    from ..io import check_target, encode_json
    from ..reductions import REDUCTIONS
    from ..report.outputs import write_outputs

    source = inv.sources[0]
    write = inv.out is not None or (not inv.json and REDUCTIONS[inv.command].files_by_default)
    out_dir = inv.out or default_out(inv.command, source)
    if write:  # before anything is computed
        from ..report.outputs import check_outputs_ahead

        check_target(out_dir, [source, *inv.extra_inputs])
        check_outputs_ahead(inv.command, source, inv.options, out_dir, inv.extra_inputs)
    import sys

    from ..io import run_limits
    from ..progress import showing

    with showing(not inv.json and sys.stderr.isatty()), run_limits(inv.limits):  # a table carries them too
        result = REDUCTIONS[inv.command].run(source, inv.options)
    o = inv.output
    unrecorded = None if write else _store_unrecorded(inv)
    if unrecorded is not None:
        from ..report.outputs import add_line

        add_line(result, "warnings", unrecorded)
    written = (
        write_outputs(
            result,
            out_dir,
            plots=inv.plots,
            formats=o.formats,
            dpi=o.dpi,
            html=o.html,
            csv_dialect=o.csv_dialect,
            xlsx=o.xlsx,
            panels=o.panels,
            figures=o.figures,
            store=o.store,
        )
        if write
        else None
    )
    if inv.json:
        from ..io import stream_json

        out = sys.stdout.buffer if hasattr(sys.stdout, "buffer") else None
        if out is None:  # a text-only stream (as in some test runners)
            typer.echo(encode_json(result.to_json()).decode("utf-8"), nl=False)
        else:
            stream_json(result.json_lazy(), out.write)
            out.flush()
        return
    from ..report.render import render

    render(result, out_dir, written)


def _store_unrecorded(inv: Invocation) -> str | None:
    """Why a run that writes no files is not recorded in the store it names (--store or $CAPRED_STORE), or None.

    A store keeps each run beside the folder of its files (its ``out_dir``; capred.lab_store.Recorder records
    the run once that folder is in place), so a run that only prints is not recorded; saying so is better than
    recording nothing in silence.
    """
    from ..lab_store import STORE_VARIABLE, store_from
    from ..reductions import REDUCTIONS

    store = store_from(inv.output.store)
    if store is None or inv.command == "history":
        return None
    given = f"--store {store}" if inv.output.store is not None else f"{STORE_VARIABLE}={store}"
    why = (
        "with --json and no --out it writes none"
        if REDUCTIONS[inv.command].files_by_default
        else f"`capred {inv.command}` writes them only with --out (it prints by default)"
    )
    return (
        f"this run was not recorded in the store: {given} records a run only when its files are written, and {why};"
        " give --out FOLDER to record it"
    )


def _batch(inv: Invocation) -> None:
    from .. import batch
    from ..reductions import REDUCTIONS

    write = inv.out is not None or (not inv.json and REDUCTIONS[inv.command].files_by_default)
    unrecorded = None if write else _store_unrecorded(inv)
    if unrecorded is not None:
        typer.echo(f"Warning: {unrecorded}", err=True)
    root = inv.out or Path.cwd() / "capred_out"
    dirs = batch.output_dirs([inv.command] * len(inv.sources), inv.sources, root)
    lines = file_command_lines(inv.command, inv.sources, [d if write else None for d in dirs])
    jobs = [
        batch.Job(
            inv.command,
            src,
            d if write else None,
            inv.options,
            inv.plots,
            keep_json=inv.json,
            output=inv.output,
            command_line=line,
        )
        for src, d, line in zip(inv.sources, dirs, lines)
    ]
    run_batch(jobs, root if write else None, inv.json, inv.workers, extra_inputs=inv.extra_inputs)


def file_command_lines(command: str, sources, out_dirs, argv=None, cmd=None) -> list:
    """The command line that reproduces each file's run of a batch alone: ``capred COMMAND FILE OPTIONS``.

    A batch ``capred shear k/*.csv --no-plots`` records in each file's provenance.json and report.html the run
    of that file (``capred shear k/a.csv --no-plots --out capred_out/a``), not the whole command line with every
    other file's path (which made each file's record grow with the batch); the batch root's provenance.json
    keeps the whole command line once. The options are the tokens of the command line that are not input
    arguments, as typed (an option's value is known from the command's declaration, so a value is never taken
    for an input), with ``--out`` naming the file's own folder and without ``--workers`` (one file).

    Parameters
    ----------
    command : str
        The command's name (``shear``, ``bridge solve``).
    sources : list of path
        The batch's input files, in order.
    out_dirs : list of (Path or None)
        Each file's output folder (None: nothing written).
    argv : list of str, optional
        The process's arguments (default ``sys.argv``).
    cmd : click.Command, optional
        The command that parses them (default: the command running now).

    Returns
    -------
    list of (str or None)
        One command line per source; None for every source where the arguments are not this command's
        (the library called outside the command line): the process's command line is recorded then.
    """
    import os
    import shlex
    import sys

    try:  # typer >= 0.2x carries its own click
        from typer._click.globals import get_current_context
    except ImportError:  # pragma: no cover - typer on the click package
        from click import get_current_context

    from ..io import source_path

    argv = list(sys.argv if argv is None else argv)
    if cmd is None:
        ctx = get_current_context(silent=True)
        cmd = ctx.command if ctx is not None else None
    words = command.split()
    start = next((i for i in range(1, len(argv)) if argv[i : i + len(words)] == words), None)
    if cmd is None or start is None:
        return [None] * len(sources)
    options = {}
    for p in cmd.params:
        if getattr(p, "param_type_name", "") == "option":
            for name in (*p.opts, *p.secondary_opts):
                options[name] = p
    kept: list[str] = []
    rest = argv[start + len(words) :]
    i, positional_only = 0, False
    while i < len(rest):
        tok = rest[i]
        i += 1
        if positional_only or tok == "-" or not tok.startswith("-"):
            continue  # an input argument
        if tok == "--":
            positional_only = True
            continue
        p = options.get(tok.split("=", 1)[0])
        takes = 0 if p is None or "=" in tok or p.is_flag or p.count else p.nargs
        if p is None or p.name not in ("out", "workers"):  # the file's own folder is named below
            kept += rest[i - 1 : i + takes]
        i += takes
    tail = "".join(" " + shlex.quote(t) for t in kept)
    head = "capred " + " ".join(words)
    cwd = os.getcwd()

    def shown(path) -> str:
        text = str(path)
        if os.path.isabs(text) and text.startswith(cwd + os.sep):  # under the working folder: as typed there
            text = text[len(cwd) + 1 :]
        return shlex.quote(text)

    return [
        None
        if src is None
        else f"{head} {shown(source_path(src))}{tail}" + (f" --out {shown(d)}" if d is not None else "")
        for src, d in zip(sources, out_dirs)
    ]


def run_batch(jobs, root: Path | None, json_out: bool, workers: int | None, extra_inputs=()) -> None:
    """Run jobs with a progress bar (on a terminal, not with --json), write index.csv, report, set the exit code.

    Parameters
    ----------
    jobs : list of capred.batch.Job
        The runs.
    root : Path or None
        Batch output folder (None: nothing written, --json only).
    json_out : bool
        Print one JSON document on stdout instead of the table.
    workers : int or None
        Worker processes (None: one per core, at most one per job).
    extra_inputs : sequence of path, optional
        Further inputs the batch root must not replace (the manifest).

    Raises
    ------
    typer.Exit
        130 when interrupted, 1 when a run failed.
    """
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    from .. import batch
    from ..io import check_target, encode_json

    if root is not None:
        check_target(root, [j.source for j in jobs] + list(extra_inputs), replace=False)
    err = Console(stderr=True)
    show = err.is_terminal and not json_out
    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
        console=err,
        disable=not show,
        transient=True,
    ) as progress:
        task = progress.add_task(f"capred: {len(jobs)} files", total=len(jobs))
        outcomes, interrupted = batch.run_all(jobs, workers, on_done=lambda o: progress.advance(task))
    season = batch.write_season(root, outcomes) if root is not None else []
    index = batch.write_index(root, outcomes, season) if root is not None else None  # lists every batch file
    bad = [o for o in outcomes if o.status in ("failed", "crashed")]
    if json_out:  # the document's keys are the fields of its records (capred.batch.BatchDocument)
        doc = batch.BatchDocument.of(outcomes, index, root is not None).to_json()
        typer.echo(encode_json(doc).decode("utf-8"), nl=False)
    else:
        _outcome_table(outcomes, index)
    for o in bad:
        typer.echo(f"Error: {o.message}", err=True)
    if interrupted:
        typer.echo("Interrupted: the files not yet reduced are marked 'interrupted' in index.csv", err=True)
        raise typer.Exit(130)
    if bad:
        raise typer.Exit(1)


def _outcome_table(outcomes, index) -> None:
    from rich.console import Console

    from ..report.render import render_tables
    from ..result import TableSpec

    done = sum(o.ok for o in outcomes)
    spec = TableSpec(
        f"{done} of {len(outcomes)} files reduced",
        [("input", "left"), ("command", "left"), ("status", "left"), ("output / error", "left")],
    )
    for o in outcomes:
        spec.rows.append([o.source, o.command, o.status, o.out_dir if o.ok else o.message.splitlines()[0]])
    con = Console()
    render_tables([spec], con)
    if index is not None:
        print(f"Index of all outputs: {index}", file=con.file)
