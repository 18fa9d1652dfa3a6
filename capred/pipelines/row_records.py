"""Per-row typed records: a frozen dataclass whose fields are the columns of one output table.

Each column is declared once with :func:`capred.result.output` (a quantity: JSON key, column, unit) or :func:`plain` (a
label, an identifier, a status, a flag). The JSON key, the CSV header (``name [unit]``) and the console header follow
from it (`bridge compare`, `bridge rupture`, `bridge yade-files`, `history`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import field

import numpy as np

from ..result import num


def plain(json: str):
    """Field metadata of a record attribute without a unit (a label, an identifier, a status, a flag).

    Its JSON key, CSV header and console header are all ``json``.

    Parameters
    ----------
    json : str
        The key.

    Returns
    -------
    dataclasses.Field
        A field defaulting to None (None: the run has no such column, e.g. no ``case`` labels).
    """
    return field(default=None, metadata={"plain": json})


def _cell(x):
    """One value of a row as JSON and the console take it: Python scalars, NaN as None."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return num(float(x))
    return x


class RowRecord:
    """Mixin of a frozen dataclass whose fields are columns of one table.

    Each is declared once with :func:`capred.result.output` (a quantity: JSON key, column, unit) or :func:`plain` (no
    unit).

    The JSON key, the CSV header (``name [unit]``, ``[-]`` for a dimensionless number) and the console header
    (the JSON key) of every column follow from that declaration. Values are held in output units.
    """

    #: fill for a ``{unit}`` placeholder in a declared unit (a record whose quantity is chosen at run time)
    unit_fill: str = ""

    def _columns(self):
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            if "plain" in f.metadata:
                yield f.metadata["plain"], f.metadata["plain"], value
            elif "output" in f.metadata:
                o = f.metadata["output"]
                unit = o.unit.format(unit=self.unit_fill) if o.unit else ""
                yield o.json, f"{o.column} [{unit or '-'}]", value

    def columns(self) -> dict:
        """The columns under their JSON keys, in declaration order (fields that are None left out).

        Returns
        -------
        dict
            JSON key -> sequence of values (output units).
        """
        return {key: value for key, _, value in self._columns()}

    def csv_columns(self) -> dict:
        """The columns under their CSV headers (``name [unit]``; a label, status or flag under its key).

        Returns
        -------
        dict
            CSV header -> sequence of values (output units).
        """
        return {head: value for _, head, value in self._columns()}

    def __len__(self) -> int:
        return len(next(iter(self.columns().values()), ()))

    def json_rows(self, start: int = 0, stop: int | None = None) -> list[dict]:
        """Rows ``start`` to ``stop - 1`` as dicts: JSON key -> Python scalar (NaN as None).

        Parameters
        ----------
        start, stop : int, optional
            The rows, ``start`` included, ``stop`` excluded (default: all).

        Returns
        -------
        list of dict
            One dict per row, in declaration order.
        """
        cols = self.columns()
        stop = len(self) if stop is None else min(stop, len(self))
        keys = list(cols)
        return [{k: _cell(cols[k][i]) for k in keys} for i in range(start, stop)]
