"""`capred bridge solve` on a long file: read, solved and kept block by block, so memory stays flat (issue 20).

Rows of ``bridge solve`` are independent: each block of lines (capred.io.blocks)
is solved as a table of its own and its output columns go to a
:class:`capred.result.Spool` on disk; only the status and the radius ratio of
every row stay in memory. A file of one block gives the ordinary
:class:`capred.pipelines.bridge.BridgeResult`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..io import blocks as blocks_module
from ..io import read_table_blocks
from ..progress import task
from ..result import InputFile, Result, Spool, input_file
from . import bridge_solve as pb

#: output columns that are text, not numbers (BridgeResult.columns leaves them out)
_TEXT_COLUMNS = ("case", "status", "note")


@dataclass(repr=False)
class BridgeBlocks(Result):
    """Bridges of a long table, one per row, their output columns kept on disk block by block.

    It offers what the writer and a script need of a :class:`BridgeResult`: ``rows()``, ``rows_range()``,
    ``columns()`` (the same keys), ``status``, ``to_json()``. The per-row SI arrays of a BridgeResult
    (``force``, ``volume``, ``neck``, ``beta``, ``suction``, ``shape``) are not kept: ``columns()`` gives the
    same quantities in output units.

    Attributes
    ----------
    source : str
        The file read.
    status : ndarray of int
        Per row: 0 a verified bridge, else the code of :data:`capred.pipelines.bridge.STATUS`.
    inputs_si : dict
        ``ratio``: R2/R per row [-]; the other inputs of :class:`BridgeResult` for the first
        :data:`capred.pipelines.bridge_solve.HEAD_ROWS` rows (what names them in the tables).
    spool : Spool
        The output columns (mm, mN, mm^3, mm^2, deg, kPa), as ``BridgeResult`` writes them.
    """

    command = "bridge solve"
    json_name = "solve.json"

    source: str
    status: np.ndarray
    inputs_si: dict
    spool: Spool
    options: pb.BridgeOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    status_text = staticmethod(pb.BridgeResult.status_text)

    def rows_range(self, start: int, stop: int) -> list[dict]:
        """JSON rows start..stop, read back from the spool.

        Parameters
        ----------
        start, stop : int
            First row and one past the last row (0-based) [-].

        Returns
        -------
        list of dict
            The JSON rows.
        """
        return pb.json_rows(self.spool.columns(start, stop))

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document (every row of the run, read back from the spool), NaN written as
        None.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        return self.rows_range(0, self.status.size)

    def row_context(self, start: int, stop: int) -> dict[str, np.ndarray]:
        """As :meth:`capred.pipelines.bridge_solve.BridgeResult.row_context` (NaN past the first HEAD_ROWS).

        Parameters
        ----------
        start, stop : int
            First row and one past the last row (0-based) [-].

        Returns
        -------
        dict
            ``R_mm``, ``gap_mm``, ``D_rupture_mm`` -> array [mm].
        """
        return pb.row_context(self.inputs_si, self.status, start, stop)

    def columns(self) -> dict[str, np.ndarray]:
        """The numeric output columns of every row, as :meth:`BridgeResult.columns` gives them (mm, mN, mm^3,
        mm^2, deg, kPa; NaN where no bridge was found), read back into memory."""
        return {k: v for k, v in self._all().items() if k not in _TEXT_COLUMNS}

    def _all(self) -> dict[str, np.ndarray]:
        return self.spool.columns(0, self.status.size)

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the bridges (a ColumnRows when lazy).

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        n = self.status.size
        return {"source": self.source, "bridges": pb.ColumnRows(n, self.spool.columns) if lazy else self.rows()}

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``solve``: every row, all in memory, for tables.xlsx).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        return {"solve": pd.DataFrame(self._all(), copy=False)}  # tables.xlsx: every row in memory

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``solve``: a HeadedSpool written block by block), under ``name
        [unit]`` headers.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        return {"solve": pb.HeadedSpool(self.spool)}  # written block by block, under name [unit] headers


def solve_in_blocks(source, opt: pb.BridgeOptions):
    """Solve every row of ``source`` block by block (see the module docstring).

    Parameters
    ----------
    source : path, DataFrame or TableSource
        The table of cases (see capred.pipelines.bridge.solve_bridges).
    opt : BridgeOptions
        Options of the run.

    Returns
    -------
    BridgeResult or BridgeBlocks
        A BridgeResult when the table is one block; else a BridgeBlocks.

    Raises
    ------
    InputError
        The problems of the first block that has any (nothing is returned).
    """
    with pb.helper(start=_long(source), workers=opt.workers):  # the same helper processes for every block
        return _solve_in_blocks(source, opt)


def _long(source) -> bool:
    """True for a CSV file read in several blocks: its blocks are long enough to be shared by two processes."""
    try:
        size = Path(source).stat().st_size if isinstance(source, (str, Path)) else 0
    except OSError:
        return False
    return size > blocks_module.BLOCK_BYTES + blocks_module.BLOCK_BYTES // 4


def _solve_in_blocks(source, opt: pb.BridgeOptions):
    blocks = read_table_blocks(source, pb.SOLVE_SCHEMA)
    table = next(blocks)
    res = pb.solve_table(table, opt)
    res.inputs = [input_file(source, table)]
    path = str(table.path)
    del table  # one block in memory at a time: its cells go before the next is read
    table = next(blocks, None)
    if table is None:
        return res
    spool = Spool()
    try:
        status, ratio = [res.status], [res.inputs_si["ratio"]]
        head = {k: v[: pb.HEAD_ROWS] for k, v in res.inputs_si.items() if k != "ratio"}
        notes, warnings, inputs = dict.fromkeys(res.notes), dict.fromkeys(res.warnings), res.inputs
        spool.append(res._cols())
        del res
        size = Path(path).stat().st_size
        with task("solving bridges, block by block", total=-(-size // blocks_module.BLOCK_BYTES)) as advance:
            advance(1)  # the first block, solved above
            while table is not None:
                part = pb.solve_table(table, opt)
                del table
                spool.append(part._cols())
                status.append(part.status)
                ratio.append(part.inputs_si["ratio"])
                notes.update(dict.fromkeys(part.notes))
                warnings.update(dict.fromkeys(part.warnings))
                del part
                advance(1)
                table = next(blocks, None)
    except BaseException:
        spool.close()
        raise
    return BridgeBlocks(
        path,
        np.concatenate(status).astype(np.int8),
        {"ratio": np.concatenate(ratio), **head},
        spool,
        opt,
        inputs,
        list(notes),
        list(warnings),
    )
