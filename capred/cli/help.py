"""`capred COMMAND --help` in groups.

The command's own options, its input, its outputs, then its input columns (or, for a command whose input is not a table,
what that input is: the reduction's ``input_description``).

Help stays plain text (rendering it through rich would double the start-up time of `capred --help`); the
groups are typer's ``rich_help_panel`` of each parameter where one is set, else the panel of the shared option
(``INPUT_OPTIONS``, ``OUTPUT_OPTIONS``), else the command's own panel. The input columns are read from the
command's schema (the ``Column`` list its pipeline reads the table with: names, units, descriptions and the
aliases of the glossary).

A command's help must stay cheap (no numpy, pandas or matplotlib), so the schema is read from where the command
declares it: the module of its Options class (``Reduction.options_path``), a numpy-free module of capred.spec,
at run time (nothing is generated or cached). An option whose help lists a registry (``--models``) is rendered
again when the help is shown (capred.cli.declare.live_help), so an entry registered by a script shows.
"""

from __future__ import annotations

import contextlib

import typer.core

try:  # typer >= 0.2x carries its own click
    from typer._click import _textwrap
    from typer._click import formatting as _formatting
    from typer._click.core import Context as _Context
except ImportError:  # typer on the click package (its floor, 0.16)
    from click import _textwrap
    from click import formatting as _formatting
    from click.core import Context as _Context

from .declare import fill_help_fields, live_help, param_metavar

#: the shared options about what is read (declared once in capred.cli.common)
INPUT_OPTIONS = (
    "sample",
    "sheet",
    "thousands",
    "ignore_column",
    "max_megabytes",
    "max_cells",
    "max_columns",
    "workers",
)
#: the shared options about what is written
OUTPUT_OPTIONS = ("out", "json_out", "plots", "formats", "dpi", "html", "csv_dialect", "xlsx", "panels", "figures")
INPUT_PANEL = "Input"
OUTPUT_PANEL = "Output"


def panel_of(param, own: str) -> str:
    """The help group of one click parameter.

    Its ``rich_help_panel``, else Input / Output for the shared options, else ``own`` (the command's options).

    Parameters
    ----------
    param : click.Parameter
        An option or argument of the command.
    own : str
        Title of the command's own options panel.

    Returns
    -------
    str
        The panel's title.
    """
    explicit = getattr(param, "rich_help_panel", None)
    if explicit:
        return explicit
    if param.name in INPUT_OPTIONS:
        return INPUT_PANEL
    if param.name in OUTPUT_OPTIONS or param.name == "help":
        return OUTPUT_PANEL if param.name != "help" else "Help"
    return own


def schema_of(command: str) -> list:
    """The input columns (capred.spec.columns.Column) a command reads; [] when none.

    The ``SCHEMA`` of the module that declares its options (a capred.spec module), or ``<LAST WORD>_SCHEMA`` for a
    command of a group (``bridge solve`` -> ``SOLVE_SCHEMA``).

    Parameters
    ----------
    command : str
        The command's registry name.

    Returns
    -------
    list of Column
    """
    from importlib import import_module

    from ..reductions import REDUCTIONS

    red = REDUCTIONS.get(command)
    if red is None or red.source == "none":
        return []
    module = import_module(red.options_path.split(":")[0])
    last = command.split()[-1].replace("-", "_").upper()
    for name in (f"{last}_SCHEMA", "SCHEMA"):
        schema = getattr(module, name, None)
        if isinstance(schema, list) and schema:
            return schema
    return []


def input_description(command: str) -> str:
    """What a command reads when it is not a table of columns (a fits.json, a lab store).

    Parameters
    ----------
    command : str
        The command's name as the CLI spells it (``"history"``, ``"bridge laws"``).

    Returns
    -------
    str
        The ``input_description`` of its reduction; "" when none.
    """
    from ..reductions import REDUCTIONS

    red = REDUCTIONS.get(command)
    return red.input_description if red is not None else ""


#: the help section of a command whose input is not a table (in place of the input columns)
INPUT_FILE_SECTION = "Input file (not a table)"


def column_lines(schema: list) -> list[tuple[str, str]]:
    """(``name [unit]``, description with its other accepted spellings) of each input column.

    Parameters
    ----------
    schema : list of Column
        Input columns (capred.io.table.Column).

    Returns
    -------
    list of tuple of str
    """
    out = []
    for c in schema:
        head = c.name + (f" [{c.unit}]" if c.unit and c.unit != "-" else "")
        text = c.description
        if c.choices:
            text += f" ({'|'.join(c.choices)})"
        if c.aliases:
            text += "; also: " + ", ".join(c.aliases)
        out.append((head, text))
    return out


@contextlib.contextmanager
def _unbroken_hyphens():
    """Wrap help text without breaking a word at its hyphens (``--reference-stress``, ``bounding-surface``).

    click's wrapper breaks lines after a hyphen, so an option named in prose read ``--reference-`` / ``stress``
    and could not be copied; here its ``wrap_text`` builds its wrapper with ``break_on_hyphens=False`` (the
    rest of its paragraph handling as it is), for the help being written only.
    """
    plain = _textwrap.TextWrapper

    class Unbroken(plain):
        def __init__(self, *args, **kwargs):
            kwargs.setdefault("break_on_hyphens", False)
            super().__init__(*args, **kwargs)

    _textwrap.TextWrapper = Unbroken
    try:
        yield
    finally:
        _textwrap.TextWrapper = plain


class HelpFormatter(_formatting.HelpFormatter):
    """click's help formatter, wrapping lines between words only (never at a word's hyphen)."""

    def write_usage(self, prog: str, args: str = "", prefix: str | None = None) -> None:
        """Click's usage line, wrapped between words (see `_unbroken_hyphens`)."""
        with _unbroken_hyphens():
            super().write_usage(prog, args, prefix)

    def write_text(self, text: str) -> None:
        """Click's paragraph, wrapped between words (see `_unbroken_hyphens`)."""
        with _unbroken_hyphens():
            super().write_text(text)

    def write_dl(self, rows, col_max: int = 30, col_spacing: int = 2) -> None:
        """Click's definition list, its help column wrapped between words (see `_unbroken_hyphens`)."""
        with _unbroken_hyphens():
            super().write_dl(rows, col_max, col_spacing)


class HelpContext(_Context):
    """The context of capred's commands and groups: their help written by `HelpFormatter`."""

    formatter_class = HelpFormatter


def help_record(param, ctx) -> tuple[str, str] | None:
    """One parameter's line of ``--help``, its value shown in capred's one vocabulary.

    The metavar is the one rule of capred.cli.declare (`param_metavar`: INTEGER, NUMBER, FILE, PATH, TEXT),
    never a Python type (``<list[Path]>``); the range of an option declared with ``min``/``max`` is not
    repeated in click's words (``[x>=1]``): the help text states it (``[>= 1]``), added where it does not.

    Parameters
    ----------
    param : click.Parameter
        An option or argument of the command.
    ctx : click.Context
        The command's context.

    Returns
    -------
    tuple of str or None
        (name and metavar, help), or None for a hidden parameter.
    """
    shown = param_metavar(param)
    if shown is not None:
        param.metavar = shown
    low, high = getattr(param, "min", None), getattr(param, "max", None)
    ranged = getattr(param, "type", None)  # typer on the click package (0.16): the range is the click type's
    if low is None and high is None and hasattr(ranged, "_describe_range"):
        low, high = getattr(ranged, "min", None), getattr(ranged, "max", None)
        ranged._describe_range = lambda: ""  # this parameter's own range type: stated in capred's words below
    if low is not None or high is not None:
        param._get_number_range_help_str = lambda: None  # stated in capred's words below
    rv = param.get_help_record(ctx)
    if rv is None:
        return None
    name, text = rv
    if param.param_type_name == "argument":  # its name is its metavar, "..." for several values
        name = (param.metavar or param.name) + ("..." if param.nargs != 1 else "")
    limits = " and ".join(
        x for x in (f">= {low}" if low is not None else "", f"<= {high}" if high is not None else "") if x
    )
    if limits and limits not in text:
        text = f"{text}  [{limits}]" if text else f"[{limits}]"
    return name, text


class HelpGroup(typer.core.TyperGroup):
    """A typer group (``capred``, ``capred bridge``) whose help is wrapped as its commands' is (`HelpFormatter`)."""

    context_class = HelpContext


class GroupedCommand(typer.core.TyperCommand):
    """A typer command whose plain-text help groups its options and lists the input columns."""

    context_class = HelpContext

    def format_usage(self, ctx, formatter) -> None:
        """The usage line, its arguments named by their metavar (``[FILE]...``, as the Arguments section names them).

        Parameters
        ----------
        ctx : click.Context
            The command's context.
        formatter : click.HelpFormatter
            The formatter written to.
        """
        for param in self.get_params(ctx):
            shown = param_metavar(param)
            if shown is not None:
                param.metavar = shown
        super().format_usage(ctx, formatter)

    def format_help_text(self, ctx, formatter) -> None:
        """The command's help text, its ``{laws}``-style fields filled in with the registries as they stand now.

        The fields are capred.cli.declare.HELP_FIELDS.

        Parameters
        ----------
        ctx : click.Context
            The command's context.
        formatter : click.HelpFormatter
            The formatter written to.
        """
        raw = self.__dict__.setdefault("_declared_help", self.help)
        if raw:
            self.help = fill_help_fields(raw)
        super().format_help_text(ctx, formatter)

    def format_options(self, ctx, formatter) -> None:
        """Write the arguments, the options panel by panel, then the input columns the command reads.

        The panels are the command's own, Input, Output and Help.

        Parameters
        ----------
        ctx : click.Context
            The command's context.
        formatter : click.HelpFormatter
            The formatter written to.
        """
        args, panels = [], {}
        own = f"{ctx.info_name or self.name} options"
        for param in self.get_params(ctx):
            if getattr(param, "help", None):
                param.help = live_help(param.help)  # a registry's entries as they stand now
            rv = help_record(param, ctx)
            if rv is None:
                continue
            if param.param_type_name == "argument":
                args.append(rv)
            else:
                panels.setdefault(panel_of(param, own), []).append(rv)
        if args:
            with formatter.section("Arguments"):
                formatter.write_dl(args)
        order = [own, INPUT_PANEL, OUTPUT_PANEL]
        for name in sorted(panels, key=lambda p: (order.index(p) if p in order else len(order), p == "Help")):
            with formatter.section(name):
                formatter.write_dl(panels[name])
        command = " ".join(ctx.command_path.split()[1:]) if ctx.command_path else self.name
        try:
            lines = column_help(command)
        except Exception:  # help never fails on a schema it cannot read  # pragma: no cover
            lines = []
        if lines:
            with formatter.section("Input columns (in any order; a header may declare its unit: 'name [unit]')"):
                formatter.write_dl(lines)
        elif input_description(command):
            with formatter.section(INPUT_FILE_SECTION):
                formatter.write_text(input_description(command))


def column_help(command: str) -> list[tuple[str, str]]:
    """The input-column lines of a command's help (:func:`column_lines` of :func:`schema_of`).

    Parameters
    ----------
    command : str
        The command's registry name (``shear``, ``bridge solve``).

    Returns
    -------
    list of tuple of str
        (``name [unit]``, description) per input column; [] for a command without a table of columns.
    """
    return column_lines(schema_of(command))


def group_help(app) -> None:
    """Give every command of ``app`` (and of its sub-apps: ``bridge``) the grouped help.

    A command that already has a class of its own (other than typer's default) keeps it.

    Parameters
    ----------
    app : typer.Typer
        The application; changed in place.
    """
    for info in app.registered_commands:
        if info.cls is None or info.cls is typer.core.TyperCommand:
            info.cls = GroupedCommand
    for group in app.registered_groups:
        if group.typer_instance is not None:
            group_help(group.typer_instance)
