"""The one rule that writes a JSON key's unit suffix as CSV header text: ``c_kPa`` -> ``c [kPa]``.

Only for the headers of tables whose columns are named by JSON keys (a record's columns carry their declared
unit already: capred.records.record_columns); no unit of a quantity is inferred from a suffix anywhere else.
"""

from __future__ import annotations

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
