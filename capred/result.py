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

This module holds the commands' Result (and names their Options base, declared in capred.spec.options); the
pieces below it live in their own modules and are named here too, so that ``from capred.result import ...`` keeps
working: capred.records (the records' mapping to JSON and tables), capred.user_units (a record's values in the
user's units), capred.spool (Rows, Spool), capred.csv_headers, capred.inputs, capred.table_spec. A Result
displays itself through capred.report (imported when a display method is called): this module sits above
report/ and io/, which import those lower modules, never this one.
"""

from __future__ import annotations

from .csv_headers import UNIT_SUFFIXES, csv_header, with_csv_headers
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
from .spec.options import Options, as_given
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
        """(paragraphs, reference keys) the run adds to its command's methods text (e.g. the models in force).

        Returns
        -------
        paragraphs : list of str
            Text added to the methods section.
        references : list of str
            Keys of capred.references.REFERENCES they cite.
        """
        return [], []

    def season_rows(self) -> list[dict]:
        """Rows of a batch's season.csv (per material: c, phi, their se, n, best model...); none by default.

        Returns
        -------
        list of dict
            One dict per season.csv row (empty by default).
        """
        return []

    def csv_tables(self) -> dict:
        """The tables the writer puts in CSV files: ``tables()`` by default.

        A large result may give plain column mappings (name -> array) instead, which write without pandas. Headers
        follow :func:`csv_header` (``name [unit]``).

        Returns
        -------
        dict
            File stem -> a DataFrame, a column mapping or a Spool, under ``name [unit]`` headers.
        """
        return {stem: with_csv_headers(table) for stem, table in self.tables().items()}

    def store_rows(self, material: str | None = None) -> list | None:
        """The rows the lab store records for the run (capred.lab_store), built from the records' declarations.

        capred.records.StoreRow: quantity, value, 95 % interval and unit of one declaration each, never by reading the
        JSON back. Every command declares its own (an empty list where it records none); None by default: a run of a
        command that declares none cannot be recorded (capred.lab_store.rows_of refuses it).

        Parameters
        ----------
        material : str, optional
            The material the inputs' metadata block names (for a run that does not name its materials).

        Returns
        -------
        list of capred.records.StoreRow or None
        """
        return None

    def extra_files(self) -> dict[str, bytes]:
        """Files of the command's own format written beside the tables (name -> bytes); none by default.

        Returns
        -------
        dict of str to bytes
            File name -> its content (empty by default).
        """
        return {}

    # --- display: capred.report presents every result; its one entry, report.notebook, is imported when a
    # display method is called (never when this module loads: result.py sits below report/) -------------
    def figures(self) -> dict:
        """The figure sheets of the run, {file stem: capred.report.sheets.Sheet} (nothing drawn yet).

        Returns
        -------
        dict of str to capred.report.sheets.Sheet
        """
        from .report.notebook import figures

        return figures(self)

    def console_tables(self) -> list[TableSpec]:
        """The summary tables of the run, as the console and report.html show them.

        Returns
        -------
        list of capred.table_spec.TableSpec
        """
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
        """Rows of the per-row table (a long result counts them without building it).

        Returns
        -------
        int
            0 for a result without tables.
        """
        return len(self.table()) if self.tables() else 0

    def all_warnings(self) -> list[str]:
        """Warnings of the run (implausible options and data), as JSON, console and report show them.

        Returns
        -------
        list of str
            Each warning once, in the order raised.
        """
        return list(dict.fromkeys(self.warnings))

    def all_notes(self) -> list[str]:
        """Notes of the run: how option units were read, then the command's own notes.

        Returns
        -------
        list of str
            Each note once, in that order.
        """
        unit_notes = self.options.unit_notes if self.options is not None else []
        return list(dict.fromkeys(unit_notes + list(self.notes)))

    def table(self):
        """The per-row table as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            The first of :meth:`tables`.
        """
        return next(iter(self.tables().values()))

    def header(self) -> dict:
        """The keys every command's document starts with.

        Returns
        -------
        dict
            ``command``, ``capred_version``, ``inputs``, ``options`` (SI values), ``option_units``, ``warnings`` and ``notes``.
        """
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
        """The JSON document with long row lists left as Rows (for streaming and summaries); cached.

        Returns
        -------
        dict
            JSON key -> value; long lists may be :class:`capred.spool.Rows`.
        """
        cached = self.__dict__.get("_json_lazy")
        if cached is None:
            cached = self.__dict__["_json_lazy"] = {**self.header(), **self.payload(lazy=True)}
        return cached

    def to_json(self) -> dict:
        """The JSON document of the run: the keys every command shares, then the command's own.

        Built once per result and cached: do not modify the returned dict.

        Returns
        -------
        dict
            The document ``--json`` prints, JSON key -> value.
        """
        cached = self.__dict__.get("_json_cache")
        if cached is None:
            cached = {k: (v.tolist() if isinstance(v, Rows) else v) for k, v in self.json_lazy().items()}
            self.__dict__["_json_cache"] = cached
        return cached
