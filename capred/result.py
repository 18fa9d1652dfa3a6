"""The reduction contract every capred command follows.

A command is one *reduction*: a schema for its input table, a pure
``run(source, options) -> Result`` and a Result that knows

- its tables (pandas DataFrames, one per output CSV; the first is ``table()``),
- its JSON document (``to_json()``, the same for the API, ``--json`` and the files),
- its figures (built only when asked for),
- its console tables (summaries for people; see capred.report.presenters),
- its options record (SI values with their unit names).

One writer (capred.io.writers.write_run) writes any Result, one renderer
(capred.report.render.render) prints any Result, one CLI path runs any
reduction on one file, many files or a manifest.

This module holds the command's Options base and its Result; the pieces below them live in their own modules
and are named here too, so that ``from capred.result import ...`` keeps working:
capred.records (the records' mapping to JSON and tables), capred.user_units (a record's values in the
user's units), capred.spool (Rows, Spool), capred.csv_headers, capred.inputs, capred.table_spec. A Result
displays itself through capred.report (imported when a display method is called): this module sits above
report/ and io/, which import those lower modules, never this one.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from .csv_headers import UNIT_SUFFIXES, csv_header, with_csv_headers
from .errors import OptionError
from .inputs import InputFile, input_file
from .nomenclature import unit_suffix
from .records import (
    Output,
    columns_of_rows,
    field_value,
    json_list,
    num,
    output,
    record_columns,
    record_json,
    record_json_columns,
    record_outputs,
    record_row,
    scale_value,
)
from .spool import Rows, Spool
from .table_spec import TableSpec
from .user_units import SIValues, user_units

__all__ = [
    "UNIT_SUFFIXES",
    "InputFile",
    "Options",
    "Output",
    "Result",
    "Rows",
    "SIValues",
    "Spool",
    "TableSpec",
    "as_given",
    "columns_of_rows",
    "csv_header",
    "field_value",
    "input_file",
    "json_list",
    "num",
    "output",
    "record_columns",
    "record_json",
    "record_json_columns",
    "record_outputs",
    "record_row",
    "scale_value",
    "unit_suffix",
    "user_units",
    "with_csv_headers",
]


class Options:
    """Base of every command's options dataclass.

    ``QUANTITIES`` maps a dimensional field to its nomenclature name. Such a
    field accepts a number in SI, a string with a unit (``"10 kN/m^3"``) or a
    pint Quantity, and holds SI after construction. Values are range checked;
    implausible constants give warnings (``self.warnings``).
    """

    QUANTITIES: dict[str, str] = {}
    #: command-line spelling of a field where it is not --field-name
    OPTION_NAMES: dict[str, str] = {}

    def option_name(self, field_name: str) -> str:
        """An option's name for messages: the Python keyword and the command-line option.

        Parameters
        ----------
        field_name : str
            The field of the options class, e.g. "gamma_w".

        Returns
        -------
        str
            E.g. ``"gamma_w (--gamma-w)"``.
        """
        cli = self.OPTION_NAMES.get(field_name, "--" + field_name.replace("_", "-"))
        return f"{field_name} ({cli})"

    def __post_init__(self) -> None:
        from .nomenclature import plausibility_warning
        from .units import to_si

        warnings: list[str] = []
        notes: list[str] = []
        for name, quantity in self.QUANTITIES.items():
            value = getattr(self, name)
            if value is None:
                continue
            where = self.option_name(name)
            try:
                si = to_si(value, quantity, where, notes)
            except OptionError as exc:  # quote the value as the API caller gave it, not its SI reading
                err = OptionError(as_given(str(exc), name, value, quantity))
                err.as_given = True  # quoted: a subclass's own quoting leaves it as it is
                raise err from None
            object.__setattr__(self, name, si)
            w = plausibility_warning(quantity, si, where)
            if w:
                warnings.append(w)
        object.__setattr__(self, "_warnings", warnings)
        object.__setattr__(self, "_notes", notes)

    @property
    def warnings(self) -> list[str]:
        """Implausible option values (e.g. a unit weight of water of 10 N/m^3)."""
        return list(getattr(self, "_warnings", []))

    @property
    def unit_notes(self) -> list[str]:
        """How option units were read (e.g. g/cm^2 as gram-force per cm^2)."""
        return list(getattr(self, "_notes", []))

    def record(self) -> tuple[dict, dict]:
        """(values, units): every option with its SI value, and the SI unit of the dimensional ones."""
        from .nomenclature import QUANTITIES
        from .units import SI_UNIT

        values, units = {}, {}
        for f in dataclasses.fields(self):
            if f.name.startswith("_"):
                continue
            v = getattr(self, f.name)
            values[f.name] = _plain(v)
            if f.name in self.QUANTITIES:
                units[f.name] = SI_UNIT[QUANTITIES[self.QUANTITIES[f.name]].kind].replace("**", "^")
        return values, units


def as_given(message: str, name: str, value, quantity: str) -> str:
    """An option's error message with its value quoted as the caller gave it (issue 28).

    The glossary's range check shows the SI reading in the output unit: ``box_area=-3`` (a plain number, read in
    m^2) reads "(got -30000 cm^2)", a value the caller never typed. The message keeps that reading beside the
    value as given, says which unit a plain number is read in and how to give one; a string is quoted as typed
    (with its reading where its unit is not the output unit).

    Parameters
    ----------
    message : str
        The message of capred.units.to_si, starting with the option's name.
    name : str
        The options field (the API keyword), e.g. "box_area".
    value : object
        The value as given.
    quantity : str
        Its glossary entry (a key of capred.nomenclature.QUANTITIES).

    Returns
    -------
    str
        E.g. ``"box_area (--box-area): shear box area must be > 0 cm^2 (got box_area=-3, a plain number read in
        m^2, that is -30000 cm^2; give a unit, e.g. box_area='-3 cm^2')"``.
    """
    import numbers
    import re

    from .nomenclature import QUANTITIES
    from .units import SI_UNIT

    q = QUANTITIES[quantity]
    m = re.search(r" \(got ([^()]*)\)$", message)
    reading = m.group(1) if m else None
    base = message[: m.start()] if m else message
    that = f", that is {reading}" if reading else ""
    if isinstance(value, str):
        if reading is not None and reading.replace(" ", "") == value.strip().replace(" ", ""):
            that = ""  # the reading is the value as typed
        return f"{base} (got {name}={value!r}{that})"
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        si = SI_UNIT[q.kind].replace("**", "^")
        if not math.isfinite(value) or q.unit in ("-", "", si):
            return f"{base} (got {name}={value!r})"
        return (
            f"{base} (got {name}={value!r}, a plain number read in {si}{that}; give a unit, "
            f"e.g. {name}='{value!r} {q.unit}')"
        )
    return f"{base} (got {value}{that})"  # a pint Quantity, as it prints


def _plain(v):
    """A JSON-ready copy of an option value (tuples as lists, dataclasses as dicts, paths as text)."""
    if dataclasses.is_dataclass(v):
        return {f.name: _plain(getattr(v, f.name)) for f in dataclasses.fields(v)}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, Path):
        return str(v)
    if isinstance(v, float) and not math.isfinite(v):
        return None  # as every JSON file writes it (null): the API's document equals the file's
    return v


class Result:
    """Base of every command's result.

    Subclasses set ``command``, the attributes ``inputs`` (list of InputFile),
    ``options`` (an Options), ``notes`` and ``warnings`` (lists of str), and
    implement ``payload()``, ``tables()``, ``console_tables()`` and, when they
    draw, ``figures()``.
    """

    command: str = ""
    json_name: str = "summary.json"

    # --- to implement -------------------------------------------------------------------------
    def payload(self, lazy: bool = False) -> dict:
        """The command's own result keys of the JSON document.

        With ``lazy``, long per-row lists may be Rows (made on demand).

        Parameters
        ----------
        lazy : bool, optional
            Allow :class:`Rows` in place of long lists (default False: plain lists).

        Returns
        -------
        dict
            JSON key -> value.
        """
        raise NotImplementedError

    def tables(self) -> dict[str, object]:
        """Output tables: file stem -> pandas DataFrame (first = the per-row table)."""
        raise NotImplementedError

    def method_notes(self) -> tuple[list[str], list[str]]:
        """(paragraphs, reference keys) the run adds to its command's methods text (e.g. the models in force)."""
        return [], []

    def season_rows(self) -> list[dict]:
        """Rows of a batch's season.csv (per material: c, phi, their se, n, best model...); none by default."""
        return []

    def csv_tables(self) -> dict:
        """The tables the writer puts in CSV files: ``tables()`` by default; a large result may give plain
        column mappings (name -> array) instead, which write without pandas. Headers follow
        :func:`csv_header` (``name [unit]``)."""
        return {stem: with_csv_headers(table) for stem, table in self.tables().items()}

    def quantity_units(self) -> dict[str, str]:
        """JSON key -> declared unit of the numbers of the document that no glossary quantity names (a fit's
        parameters, say); the lab store takes every unit from the declarations (capred.lab_store.declared_units
        and this), none from a key's spelling. None by default.

        Returns
        -------
        dict
            Key -> unit ("-" when dimensionless).
        """
        return {}

    def extra_files(self) -> dict[str, bytes]:
        """Files of the command's own format written beside the tables (name -> bytes); none by default."""
        return {}

    # --- display: capred.report presents every result; its one entry, report.notebook, is imported when a
    # display method is called (never when this module loads: result.py sits below report/) -------------
    def figures(self) -> dict:
        """The figure sheets of the run, {file stem: capred.report.sheets.Sheet} (nothing drawn yet)."""
        from .report.notebook import figures

        return figures(self)

    def console_tables(self) -> list[TableSpec]:
        """The summary tables of the run, as the console and report.html show them."""
        from .report.notebook import console_tables

        return console_tables(self)

    def plot(self, name: str | None = None):
        """Draw the run's figures without writing files.

        Parameters
        ----------
        name : str, optional
            One sheet (a key of ``figures()``, e.g. ``"report_sand"``); all sheets when omitted.

        Returns
        -------
        matplotlib.figure.Figure or dict of str to Figure
            The named sheet, or every sheet by name (a dict that a notebook shows sheet by sheet); in a
            Jupyter kernel each Figure displays as a PNG image.
        """
        from .report.notebook import plot

        return plot(self, name)

    def _repr_html_(self) -> str:
        """Notebook display: a compact summary (key tables, one small figure, under 30 KB)."""
        from .report.notebook import repr_html

        return repr_html(self)

    def report_html(self) -> str:
        """The full report of the run (report.html, figures inlined) as an HTML string; nothing is written.

        Returns
        -------
        str
            A self-contained HTML document; in a notebook ``IPython.display.HTML(result.report_html())``.
        """
        from .report.notebook import report_html

        return report_html(self)

    def __repr__(self) -> str:
        inputs = (
            ", ".join(i.path.replace("\\", "/").rsplit("/", 1)[-1] for i in getattr(self, "inputs", [])) or "options"
        )
        n = self.row_count()
        w = len(self.all_warnings())
        return (
            f"<capred {self.command} result: {inputs}; {n} rows"
            + (f"; {w} warning{'s' if w != 1 else ''}" if w else "")
            + ">"
        )

    # --- shared -------------------------------------------------------------------------------
    def row_count(self) -> int:
        """Rows of the per-row table (a long result counts them without building it)."""
        return len(self.table()) if self.tables() else 0

    def all_warnings(self) -> list[str]:
        """Warnings of the run (implausible options and data), as JSON, console and report show them."""
        return list(dict.fromkeys(self.warnings))

    def all_notes(self) -> list[str]:
        """Notes of the run: how option units were read, then the command's own notes."""
        unit_notes = self.options.unit_notes if self.options is not None else []
        return list(dict.fromkeys(unit_notes + list(self.notes)))

    def table(self):
        """The per-row table as a pandas DataFrame."""
        return next(iter(self.tables().values()))

    def header(self) -> dict:
        """The keys every command's document starts with."""
        from . import __version__

        values, units = self.options.record() if self.options is not None else ({}, {})
        return {
            "command": self.command,
            "capred_version": __version__,
            "inputs": [i.as_dict() for i in self.inputs],
            "options": values,
            "option_units": units,
            "warnings": self.all_warnings(),
            "notes": self.all_notes(),
        }

    def json_lazy(self) -> dict:
        """The JSON document with long row lists left as Rows (for streaming and summaries); cached."""
        cached = self.__dict__.get("_json_lazy")
        if cached is None:
            cached = self.__dict__["_json_lazy"] = {**self.header(), **self.payload(lazy=True)}
        return cached

    def to_json(self) -> dict:
        """The JSON document of the run: the keys every command shares, then the command's own.

        Built once per result and cached: do not modify the returned dict.
        """
        cached = self.__dict__.get("_json_cache")
        if cached is None:
            cached = {k: (v.tolist() if isinstance(v, Rows) else v) for k, v in self.json_lazy().items()}
            self.__dict__["_json_cache"] = cached
        return cached
