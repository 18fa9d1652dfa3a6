"""The ``material`` column of a triaxial table: one material per analysis, never pooled (issue 40).

`capred triaxial` analyses every material of its table separately. `capred triaxial-bounds` fits ONE effective
envelope per run, so a table with several materials runs one of them at a time (``--material NAME``); without it,
a table of several materials is refused with the list of materials, rather than pooled into one envelope.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import InputError, OptionError, Problem
from ..io import Table


def materials_of(table: Table) -> dict[str, int]:
    """{material: number of tests} in table order (blank cells count as "" ); {} without a material column.

    Parameters
    ----------
    table : capred.io.Table

    Returns
    -------
    dict of str to int
    """
    if not table.has("material"):
        return {}
    out: dict[str, int] = {}
    for v in table.columns["material"]:
        out[str(v)] = out.get(str(v), 0) + 1
    return out


def subset_rows(table: Table, keep: np.ndarray) -> Table:
    """The same table restricted to the rows ``keep`` (a boolean mask); file lines and raw cells kept.

    Parameters
    ----------
    table : capred.io.Table
    keep : numpy.ndarray of bool

    Returns
    -------
    capred.io.Table
    """
    keep = np.asarray(keep, bool)
    idx = np.flatnonzero(keep)
    return dataclasses.replace(
        table,
        columns={k: np.asarray(v)[keep] for k, v in table.columns.items()},
        raw={k: [v[i] for i in idx] for k, v in table.raw.items()},
        lines=np.asarray(table.lines)[keep],
        as_read={k: np.asarray(v)[keep] for k, v in table.as_read.items()},
        notes=list(table.notes),
        problems=list(table.problems),
        warnings=list(table.warnings),
    )


def one_material(table: Table, material: str | None) -> tuple[Table, str | None]:
    """The rows of one material of a triaxial table, for an analysis that fits one envelope.

    Parameters
    ----------
    table : capred.io.Table
        As read (``material`` column optional).
    material : str or None
        The material asked for (``--material``); None: the table must hold a single material.

    Returns
    -------
    (Table, str or None)
        The rows of that material and its name (None when the table has no material column).

    Raises
    ------
    InputError
        Several materials and none chosen (the message lists them with their number of tests).
    OptionError
        ``material`` given for a table without a material column, or not among its materials.
    """
    found = materials_of(table)
    if not found:
        if material is not None:
            raise OptionError(f"--material {material!r}: {table.path} has no material column")
        return table, None
    if material is None:
        named = [m for m in found if m]
        if len(found) == 1 or (len(named) <= 1 and "" not in found):
            return table, next(iter(found))
        listed = ", ".join(f"'{m}' ({n} tests)" if m else f"blank ({n} tests)" for m, n in found.items())
        raise InputError(
            Problem(
                table.path,
                table.header_line,
                table.headers.get("material", "material"),
                f"{len(found)} materials in one table ({listed}): triaxial-bounds fits one effective envelope per "
                "run and never pools materials; run it once per material with --material NAME, or use "
                "`capred triaxial`, which analyses every material separately",
                table.sheet,
            )
        )
    if material not in found:
        raise OptionError(f"--material {material!r} is not in {table.path}; its materials: {', '.join(found)}")
    return subset_rows(table, np.asarray(table.columns["material"], dtype=object) == material), material
