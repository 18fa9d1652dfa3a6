"""Console (and HTML) tables of the calculators `capred prism`, `skempton-b` and `rumpf`."""

from __future__ import annotations

from ..result import TableSpec
from .render import row_table


def calc_tables(result) -> list[TableSpec]:
    """Inputs and results of a calculator, one row per case (at most 20 shown).

    Parameters
    ----------
    result : capred.pipelines.calculators.CalcResult
        A calculator run (``capred prism``, ``skempton-b`` or ``rumpf``).

    Returns
    -------
    list of capred.result.TableSpec
    """
    rows = result.rows()
    return [row_table(f"{result.title}", rows, list(rows[0]), "results.csv")]
