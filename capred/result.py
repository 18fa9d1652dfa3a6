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
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from .spec.options import Options, as_given  # noqa: F401 (re-exported: capred.result.Options)


@dataclass(frozen=True)
class InputFile:
    """One input of a run: its path as given and the SHA-256 of its bytes."""

    path: str
    sha256: str | None
    sheet: str | None = None
    metadata: tuple = ()  # (key, value) pairs of the metadata block above the header

    def as_dict(self) -> dict:
        """The input as the JSON document and provenance.json record it: path, sha256, and sheet and metadata when present.

        Returns
        -------
        dict
        """
        out = {"path": self.path, "sha256": self.sha256}
        if self.sheet is not None:
            out["sheet"] = self.sheet
        if self.metadata:
            out["metadata"] = dict(self.metadata)
        return out


def input_file(source, table=None) -> InputFile:
    """InputFile of a path, a TableSource or a DataFrame (hash of its CSV text); with the sheet and the
    metadata block of the ``table`` read from it.

    Parameters
    ----------
    source : str, pathlib.Path, TableSource or pandas.DataFrame
        The input as the caller gave it.
    table : capred.io.table.Table or None, optional
        The table read from it, for its sheet and metadata block.

    Returns
    -------
    InputFile
        Path (``"<DataFrame>"`` for a DataFrame) and SHA-256 of the bytes read.
    """
    import dataclasses
    import hashlib

    path = getattr(source, "path", source) if not hasattr(source, "to_csv") else source
    if table is not None and (table.sheet is not None or table.metadata):
        base = input_file(path)
        return dataclasses.replace(base, sheet=table.sheet, metadata=tuple(table.metadata.items()))
    source = path
    if hasattr(source, "to_csv"):
        return InputFile("<DataFrame>", hashlib.sha256(source.to_csv(index=False).encode()).hexdigest())
    p = Path(source)
    if not p.is_file():
        return InputFile(str(source), None)
    h = hashlib.sha256()
    with open(p, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return InputFile(str(source), h.hexdigest())


@dataclass
class TableSpec:
    """A console table: title, column headers with alignment, rows of text.

    ``total_rows`` is the row count of the full table when only the first rows
    are shown; ``full_table`` names the output file that holds them all.
    """

    title: str
    columns: list[tuple[str, str]]  # (header, "left" | "right")
    rows: list[list[str]] = field(default_factory=list)
    total_rows: int | None = None
    full_table: str | None = None
    bold_rows: set[int] = field(default_factory=set)
    sections: set[int] = field(default_factory=set)  # rows after which a rule is drawn


# --- records: typed results and their one mapping to JSON keys and table columns -------------------
@dataclass(frozen=True)
class Output:
    """How one field of a record appears in the outputs.

    ``json`` and ``column`` are patterns: ``{model}`` is replaced by a model's
    name and ``{level}`` by the confidence level in percent (95). A field of a
    model-indexed record appears in the JSON rows as ``{json: {model: value}}``
    and in tables as one column per model. ``unit`` is the output unit shown
    in the column header ("" for a dimensionless value) and ``scale`` turns the
    SI value into it. ``pair`` fields hold (low, high) arrays: a JSON list
    ``[low, high]`` and two columns ``<column>_low``/``<column>_high`` (or the
    two ``column`` patterns given as a tuple).
    """

    json: str | None
    column: str | tuple[str, str] | None
    unit: str = ""
    scale: float = 1.0
    pair: bool = False


def output(json: str | None, column=None, unit: str = "", scale: float = 1.0, pair: bool = False):
    """Field metadata of a record attribute (see Output); use as ``x: np.ndarray = output(...)``.

    Parameters
    ----------
    json : str or None
        Key pattern in the JSON rows (``{model}``, ``{level}`` replaced); None: not in the JSON.
    column : str, tuple of str or None, optional
        Column header pattern in the tables; None: not in the tables.
    unit : str, optional
        Output unit shown in the header, e.g. "kPa" ("" for dimensionless).
    scale : float, optional
        Factor from the SI value to ``unit`` (1000 Pa -> 1 kPa: 1e-3).
    pair : bool, optional
        The field holds (low, high) arrays.

    Returns
    -------
    dataclasses.Field
        A field defaulting to None, with the :class:`Output` in its metadata.
    """
    return field(default=None, metadata={"output": Output(json, column, unit, scale, pair)})


def record_outputs(record) -> list[tuple[str, Output, object]]:
    """(field name, Output, value) of every output field of a record, in declaration order.

    Parameters
    ----------
    record : dataclass instance
        A typed record whose fields were declared with :func:`output`.

    Returns
    -------
    list of tuple
        Fields that are None are left out.
    """
    return [
        (f.name, f.metadata["output"], field_value(record, f.name))
        for f in dataclasses.fields(record)
        if "output" in f.metadata and field_value(record, f.name) is not None
    ]


def field_value(record, name: str):
    """The stored value of a record's field, as the pipeline put it there (SI for a field with a ``scale``).

    Reads past a renamed attribute's deprecation (see :func:`user_units`): capred's own writers use it, a
    lab script reads the attribute in the output unit instead (``rec.tau_kPa``).

    Parameters
    ----------
    record : dataclass instance
        A typed record.
    name : str
        One of its field names.

    Returns
    -------
    object
        The field's value.
    """
    try:
        return vars(record)[name]
    except (KeyError, TypeError):
        return getattr(record, name)


def unit_suffix(unit: str) -> str:
    """The Python-name form of an output unit: ``kPa`` -> ``kPa``, ``1/kPa`` -> ``per_kPa``, ``cm^3`` -> ``cm3``.

    Parameters
    ----------
    unit : str
        An output unit as headers show it.

    Returns
    -------
    str
        The suffix of the attribute that holds a value in that unit (``tau_kPa``).
    """
    s = unit.replace("1/", "per_").replace("/", "_per_").replace("^", "").replace(" ", "")
    return s.replace("%", "pct").replace("°", "deg")


def scale_value(value, scale: float):
    """A field's value times ``scale``: arrays, (low, high) pairs and sampled columns alike (None stays None).

    Parameters
    ----------
    value : ndarray, tuple of ndarray, object with ``scaled(factor)`` or None
        A record field's value.
    scale : float
        Factor from the stored unit to the output unit.

    Returns
    -------
    object
        The value in the output unit, of the same kind.
    """
    import numpy as np

    if value is None:
        return None
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value) * scale  # a scalar record (ModelMetrics.rmse_kPa) stays a Python float
    if isinstance(value, tuple):
        return tuple(scale_value(v, scale) for v in value)
    if hasattr(value, "scaled"):
        return value.scaled(scale)
    return np.asarray(value, dtype=float) * scale


class _RenamedField:
    """The old attribute of a field stored in SI: reads warn (capred.parameters.deprecated) and give the SI value.

    A data descriptor, so that the dataclass's ``__init__`` stores through it and ``dataclasses.replace`` (which
    reads every field) stays silent.
    """

    def __init__(self, name: str, new: str, unit: str):
        self.name, self.new, self.unit = name, new, unit

    def __get__(self, obj, cls=None):
        if obj is None:
            return self
        import sys

        value = obj.__dict__.get(self.name)
        if sys._getframe(1).f_code.co_filename == dataclasses.__file__:
            return value
        from .parameters import deprecated

        owner = type(obj).__name__
        si = {"kPa": "Pa", "MPa": "Pa", "mm": "m", "1/kPa": "1/Pa", "kPa^2": "Pa^2"}.get(self.unit, "SI")
        return deprecated(f"{owner}.{self.name} [{si}]", f"{owner}.{self.new} [{self.unit}]", value)

    def __set__(self, obj, value):
        obj.__dict__[self.name] = value


class SIValues:
    """The SI values of a record's fields, read without deprecation warnings: ``rec.si.tau`` [Pa].

    For code that hands a record's values to capred.physics (which works in SI). A lab script reads the
    attributes in the JSON's units (``rec.tau_kPa``).

    Parameters
    ----------
    record : dataclass instance
        A record decorated with :func:`user_units`.
    """

    def __init__(self, record):
        object.__setattr__(self, "_record", record)

    def __getattr__(self, name: str):
        try:
            return vars(self._record)[name]
        except KeyError:
            raise AttributeError(f"{type(self._record).__name__} has no field {name!r}") from None

    def __repr__(self) -> str:
        return f"<SI values of {type(self._record).__name__}: {', '.join(vars(self._record))}>"


def user_units(cls):
    """Class decorator: a record whose fields hold SI values offers each one in its output unit.

    For every output field with a unit and a scale (``output("sigma_cap_kPa", ..., "kPa", 1e-3)``) the record
    gains the attribute ``<field>_<unit>`` (``sigma_cap_kPa``) in the unit of the JSON and console, derived from
    the one declaration; the field's own name keeps its SI value for one release and raises a
    DeprecationWarning naming the new attribute (README, "Renamed in this release"). ``rec.si.<field>`` reads
    the SI value without a warning (for code that calls capred.physics). Apply above ``@dataclass``.

    Parameters
    ----------
    cls : type
        A dataclass whose fields were declared with :func:`output`.

    Returns
    -------
    type
        ``cls``, with the new attributes, a ``si`` view and a short ``repr``.
    """
    renamed = {}
    for f in dataclasses.fields(cls):
        spec = f.metadata.get("output")
        if spec is None or spec.scale == 1.0 or not spec.unit:
            continue
        new = f"{f.name}_{unit_suffix(spec.unit)}"
        renamed[f.name] = new
        setattr(cls, f.name, _RenamedField(f.name, new, spec.unit))

        def getter(self, _name=f.name, _scale=spec.scale):
            return scale_value(self.__dict__.get(_name), _scale)

        getter.__doc__ = f"``{f.name}`` in [{spec.unit}], the unit of the JSON and console (None if not computed)."
        setattr(cls, new, property(getter, doc=getter.__doc__))
    cls.RENAMED = renamed

    def si(self):
        return SIValues(self)

    si.__doc__ = "The fields' SI values, read without deprecation warnings (:class:`capred.result.SIValues`)."
    cls.si = property(si, doc=si.__doc__)

    def __repr__(self):
        head = [f"{k}={v!r}" for k, v in vars(self).items() if isinstance(v, str)]
        shown = []
        for k, v in vars(self).items():
            if v is None or isinstance(v, str):
                continue
            if isinstance(v, (int, float)):  # a scalar: its value in the output unit
                shown.append(f"{renamed.get(k, k)}={getattr(self, renamed.get(k, k))!r}")
            else:
                shown.append(renamed.get(k, k))
        return f"{cls.__name__}({', '.join(head + shown)})"

    cls.__repr__ = __repr__
    return cls


def record_json(record, level: str = "95") -> dict:
    """The JSON object of a record of scalars (one value per field): ``{key: value}`` in output units.

    Keys and units come from each field's :func:`output` declaration, as for per-row records
    (:func:`record_json_columns`); a value that is not finite is None (JSON null).

    Parameters
    ----------
    record : dataclass instance
        A typed record whose output fields hold numbers (``ModelMetrics``).
    level : str, optional
        Confidence level in percent, put into the ``{level}`` patterns (default "95").

    Returns
    -------
    dict
        JSON key -> number (or None), in the declared unit.
    """
    out = {}
    for _, spec, value in record_outputs(record):
        if spec.json is not None:
            out[spec.json.format(level=level)] = _scalar_out(value, spec.scale)
    return out


def record_row(record, level: str = "95") -> dict:
    """One table row of a record of scalars: ``{"name [unit]": value}`` in output units.

    Headers come from each field's :func:`output` declaration, as :func:`record_columns` makes them
    (``rmse [kPa]``, ``n [-]``).

    Parameters
    ----------
    record : dataclass instance
        A typed record whose output fields hold numbers.
    level : str, optional
        Confidence level in percent, put into the ``{level}`` patterns (default "95").

    Returns
    -------
    dict
        Header -> number (or None where not finite).
    """
    out = {}
    for _, spec, value in record_outputs(record):
        if spec.column is not None and not spec.pair:
            out[f"{spec.column.format(level=level)} [{spec.unit or '-'}]"] = _scalar_out(value, spec.scale)
    return out


def _scalar_out(value, scale: float):
    """A scalar field's value for JSON and tables: a count stays an int, a number is scaled (None if not finite)."""
    import numpy as np

    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        return value
    if isinstance(value, (int, np.integer)) and scale == 1.0:
        return int(value)
    return num(float(value) * scale)


def _scaled(values, scale: float):
    import numpy as np

    a = np.asarray(values, dtype=float)
    return a * scale if scale != 1.0 else a


def record_columns(records: dict, level: str = "95") -> dict:
    """Table columns of records, ``{header: array}``.

    ``records`` maps a model name to its record (model-indexed records) or
    ``None`` to a single record. Columns come field by field, models inner.

    Parameters
    ----------
    records : dict
        Model name (or None) -> record.
    level : str, optional
        Confidence level in percent, put into the ``{level}`` patterns (default "95").

    Returns
    -------
    dict
        Header (with unit) -> array in output units.
    """
    out: dict = {}
    first = next(iter(records.values()), None)
    if first is None:
        return out
    for name, spec, _ in record_outputs(first):
        if spec.column is None:
            continue
        for model, rec in records.items():
            value = field_value(rec, name)
            if value is None:
                continue
            names = (
                spec.column
                if isinstance(spec.column, tuple)
                else ((spec.column + "_low", spec.column + "_high") if spec.pair else (spec.column,))
            )
            parts = value if spec.pair else (value,)
            for pattern, part in zip(names, parts):
                head = pattern.format(model=model, level=level)
                out[f"{head} [{spec.unit or '-'}]"] = _scaled(part, spec.scale)
    return out


def record_json_columns(records: dict, start: int, stop: int, level: str = "95") -> dict:
    """Per-row JSON values of records for rows start..stop-1: ``{key: list}``; a model-indexed field gives a
    list of ``{model: value}`` dicts, a pair a list of ``[low, high]``.

    Parameters
    ----------
    records : dict
        Model name (or None) -> record.
    start, stop : int
        The rows, ``start`` included, ``stop`` excluded.
    level : str, optional
        Confidence level in percent, put into the ``{level}`` patterns (default "95").

    Returns
    -------
    dict
        JSON key -> list of per-row values in output units (None where not finite).
    """
    out: dict = {}
    first = next(iter(records.values()), None)
    if first is None:
        return out
    sl = slice(start, stop)
    for name, spec, _ in record_outputs(first):
        if spec.json is None:
            continue
        key = spec.json.format(level=level)
        per_model = {}
        for model, rec in records.items():
            value = field_value(rec, name)
            if value is None:
                continue
            if spec.pair:
                lo, hi = (json_list(_scaled(v[sl], spec.scale)) for v in value)
                per_model[model] = [list(p) for p in zip(lo, hi)]
            else:
                per_model[model] = json_list(_scaled(value[sl], spec.scale))
        if not per_model:
            continue
        if None in records:  # a single record
            out[key] = per_model[None]
        else:
            models = list(per_model)
            out[key] = [dict(zip(models, vals)) for vals in zip(*(per_model[m] for m in models))]
    return out


class Rows:
    """A long list of JSON rows made on demand, ``size`` at a time.

    A large result (100,000 shear tests, bridges) puts its per-row list in
    the document as Rows, so the writer can stream it to disk without ever
    holding every row's dict; ``to_json()`` turns it into a plain list.
    """

    #: True when the rows' JSON text is already written (the writer then only copies it, in its own process)
    written_ahead = False

    def __init__(self, n: int, make: Callable[[int, int], list]):
        self.n = n
        self.make = make  # (start, stop) -> list of rows

    def chunks(self, size: int = 2000):
        """The rows, ``size`` at a time (the last chunk may be shorter).

        Parameters
        ----------
        size : int, optional
            Rows per chunk (default 2000).

        Yields
        ------
        list of dict
            The rows of one chunk.
        """
        for start in range(0, self.n, size):
            yield self.make(start, min(self.n, start + size))

    def tolist(self) -> list:
        """Every row at once, as a plain list.

        Returns
        -------
        list of dict
        """
        return self.make(0, self.n)


class Spool:
    """Per-row output columns of a long run, kept block by block in a temporary file instead of in memory.

    A command whose rows are independent (``bridge solve``) appends each
    block's columns (a dict of arrays) as it computes them; the writer reads
    them back one block at a time (``blocks()``), also from a forked process
    (reads use ``os.pread``: no shared file offset). Peak memory is then one
    block's, whatever the number of rows.
    """

    def __init__(self) -> None:
        import tempfile
        import weakref

        self._file = tempfile.TemporaryFile()
        self._closer = weakref.finalize(self, self._file.close)  # the file goes with the spool
        self._index: list[tuple[int, int, int]] = []  # (offset, bytes, rows) of each block
        self._end = 0
        self._cached: tuple[int, dict] | None = None  # the block read last (rows_range reads many slices of it)
        self.n = 0

    def append(self, columns: dict) -> None:
        """Add one block: every column an array of the same length.

        Parameters
        ----------
        columns : dict
            Column name -> array; every block has the same columns.
        """
        import pickle

        data = pickle.dumps(columns, protocol=pickle.HIGHEST_PROTOCOL)
        self._file.seek(self._end)
        self._file.write(data)
        self._file.flush()
        rows = len(next(iter(columns.values()))) if columns else 0
        self._index.append((self._end, len(data), rows))
        self._end += len(data)
        self.n += rows

    def block(self, k: int) -> dict:
        """The columns of block ``k`` (the last block read is kept: reading it again costs nothing).

        Parameters
        ----------
        k : int
            Index of the block, from 0.

        Returns
        -------
        dict
            Column name -> array.
        """
        return self._block(k)

    def _block(self, k: int) -> dict:
        import os
        import pickle

        if self._cached is not None and self._cached[0] == k:
            return self._cached[1]
        offset, size, _ = self._index[k]
        block = pickle.loads(os.pread(self._file.fileno(), size, offset))
        self._cached = (k, block)
        return block

    def blocks(self):
        """The blocks' column dicts, in order."""
        for k in range(len(self._index)):
            yield self._block(k)

    def columns(self, start: int, stop: int) -> dict:
        """Every column of rows ``start`` .. ``stop - 1`` (possibly across blocks).

        Parameters
        ----------
        start, stop : int
            The rows, ``start`` included, ``stop`` excluded.

        Returns
        -------
        dict
            Column name -> array.
        """
        import numpy as np

        parts, first = [], 0
        for k, (_, _, rows) in enumerate(self._index):
            lo, hi = max(start, first), min(stop, first + rows)
            if lo < hi:
                block = self._block(k)
                parts.append({name: v[lo - first : hi - first] for name, v in block.items()})
            first += rows
            if first >= stop:
                break
        if len(parts) == 1:
            return parts[0]
        names = list(self._block(0)) if self._index else []
        return {name: np.concatenate([p[name] for p in parts]) if parts else np.empty(0) for name in names}

    def close(self) -> None:
        """Close the spool's temporary file (an unnamed file: closing it frees its disk space)."""
        self._closer()


def columns_of_rows(rows: list[dict]) -> dict:
    """Rows (dicts, some keys absent) as columns in order of first appearance, typed as pandas would type
    them, so that capred.io.writers.write_csv_file writes the bytes it writes for ``pandas.DataFrame(rows)``:
    whole numbers stay integers unless a row lacks them, numbers with a gap are floats with NaN there,
    anything else is an object column (None where absent).

    Parameters
    ----------
    rows : list of dict
        The rows.

    Returns
    -------
    dict
        Key -> numpy array.
    """
    import numpy as np

    keys = list(dict.fromkeys(k for r in rows for k in r))
    out = {}
    for k in keys:
        values = [r.get(k) for r in rows]
        present = [v for v in values if v is not None]
        numbers = present and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present)
        if numbers and len(present) == len(values) and all(isinstance(v, int) for v in present):
            out[k] = np.array(values, dtype=np.int64)
        elif numbers:
            out[k] = np.array([np.nan if v is None else v for v in values], dtype=float)
        else:
            out[k] = np.array(values, dtype=object)
    return out


def json_list(values) -> list:
    """A float array as a JSON list: every digit kept, None where not finite.

    Parameters
    ----------
    values : array_like
        Numbers.

    Returns
    -------
    list
        Python floats and None.
    """
    import numpy as np

    a = np.asarray(values, dtype=float)
    finite = np.isfinite(a)
    if finite.all():
        return a.tolist()
    return np.where(finite, a, None).tolist()


#: unit suffixes of JSON keys (``c_kPa``, ``alpha_per_kPa``), longest first, and the unit each names in a CSV
#: header. ``_N`` and ``_m`` are not among them: ``sigma_N`` is the normal stress, not a force in newtons.
UNIT_SUFFIXES = (
    ("_per_kPa", "1/kPa"),
    ("_N_per_m", "N/m"),
    ("_kPa2", "kPa^2"),
    ("_kPa", "kPa"),
    ("_MPa", "MPa"),
    ("_Pa", "Pa"),
    ("_mm3", "mm^3"),
    ("_mm2", "mm^2"),
    ("_cm3", "cm^3"),
    ("_mm", "mm"),
    ("_cm", "cm"),
    ("_mN", "mN"),
    ("_deg", "deg"),
    ("_pct", "%"),
)


def csv_header(key: str) -> str:
    """The CSV header of a JSON key: the one rule that turns ``name_unit`` keys into ``name [unit]`` headers.

    Parameters
    ----------
    key : str
        A JSON key, e.g. ``"c_kPa"``, ``"alpha_per_kPa"``, ``"material"``, or a header already in
        ``name [unit]`` form.

    Returns
    -------
    str
        ``"c [kPa]"``, ``"alpha [1/kPa]"``; a key without a unit suffix (a label, an identifier, a
        dimensionless number named by the glossary) or a header with brackets is returned unchanged.
    """
    if "[" in key:
        return key
    for suffix, unit in UNIT_SUFFIXES:
        if key.endswith(suffix) and len(key) > len(suffix):
            return f"{key[: -len(suffix)]} [{unit}]"
    return key


def with_csv_headers(table):
    """A table (dict of columns or DataFrame) under :func:`csv_header` names (not copied).

    Parameters
    ----------
    table : dict or pandas.DataFrame
        Columns under their JSON keys.

    Returns
    -------
    dict or pandas.DataFrame
        The same columns under CSV headers.
    """
    if isinstance(table, dict):
        return {csv_header(k): v for k, v in table.items()}
    return table.rename(columns=csv_header)


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


def num(x) -> float | None:
    """A float for JSON: every digit kept (shortest round-trip form on output), None when not finite.

    Parameters
    ----------
    x : float, numpy scalar or None
        A number.

    Returns
    -------
    float or None
    """
    if x is None:
        return None
    x = float(x)
    return x if x == x and x not in (float("inf"), float("-inf")) else None
