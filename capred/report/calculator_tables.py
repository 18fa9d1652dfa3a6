"""Console (and HTML) tables of the calculators `capred prism`, `skempton-b` and `rumpf`."""

from __future__ import annotations

from ..records import num
from ..table_spec import TableSpec
from .render import row_table


def calc_tables(result) -> list[TableSpec]:
    """Inputs and results of a calculator, one row per case (at most 20 shown), under ``symbol [unit]`` headers.

    The columns come from the run's typed record (``result.cases``, capred.pipelines.calculator_records): each
    header is its field's glossary label, the values its output-unit numbers.

    Parameters
    ----------
    result : capred.pipelines.calculators.CalcResult
        A calculator run (``capred prism``, ``skempton-b`` or ``rumpf``).

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    cols = result.cases.console_columns()
    labels = result.labels
    n = len(result.cases)
    rows = [
        {**({"case": labels[i]} if labels else {}), **{h: _number(v[i]) for h, v in cols.items()}} for i in range(n)
    ]
    return [row_table(f"{result.title}", rows, list(rows[0]), "results.csv")]


def _number(x):
    """A float for the table, None where not finite (as the JSON writes it)."""
    return num(x)
