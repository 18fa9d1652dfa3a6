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
from ..io.blocks import read_table_blocks
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
    #: processes that write the CSV and JSON text of the blocks ahead of the writer, and the blocks of the
    #: spool (set by a spread run)
    processes = 1
    n_blocks = 0

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
        if not lazy:
            return {"source": self.source, "bridges": self.rows()}
        encoded = self._encoded()  # a long document about to be written: its text written ahead, on every process
        rows = pb.ColumnRows(n, self.spool.columns) if encoded is None else _EncodedRows(n, self.spool.columns, encoded)
        return {"source": self.source, "bridges": rows}

    def _encoded(self):
        """The CSV and JSON text of every block, written ahead on the run's processes (None: one process)."""
        if self.processes < 2:
            return None
        if "_encoded_text" not in self.__dict__:
            self.__dict__["_encoded_text"] = _encode_blocks(self.spool, self.processes, self.n_blocks)
        return self.__dict__["_encoded_text"]

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
        # written block by block, under name [unit] headers (or the text written ahead by a spread run)
        return {"solve": pb.HeadedSpool(self.spool, self.__dict__.get("_encoded_text"))}


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
    if _long(source):
        k = pb.processes(opt.workers)
        if k > 1:
            res = _solve_spread(source, opt, k)
            if res is not None:
                return res
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


# ---------------------------------------------------------------------------------------------------------------
# a long file spread over several processes (issue 31, item 4)


def _solve_spread(source, opt: pb.BridgeOptions, k: int):
    """Read, parse and solve the blocks of ``source`` on ``k`` processes: block ``i`` in process ``i % k`` (this
    process solves blocks 0, k, 2k, ...; forked workers the others), each block whole, as one process would
    solve it; the results are gathered here in file order. The result (a :class:`BridgeBlocks`) then writes
    the CSV and JSON text of its blocks on ``k`` processes too, when its document is asked for.

    Each worker reads the file itself (capred.io.blocks.read_table_blocks with ``select``: only its own blocks
    are parsed), so nothing but the results crosses between processes. The result is the same, to the bit, as
    that of one process: the same blocks, each solved by the same operations.

    Returns None (nothing done: the caller runs the usual path, which reports any problem) when a worker
    fails or finds a problem in its blocks, or fork is missing.
    """
    workers: list[_Worker] = []
    spool = Spool()
    out = None
    try:
        for j in range(1, k):
            workers.append(_Worker(source, opt, j, k))
        out = _gather(source, opt, k, workers, spool)
    except _WorkerFailed:
        out = None
    finally:
        for w in workers:
            w.close()
        if not isinstance(out, BridgeBlocks):
            spool.close()
    return out


class _WorkerFailed(Exception):
    """A worker could not give one of its blocks (a problem in it, or the worker failed)."""


_END = object()


def _spread_blocks(source, j: int, k: int):
    """The blocks of ``source`` that process ``j`` of ``k`` parses (every other one is None)."""
    return read_table_blocks(source, pb.SOLVE_SCHEMA, select=lambda i: i % k == j)


def _solved(table, opt):
    """What the gathering process keeps of one solved block."""
    part = pb.solve_table(table, opt)
    return part, (part.status, part.inputs_si["ratio"], part._cols(), part.notes, part.warnings)


class _Worker:
    """A forked process that reads, parses and solves blocks j, j + k, j + 2k, ... of the file and sends each
    one's result back through a pipe (in order; ``None`` at the end, ``"fail"`` when it cannot go on)."""

    def __init__(self, source, opt, j: int, k: int) -> None:
        import gc
        import os

        self._from_child, write_end = os.pipe()
        gc.freeze()
        self.pid = os.fork()
        if self.pid == 0:  # the child: serve, then leave without running the parent's clean-up
            code = 1
            try:
                gc.disable()
                os.close(self._from_child)
                for fd in _Worker.live_fds:  # the other workers' pipes are theirs alone
                    try:
                        os.close(fd)
                    except OSError:
                        pass
                self._serve(source, opt, j, k, write_end)
                code = 0
            finally:
                os._exit(code)
        os.close(write_end)
        _Worker.live_fds.append(self._from_child)

    live_fds: list = []

    @staticmethod
    def _serve(source, opt, j, k, outbox) -> None:
        pb._ONE_PROCESS = True
        try:
            for table in _spread_blocks(source, j, k):
                if table is not None:
                    pb._send(outbox, _solved(table, opt)[1])
                    del table
            pb._send(outbox, None)
        except Exception:  # a problem in a block (or anything else): the gathering process runs the usual path
            pb._send(outbox, "fail")

    def result(self):
        """The next block's result; raises _WorkerFailed when the worker failed or is gone."""
        try:
            got = pb._receive(self._from_child)
        except (OSError, EOFError):
            got = "fail"
        if got is None or isinstance(got, str):
            raise _WorkerFailed
        return got

    def close(self) -> None:
        import gc
        import os
        import signal

        if self.pid is None:
            return
        try:
            os.close(self._from_child)
            os.kill(self.pid, signal.SIGKILL)  # done, or no longer needed
            os.waitpid(self.pid, 0)
        except OSError:
            pass
        finally:
            if self._from_child in _Worker.live_fds:
                _Worker.live_fds.remove(self._from_child)
            self.pid = None
            if not _Worker.live_fds:
                gc.unfreeze()


def _gather(source, opt, k: int, workers: list, spool: Spool):
    """This process's share of a spread run (blocks 0, k, 2k, ...) and the workers' results, in file order."""
    first = inputs = head = path = None
    status, ratio = [], []
    notes, warnings = {}, {}
    size = Path(source).stat().st_size
    pb._ONE_PROCESS = True
    try:
        with task("solving bridges, block by block", total=-(-size // blocks_module.BLOCK_BYTES)) as advance:
            for i, table in enumerate(_spread_blocks(source, 0, k)):
                if table is not None:
                    part, got = _solved(table, opt)
                    if i == 0:
                        first, inputs, path = part, [input_file(source, table)], str(table.path)
                        head = {key: v[: pb.HEAD_ROWS] for key, v in part.inputs_si.items() if key != "ratio"}
                    del table, part
                else:
                    got = workers[i % k - 1].result()
                st, rt, cols, block_notes, block_warnings = got
                spool.append(cols)
                status.append(st)
                ratio.append(rt)
                notes.update(dict.fromkeys(block_notes))
                warnings.update(dict.fromkeys(block_warnings))
                del got, cols
                advance(1)
    finally:
        pb._ONE_PROCESS = False
    if len(status) == 1:  # one block: the ordinary result
        first.inputs = inputs
        return first
    res = BridgeBlocks(
        path,
        np.concatenate(status).astype(np.int8),
        {"ratio": np.concatenate(ratio), **head},
        spool,
        opt,
        inputs,
        list(notes),
        list(warnings),
    )
    res.processes, res.n_blocks = k, len(status)
    return res


class _EncodedRows(pb.ColumnRows):
    """The rows of a spread run whose JSON text its processes have written ahead (:func:`_encode_blocks`)."""

    def __init__(self, n: int, columns, encoded) -> None:
        super().__init__(n, columns)
        self.encoded = encoded

    def json_chunks(self, size: int = 2000):
        """The rows' JSON objects joined by commas, one block per chunk (the bytes of
        :meth:`capred.pipelines.bridge_solve.ColumnRows.json_chunks`, cut at the blocks' ends).

        Parameters
        ----------
        size : int, optional
            Unused (a block per chunk).

        Yields
        ------
        bytes
        """
        yield from self.encoded.json_pieces()


class _Encoded:
    """The CSV (standard dialect, the header with the first block) and JSON text of every block of a spool,
    in temporary files: (file, CSV offset, CSV bytes, JSON offset, JSON bytes) per block."""

    def __init__(self, files, index) -> None:
        self.files, self.index = files, index

    def _read(self, f, offset: int, size: int) -> bytes:
        import os

        return os.pread(f.fileno(), size, offset)

    def csv_pieces(self):
        """The CSV text, block by block (bytes)."""
        for f, c_off, c_len, _, _ in self.index:
            yield self._read(f, c_off, c_len)

    def json_pieces(self):
        """The JSON rows, block by block (bytes: objects joined by commas; empty for a block of no rows)."""
        for f, _, _, j_off, j_len in self.index:
            yield self._read(f, j_off, j_len)


def _encode_block(block: dict, first: bool) -> tuple[bytes, bytes]:
    """The CSV text (with the header for the first block) and the JSON rows of one spool block: the bytes the
    writers write of it (capred.io.writers.write_csv_file, capred.io.writers.stream_json)."""
    import io

    from ..io.writers import encode_rows, write_csv_file

    buf = io.BytesIO()
    write_csv_file(buf, pb.with_csv_headers(block), "standard")
    csv = buf.getvalue()
    if not first:
        csv = csv[csv.index(b"\n") + 1 :]
    return csv, encode_rows(pb._json_chunk_rows(block))


def _encode_share(spool: Spool, j: int, k: int, n_blocks: int, f) -> list[tuple[int, int, int, int, int]]:
    """Blocks j, j + k, ... of the spool written into file ``f``: (block, CSV offset, bytes, JSON offset, bytes)."""
    out, offset = [], 0
    for i in range(j, n_blocks, k):
        csv, js = _encode_block(spool.block(i), i == 0)
        f.write(csv)
        f.write(js)
        out.append((i, offset, len(csv), offset + len(csv), len(js)))
        offset += len(csv) + len(js)
    f.flush()
    return out


def _encode_blocks(spool: Spool, k: int, n_blocks: int):
    """The CSV and JSON text of every block of ``spool``, written on ``k`` processes (this one and k - 1 forked);
    None when a process failed (the writers then write from the spool, in one process)."""
    import gc
    import os
    import tempfile

    k = max(1, min(k, n_blocks))
    files = [tempfile.TemporaryFile() for _ in range(k)]
    children = []
    gc.freeze()
    try:
        for j in range(1, k):
            read_end, write_end = os.pipe()
            pid = os.fork()
            if pid == 0:
                code = 1
                try:
                    os.close(read_end)
                    for _, fd in children:
                        os.close(fd)
                    pb._send(write_end, _encode_share(spool, j, k, n_blocks, files[j]))
                    code = 0
                finally:
                    os._exit(code)
            os.close(write_end)
            children.append((pid, read_end))
        index = {}
        for i, *where in _encode_share(spool, 0, k, n_blocks, files[0]):
            index[i] = (files[0], *where)
        ok = True
        for j, (pid, fd) in enumerate(children, start=1):
            try:
                got = pb._receive(fd)
            except (OSError, EOFError):
                got = None
            if got is None:
                ok = False
            else:
                for i, *where in got:
                    index[i] = (files[j], *where)
    finally:
        for pid, fd in children:
            os.close(fd)
            try:
                os.waitpid(pid, 0)
            except OSError:
                pass
        gc.unfreeze()
    if not ok or sorted(index) != list(range(n_blocks)):
        for f in files:
            f.close()
        return None
    return _Encoded(files, [index[i] for i in range(n_blocks)])
