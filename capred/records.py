"""Typed records and their one mapping to JSON keys and table columns.

A record is a dataclass whose fields are declared with :func:`output` (JSON key, column header, output unit,
scale from SI): :func:`record_json`, :func:`record_row`, :func:`record_columns` and
:func:`record_json_columns` derive every JSON object and table column from those declarations; :func:`num` and
:func:`json_list` are the JSON forms of numbers (every digit kept, None where not finite).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import NamedTuple


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
    of: str | None = None
    store: bool = True


def output(
    json: str | None,
    column=None,
    unit: str = "",
    scale: float = 1.0,
    pair: bool = False,
    of: str | None = None,
    store: bool = True,
):
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
    of : str, optional
        For a ``pair`` field: the name of the field whose 95 % interval it is (the lab store records it beside
        that field's value, :func:`record_store_rows`).
    store : bool, optional
        False: the lab store does not record the field (a count such as ``n``, a label).

    Returns
    -------
    dataclasses.Field
        A field defaulting to None, with the :class:`Output` in its metadata.
    """
    return field(default=None, metadata={"output": Output(json, column, unit, scale, pair, of, store)})


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
        if spec.json is None:
            continue
        key = spec.json.format(level=level)
        if spec.pair:  # a scalar (low, high): the JSON list [low, high]
            out[key] = [_scalar_out(v, spec.scale) for v in value]
        else:
            out[key] = _scalar_out(value, spec.scale)
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


class StoreRow(NamedTuple):
    """One row of the lab store's long table (capred.lab_store): a declared quantity of one material.

    ``quantity`` is the quantity's JSON key (with a model's prefix, ``vg.alpha_per_kPa``), ``value`` and the
    interval are in ``unit`` (``-`` when dimensionless), all from one declaration.
    """

    material: str | None
    quantity: str
    value: float
    ci_low: float | None
    ci_high: float | None
    unit: str


class UndeclaredQuantity(ValueError):
    """A number offered to the lab store without a declared unit: refused, never guessed from its name."""


def store_row(material, quantity: str, value, unit, ci=None) -> StoreRow | None:
    """A :class:`StoreRow` of a declared quantity; None where ``value`` is not a finite number (nothing to record).

    Parameters
    ----------
    material : str or None
        The material (or branch) the quantity belongs to.
    quantity : str
        Its JSON key.
    value : float
        Its value in ``unit``.
    unit : str
        Its declared unit (``"-"`` or ``""`` when dimensionless).
    ci : tuple of float, optional
        Its 95 % interval in ``unit``.

    Returns
    -------
    StoreRow or None

    Raises
    ------
    UndeclaredQuantity
        ``unit`` is None: the quantity has no declaration.
    """
    if unit is None:
        raise UndeclaredQuantity(f"the quantity '{quantity}' has no declared unit; the lab store does not guess one")
    v = _finite(value)
    if v is None:
        return None
    lo, hi = (None, None) if ci is None else (_finite(ci[0]), _finite(ci[1]))
    return StoreRow(material, quantity, v, lo, hi, unit if unit not in ("", "-") else "-")


def quantity_store_row(material, quantity: str, value, key: str | None = None, ci=None) -> StoreRow | None:
    """A :class:`StoreRow` of a glossary quantity (capred.nomenclature.QUANTITIES): its unit is the glossary's.

    Parameters
    ----------
    material : str or None
        The material the quantity belongs to.
    quantity : str
        A key of the glossary.
    value : float
        Its value in the glossary's output unit (as the JSON writes it).
    key : str, optional
        The JSON key it is written under where it is not the glossary's (``gamma_N_per_m`` for the surface
        tension of `capred bridge curve`); default :func:`capred.nomenclature.json_key`.
    ci : tuple of float, optional
        Its 95 % interval in the same unit.

    Returns
    -------
    StoreRow or None
        None where ``value`` is not a finite number.
    """
    from .nomenclature import QUANTITIES, json_key

    return store_row(material, key or json_key(quantity), value, QUANTITIES[quantity].unit, ci)


def _finite(x) -> float | None:
    import numpy as np

    if x is None or isinstance(x, (bool, np.bool_, str)):
        return None
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def record_store_rows(record, material=None, prefix: str = "", level: str = "95") -> list[StoreRow]:
    """The lab store's rows of a record of scalars, from its :func:`output` declarations.

    Each field with a JSON key (not a ``pair``, not declared ``store=False``) gives one row: the quantity is
    its JSON key (as :func:`record_json` writes it, after ``prefix``), the value its JSON value, the unit its
    declared unit, the interval the ``pair`` field declared ``of`` it. A value that is not a finite number is
    left out, as :func:`record_json` writes it null.

    Parameters
    ----------
    record : dataclass instance
        A typed record whose output fields hold numbers.
    material : str, optional
        The material of the rows.
    prefix : str, optional
        Put before each JSON key (a model's name and a dot, ``vg.``).
    level : str, optional
        Confidence level in percent, put into the ``{level}`` patterns (default "95").

    Returns
    -------
    list of StoreRow
    """
    outputs = record_outputs(record)
    intervals = {spec.of: (value, spec.scale) for _, spec, value in outputs if spec.pair and spec.of}
    rows = []
    for name, spec, value in outputs:
        if spec.json is None or spec.pair or not spec.store:
            continue
        if not isinstance(value, (int, float)) and not hasattr(value, "__float__"):
            continue  # a label or a list: not a quantity
        ci = None
        if name in intervals:
            pair, scale = intervals[name]
            ci = [_scalar_out(v, scale) for v in pair]
        row = store_row(material, prefix + spec.json.format(level=level), _scalar_out(value, spec.scale), spec.unit, ci)
        if row is not None:
            rows.append(row)
    return rows


def parameter_store_rows(params, material=None, prefix: str = "") -> list[StoreRow]:
    """The lab store's rows of fitted parameters (:class:`capred.parameters.Parameter`).

    Each with its JSON name, value, standard error, 95 % interval and unit: ``name`` with its interval and ``name_se``,
    both in its unit.

    Parameters
    ----------
    params : iterable of Parameter
        The parameters (``fit.params.values()``).
    material : str, optional
        The material of the rows.
    prefix : str, optional
        Put before each name (``vg.``).

    Returns
    -------
    list of StoreRow
    """
    rows = []
    for p in params:
        for row in (
            store_row(material, prefix + p.name, p.value, p.unit, p.ci95),
            store_row(material, f"{prefix}{p.name}_se", p.stderr, p.unit),
        ):
            if row is not None:
                rows.append(row)
    return rows


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
    """Per-row JSON values of records for rows start..stop-1: ``{key: list}``.

    A model-indexed field gives a list of ``{model: value}`` dicts, a pair a list of ``[low, high]``.

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


def columns_of_rows(rows: list[dict]) -> dict:
    """Rows (dicts, some keys absent) as columns in order of first appearance, typed as pandas would type them.

    So that capred.io.writers.write_csv_file writes the bytes it writes for ``pandas.DataFrame(rows)``: whole numbers
    stay integers unless a row lacks them, numbers with a gap are floats with NaN there, anything else is an object
    column (None where absent).

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


def per_case_store_rows(result, material: str | None = None) -> list:
    """The lab store's rows of a command whose numbers are per case: none (a `Result.store_rows`).

    Its numbers are per case (a table of bridges), not quantities of one material across runs; the run and its
    document are recorded with their provenance.

    Parameters
    ----------
    result : capred.result.Result
        The run's result.
    material : str, optional
        The material of the inputs' metadata block.

    Returns
    -------
    list of capred.records.StoreRow
        Empty.
    """
    return []
